//! The model of a format's error against f64: what `analyze` predicts, and what the fuzzer and
//! the tests hold to measurement (a lower bound on the PSNR, an upper bound on the object
//! mismatch).
//!
//! A format's image differs from f64's in two ways, and the model takes each separately:
//!
//! 1. **Its constants and tolerances.** The scene build stores the format's own values
//!    (positions, radii, a checkerboard's 1/size, colours) and tolerances, and a quotient
//!    saturates at its range. The model renders the scene in f64 arithmetic on those very values
//!    ([`Quantized`]) and measures that image against f64: every systematic effect, at every
//!    pixel, exactly.
//! 2. **The rounding of each operation.** It turns what a ray sees by at most a small angle:
//!    everywhere by a unit vector's steps, a point's rounding seen from the nearest surface,
//!    the drift of stepped rays and the error of fast roots ([`global_angle`]); and where a ray
//!    tree meets an object, by that object's own error ([`object_shifts`]): a sphere's
//!    silhouette moved by its discriminant's error, a triangle's edges by its determinant's
//!    and its numerators', a mesh's edges (those between its triangles too) by the most any of
//!    its triangles' move, a checkerboard's edges by the rounding of their coordinates, a
//!    glass's refraction multiplying the rounding inside by η. Where a mesh's triangles test a
//!    shared edge each by its own rounding (Möller–Trumbore; Cramer's rule in a float), a ray
//!    between two of them may miss both: a pixel within reach of such an edge may show what
//!    lies behind the mesh ([`Reference`] traces the scene without it). A pixel whose ray tree
//!    met objects i (the f64 reference records them, shadows included) may move: the edge
//!    between two neighbours by
//!    the global angle, by an object's silhouette's where one of their ray trees met the object
//!    and the other did not, and by its inner edges' where both did, which changes them by
//!    about that share δ of a pixel times their squared step (for δ < 1), and beyond that by
//!    as much as a pixel differs from those δ away ([`Reference`]). Where an object is smaller
//!    than a pixel (a distant sphere, far squares of a checkerboard), δ is the error's share of
//!    the object's own size: the chance that a pixel's one sample falls on its other side.
//!    Shading adds the rounding of Lambert's cosine and of the colour's sums and products,
//!    times the light that reaches a pixel; a highlight's, which its exponent multiplies, is in
//!    the render of 1.
//!
//! The rounding of an operation lands anywhere within its bound, and the model counts the
//! bound; the sources are independent, so their mean squared errors add. The prediction is the error to expect, and the tests and the fuzzer hold it to
//! measurement: a measured error may exceed it by chance, by little (see
//! [`crate::fuzz::MARGIN`]). Nothing is rendered in the format itself.

use super::extents;
use crate::checked::Checked;
use crate::metrics::accuracy;
use crate::quantized::{COSINE_STEPS, Quantized, coarser};
use crate::render::{Prepared, Request, exact_roots, threads_here};
use anyhow::Result;
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use image::RgbImage;
use obscura::scalar::FAST_ROOT_ERROR;
use obscura::scene::range;
use obscura::shape::CHECKER_PERIOD;
use obscura::{
    BackgroundDesc, Methods, ObjectDesc, RayMethod, RootMethod, Scalar, SceneDesc, ShapeDesc,
    TriangleMethod, Vec3,
};
use obscura_scene::{Format, FormatJob};
use rayon::prelude::*;
use std::f64::consts::FRAC_1_SQRT_2;

/// Unit-vector steps a format's rounding turns a ray by: the primary ray's and one bounce's.
const DIRECTION_STEPS: f64 = 2.0;

/// Steps of rounding in a colour: each product and sum on the way to the pixel.
const COLOUR_STEPS: f64 = 8.0;

