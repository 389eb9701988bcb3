//! `obscura render`: one scene, one format, one PNG.

use crate::cli::RenderArgs;
use crate::render::{Request, prepare};
use crate::scene_file;
use anyhow::Result;
use std::time::Instant;

pub fn run(args: &RenderArgs) -> Result<()> {
    let named = scene_file::load(&args.scene.scene)?;
    let (width, height) = args.scene.size;
    let methods = args.scene.methods.methods();
    let (format, scene) = super::resolve(
        args.scene.format,
        &named,
        methods,
        args.scene.size,
        &args.scene.auto,
    )?;
    let desc = scene.desc();
    let request = Request {
        desc: &desc,
        width,
        height,
        methods,
    };
    let prepared = prepare(format, &request)?;
    let label = format!("rendering {} in {format}", named.name);
    let start = Instant::now();
    let image = prepared.render(usize::from(args.threads), Some(&label));
    let ms = start.elapsed().as_secs_f64() * 1e3;
    super::save(&image, &args.output)?;
    println!(
        "{} {width}x{height} in {format} on {} threads: {ms:.1} ms; wrote {}",
        named.name,
        args.threads,
        args.output.display()
    );
    Ok(())
}
