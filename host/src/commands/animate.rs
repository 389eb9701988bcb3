//! `obscura animate`: a scene's camera path, every frame built and proven for its own camera,
//! rendered in a format and in f64 and measured, and written as an animated GIF at the path's
//! pace, or at a board's (`--pace-of`).

use crate::analysis::{Aim, Analysis, Choice, pick};
use crate::cli::AnimateArgs;
use crate::estimate;
use crate::firmware::{FrameTime, Target};
use crate::metrics::{Accuracy, accuracy};
use crate::output::{self, say};
use crate::render::{Request, prepare, prepare_reference};
use anyhow::{Context, Result, bail};
use image::RgbImage;
use indicatif::{ProgressBar, ProgressStyle};
use obscura::{Methods, Pixels, RowOrder};
use obscura_scene::{Format, FormatChoice, NamedScene};
use rayon::prelude::*;
use serde::Serialize;
use std::io::IsTerminal;
use std::time::Duration;

/// One frame's figures, as printed and written to JSON: `compare --json`'s accuracy columns.
#[derive(Debug, Serialize)]
struct FrameReport {
    frame: u16,
    format: &'static str,
    reference: &'static str,
    scene: String,
    width: u32,
    height: u32,
    /// `null` in JSON when the images are identical (infinite PSNR).
    psnr_db: f64,
    mean_abs_error: f64,
    max_abs_error: u8,
    differing_pixels_pct: f64,
    object_mismatch_pct: f64,
}

pub fn run(args: &AnimateArgs) -> Result<()> {
    output::check_file(&args.output)?;
    if let Some(path) = &args.json {
        output::check_file(path)?;
    }
    super::on_scene(&args.scene.scene, &args.scene.sampling, |named| {
        animate(args, named)
    })
}

fn animate(args: &AnimateArgs, named: &NamedScene) -> Result<()> {
    let Some(animation) = &named.scene.animation else {
        bail!(
            "{} has no camera path: add an [animation] table with its frames, fps and \
             [[animation.keys]] (docs/scene-files.md)",
            named.name
        );
    };
    let mut frames = named.frames();
    let methods = args.scene.methods.methods();
    let (format, pixels) = format_of_every_frame(args, &frames, methods)?;
    for frame in &mut frames {
        frame.scene.pixels = pixels;
    }
    let (width, height) = args.scene.size;
    let bar = progress(&named.name, format, frames.len());
    let rendered = (0..animation.frames)
        .into_par_iter()
        .zip(frames.par_iter())
        .map(|(k, frame)| {
            let drawn = render_frame(args, frame, k, format, methods);
            bar.inc(1);
            drawn.with_context(|| format!("frame {k} of {}'s {} frames", named.name, frames.len()))
        })
        .collect::<Vec<Result<_>>>()
        // The first frame refused, in the path's order (the frames are drawn in any).
        .into_iter()
        .collect::<Result<Vec<_>>>()?;
    bar.finish_and_clear();
    let paced = args
        .pace_of
        .map(|target| board_times(target, &frames, format, methods))
        .transpose()?;
    let held = paced.as_ref().map_or_else(
        || vec![super::frame_time(animation.fps); frames.len()],
        |times| {
            times
                .iter()
                .map(|t| Duration::from_secs_f64(t.frame))
                .collect()
        },
    );
    let images = rendered.iter().map(|(image, _)| image);
    super::save_gif(images.zip(held), &args.output)?;
    let reports: Vec<FrameReport> = rendered
        .into_iter()
        .zip(0_u16..)
        .map(|((_, accuracy), frame)| FrameReport {
            frame,
            format: format.name(),
            reference: Format::F64.name(),
            scene: named.name.clone(),
            width,
            height,
            psnr_db: accuracy.psnr_db,
            mean_abs_error: accuracy.mean_abs_error,
            max_abs_error: accuracy.max_abs_error,
            differing_pixels_pct: accuracy.differing_pixels_pct,
            object_mismatch_pct: accuracy.object_mismatch_pct,
        })
        .collect();
    let pace = args.pace_of.map_or_else(
        || format!("at {} a second", animation.fps),
        |target| {
            format!(
                "each held as long as the {} takes to draw it",
                target.board().name
            )
        },
    );
    print_reports(&reports, &pace, &args.output)?;
    if let (Some(target), Some(times)) = (args.pace_of, &paced) {
        print_pace(target, times)?;
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&reports)?;
        std::fs::write(path, text + "\n")
            .with_context(|| format!("cannot write {}", path.display()))?;
        say!("wrote {}", path.display())?;
    }
    Ok(())
}