/// The f64 reference of a scene at one size: the scene and camera themselves, to trace rays
/// beside the pixels' centres; its image; the object each primary ray hits; and the objects each
/// pixel's ray tree meets.
#[derive(Debug)]
pub struct Reference {
    /// The scene and camera, in f64.
    prepared: Prepared<f64>,
    /// The image.
    pub image: RgbImage,
    /// The object each pixel's primary ray hits.
    pub objects: Vec<Option<usize>>,
    /// The objects each pixel's ray tree meets ([`obscura::Sample::met`]).
    pub met: Vec<u64>,
    /// The triangle of its mesh each pixel's primary ray hits (0 for other objects).
    parts: Vec<u32>,
    /// The meshes whose neighbouring triangles' tests may both miss a ray between them (by a
    /// test that is not watertight), a bit each, and the f64 scene without them: what shows
    /// through such a crack (`None` where there are none, or the scene without them is empty).
    crackable: u64,
    behind: Option<Prepared<f64>>,
    /// A pixel's rays, and whether they are several or through a lens: then a moved pixel is
    /// all of them moved, against all of them where they are.
    samples: u16,
    sampled: bool,
}

/// The directions a pixel's ray is nudged in, to see what lies within a distance of it: along
/// the rows and columns and the diagonals.
const NUDGES: [(f64, f64); 8] = [
    (1.0, 0.0),
    (-1.0, 0.0),
    (0.0, 1.0),
    (0.0, -1.0),
    (FRAC_1_SQRT_2, FRAC_1_SQRT_2),
    (FRAC_1_SQRT_2, -FRAC_1_SQRT_2),
    (-FRAC_1_SQRT_2, FRAC_1_SQRT_2),
    (-FRAC_1_SQRT_2, -FRAC_1_SQRT_2),
];

impl Reference {
    /// The f64 reference of `request` (which must have exact roots: f64 has no others).
    ///
    /// # Errors
    /// When f64 cannot build the scene.
    pub fn render(request: &Request<'_>) -> Result<Self> {
        let prepared = Prepared::<f64>::new(request)?;
        let image = prepared.render(threads_here(), None)?;
        let hits = prepared.hit_map()?;
        let objects = hits
            .iter()
            .map(|hit| hit.map(|(object, _)| object))
            .collect();
        let parts = hits
            .iter()
            .map(|hit| hit.map_or(0, |(_, part)| part))
            .collect();
        let met = prepared.met_map()?;
        let desc = &request.desc;
        let mesh = |object: &ObjectDesc| matches!(object.shape, ShapeDesc::Mesh { .. });
        let crackable = if request.methods.triangle == TriangleMethod::Watertight {
            0
        } else {
            (0..)
                .zip(desc.objects)
                .filter(|(_, object)| mesh(object))
                .fold(0, |bits, (i, _)| bits | object_bit(i))
        };
        let kept: Vec<ObjectDesc> = desc.objects.iter().filter(|o| !mesh(o)).copied().collect();
        let without = SceneDesc {
            objects: &kept,
            ..*desc
        };
        let behind = (crackable != 0)
            .then(|| Prepared::<f64>::new(&request.with_desc(without)))
            .and_then(Result::ok);
        let samples = desc.samples;
        Ok(Self {
            prepared,
            image,
            objects,
            met,
            parts,
            crackable,
            behind,
            samples,
            sampled: samples > 1 || request.desc.camera.aperture > 0.0,
        })
    }

