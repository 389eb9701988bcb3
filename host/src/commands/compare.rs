//! `obscura compare`: a format against the f64 reference, in numbers and pictures.

use crate::cli::CompareArgs;
use crate::heatmap::heatmap;
use crate::metrics::{Accuracy, accuracy, psnr_db};
use crate::output::{self, say};
use crate::render::{AnyFormat, Request, all_cores, prepare, prepare_reference, rgb565_image};
use crate::timing::interleaved_median_ms;
use anyhow::{Context, Result};
use obscura::methods::MethodName;
use obscura::{Dither, Pixels, Presentation};
use obscura_scene::{Format, FormatChoice, NamedScene, OwnedScene};
use serde::Serialize;
use std::io;
use std::path::PathBuf;

/// The figures `compare` prints and writes as JSON.
#[derive(Debug, Serialize)]
pub struct Report {
    pub format: &'static str,
    pub reference: &'static str,
    pub scene: String,
    pub width: u32,
    pub height: u32,
    /// `null` in JSON when the images are identical (infinite PSNR).
    pub psnr_db: f64,
    pub mean_abs_error: f64,
    pub max_abs_error: u8,
    pub differing_pixels_pct: f64,
    pub object_mismatch_pct: f64,
    pub ms_per_frame: f64,
    pub reference_ms_per_frame: f64,
    pub runs: u16,
    /// The frame as an RGB565 display shows it, each colour rounded to the nearest level:
    /// its PSNR against f64 (`null` when identical).
    pub rgb565_psnr_db: f64,
    /// The same with the ordered dither ([`obscura::Dither::Ordered`]).
    pub rgb565_dithered_psnr_db: f64,
    /// With `--converged`: both images against an f64 render with more samples.
    pub converged: Option<Converged>,
}

/// Both images against an f64 render with many rays per pixel: how far the scene's samples are
/// from the converged image (the format's numeric error is the difference between the two).
#[derive(Debug, Serialize)]
pub struct Converged {
    /// The converged render's rays per pixel, and shadow rays per disc light.
    pub samples: u16,
    /// The scene's own rays per pixel (with adaptive samples, the most cells a pixel splits
    /// into).
    pub scene_samples: u16,
    /// Whether the scene's samples are adaptive ([`obscura::SceneDesc::adaptive_samples`]).
    pub adaptive_samples: bool,
    /// The format's image against it (`null` when identical).
    pub psnr_db: f64,
    /// The f64 image with the scene's samples against it (`null` when identical).
    pub reference_psnr_db: f64,
}

pub fn run(args: &CompareArgs) -> Result<()> {
    output::check_dir(&args.out_dir)?;
    if let Some(path) = &args.json {
        output::check_file(path)?;
    }
    super::on_scene(&args.scene.scene, &args.scene.sampling, |named| {
        compare(args, named)
    })
}

fn compare(args: &CompareArgs, named: &NamedScene) -> Result<()> {
    let super::Resolved {
        name,
        format,
        scene,
        methods,
    } = super::resolve(named, &args.scene)?;
    let (width, height) = args.scene.size;
    let request = Request::new(scene.desc(), (width, height), methods);
    let contender = prepare(format, &request)?;
    let baseline = prepare_reference(&request)?;
    let rendering = |format: Format| format!("rendering {name} in {format}");
    let image = contender
        .render(all_cores(), None)
        .with_context(|| rendering(format))?;
    let truth = baseline
        .render(all_cores(), None)
        .with_context(|| rendering(REFERENCE))?;
    if let FormatChoice::Given(format) = args.scene.format {
        let (refusal, drawn) = (&args.scene.refusal, &image);
        super::refuse_useless(refusal, format, &scene, methods, drawn, Some(&truth))?;
    }
    let times = time(args, format, contender.as_ref(), baseline.as_ref());
    let files = [
        (args.out_dir.join(format!("{format}.png")), &image),
        (args.out_dir.join(format!("{REFERENCE}.png")), &truth),
        (args.out_dir.join("diff.png"), &heatmap(&image, &truth)),
    ];
    for (path, image) in &files {
        super::save(image, path)?;
    }
    let objects = contender.object_map()?;
    let Accuracy {
        psnr_db,
        mean_abs_error,
        max_abs_error,
        differing_pixels_pct,
        object_mismatch_pct,
    } = accuracy(&image, &truth, &objects, &baseline.object_map()?);
    let rgb565 = rgb565_figures(args, format, contender.as_ref(), &truth)?;
    let converged = args
        .converged
        .map(|samples| converged(samples, &scene, &request, [&image, &truth], &objects))
        .transpose()?;
    // Adaptive pixels named beside the scene: the reference's pixels are exact.
    let scene_name = match scene.pixels {
        Pixels::Exact => name,
        pixels => format!("{name}, {}", pixels.name()),
    };
    let report = Report {
        format: format.name(),
        reference: REFERENCE.name(),
        scene: scene_name,
        width,
        height,
        psnr_db,
        mean_abs_error,
        max_abs_error,
        differing_pixels_pct,
        object_mismatch_pct,
        ms_per_frame: times[0],
        reference_ms_per_frame: times[1],
        runs: args.runs,
        rgb565_psnr_db: rgb565[0].0,
        rgb565_dithered_psnr_db: rgb565[1].0,
        converged,
    };
    print_report(&report, &rgb565, &files.map(|(path, _)| path))?;
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&report)?;
        std::fs::write(path, text + "\n")
            .with_context(|| format!("cannot write {}", path.display()))?;
        say!("wrote {}", path.display())?;
    }
    Ok(())
}

