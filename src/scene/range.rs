//! The range proof: a bound on the magnitude of every value the tracer forms for a scene, by
//! the chosen [`Methods`], and the smallest feature each computation must resolve. A format
//! holds a scene when every bound fits its range and every feature spans enough of its steps.
//!
//! # What the bounds rest on
//!
//! Positions are relative to the eye. Validation puts every sphere (centre plus radius),
//! triangle corner and light (an area light's centre plus its radius) within the world radius
//! R = `far`, and every plane within R of the eye; the tracer then keeps every value within
//! these:
//!
//! - **Ray origins** are the eye, points of its lens (within the aperture A of it, which
//!   validation keeps below every surface's distance from the eye and below R), or points on
//!   surfaces, moved off them by the surface tolerance τ. A sphere's surface point is c + r·n, within |c| + r ≤ R; a triangle's is
//!   a + u·e1 + v·e2 with u, v, u + v in [0, 1], a convex combination of its corners; a plane's
//!   is a hit that passed the world test (within the disc of radius ρ = √(R² − h²) the world
//!   cuts from a plane h from the eye, about the eye's foot on it: |p| ≤ R) projected onto the
//!   plane, which moves it by the rounding of its t. So |o| ≤ O = R + s, the slack s ([`origin_slack`]) being τ and the
//!   rounding of a surface point.
//! - **Directions** are unit vectors to within a few steps (unit vectors are correctly
//!   rounded; a mirror direction keeps the length of the incoming one; a refracted direction
//!   has unit length by construction), and hits lie within t < T = 2O, the diameter of the
//!   ball rays start in ([`ray_length`]: longer than any way from an origin to a surface).
//!   So a point along a ray, o + t·d, is within P = O + T.
//! - **Weights** (diffuse, specular, reflection, transmission) are in [0, 1] with reflection +
//!   transmission ≤ 1, so each level of a ray tree carries at most weight 1 in all.
//!
//! # Every operation, and the bound that holds it
//!
//! | where | what | bound |
//! |---|---|---|
//! | camera | image-plane points, their normalisation | \|s\|² of an image corner ([`crate::Scene::camera`]), with a lens the corner plus the lens's tilt A/f |
//! | lens | a lens point A·(a·right + b·up), its tilt (A/f)·(a·right + b·up) | within A ≤ R and A/f, a² + b² ≤ 1 |
//! | every shape | o + t·d, o − (corner or centre) and their sums | [`magnitudes`]: a point along a ray, P |
//! | plane | n·d·t for t in the span, offset − n·o | a ray's length T, and P |
//! | plane, row pass | n·p over the row's n·s, tested against min·(n·s) and (T/2)·(n·s) first; t·s | t ≤ T/2 and each coordinate of s within 3 (rows reaching further trace in general, [`crate::row_pass`]): within 3T/2 = P |
//! | plane | the world test | a hit less the eye's foot, P + R; each coordinate tested against ρ, then scaled within 1 by a power of two near 1/ρ, which must fit |
//! | plane | checker coordinates (p − corner)·axis/size | a checker coordinate |
//! | sphere, quadratic | o − c, b = d·(o − c), \|o − c\|², b², b² − c | b² − c: (\|o\| + \|c\|)² + r² |
//! | sphere, stable | f = o − c, \|f\|², f + b·d, \|f + b·d\|², r² − that | \|f\|² ≤ (\|o\| + \|c\|)² |
//! | sphere | −b ± √Δ, b ± √Δ | the sphere's roots, \|b\| + √(b² + r²) |
//! | sphere | p − c for the normal; c + r·n | a hit point less the centre, P + \|c\| |
//! | triangle, Cramer | e1 × e2, det[−d s e2], det[−d e1 s], s·(e1 × e2) | Cramer's determinants |
//! | triangle, Möller–Trumbore | d × e2, s × e1, their dot products; each times 1/det | its numerators; 1/det is cut off where it, or a numerator over it, would leave the format |
//! | triangle, watertight | sheared corners, edge functions, their sum | the watertight edge functions |
//! | triangle | a + u·e1 + v·e2 | a convex combination of the corners: O |
//! | shading | cosines, mirror direction d + 2(cos)·n, Phong's power of a cosine clamped to 1 | at most 3: a direction's reflection |
//! | shading | the light's direction and distance | normalised from \|L − o\| ≤ R + O in the wide integer: no square forms |
//! | area light | two unit vectors across the light's direction: 1/(1 + \|l_z\|) and products of unit coordinates | within 2 |
//! | area light | a point of its disc, L + r·a·u + r·b·v with a² + b² ≤ 1 | within \|L\| + r ≤ R, as a light, but for the 16-bit rounding of a and b and the rounding of u and v: a few steps, within the headroom; its direction and distance as a light's |
//! | area light | the shadow rays' transmittances, summed in 16-bit fractions | integers: at most [`MAX_SAMPLES`](crate::pattern::MAX_SAMPLES) · 2¹⁶ < 2³² (const-asserted) |
//! | refraction | (d + cos·n)·η, its squared length | η² in Snell's law |
//! | colour | each level's ambient, Lambert, Phong times the light, times its weight; the sum | a pixel's sum of colours over its ray tree |
//! | narrow | unit vectors narrowed for shading's cosines, the cosines, surface colours, material weights, Lambert's and Phong's factors, a shadow's transmittance, the weights along the ray tree, their products and the sum reflection + transmission | within 1, a cosine a few steps beyond: 1.0625 at most, within every narrow format's 2 (const-asserted) |
//! | narrow | light times a narrow number: the ambient and each light filtered by a surface, a sky's rise by its cosine, a ray's colour by its weight | no larger than the light: within a pixel's sum of colours |
//! | quotients, roots | every division and root | total: they saturate (fixed point) or reach infinity (floats) |

crate::phase::declare_phase!(Some(crate::phase::Phase::Build));

use super::SURFACE_TOLERANCE_STEPS;
use super::error::{Item, Remedy, SceneError};
use crate::desc::{BackgroundDesc, ObjectDesc, SceneDesc, ShapeDesc};
use crate::methods::{MethodName, Methods, RootMethod, SphereMethod, TriangleMethod};
use crate::scalar::FAST_ROOT_ERROR;
use crate::scalar::{FormatInfo, FormatSet, Fx, Precision, Scalar};
use crate::shape::CHECKER_PERIOD;
use crate::vec3::Vec3;

/// A feature must span this many steps of the error its computation makes, or rounding would
/// change its shape visibly.
pub const MIN_FEATURE_STEPS: f64 = 16.0;

/// Extra room every magnitude must leave in the format's range, for rounding.
pub const RANGE_HEADROOM: f64 = 1.01;

