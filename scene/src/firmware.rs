//! What a firmware draws, as its build script (`firmware/build.rs`) reads it from the
//! environment ([`FirmwareSettings`]: the scenes, built-in names or scene files, the formats,
//! the methods, the sampling and the presentation). It builds and so proves each scene in each
//! format by the chosen methods, with the core's own scene build (a refusal placed at the scene
//! file's line and column), and writes the Rust source of what the firmware draws: each frame's
//! proven scene and camera as constant words ([`obscura::words`]), read back on the chip in
//! storage sized exactly to the scene, by a tracer of only the parts the scenes use
//! ([`obscura::Uses`]); the chip runs no scene build and no range proof. A scene with a camera
//! path is drawn as its frames, each a still scene of its frame's camera proven on its own
//! ([`with_paths_as_frames`]), and a board loops over them for good (`LOOPS`). The harness
//! (`obscura firmware`, `obscura chart`) asks for an image through the same variables
//! ([`FirmwareSettings::environment`]).

use crate::build::{
    Words, array_source, corner_rows_source, parts_source, parts_used, prove, refused,
    scene_generics, words_source,
};
use crate::{
    FirmwareSettings, Format, FormatChoice, MAX_LIGHTS, MAX_OBJECTS, NamedScene, RAY_STACK,
    Variants,
};
use anyhow::{Context, Result, bail};
use obscura::{Methods, Presentation, SceneError, Uses};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The side of the firmware's square display, in pixels.
pub const SIDE: u32 = 240;

/// Every variable a firmware's build reads ([`FirmwareSettings`]).
pub fn variables() -> impl Iterator<Item = &'static str> {
    FirmwareSettings::settings().map(|setting| setting.variable)
}

/// `scenes` as a firmware draws them, and whether one had a camera path: a still scene as it
/// is, and a scene with a path as each of its frames in order, the still scene of that frame's
/// camera ([`NamedScene::at_frame`], named `NAME-frame-K`).
#[must_use]
pub fn with_paths_as_frames(scenes: Vec<NamedScene>) -> (Vec<NamedScene>, bool) {
    let loops = scenes.iter().any(|s| s.scene.animation.is_some());
    let frames = scenes.iter().flat_map(NamedScene::frames).collect();
    (frames, loops)
}

/// What a firmware draws: each scene in each format, by the methods (and with `variants`, by
/// each variant that changes one of them).
#[derive(Debug)]
pub struct Configuration {
    /// The scenes, in order: a camera path's frames each a scene ([`with_paths_as_frames`]).
    pub scenes: Vec<NamedScene>,
    /// Whether a scene had a camera path: a board then draws the frames again and again.
    pub loops: bool,
    /// The formats, in order.
    pub formats: Vec<Format>,
    /// The methods.
    pub methods: Methods,
    /// Whether each variant that changes one method is drawn too.
    pub variants: bool,
    /// The order of the rows and the dither.
    pub presentation: Presentation,
}

/// The firmware's Rust source, and the files it was made from (for the build script to watch).
#[derive(Debug)]
pub struct Generated {
    /// The source: `render_all`, which draws every frame.
    pub source: String,
    /// The scene files read.
    pub inputs: Vec<PathBuf>,
}

/// The configuration the environment gives (`var` reads a variable), scene files found from
/// `workspace`.
///
/// # Errors
/// When a variable is malformed or a scene cannot be read.
pub fn configure(workspace: &Path, var: impl Fn(&str) -> Option<String>) -> Result<Configuration> {
    Configuration::of(workspace, &FirmwareSettings::from_env(var)?)
}