    /// The mean squared error, in levels², and the share of pixels whose primary ray may hit
    /// another object, when every ray may move by up to `shift(p, q)` pixels where pixel p
    /// meets its neighbour q: each pixel's ray nudged by the most an edge within its reach
    /// moves ([`reach`]: its own, or one that moves across it from pixels away), in each of
    /// eight directions, may see whatever the f64 scene shows there (worst case: the most
    /// different). A pixel alike its eight neighbours, whose edges move by less than a pixel,
    /// is left alone. Past the image's edge, a pixel may show anything.
    fn moved(&self, shift: impl Fn(usize, usize) -> f64 + Sync, cracks: bool) -> (f64, f64) {
        let (width, height) = self.image.dimensions();
        let index = |x: u32, y: u32| (y * width + x) as usize;
        let own_row = |y: u32| -> Vec<f64> {
            (0..width)
                .map(|x| {
                    let here = index(x, y);
                    neighbours(width, height, x, y)
                        .map(|(nx, ny)| shift(here, index(nx, ny)))
                        .fold(shift(here, here), f64::max)
                })
                .collect()
        };
        // On every core, or on one within a thread pool's task (the fuzzer's, the analyses'),
        // as the renders are: a small image of many shadow rays is as dear as a large one.
        let parallel = threads_here() > 1;
        let own: Vec<f64> = if parallel {
            (0..height).into_par_iter().flat_map_iter(own_row).collect()
        } else {
            (0..height).flat_map(own_row).collect()
        };
        let reaches = reach(&own, width, height);
        let around = |x: u32, y: u32| neighbours(width, height, x, y);
        let pixel = |x: u32, y: u32| -> (f64, f64) {
            let here = index(x, y);
            let delta = reaches.get(here).copied().unwrap_or(0.0);
            if delta <= 0.0 {
                return (0.0, 0.0);
            }
            if delta >= f64::from(width.max(height)) {
                return (3.0 * LEVELS * LEVELS, 1.0);
            }
            let colour = self.image.get_pixel(x, y).0;
            let object = self.objects.get(here).copied().flatten();
            let alike = around(x, y).all(|(nx, ny)| {
                self.image.get_pixel(nx, ny).0 == colour
                    && self.objects.get(index(nx, ny)) == self.objects.get(here)
                    && self.met.get(index(nx, ny)) == self.met.get(here)
                    && self.parts.get(index(nx, ny)) == self.parts.get(here)
            });
            if alike && delta < 1.0 {
                return (0.0, 0.0);
            }
            // Several rays are moved all together, and held to themselves unmoved: their
            // mean is not the reference's pixel where adaptive samples took only some.
            let unmoved = if self.sampled {
                self.prepared.pixel(x, y, [0.0; 2], self.samples)
            } else {
                Some((Rgb888::new(colour[0], colour[1], colour[2]), object))
            };
            let Some((colour, object)) = unmoved else {
                return (0.0, 0.0);
            };
            let squared = |seen: Rgb888| -> f64 {
                [seen.r(), seen.g(), seen.b()]
                    .iter()
                    .zip([colour.r(), colour.g(), colour.b()])
                    .map(|(&a, b)| (f64::from(a) - f64::from(b)).powi(2))
                    .sum()
            };
            let part = self.parts.get(here).copied().unwrap_or(0);
            let crackable = cracks && object.is_some_and(|o| self.crackable & object_bit(o) != 0);
            let mut worst = 0.0_f64;
            let mut mismatched = false;
            for (across, down) in NUDGES {
                let offset = [across * delta, down * delta];
                let Some((seen, seen_object)) = self.prepared.pixel(x, y, offset, self.samples)
                else {
                    continue;
                };
                worst = worst.max(squared(seen));
                mismatched |= seen_object != object;
                // Across an edge between two of a crackable mesh's triangles, the ray may miss
                // both and see what lies behind the mesh (anything, where nothing does).
                let across_mesh = crackable
                    && self
                        .prepared
                        .hit_at(x, y, offset)
                        .is_some_and(|(o, p)| Some(o) == object && p != part);
                if across_mesh {
                    let through = self.behind.as_ref();
                    let through = through.and_then(|b| b.pixel(x, y, offset, self.samples));
                    worst = worst.max(through.map_or(3.0 * LEVELS * LEVELS, |(c, _)| squared(c)));
                    mismatched = true;
                }
            }
            (worst, if mismatched { 1.0 } else { 0.0 })
        };
        let row = |y: u32| {
            (0..width)
                .map(|x| pixel(x, y))
                .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
        };
        let add = |a: (f64, f64), b: (f64, f64)| (a.0 + b.0, a.1 + b.1);
        // Summed in the rows' order however they were found, so that a prediction is the same
        // to the bit on any number of cores.
        let rows: Vec<(f64, f64)> = if parallel {
            (0..height).into_par_iter().map(row).collect()
        } else {
            (0..height).map(row).collect()
        };
        let (squared, mismatched) = rows.into_iter().fold((0.0, 0.0), add);
        let pixels = f64::from(width) * f64::from(height);
        (squared / (3.0 * pixels), mismatched / pixels)
    }
}

/// Object `i`'s bit in a [`Reference::met`] mask (objects 64 and beyond share bit 63).
fn object_bit(i: usize) -> u64 {
    1 << i.min(63)
}