/// The errors a light must be from a surface for its shadow rays to tell which side of it the
/// light is on: a decision, not a shape, so fewer than [`MIN_FEATURE_STEPS`].
pub(crate) const SIDE_STEPS: f64 = 2.0;

/// The steps between neighbouring pixels' rays a format must resolve: at fewer, neighbouring
/// pixels would see along one ray.
pub(crate) const MIN_PIXEL_STEPS: f64 = 2.0;

/// The largest magnitude one computation reaches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Magnitude {
    /// Whose computation.
    pub item: Item,
    /// What is computed.
    pub quantity: &'static str,
    /// Its largest magnitude in this scene.
    pub value: f64,
    /// What to change to make it smaller.
    pub remedy: Remedy,
}

/// A small quantity a computation must resolve against the rounding error it makes.
///
/// The error is a sum of terms, each a coefficient times the format's resolution at some
/// magnitude ([`crate::scalar::Precision::resolution`]): for a fixed format a multiple of its LSB, for a float a
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
    /// What to change to make it resolvable.
    pub remedy: Remedy,
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
        self.minimum_with(&FormatInfo::of::<S>())
    }

    /// The smallest value `format` resolves here.
    #[must_use]
    pub fn minimum_with(&self, format: &FormatInfo) -> f64 {
        self.steps * error_with(&self.terms, format)
    }
}

/// What one term of an error is a multiple of.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// The format's resolution at this magnitude ([`crate::scalar::Precision::resolution`]): the rounding of a
    /// number that large.
    At(f64),
    /// The error of a unit vector's coordinates ([`crate::scalar::Precision::UNIT_ERROR`]): a direction's
    /// rounding, and a cosine's.
    Unit,
}

/// An error as a sum of terms, each a coefficient times a [`Scale`] of the format's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Terms {
    terms: [(f64, Scale); Terms::CAPACITY],
    len: usize,
}

impl Terms {
    /// The most terms an error has here.
    pub const CAPACITY: usize = 12;

    /// The error of these terms, each (coefficient, magnitude) a multiple of the resolution at
    /// the magnitude (at most [`Self::CAPACITY`] in all; more are a bug, and dropped).
    #[must_use]
    pub fn new(terms: &[(f64, f64)]) -> Self {
        let mut all = Self {
            terms: [(0.0, Scale::Unit); Self::CAPACITY],
            len: 0,
        };
        for &(coefficient, magnitude) in terms {
            all.push((coefficient, Scale::At(magnitude)));
        }
        all
    }

    /// This error plus `coefficient` unit vector errors.
    #[must_use]
    pub fn units(mut self, coefficient: f64) -> Self {
        self.push((coefficient, Scale::Unit));
        self
    }

    fn push(&mut self, term: (f64, Scale)) {
        debug_assert!(self.len < Self::CAPACITY, "an error of too many terms");
        if let Some(slot) = self.terms.get_mut(self.len) {
            *slot = term;
            self.len += 1;
        }
    }

    /// This error and `other` together.
    #[must_use]
    pub fn plus(mut self, other: Self) -> Self {
        for term in other.iter() {
            self.push(term);
        }
        self
    }

    /// This error times `factor`.
    #[must_use]
    pub fn times(mut self, factor: f64) -> Self {
        for (coefficient, _) in &mut self.terms {
            *coefficient *= factor;
        }
        self
    }

    /// The terms, as (coefficient, scale).
    pub fn iter(&self) -> impl Iterator<Item = (f64, Scale)> + '_ {
        self.terms.iter().take(self.len).copied()
    }
}

/// The size of the error `terms` describe in format `S`.
#[must_use]
pub(crate) fn error<S: Scalar>(terms: &Terms) -> f64 {
    error_with(terms, &FormatInfo::of::<S>())
}

/// The size of the error `terms` describe in `format`.
#[must_use]
pub(crate) fn error_with(terms: &Terms, format: &FormatInfo) -> f64 {
    terms
        .iter()
        .map(|(coefficient, scale)| {
            coefficient
                * match scale {
                    Scale::At(magnitude) => (format.resolution)(magnitude),
                    Scale::Unit => format.unit_error,
                }
        })
        .sum()
}

/// The surface tolerance ([`SURFACE_TOLERANCE_STEPS`]) at a surface point whose largest
/// coordinate is at most `reach` (relative to the eye), on a sphere of `radius` or a sheet.
#[must_use]
pub(crate) fn tolerance_terms(reach: f64, radius: Option<f64>) -> Terms {
    let sheet =
        Terms::new(&[(SURFACE_TOLERANCE_STEPS, 0.0)]).units(SURFACE_TOLERANCE_STEPS * reach);
    radius.map_or(sheet, |r| sheet.plus(own_tolerance_terms(r)))
}

/// A sphere's own part of the surface tolerance ([`super::Object::tolerance`]): the rounding
/// of a point `radius` from its centre, and the error of the root its test finds for a ray
/// that starts on it, c/2r with c rounded at r².
#[must_use]
pub(crate) fn own_tolerance_terms(radius: f64) -> Terms {
    Terms::new(&[(SURFACE_TOLERANCE_STEPS / radius, radius * radius)])
        .units(SURFACE_TOLERANCE_STEPS * radius)
}

/// A triangle's own part of the surface tolerance ([`super::Object::tolerance`]): a ray that
/// starts on it finds it again at a distance of about s·(e1 × e2) / (d·(e1 × e2)), with s the
/// origin less a corner. The numerator rounds with s, which is formed at the corners' distance
/// from the eye (`reach`: the error the sheet tolerance counts is the point's, at its own
/// distance); with e1 × e2, at the square of the longest edge L, times |s| ≤ L; and as a triple
/// product, at L³; the denominator is twice the area A, seen along the ray.
#[must_use]
pub(crate) fn triangle_tolerance_terms(vertices: [[f32; 3]; 3], eye: Vec3<f64>) -> Terms {
    let corners = vertices.map(Vec3::from_f32);
    let [a, b, c] = corners;
    let (e1, e2) = (b - a, c - a);
    let longest = e1.length().max(e2.length()).max((c - b).length());
    let area = e1.cross(e2).length();
    let reach = corners
        .iter()
        .map(|&v| (v - eye).length())
        .fold(0.0, f64::max);
    Terms::new(&[
        (SURFACE_TOLERANCE_STEPS, reach),
        (SURFACE_TOLERANCE_STEPS * longest / area, longest * longest),
        (SURFACE_TOLERANCE_STEPS / area, longest * longest * longest),
    ])
}

/// The error in |d|² of a unit direction, in resolutions at 1: each coordinate is rounded.
const DIRECTION_LENGTH: f64 = 2.0;

