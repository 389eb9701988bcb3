//! The cheap path for a firmware of your own: your build script proves a scene file in a format
//! on the host, at your display's size, and writes what the chip needs as Rust source for your
//! firmware to `include!`; the chip reads the scene and its camera back with one call,
//! [`obscura::Scene::from_proven`], and links no scene build, no range proof and no `f64`
//! arithmetic. A scene the format cannot hold stops the build with the refusal placed at its
//! line and column in the scene file, as `obscura analyze` would place it.
//!
//! ```no_run
//! // build.rs
//! use obscura_scene::{Format, build::Proof};
//!
//! fn main() {
//!     Proof::new("scene.toml", Format::I16f16, (240, 240)).write("scene.rs");
//! }
//! ```
//!
//! ```ignore
//! // src/main.rs
//! mod scene {
//!     include!(concat!(env!("OUT_DIR"), "/scene.rs"));
//! }
//! scene::draw(&mut display)?; // any embedded-graphics DrawTarget<Color = Rgb565>
//! ```
//!
//! The source defines, for the scene as proven:
//! - `draw(&mut display)`, which draws the first frame, top down and undithered, and
//!   `draw_frame(frame, presentation, &mut display)`, which draws any of `FRAMES` in any row
//!   order and dither: each reads the scene and camera back (`Scene::from_proven`) and traces
//!   them through a line buffer and the corner rows on the stack ([`obscura::render_frame`]),
//!   and fails with one error type, [`obscura::RenderError`];
//! - `Scene`, the core's scene in the format with storage sized to exactly its objects, lights
//!   and ray tree and a tracer of only the parts it uses (`Parts`, an [`obscura::Parts`]), its
//!   meshes read in place from flash;
//! - `WIDTH` and `HEIGHT`, the image the camera was placed for;
//! - `CORNER_ROWS`, the corners adaptive anti-aliasing keeps (0 without it: pass `&mut []`);
//! - `FRAMES`, the words of each frame ([`obscura::ProvenScene`]): one for a still scene, and
//!   for a scene with a camera path (`[animation]`) each of its frames, proven for its own
//!   camera; and `PROVEN`, the first.
//!
//! The scene file is watched (`cargo::rerun-if-changed`); a mesh file it names is not: after
//! changing one, touch the scene file.

use crate::{Format, FormatJob, HostScene, NamedScene};
use anyhow::{Context, Result, bail};
use obscura::{Bits, Methods, SceneDesc, SceneError, Uses};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A scene file to prove in a format at a display's size, by some methods: what a build script
/// asks for ([`Self::write`]).
#[derive(Clone, Debug)]
pub struct Proof {
    scene_file: PathBuf,
    format: Format,
    size: (u32, u32),
    methods: Methods,
}

impl Proof {
    /// The scene file at `scene_file` (relative to the package, where a build script runs),
    /// proven in `format` for an image of `(width, height)` pixels, by the lecture's methods
    /// ([`Methods::default`]).
    pub fn new(scene_file: impl Into<PathBuf>, format: Format, size: (u32, u32)) -> Self {
        Self {
            scene_file: scene_file.into(),
            format,
            size,
            methods: Methods::default(),
        }
    }

    /// The same proof by `methods` (`obscura chart` compares them).
    #[must_use]
    pub fn methods(self, methods: Methods) -> Self {
        Self { methods, ..self }
    }