impl Configuration {
    /// What `settings` ask a firmware to draw, scene files found from `workspace`.
    ///
    /// # Errors
    /// When a scene cannot be read, or a format is `auto` (the harness's choice) or `f64`.
    pub fn of(workspace: &Path, settings: &FirmwareSettings) -> Result<Self> {
        let mut scenes = settings
            .frames
            .scene
            .iter()
            .map(|name| {
                let path = workspace.join(name);
                let name = if obscura::scenes::find(name).is_none() && path.is_file() {
                    path.to_string_lossy().into_owned()
                } else {
                    name.clone()
                };
                crate::load(&name).context("OBSCURA_SCENES")
            })
            .collect::<Result<Vec<_>>>()?;
        for scene in &mut scenes {
            settings.sampling.apply(&mut scene.scene);
        }
        let (scenes, loops) = with_paths_as_frames(scenes);
        let mut formats = Vec::new();
        for &choice in &settings.frames.format {
            let format = match choice {
                FormatChoice::Auto => bail!(
                    "OBSCURA_FORMATS: `auto` is the harness's choice, made by rendering the \
                     scenes on the host: `obscura firmware --target m0 --scene {scenes} --format \
                     auto` prints the format it takes on the Pico's Cortex-M0+ (`--target m4f` \
                     on the Black Pill's Cortex-M4F; add the flags of any other OBSCURA_ \
                     variable set here, `--samples` for OBSCURA_SAMPLES); give that here",
                    scenes = settings.frames.scene.join(",")
                ),
                FormatChoice::Given(Format::F64) => bail!(
                    "OBSCURA_FORMATS: `f64` is not a firmware format: {}",
                    Format::firmware_names()
                ),
                FormatChoice::Given(format) => format,
            };
            if !formats.contains(&format) {
                formats.push(format);
            }
        }
        Ok(Self {
            scenes,
            loops,
            formats,
            methods: settings.methods.methods(),
            variants: settings.frames.variants == Variants::Each,
            presentation: settings.presentation.presentation(),
        })
    }