/// The pixels around (x, y) in an image of `width` × `height`: its eight neighbours, less
/// those past the image's edge.
fn neighbours(width: u32, height: u32, x: u32, y: u32) -> impl Iterator<Item = (u32, u32)> {
    (-1_i64..=1)
        .flat_map(move |dy| (-1_i64..=1).map(move |dx| (dx, dy)))
        .filter(|&(dx, dy)| dx != 0 || dy != 0)
        .filter_map(move |(dx, dy)| {
            let (nx, ny) = (i64::from(x) + dx, i64::from(y) + dy);
            let inside = nx >= 0 && ny >= 0 && nx < i64::from(width) && ny < i64::from(height);
            inside.then_some((nx as u32, ny as u32))
        })
}

/// How far each pixel's ray may move, given `own[i]`, the most the edges of pixel i with its
/// neighbours move: its own, or the shift of an edge D pixels away that moves across it (an
/// edge moved by D changes every pixel within D of it, not only its neighbours). Each pixel's
/// own shift spreads to the pixels within it (less one per pixel, as a chessboard counts them)
/// by two raster passes of a chamfer (Rosenfeld and Pfaltz), carrying the shift of the edge
/// whose reach is longest there; a pixel that reach covers (by at least one) takes that
/// shift, enough for its nudged ray to cross the edge.
fn reach(own: &[f64], width: u32, height: u32) -> Vec<f64> {
    let (w, h) = (i64::from(width), i64::from(height));
    // (reach left, the shift of its edge) per pixel.
    let mut spread: Vec<(f64, f64)> = own.iter().map(|&d| (d, d)).collect();
    // The neighbours a raster pass has visited before a pixel: forwards, then backwards.
    let passes: [(&[(i64, i64)], bool); 2] = [
        (&[(-1, 0), (-1, -1), (0, -1), (1, -1)], false),
        (&[(1, 0), (1, 1), (0, 1), (-1, 1)], true),
    ];
    for (visited, backwards) in passes {
        for k in 0..w * h {
            let i = if backwards { w * h - 1 - k } else { k };
            let (x, y) = (i % w, i / w);
            for &(dx, dy) in visited {
                let (nx, ny) = (x + dx, y + dy);
                if nx < 0 || ny < 0 || nx >= w || ny >= h {
                    continue;
                }
                let (left, shift) = spread[(ny * w + nx) as usize];
                if left - 1.0 > spread[i as usize].0 {
                    spread[i as usize] = (left - 1.0, shift);
                }
            }
        }
    }
    own.iter()
        .zip(spread)
        .map(|(&own, (left, shift))| if left >= 1.0 { own.max(shift) } else { own })
        .collect()
}

/// What the model predicts for one format.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prediction {
    /// The PSNR against f64 the format is predicted to reach at least, in dB.
    pub psnr_db: f64,
    /// The share of pixels, in percent, whose primary ray it is predicted to see hit another
    /// object than f64's, at most.
    pub mismatch_pct: f64,
    /// The mean squared error of its constants and tolerances alone, in levels².
    pub constants_mse: f64,
    /// How far its rounding may move the image, in pixels.
    pub shift_px: f64,
    /// How far its rounding may move a pixel's shading, in levels.
    pub shading_levels: f64,
}