    /// The Rust source that holds the proven scene (see the [module](self)).
    ///
    /// # Errors
    /// When the scene file cannot be read, the format is `f64` (the host's reference), or the
    /// format cannot hold the scene or its camera at this size (placed in the scene file).
    pub fn source(&self) -> Result<String> {
        if self.format == Format::F64 {
            bail!(
                "f64 is not a firmware format: take one of {}",
                Format::firmware_names()
            );
        }
        let path = self.scene_file.to_string_lossy();
        let named = crate::load(&path)?;
        let frames: Vec<Words> = named
            .frames()
            .iter()
            .map(|frame| {
                prove(&frame.scene.desc(), self.format, self.methods, self.size)
                    .map_err(|refusal| refused(frame, self.format, refusal))
            })
            .collect::<Result<_>>()?;
        let uses = parts_used(&frames);
        let desc = named.scene.desc();
        let (width, height) = self.size;
        let format = self.format.rust_type();
        let mut out = format!(
            "// Written by obscura_scene::build::Proof from {path} in {} at {width}×{height} by \
             {}; do not edit.\n\n",
            self.format, self.methods
        );
        let _ = writeln!(
            out,
            "{}\n/// The scene as the chip holds it, in {}: storage for its {} objects, {} lights \
             and ray trees {} deep, and a tracer of its parts ([`Parts`]).\n\
             pub type Scene = obscura::Scene<{}, obscura::mesh::MeshWords<{format}>>;\n",
            parts_source("Parts", uses),
            self.format,
            desc.objects.len(),
            desc.lights.len(),
            desc.max_depth,
            scene_generics(self.format, &desc, "Parts"),
        );
        let _ = writeln!(
            out,
            "/// The width of the image the camera was placed for.\npub const WIDTH: u32 = \
             {width};\n/// Its height.\npub const HEIGHT: u32 = {height};\n"
        );
        let _ = writeln!(out, "{}", corner_rows_source([&desc], width));
        let _ = writeln!(
            out,
            "/// Each frame's scene and camera as proven words: {}.\npub static FRAMES: \
             [obscura::ProvenScene<'static>; {}] = [",
            if frames.len() == 1 {
                "the still scene's"
            } else {
                "the camera path's frames in order"
            },
            frames.len()
        );
        for words in &frames {
            let _ = writeln!(
                out,
                "    obscura::ProvenScene {{\n        scene: {},\n        meshes: {},\n        \
                 camera: {},\n    }},",
                words_source(&words.scene),
                words_source(&words.meshes),
                words_source(&words.camera),
            );
        }
        let _ = writeln!(
            out,
            "];\n\n/// The first frame: `Scene::from_proven(PROVEN)`.\npub static PROVEN: \
             &obscura::ProvenScene<'static> = &FRAMES[0];\n"
        );
        out.push_str(DRAW_SOURCE);
        Ok(out)
    }

    /// In a build script: writes [`Self::source`] to `file_name` in `OUT_DIR` and has Cargo run
    /// the script again when the scene file changes; or, where the scene cannot be proven,
    /// fails the build with the reason (`cargo::error`), placed in the scene file.
    pub fn write(&self, file_name: &str) {
        println!("cargo::rerun-if-changed={}", self.scene_file.display());
        let written = self.source().and_then(|source| {
            let out = std::env::var_os("OUT_DIR")
                .context("OUT_DIR is not set: Proof::write is for a build script")?;
            let path = Path::new(&out).join(file_name);
            std::fs::write(&path, source)
                .with_context(|| format!("cannot write {}", path.display()))
        });
        if let Err(error) = written {
            fail(&error);
        }
    }
}

/// The end of the source [`Proof`] writes: the functions that draw a frame in one call.
const DRAW_SOURCE: &str = "\
/// Draws the first frame ([`PROVEN`]) onto `display`, its rows top down and undithered: the
/// scene and camera read back from their words and traced row by row through a line buffer and
/// the corner rows, on the stack. A frame in one call; [`draw_frame`] takes another frame and
/// another presentation.
///
/// # Errors
/// The display's error, or words that do not read back ([`obscura::RenderError`]).
#[allow(dead_code, reason = \"a firmware may draw its frames with draw_frame alone\")]
pub fn draw<D>(display: &mut D) -> Result<(), obscura::RenderError<D::Error>>
where
    D: obscura::embedded_graphics_core::draw_target::DrawTarget<
            Color = obscura::embedded_graphics_core::pixelcolor::Rgb565,
        >,
{
    draw_frame(PROVEN, obscura::Presentation::default(), display)
}

/// Draws `frame` (one of [`FRAMES`]) onto `display`, its rows in `presentation`'s order and its
/// colours rounded by its dither, as [`draw`] draws the first.
///
/// # Errors
/// The display's error, or words that do not read back ([`obscura::RenderError`]).
pub fn draw_frame<C, D>(
    frame: &obscura::ProvenScene<'_>,
    presentation: obscura::Presentation,
    display: &mut D,
) -> Result<(), obscura::RenderError<D::Error>>
where
    C: obscura::DisplayColor,
    D: obscura::embedded_graphics_core::draw_target::DrawTarget<Color = C>,
{
    let (scene, camera) = Scene::from_proven(frame).map_err(obscura::RenderError::Words)?;
    let mut line = [C::BLACK; WIDTH as usize];
    let mut corners = [obscura::Corner::ZERO; CORNER_ROWS];
    obscura::render_frame(&scene, &camera, presentation, &mut line, &mut corners, display)
}
";