    /// Every frame the firmware draws, each scene built and proven in each format by the
    /// methods (and with `variants`, by each variant that changes one of them and tells it
    /// apart in that format), as the firmware's tracer will take it: what the core refuses,
    /// this refuses, with the figures.
    ///
    /// # Errors
    /// The first refusal, placed in its scene file, but a variant's: a variant the format
    /// cannot hold is a frame refused (what the chart compares).
    pub fn frames(&self) -> Result<Vec<Frame<'_>>> {
        let mut frames = Vec::new();
        for named in &self.scenes {
            let desc = named.scene.desc();
            for &format in &self.formats {
                for methods in self.methods_of(format, desc.has_triangles()) {
                    let proven = match prove(&desc, format, methods, (SIDE, SIDE)) {
                        // The methods asked for must hold every scene; a variant need not.
                        Err(refusal) if !self.variants => {
                            return Err(refused(named, format, refusal));
                        }
                        proven => proven,
                    };
                    frames.push(Frame {
                        scene: named,
                        format,
                        methods,
                        proven,
                    });
                }
            }
        }
        Ok(frames)
    }

    /// The methods each scene is drawn by in `format`: the configuration's, and with
    /// `variants` each variant that changes one of them where that changes the frame
    /// ([`Format::methods_matter`]).
    fn methods_of(&self, format: Format, has_triangles: bool) -> Vec<Methods> {
        if !self.variants {
            return vec![self.methods];
        }
        let mut all: Vec<Methods> = Vec::new();
        for m in self.methods.variants() {
            if !all.contains(&m) && format.methods_matter(&m, &self.methods, has_triangles) {
                all.push(m);
            }
        }
        all
    }

    /// The firmware's source: the display's side (`SIDE`), the run-time capacities the sized
    /// storage is reported against, the corner rows adaptive samples keep (`CORNER_ROWS`), and
    /// a function `render_all(backend, clock)` that draws each frame by calling the firmware's
    /// `frames::draw::<S, OBJECTS, LIGHTS, RAYS>(backend, clock, &job, &SCENE, &CAMERA)`, with
    /// the proven scene's and camera's words and the capacities exactly the scene's (or
    /// reports a refused variant with the host's reason).
    ///
    /// # Errors
    /// As [`Self::frames`].
    pub fn source(&self) -> Result<String> {
        let frames = self.frames()?;
        let mut out = String::new();
        let _ = writeln!(
            out,
            "// Written by obscura_scene::firmware for the configuration the environment \
             gave the build; do not edit.\n"
        );
        let _ = writeln!(
            out,
            "/// The side of the square display, in pixels.\npub const SIDE: u32 = {SIDE};\n"
        );
        let _ = writeln!(
            out,
            "/// The capacities of a scene built at run time (the harness's), against which the \
             storage sized to the scene is reported: objects, lights and the ray stack.\n\
             pub const MAX_OBJECTS: usize = {MAX_OBJECTS};\n/// Lights, as above.\n\
             pub const MAX_LIGHTS: usize = {MAX_LIGHTS};\n/// The ray stack, as above.\n\
             pub const RAY_STACK: usize = {RAY_STACK};\n"
        );
        let _ = writeln!(
            out,
            "/// Whether a scene has a camera path: a board draws the frames again and again.\n\
             pub const LOOPS: bool = {};\n",
            self.loops
        );
        let descs: Vec<_> = self.scenes.iter().map(|s| s.scene.desc()).collect();
        let _ = writeln!(out, "{}", corner_rows_source(&descs, SIDE));
        // One tracer per format: of the parts its frames use between them.
        for &format in &self.formats {
            let _ = writeln!(
                out,
                "{}",
                parts_source(&parts_name(format), tracer_uses(&frames, format))
            );
        }
        let _ = writeln!(
            out,
            "/// Draws {} in {}, by {}.",
            self.scenes
                .iter()
                .map(|s| s.name.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            self.formats
                .iter()
                .map(|f| f.name())
                .collect::<Vec<_>>()
                .join(", "),
            if self.variants {
                format!("{} and each variant that changes one method", self.methods)
            } else {
                self.methods.to_string()
            }
        );
        let _ = writeln!(
            out,
            "pub fn render_all(backend: &mut impl crate::frames::Backend, clock: &crate::clock::Clock) {{"
        );
        let Presentation { order, dither } = self.presentation;
        let _ = writeln!(
            out,
            "    const PRESENTATION: obscura::Presentation = obscura::Presentation {{ order: \
             obscura::RowOrder::{order:?}, dither: obscura::Dither::{dither:?} }};"
        );
        let mut drawn = vec![false; frames.len()];
        for (i, frame) in frames.iter().enumerate() {
            if drawn[i] {
                continue;
            }
            let job = |name: &str| {
                format!(
                    "&crate::frames::Job {{ scene: {name:?}, frame: None, format: {:?}, methods: \
                     {:?}, presentation: PRESENTATION }}",
                    frame.format.name(),
                    frame.methods.to_string()
                )
            };
            let Ok(words) = &frame.proven else {
                if let Err(refusal) = &frame.proven {
                    let reason = refusal.to_string();
                    let _ = writeln!(
                        out,
                        "    backend.refused({}, &{reason:?});",
                        job(&frame.scene.name)
                    );
                }
                continue;
            };
            let desc = frame.scene.scene.desc();
            let generics = scene_generics(frame.format, &desc, &parts_name(frame.format));
            if let Some(path) = path_of(&frames, i) {
                for &j in &path {
                    drawn[j] = true;
                }
                let _ = write!(out, "{}", path_source(&frames, &path, &generics, &job));
                continue;
            }
            let _ = writeln!(
                out,
                "    crate::frames::draw::<{generics}>(\n        backend,\n        clock,\n        \
                 {},\n        {},\n        {},\n        {},\n    );",
                job(&frame.scene.name),
                words_source(&words.scene),
                words_source(&words.meshes),
                words_source(&words.camera),
            );
        }
        let _ = writeln!(out, "}}");
        Ok(out)
    }

    /// The scene files the configuration read.
    #[must_use]
    pub fn inputs(&self) -> Vec<PathBuf> {
        self.scenes
            .iter()
            .filter_map(|s| s.path().map(Path::to_path_buf))
            .collect()
    }
}

/// The configuration from the environment of a build script, checked, and its source.
///
/// # Errors
/// As [`configure`].
pub fn generate(workspace: &Path) -> Result<Generated> {
    let configuration = configure(workspace, |name| std::env::var(name).ok())?;
    Ok(Generated {
        source: configuration.source()?,
        inputs: configuration.inputs(),
    })
}

/// The name of the type of the tracer's parts in `format` ([`obscura::Parts`]).
fn parts_name(format: Format) -> String {
    format!("Parts{format:?}")
}

/// The parts of the tracer that the proven frames in `format` use between them: the tracer the
/// firmware holds for the format.
fn tracer_uses(frames: &[Frame<'_>], format: Format) -> Uses {
    parts_used(
        frames
            .iter()
            .filter(|frame| frame.format == format)
            .filter_map(|frame| frame.proven.as_ref().ok()),
    )
}

/// One frame a firmware draws: a scene in a format by some methods, proven, or refused (a
/// variant's) with the reason.
#[derive(Debug)]
pub struct Frame<'a> {
    /// The scene.
    pub scene: &'a NamedScene,
    /// The format.
    pub format: Format,
    /// The methods.
    pub methods: Methods,
    /// The scene and its camera as words, or why the format cannot hold the scene.
    pub proven: Result<Words, SceneError>,
}