/// The model's prediction for `format` on `desc` by `methods` at the reference's size (see
/// the module documentation).
///
/// # Errors
/// When the format cannot build the scene (then there is nothing to predict).
pub fn predict(
    format: Format,
    desc: &SceneDesc<'_>,
    methods: Methods,
    reference: &Reference,
) -> Result<Prediction> {
    struct Job<'a, 'b>(&'a SceneDesc<'b>, Methods, &'a Reference);
    impl FormatJob for Job<'_, '_> {
        type Output = Result<Prediction>;
        fn run<S: Scalar>(self) -> Self::Output {
            predict_in::<S>(self.0, self.1, self.2)
        }
    }
    format.run::<Checked, _>(Job(desc, methods, reference))
}

fn predict_in<S: Scalar>(
    desc: &SceneDesc<'_>,
    methods: Methods,
    reference: &Reference,
) -> Result<Prediction> {
    let (width, height) = reference.image.dimensions();
    // The format's constants and tolerances alone: f64 arithmetic on its stored values, by the
    // methods' exact roots (their error is the rounding's, below).
    let constants =
        Prepared::<Quantized<S>>::new(&Request::new(*desc, (width, height), exact_roots(methods)))?;
    let measured = accuracy(
        &constants.render(threads_here(), None)?,
        &reference.image,
        &constants.object_map()?,
        &reference.objects,
    );
    let constants_mse = mse(measured.psnr_db);
    let pixel = pixel_angle(desc, width, height);
    let global_angle = global_angle::<S>(desc, &methods, width, height);
    let global = global_angle / pixel;
    let shifts = object_shifts::<S>(desc, &methods, pixel);
    // The edge between two pixels moves by the global shift; by an object's silhouette's
    // where one ray tree met the object and the other did not; by its inner edges' where both
    // did.
    let shift = |p: usize, q: usize| {
        let met = |i: usize| reference.met.get(i).copied().unwrap_or(u64::MAX);
        let (a, b) = (met(p), met(q));
        let own: f64 = shifts
            .iter()
            .enumerate()
            .map(|(object, shift)| {
                let bit = object_bit(object);
                match (a & bit != 0, b & bit != 0) {
                    (true, true) => shift.inner,
                    (true, false) | (false, true) => shift.silhouette,
                    (false, false) => 0.0,
                }
            })
            .sum();
        global + own
    };
    let shift_px = shifts
        .iter()
        .map(|shift| shift.silhouette.max(shift.inner))
        .sum::<f64>()
        + global;
    let shading_levels = LEVELS * shading_error::<S>(desc);
    // Rounding a colour that errs by e levels to the nearest level changes it by one level in
    // an e share of pixels.
    let shading_mse = shading_levels * shading_levels + shading_levels.min(1.0);
    // Two neighbouring triangles of a mesh may both miss a ray between them where each tests
    // its edges by its own rounding (`obscura stress`'s mesh case measures it): by
    // Möller–Trumbore, whose rounded 1/det moves each triangle's edges its own way, and by
    // Cramer's rule in a float, whose rounding differs between the two; Cramer's rule almost
    // never does in the fixed formats, the watertight test never.
    let floating = S::resolution(2.0) > S::resolution(1.0);
    let cracks = match methods.triangle {
        TriangleMethod::MollerTrumbore => true,
        TriangleMethod::Cramer => floating,
        TriangleMethod::Watertight => false,
    };
    let (moved_mse, moved_share) = reference.moved(shift, cracks);
    // No image strays further than every channel of every pixel by full scale: 0 dB.
    let total = (constants_mse + moved_mse + shading_mse).min(LEVELS * LEVELS);
    let mismatch_pct = measured.object_mismatch_pct + 100.0 * moved_share;
    Ok(Prediction {
        psnr_db: psnr(total),
        mismatch_pct: mismatch_pct.min(100.0),
        constants_mse,
        shift_px,
        shading_levels,
    })
}

/// A channel's full scale, in levels.
const LEVELS: f64 = 255.0;

/// The mean squared error, in levels², of a PSNR in dB.
fn mse(psnr_db: f64) -> f64 {
    LEVELS * LEVELS / 10_f64.powf(psnr_db / 10.0)
}

/// The PSNR, in dB, of a mean squared error in levels².
fn psnr(mse: f64) -> f64 {
    if mse > 0.0 {
        10.0 * (LEVELS * LEVELS / mse).log10()
    } else {
        f64::INFINITY
    }
}

/// The smallest angle between neighbouring pixels' rays: at the image's corner, where the
/// image plane is seen most obliquely.
pub(crate) fn pixel_angle(desc: &SceneDesc<'_>, width: u32, height: u32) -> f64 {
    let half_height = (f64::from(desc.camera.vfov_degrees).to_radians() / 2.0).tan();
    let half_width = half_height * f64::from(width) / f64::from(height);
    let (corner, _, _) = range::camera(half_width, half_height, width, height, 0.0);
    let pitch = (2.0 * half_width / f64::from(width)).min(2.0 * half_height / f64::from(height));
    pitch / (corner.value * corner.value)
}

/// The angle, in radians, by which format `S`'s rounding may turn what any ray sees (see the
/// module documentation).
fn global_angle<S: Scalar>(
    desc: &SceneDesc<'_>,
    methods: &Methods,
    width: u32,
    height: u32,
) -> f64 {
    let nearest = extents(desc).nearest.max(f64::MIN_POSITIVE);
    let step = S::UNIT_ERROR;
    // A point rounds at its own size, seen from as far: largest for the nearest.
    let mut angle = DIRECTION_STEPS * (step + S::resolution(nearest) / nearest);
    if methods.roots == RootMethod::Approx && S::FAST_ROOTS {
        angle += DIRECTION_STEPS * FAST_ROOT_ERROR;
    }
    if methods.rays == RayMethod::Stepped {
        // The step along the row is rounded once and added at every pixel, so its rounding
        // grows with the row; each sum rounds too, at the image plane's size, which adds up as
        // chance does (exactly, in fixed point).
        let half_height = (f64::from(desc.camera.vfov_degrees).to_radians() / 2.0).tan();
        let across = 2.0 * half_height * f64::from(width) / f64::from(height);
        let pixels = f64::from(width);
        angle += pixels * S::resolution(across / pixels) + pixels.sqrt() * S::resolution(1.0);
    }
    if methods.triangle == TriangleMethod::Watertight {
        // Its shear's two quotients round the sheared corners.
        angle += DIRECTION_STEPS * step;
    }
    angle
}

/// How far format `S`'s rounding may move an object's edges, in pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Shifts {
    /// Its silhouette (its edge against what is behind it).
    silhouette: f64,
    /// The edges within it (a checkerboard's, those seen through it).
    inner: f64,
}

