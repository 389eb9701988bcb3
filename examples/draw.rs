//! A board-agnostic `draw`: a scene traced in fixed point onto any display whose colour is
//! RGB565, one row at a time through a single line buffer, as a board's firmware does. Here
//! the display is embedded-graphics' `MockDisplay` (64 × 64); on a board it is its driver
//! (mipidsi's ST7789, say).
//!
//! `cargo run --example draw`

use core::fmt;
use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use obscura::{
    I16F16, Presentation, RenderError, Scene, SceneDesc, SceneError, render_frame, scenes,
};

/// The widest display `draw` serves: its line buffer's length.
const MOST_WIDTH: usize = 320;

/// Why a scene was not drawn.
#[derive(Debug)]
enum DrawError<E> {
    /// The scene, or its camera at the display's size, was refused (and why).
    Scene(SceneError),
    /// The display failed, or is wider than the line buffer.
    Render(RenderError<E>),
}

impl<E: fmt::Debug> fmt::Display for DrawError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Scene(error) => write!(f, "{error}"),
            Self::Render(error) => write!(f, "{error}"),
        }
    }
}

/// Draws `desc` onto `display`, filling it, in 16.16 fixed point: at most 8 objects, 4 lights
/// and a ray stack of 6 (a ray tree 5 levels deep). No heap, no panic.
fn draw<D: DrawTarget<Color = Rgb565>>(
    desc: &SceneDesc<'_>,
    display: &mut D,
) -> Result<(), DrawError<D::Error>> {
    let size = display.bounding_box().size;
    let scene = Scene::<I16F16, 8, 4, 6>::build(desc).map_err(DrawError::Scene)?;
    let camera = scene
        .camera(size.width, size.height)
        .map_err(DrawError::Scene)?;
    let mut line = [Rgb565::BLACK; MOST_WIDTH];
    render_frame(
        &scene,
        &camera,
        Presentation::default(),
        &mut line,
        &mut [],
        display,
    )
    .map_err(DrawError::Render)
}

fn main() {
    let mut display = MockDisplay::<Rgb565>::new();
    match draw(&scenes::WHITTED, &mut display) {
        Ok(()) => {
            let lit = display.affected_area().size;
            println!("drew whitted onto a {}x{} display", lit.width, lit.height);
        }
        Err(error) => {
            eprintln!("error: {error}");
            std::process::exit(1);
        }
    }
}
