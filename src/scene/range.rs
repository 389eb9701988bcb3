//! Range analysis: the largest magnitude each computation of the tracer reaches in a scene,
//! and the smallest feature each must resolve. A format holds a scene when every magnitude
//! fits its range and every feature spans enough of its steps.
//!
//! All positions are relative to the eye and lie within the world radius R = `far`, so a ray
//! origin o satisfies |o| ≤ R and a ray is never longer than the world's diameter 2R.

use super::error::{Item, SceneError};
use super::validate::distance;
use crate::desc::{BackgroundDesc, SceneDesc, ShapeDesc};
use crate::scalar::Scalar;
use crate::vec3::Vec3;

/// A feature must span this many steps of a format's resolution, or rounding would change its
/// shape visibly.
pub const MIN_FEATURE_STEPS: f64 = 16.0;

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

/// A small quantity a computation must resolve against the large ones it is computed with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Feature {
    /// Whose feature.
    pub item: Item,
    /// What it is.
    pub quantity: &'static str,
    /// Its size.
    pub value: f64,
    /// The magnitude of the values it is computed against: a float resolves `value` relative
    /// to this.
    pub against: f64,
}

impl Feature {
    /// The smallest value format `S` resolves here: [`MIN_FEATURE_STEPS`] steps near `against`.
    #[must_use]
    pub fn minimum<S: Scalar>(&self) -> f64 {
        MIN_FEATURE_STEPS * S::resolution(self.against)
    }
}

/// Every magnitude of the scene's computations (the description must have passed validation).
///
/// With R = `far`, every position lies within R of the eye, every ray origin too (up to the
/// surface tolerance), every direction is a unit vector and every material weight and colour
/// is in [0, 1] with reflection + transmission ≤ 1. The bounds below follow from that, one per
/// computation that could grow largest; [`RANGE_HEADROOM`] covers rounding.
pub fn magnitudes<'a>(desc: &'a SceneDesc<'a>) -> impl Iterator<Item = Magnitude> + 'a {
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
                    let oc = world + distance(center, eye);
                    [Some(("|o − c|² in the sphere test", oc * oc)), None]
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
                    let (e1, e2) = edges(vertices);
                    let (e1, e2) = (e1.length(), e2.length());
                    let s = world + distance(vertices[0], eye);
                    let largest = (s * e1 * e2).max(s * e1.max(e2)).max(e1 * e2);
                    [Some(("Cramer's determinants", largest)), None]
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

/// Extra room every magnitude must leave in the format's range, for rounding.
pub const RANGE_HEADROOM: f64 = 1.01;

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

/// Every feature the scene's computations must resolve.
pub fn features<'a>(desc: &'a SceneDesc<'a>) -> impl Iterator<Item = Feature> + 'a {
    let world = f64::from(desc.far);
    let eye = desc.camera.eye;
    desc.objects
        .iter()
        .enumerate()
        .filter_map(move |(i, object)| {
            let item = Item::Object(i);
            match object.shape {
                ShapeDesc::Sphere { center, radius } => {
                    let oc = world + distance(center, eye);
                    let r = f64::from(radius);
                    Some(Feature {
                        item,
                        quantity: "radius²",
                        value: r * r,
                        against: oc * oc,
                    })
                }
                ShapeDesc::Plane { checker, .. } => checker.map(|checker| Feature {
                    item,
                    quantity: "checker square size",
                    value: f64::from(checker.size),
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
                        against: s * longest,
                    })
                }
            }
        })
}

/// Proves that format `S` holds the scene, or says which value does not fit.
pub(super) fn check<S: Scalar>(desc: &SceneDesc<'_>) -> Result<(), SceneError> {
    if let Some(m) = magnitudes(desc).find(|m| m.value * RANGE_HEADROOM > S::RANGE) {
        return Err(SceneError::OutOfRange {
            item: m.item,
            quantity: m.quantity,
            value: m.value,
            format: S::NAME,
            range: S::RANGE,
        });
    }
    if let Some(f) = features(desc).find(|f| f.value < f.minimum::<S>()) {
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
