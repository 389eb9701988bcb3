//! `obscura analyze`: a scene's range analysis, in tables (see [`crate::analysis`]).

use crate::analysis::{
    Aim, Analysis, Bits, Choice, Extents, Fit, Pick, measure, measure_accuracy, pick,
};
use crate::cli::AnalyzeArgs;
use crate::cost::Machine;
use crate::output::say;
use anyhow::Result;
use obscura::{MethodName, Pixels};
use obscura_scene::{Format, NamedScene, OwnedScene};
use std::io;

pub fn run(args: &AnalyzeArgs) -> Result<()> {
    super::on_scene(&args.scene, &args.sampling, |named| analyze(args, named))
}

fn analyze(args: &AnalyzeArgs, named: &NamedScene) -> Result<()> {
    let (width, height) = args.size;
    let methods = args.methods.methods();
    // A camera path's every frame, each a still scene of its camera; a still scene alone.
    let frames = named.frames();
    let analyses = frames
        .iter()
        .map(|frame| Analysis::of(&frame.scene, methods, width, height))
        .collect::<Result<Vec<_>>>()?;
    let worst = worst_frame(&analyses);
    let (frame, analysis) = (&frames[worst], &analyses[worst]);
    say!("# {} by methods {methods}\n", frame.name)?;
    if frames.len() > 1 {
        say!(
            "{}'s camera path has {} frames, each analysed for its own camera; the tables are \
             of the one that needs the most integer bits, frame {worst}, and the pick holds for \
             every frame.\n",
            named.name,
            frames.len()
        )?;
    }
    print_extents(&analysis.extents)?;
    print_bits(&analysis.bits)?;
    print_split(analysis)?;
    print_formats(args, frame, analysis)?;
    let pairs: Vec<_> = frames.iter().map(|f| &f.scene).zip(&analyses).collect();
    let choice = pick_for(args, &pairs)?;
    if let Choice::Reaches(pick) | Choice::Closest(pick) = &choice {
        print_pixels(args, frame, analysis, pick)?;
    }
    print_pick(args, &choice)
}

/// Of a camera path's frames' `analyses`, the one whose 32-bit split has the fewest fraction
/// bits (none holding it first): the frame a format must be chosen for. The first such.
fn worst_frame(analyses: &[Analysis]) -> usize {
    let fraction = |a: &Analysis| a.split(false).and_then(|f| f.split()).map(|(_, f)| f);
    (0..analyses.len())
        .min_by_key(|&i| fraction(&analyses[i]).map_or(-1, i64::from))
        .unwrap_or(0)
}

/// The scene's 32-bit split, as it is or rescaled.
fn print_split(analysis: &Analysis) -> io::Result<()> {
    let split_line = |split: Format| {
        let (integer, fraction) = split.split().unwrap_or_default();
        format!(
            "the 32-bit fixed format with the most fraction bits that holds it: **{split}** \
             ({integer} integer bits, the sign among them, and {fraction} fraction bits)"
        )
    };
    match (analysis.split(false), analysis.split(true)) {
        (Some(split), _) => say!("\nThe scene's 32-bit split, {}.", split_line(split)),
        (None, Some(split)) => say!(
            "\nNo 32-bit fixed format holds the scene as it is; rescaled about the eye, its split \
             is {}.",
            split_line(split)
        ),
        (None, None) => say!("\nNo 32-bit fixed format holds the scene, even rescaled."),
    }
}

