//! [`Sampling`]: how many rays a pixel and an area light take, given over a scene's own counts.
//! Each setting is declared once, below: its field is the scene file's key and the command
//! line's flag (`samples`, `--samples`), and it names its environment variable
//! (`OBSCURA_SAMPLES`: the firmware's build reads it, and the harness's flag falls back on it)
//! and the parser that checks its values, for the flag and the variable alike.

use crate::OwnedScene;
use anyhow::{Result, anyhow};
use obscura::pattern::MAX_SAMPLES;

/// Declares [`Sampling`] from one line per setting: its documentation, field, type,
/// environment variable and parser.
macro_rules! sampling {
    ($($(#[$doc:meta])* $field:ident: $ty:ty, $env:literal, $parse:path;)*) => {
        /// How many rays a pixel and an area light take, over the scene's own `samples`,
        /// `adaptive_samples`, `shadow_samples` and `adaptive_shadows`: a setting not given
        /// keeps the scene's own.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        #[cfg_attr(feature = "clap", derive(clap::Args))]
        pub struct Sampling {
            $(
                $(#[$doc])*
                #[cfg_attr(feature = "clap", arg(long, env = $env, value_parser = $parse))]
                pub $field: Option<$ty>,
            )*
        }

        impl Sampling {
            /// Each setting's environment variable, in the order of the fields.
            pub const VARIABLES: [&'static str; [$($env),*].len()] = [$($env),*];

            /// `scene` with the settings given here.
            pub fn apply(&self, scene: &mut OwnedScene) {
                $(
                    if let Some(value) = self.$field {
                        scene.$field = value;
                    }
                )*
            }

            /// The settings the environment gives (`var` reads a variable; one unset or
            /// empty keeps the scene's own).
            ///
            /// # Errors
            /// A value its parser refuses, with the variable's name.
            pub fn from_env(var: impl Fn(&str) -> Option<String>) -> Result<Self> {
                Ok(Self {
                    $(
                        $field: var($env)
                            .filter(|text| !text.trim().is_empty())
                            .map(|text| $parse(text.trim()).map_err(|why| anyhow!("{}: {why}", $env)))
                            .transpose()?,
                    )*
                })
            }

            /// Each variable with the value that gives these settings to a build (`None`:
            /// unset, the scene's own).
            #[must_use]
            pub fn environment(&self) -> [(&'static str, Option<String>); [$($env),*].len()] {
                [$(($env, self.$field.map(|value| value.to_string())),)*]
            }
        }
    };
}

sampling! {
    /// Rays per pixel, 1 to 256, spread over the pixel and averaged (anti-aliasing); the
    /// scene's own `samples` when not given.
    samples: u16, "OBSCURA_SAMPLES", rays;
    /// Whether a pixel takes rays at its corners and splits where they differ, down to
    /// 1/samples of it (`true`: Whitted's adaptive anti-aliasing, samples 4, 16, 64 or 256),
    /// or takes all its samples (`false`); the scene's own `adaptive_samples` when not given.
    adaptive_samples: bool, "OBSCURA_ADAPTIVE_SAMPLES", switch;
    /// Shadow rays per light with a radius, 1 to 256, spread over the light (soft shadows);
    /// the scene's own `shadow_samples` when not given.
    shadow_samples: u16, "OBSCURA_SHADOW_SAMPLES", rays;
    /// Whether a point takes an area light's first 4 shadow rays and the rest only where they
    /// disagree (`true`), or all of them (`false`); the scene's own `adaptive_shadows` when not
    /// given.
    adaptive_shadows: bool, "OBSCURA_ADAPTIVE_SHADOWS", switch;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_setting_reads_its_variable_and_refuses_what_its_parser_refuses() {
        let given = |pairs: &'static [(&str, &str)]| {
            Sampling::from_env(|name| {
                pairs
                    .iter()
                    .find(|(n, _)| *n == name)
                    .map(|(_, v)| (*v).to_owned())
            })
        };
        assert_eq!(given(&[]).unwrap(), Sampling::default());
        let all = given(&[
            ("OBSCURA_SAMPLES", "16"),
            ("OBSCURA_ADAPTIVE_SAMPLES", "true"),
            ("OBSCURA_SHADOW_SAMPLES", " 4 "),
            ("OBSCURA_ADAPTIVE_SHADOWS", "false"),
        ])
        .unwrap();
        assert_eq!(
            all,
            Sampling {
                samples: Some(16),
                adaptive_samples: Some(true),
                shadow_samples: Some(4),
                adaptive_shadows: Some(false),
            }
        );
        // What a build is given reads back as the same settings.
        let environment = all.environment();
        let back = Sampling::from_env(|name| {
            environment
                .iter()
                .find(|(n, _)| *n == name)
                .and_then(|(_, v)| v.clone())
        });
        assert_eq!(back.unwrap(), all);
        for (variable, wrong) in [
            ("OBSCURA_SAMPLES", "0"),
            ("OBSCURA_SAMPLES", "257"),
            ("OBSCURA_SHADOW_SAMPLES", "four"),
            ("OBSCURA_ADAPTIVE_SHADOWS", "yes"),
        ] {
            let pairs: &'static [(&str, &str)] = Box::leak(Box::new([(variable, wrong)]));
            let message = given(pairs).unwrap_err().to_string();
            assert!(
                message.starts_with(variable) && message.contains(wrong),
                "{message}"
            );
        }
    }
}
