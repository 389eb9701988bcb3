//! The settings of a render besides its scene, each declared once (in `settings!`'s uses
//! below): its field is the command line's flag (`samples`, `--samples`), it names its
//! environment variable (`OBSCURA_SAMPLES`: the firmware's build reads it, and every command's
//! flag falls back on it, through clap's `env`), its default (where it has one) and the parser
//! that checks its values, for the flag, the variable and the default alike. [`table`] lists
//! them all, as `obscura settings` prints them into the book (`docs/boards.md`).
//!
//! - [`Sampling`]: rays per pixel and per area light, over the scene's own counts.
//! - [`MethodSettings`]: the numerical methods.
//! - [`PresentationSettings`]: the order of a frame's rows and its rounding to the display.
//! - [`FrameSettings`]: which scenes a firmware draws, in which formats.
//! - [`FirmwareSettings`]: all four, what a firmware's build reads.

use crate::{Format, OwnedScene};
use anyhow::{Result, anyhow};
use obscura::methods::MethodName;
use obscura::pattern::MAX_SAMPLES;
use obscura::{
    BiasMethod, Dither, Methods, Pixels, Presentation, RayMethod, RootMethod, RowOrder,
    SphereMethod, TriangleMethod,
};
use std::fmt;

/// One setting, as [`table`] lists it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Setting {
    /// The field, which is the flag: `adaptive_samples` is `--adaptive-samples`.
    pub field: &'static str,
    /// The environment variable.
    pub variable: &'static str,
    /// The value it takes when not given; `None`: the scene's own.
    pub default: Option<&'static str>,
    /// What it is (its documentation).
    pub about: &'static str,
}

impl Setting {
    /// The command line's flag.
    #[must_use]
    pub fn flag(&self) -> String {
        format!("--{}", self.field.replace('_', "-"))
    }
}

/// A value as a setting's variable spells it, which its parser reads back.
pub trait Spelled {
    /// The value's spelling.
    fn spelled(&self) -> String;
}

macro_rules! spelled_by_display {
    ($($t:ty),*) => {$(
        impl Spelled for $t {
            fn spelled(&self) -> String {
                self.to_string()
            }
        }
    )*};
}
spelled_by_display!(u16, bool, String, Format, FormatChoice);

macro_rules! spelled_by_name {
    ($($t:ty),*) => {$(
        impl Spelled for $t {
            fn spelled(&self) -> String {
                self.name().to_owned()
            }
        }
    )*};
}
spelled_by_name!(
    SphereMethod,
    TriangleMethod,
    RootMethod,
    RayMethod,
    BiasMethod,
    RowOrder,
    Dither,
    Variants,
    Pixels
);

/// A setting read from its variable, or from its default: `text` by `parse`, or the error with
/// the variable's name.
fn parsed<T>(
    variable: &str,
    text: &str,
    parse: fn(&str) -> Result<T, String>,
) -> Result<T, anyhow::Error> {
    parse(text.trim()).map_err(|why| anyhow!("{variable}: {why}"))
}

/// The variable's text, when it is set and not blank.
fn given(var: &impl Fn(&str) -> Option<String>, variable: &str) -> Option<String> {
    var(variable).filter(|text| !text.trim().is_empty())
}

