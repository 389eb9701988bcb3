//! What a firmware draws, as its build script (`firmware/build.rs`) reads it from the
//! environment: the scenes (built-in names or scene files), the formats, the methods, the
//! sampling and the presentation. It proves that each scene builds in each format by the
//! chosen methods, with the core's own scene build (a refusal placed at the scene file's line
//! and column), and writes the Rust source of what the firmware draws: each scene as const
//! data, with capacities exactly its own. The harness (`obscura firmware`, `obscura chart`)
//! asks for an image through the same variables ([`Image::environment`]).
//!
//! | variable | what | default |
//! |---|---|---|
//! | `OBSCURA_SCENES` | built-in scenes or scene files (relative to the workspace, or absolute), comma-separated | `whitted` |
//! | `OBSCURA_FORMATS` | formats, comma-separated (`auto` is the harness's: `obscura firmware --format auto` prints the one it takes) | `i16f16` |
//! | `OBSCURA_SAMPLES`, `OBSCURA_ADAPTIVE_SAMPLES`, `OBSCURA_SHADOW_SAMPLES`, `OBSCURA_ADAPTIVE_SHADOWS` | the [`Sampling`] of every scene | unset: each scene's own |
//! | `OBSCURA_METHODS` | the methods that differ from the lecture's, e.g. `sphere=stable,bias=exclude` | the lecture's |
//! | `OBSCURA_VARIANTS` | `each`: also draw each variant that changes one method (what `obscura chart` measures) | none |
//! | `OBSCURA_ORDER` | the order of the rows: `top-down`, or `progressive` (every 8th row first, as blocks) | `top-down` |
//! | `OBSCURA_DITHER` | the rounding to RGB565: `none`, or `ordered` (a 4×4 Bayer dither) | `none` |

use crate::{Format, FormatJob, MAX_LIGHTS, MAX_OBJECTS, NamedScene, RAY_STACK, Sampling};
use anyhow::{Context, Result, bail};
use obscura::methods::MethodName;
use obscura::scalar::Proven;
use obscura::{
    BackgroundDesc, CameraDesc, CheckerDesc, LightDesc, MaterialDesc, Methods, ObjectDesc,
    Presentation, Scalar, Scene, SceneDesc, SceneError, ShapeDesc,
};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The side of the firmware's square display, in pixels.
pub const SIDE: u32 = 240;

/// The firmware's own environment variables, as (name, default); the sampling's are
/// [`Sampling::VARIABLES`] (unset: each scene's own).
pub const VARIABLES: [(&str, &str); 6] = [
    (SCENES, "whitted"),
    (FORMATS, "i16f16"),
    (METHODS, "lecture"),
    (VARIANTS, "none"),
    (ORDER, "top-down"),
    (DITHER, "none"),
];

/// Every variable a firmware's build reads: its own and the sampling's.
pub fn variables() -> impl Iterator<Item = &'static str> {
    VARIABLES
        .iter()
        .map(|(name, _)| *name)
        .chain(Sampling::VARIABLES)
}

const SCENES: &str = "OBSCURA_SCENES";
const FORMATS: &str = "OBSCURA_FORMATS";
const METHODS: &str = "OBSCURA_METHODS";
const VARIANTS: &str = "OBSCURA_VARIANTS";
const ORDER: &str = "OBSCURA_ORDER";
const DITHER: &str = "OBSCURA_DITHER";

/// What a firmware draws: each scene in each format, by the methods (and with `variants`, by
/// each variant that changes one of them).
#[derive(Debug)]
pub struct Configuration {
    /// The scenes, in order.
    pub scenes: Vec<NamedScene>,
    /// The formats, in order.
    pub formats: Vec<Format>,
    /// The methods.
    pub methods: Methods,
    /// Whether each variant that changes one method is drawn too.
    pub variants: bool,
    /// The order of the rows and the dither.
    pub presentation: Presentation,
}