/// Each object's [`Shifts`] in format `S`, for pixels `pixel` radians apart (see the module
/// documentation).
fn object_shifts<S: Scalar>(desc: &SceneDesc<'_>, methods: &Methods, pixel: f64) -> Vec<Shifts> {
    let nearest = extents(desc).nearest.max(f64::MIN_POSITIVE);
    let eye = Vec3::from_f32(desc.camera.eye);
    let mut shifts: Vec<Shifts> = desc
        .objects
        .iter()
        .map(|object| {
            // Leaving a glass of index η multiplies the rounding of the direction inside by η.
            let m = &object.material;
            let solid = matches!(object.shape, ShapeDesc::Sphere { .. });
            let inner = if solid && m.transmission > 0.0 {
                f64::from(m.ior) * DIRECTION_STEPS * S::UNIT_ERROR / pixel
            } else {
                0.0
            };
            Shifts {
                silhouette: 0.0,
                inner,
            }
        })
        .collect();
    // A mesh's edges are its triangles', its silhouette and the edges within it alike: they
    // move by the most any of its triangles' do.
    for (i, primitive) in desc.primitives() {
        let (Some(object), Some(shift)) = (desc.objects.get(i), shifts.get_mut(i)) else {
            continue;
        };
        let own = primitive_shifts::<S>(desc, methods, i, &primitive, pixel, nearest, eye);
        let mesh = matches!(object.shape, ShapeDesc::Mesh { .. });
        shift.silhouette = shift.silhouette.max(own.silhouette);
        shift.inner = shift
            .inner
            .max(if mesh { own.silhouette } else { own.inner });
    }
    shifts
}

