//! # obscura
//!
//! A `no_std` ray tracer for microcontroller displays that computes in fixed point: Whitted's
//! ray tracer (pinhole camera, spheres, planes and triangles, shadows, reflection, refraction)
//! and from distributed ray tracing several rays per pixel, soft shadows from disc lights and
//! depth of field through a thin lens, written once over a [`Scalar`] number format, drawing
//! scanline by scanline onto any embedded-graphics
//! [`DrawTarget`](embedded_graphics_core::draw_target::DrawTarget) through a single line
//! buffer.
//!
//! A firmware proves its scene when it is built, on the computer: its build script's
//! `obscura_scene::build::Proof` writes `scene.rs`, and the chip draws the proven scene in one
//! call, keeping only its numbers in flash (the repository's `templates/pico` is such a firmware):
//!
//! ```ignore
//! mod scene {
//!     include!(concat!(env!("OUT_DIR"), "/scene.rs"));
//! }
//! scene::draw(&mut display)?; // any DrawTarget<Color = Rgb565>; errors are RenderError
//! ```
//!
//! A scene can also be built and proven where it is drawn, as here on the desktop:
//!
//! ```
//! use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb565};
//! use obscura::{I16F16, Presentation, Scene, render_frame, scenes};
//!
//! // At most 8 objects, 4 lights, and a ray stack for a tree 5 levels deep.
//! let scene = Scene::<I16F16, 8, 4, 6>::build(&scenes::WHITTED)?;
//! let camera = scene.camera(32, 32)?;
//! let mut display = MockDisplay::<Rgb565>::new();
//! let mut line = [Rgb565::default(); 32];
//! // Top to bottom, undithered: `Presentation` says otherwise.
//! let frame = Presentation::default();
//! render_frame(&scene, &camera, frame, &mut line, &mut [], &mut display).unwrap();
//! # Ok::<(), obscura::SceneError>(())
//! ```
//!
//! The core never allocates and never panics on input: [`Scene::build`] validates a
//! [`SceneDesc`] and proves that the chosen format holds every value the tracer will compute
//! for it, or returns a [`SceneError`] that says what is wrong and how to fix it.
#![cfg_attr(not(test), no_std)]
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]
#![cfg_attr(not(test), deny(clippy::indexing_slicing, clippy::unreachable))]

phase::declare_phase!(Some(phase::Phase::Build));

#[cfg(feature = "alloc")]
extern crate alloc;

/// The front page's example (`README.md`), compiled and run as a doc test.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct FrontPage;

/// Declares modules that are the core's own: private, or with the feature `instrument` (which
/// only the workspace's tools enable: the harness and the scene crate, for their counting and
/// checked number formats, their analyses and their fuzzer) public and hidden from the
/// documentation. A user's API is the crate root's re-exports and the public modules below.
macro_rules! internal_modules {
    ($($(#[$attribute:meta])* $name:ident;)*) => {$(
        $(#[$attribute])*
        #[cfg(feature = "instrument")]
        #[doc(hidden)]
        pub mod $name;
        $(#[$attribute])*
        #[cfg(not(feature = "instrument"))]
        // What only the workspace's tools call is unused without them.
        #[allow(dead_code, unused_imports)]
        mod $name;
    )*};
}

mod format_list;

internal_modules! {
    adaptive;
    blocks;
    camera;
    color;
    cull;
    desc;
    light;
    material;
    methods;
    occlusion;
    pattern;
    phase;
    ray;
    render;
    row_pass;
    scalar;
    scene;
    shade;
    shape;
    /// The checks the tests and the fuzzer hold culling and the shadow cones to.
    skips;
    uses;
    vec3;
    words;
}

pub mod scenes;

/// Every module with the phase of its work it declares ([`phase::MODULES`]), but the tests'
/// helpers.
const MODULE_PHASES: &[phase::Module] = &[
    PHASE,
    adaptive::PHASE,
    blocks::PHASE,
    camera::PHASE,
    color::PHASE,
    cull::PHASE,
    desc::PHASE,
    format_list::PHASE,
    light::PHASE,
    material::PHASE,
    methods::PHASE,
    occlusion::PHASE,
    pattern::PHASE,
    phase::PHASE,
    ray::PHASE,
    render::PHASE,
    row_pass::PHASE,
    scalar::PHASE,
    scalar::approx::PHASE,
    scalar::bits::PHASE,
    scalar::fixed_point::PHASE,
    scalar::float::PHASE,
    scalar::isqrt::PHASE,
    scalar::kernels::PHASE,
    scene::PHASE,
    scene::error::PHASE,
    scene::range::PHASE,
    scene::validate::PHASE,
    scenes::PHASE,
    shade::PHASE,
    shape::PHASE,
    mesh::PHASE,
    mesh::flash::PHASE,
    mesh::hierarchy::PHASE,
    #[cfg(feature = "alloc")]
    mesh::vecs::PHASE,
    shape::plane::PHASE,
    shape::sphere::PHASE,
    shape::triangle::PHASE,
    skips::PHASE,
    uses::PHASE,
    vec3::PHASE,
    words::PHASE,
];

#[cfg(test)]
mod test_util;

pub use adaptive::{Corner, CornerRows, corner_rows};
pub use camera::{Camera, MAX_IMAGE_SIDE};
pub use color::{DisplayColor, Dither, Rgb};
pub use desc::{
    BackgroundDesc, CameraDesc, CheckerDesc, LightDesc, MaterialDesc, MeshesDesc, NodeDesc,
    ObjectDesc, Pixels, SceneDesc, ShapeDesc, Y_UP,
};
/// embedded-graphics' core, whose `DrawTarget` every frame is drawn onto: the version the core
/// draws with, for code (such as the source `obscura_scene::build::Proof` writes) that names it.
pub use embedded_graphics_core;
/// The `fixed` crate, whose types give [`Fx`] its binary point: `Fx<fixed::types::I12F20>`.
pub use fixed;
pub use methods::{
    BiasMethod, MethodName, Methods, ParseMethodsError, RayMethod, RootMethod, SphereMethod,
    TriangleMethod,
};
pub use pattern::{MAX_SAMPLES, SHADOW_PROBES, SampleId};
pub use ray::Ray;
pub use render::{Presentation, RenderError, RowOrder, RowTracer, render_frame, send_row};
pub use scalar::names as formats;
pub use scalar::{Bits, F32Approx, Fx, I16F16, I20F12, I32F32, Scalar};
pub use scene::{Item, Remedy, Scene, SceneError};
pub use shade::Sample;
pub use shape::mesh;
pub use uses::{Everything, Parts, Uses};
pub use vec3::Vec3;
pub use words::{ProvenScene, WordsError};