/// What one firmware image is to draw, as the host asks its build for it.
#[derive(Debug)]
pub struct Image<'a> {
    /// Built-in scenes' names, or scene files' paths.
    pub scenes: Vec<String>,
    /// Rays per pixel and per area light for every scene, where not each scene's own.
    pub sampling: Sampling,
    /// The formats.
    pub formats: &'a [Format],
    /// The methods.
    pub methods: Methods,
    /// Whether each variant that changes one method is drawn too.
    pub variants: bool,
    /// The order of the rows and the dither.
    pub presentation: Presentation,
}

impl Image<'_> {
    /// The build script's environment for this image: every variable, so that none is
    /// inherited from the caller's (`None`: to be unset).
    #[must_use]
    pub fn environment(&self) -> Vec<(&'static str, Option<String>)> {
        let own = [
            (SCENES, self.scenes.join(",")),
            (
                FORMATS,
                self.formats
                    .iter()
                    .map(|f| f.name())
                    .collect::<Vec<_>>()
                    .join(","),
            ),
            (METHODS, self.methods.to_string()),
            (
                VARIANTS,
                if self.variants { "each" } else { "none" }.to_owned(),
            ),
            (ORDER, self.presentation.order.name().to_owned()),
            (DITHER, self.presentation.dither.name().to_owned()),
        ];
        own.into_iter()
            .map(|(name, value)| (name, Some(value)))
            .chain(self.sampling.environment())
            .collect()
    }
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
/// When a variable is malformed, a scene cannot be read, or a format cannot hold a scene (said
/// as the harness says it, at the scene file's line and column).
pub fn configure(workspace: &Path, var: impl Fn(&str) -> Option<String>) -> Result<Configuration> {
    let value = |name: &str| {
        var(name)
            .filter(|v| !v.trim().is_empty())
            .unwrap_or_else(|| {
                VARIABLES
                    .iter()
                    .find(|(n, _)| *n == name)
                    .map_or_else(String::new, |(_, default)| (*default).to_owned())
            })
    };
    let methods: Methods = value(METHODS)
        .parse()
        .map_err(|e| anyhow::anyhow!("{METHODS}: {e}"))?;
    let variants = match value(VARIANTS).trim() {
        "none" => false,
        "each" => true,
        other => bail!("{VARIANTS} is `none` or `each`, not `{other}`"),
    };
    let presentation = Presentation {
        order: choice(ORDER, &value(ORDER))?,
        dither: choice(DITHER, &value(DITHER))?,
    };
    let mut scenes = value(SCENES)
        .split(',')
        .map(str::trim)
        .map(|name| {
            let path = workspace.join(name);
            let name = if obscura::scenes::find(name).is_none() && path.is_file() {
                path.to_string_lossy().into_owned()
            } else {
                name.to_owned()
            };
            crate::load(&name).context(SCENES)
        })
        .collect::<Result<Vec<_>>>()?;
    let sampling = Sampling::from_env(&var)?;
    for scene in &mut scenes {
        sampling.apply(&mut scene.scene);
    }
    let mut formats = Vec::new();
    for name in value(FORMATS).split(',').map(str::trim) {
        let format = match Format::from_name(name) {
            None if name == "auto" => bail!(
                "{FORMATS}: `auto` is the harness's choice, made by rendering the scenes on the \
                 host: `obscura firmware --target <m4f or m0> --scene <scenes> --format auto` \
                 prints the format it takes; give that here"
            ),
            Some(Format::F64) | None => bail!(
                "{FORMATS}: `{name}` is not a firmware format: {}",
                Format::firmware_names()
            ),
            Some(format) => format,
        };
        if !formats.contains(&format) {
            formats.push(format);
        }
    }
    let configuration = Configuration {
        scenes,
        formats,
        methods,
        variants,
        presentation,
    };
    // Variants are what the chart compares, refusals included; the methods asked for must
    // hold every scene.
    if !variants {
        configuration.check()?;
    }
    Ok(configuration)
}

/// The choice `text` names for `variable`, or an error listing the choices.
fn choice<M: MethodName + PartialEq>(variable: &str, text: &str) -> Result<M> {
    M::from_name(text.trim()).with_context(|| {
        let names: Vec<_> = M::ALL.iter().map(|(_, name)| *name).collect();
        format!(
            "{variable} is {}, not `{}`",
            names.join(" or "),
            text.trim()
        )
    })
}