/// How far format `S`'s rounding may move the edges of `primitive`, object `i` of `desc` or one
/// of its mesh's triangles, seen from `eye` (no nearer than `nearest`), for pixels `pixel`
/// radians apart: the sum over its features' errors.
fn primitive_shifts<S: Scalar>(
    desc: &SceneDesc<'_>,
    methods: &Methods,
    i: usize,
    primitive: &ObjectDesc,
    pixel: f64,
    nearest: f64,
    eye: Vec3<f64>,
) -> Shifts {
    let mut shift = Shifts::default();
    let seen = range::clearance(primitive, eye).max(nearest);
    let longest = |vertices: [[f32; 3]; 3]| {
        let [a, b, c] = vertices.map(Vec3::from_f32);
        (b - a).length().max((c - a).length()).max((c - b).length())
    };
    for feature in range::object_features(desc, methods, i, primitive)
        .into_iter()
        .flatten()
    {
        let error = feature.error::<S>();
        match (primitive.shape, feature.quantity) {
            // The silhouette moves by the discriminant's error over 2r, seen from the eye.
            (ShapeDesc::Sphere { center, radius }, "radius² seen from the eye") => {
                let r = f64::from(radius);
                let from_eye = (Vec3::from_f32(center) - eye).length().max(nearest);
                shift.silhouette += error / (2.0 * r * from_eye) / pixel;
            }
            // An edge moves by the determinant's error over the edge's length.
            (ShapeDesc::Triangle { vertices }, "twice the triangle's area") => {
                shift.silhouette += error / (longest(vertices) * seen) / pixel;
            }
            // Möller–Trumbore's 1/det errs relatively by its rounding over itself, and so do
            // the barycentric coordinates, moving an edge by that share of the triangle.
            (ShapeDesc::Triangle { vertices }, "Möller–Trumbore's 1/det, against its rounding") =>
            {
                shift.silhouette += error / feature.value * longest(vertices) / seen / pixel;
            }
            // The rim of a plane's visible disc moves across the plane by its error, seen from
            // the eye, R away, at the sine h/R of its angle with the plane.
            (ShapeDesc::Plane { .. }, range::VISIBLE_DISC) => {
                let world = f64::from(desc.far);
                let height = range::clearance(primitive, eye);
                shift.silhouette += error * height / (world * world) / pixel;
            }
            // A checker coordinate, counted in squares, is rounded at its size: a point seen at
            // distance d is about d from the eye's foot, where the count starts, so its edges
            // move by size·res(d/size)/d, most at the nearest.
            (
                ShapeDesc::Plane {
                    checker: Some(checker),
                    ..
                },
                "checker square size",
            ) => {
                let size = f64::from(checker.size);
                shift.inner += size * S::resolution(seen / size + CHECKER_PERIOD) / seen / pixel;
            }
            _ => {}
        }
    }
    shift
}

/// How far format `S`'s rounding may move a pixel's colour, as a share of full intensity: the
/// rounding of Lambert's cosine times the diffuse weight, times the light that reaches a
/// surface, and the rounding of the colour's products and sums, over every level of the ray
/// tree; where the narrow format ([`Scalar::Narrow`]) is the coarser, the rounding of the unit
/// vectors the cosine is taken of and of the narrow products too; and a sky's gradient, its
/// rise times the rounding of its cosine. (The highlights' rounding is in the render of the
/// constants.)
fn shading_error<S: Scalar>(desc: &SceneDesc<'_>) -> f64 {
    let narrowing = coarser::<S, S::Narrow>();
    let cosine = COSINE_STEPS * (S::UNIT_ERROR + narrowing);
    let local = desc
        .objects
        .iter()
        .map(|object| f64::from(object.material.diffuse) * cosine)
        .fold(0.0, f64::max);
    let brightest = |c: [f32; 3]| f64::from(c.iter().copied().fold(0.0_f32, f32::max));
    let light: f64 = desc.lights.iter().map(|l| brightest(l.colour)).sum();
    let passed_on = desc
        .objects
        .iter()
        .map(|object| f64::from(object.material.reflection + object.material.transmission))
        .fold(0.0, f64::max)
        .min(1.0);
    let levels: f64 = (0..=desc.max_depth)
        .map(|k| passed_on.powi(i32::from(k)))
        .sum();
    let colour = brightest(desc.ambient) + 2.0 * light;
    let rounding = S::resolution(colour.max(1.0)) + narrowing;
    // A sky is its horizon plus its rise times the cosine of a ray with its up: the cosine's
    // rounding times the rise, which a sky far brighter than the display multiplies.
    let sky = match desc.background {
        BackgroundDesc::Gradient {
            horizon, zenith, ..
        } => {
            let rise = (0..3)
                .map(|i| f64::from((zenith[i] - horizon[i]).abs()))
                .fold(0.0, f64::max);
            let brightest = brightest(horizon).max(brightest(zenith));
            rise * cosine + COLOUR_STEPS * S::resolution(brightest.max(1.0)) * brightest
        }
        BackgroundDesc::Solid(_) => 0.0,
    };
    levels * (light * local + COLOUR_STEPS * rounding * colour + sky)
}

