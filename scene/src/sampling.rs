//! [`Sampling`]: how many rays a pixel and an area light take, given over a scene's own counts
//! (by the command line, or the firmware's build environment).

use crate::OwnedScene;
#[cfg(feature = "clap")]
use obscura::pattern::MAX_SAMPLES;

/// How many rays a pixel and an area light take, over the scene's own `samples` and
/// `shadow_samples`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct Sampling {
    /// Rays per pixel, 1 to 256, spread over the pixel and averaged (anti-aliasing); the
    /// scene's own `samples` when not given.
    #[cfg_attr(
        feature = "clap",
        arg(long, value_parser = clap::value_parser!(u16).range(1..=i64::from(MAX_SAMPLES)))
    )]
    pub samples: Option<u16>,
    /// Whether a pixel takes rays at its corners and splits where they differ, down to
    /// 1/samples of it (`true`: Whitted's adaptive anti-aliasing, samples 4, 16, 64 or 256),
    /// or takes all its samples (`false`); the scene's own `adaptive_samples` when not given.
    #[cfg_attr(feature = "clap", arg(long))]
    pub adaptive_samples: Option<bool>,
    /// Shadow rays per light with a radius, 1 to 256, spread over the light (soft shadows);
    /// the scene's own `shadow_samples` when not given.
    #[cfg_attr(
        feature = "clap",
        arg(long, value_parser = clap::value_parser!(u16).range(1..=i64::from(MAX_SAMPLES)))
    )]
    pub shadow_samples: Option<u16>,
    /// Whether a point takes an area light's first 4 shadow rays and the rest only where they
    /// disagree (`true`), or all of them (`false`); the scene's own `adaptive_shadows` when not
    /// given.
    #[cfg_attr(feature = "clap", arg(long))]
    pub adaptive_shadows: Option<bool>,
}

impl Sampling {
    /// `scene` with the counts given here.
    pub fn apply(&self, scene: &mut OwnedScene) {
        if let Some(samples) = self.samples {
            scene.samples = samples;
        }
        if let Some(adaptive) = self.adaptive_samples {
            scene.adaptive_samples = adaptive;
        }
        if let Some(shadow_samples) = self.shadow_samples {
            scene.shadow_samples = shadow_samples;
        }
        if let Some(adaptive) = self.adaptive_shadows {
            scene.adaptive_shadows = adaptive;
        }
    }
}