/// A frame's scene and camera, proven on the host, as the words the firmware reads them from
/// ([`obscura::ProvenScene`]), and the tracer's parts they use.
#[derive(Debug)]
pub struct Words {
    /// The scene's words.
    pub scene: Vec<u32>,
    /// Its meshes' words ([`obscura::mesh::MeshWords`]), which the firmware reads in place.
    pub meshes: Vec<u32>,
    /// The camera's words, at the display's size.
    pub camera: Vec<u32>,
    /// What of the tracer the scene and the camera use ([`Uses`]).
    pub uses: Uses,
}

/// Builds `desc` in `format` by `methods` (with the capacities of a scene built at run time: a
/// firmware's are exactly its scene's), places its camera for an image of `size`, and writes
/// both as words.
///
/// # Errors
/// The core's refusal of the scene or the camera in the format.
pub fn prove(
    desc: &SceneDesc<'_>,
    format: Format,
    methods: Methods,
    size: (u32, u32),
) -> Result<Words, SceneError> {
    /// The work of [`prove`], generic over the format.
    struct Prove<'a>(&'a SceneDesc<'a>, Methods, (u32, u32));

    impl FormatJob for Prove<'_> {
        type Output = Result<Words, SceneError>;
        fn run<S: Bits>(self) -> Self::Output {
            let Self(desc, methods, (width, height)) = self;
            let scene = HostScene::<S>::build_with(desc, methods)?;
            let camera = scene.camera(width, height)?;
            let mut words = Words {
                scene: Vec::new(),
                meshes: Vec::new(),
                camera: Vec::new(),
                uses: scene.uses().union(camera.uses()),
            };
            scene.write_words(&mut |word| words.scene.push(word));
            scene.write_mesh_words(&mut |word| words.meshes.push(word));
            camera.write_words(&mut |word| words.camera.push(word));
            Ok(words)
        }
    }
    format.run::<obscura::scalar::Proven, _>(Prove(desc, methods, size))
}

/// Why `named` cannot be drawn in `format`: `refusal`, placed in its scene file (at the line
/// and column of what it is about) or naming the built-in scene.
pub(crate) fn refused(named: &NamedScene, format: Format, refusal: SceneError) -> anyhow::Error {
    let error =
        anyhow::Error::new(refusal).context(format!("the scene cannot be built in {format}"));
    match named.path() {
        Some(_) => named.locate(error),
        None => error.context(format!(
            "the firmware cannot draw {} in {format}",
            named.name
        )),
    }
}

/// The core's scene type's arguments but its meshes' storage, as Rust source: `format`,
/// storage for exactly `desc`'s objects and lights, a ray stack for its ray trees, and the
/// parts type `parts`.
pub(crate) fn scene_generics(format: Format, desc: &SceneDesc<'_>, parts: &str) -> String {
    format!(
        "{}, {}, {}, {}, {parts}",
        format.rust_type(),
        desc.objects.len(),
        desc.lights.len(),
        usize::from(desc.max_depth) + 1,
    )
}

/// The parts of the tracer that the proven `frames` use between them.
pub(crate) fn parts_used<'a>(frames: impl IntoIterator<Item = &'a Words>) -> Uses {
    frames
        .into_iter()
        .fold(Uses::NOTHING, |uses, words| uses.union(words.uses))
}

/// The corners a frame `width` pixels wide of any of `scenes` keeps: the most any of them
/// keeps for adaptive samples or pixels ([`SceneDesc::corner_rows`]), none where none does.
pub fn corners_kept<'a>(scenes: impl IntoIterator<Item = &'a SceneDesc<'a>>, width: u32) -> usize {
    scenes
        .into_iter()
        .map(|desc| desc.corner_rows(width))
        .max()
        .unwrap_or(0)
}