/// Every format: whether it holds the scene, its prediction beside the PSNR measured, and its
/// costs from the chart (`docs/images/speed-accuracy.csv`).
fn print_formats(args: &AnalyzeArgs, named: &NamedScene, analysis: &Analysis) -> Result<()> {
    let size @ (width, height) = args.size;
    let methods = args.methods.methods();
    say!(
        "\n## Formats, at {width}x{height}\n\nThe model's bound against f64 (the format's \
         constants and tolerances, rendered in f64; its rounding, which may move each pixel's \
         ray by up to the shift shown, tried on the f64 scene; and the shading's rounding), \
         beside the PSNR measured on the host, which computes the firmware's bits. \"narrow\": \
         the format its cosines, colours and weights are kept in (2.14 bits on 16, or 2.30 on \
         32: one 16×16 product where the M0 takes four). Cost per \
         pixel from the chart (docs/images/speed-accuracy.csv), on the built-in scene like this one ({}).\n",
        if analysis.has_triangles {
            "with triangles"
        } else {
            "without triangles"
        }
    )?;
    let scene = &named.scene;
    if !scene.desc().traces_one_ray() {
        say!(
            "The chart measures one ray per pixel and one shadow ray per light; this scene takes \
             {} rays per pixel and up to {} shadow rays per area light, which multiply the costs \
             below (`obscura firmware` measures them).\n",
            scene.samples,
            scene.shadow_samples
        )?;
    }
    let (cost_headings, cost_rule) = Machine::columns();
    say!(
        "| format | narrow | holds the scene | predicted PSNR ≥ (dB) | shift (px) | predicted \
         object mismatch ≤ | measured PSNR (dB) |{cost_headings}"
    )?;
    say!("|---|---|---|---:|---:|---:|---:|{cost_rule}")?;
    let number = |x: Option<f64>| x.map_or("–".to_owned(), |x| format!("{x:.0}"));
    for verdict in &analysis.verdicts {
        let scene = match verdict.fit {
            Fit::Holds => Some(named.scene.clone()),
            Fit::Rescaled(factor) => Some(named.scene.scaled(factor as f32)),
            Fit::Refused(_) => None,
        };
        let measured = scene
            .map(|scene| measure(verdict.format, &scene, methods, size))
            .transpose()?;
        let fit = match &verdict.fit {
            Fit::Holds => "yes".to_owned(),
            Fit::Rescaled(factor) => format!("rescaled ×{factor} about the eye"),
            Fit::Refused(reason) => format!("no: {reason}"),
        };
        let p = verdict.prediction;
        let costs =
            Machine::cells(|m| number(analysis.cost(m, verdict.format, &methods, Pixels::Exact)));
        say!(
            "| {} | {} | {fit} | {} | {} | {} | {} |{costs}",
            verdict.format,
            verdict.format.narrow(),
            p.map_or("–".to_owned(), |p| decibels(p.psnr_db)),
            p.map_or("–".to_owned(), |p| format!("{:.3}", p.shift_px)),
            p.map_or("–".to_owned(), |p| format!("{:.3} %", p.mismatch_pct)),
            measured.map_or("–".to_owned(), decibels),
        )?;
    }
    Ok(())
}

/// The cheapest format (and pixels, where the scene leaves them to it) that reaches the target
/// on every one of `frames`, what `--format auto` takes; a camera path's frames are not
/// rescaled.
fn pick_for(args: &AnalyzeArgs, frames: &[(&OwnedScene, &Analysis)]) -> Result<Choice> {
    let aim = Aim {
        machine: args.auto.cost_on,
        target_psnr: args.auto.target_psnr,
        rescale: frames.len() == 1,
        choose_pixels: super::chooses_pixels(&args.sampling, frames.iter().map(|(s, _)| *s)),
    };
    pick(frames, args.methods.methods(), args.size, aim)
}