/// What a format is compared against.
const REFERENCE: Format = Format::F64;

/// The median single-thread times of a frame in `format` and in f64, interleaved.
fn time(
    args: &CompareArgs,
    format: Format,
    contender: &dyn AnyFormat,
    baseline: &dyn AnyFormat,
) -> Vec<f64> {
    eprintln!(
        "timing {format} and {REFERENCE} on 1 thread, {} interleaved runs each",
        args.runs
    );
    interleaved_median_ms(
        usize::from(args.runs),
        &[&|| drop(contender.render(1, None)), &|| {
            drop(baseline.render(1, None))
        }],
    )
}

/// The frame as an RGB565 display shows it, rounded to the nearest level and dithered: each
/// one's PSNR against f64, and the PNG written of it.
fn rgb565_figures(
    args: &CompareArgs,
    format: Format,
    contender: &dyn AnyFormat,
    truth: &image::RgbImage,
) -> Result<Vec<(f64, PathBuf)>> {
    let mut figures = Vec::new();
    for dither in [Dither::None, Dither::Ordered] {
        let presentation = Presentation {
            dither,
            ..Presentation::default()
        };
        let frame = rgb565_image(
            &contender.rgb565_frame(presentation, &mut |_, _| {})?,
            args.scene.size.0,
        );
        let path = args
            .out_dir
            .join(format!("{format}-rgb565-dither-{}.png", dither.name()));
        super::save(&frame, &path)?;
        figures.push((psnr_db(&frame, truth), path));
    }
    Ok(figures)
}

/// The format's and f64's `images` against an f64 render of `scene` with `samples` rays per
/// pixel and per disc light, all traced.
fn converged(
    samples: u16,
    scene: &OwnedScene,
    request: &Request<'_>,
    [image, truth]: [&image::RgbImage; 2],
    objects: &[Option<usize>],
) -> Result<Converged> {
    let mut many = scene.clone();
    many.samples = samples;
    many.adaptive_samples = false;
    many.shadow_samples = samples;
    many.adaptive_shadows = false;
    let converged = prepare_reference(&request.with_desc(many.desc()))?
        .render(all_cores(), Some("converged f64"))
        .context("rendering the converged f64 image")?;
    let psnr = |image| accuracy(image, &converged, objects, objects).psnr_db;
    Ok(Converged {
        samples,
        scene_samples: scene.samples,
        adaptive_samples: scene.adaptive_samples,
        psnr_db: psnr(image),
        reference_psnr_db: psnr(truth),
    })
}

/// The table, the RGB565 figures, the converged figures, and the files written.
fn print_report(
    report: &Report,
    rgb565: &[(f64, PathBuf)],
    files: &[PathBuf; 3],
) -> io::Result<()> {
    print_table(report)?;
    if let [(_, plain), (_, dithered)] = rgb565 {
        say!(
            "as an RGB565 display shows it: {:.2} dB against f64 rounded to the nearest level, \
             {:.2} dB with the ordered dither (wrote {} and {})",
            report.rgb565_psnr_db,
            report.rgb565_dithered_psnr_db,
            plain.display(),
            dithered.display()
        )?;
    }
    if let Some(c) = &report.converged {
        say!(
            "against f64 with {} rays per pixel (how far {}{} are from converged): {} {:.2} \
             dB, {REFERENCE} {:.2} dB",
            c.samples,
            if c.adaptive_samples { "adaptive " } else { "" },
            c.scene_samples,
            report.format,
            c.psnr_db,
            c.reference_psnr_db
        )?;
    }
    say!(
        "wrote {}, {} and {} (diff: largest channel error per pixel, log scale, legend below)",
        files[0].display(),
        files[1].display(),
        files[2].display()
    )
}

fn print_table(r: &Report) -> io::Result<()> {
    let psnr = if r.psnr_db.is_infinite() {
        "∞ (identical)".to_owned()
    } else {
        format!("{:.2}", r.psnr_db)
    };
    // Times, where shown, as the last two columns.
    use crate::timing::or_omitted;
    let time_heads = or_omitted(|| " ms/frame | f64 ms/frame |".to_owned());
    let time_rule = or_omitted(|| "---:|---:|".to_owned());
    let time_cells =
        or_omitted(|| format!(" {:.1} | {:.1} |", r.ms_per_frame, r.reference_ms_per_frame));
    say!(
        "| scene | size | format | PSNR (dB) | mean error | max error | pixels differing | object mismatch |{time_heads}"
    )?;
    say!("|---|---|---|---:|---:|---:|---:|---:|{time_rule}")?;
    say!(
        "| {} | {}x{} | {} | {psnr} | {:.4} | {} | {:.3} % | {:.4} % |{time_cells}",
        r.scene,
        r.width,
        r.height,
        r.format,
        r.mean_abs_error,
        r.max_abs_error,
        r.differing_pixels_pct,
        r.object_mismatch_pct,
    )?;
    Ok(())
}