impl Configuration {
    /// Proves that each scene builds in each format by the methods, as the firmware will build
    /// it: what the firmware would refuse (by the same code), this refuses, with the figures.
    ///
    /// # Errors
    /// The first refusal, placed in its scene file.
    pub fn check(&self) -> Result<()> {
        for named in &self.scenes {
            let desc = named.scene.desc();
            for &format in &self.formats {
                format
                    .run::<Proven, _>(Prove(&desc, self.methods))
                    .map_err(anyhow::Error::new)
                    .with_context(|| format!("the scene cannot be built in {format}"))
                    .map_err(|error| match named.path() {
                        // A scene file's refusal names the file, its line and its column.
                        Some(_) => named.locate(error),
                        None => error.context(format!(
                            "the firmware cannot draw {} in {format}",
                            named.name
                        )),
                    })?;
            }
        }
        Ok(())
    }

    /// The firmware's source: the display's side (`SIDE`), the run-time capacities the sized
    /// storage is reported against, the corner rows adaptive samples keep (`CORNER_ROWS`), and a function `render_all(backend, clock)` that draws each scene in
    /// each format by calling the firmware's `frames::variants::<S, OBJECTS, LIGHTS, RAYS>(backend,
    /// clock, name, &DESC, METHODS)`, with the scene as a const and
    /// its capacities exactly its own.
    #[must_use]
    pub fn source(&self) -> String {
        let mut out = String::new();
        let methods: Vec<Methods> = if self.variants {
            let mut all = Vec::new();
            for m in self.methods.variants() {
                if !all.contains(&m) {
                    all.push(m);
                }
            }
            all
        } else {
            vec![self.methods]
        };
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
        let adaptive = self.scenes.iter().any(|s| s.scene.adaptive_samples);
        let _ = writeln!(
            out,
            "/// The corner rows of adaptive anti-aliasing a frame keeps (none if no scene takes \
             adaptive samples).\npub const CORNER_ROWS: usize = {};\n",
            if adaptive {
                obscura::corner_rows(SIDE)
            } else {
                0
            }
        );
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
        let _ = writeln!(out, "    const METHODS: &[obscura::Methods] = &[");
        for m in &methods {
            let _ = writeln!(out, "        {},", methods_source(m));
        }
        let _ = writeln!(out, "    ];");
        let Presentation { order, dither } = self.presentation;
        let _ = writeln!(
            out,
            "    const PRESENTATION: obscura::Presentation = obscura::Presentation {{ order: \
             obscura::RowOrder::{order:?}, dither: obscura::Dither::{dither:?} }};"
        );
        for named in &self.scenes {
            let desc = named.scene.desc();
            let _ = writeln!(out, "    {{");
            let _ = writeln!(
                out,
                "        const DESC: obscura::SceneDesc<'static> = {};",
                scene_source(&desc)
            );
            for &format in &self.formats {
                let _ = writeln!(
                    out,
                    "        crate::frames::variants::<{}, {}, {}, {}>(backend, clock, {:?}, &DESC, METHODS, \
                     PRESENTATION);",
                    format.rust_type(),
                    desc.objects.len(),
                    desc.lights.len(),
                    usize::from(desc.max_depth) + 1,
                    named.name
                );
            }
            let _ = writeln!(out, "    }}");
        }
        let _ = writeln!(out, "}}");
        out
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
        source: configuration.source(),
        inputs: configuration.inputs(),
    })
}

/// Builds a scene in a format, and its camera at the display's size, as a firmware does
/// (with the capacities of a scene built at run time: a firmware's are exactly its scene's).
struct Prove<'a>(&'a SceneDesc<'a>, Methods);

