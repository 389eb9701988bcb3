//! obscura's scene files: a TOML file read into an [`OwnedScene`] (the core's
//! [`obscura::SceneDesc`] with owned lists, which serde deserializes), or a built-in scene by
//! name ([`load`]); and the core's refusals of a scene placed at the file's line and column
//! ([`NamedScene::locate`], [`Located`], [`error_text`]). The desktop harness and the
//! firmware's build script both read scenes through it, so a refusal reads the same from
//! either.
//!
//! ```
//! # fn main() -> anyhow::Result<()> {
//! # let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../host/scenes/pyramid.toml");
//! let named = obscura_scene::load(path)?;
//! let scene = obscura::Scene::<f32, 8, 4, 6>::build(&named.scene.desc())
//!     .map_err(|refusal| named.locate(refusal.into()))?;
//! # let _ = scene;
//! # Ok(())
//! # }
//! ```

/// The book's chapter on scene files (`docs/scene-files.md`): its examples compiled as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../docs/scene-files.md")]
struct SceneFilesChapter;

mod animation;
pub mod build;
mod file;
pub mod firmware;
mod format;
mod mesh_file;
mod meshes;
mod object;
mod owned;
mod settings;

pub use animation::{Animation, AnimationError, Key};
pub use file::{Located, MAX_FILE_BYTES, NamedScene, load, parse, path_frame};
pub use format::{Format, FormatJob};
pub use mesh_file::{CornerNormals, obj_text};
pub use meshes::{Added, OwnedMeshes};
pub use owned::OwnedScene;
pub use settings::{
    FirmwareSettings, FormatChoice, FrameSettings, MethodSettings, PresentationSettings, Sampling,
    Setting, Spelled, Variants, table as settings_table,
};

/// Objects a scene built at run time may have (the harness's scenes, and the proof of a
/// firmware's; a firmware's own capacities are exactly its scene's).
pub const MAX_OBJECTS: usize = 64;
/// Lights a scene built at run time may have.
pub const MAX_LIGHTS: usize = 16;
/// The ray stack of a scene built at run time: ray trees up to 15 levels deep.
pub const RAY_STACK: usize = 16;

/// A scene built at run time in format `S`, of the capacities above, its meshes in `Vec`s: the
/// harness's scenes, and the proof of a firmware's.
pub type HostScene<S> = obscura::Scene<
    S,
    MAX_OBJECTS,
    MAX_LIGHTS,
    RAY_STACK,
    obscura::Everything,
    obscura::mesh::MeshVecs<S>,
>;

/// An error as the `obscura` command and the firmware's build print it: `error: ` and its
/// chain, and where it is at a place in a scene file, that line with the place marked.
#[must_use]
pub fn error_text(error: &anyhow::Error) -> String {
    match error.downcast_ref::<Located>() {
        Some(place) => format!("error: {error:#}\n{}", place.excerpt()),
        None => format!("error: {error:#}"),
    }
}
