//! The checks the stress cases share: an image against the f64 reference with a quarter-pixel
//! excuse and the epsilon method's own offsets, and the error model's band around a sphere's
//! silhouette.

use crate::metrics::accuracy;
use crate::render::HostScene;
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use obscura::camera::Row;
use obscura::methods::RootMethod;
use obscura::pattern::SampleId;
use obscura::scalar::FormatInfo;
use obscura::scene::range;
use obscura::{Methods, Ray, RayMethod, Scalar, SceneDesc, SceneError, Vec3};

/// A pixel may be off by this many 8-bit levels on a channel before it counts as wrong:
/// below it lie the rounding of smooth shading, not a wrong object, shadow or edge.
pub const TOLERANCE: u8 = 8;

/// The directions a ray is nudged in to see whether its f64 colour is stable: along the rows,
/// the columns and the diagonals.
const NUDGE_DIRECTIONS: [(f64, f64); 8] = [
    (1.0, 0.0),
    (-1.0, 0.0),
    (0.0, 1.0),
    (0.0, -1.0),
    (1.0, 1.0),
    (1.0, -1.0),
    (-1.0, 1.0),
    (-1.0, -1.0),
];

/// How far, in pixels, up to a quarter.
const NUDGE_DISTANCES: [f64; 4] = [0.25, 0.125, 0.0625, 0.03125];

/// Errors may reach this many of the error model's estimates before they count as wrong.
pub const MODEL_ERRORS: f64 = 4.0;

/// An image measured against its f64 reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageCheck {
    /// PSNR against f64 (infinite for identical images).
    pub psnr_db: f64,
    /// Pixels off by more than [`TOLERANCE`], in percent.
    pub wrong_pct: f64,
    /// Of those, the ones neither a quarter-pixel nudge of the ray nor the method's offsets
    /// excuse.
    pub unexcused: usize,
}

/// Renders `desc` at `size`×`size` in `S` by `methods` and in f64 (exact roots, a ray per pixel:
/// the ideal image), and counts the pixels off by more than [`TOLERANCE`] whose f64 colour does
/// not itself change by that much when the ray is nudged by up to a quarter pixel in some
/// direction, and which f64 does not draw within [`TOLERANCE`] of `S`'s colour when it starts
/// its secondary rays as far off their surfaces as `S` does (the epsilon method's offsets,
/// sized for `S`'s rounding, are the method's error, not the rounding's: near the critical
/// angle they decide whether a chain of internal reflections stays total).
pub fn image<S: Scalar>(
    desc: &SceneDesc<'_>,
    methods: Methods,
    size: u32,
) -> Result<ImageCheck, SceneError> {
    let scene = HostScene::<S>::build_with(desc, methods)?;
    let camera = scene.camera(size, size)?;
    let ideal = Methods {
        roots: RootMethod::Exact,
        rays: RayMethod::PerPixel,
        ..methods
    };
    let reference = HostScene::<f64>::build_with(desc, ideal)?;
    let ref_camera = reference.camera(size, size)?;
    let offset = HostScene::<f64>::build_with_tolerances_of(desc, ideal, &FormatInfo::of::<S>())?;
    // Each pixel's rays, its nudged ones too, take the pixel's pattern on an area light.
    let trace_f64 =
        |dir: Vec3<f64>, id| colour(reference.trace(Ray::new(Vec3::ZERO, dir), id).colour);
    let trace_offset =
        |dir: Vec3<f64>, id| colour(offset.trace(Ray::new(Vec3::ZERO, dir), id).colour);
    let mut got = image::RgbImage::new(size, size);
    let mut want = image::RgbImage::new(size, size);
    let mut wrong = 0;
    let mut unexcused = 0;
    for y in 0..size {
        for (x, ray) in (0..size).zip(camera.row(y).into_iter().flat_map(Row::rays)) {
            let id = SampleId { x, y, sample: 0 };
            let g = colour(scene.trace(ray, id).colour);
            let ray_at = |x, y| ref_camera.ray(x, y).map_or(Vec3::ZERO, |ray| ray.dir);
            let centre = ray_at(x, y);
            let w = trace_f64(centre, id);
            got.put_pixel(x, y, image::Rgb(g));
            want.put_pixel(x, y, image::Rgb(w));
            if off(g, w) <= TOLERANCE {
                continue;
            }
            wrong += 1;
            let across = ray_at(if x + 1 < size { x + 1 } else { x - 1 }, y) - centre;
            let down = ray_at(x, if y + 1 < size { y + 1 } else { y - 1 }) - centre;
            // Within a quarter pixel, in eight directions at four distances: near a corner of
            // a checkerboard a full quarter pixel may cross two edges at once and change
            // nothing where a shorter nudge crosses one.
            let excused = off(trace_offset(centre, id), g) <= TOLERANCE
                || NUDGE_DIRECTIONS.iter().any(|&(a, b)| {
                    NUDGE_DISTANCES.iter().any(|&distance| {
                        let nudge = across * (distance * a) + down * (distance * b);
                        let dir = (centre + nudge).normalized(RootMethod::Exact);
                        off(trace_f64(dir, id), w) > TOLERANCE
                    })
                });
            unexcused += usize::from(!excused);
        }
    }
    let pixels = (size * size) as usize;
    let no_objects = vec![None; pixels];
    let acc = accuracy(&got, &want, &no_objects, &no_objects);
    Ok(ImageCheck {
        psnr_db: acc.psnr_db,
        wrong_pct: 100.0 * wrong as f64 / pixels as f64,
        unexcused,
    })
}

