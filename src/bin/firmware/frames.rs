//! What the firmware renders: each enabled scene in each enabled format, with the scene's
//! storage (objects, lights, ray stack) sized by const generics to exactly what it needs.

use crate::SIDE;
use crate::clock::Clock;
use crate::stack;
use core::fmt;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use obscura::{Scalar, Scene, SceneDesc, render_rows, scenes};

/// What a display back-end provides: a display to draw each frame on, and a place to say how
/// it went.
pub trait Backend {
    /// The display.
    type Display: DrawTarget<Color = Rgb565, Error: fmt::Debug>;
    /// Lets `draw` draw the frame of `scene` in `format`.
    fn frame<R>(
        &mut self,
        scene: &str,
        format: &str,
        draw: impl FnOnce(&mut Self::Display) -> R,
    ) -> R;
    /// Reports a finished frame.
    fn report(&mut self, report: &Report<'_>);
    /// Reports a frame that could not be drawn, and why.
    fn failed(&mut self, scene: &str, format: &str, why: &dyn fmt::Display);
}

/// The measurements of one frame.
pub struct Report<'a> {
    /// The scene's name.
    pub scene: &'a str,
    /// The format's name.
    pub format: &'a str,
    /// SysTick ticks the frame took, from the first row to the last.
    pub ticks: u64,
    /// The stack's high-water mark during the frame, in bytes.
    pub stack_bytes: u32,
}

/// Renders one scene in each enabled format, its capacities computed from the description.
macro_rules! formats {
    ($backend:expr, $clock:expr, $name:literal, $desc:path) => {{
        const DESC: SceneDesc<'static> = $desc;
        const OBJECTS: usize = DESC.objects.len();
        const LIGHTS: usize = DESC.lights.len();
        const RAYS: usize = DESC.max_depth as usize + 1;
        #[cfg(feature = "format-i16f16")]
        render::<obscura::I16F16, OBJECTS, LIGHTS, RAYS>($backend, $clock, $name, &DESC);
        #[cfg(feature = "format-i32f32")]
        render::<obscura::I32F32, OBJECTS, LIGHTS, RAYS>($backend, $clock, $name, &DESC);
        #[cfg(feature = "format-f32")]
        render::<f32, OBJECTS, LIGHTS, RAYS>($backend, $clock, $name, &DESC);
    }};
}

/// Renders each enabled scene in each enabled format.
pub fn render_all(backend: &mut impl Backend, clock: &Clock) {
    #[cfg(feature = "scene-whitted")]
    formats!(backend, clock, "whitted", scenes::WHITTED);
    #[cfg(feature = "scene-shapes")]
    formats!(backend, clock, "shapes", scenes::SHAPES);
}

/// Builds the scene in format `S`, renders it top to bottom and reports the frame.
fn render<S: Scalar, const OBJECTS: usize, const LIGHTS: usize, const RAYS: usize>(
    backend: &mut impl Backend,
    clock: &Clock,
    name: &str,
    desc: &SceneDesc<'_>,
) {
    let built = Scene::<S, OBJECTS, LIGHTS, RAYS>::build(desc).and_then(|scene| {
        let camera = scene.camera(SIDE, SIDE)?;
        Ok((scene, camera))
    });
    let (scene, camera) = match built {
        Ok(built) => built,
        Err(error) => return backend.failed(name, S::NAME, &error),
    };
    let ((drawn, ticks), stack_bytes) = backend.frame(name, S::NAME, |display| {
        let mut line = [Rgb565::BLACK; SIDE as usize];
        stack::paint();
        let measured = clock.measure(|| render_rows(&scene, &camera, 0..SIDE, &mut line, display));
        (measured, stack::high_water())
    });
    match drawn {
        Ok(()) => backend.report(&Report {
            scene: name,
            format: S::NAME,
            ticks,
            stack_bytes,
        }),
        Err(error) => backend.failed(name, S::NAME, &error),
    }
}