/// Declares a struct of settings, each a line: its documentation, field, type, default (for
/// those in `list` and `one`), environment variable and parser (`fn(&str) -> Result<T,
/// String>`). Those in `list` take a comma-separated list, those in `one` one value, those in
/// `optional` one value or none (the scene's own). With the `clap` feature the struct is
/// clap's `Args`, each setting a flag that falls back on its variable.
macro_rules! settings {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            list { $($(#[doc = $list_doc:literal])* $list:ident: $list_ty:ty = $list_default:literal, $list_env:literal, $list_parse:expr;)* }
            one { $($(#[doc = $one_doc:literal])* $one:ident: $one_ty:ty = $one_default:literal, $one_env:literal, $one_parse:expr;)* }
            optional { $($(#[doc = $opt_doc:literal])* $opt:ident: $opt_ty:ty, $opt_env:literal, $opt_parse:expr;)* }
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Debug, PartialEq, Eq)]
        #[cfg_attr(feature = "clap", derive(clap::Args))]
        pub struct $name {
            $(
                $(#[doc = $list_doc])*
                #[cfg_attr(feature = "clap", arg(long, env = $list_env, value_parser = $list_parse, value_delimiter = ',', default_value = $list_default))]
                pub $list: Vec<$list_ty>,
            )*
            $(
                $(#[doc = $one_doc])*
                #[cfg_attr(feature = "clap", arg(long, env = $one_env, value_parser = $one_parse, default_value = $one_default))]
                pub $one: $one_ty,
            )*
            $(
                $(#[doc = $opt_doc])*
                #[cfg_attr(feature = "clap", arg(long, env = $opt_env, value_parser = $opt_parse))]
                pub $opt: Option<$opt_ty>,
            )*
        }

        impl $name {
            /// The settings, in the order of the fields.
            pub const SETTINGS: &'static [Setting] = &[
                $(Setting { field: stringify!($list), variable: $list_env, default: Some($list_default), about: concat!($($list_doc),*) },)*
                $(Setting { field: stringify!($one), variable: $one_env, default: Some($one_default), about: concat!($($one_doc),*) },)*
                $(Setting { field: stringify!($opt), variable: $opt_env, default: None, about: concat!($($opt_doc),*) },)*
            ];

            /// The settings the environment gives (`var` reads a variable; one unset or blank
            /// takes its default, or for an optional one none).
            ///
            /// # Errors
            /// A value its parser refuses, with the variable's name.
            pub fn from_env(var: impl Fn(&str) -> Option<String>) -> Result<Self> {
                Ok(Self {
                    $($one: parsed($one_env, &given(&var, $one_env).unwrap_or_else(|| $one_default.to_owned()), $one_parse)?,)*
                    $($list: given(&var, $list_env)
                        .unwrap_or_else(|| $list_default.to_owned())
                        .split(',')
                        .map(|item| parsed($list_env, item, $list_parse))
                        .collect::<Result<_>>()?,)*
                    $($opt: given(&var, $opt_env)
                        .map(|text| parsed($opt_env, &text, $opt_parse))
                        .transpose()?,)*
                })
            }

            /// Each variable with the value that gives these settings to a build (`None`:
            /// unset).
            #[must_use]
            pub fn environment(&self) -> Vec<(&'static str, Option<String>)> {
                vec![
                    $(($list_env, Some(self.$list.iter().map(Spelled::spelled).collect::<Vec<_>>().join(","))),)*
                    $(($one_env, Some(self.$one.spelled())),)*
                    $(($opt_env, self.$opt.as_ref().map(Spelled::spelled)),)*
                ]
            }
        }

        impl Default for $name {
            /// Every setting's default.
            fn default() -> Self {
                Self::from_env(|_| None).expect("every default parses (tested)")
            }
        }
    };
}

settings! {
    /// How many rays a pixel and an area light take, over the scene's own `samples`,
    /// `adaptive_samples`, `shadow_samples`, `adaptive_shadows` and `pixels` (the fields are
    /// the scene file's keys too): a setting not given keeps the scene's own.
    pub struct Sampling {
        list {}
        one {}
        optional {
            /// Rays per pixel, 1 to 256, spread over the pixel and averaged (anti-aliasing).
            samples: u16, "OBSCURA_SAMPLES", rays;
            /// Whether a pixel takes rays at its corners and splits where they differ, down to
            /// 1/samples of it (`true`: Whitted's adaptive anti-aliasing, samples 4, 16, 64 or
            /// 256), or takes all its samples (`false`).
            adaptive_samples: bool, "OBSCURA_ADAPTIVE_SAMPLES", switch;
            /// Shadow rays per light with a radius, 1 to 256, spread over the light (soft
            /// shadows).
            shadow_samples: u16, "OBSCURA_SHADOW_SAMPLES", rays;
            /// Whether a point takes an area light's first 4 shadow rays and the rest only
            /// where they disagree (`true`), or all of them (`false`).
            adaptive_shadows: bool, "OBSCURA_ADAPTIVE_SHADOWS", switch;
            /// How a frame's pixels are found: `exact` (each by its own rays), or
            /// `adaptive:N` (N = 2, 4 or 8: blocks of N×N filled from their corners where
            /// the corners agree, split where they do not).
            pixels: Pixels, "OBSCURA_PIXELS", choice::<Pixels>;
        }
    }
}

impl Sampling {
    /// `scene` with the settings given here.
    pub fn apply(&self, scene: &mut OwnedScene) {
        let Self {
            samples,
            adaptive_samples,
            shadow_samples,
            adaptive_shadows,
            pixels,
        } = *self;
        scene.samples = samples.unwrap_or(scene.samples);
        scene.adaptive_samples = adaptive_samples.unwrap_or(scene.adaptive_samples);
        scene.shadow_samples = shadow_samples.unwrap_or(scene.shadow_samples);
        scene.adaptive_shadows = adaptive_shadows.unwrap_or(scene.adaptive_shadows);
        scene.pixels = pixels.unwrap_or(scene.pixels);
    }
}

impl Copy for Sampling {}

settings! {
    /// The numerical methods, one choice each (see [`obscura::methods`]).
    pub struct MethodSettings {
        list {}
        one {
            /// Ray–sphere: the lecture's `quadratic`, or the `stable` form (Haines et al.).
            sphere: SphereMethod = "quadratic", "OBSCURA_SPHERE", choice::<SphereMethod>;
            /// Ray–triangle: Cramer's rule (`cramer`, the lecture's), `moller-trumbore`, or
            /// `watertight`.
            triangle: TriangleMethod = "cramer", "OBSCURA_TRIANGLE", choice::<TriangleMethod>;
            /// Square roots and quotients: `exact`, or the 32-bit fixed formats' fast
            /// approximations (`approx`).
            sqrt: RootMethod = "exact", "OBSCURA_SQRT", choice::<RootMethod>;
            /// Primary rays: computed `per-pixel`, or `stepped` along the scanline.
            rays: RayMethod = "per-pixel", "OBSCURA_RAYS", choice::<RayMethod>;
            /// Self-intersection: an `epsilon` offset, or `exclude` the primitive just left.
            bias: BiasMethod = "epsilon", "OBSCURA_BIAS", choice::<BiasMethod>;
        }
        optional {}
    }
}

impl MethodSettings {
    /// The methods chosen.
    #[must_use]
    pub fn methods(&self) -> Methods {
        Methods {
            sphere: self.sphere,
            triangle: self.triangle,
            roots: self.sqrt,
            rays: self.rays,
            bias: self.bias,
        }
    }

    /// The settings that choose `methods`.
    #[must_use]
    pub fn of(methods: &Methods) -> Self {
        Self {
            sphere: methods.sphere,
            triangle: methods.triangle,
            sqrt: methods.roots,
            rays: methods.rays,
            bias: methods.bias,
        }
    }

    /// The command line's flags that choose these methods.
    #[must_use]
    pub fn flags(&self) -> String {
        let flags: Vec<String> = Self::SETTINGS
            .iter()
            .zip(self.environment())
            .map(|(setting, (_, value))| {
                format!("{} {}", setting.flag(), value.unwrap_or_default())
            })
            .collect();
        flags.join(" ")
    }
}

impl Copy for MethodSettings {}

settings! {
    /// How a frame goes to the display.
    pub struct PresentationSettings {
        list {}
        one {
            /// The order of the rows on the display: `top-down`, or `progressive` (every 8th
            /// row first, each as a block down to the next; the final frame is the same).
            order: RowOrder = "top-down", "OBSCURA_ORDER", choice::<RowOrder>;
            /// The rounding to RGB565: `none`, or `ordered` (a 4×4 Bayer dither, the same on
            /// the host and the microcontroller).
            dither: Dither = "none", "OBSCURA_DITHER", choice::<Dither>;
        }
        optional {}
    }
}

impl PresentationSettings {
    /// The presentation chosen.
    #[must_use]
    pub fn presentation(&self) -> Presentation {
        Presentation {
            order: self.order,
            dither: self.dither,
        }
    }
}

impl Copy for PresentationSettings {}

settings! {
    /// Which scenes a firmware draws, in which formats, by which of the methods' variants.
    pub struct FrameSettings {
        list {
            /// Built-in scenes or scene files (relative to the workspace, or absolute),
            /// comma-separated.
            scene: String = "whitted", "OBSCURA_SCENES", scene_name;
            /// Formats, comma-separated; `auto` is the cheapest on the target that holds
            /// every scene and measures at the target PSNR on the host, which `obscura
            /// firmware` picks (a build alone cannot: it names the command that does).
            format: FormatChoice = "i16f16", "OBSCURA_FORMATS", format_choice;
        }
        one {
            /// `each`: also draw each variant of the methods that changes one of them (what
            /// `obscura chart` measures); `none`: the methods alone.
            variants: Variants = "none", "OBSCURA_VARIANTS", choice::<Variants>;
        }
        optional {}
    }
}

/// Everything a firmware's build reads from its environment.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct FirmwareSettings {
    /// The scenes and formats.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub frames: FrameSettings,
    /// The methods.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub methods: MethodSettings,
    /// The sampling of every scene.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub sampling: Sampling,
    /// The order of the rows and the dither.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub presentation: PresentationSettings,
}

impl FirmwareSettings {
    /// Every setting, in the order [`table`] lists them.
    pub fn settings() -> impl Iterator<Item = &'static Setting> {
        FrameSettings::SETTINGS
            .iter()
            .chain(MethodSettings::SETTINGS)
            .chain(Sampling::SETTINGS)
            .chain(PresentationSettings::SETTINGS)
    }

    /// The settings the environment gives.
    ///
    /// # Errors
    /// A value its parser refuses, with the variable's name.
    pub fn from_env(var: impl Fn(&str) -> Option<String>) -> Result<Self> {
        Ok(Self {
            frames: FrameSettings::from_env(&var)?,
            methods: MethodSettings::from_env(&var)?,
            sampling: Sampling::from_env(&var)?,
            presentation: PresentationSettings::from_env(&var)?,
        })
    }

    /// Each variable with the value that gives these settings to a build (`None`: unset):
    /// every variable, so that a build inherits none from its caller.
    #[must_use]
    pub fn environment(&self) -> Vec<(&'static str, Option<String>)> {
        let mut all = self.frames.environment();
        all.extend(self.methods.environment());
        all.extend(self.sampling.environment());
        all.extend(self.presentation.environment());
        all
    }
}

/// The settings as a Markdown table: variable, flag, default, what (`obscura settings`, which
/// writes it into the book).
#[must_use]
pub fn table() -> String {
    let mut out = String::from("| variable | flag | default | what |\n|---|---|---|---|\n");
    for setting in FirmwareSettings::settings() {
        out.push_str(&format!(
            "| `{}` | `{}` | {} | {} |\n",
            setting.variable,
            setting.flag(),
            setting
                .default
                .map_or_else(|| "the scene's own".to_owned(), |d| format!("`{d}`")),
            setting.about.trim().replace('\n', " ")
        ));
    }
    out
}

/// Whether a firmware draws each variant of its methods too.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Variants {
    /// The methods alone.
    #[default]
    None,
    /// Each variant that changes one method, too.
    Each,
}

impl MethodName for Variants {
    const ALL: &'static [(Self, &'static str)] = &[(Self::None, "none"), (Self::Each, "each")];
}

/// A number format, or `auto`: the cheapest measured to meet a target.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormatChoice {
    /// The cheapest format that holds the scene and, rendered on the host, reaches the target
    /// PSNR against f64 (see `obscura analyze`).
    Auto,
    /// This format.
    Given(Format),
}

impl fmt::Display for FormatChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Auto => f.write_str("auto"),
            Self::Given(format) => format.fmt(f),
        }
    }
}

