//! [`Material`]: how a surface answers light, in the tracer's number format.

use crate::color::Rgb;

/// Whitted's surface model: local (ambient, Lambert diffuse, Phong specular) plus mirror
/// reflection and refraction, each with its weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material<S> {
    /// The surface colour.
    pub colour: Rgb<S>,
    /// Lambertian weight.
    pub diffuse: S,
    /// Phong highlight weight.
    pub specular: S,
    /// Phong exponent.
    pub shininess: u16,
    /// Mirror reflection weight.
    pub reflection: S,
    /// Transmission weight.
    pub transmission: S,
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