/// A colour as an 8-bit image holds it.
pub(crate) fn colour<S: Scalar>(c: obscura::Rgb<S>) -> [u8; 3] {
    let q: Rgb888 = c.quantize();
    [q.r(), q.g(), q.b()]
}

/// The largest channel difference.
pub(crate) fn off(a: [u8; 3], b: [u8; 3]) -> u8 {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.abs_diff(y))
        .max()
        .unwrap_or(0)
}

/// The error model's estimate of the rounding error of the test of object `index` of `desc`
/// by `methods` in format `S`, for a ray from the eye (in the units of its feature: a
/// discriminant for a sphere, twice an area for a triangle): the object's first feature.
pub fn model_error<S: Scalar>(desc: &SceneDesc<'_>, methods: &Methods, index: usize) -> f64 {
    range::features(desc, methods)
        .find(|f| f.item == obscura::Item::Object(index))
        .map_or(0.0, |f| f.error::<S>())
}

/// The exact discriminant of a sphere test, r² − |f − (f·d)d|² with f = o − c, in f64 for the
/// ray as format `S` holds it.
pub fn discriminant<S: Scalar>(ray: &Ray<S>, center: [f64; 3], radius: f64) -> f64 {
    let exact = to_f64(ray);
    let (o, d) = (exact.origin.to_f64(), exact.dir.to_f64());
    let f: [f64; 3] = std::array::from_fn(|i| o[i] - center[i]);
    let along = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
    let l: [f64; 3] = std::array::from_fn(|i| f[i] - along * d[i]);
    radius * radius - (l[0] * l[0] + l[1] * l[1] + l[2] * l[2])
}

/// The ray as format `S` holds it, in f64 (its direction made exactly unit): the reference
/// for its own rounding.
pub fn to_f64<S: Scalar>(ray: &Ray<S>) -> Ray<f64> {
    let [ox, oy, oz] = ray.origin.to_f64();
    let [dx, dy, dz] = ray.dir.to_f64();
    Ray::new(
        Vec3::new(ox, oy, oz),
        Vec3::new(dx, dy, dz).normalized(RootMethod::Exact),
    )
}

/// The ray from the origin towards `target`, in format `S`.
pub fn towards<S: Scalar>(target: [f64; 3]) -> Option<Ray<S>> {
    let length = (target[0] * target[0] + target[1] * target[1] + target[2] * target[2]).sqrt();
    let dir = Vec3::from_f64(target.map(|c| c / length))?;
    Some(Ray::new(Vec3::ZERO, dir))
}
