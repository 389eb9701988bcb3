//! Range analysis: the largest magnitude each computation of the tracer reaches in a scene,
//! and the smallest feature each must resolve, for the chosen [`Methods`]. A format holds a
//! scene when every magnitude fits its range and every feature spans enough of its steps.
//!
//! All positions are relative to the eye and lie within the world radius R = `far`, so a ray
//! origin o satisfies |o| ≤ R and a ray is never longer than the world's diameter 2R.

use super::error::{Item, SceneError};
use super::validate::distance;
use crate::desc::{BackgroundDesc, SceneDesc, ShapeDesc};
use crate::methods::{Methods, SphereMethod, TriangleMethod};
use crate::scalar::Scalar;
use crate::vec3::Vec3;

/// A feature must span this many steps of the error its computation makes, or rounding would
/// change its shape visibly.
pub const MIN_FEATURE_STEPS: f64 = 16.0;

/// Extra room every magnitude must leave in the format's range, for rounding.
pub const RANGE_HEADROOM: f64 = 1.01;

/// The largest magnitude one computation reaches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Magnitude {
    /// Whose computation.
    pub item: Item,
    /// What is computed.
    pub quantity: &'static str,
    /// Its largest magnitude in this scene.
    pub value: f64,
}

/// A small quantity a computation must resolve against the rounding error it makes.
///
/// The error is `scale` times the format's resolution at `against` ([`Scalar::resolution`]):
/// for a fixed format a multiple of its LSB, for a float a multiple of its relative precision
/// at that magnitude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Feature {
    /// Whose feature.
    pub item: Item,
    /// What it is.
    pub quantity: &'static str,
    /// Its size.
    pub value: f64,
    /// How many resolution steps one rounding error of the computation spans.
    pub scale: f64,
    /// The magnitude at which the computation rounds.
    pub against: f64,
}

impl Feature {
    /// The error format `S` makes computing this feature.
    #[must_use]
    pub fn error<S: Scalar>(&self) -> f64 {
        self.scale * S::resolution(self.against)
    }

    /// The smallest value format `S` resolves here: [`MIN_FEATURE_STEPS`] of its errors.
    #[must_use]
    pub fn minimum<S: Scalar>(&self) -> f64 {
        MIN_FEATURE_STEPS * self.error::<S>()
    }
}

/// Every magnitude of the scene's computations by `methods` (the description must have passed
/// validation).
///
/// With R = `far`, every position lies within R of the eye, every ray origin too (up to the
/// surface tolerance), every direction is a unit vector and every material weight and colour
/// is in [0, 1] with reflection + transmission ≤ 1. The bounds below follow from that, one per
/// computation that could grow largest; [`RANGE_HEADROOM`] covers rounding.
pub fn magnitudes<'a>(
    desc: &'a SceneDesc<'a>,
    methods: &'a Methods,
) -> impl Iterator<Item = Magnitude> + 'a {
    let world = f64::from(desc.far);
    let eye = desc.camera.eye;
    let scene = |quantity, value| Magnitude {
        item: Item::Scene,
        quantity,
        value,
    };
    let global = [
        scene("a ray's length (the world's diameter)", 2.0 * world),
        scene("a point along a ray, o + t·d", 3.0 * world),
        scene(
            "a pixel's sum of colours over its ray tree",
            colour_sum(desc),
        ),
    ];
    let objects = desc
        .objects
        .iter()
        .enumerate()
        .flat_map(move |(i, object)| {
            let item = Item::Object(i);
            let shape: [Option<(&'static str, f64)>; 2] = match object.shape {
                ShapeDesc::Sphere { center, .. } => {
                    // Both forms square |o − c| (the quadratic also squares b = d·(o − c), no larger).
                    let oc = world + distance(center, eye);
                    let quantity = match methods.sphere {
                        SphereMethod::Quadratic => "|o − c|² in the quadratic",
                        SphereMethod::Stable => "|o − c|² in the stable form",
                    };
                    [Some((quantity, oc * oc)), None]
                }
                ShapeDesc::Plane { checker, .. } => {
                    let checker = checker.map(|checker| {
                        // The checker origin is a grid corner within a square's diagonal of the
                        // plane's point nearest the eye, which is inside the world.
                        let size = f64::from(checker.size);
                        ("a checker coordinate", (2.0 * world + 2.0 * size) / size)
                    });
                    // The world test squares a point only once each coordinate is within R.
                    [
                        Some(("|p|² in the world test", 3.0 * world * world)),
                        checker,
                    ]
                }
                ShapeDesc::Triangle { vertices } => {
                    let corners = vertices.map(Vec3::from_f32);
                    [
                        Some(triangle_magnitude(
                            methods.triangle,
                            world,
                            Vec3::from_f32(eye),
                            corners,
                        )),
                        None,
                    ]
                }
            };
            let refraction = (object.material.transmission > 0.0).then(|| {
                let ior = f64::from(object.material.ior);
                ("η² + 1 in Snell's law", ior * ior + 1.0)
            });
            shape
                .into_iter()
                .chain([refraction])
                .flatten()
                .map(move |(quantity, value)| Magnitude {
                    item,
                    quantity,
                    value,
                })
        });
    let lights = desc.lights.iter().enumerate().map(move |(i, light)| {
        let reach = world + distance(light.position, eye);
        Magnitude {
            item: Item::Light(i),
            quantity: "|light − p|²",
            value: reach * reach,
        }
    });
    global.into_iter().chain(objects).chain(lights)
}

