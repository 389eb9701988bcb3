//! `obscura render`: one scene, one format, one PNG.

use crate::cli::RenderArgs;
use crate::render::{Request, prepare};
use anyhow::Result;
use std::time::Instant;

pub fn run(args: &RenderArgs) -> Result<()> {
    let scene = super::scene(&args.scene.scene)?;
    let (width, height) = args.scene.size;
    let methods = args.scene.methods.methods();
    let request = Request {
        desc: &scene.desc,
        width,
        height,
        methods,
    };
    let prepared = prepare(args.scene.format, &request)?;
    let label = format!("rendering {} in {}", scene.name, args.scene.format);
    let start = Instant::now();
    let image = prepared.render(usize::from(args.threads), Some(&label));
    let ms = start.elapsed().as_secs_f64() * 1e3;
    super::save(&image, &args.output)?;
    println!(
        "{} {width}x{height} in {} on {} threads: {ms:.1} ms; wrote {}",
        scene.name,
        args.scene.format,
        args.threads,
        args.output.display()
    );
    Ok(())
}