impl FormatJob for Prove<'_> {
    type Output = Result<(), SceneError>;
    fn run<S: Scalar>(self) -> Self::Output {
        let scene = Scene::<S, MAX_OBJECTS, MAX_LIGHTS, RAY_STACK>::build_with(self.0, self.1)?;
        scene.camera(SIDE, SIDE)?;
        Ok(())
    }
}

/// `methods` as a Rust expression.
fn methods_source(methods: &Methods) -> String {
    let Methods {
        sphere,
        triangle,
        roots,
        rays,
        bias,
    } = methods;
    format!(
        "obscura::Methods {{ sphere: obscura::SphereMethod::{sphere:?}, triangle: \
         obscura::TriangleMethod::{triangle:?}, roots: obscura::RootMethod::{roots:?}, rays: \
         obscura::RayMethod::{rays:?}, bias: obscura::BiasMethod::{bias:?} }}"
    )
}

/// `desc` as a Rust expression of type `SceneDesc<'static>`, every number exactly as it is.
fn scene_source(desc: &SceneDesc<'_>) -> String {
    let SceneDesc {
        camera,
        objects,
        lights,
        ambient,
        background,
        far,
        max_depth,
        samples,
        adaptive_samples,
        shadow_samples,
        adaptive_shadows,
    } = desc;
    let CameraDesc {
        eye,
        look_at,
        up,
        vfov_degrees,
        aperture,
        focus_distance,
    } = camera;
    let objects: Vec<String> = objects.iter().map(object_source).collect();
    let lights: Vec<String> = lights
        .iter()
        .map(
            |LightDesc {
                 position,
                 colour,
                 radius,
             }| {
                format!(
                    "obscura::LightDesc {{ position: {}, colour: {}, radius: {} }}",
                    vector(position),
                    vector(colour),
                    number(*radius)
                )
            },
        )
        .collect();
    let background = match background {
        BackgroundDesc::Solid(colour) => {
            format!("obscura::BackgroundDesc::Solid({})", vector(colour))
        }
        BackgroundDesc::Gradient {
            horizon,
            zenith,
            up,
        } => format!(
            "obscura::BackgroundDesc::Gradient {{ horizon: {}, zenith: {}, up: {} }}",
            vector(horizon),
            vector(zenith),
            vector(up)
        ),
    };
    format!(
        "obscura::SceneDesc {{\n            camera: obscura::CameraDesc {{ eye: {}, look_at: {}, \
         up: {}, vfov_degrees: {}, aperture: {}, focus_distance: {} }},\n            objects: &[\n{}            ],\n            \
         lights: &[{}],\n            ambient: {},\n            background: {background},\n            \
         far: {},\n            max_depth: {max_depth},\n            samples: {samples},\n            adaptive_samples: \
         {adaptive_samples},\n            shadow_samples: {shadow_samples},\n            adaptive_shadows: {adaptive_shadows},\n        }}",
        vector(eye),
        vector(look_at),
        vector(up),
        number(*vfov_degrees),
        number(*aperture),
        focus_distance.map_or_else(|| "None".to_owned(), |f| format!("Some({})", number(f))),
        objects
            .iter()
            .map(|o| format!("                {o},\n"))
            .collect::<String>(),
        lights.join(", "),
        vector(ambient),
        number(*far),
    )
}

fn object_source(object: &ObjectDesc) -> String {
    let ObjectDesc { shape, material } = object;
    let shape = match shape {
        ShapeDesc::Sphere { center, radius } => format!(
            "obscura::ShapeDesc::Sphere {{ center: {}, radius: {} }}",
            vector(center),
            number(*radius)
        ),
        ShapeDesc::Plane {
            point,
            normal,
            checker,
        } => format!(
            "obscura::ShapeDesc::Plane {{ point: {}, normal: {}, checker: {} }}",
            vector(point),
            vector(normal),
            checker.map_or_else(
                || "None".to_owned(),
                |CheckerDesc { colour, size }| format!(
                    "Some(obscura::CheckerDesc {{ colour: {}, size: {} }})",
                    vector(&colour),
                    number(size)
                )
            )
        ),
        ShapeDesc::Triangle { vertices } => format!(
            "obscura::ShapeDesc::Triangle {{ vertices: [{}] }}",
            vertices.iter().map(vector).collect::<Vec<_>>().join(", ")
        ),
    };
    let MaterialDesc {
        colour,
        diffuse,
        specular,
        shininess,
        reflection,
        transmission,
        ior,
    } = material;
    format!(
        "obscura::ObjectDesc {{ shape: {shape}, material: obscura::MaterialDesc {{ colour: {}, \
         diffuse: {}, specular: {}, shininess: {shininess}, reflection: {}, transmission: {}, \
         ior: {} }} }}",
        vector(colour),
        number(*diffuse),
        number(*specular),
        number(*reflection),
        number(*transmission),
        number(*ior)
    )
}