/// How much larger a miss across the focal plane is than one coordinate's error: its two
/// coordinates err independently.
const MISS_ACROSS_PLANE: f64 = core::f64::consts::SQRT_2;

/// The roundings in each coordinate of a lens point a·(A·right) + b·(A·up): the two axes
/// stored at the aperture's size, their two products, their sum (counted as four: the axes'
/// roundings are scaled by |a|, |b| ≤ 1 together).
const LENS_POINT_ROUNDINGS: f64 = 4.0;

/// One 8-bit level of a display channel: the least change of colour that can show.
const LEVEL: f64 = 1.0 / 255.0;

/// The largest component of a mirror direction d + 2(cos θ)·n of unit d and n.
const MIRROR: f64 = 3.0;

/// The largest a smooth mesh's interpolated normal is before it is normalised: 1 + 2 + 2.
const SMOOTH_NORMAL: f64 = 5.0;

/// The largest number the tracer keeps in a narrow format ([`crate::Scalar::Narrow`]): a
/// cosine of two unit vectors, 1 plus the rounding of their coordinates (a few steps of the
/// coarsest format's 2⁻⁸, far within this); a colour, a weight, or a product of them, at most
/// 1. Every narrow format's range is 2, less a step: 2.14's, the coarser, is the bound.
const NARROW: f64 = 1.0625;

const _: () = assert!(
    NARROW * RANGE_HEADROOM < <Fx<fixed::types::I2F14> as Precision>::RANGE,
    "the narrow numbers fit the narrow formats"
);

/// How far beyond the world's radius a ray can start in `format` (see the module
/// documentation): the largest surface tolerance (a sphere's or a triangle's own part at its
/// largest), the rounding of a surface point, and with fast roots the error of the quotient
/// that places a plane's hit.
#[must_use]
pub fn origin_slack(desc: &SceneDesc<'_>, methods: &Methods, format: &FormatInfo) -> f64 {
    let world = f64::from(desc.far);
    let smallest_radius = desc
        .primitives()
        .filter_map(|(_, object)| match object.shape {
            ShapeDesc::Sphere { radius, .. } => Some(f64::from(radius)),
            _ => None,
        })
        .fold(None, |smallest: Option<f64>, r| {
            Some(smallest.map_or(r, |s| s.min(r)))
        });
    // The own tolerance is largest for the smallest sphere, its rounding for the largest; both
    // terms are bounded by taking each at its worst.
    let tolerance = error_with(&tolerance_terms(world, None), format)
        + smallest_radius.map_or(0.0, |r| {
            error_with(&own_tolerance_terms(r), format)
                + SURFACE_TOLERANCE_STEPS * world * format.unit_error
        })
        + desc
            .primitives()
            .filter_map(|(_, object)| match object.shape {
                ShapeDesc::Triangle { vertices } => Some(error_with(
                    &triangle_tolerance_terms(vertices, Vec3::from_f32(desc.camera.eye)),
                    format,
                )),
                _ => None,
            })
            .fold(0.0, f64::max);
    let rounding = SURFACE_TOLERANCE_STEPS * (format.resolution)(3.0 * world);
    let quotient = if format.fast_roots && methods.roots == RootMethod::Approx {
        2.0 * world * FAST_ROOT_ERROR
    } else {
        0.0
    };
    tolerance + rounding + quotient
}

/// The largest magnitude of a mesh's box test ([`crate::shape::mesh`]) in a world of radius `world`
/// whose rays start up to `slack` beyond it: a ray's midpoint up to its length's half from its
/// origin, 2(R + s) from the eye, less a box's centre, whose coordinates validation keeps
/// within R (√3·R); the products of that with a unit direction are no larger.
#[must_use]
pub fn box_magnitude(world: f64, slack: f64) -> f64 {
    ray_length(world, slack) + 3.0_f64.sqrt() * world
}

/// The longest a ray is followed in a world of radius `world` whose rays start up to `slack`
/// beyond it ([`origin_slack`]): the diameter of the ball they start in, 2(R + s). A surface
/// lies within R of the eye (to within its rounding, which the slack exceeds), so that a ray
/// finds it however far across the world it is (a mirror sphere about the eye sends its rays
/// exactly 2R across).
#[must_use]
pub fn ray_length(world: f64, slack: f64) -> f64 {
    2.0 * (world + slack)
}