#[cfg(feature = "clap")]
impl clap::ValueEnum for FormatChoice {
    fn value_variants<'a>() -> &'a [Self] {
        static CHOICES: std::sync::LazyLock<Vec<FormatChoice>> = std::sync::LazyLock::new(|| {
            let given = Format::ALL.iter().copied().map(FormatChoice::Given);
            given.chain([FormatChoice::Auto]).collect()
        });
        &CHOICES
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        match self {
            Self::Given(format) => Some(clap::builder::PossibleValue::new(format.name())),
            Self::Auto => Some(clap::builder::PossibleValue::new("auto").help(
                "The cheapest format that holds the scene and is predicted to reach \
                 --target-psnr (see `obscura analyze`)",
            )),
        }
    }
}

/// A count of rays, 1 to [`MAX_SAMPLES`].
fn rays(text: &str) -> Result<u16, String> {
    text.parse()
        .ok()
        .filter(|n| (1..=MAX_SAMPLES).contains(n))
        .ok_or_else(|| format!("a number of rays from 1 to {MAX_SAMPLES}, not `{text}`"))
}

/// `true` or `false`.
fn switch(text: &str) -> Result<bool, String> {
    text.parse()
        .map_err(|_| format!("`true` or `false`, not `{text}`"))
}

/// The choice called `text`.
fn choice<M: MethodName + PartialEq>(text: &str) -> Result<M, String> {
    M::from_name(text).ok_or_else(|| {
        let names: Vec<_> = M::ALL.iter().map(|(_, name)| format!("`{name}`")).collect();
        format!("{}, not `{text}`", names.join(" or "))
    })
}

