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
//!    tree meets an object, by that object's own error ([`object_angles`]): a sphere's
//!    silhouette moved by its discriminant's error, a triangle's edges by its determinants', a
//!    checkerboard's edges by the rounding of their coordinates, a glass's refraction
//!    multiplying the rounding inside by η. A pixel whose ray tree met objects i (the f64
//!    reference records them, shadows included) may move: the edge between two neighbours by
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
//! The rounding of an operation lands anywhere within its bound, on average half of it
//! ([`EVEN`]), and so the model counts it; the sources are independent, so their mean squared
//! errors add. The prediction is the error to expect, and the tests and the fuzzer hold it to
//! measurement: a measured error may exceed it by chance, by little (see
//! [`crate::fuzz::MARGIN`]). Nothing is rendered in the format itself.

use super::extents;
use crate::format::{Format, FormatJob};
use crate::metrics::accuracy;
use crate::quantized::{COSINE_STEPS, Quantized};
use crate::render::{Prepared, Request, exact_roots};
use anyhow::Result;
use image::RgbImage;
use obscura::scene::range::{self, FAST_ROOT_ERROR};
use obscura::{
    Item, Methods, RayMethod, RootMethod, Scalar, SceneDesc, ShapeDesc, TriangleMethod, Vec3,
};

/// Unit-vector steps a format's rounding turns a ray by: the primary ray's and one bounce's.
const DIRECTION_STEPS: f64 = 2.0;

/// What an error spread evenly over its bound comes to on average: half the bound.
const EVEN: f64 = 0.5;

/// Steps of rounding in a colour: each product and sum on the way to the pixel.
const COLOUR_STEPS: f64 = 8.0;

/// The f64 reference of a scene at one size: its image, the object each primary ray hits, the
/// objects each pixel's ray tree meets, and the image's structure.
#[derive(Debug)]
pub struct Reference {
    /// The image.
    pub image: RgbImage,
    /// The object each pixel's primary ray hits.
    pub objects: Vec<Option<usize>>,
    /// The objects each pixel's ray tree meets ([`obscura::Sample::met`]).
    pub met: Vec<u64>,
    /// The image's structure.
    pub structure: Structure,
}

impl Reference {
    /// The reference of an image, its objects and what each pixel met.
    pub fn new(image: RgbImage, objects: Vec<Option<usize>>, met: Vec<u64>) -> Self {
        let structure = Structure::of(&image, &objects);
        Self {
            image,
            objects,
            met,
            structure,
        }
    }

    /// The mean squared error, in levels², of the image when the edge between each pixel p and
    /// its neighbour q moves by `shift(p, q)` pixels: for δ ≤ 1, the squared step between them
    /// (across and below) times δ; where a pixel's edges move by more, its largest squared
    /// difference from the pixels up to the next power of two of δ away, or, past the image's
    /// edge, any colour at all.
    fn moved(&self, shift: impl Fn(usize, usize) -> f64) -> f64 {
        let (width, height) = self.image.dimensions();
        let pixel = |x: u32, y: u32| self.image.get_pixel(x, y).0;
        let squared = |a: [u8; 3], b: [u8; 3]| -> f64 {
            a.iter()
                .zip(b)
                .map(|(&p, q)| (f64::from(p) - f64::from(q)).powi(2))
                .sum()
        };
        let neighbours = |x: u32, y: u32| {
            [
                x.checked_sub(1).map(|nx| (nx, y)),
                (x + 1 < width).then(|| (x + 1, y)),
                y.checked_sub(1).map(|ny| (x, ny)),
                (y + 1 < height).then(|| (x, y + 1)),
            ]
            .into_iter()
            .flatten()
        };
        let mut sum = 0.0;
        for y in 0..height {
            for x in 0..width {
                let here = pixel(x, y);
                let i = (y * width + x) as usize;
                let pairs = |k: u32| {
                    [(x + k, y), (x, y + k)]
                        .into_iter()
                        .filter(move |&(nx, ny)| nx < width && ny < height)
                };
                // A pixel moves with the edges around it.
                let delta = neighbours(x, y)
                    .map(|(nx, ny)| shift(i, (ny * width + nx) as usize))
                    .fold(shift(i, i), f64::max);
                sum += if delta <= 1.0 {
                    pairs(1)
                        .map(|(nx, ny)| {
                            let j = (ny * width + nx) as usize;
                            shift(i, j) * squared(here, pixel(nx, ny))
                        })
                        .sum::<f64>()
                } else if delta >= f64::from(width.max(height)) {
                    // Beyond the image, a pixel may show anything.
                    3.0 * 255.0 * 255.0
                } else {
                    let mut k = 1;
                    let mut largest: f64 = 0.0;
                    while f64::from(k) < 2.0 * delta {
                        let steps: f64 =
                            pairs(k).map(|(nx, ny)| squared(here, pixel(nx, ny))).sum();
                        largest = largest.max(steps);
                        k *= 2;
                    }
                    largest
                };
            }
        }
        sum / (3.0 * f64::from(width) * f64::from(height))
    }