/// The pixels axis in the format `pick` took: each way of finding pixels the scene takes, its
/// PSNR and object mismatch against f64 with exact pixels, measured, and its cost on each
/// machine by the charts (the format's, times what the pixels axis measured adaptive pixels
/// to cost in its kind).
fn print_pixels(
    args: &AnalyzeArgs,
    named: &NamedScene,
    analysis: &Analysis,
    pick: &Pick,
) -> Result<()> {
    let (format, methods) = (pick.format, args.methods.methods());
    let (width, height) = args.size;
    say!(
        "\n## Pixels, in {format} at {width}x{height}\n\nExact pixels trace every pixel; \
         adaptive:N traces the corners of N×N blocks and fills a block whose corners agree \
         (docs/several-rays.md). Measured against f64 with exact pixels; the cost is the \
         format's times what adaptive pixels cost in its kind on the chart's pixels axis \
         (docs/images/pixels-accuracy.csv; – where it was not measured).\n"
    )?;
    let desc = named.scene.desc();
    if let Err(why) = desc.takes_pixels(Pixels::Adaptive(2)) {
        say!("The scene takes exact pixels only: {why}.")?;
        return Ok(());
    }
    let (cost_headings, cost_rule) = Machine::columns();
    say!("| pixels | measured PSNR (dB) | object mismatch |{cost_headings}")?;
    say!("|---|---:|---:|{cost_rule}")?;
    for &(pixels, name) in Pixels::ALL {
        let scene = Pick {
            pixels,
            ..pick.clone()
        }
        .scene(&named.scene);
        let measured = measure_accuracy(format, &scene, methods, args.size)?;
        let costs = Machine::cells(|m| {
            let cost = analysis.cost(m, format, &methods, pixels);
            cost.map_or("–".to_owned(), |x| format!("{x:.0}"))
        });
        say!(
            "| {name} | {} | {:.4} % |{costs}",
            decibels(measured.psnr_db),
            measured.object_mismatch_pct
        )?;
    }
    Ok(())
}

/// What `--format auto` takes by `choice`, or why it takes nothing.
fn print_pick(args: &AnalyzeArgs, choice: &Choice) -> Result<()> {
    let (target, machine) = (args.auto.target_psnr, args.auto.cost_on);
    match choice {
        Choice::Reaches(pick) => {
            let how = pick.rescaled.map_or(String::new(), |factor| {
                format!(", rescaled ×{factor} about the eye")
            });
            say!(
                "\nthe cheapest on {machine} that reaches {target} dB: {}{how} (--format auto)",
                pick.named()
            )?;
        }
        choice => say!("\n{}", choice.shortfall(target).unwrap_or_default())?,
    }
    Ok(())
}

/// A PSNR in dB as the tables print it.
pub fn decibels(db: f64) -> String {
    if db.is_finite() {
        format!("{db:.1}")
    } else {
        "∞".to_owned()
    }
}

fn print_extents(e: &Extents) -> io::Result<()> {
    say!("## Extents, relative to the eye\n")?;
    say!(
        "- objects: {}, lights: {}; the world reaches {} from the eye",
        e.objects,
        e.lights,
        e.world
    )?;
    if let Some((lo, hi)) = e.bounds {
        say!(
            "- spheres and triangles within x {:.3} to {:.3}, y {:.3} to {:.3}, z {:.3} to {:.3}",
            lo[0],
            hi[0],
            lo[1],
            hi[1],
            lo[2],
            hi[2]
        )?;
    }
    say!(
        "- depth: the nearest surface {:.4} from the eye, the farthest {:.4}",
        e.nearest,
        e.farthest
    )?;
    let smallest = |what: &str, found: Option<(f64, usize)>| {
        if let Some((value, object)) = found {
            say!("- smallest {what}: {value} (object {object})")?;
        }
        Ok(())
    };
    smallest("sphere radius", e.smallest_radius)?;
    smallest("triangle edge", e.shortest_edge)?;
    smallest("checker square", e.smallest_square)
}

fn print_bits(rows: &[Bits]) -> io::Result<()> {
    say!(
        "\n## Bits a fixed-point format needs\n\nInteger bits (sign included) hold the largest \
         intermediate value; fraction bits resolve the most demanding feature.\n"
    )?;
    say!(
        "| computation | largest intermediate | integer bits | most demanding feature | \
         fraction bits |"
    )?;
    say!("|---|---|---:|---|---:|")?;
    for row in rows {
        let largest = row.largest.map_or("–".to_owned(), |m| {
            format!("{}: {} = {:.4e}", m.item, m.quantity, m.value)
        });
        let finest = row.finest.map_or("–".to_owned(), |f| {
            format!("{}: {} = {:.4e}", f.item, f.quantity, f.value)
        });
        say!(
            "| {} | {largest} | {} | {finest} | {} |",
            row.computation,
            row.integer,
            row.fraction
        )?;
    }
    Ok(())
}