#[cfg(test)]
mod tests {
    use super::*;
    use obscura::{BackgroundDesc, CameraDesc, MaterialDesc, ObjectDesc, ShapeDesc, scenes};

    /// A white sphere on black, seen head on at 32×32.
    fn ball() -> Reference {
        let objects = [ObjectDesc {
            shape: ShapeDesc::Sphere {
                center: [0.0, 0.0, 5.0],
                radius: 1.0,
            },
            material: MaterialDesc {
                diffuse: 0.0,
                ..MaterialDesc::matte([1.0; 3])
            },
        }];
        let desc = SceneDesc {
            camera: CameraDesc::pinhole([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 30.0),
            objects: &objects,
            lights: &[],
            ambient: [1.0; 3],
            background: BackgroundDesc::Solid([0.0; 3]),
            far: 10.0,
            max_depth: 0,
            ..SceneDesc::DEFAULT
        };
        Reference::render(&Request::new(desc, (32, 32), Methods::LECTURE)).expect("renders")
    }

    #[test]
    fn a_nudge_finds_the_pixels_within_its_reach_of_an_edge() {
        let reference = ball();
        assert_eq!(reference.moved(|_, _| 0.0, false), (0.0, 0.0));
        // Half a pixel's nudge reaches the silhouette from the pixels next to it, no farther.
        let (half, half_share) = reference.moved(|_, _| 0.5, false);
        let (two, two_share) = reference.moved(|_, _| 2.0, false);
        assert!(half > 0.0 && half_share > 0.0);
        assert!(two > half && two_share > half_share);
        // Each pixel that may change may change by all of white to black.
        let pixels = 32.0 * 32.0;
        assert!((half - half_share * 255.0 * 255.0).abs() * pixels < 1e-6);
        // Past the image's edge, anything.
        assert_eq!(reference.moved(|_, _| 40.0, false), (255.0 * 255.0, 1.0));
    }

    #[test]
    fn an_edge_that_moves_far_reaches_the_pixels_it_crosses() {
        // One row: the edge between pixels 5 and 6 moves by 3.5 pixels, across 3 on each side.
        let mut own = vec![0.1; 12];
        own[5] = 3.5;
        own[6] = 3.5;
        let far = 3.5;
        let near = 0.1;
        assert_eq!(
            reach(&own, 12, 1),
            [
                near, near, near, far, far, far, far, far, far, near, near, near
            ]
        );
        // The same along a column, and in the plane by a chessboard's count: a pixel's edges
        // moved by 2.5 reach its eight neighbours, not the ring beyond.
        assert_eq!(reach(&own, 1, 12), reach(&own, 12, 1));
        let mut square = vec![0.0; 25];
        square[12] = 2.5;
        let reached = reach(&square, 5, 5);
        for (i, &delta) in reached.iter().enumerate() {
            let (x, y) = (i % 5, i / 5);
            let ring = x.abs_diff(2).max(y.abs_diff(2));
            assert_eq!(delta, if ring <= 1 { 2.5 } else { 0.0 }, "({x}, {y})");
        }
    }

    #[test]
    fn the_prediction_for_f64_itself_is_of_no_error() {
        let whitted = scenes::WHITTED;
        let request = Request::new(whitted, (48, 48), Methods::LECTURE);
        let reference = Reference::render(&request).expect("renders");
        let f64s = predict(Format::F64, &whitted, Methods::LECTURE, &reference).expect("holds");
        assert!(f64s.psnr_db > 100.0, "{f64s:?}");
        let i20f12 =
            predict(Format::I20f12, &whitted, Methods::LECTURE, &reference).expect("holds");
        assert!(i20f12.psnr_db < f64s.psnr_db && i20f12.shift_px > f64s.shift_px);
    }
}