    /// The share of pixels whose primary ray may hit another object when the edge between each
    /// pixel p and its neighbour q moves by `shift(p, q)` pixels: a δ share of those next to a
    /// boundary between objects, and every one within the largest δ of one.
    fn mismatched(&self, shift: impl Fn(usize, usize) -> f64) -> f64 {
        let (width, height) = self.image.dimensions();
        let (w, h) = (width as usize, height as usize);
        let neighbours = |i: usize| {
            let (x, y) = (i % w.max(1), i / w.max(1));
            [
                (x > 0).then(|| i - 1),
                (x + 1 < w).then(|| i + 1),
                (y > 0).then(|| i - w),
                (y + 1 < h).then(|| i + w),
            ]
            .into_iter()
            .flatten()
        };
        let objects = &self.objects;
        let edge = |i: usize| {
            neighbours(i)
                .filter(|&j| objects.get(j) != objects.get(i))
                .map(|j| shift(i, j))
                .fold(0.0, f64::max)
        };
        let farthest = (0..self.structure.boundary.len())
            .map(edge)
            .fold(0.0, f64::max);
        let share: f64 = self
            .structure
            .boundary
            .iter()
            .enumerate()
            .map(|(i, &distance)| {
                if distance == 0 {
                    edge(i).min(1.0)
                } else if f64::from(distance) < farthest {
                    1.0
                } else {
                    0.0
                }
            })
            .sum();
        share / self.structure.boundary.len().max(1) as f64
    }
}

/// How much an image changes when it moves: its mean squared difference of neighbouring pixels
/// (across and below), and each pixel's distance from a boundary between objects.
#[derive(Clone, Debug, PartialEq)]
pub struct Structure {
    /// G: the mean squared difference of neighbouring pixels, in 8-bit levels².
    edge_energy: f64,
    /// Each pixel's distance, in pixels, from the nearest pixel next to another object.
    boundary: Vec<u32>,
}

impl Structure {
    fn of(image: &RgbImage, objects: &[Option<usize>]) -> Self {
        let (width, height) = image.dimensions();
        Self {
            edge_energy: structure_function(image, 1),
            boundary: boundary_distance(objects, width, height),
        }
    }

    /// G: the mean squared difference of neighbouring pixels.
    pub fn edge_energy(&self) -> f64 {
        self.edge_energy
    }
}

/// D(k): see [`Structure`].
fn structure_function(image: &RgbImage, k: u32) -> f64 {
    let (width, height) = image.dimensions();
    let mut sum = 0.0;
    for y in 0..height {
        for x in 0..width {
            let here = image.get_pixel(x, y).0;
            for (nx, ny) in [(x + k, y), (x, y + k)] {
                if nx < width && ny < height {
                    let there = image.get_pixel(nx, ny).0;
                    sum += here
                        .iter()
                        .zip(there)
                        .map(|(&a, b)| (f64::from(a) - f64::from(b)).powi(2))
                        .sum::<f64>();
                }
            }
        }
    }
    sum / (3.0 * f64::from(width) * f64::from(height))
}

/// Each pixel's distance, in pixels (the larger of across and down), from the nearest pixel
/// next to a boundary between objects: 0 for such a pixel, by two passes of a chamfer
/// transform.
fn boundary_distance(objects: &[Option<usize>], width: u32, height: u32) -> Vec<u32> {
    let (w, h) = (width as usize, height as usize);
    let at = |x: usize, y: usize| objects.get(y * w + x).copied().flatten();
    let mut distance = vec![u32::MAX; w * h];
    for y in 0..h {
        for x in 0..w {
            let here = at(x, y);
            let boundary = (x > 0 && at(x - 1, y) != here)
                || (x + 1 < w && at(x + 1, y) != here)
                || (y > 0 && at(x, y - 1) != here)
                || (y + 1 < h && at(x, y + 1) != here);
            if boundary {
                distance[y * w + x] = 0;
            }
        }
    }
    let relax = |distance: &mut Vec<u32>, x: usize, y: usize, nx: usize, ny: usize| {
        let through = distance[ny * w + nx].saturating_add(1);
        if through < distance[y * w + x] {
            distance[y * w + x] = through;
        }
    };
    for y in 0..h {
        for x in 0..w {
            for (dx, dy) in [(-1, 0), (-1, -1), (0, -1), (1, -1)] {
                let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                if nx >= 0 && ny >= 0 && (nx as usize) < w {
                    relax(&mut distance, x, y, nx as usize, ny as usize);
                }
            }
        }
    }
    for y in (0..h).rev() {
        for x in (0..w).rev() {
            for (dx, dy) in [(1, 0), (1, 1), (0, 1), (-1, 1)] {
                let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                if nx >= 0 && (nx as usize) < w && (ny as usize) < h {
                    relax(&mut distance, x, y, nx as usize, ny as usize);
                }
            }
        }
    }
    distance
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
    format.run(Job(desc, methods, reference))
}