/// An `f32` literal that reads back as exactly `x` (Rust prints the shortest such digits).
fn number(x: f32) -> String {
    format!("{x:?}_f32")
}

fn vector(v: &[f32; 3]) -> String {
    format!("[{}, {}, {}]", number(v[0]), number(v[1]), number(v[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn numbers_are_written_so_that_they_read_back_exactly() {
        for x in [
            0.1_f32,
            1e-6,
            30.0,
            -2.2,
            f32::MIN_POSITIVE,
            16_777_217.0,
            3.4e38,
        ] {
            let text = number(x);
            let back: f32 = text.trim_end_matches("_f32").parse().unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{text}");
        }
    }

    #[test]
    fn a_configuration_reads_scene_files_formats_and_methods() {
        let configuration = configure(
            &workspace(),
            env(&[
                (SCENES, "whitted, host/scenes/marbles.toml"),
                (FORMATS, "f32,i32f32,f32"),
                (METHODS, "sphere=stable"),
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
        let source = configuration.source();
        assert!(
            source.contains(
                "crate::frames::variants::<obscura::formats::F32, 5, 2, 5>(backend, clock, \"marbles\""
            ),
            "{source}"
        );
        assert!(source.contains("samples: 1,"), "{source}");
    }

    #[test]
    fn sampling_holds_for_every_scene() {
        let configure_sampling = |variable, value| {
            configure(
                &workspace(),
                env(&[
                    (SCENES, "whitted,shapes"),
                    (FORMATS, "f32"),
                    (variable, value),
                ]),
            )
        };
        let configuration = configure_sampling("OBSCURA_SAMPLES", "4").unwrap();
        assert!(configuration.scenes.iter().all(|s| s.scene.samples == 4));
        assert_eq!(configuration.source().matches(" samples: 4,").count(), 2);
        let configuration = configure_sampling("OBSCURA_SHADOW_SAMPLES", "16").unwrap();
        assert!(
            configuration
                .scenes
                .iter()
                .all(|s| s.scene.shadow_samples == 16)
        );
        assert_eq!(
            configuration
                .source()
                .matches("shadow_samples: 16,")
                .count(),
            2
        );
        let configuration = configure_sampling("OBSCURA_ADAPTIVE_SHADOWS", "true").unwrap();
        assert!(
            configuration
                .scenes
                .iter()
                .all(|s| s.scene.adaptive_shadows)
        );
        assert_eq!(
            configuration
                .source()
                .matches("adaptive_shadows: true,")
                .count(),
            2
        );
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
    fn a_scene_the_format_cannot_hold_is_refused_at_its_line_and_column() {
        let error = configure(
            &workspace(),
            env(&[
                (SCENES, "host/scenes/hostile/low-light.toml"),
                (FORMATS, "i16f16"),
            ]),
        )
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
            (&[(FORMATS, "i17f15")][..], "not a firmware format"),
            (
                &[(METHODS, "sphere=round")][..],
                "the sphere method is quadratic or stable",
            ),
            (&[(VARIANTS, "all")][..], "`none` or `each`"),
            (&[(FORMATS, "auto")][..], "obscura firmware --target"),
            (
                &[(DITHER, "floyd")][..],
                "OBSCURA_DITHER is none or ordered, not `floyd`",
            ),
            (&[(ORDER, "bottom-up")][..], "top-down or progressive"),
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
