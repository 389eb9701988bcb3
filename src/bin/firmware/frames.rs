//! What the firmware renders: each enabled scene in each enabled format, by the methods the
//! features choose (or, with `chart`, by each variant of them), with the scene's storage
//! (objects, lights, ray stack) sized by const generics to exactly what it needs.

use crate::SIDE;
use crate::clock::Clock;
use crate::stack;
use core::fmt;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use obscura::{
    BiasMethod, Methods, RayMethod, RootMethod, Scalar, Scene, SceneDesc, SceneError, SphereMethod,
    TriangleMethod, render_rows, scenes,
};

/// What a display back-end provides: a display to draw each frame on, and a place to say how
/// it went.
pub trait Backend {
    /// The display.
    type Display: DrawTarget<Color = Rgb565, Error: fmt::Debug>;
    /// Lets `draw` draw the frame of `job`.
    fn frame<R>(&mut self, job: &Job<'_>, draw: impl FnOnce(&mut Self::Display) -> R) -> R;
    /// Reports a finished frame.
    fn report(&mut self, report: &Report<'_>);
    /// Reports a frame that could not be drawn, and why.
    fn failed(&mut self, job: &Job<'_>, why: &dyn fmt::Display);
    /// Reports a chart variant whose scene the format cannot hold by its methods, and why:
    /// an outcome of the comparison, not a failure.
    fn refused(&mut self, job: &Job<'_>, why: &dyn fmt::Display);
}

/// One frame to draw.
pub struct Job<'a> {
    /// The scene's name.
    pub scene: &'a str,
    /// The format's name.
    pub format: &'a str,
    /// The methods.
    pub methods: Methods,
}

/// The measurements of one frame.
pub struct Report<'a> {
    /// What was drawn.
    pub job: &'a Job<'a>,
    /// SysTick ticks the frame took, from the first row to the last.
    pub ticks: u64,
    /// The stack's high-water mark during the frame, in bytes.
    pub stack_bytes: u32,
    /// Bytes of the scene and its ray stack with capacities sized to the scene.
    pub storage_bytes: usize,
    /// The same with the host's fixed capacities (64 objects, 16 lights, 16 rays).
    pub fixed_storage_bytes: usize,
}

/// The methods the features choose; the lecture's where they choose none.
const METHODS: Methods = Methods {
    sphere: if cfg!(feature = "sphere-stable") {
        SphereMethod::Stable
    } else {
        SphereMethod::Quadratic
    },
    triangle: if cfg!(feature = "triangle-watertight") {
        TriangleMethod::Watertight
    } else if cfg!(feature = "triangle-moller-trumbore") {
        TriangleMethod::MollerTrumbore
    } else {
        TriangleMethod::Cramer
    },
    roots: if cfg!(feature = "sqrt-approx") {
        RootMethod::Approx
    } else {
        RootMethod::Exact
    },
    rays: if cfg!(feature = "rays-stepped") {
        RayMethod::Stepped
    } else {
        RayMethod::PerPixel
    },
    bias: if cfg!(feature = "bias-exclude") {
        BiasMethod::Exclude
    } else {
        BiasMethod::Epsilon
    },
};

/// The host's capacities, against which the sized storage is reported.
const FIXED_OBJECTS: usize = 64;
const FIXED_LIGHTS: usize = 16;
const FIXED_RAYS: usize = 16;

/// Renders one scene in each enabled format, its capacities computed from the description.
macro_rules! formats {
    ($backend:expr, $clock:expr, $name:literal, $desc:path) => {{
        const DESC: SceneDesc<'static> = $desc;
        const OBJECTS: usize = DESC.objects.len();
        const LIGHTS: usize = DESC.lights.len();
        const RAYS: usize = DESC.max_depth as usize + 1;
        #[cfg(feature = "format-i16f16")]
        variants::<obscura::I16F16, OBJECTS, LIGHTS, RAYS>($backend, $clock, $name, &DESC);
        #[cfg(feature = "format-i20f12")]
        variants::<obscura::I20F12, OBJECTS, LIGHTS, RAYS>($backend, $clock, $name, &DESC);
        #[cfg(feature = "format-i32f32")]
        variants::<obscura::I32F32, OBJECTS, LIGHTS, RAYS>($backend, $clock, $name, &DESC);
        #[cfg(feature = "format-f32-approx")]
        variants::<obscura::F32Approx, OBJECTS, LIGHTS, RAYS>($backend, $clock, $name, &DESC);
        #[cfg(feature = "format-f32")]
        variants::<f32, OBJECTS, LIGHTS, RAYS>($backend, $clock, $name, &DESC);
    }};
}

/// Renders each enabled scene in each enabled format.
pub fn render_all(backend: &mut impl Backend, clock: &Clock) {
    #[cfg(feature = "scene-whitted")]
    formats!(backend, clock, "whitted", scenes::WHITTED);
    #[cfg(feature = "scene-shapes")]
    formats!(backend, clock, "shapes", scenes::SHAPES);
}

/// Renders a scene in format `S` by [`METHODS`], and with `chart` by each of its variants that
/// makes sense ([`Methods::variants`], [`Methods::matter`]), none twice.
fn variants<S: Scalar, const OBJECTS: usize, const LIGHTS: usize, const RAYS: usize>(
    backend: &mut impl Backend,
    clock: &Clock,
    name: &str,
    desc: &SceneDesc<'_>,
) {
    let variants = METHODS.variants();
    let chosen = if cfg!(feature = "chart") {
        &variants[..]
    } else {
        &variants[..1]
    };
    for (i, &methods) in chosen.iter().enumerate() {
        let repeated = chosen
            .get(..i)
            .is_some_and(|earlier| earlier.contains(&methods));
        if !repeated && methods.matter::<S>(&METHODS, desc.has_triangles()) {
            let job = Job {
                scene: name,
                format: S::NAME,
                methods,
            };
            render::<S, OBJECTS, LIGHTS, RAYS>(backend, clock, &job, desc);
        }
    }
}

/// Builds the scene in format `S`, renders it top to bottom and reports the frame.
fn render<S: Scalar, const OBJECTS: usize, const LIGHTS: usize, const RAYS: usize>(
    backend: &mut impl Backend,
    clock: &Clock,
    job: &Job<'_>,
    desc: &SceneDesc<'_>,
) {
    // Hidden from the optimiser, so that no build folds a constant scene into the tracer: every
    // frame measures the same general code, whichever scenes and formats share the firmware.
    let desc = core::hint::black_box(desc);
    // The stack is measured over the whole job: building the scene proves its range in f64
    // and takes more stack than many a frame.
    stack::paint();
    let scene = match Scene::<S, OBJECTS, LIGHTS, RAYS>::build_with(desc, job.methods) {
        Ok(scene) => scene,
        Err(error) => return refuse(backend, job, &error),
    };
    let camera = match scene.camera(SIDE, SIDE) {
        Ok(camera) => camera,
        Err(error) => return refuse(backend, job, &error),
    };
    let (drawn, ticks) = backend.frame(job, |display| {
        let mut line = [Rgb565::BLACK; SIDE as usize];
        clock.measure(|| render_rows(&scene, &camera, 0..SIDE, &mut line, display))
    });
    let stack_bytes = stack::high_water();
    match drawn {
        Ok(()) => backend.report(&Report {
            job,
            ticks,
            stack_bytes,
            storage_bytes: Scene::<S, OBJECTS, LIGHTS, RAYS>::storage_bytes(),
            fixed_storage_bytes: Scene::<S, FIXED_OBJECTS, FIXED_LIGHTS, FIXED_RAYS>::storage_bytes(
            ),
        }),
        Err(error) => backend.failed(job, &error),
    }
}

/// Reports a scene the firmware cannot build: without its figures, as formatting floats would
/// cost a quarter of the flash, and the host's build of the same scene and format says the same
/// with them. The chart firmware tries every method variant and expects some to be refused.
fn refuse(backend: &mut impl Backend, job: &Job<'_>, error: &SceneError) {
    if cfg!(feature = "chart") {
        backend.refused(job, &error.without_figures());
    } else {
        backend.failed(job, &error.without_figures());
    }
}