/// Every magnitude of the scene's computations by `methods`, for rays that start within
/// `slack` beyond the world ([`origin_slack`]); the description must have passed validation.
/// See the module documentation for what each bounds.
pub fn magnitudes<'a>(
    desc: &'a SceneDesc<'a>,
    methods: &'a Methods,
    slack: f64,
) -> impl Iterator<Item = Magnitude> + 'a {
    let world = f64::from(desc.far);
    let eye = desc.camera.eye;
    let aperture = f64::from(desc.camera.aperture);
    let origin = world + slack;
    let length = ray_length(world, slack);
    let along = origin + length;
    let scene = |quantity, value, remedy| Magnitude {
        item: Item::Scene,
        quantity,
        value,
        remedy,
    };
    let global = [
        scene(
            "a ray's length (the world's diameter and its slack)",
            length,
            Remedy::ShrinkWorld,
        ),
        scene("a point along a ray, o + t·d", along, Remedy::ShrinkWorld),
        scene(
            "a direction's reflection, d + 2(cos θ)·n",
            MIRROR,
            Remedy::ShrinkWorld,
        ),
        scene(
            "a pixel's sum of colours over its ray tree",
            colour_sum(desc),
            Remedy::LessLight,
        ),
    ];
    let has_meshes = desc
        .objects
        .iter()
        .any(|object| matches!(object.shape, ShapeDesc::Mesh { .. }));
    let meshes = has_meshes.then(|| {
        scene(
            "a ray's midpoint less a mesh's box's centre",
            box_magnitude(world, slack),
            Remedy::ShrinkWorld,
        )
    });
    let smooth = (has_meshes && !desc.meshes.normals.is_empty()).then(|| {
        scene(
            "a smooth mesh's normal, n₀ + u·(n₁ − n₀) + v·(n₂ − n₀)",
            SMOOTH_NORMAL,
            Remedy::ShrinkWorld,
        )
    });
    let objects = desc.primitives().flat_map(move |(i, object)| {
        let item = Item::Object(i);
        let shape: [Option<(&'static str, f64, Remedy)>; 3] = match object.shape {
            ShapeDesc::Sphere { center, radius } => {
                let (c, r) = (distance(center, eye), f64::from(radius));
                let f = origin + c;
                let square = match methods.sphere {
                    SphereMethod::Quadratic => ("b² − c in the quadratic", f * f + r * r),
                    SphereMethod::Stable => ("|o − c|² in the stable form", f * f),
                };
                [
                    Some((square.0, square.1, Remedy::ShrinkWorld)),
                    Some((
                        "the sphere's roots, |b| + √(b² + r²)",
                        f + (f * f + r * r).sqrt(),
                        Remedy::ShrinkWorld,
                    )),
                    Some((
                        "a hit point less the sphere's centre",
                        along + c,
                        Remedy::ShrinkWorld,
                    )),
                ]
            }
            ShapeDesc::Plane { checker, .. } => [
                Some((
                    "a hit less the eye's foot on the plane",
                    along + world,
                    Remedy::ShrinkWorld,
                )),
                checker.map(|checker| {
                    let size = f64::from(checker.size);
                    (
                        "a checker coordinate",
                        checker_reach(origin, world) / size + CHECKER_PERIOD,
                        Remedy::LargerSquares,
                    )
                }),
                None,
            ],
            // Its triangles are bounded one by one ([`SceneDesc::primitives`]).
            ShapeDesc::Mesh { .. } => [None, None, None],
            ShapeDesc::Triangle { vertices } => {
                let corners = vertices.map(Vec3::from_f32);
                let eye = Vec3::from_f32(eye);
                let (quantity, value) = triangle_magnitude(methods.triangle, origin, eye, corners);
                // Möller–Trumbore takes a determinant below numerators/range (or
                // 1/range, where 1/det itself would not fit) for a ray parallel to the
                // triangle: the primary rays' must stay above it, or it misses a
                // triangle it faces.
                let seen = (methods.triangle == TriangleMethod::MollerTrumbore)
                    .then(|| smallest_determinant(eye, aperture, corners))
                    .flatten()
                    .map(|det| {
                        (
                            "Möller–Trumbore's numerators (or 1) over a primary ray's \
                                     determinant",
                            reciprocal_multiples(origin, eye, corners) / det,
                            Remedy::LargerTriangle,
                        )
                    });
                [Some((quantity, value, Remedy::ShrinkWorld)), seen, None]
            }
        };
        let refraction = (object.material.transmission > 0.0).then(|| {
            let ior = f64::from(object.material.ior);
            ("η² in Snell's law", ior * ior + 1.0, Remedy::LowerIor)
        });
        shape
            .into_iter()
            .chain([refraction])
            .flatten()
            .map(move |(quantity, value, remedy)| Magnitude {
                item,
                quantity,
                value,
                remedy,
            })
    });
    global
        .into_iter()
        .chain(meshes)
        .chain(smooth)
        .chain(objects)
}

/// The farthest a point of a plane's surface is from its checkerboard's origin: the point
/// within `origin` of the eye, the origin (the eye's foot on the plane) within the world.
fn checker_reach(origin: f64, world: f64) -> f64 {
    origin + world
}

/// The largest numerator of Cramer's rule and of Möller–Trumbore, with |s| = |o − a| at most
/// `origin` + |a|: det[s e1 e2] ≤ |s||e1||e2|, the cross products with s at most |s|·|e|, and
/// e1 × e2 at most |e1||e2|.
pub(crate) fn triangle_numerators(origin: f64, eye: Vec3<f64>, [a, b, c]: [Vec3<f64>; 3]) -> f64 {
    let (e1, e2) = ((b - a).length(), (c - a).length());
    let s = origin + (a - eye).length();
    (s * e1 * e2).max(s * e1.max(e2)).max(e1 * e2)
}

/// What Möller–Trumbore's 1/det is multiplied by at most: its numerators
/// ([`triangle_numerators`]), or 1 where they are smaller, for 1/det itself must fit the
/// format. A determinant below this over the format's range is taken for a parallel ray.
pub(crate) fn reciprocal_multiples(origin: f64, eye: Vec3<f64>, corners: [Vec3<f64>; 3]) -> f64 {
    triangle_numerators(origin, eye, corners).max(1.0)
}

/// The smallest |det| = |d·(e1 × e2)| of a unit ray from the eye, or from a point of its lens
/// within `aperture` of it, that meets the triangle: |e1 × e2| times the cosine at its
/// farthest corner, h/|v − o| with h the origin's distance from the triangle's plane (at least
/// the eye's less the aperture); `None` where the eye is in that plane (no primary ray meets
/// it), 0 where only its lens reaches the plane (its points near the plane see the triangle
/// edge-on).
fn smallest_determinant(eye: Vec3<f64>, aperture: f64, [a, b, c]: [Vec3<f64>; 3]) -> Option<f64> {
    let cross = (b - a).cross(c - a);
    let area = cross.length();
    let from_eye = (cross.dot(a - eye) / area).abs();
    let h = (from_eye - aperture).max(0.0);
    let farthest = [a, b, c]
        .iter()
        .map(|&v| (v - eye).length() + aperture)
        .fold(0.0, f64::max);
    (from_eye > 0.0 && area > 0.0).then(|| area * h / farthest)
}