/// The largest numerator of Cramer's rule and of Möller–Trumbore, with |s| = |o − a| ≤ R + |a|:
/// det[s e1 e2] ≤ |s||e1||e2| and the cross products with s, ≤ |s|·|e|.
pub(crate) fn triangle_numerators(world: f64, eye: Vec3<f64>, [a, b, c]: [Vec3<f64>; 3]) -> f64 {
    let (e1, e2) = ((b - a).length(), (c - a).length());
    let s = world + (a - eye).length();
    (s * e1 * e2).max(s * e1.max(e2)).max(e1 * e2)
}

fn triangle_magnitude(
    method: TriangleMethod,
    world: f64,
    eye: Vec3<f64>,
    corners: [Vec3<f64>; 3],
) -> (&'static str, f64) {
    match method {
        TriangleMethod::Cramer => (
            "Cramer's determinants",
            triangle_numerators(world, eye, corners),
        ),
        TriangleMethod::MollerTrumbore => (
            "Möller–Trumbore's numerators",
            triangle_numerators(world, eye, corners),
        ),
        TriangleMethod::Watertight => {
            // Sheared corners are at most √2·M from the origin (|Sx|, |Sy| ≤ 1), with M the
            // farthest corner from a ray origin; each edge function is a difference of two
            // products of them, and the determinant the sum of three.
            let far = corners
                .iter()
                .map(|&p| world + (p - eye).length())
                .fold(0.0, f64::max);
            (
                "the watertight edge functions and their sum",
                12.0 * far * far,
            )
        }
    }
}

/// The largest colour a pixel can sum: every level of the ray tree carries at most weight 1 in
/// all (reflection + transmission ≤ 1), and each hit adds at most the ambient light plus, per
/// light, its colour times (diffuse + specular) ≤ 2; a miss adds the background.
fn colour_sum(desc: &SceneDesc<'_>) -> f64 {
    let brightest = |c: [f32; 3]| c.iter().copied().fold(0.0_f32, f32::max);
    let lights: f64 = desc
        .lights
        .iter()
        .map(|l| 2.0 * f64::from(brightest(l.colour)))
        .sum();
    let local = f64::from(brightest(desc.ambient)) + lights;
    let background = match desc.background {
        BackgroundDesc::Solid(c) => f64::from(brightest(c)),
        BackgroundDesc::Gradient { horizon, zenith } => {
            f64::from(brightest(horizon)) + f64::from(brightest(zenith))
        }
    };
    (f64::from(desc.max_depth) + 1.0) * local.max(background)
}

/// Every feature the scene's computations by `methods` must resolve.
pub fn features<'a>(
    desc: &'a SceneDesc<'a>,
    methods: &'a Methods,
) -> impl Iterator<Item = Feature> + 'a {
    let world = f64::from(desc.far);
    let eye = desc.camera.eye;
    desc.objects
        .iter()
        .enumerate()
        .filter_map(move |(i, object)| {
            let item = Item::Object(i);
            match object.shape {
                ShapeDesc::Sphere { center, radius } => {
                    let f = world + distance(center, eye);
                    let r = f64::from(radius);
                    // The discriminant is r² less a rounded difference. The quadratic's, b² − c,
                    // errs by about |f| times the resolution at |f| (half a step in b, doubled by
                    // the square); the stable form's, r² − |f + b·d|², by about 2r times it.
                    let (quantity, scale) = match methods.sphere {
                        SphereMethod::Quadratic => ("radius² against the quadratic's b² − c", f),
                        SphereMethod::Stable => {
                            ("radius² against the stable discriminant", 2.0 * r)
                        }
                    };
                    Some(Feature {
                        item,
                        quantity,
                        value: r * r,
                        scale,
                        against: f,
                    })
                }
                ShapeDesc::Plane { checker, .. } => checker.map(|checker| Feature {
                    item,
                    quantity: "checker square size",
                    value: f64::from(checker.size),
                    scale: 1.0,
                    against: world,
                }),
                ShapeDesc::Triangle { vertices } => {
                    let (e1, e2) = edges(vertices);
                    let s = world + distance(vertices[0], eye);
                    let longest = e1.length().max(e2.length());
                    Some(Feature {
                        item,
                        quantity: "twice the triangle's area",
                        value: e1.cross(e2).length(),
                        scale: 1.0,
                        against: s * longest,
                    })
                }
            }
        })
}

/// Proves that format `S` holds the scene for `methods`, or says which value does not fit.
pub(super) fn check<S: Scalar>(desc: &SceneDesc<'_>, methods: &Methods) -> Result<(), SceneError> {
    if let Some(m) = magnitudes(desc, methods).find(|m| m.value * RANGE_HEADROOM > S::RANGE) {
        return Err(SceneError::OutOfRange {
            item: m.item,
            quantity: m.quantity,
            value: m.value,
            format: S::NAME,
            range: S::RANGE,
        });
    }
    if let Some(f) = features(desc, methods).find(|f| f.value < f.minimum::<S>()) {
        return Err(SceneError::BelowResolution {
            item: f.item,
            quantity: f.quantity,
            value: f.value,
            format: S::NAME,
            minimum: f.minimum::<S>(),
        });
    }
    Ok(())
}

/// A triangle's two edges from its first corner, in `f64`.
fn edges(vertices: [[f32; 3]; 3]) -> (Vec3<f64>, Vec3<f64>) {
    let [a, b, c] = vertices.map(Vec3::from_f32);
    (b - a, c - a)
}
