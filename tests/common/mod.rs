//! Shared helpers of the integration tests: whole frames rendered through the public API.

#![allow(dead_code, reason = "each test file uses a part")]

use core::convert::Infallible;
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use obscura::{Corner, Methods, Presentation, Scalar, Scene, SceneDesc, corner_rows, render_frame};

/// A frame in memory: what a display would show.
pub struct Frame {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Rgb888>,
}

impl OriginDimensions for Frame {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

impl DrawTarget for Frame {
    type Color = Rgb888;
    type Error = Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            self.pixels[(p.y as u32 * self.width + p.x as u32) as usize] = c;
        }
        Ok(())
    }
}

/// The scene rendered in format `S` by `methods`, and the object each primary ray hit.
pub fn render<S: Scalar>(
    desc: &SceneDesc<'_>,
    width: u32,
    height: u32,
    methods: Methods,
) -> (Frame, Vec<Option<usize>>) {
    let scene = Scene::<S, 16, 4, 8>::build_with(desc, methods).expect("the scene builds");
    let camera = scene.camera(width, height).expect("the size is valid");
    let mut frame = Frame {
        width,
        height,
        pixels: vec![Rgb888::BLACK; (width * height) as usize],
    };
    let mut line = vec![Rgb888::BLACK; width as usize];
    let mut corners = vec![Corner::ZERO; corner_rows(width)];
    render_frame(
        &scene,
        &camera,
        Presentation::default(),
        &mut line,
        corners.as_mut_slice(),
        &mut frame,
    )
    .expect("renders");
    let objects = (0..height)
        .filter_map(|y| camera.row(y))
        .flat_map(|row| row.rays())
        .map(|ray| scene.first_hit(&ray).map(|(object, _)| object))
        .collect();
    (frame, objects)
}

/// PSNR in dB over the RGB888 channels; infinite for identical frames.
pub fn psnr(a: &Frame, b: &Frame) -> f64 {
    let channels = |c: &Rgb888| [c.r(), c.g(), c.b()];
    let squared: f64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(p, q)| channels(p).into_iter().zip(channels(q)))
        .map(|(x, y)| f64::from(x.abs_diff(y)).powi(2))
        .sum();
    let mse = squared / (3 * a.pixels.len()) as f64;
    10.0 * (255.0 * 255.0 / mse).log10()
}

/// The share of pixels, in percent, whose primary ray hit another object.
pub fn mismatch_pct(a: &[Option<usize>], b: &[Option<usize>]) -> f64 {
    100.0 * a.iter().zip(b).filter(|(x, y)| x != y).count() as f64 / a.len() as f64
}
