//! [`Material`]: how a surface answers light, in the tracer's number format.

crate::phase::declare_phase!(Some(crate::phase::Phase::Shading));

use crate::color::Rgb;
use crate::scalar::Scalar;

/// Whitted's surface model: local (ambient, Lambert diffuse, Phong specular) plus mirror
/// reflection and refraction, each with its weight. The colour and the weights are within
/// [0, 1]: narrow numbers ([`Scalar::Narrow`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material<S: Scalar> {
    /// The surface colour.
    pub colour: Rgb<S::Narrow>,
    /// Lambertian weight.
    pub diffuse: S::Narrow,
    /// Phong highlight weight.
    pub specular: S::Narrow,
    /// Phong exponent.
    pub shininess: u16,
    /// Mirror reflection weight.
    pub reflection: S::Narrow,
    /// Transmission weight.
    pub transmission: S::Narrow,
    /// Index of refraction.
    pub ior: S,
    /// 1 / index of refraction: the ratio η for a ray entering the material.
    pub inv_ior: S,
}

crate::words::words_of_struct!(Material<S> {
    colour,
    diffuse,
    specular,
    shininess,
    reflection,
    transmission,
    ior,
    inv_ior
});

impl<S: Scalar> Material<S> {
    /// Whether the surface sends back light along no ray's direction: no highlight, mirror or
    /// transmission, so that it shades alike whatever the direction a ray arrives along on a
    /// side (the row pass's planes, [`crate::row_pass`]).
    #[must_use]
    pub(crate) fn is_matte(&self) -> bool {
        [self.specular, self.reflection, self.transmission]
            .iter()
            .all(|weight| *weight == S::Narrow::ZERO)
    }
}