fn triangle_magnitude(
    method: TriangleMethod,
    origin: f64,
    eye: Vec3<f64>,
    corners: [Vec3<f64>; 3],
) -> (&'static str, f64) {
    match method {
        TriangleMethod::Cramer => (
            "Cramer's determinants",
            triangle_numerators(origin, eye, corners),
        ),
        TriangleMethod::MollerTrumbore => (
            "Möller–Trumbore's numerators",
            triangle_numerators(origin, eye, corners),
        ),
        TriangleMethod::Watertight => {
            // Sheared corners are at most √2·M from the origin (|Sx|, |Sy| ≤ 1), with M the
            // farthest corner from a ray origin; each edge function is a difference of two
            // products of them, and the determinant the sum of three.
            let far = corners
                .iter()
                .map(|&p| origin + (p - eye).length())
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
        BackgroundDesc::Gradient {
            horizon, zenith, ..
        } => f64::from(brightest(horizon)) + f64::from(brightest(zenith)),
    };
    (f64::from(desc.max_depth) + 1.0) * local.max(background)
}

/// The error with which a ray from `from` away finds the surface of `object` by `methods`:
/// the surface tolerance there, and the error of the distance along the ray its test finds —
/// for a sphere the discriminant's error over 2r, for a triangle its determinant's error
/// relative to the determinant (from its stored edges' rounding, and for Möller–Trumbore the
/// rounding of 1/det), times the way the ray has come. A point (the eye, a light) nearer the
/// surface than this is on either side of it at random.
fn locating(shape: &ShapeDesc, methods: &Methods, from: f64, eye: [f32; 3]) -> Terms {
    match *shape {
        ShapeDesc::Sphere { radius, .. } => {
            let r = f64::from(radius);
            tolerance_terms(from, Some(r))
                .plus(discriminant_error(methods.sphere, r, from + r).times(0.5 / r))
        }
        // Its triangles are located one by one ([`SceneDesc::primitives`]).
        ShapeDesc::Plane { .. } | ShapeDesc::Mesh { .. } => tolerance_terms(from, None),
        ShapeDesc::Triangle { vertices } => {
            let [a, b, c] = vertices.map(Vec3::from_f32);
            let (e1, e2) = (b - a, c - a);
            let longest = e1.length().max(e2.length());
            let area = e1.cross(e2).length();
            let determinant =
                area_error(methods.triangle, from + longest, longest, area).times(from / area);
            let reciprocal = if methods.triangle == TriangleMethod::MollerTrumbore {
                Terms::new(&[(from * area, 1.0 / area)])
            } else {
                Terms::new(&[])
            };
            tolerance_terms(from, None)
                .plus(triangle_tolerance_terms(vertices, Vec3::from_f32(eye)))
                .plus(determinant)
                .plus(reciprocal)
        }
    }
}

/// The error with which a ray from the eye, or from a point up to `beyond` farther from the
/// shape, finds `shape` by `methods` ([`locating`], at the shape's far side), and the rounding
/// of its description into the format: how far outside the described shape such a ray (a
/// primary ray, for `beyond` 0) may be judged to meet it; `None` where no such bound holds. Möller–Trumbore multiplies by 1/det rounded, which in a coarse format
/// can make a ray meet a small triangle pixels away from it (the fuzzer found rays in `i10f22`
/// meeting a triangle two hundredths of a unit across two pixels of a five-pixel-wide image
/// beyond its edge): beyond what the error model bounds.
pub(crate) fn finding_error<S: Scalar>(
    shape: &ShapeDesc,
    methods: &Methods,
    eye: [f32; 3],
    beyond: f64,
) -> Option<f64> {
    let reach = beyond
        + match *shape {
            ShapeDesc::Sphere { center, radius } => distance(center, eye) + f64::from(radius),
            ShapeDesc::Plane { point, .. } => distance(point, eye),
            // A mesh's is its triangles' largest, which its scene build takes.
            ShapeDesc::Mesh { .. } => return None,
            ShapeDesc::Triangle { .. } if methods.triangle == TriangleMethod::MollerTrumbore => {
                return None;
            }
            ShapeDesc::Triangle { vertices } => vertices
                .iter()
                .map(|&corner| distance(corner, eye))
                .fold(0.0, f64::max),
        };
    let rounding = Terms::new(&[(2.0, reach)]);
    Some(error::<S>(
        &locating(shape, methods, reach, eye).plus(rounding),
    ))
}

/// The error of a triangle's determinant (twice its area seen along a ray) and of its
/// barycentric numerators by `method`, for a ray `s` from its corner: the rounding of the unit
/// direction times |s|·|e| with e the longest edge, the area's own rounding, and the rounding
/// of the numerators' products. Cramer's rule rounds s × e's products and their dot product
/// with d, each as large as |s|·|e| (2√3 + 3 roundings); Möller–Trumbore rounds d × e at its
/// size and multiplies it by s (2√3·|s| of them), then rounds the dot product's (3). Watertight
/// tests the signs of its edge functions exactly.
fn area_error(method: TriangleMethod, s: f64, longest: f64, area: f64) -> Terms {
    const SQRT_3: f64 = 1.732_050_807_568_877_2;
    const CROSS_AND_DOT: f64 = 2.0 * SQRT_3 + 3.0;
    let numerators = match method {
        TriangleMethod::Cramer => Terms::new(&[(CROSS_AND_DOT, s * longest)]),
        TriangleMethod::MollerTrumbore => {
            Terms::new(&[(2.0 * SQRT_3 * s, longest), (3.0, s * longest)])
        }
        TriangleMethod::Watertight => Terms::new(&[]),
    };
    Terms::new(&[(1.0, area)])
        .units(s * longest)
        .plus(numerators)
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
    let objects = desc.primitives().flat_map(move |(i, object)| {
        // Built when asked for, one at a time, so that the iterator holds no array of
        // features: on a microcontroller a scene is built on the stack the tracer needs.
        (0..OBJECT_FEATURES).filter_map(move |k| {
            object_features(desc, methods, i, &object)
                .into_iter()
                .nth(k)
                .flatten()
        })
    });
    let lights = desc.lights.iter().enumerate().flat_map(move |(i, light)| {
        let item = Item::Light(i);
        let intensity = light.colour.iter().copied().fold(0.0_f32, f32::max);
        // A light multiplies the rounding of a cosine (Lambert's, a highlight's) by its
        // intensity: that must stay below one level of a display channel.
        let level = Feature {
            item,
            quantity: "one display level against the light's intensity times a rounded cosine",
            value: LEVEL,
            terms: Terms::new(&[]).units(f64::from(intensity)),
            steps: 1.0,
            remedy: Remedy::DimLight,
        };
        // A shadow ray starts a tolerance off its surface and looks for occluders between
        // there and the light, from anywhere in the world: a light nearer a surface than such a
        // ray can tell is on either side of it at random. For an area light, that is every
        // point within its radius.
        let position = Vec3::from_f32(light.position);
        let reach = world + distance(light.position, eye) + f64::from(light.radius);
        let clear = desc.primitives().map(move |(_, object)| Feature {
            item,
            quantity: "its distance from a surface (less its radius), against the error with \
                       which a shadow ray finds the surface",
            value: clearance(&object, position) - f64::from(light.radius),
            terms: locating(&object.shape, methods, reach, eye),
            steps: SIDE_STEPS,
            remedy: Remedy::MoveLight,
        });
        core::iter::once(level).chain(clear)
    });
    // A lens ray starts from its lens point rounded at the aperture's size, and so meets the
    // focal plane that far off where it should: its three products and their sum, a vector
    // across the plane, must stay within a sixteenth of the aperture, as its tilt's error does
    // ([`camera`]).
    let aperture = f64::from(desc.camera.aperture);
    let lens = (aperture > 0.0).then(|| Feature {
        item: Item::Camera,
        quantity: "aperture, the lens's radius, against the rounding of a point of the lens",
        value: aperture,
        terms: Terms::new(&[(LENS_POINT_ROUNDINGS, aperture)]).times(MISS_ACROSS_PLANE),
        steps: MIN_FEATURE_STEPS,
        remedy: Remedy::WiderAperture,
    });
    objects.chain(lights).chain(lens)
}

/// How many features [`object_features`] gives an object at most.
pub const OBJECT_FEATURES: usize = 4;

/// The features of object `i` of `desc`, by `methods` (see [`features`]): `object` is the
/// object itself, or one of a mesh's triangles ([`SceneDesc::primitives`]).
#[must_use]
pub fn object_features(
    desc: &SceneDesc<'_>,
    methods: &Methods,
    i: usize,
    object: &ObjectDesc,
) -> [Option<Feature>; OBJECT_FEATURES] {
    let world = f64::from(desc.far);
    let eye = desc.camera.eye;
    // A lens starts primary rays up to its aperture from the eye: nearer a surface, farther
    // from a sphere's far side.
    let aperture = f64::from(desc.camera.aperture);
    let item = Item::Object(i);
    let feature = |quantity, value, terms, remedy| Feature {
        item,
        quantity,
        value,
        terms,
        steps: MIN_FEATURE_STEPS,
        remedy,
    };
    // The surface tolerance is a dead zone in front of every surface: the eye (and all its
    // lens) must stand well clear of it, or the tolerance bends every ray it sends there. The
    // surface's own coordinates, rounded at their size, place it only so precisely.
    let gap = clearance(object, Vec3::from_f32(eye));
    let clearance = |reach: f64| {
        feature(
            "the eye's distance from its surface (less the aperture), against the error with \
             which a ray from the eye finds the surface",
            gap - aperture,
            locating(&object.shape, methods, reach + aperture, eye),
            Remedy::MoveEye,
        )
    };
    match object.shape {
        ShapeDesc::Sphere { center, radius } => {
            let r = f64::from(radius);
            let from_eye = distance(center, eye) + aperture;
            // Seen from the eye (or its lens) the sphere must keep its shape; seen from anywhere in the
            // world (a secondary ray's origin) it must at least not vanish.
            let across_world = Feature {
                steps: 1.0,
                ..feature(
                    "radius² seen from across the world",
                    r * r,
                    discriminant_error(methods.sphere, r, world + from_eye),
                    Remedy::LargerSphere,
                )
            };
            [
                Some(feature(
                    "radius² seen from the eye",
                    r * r,
                    discriminant_error(methods.sphere, r, from_eye),
                    Remedy::LargerSphere,
                )),
                Some(across_world),
                Some(feature(
                    "radius, against the surface tolerance",
                    r,
                    tolerance_terms(from_eye + r, Some(r)),
                    Remedy::LargerSphere,
                )),
                Some(clearance(from_eye + r)),
            ]
        }
        ShapeDesc::Plane { checker, point, .. } => {
            let reach = gap.max(distance(point, eye));
            let checker = checker.map(|checker| {
                let size = f64::from(checker.size);
                // Counted in squares, a coordinate errs by the rounding of the axes
                // (each 1/size, rounded at its own size) over the checker's reach, and
                // by its own rounding: that must stay within a sixteenth of a square.
                let reach = checker_reach(world, world);
                [
                    feature(
                        "checker square size",
                        size,
                        Terms::new(&[(1.0, world), (1.0, size)]),
                        Remedy::LargerSquares,
                    ),
                    feature(
                        "one checker square, against the rounding of 1/size over the world",
                        1.0,
                        Terms::new(&[
                            (3.0_f64.sqrt() * reach, 1.0 / size),
                            (1.0, reach / size + CHECKER_PERIOD),
                        ]),
                        Remedy::LargerSquares,
                    ),
                ]
            });
            let [square, reciprocal] = checker.map_or([None, None], |[a, b]| [Some(a), Some(b)]);
            let rim = visible_rim(world, gap);
            let rim = feature(
                VISIBLE_DISC,
                rim,
                rim_error(world, rim),
                Remedy::AwayFromTheEdge,
            );
            [square, reciprocal, Some(clearance(reach)), Some(rim)]
        }
        ShapeDesc::Triangle { vertices } => {
            // The tests' determinants are twice the area seen along the ray; their
            // numerators err by the rounding of the unit direction times |s|·|e|, with s the
            // way from the ray's origin to a corner and e the longest edge.
            let corners = vertices.map(Vec3::from_f32);
            let (e1, e2) = (corners[1] - corners[0], corners[2] - corners[0]);
            let s = world + distance(vertices[0], eye) + aperture;
            let longest = e1.length().max(e2.length());
            let area = e1.cross(e2).length();
            let reach = vertices
                .iter()
                .map(|&v| distance(v, eye))
                .fold(gap, f64::max);
            // Möller–Trumbore multiplies by 1/det, rounded at its size: the barycentric
            // coordinates err by its relative rounding, which must stay within a
            // sixteenth of the triangle.
            let reciprocal = (methods.triangle == TriangleMethod::MollerTrumbore).then(|| {
                feature(
                    "Möller–Trumbore's 1/det, against its rounding",
                    1.0 / area,
                    Terms::new(&[(1.0, 1.0 / area)]),
                    Remedy::SmallerTriangle,
                )
            });
            // Cramer's rule and Möller–Trumbore find t as a triple product (t·det, a
            // length times twice an area) over det: for a hit as near as the eye (or its
            // lens) is, the product must resolve against its rounding (the stored e1 × e2
            // rounded at its size, times |s|, and its own).
            let near = gap - aperture;
            let product = (methods.triangle != TriangleMethod::Watertight).then(|| {
                feature(
                    "t·det of a hit as near as the eye, against its rounding",
                    near * area,
                    Terms::new(&[(3.0_f64.sqrt() * s, area), (1.0, near * area)]),
                    Remedy::LargerTriangle,
                )
            });
            [
                Some(feature(
                    "twice the triangle's area",
                    area,
                    area_error(methods.triangle, s, longest, area),
                    Remedy::FatterTriangle,
                )),
                Some(clearance(reach)),
                reciprocal,
                product,
            ]
        }
        // A mesh's triangles are features one by one ([`SceneDesc::primitives`]).
        ShapeDesc::Mesh { .. } => [None, None, None, None],
    }
}

/// What a plane's feature at the world's edge is called: the radius of the disc the world cuts
/// from it (the analysis moves the plane's silhouette by its error).
pub const VISIBLE_DISC: &str = "the radius of the disc the world (far) cuts from the plane";

/// The error with which a hit is placed on a plane, against its visible disc of radius `rim`,
/// in a world of radius `world`: the rounding of a point along a ray and of its difference
/// from the eye's foot, the rounding of its direction times its length (up to the world's
/// diameter), and the rounding of the squares, scaled to within (¼, 1], relative to them.
/// (Where the disc is small its rim is seen nearly head on, so that the rounding of the
/// distance along the ray hardly moves the hit across the plane.)
#[must_use]
pub fn rim_error(world: f64, rim: f64) -> Terms {
    Terms::new(&[(2.0, world), (2.0 * rim, 1.0)]).units(2.0 * world)
}

/// The error of a sphere's discriminant, for a ray whose origin is `f` from the centre.
///
/// The discriminant is r² less a rounded difference. The quadratic's, b² − c, errs by f² times
/// the error in |d|² (it takes a = |d|² as 1, and c = |f|² − r²), by f times half a step at f
/// (b rounded, then squared) and by r²'s own rounding; the stable form's, r² − |f + b·d|², by
/// 2r·f times the error in |d|², 2r times half a step at f, and r²'s rounding.
fn discriminant_error(method: SphereMethod, r: f64, f: f64) -> Terms {
    match method {
        SphereMethod::Quadratic => {
            Terms::new(&[(f, f), (1.0, r * r)]).units(f * f * DIRECTION_LENGTH)
        }
        SphereMethod::Stable => {
            Terms::new(&[(2.0 * r, f), (1.0, r * r)]).units(2.0 * r * f * DIRECTION_LENGTH)
        }
    }
}

/// The camera's bound and features for an image of `width × height` pixels whose image plane,
/// one unit ahead, reaches `half_width` and `half_height` from its centre, through a lens that
/// tilts rays by up to `tilt` = A/f on it (0 for a pinhole): the corner of the image plane
/// (plus the tilt), the angle between neighbouring pixels there, where the plane is seen most
/// obliquely (the pitch over |s|²), and the angle by which the lens's edge turns a ray there
/// (the tilt over |s|²), each against the rounding of a direction (its unit vector, and the
/// image-plane point rounded at its size; for a lens ray also the tilt's products, and the miss
/// as a vector). At fewer than [`MIN_FEATURE_STEPS`] errors of the tilt, the rays through one
/// point of the focal plane meet more than a sixteenth of the aperture off it (the rounding of
/// the lens points themselves is [`features`]'s; the stress case `focal-plane` measures both).
#[must_use]
pub fn camera(
    half_width: f64,
    half_height: f64,
    width: u32,
    height: u32,
    tilt: f64,
) -> (Magnitude, Feature, Option<Feature>) {
    let corner = (1.0 + half_width * half_width + half_height * half_height).sqrt();
    let aim = corner + tilt;
    let pitch = (2.0 * half_width / f64::from(width)).min(2.0 * half_height / f64::from(height));
    // A field of view so wide that its corner is more than twice as far as its centre crams
    // the corner's pixels together; otherwise the pixels are simply too many or too narrow.
    let remedy = if corner > 2.0 {
        Remedy::NarrowerView
    } else {
        Remedy::WiderView
    };
    let magnitude = Magnitude {
        item: Item::Camera,
        quantity: "a corner of the image plane, one unit ahead (plus the lens's tilt)",
        value: aim,
        remedy: Remedy::NarrowerView,
    };
    let error = Terms::new(&[(1.0 / corner, aim)]).units(1.0);
    let feature = Feature {
        item: Item::Camera,
        quantity: "the angle between neighbouring pixels at the image's corner",
        value: pitch / (corner * corner),
        terms: error,
        steps: MIN_PIXEL_STEPS,
        remedy,
    };
    // A lens ray's aim s − (A/f)·(a·right + b·up) also rounds the two tilts' products, and
    // its miss on the focal plane is a vector across it: up to √2 times a coordinate's.
    let aim_error = Terms::new(&[(1.0 / corner, aim), (2.0 / corner, tilt)])
        .units(1.0)
        .times(MISS_ACROSS_PLANE);
    let lens = (tilt > 0.0).then(|| Feature {
        item: Item::Camera,
        quantity: "aperture / focus_distance, the angle by which the lens's edge turns a ray at \
                   the image's corner",
        value: tilt / (corner * corner),
        terms: aim_error,
        steps: MIN_FEATURE_STEPS,
        remedy: Remedy::WiderAperture,
    });
    (magnitude, feature, lens)
}

/// Proves that `format` aims the rays of an image of `width × height` pixels through a lens
/// of tilt `tilt` (see [`camera`]), or says why not.
pub(super) fn check_camera(
    format: &FormatInfo,
    half_width: f64,
    half_height: f64,
    (width, height): (u32, u32),
    tilt: f64,
) -> Result<(), SceneError> {
    // A pixel's centre is the ratio (2i + 1)/2n of two integers the format holds.
    let side = Magnitude {
        item: Item::Camera,
        quantity: "twice the image's longer side in pixels (a pixel centre's denominator)",
        value: 2.0 * f64::from(width.max(height)),
        remedy: Remedy::SmallerImage,
    };
    if !fits(side.value, format.range) {
        return Err(out_of_range(format, &side));
    }
    let (m, pixels, lens) = camera(half_width, half_height, width, height, tilt);
    if !fits(m.value, format.range) {
        return Err(out_of_range(format, &m));
    }
    for f in core::iter::once(pixels).chain(lens) {
        if f.value < f.minimum_with(format) {
            return Err(below_resolution(format, &f, None));
        }
    }
    Ok(())
}

/// The refusal of magnitude `m` in `format`.
fn out_of_range(format: &FormatInfo, m: &Magnitude) -> SceneError {
    SceneError::OutOfRange {
        item: m.item,
        quantity: m.quantity,
        value: m.value,
        format: format.name,
        range: format.range,
        remedy: m.remedy,
        holds: FormatSet::of(|other| fits(m.value, other.range)),
    }
}

/// The refusal of feature `f` in `format`, naming a `method` that resolves it if one does.
fn below_resolution(
    format: &FormatInfo,
    f: &Feature,
    method: Option<(&'static str, &'static str)>,
) -> SceneError {
    SceneError::BelowResolution {
        item: f.item,
        quantity: f.quantity,
        value: f.value,
        format: format.name,
        minimum: f.minimum_with(format),
        remedy: f.remedy,
        holds: FormatSet::of(|other| f.value >= f.minimum_with(other)),
        method,
    }
}

/// Proves that `format` holds the scene for `methods`, or says which value does not fit, the
/// formats that would hold it, and a method that would where one does. (It takes the format's
/// description rather than its type, so that a firmware with several formats holds one copy.)
///
/// A triangle too thin for the format is refused as such first: its tolerance, the rounding of
/// the distance it finds, would also start its rays far off it, beyond the range.
pub(super) fn check(
    format: &FormatInfo,
    desc: &SceneDesc<'_>,
    methods: &Methods,
) -> Result<(), SceneError> {
    let thin = |f: &Feature| f.remedy == Remedy::FatterTriangle;
    if let Some(f) = unresolved(format, desc, methods).filter(thin) {
        return Err(below_resolution(format, &f, None));
    }
    if let Some(m) = too_large(format, desc, methods) {
        return Err(out_of_range(format, &m));
    }
    if let Some(f) = unresolved(format, desc, methods) {
        let method = methods
            .variants()
            .into_iter()
            .filter(|other| other != methods)
            .find(|other| {
                too_large(format, desc, other).is_none()
                    && unresolved(format, desc, other).is_none()
            })
            .and_then(|other| other.changed_from(methods));
        return Err(below_resolution(format, &f, method));
    }
    Ok(())
}

/// The first magnitude that does not fit `format` by `methods`.
fn too_large(format: &FormatInfo, desc: &SceneDesc<'_>, methods: &Methods) -> Option<Magnitude> {
    let slack = origin_slack(desc, methods, format);
    magnitudes(desc, methods, slack)
        .chain(plane_scales(format, desc))
        .find(|m| !fits(m.value, format.range))
}

/// A plane keeps a hit to its visible disc by testing |q·s|² ≤ (ρ·s)², each coordinate of q
/// (the hit less the eye's foot) within ρ and s the power of two that brings ρ within (½, 1]:
/// that power must fit the format (a disc far smaller than 1 needs a large one), or, where the
/// format resolves no finer than one LSB, ρ·s outgrows 1 and the sum of the three squares,
/// 3(ρ·s)², must fit. (A disc of radius 0 is refused as a feature: [`features`].)
fn plane_scales<'a>(
    format: &'a FormatInfo,
    desc: &'a SceneDesc<'a>,
) -> impl Iterator<Item = Magnitude> + 'a {
    let world = f64::from(desc.far);
    let eye = Vec3::from_f32(desc.camera.eye);
    desc.objects
        .iter()
        .enumerate()
        .filter_map(move |(i, object)| Some((Item::Object(i), plane_rim(object, eye, world)?)))
        .filter(|&(_, rim)| rim > 0.0)
        .flat_map(move |(item, rim)| {
            // As the plane finds it: halved until ρ·s ≤ 1, or doubled while ρ·s ≤ ½ (each
            // loop ends within f64's exponents: ρ is a normal f64 below f32's largest).
            let mut ideal = 1.0_f64;
            while rim * ideal > 1.0 {
                ideal /= 2.0;
            }
            while rim * ideal <= 0.5 {
                ideal *= 2.0;
            }
            let scaled = rim * ideal.max((format.resolution)(1.0));
            [
                Magnitude {
                    item,
                    quantity: "the power of two that brings the radius of the plane's visible \
                               disc within (½, 1]",
                    value: ideal,
                    remedy: Remedy::AwayFromTheEdge,
                },
                Magnitude {
                    item,
                    quantity: "the sum of a hit's squared coordinates in the plane's scale",
                    value: 3.0 * scaled * scaled,
                    remedy: Remedy::ShrinkWorld,
                },
            ]
        })
}