/// The format every frame is drawn in, and its pixels: the format given with the frames' own
/// pixels, or with `auto` the cheapest format (and pixels, where the frames leave them to it)
/// that holds every frame and reaches the target on the worst.
fn format_of_every_frame(
    args: &AnimateArgs,
    frames: &[NamedScene],
    methods: Methods,
) -> Result<(Format, Pixels)> {
    let FormatChoice::Given(format) = args.scene.format else {
        let size = args.scene.size;
        let analyses = frames
            .iter()
            .map(|frame| Analysis::fits(&frame.scene, methods, size.0, size.1))
            .collect::<Result<Vec<_>>>()?;
        let pairs: Vec<_> = frames.iter().map(|f| &f.scene).zip(&analyses).collect();
        let auto = &args.scene.auto;
        let aim = Aim {
            machine: auto.cost_on,
            target_psnr: auto.target_psnr,
            rescale: false,
            choose_pixels: super::chooses_pixels(
                &args.scene.sampling,
                frames.iter().map(|f| &f.scene),
            ),
        };
        let picked = pick(&pairs, methods, size, aim)?;
        let Choice::Reaches(pick) = &picked else {
            let why = picked.shortfall(auto.target_psnr).unwrap_or_default();
            bail!("for every frame of the path: {why}");
        };
        eprintln!(
            "--format auto: {} is the cheapest on {} that reaches {} dB on every frame (its \
             worst: {:.1} dB)",
            pick.named(),
            auto.cost_on,
            auto.target_psnr,
            pick.psnr_db
        );
        return Ok((pick.format, pick.pixels));
    };
    let own = frames.first().map_or(Pixels::Exact, |f| f.scene.pixels);
    Ok((format, own))
}

/// Frame `k`, built and proven for its own camera, drawn in `format` and in f64, and how far
/// apart the two are; refused where `format` strays from f64 as `compare` refuses.
fn render_frame(
    args: &AnimateArgs,
    frame: &NamedScene,
    k: u16,
    format: Format,
    methods: Methods,
) -> Result<(RgbImage, Accuracy)> {
    let request = Request::new(frame.scene.desc(), args.scene.size, methods);
    let contender = prepare(format, &request)?;
    let baseline = prepare_reference(&request)?;
    let image = contender.render(1, None)?;
    let truth = baseline.render(1, None)?;
    if args.scene.format == FormatChoice::Given(format) {
        let refusal = &args.scene.refusal;
        super::refuse_useless(refusal, format, &frame.scene, methods, &image, Some(&truth))
            .with_context(|| format!("frame {k}"))?;
    }
    let measured = accuracy(
        &image,
        &truth,
        &contender.object_map()?,
        &baseline.object_map()?,
    );
    Ok((image, measured))
}

/// Each frame's time on `target`'s board, a 240×240 frame in `format` drawn top-down (the
/// firmware's estimate, as `obscura preview` paces it).
fn board_times(
    target: Target,
    frames: &[NamedScene],
    format: Format,
    methods: Methods,
) -> Result<Vec<FrameTime>> {
    frames
        .iter()
        .zip(0_u16..)
        .map(|(frame, k)| {
            estimate::frame(target, format, &frame.scene.desc(), methods)?
                .map(|e| e.time(RowOrder::TopDown))
                .with_context(|| {
                    format!(
                        "no firmware runs {format}: the {} cannot pace frame {k}",
                        target.board().name
                    )
                })
        })
        .collect()
}

/// The loop on `target`'s board: each frame's time, the loop's and frames a second.
fn print_pace(target: Target, times: &[FrameTime]) -> Result<()> {
    let board = target.board();
    let seconds: f64 = times.iter().map(|t| t.frame).sum();
    let slowest = times.iter().map(|t| t.frame).fold(0.0, f64::max);
    say!(
        "on the {} (estimated, 240x240): {seconds:.2} s a loop, {:.2} frames a second, the \
         slowest frame {slowest:.2} s ({})",
        board.name,
        times.len() as f64 / seconds,
        if board.sends_by_dma {
            "each frame's sending overlapped with its tracing by DMA"
        } else {
            "each frame traced, then sent"
        }
    )?;
    Ok(())
}

/// A bar of `frames` frames on standard error when it is a terminal.
fn progress(name: &str, format: Format, frames: usize) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(frames as u64);
    let style = ProgressStyle::with_template("{msg}: {bar:40} {pos}/{len} frames {eta}")
        .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar.set_message(format!("{name} in {format}"));
    bar
}

/// One line per frame, then the worst.
fn print_reports(reports: &[FrameReport], pace: &str, gif: &std::path::Path) -> Result<()> {
    say!(
        "| frame | PSNR against f64 (dB) | mean abs error | max abs error | differing pixels | object mismatch |"
    )?;
    say!("|---:|---:|---:|---:|---:|---:|")?;
    for r in reports {
        say!(
            "| {} | {:.2} | {:.3} | {} | {:.2} % | {:.3} % |",
            r.frame,
            r.psnr_db,
            r.mean_abs_error,
            r.max_abs_error,
            r.differing_pixels_pct,
            r.object_mismatch_pct
        )?;
    }
    say!("wrote {} ({} frames {pace})", gif.display(), reports.len())?;
    if let Some(worst) = reports
        .iter()
        .min_by(|a, b| a.psnr_db.total_cmp(&b.psnr_db))
    {
        say!(
            "the worst frame: {} of {} in {}, {:.2} dB against f64 at {}x{}",
            worst.frame,
            worst.scene,
            worst.format,
            worst.psnr_db,
            worst.width,
            worst.height
        )?;
    }
    Ok(())
}
