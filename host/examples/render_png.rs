//! A scene file rendered to a PNG on a desktop with the core alone: a `DrawTarget` over an
//! `image` buffer, drawn row by row as a display is, in `f32`. (`obscura render` does this and
//! more: every format, threads, the refusal of a useless format.)
//!
//! `cargo run --example render_png -- host/scenes/ball.toml ball.png`

use anyhow::{Context, Result};
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use image::RgbImage;
use obscura::{Presentation, render_frame};
use obscura_scene::{HostScene, error_text};
use std::convert::Infallible;

/// The image's side, in pixels.
const SIDE: u32 = 512;

/// An image as a display: each pixel drawn is written into it.
struct Canvas(RgbImage);

impl OriginDimensions for Canvas {
    fn size(&self) -> Size {
        Size::new(self.0.width(), self.0.height())
    }
}

impl DrawTarget for Canvas {
    type Color = Rgb888;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Infallible> {
        for Pixel(point, colour) in pixels {
            if let (Ok(x), Ok(y)) = (u32::try_from(point.x), u32::try_from(point.y))
                && let Some(pixel) = self.0.get_pixel_mut_checked(x, y)
            {
                *pixel = image::Rgb([colour.r(), colour.g(), colour.b()]);
            }
        }
        Ok(())
    }
}

/// Renders the scene file (or built-in scene) `name` to the PNG `output`.
fn render(name: &str, output: &str) -> Result<()> {
    let named = obscura_scene::load(name)?;
    let scene = HostScene::<f32>::build(&named.scene.desc())
        .map_err(|refusal| named.locate(refusal.into()))?;
    let camera = scene.camera(SIDE, SIDE)?;
    let mut canvas = Canvas(RgbImage::new(SIDE, SIDE));
    let mut line = vec![Rgb888::BLACK; SIDE as usize];
    let mut corners = vec![obscura::Corner::ZERO; obscura::corner_rows(SIDE)];
    render_frame(
        &scene,
        &camera,
        Presentation::default(),
        &mut line,
        &mut corners[..],
        &mut canvas,
    )?;
    canvas
        .0
        .save(output)
        .with_context(|| format!("cannot write {output}"))?;
    println!("wrote {} at {SIDE}x{SIDE} in f32 to {output}", named.name);
    Ok(())
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let outcome = match args.as_slice() {
        [scene, output] => render(scene, output),
        _ => Err(anyhow::anyhow!(
            "give a scene and a PNG to write: render_png host/scenes/ball.toml ball.png"
        )),
    };
    if let Err(error) = outcome {
        eprintln!("{}", error_text(&error));
        std::process::exit(1);
    }
}