/// The radius of the disc a world of radius `world` cuts from a plane `height` from the eye
/// (the plane within the world): √(R² − h²), as (R − h)(R + h) so that it keeps its digits
/// where h is near R.
#[must_use]
pub fn visible_rim(world: f64, height: f64) -> f64 {
    let h = height.abs().min(world);
    ((world - h) * (world + h)).sqrt()
}

/// The radius of `object`'s visible disc in a world of radius `world` about `eye`, if it is a
/// plane.
fn plane_rim(object: &ObjectDesc, eye: Vec3<f64>, world: f64) -> Option<f64> {
    matches!(object.shape, ShapeDesc::Plane { .. })
        .then(|| visible_rim(world, clearance(object, eye)))
}

/// The first feature `format` cannot resolve by `methods`.
fn unresolved(format: &FormatInfo, desc: &SceneDesc<'_>, methods: &Methods) -> Option<Feature> {
    features(desc, methods).find(|f| f.value < f.minimum_with(format))
}

/// Whether `value`, with [`RANGE_HEADROOM`], fits a format of this `range`.
pub(super) fn fits(value: f64, range: f64) -> bool {
    value * RANGE_HEADROOM <= range
}

/// How far `point` is from the nearest point of `object`'s surface.
#[must_use]
pub fn clearance(object: &ObjectDesc, point: Vec3<f64>) -> f64 {
    match object.shape {
        ShapeDesc::Sphere { center, radius } => {
            ((Vec3::from_f32(center) - point).length() - f64::from(radius)).abs()
        }
        ShapeDesc::Plane {
            point: on, normal, ..
        } => Vec3::from_f32(normal)
            .direction()
            .map_or(0.0, |n| n.dot(point - Vec3::from_f32(on)).abs()),
        ShapeDesc::Triangle { vertices } => {
            distance_to_triangle(point, vertices.map(Vec3::from_f32))
        }
        // Its triangles are measured one by one ([`SceneDesc::primitives`]).
        ShapeDesc::Mesh { .. } => f64::INFINITY,
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

impl Methods {
    /// The one method in which `self` differs from `base`, as (question, name), e.g.
    /// `("sphere", "stable")`; `None` when they differ in none or in more than one.
    #[must_use]
    pub fn changed_from(&self, base: &Self) -> Option<(&'static str, &'static str)> {
        let changes = [
            (self.sphere != base.sphere).then(|| ("sphere", self.sphere.name())),
            (self.triangle != base.triangle).then(|| ("triangle", self.triangle.name())),
            (self.roots != base.roots).then(|| ("sqrt", self.roots.name())),
            (self.rays != base.rays).then(|| ("rays", self.rays.name())),
            (self.bias != base.bias).then(|| ("bias", self.bias.name())),
        ];
        let mut changed = changes.into_iter().flatten();
        let first = changed.next()?;
        changed.next().is_none().then_some(first)
    }
}

/// The distance between two points of a description.
pub(super) fn distance(a: [f32; 3], b: [f32; 3]) -> f64 {
    (Vec3::from_f32(a) - Vec3::from_f32(b)).length()
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

    #[test]
    fn a_change_of_one_method_is_named() {
        let stable = Methods {
            sphere: SphereMethod::Stable,
            ..Methods::LECTURE
        };
        assert_eq!(
            stable.changed_from(&Methods::LECTURE),
            Some(("sphere", "stable"))
        );
        assert_eq!(Methods::LECTURE.changed_from(&Methods::LECTURE), None);
        let two = Methods {
            triangle: TriangleMethod::Watertight,
            ..stable
        };
        assert_eq!(two.changed_from(&Methods::LECTURE), None);
    }
}