/// The Rust source of `CORNER_ROWS`, the corners a frame `width` pixels wide of any of `scenes`
/// keeps ([`corners_kept`]): the length of the corner rows `render_frame` takes.
pub(crate) fn corner_rows_source<'a>(
    scenes: impl IntoIterator<Item = &'a SceneDesc<'a>>,
    width: u32,
) -> String {
    format!(
        "/// The corners adaptive samples or pixels keep: the corner rows `render_frame` takes \
         (0: no scene takes either).\npub const CORNER_ROWS: usize = {};\n",
        corners_kept(scenes, width)
    )
}

/// Fails a build script with `error`: each line of its text (placed in the scene file where it
/// has a place, as `obscura` places it) a `cargo::error`.
pub fn fail(error: &anyhow::Error) {
    let text = crate::error_text(error);
    for line in text.strip_prefix("error: ").unwrap_or(&text).lines() {
        println!("cargo::error={line}");
    }
}

/// The Rust source of a type `name` of the tracer's parts `uses` ([`obscura::Parts`]).
pub(crate) fn parts_source(name: &str, uses: Uses) -> String {
    format!(
        "/// The tracer's parts: {uses}.\n#[derive(Clone, Copy, Debug, PartialEq, Eq)]\npub struct \
         {name};\n\nimpl obscura::Parts for {name} {{\n    const USES: obscura::Uses = \
         obscura::Uses::from_bits({:#010x});\n}}\n",
        uses.bits()
    )
}

/// `words` as a Rust array expression, eight to a line.
pub(crate) fn array_source(words: &[u32]) -> String {
    let lines: Vec<String> = words
        .chunks(8)
        .map(|line| {
            let line: Vec<String> = line.iter().map(|w| format!("{w:#010x}")).collect();
            format!("            {},\n", line.join(", "))
        })
        .collect();
    format!("[\n{}        ]", lines.concat())
}

/// `words` as a Rust expression of type `&[u32]`, eight to a line.
pub(crate) fn words_source(words: &[u32]) -> String {
    format!("&{}", array_source(words))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene_file(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../host/scenes")
            .join(name)
    }

    #[test]
    fn a_still_scene_is_one_proven_frame_of_a_type_sized_to_it() {
        let source = Proof::new(scene_file("pyramid.toml"), Format::I16f16, (48, 32))
            .source()
            .unwrap();
        for expected in [
            "pub type Scene = obscura::Scene<obscura::formats::I16f16, ",
            "obscura::mesh::MeshWords<obscura::formats::I16f16>>;",
            "pub const WIDTH: u32 = 48;",
            "pub const HEIGHT: u32 = 32;",
            "pub const CORNER_ROWS: usize = 0;",
            "pub static FRAMES: [obscura::ProvenScene<'static>; 1] = [",
            "pub static PROVEN: &obscura::ProvenScene<'static> = &FRAMES[0];",
            "pub fn draw<D>(display: &mut D) -> Result<(), obscura::RenderError<D::Error>>",
        ] {
            assert!(source.contains(expected), "{expected} in {source}");
        }
    }

    #[test]
    fn a_camera_path_is_each_of_its_frames_proven() {
        let source = Proof::new(scene_file("orbit.toml"), Format::I16f16, (32, 32))
            .source()
            .unwrap();
        assert!(
            source.contains("[obscura::ProvenScene<'static>; 16]"),
            "{source}"
        );
        assert_eq!(source.matches("obscura::ProvenScene {").count(), 16);
    }

    #[test]
    fn what_cannot_be_proven_is_refused_where_it_is_said() {
        let refused = |proof: Proof| format!("{:#}", proof.source().unwrap_err());
        let message = refused(Proof::new(
            scene_file("hostile/low-light.toml"),
            Format::I16f16,
            (240, 240),
        ));
        assert!(message.contains("low-light.toml:14:1"), "{message}");
        let message = refused(Proof::new(scene_file("pyramid.toml"), Format::F64, (8, 8)));
        assert!(
            message.contains("f64 is not a firmware format"),
            "{message}"
        );
        let message = refused(Proof::new(scene_file("nowhere.toml"), Format::F32, (8, 8)));
        assert!(message.contains("there is no scene"), "{message}");
        let message = refused(Proof::new(scene_file("pyramid.toml"), Format::F32, (0, 8)));
        assert!(message.contains("each side must be 1 to"), "{message}");
    }
}
