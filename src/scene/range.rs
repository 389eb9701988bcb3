//! Range analysis: the largest magnitude each computation of the tracer reaches in a scene,
//! and the smallest feature each must resolve, for the chosen [`Methods`]. A format holds a
//! scene when every magnitude fits its range and every feature spans enough of its steps.
//!
//! All positions are relative to the eye and lie within the world radius R = `far`, so a ray
//! origin o satisfies |o| ≤ R and a ray is never longer than the world's diameter 2R.

use super::SURFACE_TOLERANCE_STEPS;
use super::error::{Item, SceneError};
use super::validate::distance;
use crate::desc::{BackgroundDesc, ObjectDesc, SceneDesc, ShapeDesc};
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
/// The error is a sum of terms, each a coefficient times the format's resolution at some
/// magnitude ([`Scalar::resolution`]): for a fixed format a multiple of its LSB, for a float a
/// multiple of its relative precision at that magnitude. The feature must span `steps` errors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Feature {
    /// Whose feature.
    pub item: Item,
    /// What it is.
    pub quantity: &'static str,
    /// Its size.
    pub value: f64,
    /// The error's terms.
    pub terms: Terms,
    /// How many errors the feature must span.
    pub steps: f64,
}

impl Feature {
    /// The error format `S` makes computing this feature.
    #[must_use]
    pub fn error<S: Scalar>(&self) -> f64 {
        error::<S>(&self.terms)
    }

    /// The smallest value format `S` resolves here: `steps` of its errors.
    #[must_use]
    pub fn minimum<S: Scalar>(&self) -> f64 {
        self.steps * self.error::<S>()
    }
}

/// An error as a sum of terms, each (coefficient, magnitude): the coefficient times the
/// format's resolution at the magnitude. Unused terms are (0, 0).
pub type Terms = [(f64, f64); 4];

/// The size of the error `terms` describe in format `S`.
#[must_use]
pub fn error<S: Scalar>(terms: &[(f64, f64)]) -> f64 {
    terms
        .iter()
        .map(|&(coefficient, magnitude)| coefficient * S::resolution(magnitude))
        .sum()
}

/// The surface tolerance ([`SURFACE_TOLERANCE_STEPS`]) at a surface point whose largest
/// coordinate is at most `reach` (relative to the eye), on a sphere of `radius` or a sheet.
#[must_use]
pub fn tolerance_terms(reach: f64, radius: Option<f64>) -> Terms {
    let [own, own_small] = radius.map_or([(0.0, 0.0); 2], own_tolerance_terms);
    [
        (SURFACE_TOLERANCE_STEPS, 0.0),
        (SURFACE_TOLERANCE_STEPS * reach, 1.0),
        own,
        own_small,
    ]
}

/// A sphere's own part of the surface tolerance ([`super::Object::tolerance`]): the rounding
/// of a point `radius` from its centre, and the error of the root its test finds for a ray
/// that starts on it, c/2r with c rounded at r².
#[must_use]
pub fn own_tolerance_terms(radius: f64) -> [(f64, f64); 2] {
    [
        (SURFACE_TOLERANCE_STEPS * radius, 1.0),
        (SURFACE_TOLERANCE_STEPS / radius, radius * radius),
    ]
}

/// The error in |d|² of a unit direction, in resolutions at 1: each coordinate is rounded.
const DIRECTION_LENGTH: f64 = 2.0;

/// One 8-bit level of a display channel: the least change of colour that can show.
const LEVEL: f64 = 1.0 / 255.0;

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
                    // The world test squares a point only scaled to within 1 on every axis.
                    [checker, None]
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

/// Every feature the scene's computations by `methods` must resolve, object by object and then
/// light by light. A sphere's or a triangle's first feature is its intersection test's (for a
/// sphere, as seen from the eye), whose error is the band around its edge where a ray may be
/// misjudged.
pub fn features<'a>(
    desc: &'a SceneDesc<'a>,
    methods: &'a Methods,
) -> impl Iterator<Item = Feature> + 'a {
    let world = f64::from(desc.far);
    let eye = desc.camera.eye;
    let objects = desc
        .objects
        .iter()
        .enumerate()
        .flat_map(move |(i, object)| {
            let item = Item::Object(i);
            let feature = |quantity, value, terms| Feature {
                item,
                quantity,
                value,
                terms,
                steps: MIN_FEATURE_STEPS,
            };
            // The surface tolerance is a dead zone in front of every surface: the eye must stand
            // well clear of it, or the tolerance bends every ray it sends there.
            let gap = clearance(desc, object);
            let clearance = |value, reach, radius| {
                feature(
                    "the eye's distance from its surface, against the surface tolerance",
                    value,
                    tolerance_terms(reach, radius),
                )
            };
            match object.shape {
                ShapeDesc::Sphere { center, radius } => {
                    let r = f64::from(radius);
                    let from_eye = distance(center, eye);
                    // Seen from the eye the sphere must keep its shape; seen from anywhere in the
                    // world (a secondary ray's origin) it must at least not vanish.
                    let across_world = Feature {
                        steps: 1.0,
                        ..feature(
                            "radius² seen from across the world",
                            r * r,
                            discriminant_error(methods.sphere, r, world + from_eye),
                        )
                    };
                    [
                        Some(feature(
                            "radius² seen from the eye",
                            r * r,
                            discriminant_error(methods.sphere, r, from_eye),
                        )),
                        Some(across_world),
                        Some(feature(
                            "radius, against the surface tolerance",
                            r,
                            tolerance_terms(from_eye + r, Some(r)),
                        )),
                        Some(clearance(gap, from_eye + r, Some(r))),
                    ]
                }
                ShapeDesc::Plane { checker, .. } => [
                    checker.map(|checker| {
                        let size = f64::from(checker.size);
                        feature(
                            "checker square size",
                            size,
                            [(1.0, world), (1.0, size), (0.0, 0.0), (0.0, 0.0)],
                        )
                    }),
                    Some(clearance(gap, gap, None)),
                    None,
                    None,
                ],
                ShapeDesc::Triangle { vertices } => {
                    // The tests' determinants are twice the area seen along the ray; their
                    // numerators err by the rounding of the unit direction times |s|·|e|, with s the
                    // way from the ray's origin to a corner and e the longest edge.
                    let corners = vertices.map(Vec3::from_f32);
                    let (e1, e2) = (corners[1] - corners[0], corners[2] - corners[0]);
                    let s = world + distance(vertices[0], eye);
                    let longest = e1.length().max(e2.length());
                    let area = e1.cross(e2).length();
                    [
                        Some(feature(
                            "twice the triangle's area",
                            area,
                            [(s * longest, 1.0), (1.0, area), (0.0, 0.0), (0.0, 0.0)],
                        )),
                        Some(clearance(gap, gap, None)),
                        None,
                        None,
                    ]
                }
            }
            .into_iter()
            .flatten()
        });
    // A light multiplies the rounding of a cosine (Lambert's, a highlight's) by its intensity:
    // that must stay below one level of a display channel.
    let lights = desc.lights.iter().enumerate().map(move |(i, light)| {
        let intensity = light.colour.iter().copied().fold(0.0_f32, f32::max);
        Feature {
            item: Item::Light(i),
            quantity: "one display level against the light's intensity times a rounded cosine",
            value: LEVEL,
            terms: [
                (f64::from(intensity), 1.0),
                (0.0, 0.0),
                (0.0, 0.0),
                (0.0, 0.0),
            ],
            steps: 1.0,
        }
    });
    objects.chain(lights)
}

