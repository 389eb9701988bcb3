//! `obscura render`: one scene, one format, one PNG.

use crate::cli::RenderArgs;
use crate::operations;
use crate::output::{self, say};
use crate::render::{Request, prepare};
use anyhow::{Context, Result};
use obscura_scene::{FormatChoice, NamedScene};
use std::time::Instant;

pub fn run(args: &RenderArgs) -> Result<()> {
    output::check_image(&args.output)?;
    super::on_scene(&args.scene.scene, &args.scene.sampling, |named| {
        render(args, named)
    })
}

fn render(args: &RenderArgs, named: &NamedScene) -> Result<()> {
    let super::Resolved {
        name,
        format,
        scene,
        methods,
    } = super::resolve(named, &args.scene)?;
    let (width, height) = args.scene.size;
    let request = Request::new(scene.desc(), (width, height), methods);
    let prepared = prepare(format, &request)?;
    let label = format!("rendering {} in {format}", name);
    let start = Instant::now();
    let image = prepared
        .render(usize::from(args.threads), Some(&label))
        .with_context(|| format!("rendering {name} in {format}"))?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    if let FormatChoice::Given(format) = args.scene.format {
        super::refuse_useless(&args.scene.refusal, format, &scene, methods, &image, None)?;
    }
    super::save(&image, &args.output)?;
    let time = crate::timing::or_omitted(|| format!(" on {} threads in {ms:.1} ms", args.threads));
    say!(
        "{name} {width}x{height} in {}{time}: wrote {}",
        crate::analysis::with_pixels(format, scene.pixels),
        args.output.display()
    )?;
    if args.count {
        let (count, counted) = operations::count(format, &request)
            .with_context(|| format!("counting the operations of {name} in {format}"))?;
        anyhow::ensure!(
            counted == image,
            "counting changed the picture of {name} in {format} (a bug in obscura's counter)"
        );
        say!(
            "{name} {width}x{height} in {format} by {methods}, the tracer's operations \
             (counted on the host, one per textbook operation):\n{}",
            count.table()
        )?;
    }
    Ok(())
}