fn predict_in<S: Scalar>(
    desc: &SceneDesc<'_>,
    methods: Methods,
    reference: &Reference,
) -> Result<Prediction> {
    let (width, height) = reference.image.dimensions();
    // The format's constants and tolerances alone: f64 arithmetic on its stored values, by the
    // methods' exact roots (their error is the rounding's, below).
    let constants = Prepared::<Quantized<S>>::new(&Request {
        desc,
        width,
        height,
        methods: exact_roots(methods),
    })?;
    let measured = accuracy(
        &constants.render(1, None)?,
        &reference.image,
        &constants.object_map()?,
        &reference.objects,
    );
    let constants_mse = mse(measured.psnr_db);
    let pixel = pixel_angle(desc, width, height);
    let global_angle = global_angle::<S>(desc, &methods, width, height);
    let global = EVEN * global_angle / pixel;
    let shifts: Vec<Shifts> = object_shifts::<S>(desc, &methods, pixel, global_angle)
        .into_iter()
        .map(|shift| Shifts {
            silhouette: EVEN * shift.silhouette,
            inner: EVEN * shift.inner,
        })
        .collect();
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
                let bit = 1 << object.min(63);
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
    let shading_levels = EVEN * 255.0 * shading_error::<S>(desc);
    // Rounding a colour that errs by e levels to the nearest level changes it by one level in
    // an e share of pixels.
    let shading_mse = shading_levels * shading_levels + shading_levels.min(1.0);
    let total = constants_mse + reference.moved(shift) + shading_mse;
    let mismatch_pct = measured.object_mismatch_pct + 100.0 * reference.mismatched(shift);
    Ok(Prediction {
        psnr_db: psnr(total),
        mismatch_pct: mismatch_pct.min(100.0),
        constants_mse,
        shift_px,
        shading_levels,
    })
}

/// The mean squared error, in levels², of a PSNR in dB.
fn mse(psnr_db: f64) -> f64 {
    255.0 * 255.0 / 10_f64.powf(psnr_db / 10.0)
}

/// The PSNR, in dB, of a mean squared error in levels².
fn psnr(mse: f64) -> f64 {
    if mse > 0.0 {
        10.0 * (255.0 * 255.0 / mse).log10()
    } else {
        f64::INFINITY
    }
}

/// The smallest angle between neighbouring pixels' rays: at the image's corner, where the
/// image plane is seen most obliquely.
fn pixel_angle(desc: &SceneDesc<'_>, width: u32, height: u32) -> f64 {
    let half_height = (f64::from(desc.camera.vfov_degrees).to_radians() / 2.0).tan();
    let half_width = half_height * f64::from(width) / f64::from(height);
    let (corner, _) = range::camera(half_width, half_height, width, height);
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
    let world = f64::from(desc.far);
    let nearest = extents(desc).nearest.max(f64::MIN_POSITIVE);
    let step = S::UNIT_ERROR;
    // A point rounds at its own size, seen from as far: largest for the nearest.
    let _ = world;
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

/// How far format `S`'s rounding may move an object's edges, in pixels: the share of a pixel
/// an edge moves by where the object is larger than a pixel, and where it is smaller (a
/// checkerboard's squares far away, a sphere in the distance), the share of its own size, which
/// is the chance that a pixel's one sample lands on the other side.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Shifts {
    /// Its silhouette (its edge against what is behind it).
    silhouette: f64,
    /// The edges within it (a checkerboard's, those seen through it).
    inner: f64,
}