/// A scene's name or file: anything but nothing.
fn scene_name(text: &str) -> Result<String, String> {
    let name = text.trim();
    if name.is_empty() {
        Err("a built-in scene's name or a scene file, not nothing".to_owned())
    } else {
        Ok(name.to_owned())
    }
}

/// A format's name, or `auto`.
fn format_choice(text: &str) -> Result<FormatChoice, String> {
    match (text, Format::from_name(text)) {
        ("auto", _) => Ok(FormatChoice::Auto),
        (_, Some(format)) => Ok(FormatChoice::Given(format)),
        (_, None) => Err(format!(
            "a format ({}, f64) or `auto`, not `{text}`",
            Format::firmware_names()
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reader of the variables in `pairs`.
    fn given(pairs: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let pairs: Vec<(String, String)> = pairs
            .iter()
            .map(|(n, v)| ((*n).to_owned(), (*v).to_owned()))
            .collect();
        move |name| {
            pairs
                .iter()
                .find(|(n, _)| n == name)
                .map(|(_, v)| v.clone())
        }
    }

    #[test]
    fn every_default_parses_and_every_setting_is_named_once() {
        let defaults = FirmwareSettings::default();
        assert_eq!(defaults.methods.methods(), Methods::LECTURE);
        assert_eq!(
            defaults.sampling,
            Sampling {
                samples: None,
                adaptive_samples: None,
                shadow_samples: None,
                adaptive_shadows: None,
                pixels: None,
            }
        );
        assert_eq!(defaults.frames.scene, ["whitted"]);
        assert_eq!(
            defaults.frames.format,
            [FormatChoice::Given(Format::I16f16)]
        );
        let mut seen = std::collections::HashSet::new();
        for setting in FirmwareSettings::settings() {
            assert!(seen.insert(setting.variable), "{} twice", setting.variable);
            assert!(seen.insert(setting.field), "{} twice", setting.field);
            assert!(setting.variable.starts_with("OBSCURA_"));
            assert!(!setting.about.trim().is_empty());
        }
    }

    #[test]
    fn each_setting_reads_its_variable_and_refuses_what_its_parser_refuses() {
        let all = FirmwareSettings::from_env(given(&[
            ("OBSCURA_SCENES", "whitted, host/scenes/marbles.toml"),
            ("OBSCURA_FORMATS", "f32,auto"),
            ("OBSCURA_SPHERE", "stable"),
            ("OBSCURA_SAMPLES", " 16 "),
            ("OBSCURA_ADAPTIVE_SAMPLES", "true"),
            ("OBSCURA_SHADOW_SAMPLES", "4"),
            ("OBSCURA_DITHER", "ordered"),
            ("OBSCURA_VARIANTS", "each"),
        ]))
        .unwrap();
        assert_eq!(all.frames.scene, ["whitted", "host/scenes/marbles.toml"]);
        assert_eq!(
            all.frames.format,
            [FormatChoice::Given(Format::F32), FormatChoice::Auto]
        );
        assert_eq!(all.methods.sphere, SphereMethod::Stable);
        assert_eq!(all.sampling.samples, Some(16));
        assert_eq!(all.sampling.adaptive_samples, Some(true));
        assert_eq!(all.sampling.adaptive_shadows, None);
        assert_eq!(all.presentation.dither, Dither::Ordered);
        assert_eq!(all.frames.variants, Variants::Each);
        // What a build is given reads back as the same settings.
        let environment = all.environment();
        let back = FirmwareSettings::from_env(|name| {
            environment
                .iter()
                .find(|(n, _)| *n == name)
                .and_then(|(_, v)| v.clone())
        });
        assert_eq!(back.unwrap(), all);
        assert_eq!(environment.len(), FirmwareSettings::settings().count());
        for (variable, wrong) in [
            ("OBSCURA_SAMPLES", "0"),
            ("OBSCURA_SAMPLES", "257"),
            ("OBSCURA_SHADOW_SAMPLES", "four"),
            ("OBSCURA_ADAPTIVE_SHADOWS", "yes"),
            ("OBSCURA_SPHERE", "exact"),
            ("OBSCURA_FORMATS", "i16f16,i17f15"),
            ("OBSCURA_ORDER", "sideways"),
            ("OBSCURA_SCENES", "whitted,,shapes"),
        ] {
            let message = FirmwareSettings::from_env(given(&[(variable, wrong)]))
                .unwrap_err()
                .to_string();
            assert!(message.starts_with(variable), "{message}");
        }
    }

    #[test]
    fn methods_read_back_from_their_flags() {
        let methods = Methods {
            sphere: SphereMethod::Stable,
            bias: BiasMethod::Exclude,
            ..Methods::LECTURE
        };
        let flags = MethodSettings::of(&methods).flags();
        assert_eq!(
            flags,
            "--sphere stable --triangle cramer --sqrt exact --rays per-pixel --bias exclude"
        );
        assert_eq!(MethodSettings::of(&methods).methods(), methods);
    }
}
