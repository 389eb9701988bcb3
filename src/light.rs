//! What lights a scene ([`Light`]) and what a ray sees when it escapes ([`Background`]).

crate::phase::declare_phase!(Some(crate::phase::Phase::Shading));

use crate::color::Rgb;
use crate::scalar::Scalar;
use crate::vec3::Vec3;

/// A light: a point, or a disc facing every point it lights
/// ([`LightDesc`](crate::LightDesc)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light<S> {
    /// Where it is (the disc's centre), relative to the eye.
    pub position: Vec3<S>,
    /// Its colour and intensity.
    pub colour: Rgb<S>,
    /// The disc's radius; zero for a point.
    pub radius: S,
    /// The shadow rays a point takes to it: 1 for a point light (a radius of 0, or one that
    /// rounds to 0 in the format) or a disc at one shadow sample, else the scene's
    /// [`shadow_samples`](crate::SceneDesc::shadow_samples).
    pub(crate) shadow_rays: u16,
    /// Its place in the scene's lights, which chooses its pattern of shadow rays.
    pub(crate) index: u16,
}

crate::words::words_of_struct!(Light<S> {
    position,
    colour,
    radius,
    shadow_rays,
    index
});

/// The colour of rays that hit nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Background<S> {
    /// One colour.
    Solid(Rgb<S>),
    /// A sky: `horizon` at and below the horizon, `horizon + rise` straight up.
    Gradient {
        /// The colour at the horizon.
        horizon: Rgb<S>,
        /// Zenith minus horizon.
        rise: Rgb<S>,
        /// The unit vector straight up.
        up: Vec3<S>,
    },
}

crate::words::words_of_enum!(Background<S> {
    Solid(colour),
    Gradient { horizon, rise, up }
});

impl<S: Scalar> Background<S> {
    /// The colour seen along the unit direction `dir`.
    #[must_use]
    pub fn colour(&self, dir: Vec3<S>) -> Rgb<S> {
        match *self {
            Self::Solid(colour) => colour,
            Self::Gradient { horizon, rise, up } => {
                horizon + rise.scale_narrow(dir.dot(up).max(S::ZERO).narrow())
            }
        }
    }
}