/// Each object's [`Shifts`] in format `S`, for pixels `pixel` radians apart and a global
/// rounding of `global` radians (see the module documentation).
fn object_shifts<S: Scalar>(
    desc: &SceneDesc<'_>,
    methods: &Methods,
    pixel: f64,
    global: f64,
) -> Vec<Shifts> {
    let world = f64::from(desc.far);
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
    for feature in range::features(desc, methods) {
        let Item::Object(i) = feature.item else {
            continue;
        };
        let (Some(object), Some(shift)) = (desc.objects.get(i), shifts.get_mut(i)) else {
            continue;
        };
        let seen = range::clearance(object, eye).max(nearest);
        let error = feature.error::<S>();
        let sides = |vertices: [[f32; 3]; 3]| {
            let [a, b, c] = vertices.map(Vec3::from_f32);
            let longest = (b - a).length().max((c - a).length()).max((c - b).length());
            (longest, (b - a).cross(c - a).length() / longest)
        };
        // An angle over the larger of a pixel and the feature's own angular size.
        let share = |angle: f64, size: f64| angle / pixel.min(size);
        match (object.shape, feature.quantity) {
            // The silhouette moves by the discriminant's error over 2r, seen from the eye.
            (ShapeDesc::Sphere { center, radius }, "radius² seen from the eye") => {
                let r = f64::from(radius);
                let from_eye = (Vec3::from_f32(center) - eye).length().max(nearest);
                shift.silhouette += share(error / (2.0 * r * from_eye), r / from_eye);
            }
            // An edge moves by the determinant's error over the edge's length.
            (ShapeDesc::Triangle { vertices }, "twice the triangle's area") => {
                let (longest, height) = sides(vertices);
                shift.silhouette += share(error / (longest * seen), height / seen);
            }
            // Möller–Trumbore's 1/det errs relatively by its rounding over itself, and so do
            // the barycentric coordinates, moving an edge by that share of the triangle.
            (ShapeDesc::Triangle { vertices }, "Möller–Trumbore's 1/det, against its rounding") =>
            {
                let (longest, height) = sides(vertices);
                let angle = error / feature.value * longest / seen;
                shift.silhouette += share(angle, height / seen);
            }
            // A checker coordinate, counted in squares, errs by its rounding at that size and
            // by where the point was put: the global rounding along a ray across the world, and
            // the point's own rounding. Near, that moves the edges by a share of a pixel; where
            // the squares are smaller than a pixel, by that share of a square.
            (
                ShapeDesc::Plane {
                    checker: Some(checker),
                    ..
                },
                "checker square size",
            ) => {
                let size = f64::from(checker.size);
                let near = seen / size + 1.0;
                let edge = size * S::resolution(near) / seen;
                let across = 2.0 * world;
                let squares = (across * global + S::resolution(across)) / size
                    + S::resolution(across / size + 1.0);
                shift.inner += (edge / pixel).max(2.0 * squares);
            }
            _ => {}
        }
    }
    shifts
}

/// How far format `S`'s rounding may move a pixel's colour, as a share of full intensity: the
/// rounding of Lambert's cosine times the diffuse weight, times the light that reaches a
/// surface, and the rounding of the colour's products and sums, over every level of the ray
/// tree. (The highlights' rounding is in the render of the constants.)
fn shading_error<S: Scalar>(desc: &SceneDesc<'_>) -> f64 {
    let cosine = COSINE_STEPS * S::UNIT_ERROR;
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
    levels * (light * local + COLOUR_STEPS * S::resolution(colour.max(1.0)) * colour)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_known_image_moved_by_a_known_shift() {
        // A vertical edge: black | white, two pixels wide, one high.
        let mut image = RgbImage::new(2, 1);
        image.put_pixel(1, 0, image::Rgb([255, 255, 255]));
        let reference = Reference::new(image, vec![Some(0), Some(1)], vec![1, 2]);
        // One pair across, 255² in each of three channels, over 2 pixels × 3 channels.
        assert!((reference.structure.edge_energy() - 255.0 * 255.0 / 2.0).abs() < 1e-9);
        // Half a pixel's move changes half of that; both pixels are next to the boundary.
        assert!((reference.moved(|_, _| 0.5) - 255.0 * 255.0 / 4.0).abs() < 1e-9);
        assert!((reference.mismatched(|_, _| 0.5) - 0.5).abs() < 1e-9);
        // Beyond the image, a pixel may show anything.
        assert!((reference.moved(|_, _| 3.0) - 255.0 * 255.0).abs() < 1e-9);
        assert!((reference.mismatched(|_, _| 3.0) - 1.0).abs() < 1e-9);
        assert!(reference.moved(|_, _| 0.0).abs() < 1e-9);
    }

    #[test]
    fn boundary_distances_grow_away_from_the_edge() {
        // Object 0 on the left three columns, object 1 on the right three, two rows.
        let objects: Vec<Option<usize>> = (0..12).map(|i| Some(usize::from(i % 6 >= 3))).collect();
        let distance = boundary_distance(&objects, 6, 2);
        assert_eq!(distance, [2, 1, 0, 0, 1, 2, 2, 1, 0, 0, 1, 2]);
    }
}