/// The frames, `i` first, of the camera path whose frame 0 is frame `i`, in `frames`' order:
/// a path's every frame in `i`'s format by its methods, all proven, their scenes' words of one
/// length and their meshes' the same. `None` where frame `i` is no path's frame 0.
fn path_of(frames: &[Frame<'_>], i: usize) -> Option<Vec<usize>> {
    let first = frames.get(i)?;
    let (path, 0) = first.scene.path_frame()? else {
        return None;
    };
    let words = first.proven.as_ref().ok()?;
    let members: Vec<usize> = frames
        .iter()
        .enumerate()
        .filter(|(_, f)| {
            f.format == first.format
                && f.methods == first.methods
                && f.scene.path_frame().is_some_and(|(p, _)| p == path)
        })
        .map(|(j, _)| j)
        .collect();
    let alike = members.iter().all(|&j| {
        frames[j].proven.as_ref().is_ok_and(|w| {
            w.scene.len() == words.scene.len()
                && w.meshes == words.meshes
                && w.camera.len() == words.camera.len()
        })
    });
    alike.then_some(members)
}

/// The source that draws the camera path of `members` (frame 0 first) by
/// `crate::frames::draw_path`: its scenes' and its cameras' words, each shared by the frames
/// but where they differ ([`shared_source`]).
fn path_source(
    frames: &[Frame<'_>],
    members: &[usize],
    generics: &str,
    job: &dyn Fn(&str) -> String,
) -> String {
    let words: Vec<&Words> = members
        .iter()
        .filter_map(|&j| frames[j].proven.as_ref().ok())
        .collect();
    let Some(first) = words.first() else {
        return String::new();
    };
    let path = frames[members[0]]
        .scene
        .path_frame()
        .map_or("", |(path, _)| path);
    let scenes: Vec<&[u32]> = words.iter().map(|w| w.scene.as_slice()).collect();
    let cameras: Vec<&[u32]> = words.iter().map(|w| w.camera.as_slice()).collect();
    let (scene, scene_changed) = shared_source(&scenes);
    let (camera, camera_changed) = shared_source(&cameras);
    format!(
        "    // {path}: {} frames, differing in {scene_changed} of their scene's {} words and \
         {camera_changed} of their camera's {}.\n    {{\n        \
         static SCENE: crate::frames::Shared<{}> = {scene};\n        \
         static CAMERA: crate::frames::Shared<{}> = {camera};\n        \
         crate::frames::draw_path::<{generics}, {}, {}>(\n            backend,\n            \
         clock,\n            {},\n            (&SCENE, &CAMERA),\n            {},\n            \
         {},\n        );\n    }}\n",
        words.len(),
        first.scene.len(),
        first.camera.len(),
        first.scene.len(),
        first.camera.len(),
        first.scene.len(),
        first.camera.len(),
        job(path),
        words.len(),
        words_source(&first.meshes),
    )
}

/// Each frame's `words` (all of one length) as a `crate::frames::Shared` expression: frame 0's
/// words, the places where any frame's differ, and each frame's there; and how many places.
fn shared_source(words: &[&[u32]]) -> (String, usize) {
    let base = words.first().copied().unwrap_or_default();
    let changed: Vec<usize> = (0..base.len())
        .filter(|&w| words.iter().any(|frame| frame[w] != base[w]))
        .collect();
    let values: Vec<u32> = words
        .iter()
        .flat_map(|frame| changed.iter().map(|&w| frame[w]))
        .collect();
    let places: Vec<String> = changed.iter().map(ToString::to_string).collect();
    let source = format!(
        "crate::frames::Shared {{\n            base: {},\n            changed: &[{}],\n            \
         values: {},\n        }}",
        array_source(base),
        places.join(", "),
        words_source(&values),
    );
    (source, changed.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENES: &str = "OBSCURA_SCENES";
    const FORMATS: &str = "OBSCURA_FORMATS";
    const VARIANTS: &str = "OBSCURA_VARIANTS";

    fn env<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        |name| {
            pairs
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, v)| (*v).to_owned())
        }
    }

    fn workspace() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .expect("the scene crate is in the workspace")
            .to_path_buf()
    }

    #[test]
    fn a_camera_path_is_drawn_as_its_frames_sharing_their_words_and_looping() {
        let configuration = configure(
            &workspace(),
            env(&[
                (SCENES, "host/scenes/orbit.toml, whitted"),
                (FORMATS, "i16f16"),
            ]),
        )
        .unwrap();
        let names: Vec<_> = configuration
            .scenes
            .iter()
            .map(|s| s.name.as_str())
            .collect();
        assert_eq!(names.len(), 17);
        assert_eq!(
            (names[0], names[15], names[16]),
            ("orbit-frame-0", "orbit-frame-15", "whitted")
        );
        assert!(configuration.loops);
        let source = configuration.source().unwrap();
        assert!(source.contains("pub const LOOPS: bool = true;"), "{source}");
        // One path call for the 16 frames, one draw for the still scene.
        assert_eq!(
            source.matches("crate::frames::draw_path::<").count(),
            1,
            "{source}"
        );
        assert_eq!(
            source.matches("crate::frames::draw::<").count(),
            1,
            "{source}"
        );
        assert!(
            source.contains("// orbit: 16 frames, differing in "),
            "{source}"
        );
        let still = configure(&workspace(), env(&[(SCENES, "whitted")])).unwrap();
        assert!(!still.loops);
        assert!(
            still
                .source()
                .unwrap()
                .contains("pub const LOOPS: bool = false;")
        );
    }

    #[test]
    fn a_configuration_reads_scene_files_formats_and_methods() {
        let configuration = configure(
            &workspace(),
            env(&[
                (SCENES, "whitted, host/scenes/marbles.toml"),
                (FORMATS, "f32,i32f32,f32"),
                ("OBSCURA_SPHERE", "stable"),
            ]),
        )
        .unwrap();
        let names: Vec<_> = configuration
            .scenes
            .iter()
            .map(|s| s.name.as_str())
            .collect();
        assert_eq!(names, ["whitted", "marbles"]);
        assert_eq!(configuration.formats, [Format::F32, Format::I32f32]);
        assert_eq!(
            configuration.methods.to_string().split(' ').next(),
            Some("sphere=stable")
        );
        assert_eq!(configuration.inputs().len(), 1);
        let source = configuration.source().unwrap();
        assert!(
            source.contains("crate::frames::draw::<obscura::formats::F32, 5, 2, 5, PartsF32>")
                && source.contains("scene: \"marbles\", frame: None, format: \"f32\""),
            "{source}"
        );
        // The tracer of each format has the parts its scenes use: no triangles in f32's.
        assert!(
            source.contains(
                "/// The tracer's parts: spheres, planes; stable, cramer, exact, per-pixel, epsilon.\n\
                 #[derive(Clone, Copy, Debug, PartialEq, Eq)]\npub struct PartsF32;"
            ),
            "{source}"
        );
    }

    #[test]
    fn a_frame_is_its_proven_scene_and_camera_as_words() {
        let configuration = configure(
            &workspace(),
            env(&[(SCENES, "whitted"), (FORMATS, "f32"), (VARIANTS, "each")]),
        )
        .unwrap();
        let frames = configuration.frames().unwrap();
        assert!(frames.len() > 1, "the variants that change whitted's frame");
        let desc = configuration.scenes[0].scene.desc();
        for frame in &frames {
            let words = frame.proven.as_ref().unwrap();
            let scene = obscura::Scene::<f32, 8, 4, 8>::build_with(&desc, frame.methods).unwrap();
            assert_eq!(obscura::Scene::from_words(&words.scene), Ok(scene.clone()));
            let camera = scene.camera(SIDE, SIDE).unwrap();
            assert_eq!(obscura::Camera::from_words(&words.camera), Ok(camera));
        }
        let source = configuration.source().unwrap();
        assert_eq!(
            source.matches("crate::frames::draw::<").count(),
            frames.len()
        );
    }

    #[test]
    fn a_variant_the_format_cannot_hold_is_a_frame_refused() {
        let configuration = configure(
            &workspace(),
            env(&[(SCENES, "shapes"), (FORMATS, "i8f24"), (VARIANTS, "each")]),
        )
        .unwrap();
        let source = configuration.source().unwrap();
        assert!(source.contains("backend.refused("), "{source}");
    }

    #[test]
    fn sampling_holds_for_every_scene() {
        let configure_sampling = |variable, value| {
            configure(
                &workspace(),
                env(&[
                    (SCENES, "whitted,soft"),
                    (FORMATS, "f32"),
                    (variable, value),
                ]),
            )
        };
        let own = configure(
            &workspace(),
            env(&[(SCENES, "whitted,soft"), (FORMATS, "f32")]),
        )
        .unwrap()
        .source()
        .unwrap();
        let configuration = configure_sampling("OBSCURA_SAMPLES", "4").unwrap();
        assert!(configuration.scenes.iter().all(|s| s.scene.samples == 4));
        assert_ne!(configuration.source().unwrap(), own);
        let configuration = configure_sampling("OBSCURA_SHADOW_SAMPLES", "4").unwrap();
        assert!(
            configuration
                .scenes
                .iter()
                .all(|s| s.scene.shadow_samples == 4)
        );
        assert_ne!(configuration.source().unwrap(), own);
        let configuration = configure_sampling("OBSCURA_ADAPTIVE_SHADOWS", "true").unwrap();
        assert!(
            configuration
                .scenes
                .iter()
                .all(|s| s.scene.adaptive_shadows)
        );
        assert_ne!(configuration.source().unwrap(), own);
        for (variable, wrong) in [
            ("OBSCURA_SAMPLES", "0"),
            ("OBSCURA_SAMPLES", "257"),
            ("OBSCURA_SAMPLES", "four"),
            ("OBSCURA_SHADOW_SAMPLES", "0"),
            ("OBSCURA_ADAPTIVE_SHADOWS", "yes"),
        ] {
            let message = format!("{:#}", configure_sampling(variable, wrong).unwrap_err());
            assert!(
                message.contains(variable) && message.contains(wrong),
                "{message}"
            );
        }
    }

    #[test]
    fn each_formats_parts_type_is_named_in_upper_camel_case() {
        for &format in Format::FIRMWARE {
            let name = parts_name(format);
            assert!(name.chars().all(char::is_alphanumeric), "{name}");
        }
        assert_eq!(parts_name(Format::F32Approx), "PartsF32Approx");
    }

    #[test]
    fn a_scene_the_format_cannot_hold_is_refused_at_its_line_and_column() {
        let error = configure(
            &workspace(),
            env(&[
                (SCENES, "host/scenes/hostile/low-light.toml"),
                (FORMATS, "i16f16"),
            ]),
        )
        .and_then(|configuration| configuration.source())
        .unwrap_err();
        let message = format!("{error:#}");
        assert!(message.contains("low-light.toml:14:1"), "{message}");
        assert!(
            message.contains("move the light away from the surface"),
            "{message}"
        );
    }

    #[test]
    fn malformed_variables_say_what_they_take() {
        for (pairs, expected) in [
            (&[(FORMATS, "f64")][..], "not a firmware format"),
            (&[(FORMATS, "i17f15")][..], "OBSCURA_FORMATS: a format"),
            (
                &[("OBSCURA_SPHERE", "round")][..],
                "OBSCURA_SPHERE: `quadratic` or `stable`, not `round`",
            ),
            (&[(VARIANTS, "all")][..], "`none` or `each`"),
            (
                &[(FORMATS, "auto"), (SCENES, "host/scenes/pyramid.toml")][..],
                "`obscura firmware --target m0 --scene host/scenes/pyramid.toml --format auto`",
            ),
            (
                &[("OBSCURA_DITHER", "floyd")][..],
                "OBSCURA_DITHER: `none` or `ordered`, not `floyd`",
            ),
            (
                &[("OBSCURA_ORDER", "bottom-up")][..],
                "`top-down` or `progressive`",
            ),
            (&[(SCENES, "no-such-scene")][..], "there is no scene"),
        ] {
            let error = configure(&workspace(), env(pairs)).unwrap_err();
            let message = format!("{error:#}");
            assert!(message.contains(expected), "{message}");
        }
    }

    #[test]
    fn without_a_format_the_firmware_computes_in_i16f16() {
        let configuration = configure(&workspace(), env(&[])).unwrap();
        assert_eq!(configuration.formats, [Format::I16f16]);
        assert_eq!(configuration.scenes[0].name, "whitted");
    }
}