/// The error of a sphere's discriminant, for a ray whose origin is `f` from the centre.
///
/// The discriminant is r² less a rounded difference. The quadratic's, b² − c, errs by f² times
/// the error in |d|² (it takes a = |d|² as 1, and c = |f|² − r²), by f times half a step at f
/// (b rounded, then squared) and by r²'s own rounding; the stable form's, r² − |f + b·d|², by
/// 2r·f times the error in |d|², 2r times half a step at f, and r²'s rounding.
fn discriminant_error(method: SphereMethod, r: f64, f: f64) -> Terms {
    match method {
        SphereMethod::Quadratic => [
            (f * f * DIRECTION_LENGTH, 1.0),
            (f, f),
            (1.0, r * r),
            (0.0, 0.0),
        ],
        SphereMethod::Stable => [
            (2.0 * r * f * DIRECTION_LENGTH, 1.0),
            (2.0 * r, f),
            (1.0, r * r),
            (0.0, 0.0),
        ],
    }
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

/// How far the eye is from the nearest point of `object`'s surface.
#[must_use]
pub fn clearance(desc: &SceneDesc<'_>, object: &ObjectDesc) -> f64 {
    let eye = Vec3::from_f32(desc.camera.eye);
    match object.shape {
        ShapeDesc::Sphere { center, radius } => {
            ((Vec3::from_f32(center) - eye).length() - f64::from(radius)).abs()
        }
        ShapeDesc::Plane { point, normal, .. } => Vec3::from_f32(normal)
            .direction()
            .map_or(0.0, |n| n.dot(eye - Vec3::from_f32(point)).abs()),
        ShapeDesc::Triangle { vertices } => distance_to_triangle(eye, vertices.map(Vec3::from_f32)),
    }
}

/// The distance from `p` to the nearest point of the triangle `[a, b, c]` (Ericson, Real-Time
/// Collision Detection, 5.1.5: which corner, edge or the face that point lies on).
fn distance_to_triangle(p: Vec3<f64>, [a, b, c]: [Vec3<f64>; 3]) -> f64 {
    let (ab, ac) = (b - a, c - a);
    let (d1, d2) = (ab.dot(p - a), ac.dot(p - a));
    let (d3, d4) = (ab.dot(p - b), ac.dot(p - b));
    let (d5, d6) = (ab.dot(p - c), ac.dot(p - c));
    let (va, vb, vc) = (d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2);
    let nearest = if d1 <= 0.0 && d2 <= 0.0 {
        a
    } else if d3 >= 0.0 && d4 <= d3 {
        b
    } else if d6 >= 0.0 && d5 <= d6 {
        c
    } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        a.add_scaled(ab, d1 / (d1 - d3))
    } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        a.add_scaled(ac, d2 / (d2 - d6))
    } else if va <= 0.0 && d4 >= d3 && d5 >= d6 {
        b.add_scaled(c - b, (d4 - d3) / ((d4 - d3) + (d5 - d6)))
    } else {
        let sum = va + vb + vc;
        a.add_scaled(ab, vb / sum).add_scaled(ac, vc / sum)
    };
    (p - nearest).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_distance_to_a_triangle_is_to_its_face_edge_or_corner() {
        let corners = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(0.0, 4.0, 0.0),
        ];
        let cases = [
            // Above the face, beside an edge, beyond a corner, in the plane inside.
            (Vec3::new(1.0, 1.0, 3.0), 3.0),
            (Vec3::new(2.0, -2.0, 0.0), 2.0),
            (Vec3::new(7.0, -4.0, 0.0), 5.0),
            (Vec3::new(1.0, 1.0, 0.0), 0.0),
            (Vec3::new(3.0, 3.0, 0.0), 2.0_f64.sqrt()),
        ];
        for (p, want) in cases {
            let got = distance_to_triangle(p, corners);
            assert!((got - want).abs() < 1e-12, "{p:?}: {got} ≠ {want}");
        }
    }
}
