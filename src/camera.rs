//! [`Camera`]: the pinhole camera of the lecture, which turns a pixel into a primary ray
//! r(t) = e + t·(s − e) through the pixel's centre s on the image plane; and its [`Lens`], a
//! thin lens about the eye that starts each of a pixel's rays from another point of it, aimed
//! at the point the pinhole's ray meets on the focal plane (depth of field).

crate::phase::declare_phase!(Some(crate::phase::Phase::Camera));

use crate::desc::CameraDesc;
use crate::methods::{Methods, RayMethod, RootMethod};
use crate::ray::Ray;
use crate::scalar::{Bits, Scalar};
use crate::scalar::{FAST_ROOT_ERROR, REACH_ERRORS};
use crate::uses::Uses;
use crate::vec3::Vec3;
use crate::words::{self, WordsError};

/// The largest image side: it keeps every pixel coordinate exact in every format.
pub const MAX_IMAGE_SIDE: u32 = 8192;

/// A camera, pinhole or through a lens, for one image size. Coordinates are relative to the
/// eye, which is at the origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera<S> {
    width: u32,
    height: u32,
    /// s for the image's top-left corner (not a pixel centre), one unit in front of the eye.
    top_left: Vec3<S>,
    /// From the left edge of the image plane to the right edge.
    across: Vec3<S>,
    /// From the top edge to the bottom edge.
    down: Vec3<S>,
    /// One pixel across: `across` / width, for the samples within a pixel.
    pixel_across: Vec3<S>,
    /// One pixel down: `down` / height.
    pixel_down: Vec3<S>,
    lens: Option<Lens<S>>,
    /// The image plane, for culling ([`crate::cull`]); `None` through a lens.
    plane: Option<ImagePlane>,
    rays: RayMethod,
    roots: RootMethod,
}

crate::words::words_of_struct!(Camera<S> {
    width,
    height,
    top_left,
    across,
    down,
    pixel_across,
    pixel_down,
    lens,
    plane,
    rays,
    roots
});

/// A thin lens of radius A about the eye, focused on the plane f ahead (Cook, Porter and
/// Carpenter, 1984). A point (a, b) of the unit disc is the lens point o = A·(a·right + b·up);
/// the pinhole's ray through s on the image plane (one unit ahead) meets the focal plane at f·s,
/// so o's ray there has the direction f·s − o, or, divided by f, s − (A/f)·(a·right + b·up).
/// Every ray through one point of the focal plane meets there whichever the lens point: the
/// plane is sharp, and a point off it spreads over a disc that grows with A.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lens<S> {
    /// A·right and A·up: the lens point of (a, b) is a·across + b·up.
    across: Vec3<S>,
    up: Vec3<S>,
    /// The same over f: how far the lens point of (a, b) turns its ray on the image plane.
    tilt_across: Vec3<S>,
    tilt_up: Vec3<S>,
}

crate::words::words_of_struct!(Lens<S> {
    across,
    up,
    tilt_across,
    tilt_up
});

/// A coordinate on the image plane in units of 2⁻³² of its half height h = tan(vfov / 2): a
/// coordinate c as c / h · 2³², clamped to ±[`COORDINATE_LIMIT`]. In these units pixel x of an
/// image W × H pixels spans a from (2x − W)/H to (2x + 2 − W)/H, and row y spans b from
/// (H − 2y − 2)/H to (H − 2y)/H (the image is 2h high and 2h·W/H wide).
pub type Coordinate = i64;

/// 2³²: a [`Coordinate`]'s units per half height.
pub(crate) const UNITS: f64 = 4_294_967_296.0;

/// The largest [`Coordinate`], 2¹⁶ half heights: beyond the widest image (8 192 half heights
/// across), and small enough that a coordinate times an image side (up to 2¹³) and a few of
/// their sums fit an `i64`.
pub const COORDINATE_LIMIT: Coordinate = 1 << 48;

/// `x` half heights as a [`Coordinate`], rounded by `round` (`libm::floor`, `libm::ceil` or
/// `libm::round`) and clamped to ±[`COORDINATE_LIMIT`].
pub(crate) fn coordinate(x: f64, round: fn(f64) -> f64) -> Coordinate {
    let limit = COORDINATE_LIMIT as f64;
    #[allow(
        clippy::cast_possible_truncation,
        reason = "clamped to ±2⁴⁸, an integer"
    )]
    let units = round(x * UNITS).clamp(-limit, limit) as Coordinate;
    units
}

/// The range `[low, high]` of half heights as [`Coordinate`]s, rounded outwards and one unit
/// further, for the rounding of the quotient that gave them.
pub(crate) fn outwards([low, high]: [f64; 2]) -> [Coordinate; 2] {
    [
        coordinate(low, libm::floor).saturating_sub(1),
        coordinate(high, libm::ceil).saturating_add(1),
    ]
}

/// A camera's image plane, for turning bounds into the pixel ranges of rows ([`crate::cull`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ImagePlane {
    /// The image's width in pixels, W.
    pub(crate) width: u32,
    /// The image's height in pixels, H.
    pub(crate) height: u32,
    /// How far a primary ray may be from where its pixel says, on the image plane, in
    /// [`Coordinate`] units, rounded up.
    pub(crate) slack: Coordinate,
}

crate::words::words_of_struct!(ImagePlane {
    width,
    height,
    slack
});

impl ImagePlane {
    /// The image plane of half height `half_height` (a unit from the eye) of an image of
    /// `width × height` pixels (each in 1..=[`MAX_IMAGE_SIDE`]), whose rays'
    /// directions are off by at most `aim_error(corner)`, an angle, with `corner` the distance
    /// of the plane's corner.
    #[must_use]
    pub(crate) fn new(
        half_height: f64,
        width: u32,
        height: u32,
        aim_error: impl FnOnce(f64) -> f64,
    ) -> Self {
        // A direction off by an angle θ meets the plane up to θ·|s|² away, |s| at most the
        // image's corner.
        let half_width = half_height * f64::from(width) / f64::from(height);
        let corner_squared = 1.0 + half_width * half_width + half_height * half_height;
        let slack = REACH_ERRORS * aim_error(libm::sqrt(corner_squared)) * corner_squared;
        Self {
            width,
            height,
            slack: coordinate(slack / half_height, libm::ceil).saturating_add(1),
        }
    }
}

/// The camera's frame in double precision: where it looks and how wide, per unit distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Frame {
    pub(crate) forward: Vec3<f64>,
    pub(crate) right: Vec3<f64>,
    pub(crate) up: Vec3<f64>,
    /// tan(vfov / 2): half the image plane's height one unit ahead.
    pub(crate) half_height: f64,
    /// The lens's radius (0 for a pinhole) and its focus distance.
    pub(crate) aperture: f64,
    pub(crate) focus: f64,
}

crate::words::words_of_struct!(Frame {
    forward,
    right,
    up,
    half_height,
    aperture,
    focus
});

/// tan x for 0 < x < π/2 (half a field of view): beyond π/4 as cot(π/2 − x), π/2 − x taken
/// with π/2 to twice f64's precision, so that a field of view near 180° loses nothing; the
/// sine and cosine of an angle up to π/4 from their Taylor series to the terms in x²¹, below
/// 10⁻¹⁹ there. To a few units in the last place, where `libm`'s tan, which reduces any
/// argument, took some 4 KB of a firmware's flash.
fn tan(x: f64) -> f64 {
    /// π/2 − `FRAC_PI_2`.
    const FRAC_PI_2_LOW: f64 = 6.123_233_995_736_766e-17;
    let complement = x > core::f64::consts::FRAC_PI_4;
    // Exact before the low part is added: x is within a factor of 2 of π/2 (Sterbenz).
    let y = if complement {
        (core::f64::consts::FRAC_PI_2 - x) + FRAC_PI_2_LOW
    } else {
        x
    };
    let minus_y2 = -y * y;
    let (mut sin, mut cos, mut sin_term, mut cos_term) = (y, 1.0, y, 1.0);
    for k in 1..=10 {
        let n = f64::from(2 * k);
        cos_term *= minus_y2 / ((n - 1.0) * n);
        sin_term *= minus_y2 / (n * (n + 1.0));
        cos += cos_term;
        sin += sin_term;
    }
    if complement { cos / sin } else { sin / cos }
}

impl Frame {
    /// The orthonormal frame of a camera description, or `None` when the view direction is
    /// zero or parallel to `up` (the scene build reports which).
    pub(crate) fn new(desc: &CameraDesc) -> Option<Self> {
        let forward = (Vec3::from_f32(desc.look_at) - Vec3::from_f32(desc.eye)).direction()?;
        let right = forward.cross(Vec3::from_f32(desc.up)).direction()?;
        let up = right.cross(forward);
        let half_height = tan(f64::from(desc.vfov_degrees).to_radians() / 2.0);
        let focus = desc.focus_distance.map_or_else(
            || (Vec3::from_f32(desc.look_at) - Vec3::from_f32(desc.eye)).length(),
            f64::from,
        );
        Some(Self {
            forward,
            right,
            up,
            half_height,
            aperture: f64::from(desc.aperture),
            focus,
        })
    }

    /// How far the lens's edge turns a ray on the image plane one unit ahead: A/f (0 for a
    /// pinhole).
    pub(crate) fn lens_tilt(&self) -> f64 {
        if self.aperture > 0.0 {
            self.aperture / self.focus
        } else {
            0.0
        }
    }

    /// Half the image plane's width one unit ahead, for an image of this size.
    pub(crate) fn half_width(&self, width: u32, height: u32) -> f64 {
        self.half_height * f64::from(width) / f64::from(height)
    }
}

impl<S: Bits> Camera<S> {
    /// Writes the camera as words to `sink` (as [`ProvenScene`](crate::ProvenScene) holds them): what a firmware's build keeps
    /// as constants of a camera it has made from a proven scene ([`crate::Scene::camera`]).
    pub fn write_words(&self, sink: &mut dyn FnMut(u32)) {
        words::write::<S>("camera", self, sink);
    }

    /// The camera [`Self::write_words`] wrote in format `S`.
    ///
    /// # Errors
    /// When `words` are not such a camera's.
    pub fn from_words(words: &[u32]) -> Result<Self, WordsError> {
        words::read::<S, _>("camera", words)
    }
}

impl<S: Scalar> Camera<S> {
    /// The camera of `frame` for an image of `width × height` pixels (each in
    /// 1..=[`MAX_IMAGE_SIDE`], which the caller has checked), generating rays by `methods`, or
    /// `None` if its image plane does not fit format `S`.
    pub(crate) fn new(frame: &Frame, width: u32, height: u32, methods: &Methods) -> Option<Self> {
        let half_width = frame.half_width(width, height);
        let top_left = frame.forward - frame.right * half_width + frame.up * frame.half_height;
        // The range proof has checked that the format resolves the lens's radius and tilt.
        let lens = if frame.aperture > 0.0 {
            let tilt = frame.lens_tilt();
            Some(Lens {
                across: (frame.right * frame.aperture).convert()?,
                up: (frame.up * frame.aperture).convert()?,
                tilt_across: (frame.right * tilt).convert()?,
                tilt_up: (frame.up * tilt).convert()?,
            })
        } else {
            None
        };
        let plane = lens.is_none().then(|| {
            ImagePlane::new(frame.half_height, width, height, |corner| {
                aim_error::<S>(corner, width, methods)
            })
        });
        Some(Self {
            width,
            height,
            plane,
            top_left: top_left.convert()?,
            across: (frame.right * (2.0 * half_width)).convert()?,
            down: (frame.up * (-2.0 * frame.half_height)).convert()?,
            pixel_across: (frame.right * (2.0 * half_width / f64::from(width))).convert()?,
            pixel_down: (frame.up * (-2.0 * frame.half_height / f64::from(height))).convert()?,
            lens,
            rays: methods.rays,
            roots: methods.roots,
        })
    }

    /// The image width in pixels.
    #[must_use]
    pub const fn width(&self) -> u32 {
        self.width
    }

    /// The image height in pixels.
    #[must_use]
    pub const fn height(&self) -> u32 {
        self.height
    }

    /// The image plane, for culling ([`crate::cull`]); `None` through a lens, whose rays
    /// start away from the eye.
    #[must_use]
    pub(crate) const fn image_plane(&self) -> Option<&ImagePlane> {
        self.plane.as_ref()
    }

    /// What of the tracer the camera uses ([`Uses`]): its methods for rays and roots, and its
    /// lens.
    #[must_use]
    pub fn uses(&self) -> Uses {
        let lens = if self.lens.is_some() {
            Uses::LENS
        } else {
            Uses::NOTHING
        };
        Uses::method(self.rays)
            .union(Uses::method(self.roots))
            .union(lens)
    }

    /// The camera as a tracer of the parts `uses` takes it, which has checked that the camera
    /// needs no other ([`Self::uses`]): each method of which `uses` holds one is that method, a
    /// constant, and without [`Uses::LENS`] it has no lens.
    #[inline(always)]
    #[must_use]
    pub(crate) fn narrowed(&self, uses: Uses) -> Self {
        Self {
            rays: uses.only().unwrap_or(self.rays),
            roots: uses.only().unwrap_or(self.roots),
            lens: if uses.contains(Uses::LENS) {
                self.lens
            } else {
                None
            },
            ..*self
        }
    }

    /// The lens, or `None` for a pinhole.
    #[must_use]
    pub const fn lens(&self) -> Option<&Lens<S>> {
        self.lens.as_ref()
    }

    /// Row y of the image (counting down from the top), ready to give its pixels' rays, or
    /// `None` below the image.
    ///
    /// ```
    /// use obscura::{Scene, scenes};
    ///
    /// let camera = Scene::<f32, 8, 4, 6>::build(&scenes::WHITTED)?.camera(32, 24)?;
    /// assert_eq!(camera.row(23).map(|row| row.rays().count()), Some(32));
    /// assert!(camera.row(24).is_none());
    /// # Ok::<(), obscura::SceneError>(())
    /// ```
    #[must_use]
    pub fn row(&self, y: u32) -> Option<Row<S>> {
        (y < self.height).then(|| Row {
            start: self
                .top_left
                .add_scaled(self.down, pixel_centre::<S>(y, self.height, self.roots)),
            camera: *self,
        })
    }

    /// The primary ray through the centre of pixel (x, y), computed for that pixel alone
    /// (whichever [`RayMethod`] the camera's rows use), or `None` outside the image.
    #[must_use]
    pub fn ray(&self, x: u32, y: u32) -> Option<Ray<S>> {
        self.row(y)?.ray(x)
    }

    /// The primary ray through the point `offset` (across, down) pixels from the centre of pixel
    /// (x, y) — a sample within the pixel, or beside it — or `None` when (x, y) is outside the
    /// image. An offset of zero is [`Self::ray`].
    #[must_use]
    pub fn ray_offset(&self, x: u32, y: u32, offset: [S; 2]) -> Option<Ray<S>> {
        self.row(y)?.ray_offset(x, offset)
    }

    /// The ray from the lens point `lens` (a point of the unit disc) through
    /// the focal plane where the pinhole's ray through `offset` from pixel (x, y)'s centre
    /// meets it: [`Self::ray_offset`] for a pinhole, or `None` outside the image.
    #[must_use]
    pub fn ray_through_lens(&self, x: u32, y: u32, offset: [S; 2], lens: [S; 2]) -> Option<Ray<S>> {
        self.row(y)?.ray_through_lens(x, offset, lens)
    }
}

/// One row of a camera's image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row<S> {
    /// s at the left edge of the row, at its vertical centre.
    start: Vec3<S>,
    camera: Camera<S>,
}

impl<S: Scalar> Row<S> {
    /// The primary ray through the centre of pixel x: with e at the origin and
    /// s = top_left + down·(y + ½)/height + across·(x + ½)/width, the direction is
    /// (s − e)/|s − e|. Each fraction is one exact ratio, so no error accumulates along a row.
    /// `None` beyond the row's end.
    #[must_use]
    pub fn ray(&self, x: u32) -> Option<Ray<S>> {
        (x < self.camera.width).then(|| {
            let fx = pixel_centre::<S>(x, self.camera.width, self.camera.roots);
            self.through(self.start.add_scaled(self.camera.across, fx))
        })
    }

    /// The primary ray through the point `offset` (across, down) pixels from the centre of
    /// pixel x (see [`Camera::ray_offset`]), or `None` beyond the row's end.
    #[must_use]
    pub fn ray_offset(&self, x: u32, offset: [S; 2]) -> Option<Ray<S>> {
        Some(self.through(self.beside(self.centre(x)?, offset)))
    }

    /// The ray from lens point `lens` through the focal plane where the pinhole's ray through
    /// `offset` from pixel x's centre meets it (see [`Camera::ray_through_lens`]), or `None`
    /// beyond the row's end.
    #[must_use]
    pub fn ray_through_lens(&self, x: u32, offset: [S; 2], lens: [S; 2]) -> Option<Ray<S>> {
        Some(self.sample(self.centre(x)?, offset, lens))
    }

    /// Pixel x's centre on the image plane, s = top_left + down·(y + ½)/height +
    /// across·(x + ½)/width, or `None` beyond the row's end: where a pixel's samples start.
    #[must_use]
    pub fn centre(&self, x: u32) -> Option<Vec3<S>> {
        let camera = &self.camera;
        (x < camera.width).then(|| {
            let fx = pixel_centre::<S>(x, camera.width, camera.roots);
            self.start.add_scaled(camera.across, fx)
        })
    }

    /// The ray through the point `offset` (across, down) pixels from `centre`, a pixel's
    /// [`Self::centre`]: from the eye, or through a lens from lens point `lens` (see
    /// [`Camera::ray_through_lens`]).
    #[must_use]
    pub fn sample(&self, centre: Vec3<S>, offset: [S; 2], [a, b]: [S; 2]) -> Ray<S> {
        let s = self.beside(centre, offset);
        let Some(lens) = &self.camera.lens else {
            return self.through(s);
        };
        let origin = (lens.across * a).add_scaled(lens.up, b);
        let aim = s - (lens.tilt_across * a).add_scaled(lens.tilt_up, b);
        Ray::new(origin, aim.normalized(self.camera.roots))
    }

    /// The point of the image plane `offset` (across, down) pixels from `centre`.
    fn beside(&self, centre: Vec3<S>, [across, down]: [S; 2]) -> Vec3<S> {
        centre
            .add_scaled(self.camera.pixel_across, across)
            .add_scaled(self.camera.pixel_down, down)
    }

    /// The row of the camera [`Camera::narrowed`] to `uses`.
    #[inline(always)]
    #[must_use]
    pub(crate) fn narrowed(&self, uses: Uses) -> Self {
        Self {
            camera: self.camera.narrowed(uses),
            ..*self
        }
    }

    /// The camera the row is of.
    #[must_use]
    pub const fn camera(&self) -> &Camera<S> {
        &self.camera
    }

    /// Whether the camera has a lens (see [`Camera::lens`]).
    #[must_use]
    pub const fn has_lens(&self) -> bool {
        self.camera.lens.is_some()
    }

    /// The primary rays of the row's pixels, left to right, by the camera's [`RayMethod`].
    #[must_use]
    pub fn rays(self) -> Rays<S> {
        Rays {
            points: self.points(),
        }
    }

    /// The points of the image plane the row's primary rays pass through, left to right, by
    /// the camera's [`RayMethod`]: each pixel's s, before [`Self::through`] normalises it.
    #[must_use]
    pub(crate) fn points(self) -> Points<S> {
        let width = self.camera.width;
        let roots = self.camera.roots;
        // Stepping starts half a pixel in and adds a whole one each time.
        let first = self
            .start
            .add_scaled(self.camera.across, pixel_centre::<S>(0, width, roots));
        let step = self.camera.across
            * roots.div(
                S::ONE,
                S::from_int(i32::try_from(width).unwrap_or(i32::MAX)),
            );
        let centres = (self.camera.rays == RayMethod::PerPixel && roots == RootMethod::Exact)
            .then(|| Centres::new(width))
            .flatten();
        Points {
            row: self,
            x: 0,
            s: first,
            step,
            centres,
        }
    }

    /// The coordinate `axis` (0, 1, 2: x, y, z) of every point of the row, where the row does
    /// not move along it (the camera's `across` is exactly 0 there: a level camera's rows, on
    /// the vertical axis), or `None`.
    #[must_use]
    pub(crate) fn level(&self, axis: usize) -> Option<S> {
        (self.camera.across.get(axis) == Some(S::ZERO))
            .then(|| self.start.get(axis))
            .flatten()
    }

    /// The row's two ends on the image plane, its left edge and its right: every point of the
    /// row lies between them.
    #[must_use]
    pub(crate) fn ends(&self) -> [Vec3<S>; 2] {
        [self.start, self.start + self.camera.across]
    }

    /// The primary ray through the image-plane point `s`: from the eye along s/|s|.
    #[must_use]
    pub(crate) fn through(&self, s: Vec3<S>) -> Ray<S> {
        Ray::new(Vec3::ZERO, s.normalized(self.camera.roots))
    }
}

/// The primary rays of one row, left to right (see [`Row::rays`]).
#[derive(Clone, Copy, Debug)]
pub struct Rays<S> {
    points: Points<S>,
}

impl<S: Scalar> Iterator for Rays<S> {
    type Item = Ray<S>;

    #[inline(always)]
    fn next(&mut self) -> Option<Ray<S>> {
        let s = self.points.next()?;
        Some(self.points.row.through(s))
    }
}

/// The image-plane points of one row's primary rays, left to right (see [`Row::points`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Points<S> {
    row: Row<S>,
    x: u32,
    /// The stepped point on the image plane.
    s: Vec3<S>,
    step: Vec3<S>,
    /// The per-pixel rays' centres, stepped exactly where the format allows.
    centres: Option<Centres<S>>,
}

impl<S: Scalar> Iterator for Points<S> {
    type Item = Vec3<S>;

    #[inline(always)]
    fn next(&mut self) -> Option<Vec3<S>> {
        if self.x >= self.row.camera.width {
            return None;
        }
        let s = match self.row.camera.rays {
            RayMethod::PerPixel => {
                let fx = match &mut self.centres {
                    Some(centres) => centres.next(),
                    None => pixel_centre::<S>(self.x, self.row.camera.width, self.row.camera.roots),
                };
                self.row.start.add_scaled(self.row.camera.across, fx)
            }
            RayMethod::Stepped => {
                let s = self.s;
                self.s = self.s + self.step;
                s
            }
        };
        self.x += 1;
        Some(s)
    }
}

/// How far, as an angle in radians, a primary ray's direction in format `S` by `methods` may be
/// from the exact one through its point of an image plane `width` pixels wide whose corner is
/// `corner` from the eye: its unit vector's rounding, the rounding of the image plane's corner
/// and axes at their size, the fast roots' (in the unit vector and in the pixel's place) and,
/// when stepped, the step's rounding summed along a row; an angle errs by at most √3 times a
/// coordinate.
fn aim_error<S: Scalar>(corner: f64, width: u32, methods: &Methods) -> f64 {
    let mut unit = S::UNIT_ERROR + 4.0 * S::resolution(corner);
    if methods.roots == RootMethod::Approx {
        unit += 2.0 * FAST_ROOT_ERROR;
    }
    if methods.rays == RayMethod::Stepped {
        unit += f64::from(width) * S::resolution(corner);
    }
    libm::sqrt(3.0) * unit
}

/// (i + ½) / n = (2i + 1) / 2n for i < n ≤ [`MAX_IMAGE_SIDE`], one quotient of integers that
/// every format holds exactly (with approximate roots, to their 14 bits).
#[inline]
fn pixel_centre<S: Scalar>(i: u32, n: u32, roots: RootMethod) -> S {
    let num = i32::try_from(2 * i + 1).unwrap_or(i32::MAX);
    let den = i32::try_from(2 * n).unwrap_or(i32::MAX);
    roots.div(S::from_int(num), S::from_int(den))
}

/// The pixel centres (2i + 1)/2n of a row, i = 0, 1, …, each bit for bit the quotient
/// [`pixel_centre`] divides for it, by additions. A fixed format with f fraction bits truncates
/// (2i + 1)·2^f / 2n; adding 2·2^f to the dividend adds ⌊2^f / n⌋ units to the quotient and
/// 2·(2^f mod n) to the remainder, and one unit more where the remainder reaches 2n. A float
/// rounds its quotient to its exponent's places, which no constant step follows: it divides.
#[derive(Clone, Copy, Debug)]
struct Centres<S> {
    /// The next centre, ⌊(2i + 1)·2^f / 2n⌋ units.
    next: S,
    /// ⌊2^f / n⌋ units.
    step: S,
    /// One unit, 2^−f.
    unit: S,
    /// (2i + 1)·2^f mod 2n.
    remainder: u64,
    /// 2·2^f mod 2n.
    remainder_step: u64,
    /// 2n.
    divisor: u64,
}

impl<S: Scalar> Centres<S> {
    /// The centres across `n` pixels, or `None` for a float.
    fn new(n: u32) -> Option<Self> {
        let (_, fraction) = S::SPLIT?;
        let one = 1_u64 << fraction;
        let divisor = 2 * u64::from(n);
        Some(Self {
            next: pixel_centre::<S>(0, n, RootMethod::Exact),
            step: S::ratio(1, i32::try_from(n).ok()?),
            unit: S::from_f64(1.0 / one as f64)?,
            remainder: one % divisor,
            remainder_step: (2 * one) % divisor,
            divisor,
        })
    }

    /// The next pixel's centre.
    #[inline(always)]
    fn next(&mut self) -> S {
        let centre = self.next;
        self.next = self.next + self.step;
        self.remainder += self.remainder_step;
        if self.remainder >= self.divisor {
            self.remainder -= self.divisor;
            self.next = self.next + self.unit;
        }
        centre
    }
}

#[cfg(test)]
mod tests {
    use crate::scalar::Precision;
    #[test]
    fn the_tangent_of_half_a_field_of_view_is_libms_to_a_few_ulps() {
        for degrees in [
            0.001_f64, 1.0, 30.0, 45.0, 60.0, 90.0, 120.0, 150.0, 170.0, 179.0,
        ] {
            let x = degrees.to_radians() / 2.0;
            let (ours, reference) = (tan(x), libm::tan(x));
            assert!(
                (ours - reference).abs() <= 8.0 * f64::EPSILON * reference,
                "{degrees}°: {ours} against {reference}"
            );
        }
    }

    use super::*;
    use crate::test_util::{assert_close, for_each_format};

    const DESC: CameraDesc =
        CameraDesc::pinhole([1.0, 2.0, 3.0], [1.0, 2.0, 10.0], [0.0, 1.0, 0.0], 90.0);

    #[test]
    fn centre_pixel_looks_at_the_target_and_corners_span_the_field_of_view() {
        for_each_format!(S, {
            let frame = Frame::new(&DESC).unwrap();
            // An odd size has a pixel whose centre is the image centre.
            let camera = Camera::<S>::new(&frame, 3, 3, &Methods::LECTURE).unwrap();
            let centre = camera.ray(1, 1).unwrap();
            assert_eq!(centre.origin, Vec3::ZERO);
            assert_close(centre.dir.z, 1.0, 1e-4);
            // With vfov 90°, the top-left pixel centre of a 3×3 image is at s = (−⅔, ⅔, 1)
            // (x to the left: right = forward × up = −x for this frame).
            let corner = camera.ray(0, 0).unwrap().dir;
            let n = (2.0_f64 * 4.0 / 9.0 + 1.0).sqrt();
            assert_close(corner.x, 2.0 / 3.0 / n, 1e-4);
            assert_close(corner.y, 2.0 / 3.0 / n, 1e-4);
            assert_close(corner.z, 1.0 / n, 1e-4);
        });
    }

    #[test]
    fn a_wide_image_widens_the_horizontal_field() {
        let frame = Frame::new(&DESC).unwrap();
        let camera = Camera::<f64>::new(&frame, 4, 2, &Methods::LECTURE).unwrap();
        // vfov 90° on a 4×2 image: the plane spans 2 units vertically and 4 across, so the
        // first pixel centre is 1.5 units from the axis (right = forward × up = −x here).
        let first = camera.ray(0, 0).unwrap().dir;
        let last = camera.ray(3, 0).unwrap().dir;
        assert_close(first.x / first.z, 1.5, 1e-12);
        assert_close(last.x / last.z, -1.5, 1e-12);
        assert_close(first.y / first.z, 0.5, 1e-12);
    }

    #[test]
    fn stepped_rays_follow_the_per_pixel_ones() {
        for_each_format!(S, {
            let frame = Frame::new(&DESC).unwrap();
            let stepped = Methods {
                rays: RayMethod::Stepped,
                ..Methods::LECTURE
            };
            let per_pixel = Camera::<S>::new(&frame, 64, 8, &Methods::LECTURE).unwrap();
            let camera = Camera::<S>::new(&frame, 64, 8, &stepped).unwrap();
            let row = camera.row(3).unwrap();
            assert_eq!(row.rays().count(), 64);
            for (x, ray) in (0..64).zip(row.rays()) {
                let exact = per_pixel.ray(x, 3).unwrap().dir;
                assert_close(ray.dir.x, exact.x.to_f64(), 1e-3);
                assert_close(ray.dir.y, exact.y.to_f64(), 1e-3);
            }
            assert_eq!(
                per_pixel.row(3).unwrap().rays().collect::<Vec<_>>(),
                (0..64)
                    .map(|x| per_pixel.ray(x, 3).unwrap())
                    .collect::<Vec<_>>()
            );
        });
    }

    #[test]
    fn stepped_centres_are_the_quotients_bit_for_bit() {
        for_each_format!(S, {
            let widths = [
                1,
                2,
                3,
                7,
                63,
                64,
                100,
                240,
                320,
                1000,
                1024,
                4095,
                MAX_IMAGE_SIDE,
            ];
            // A format counts a row's pixels only while 2n fits it (i8f24: 63).
            for n in widths.into_iter().filter(|&n| f64::from(2 * n) < S::RANGE) {
                let Some(mut centres) = Centres::<S>::new(n) else {
                    assert!(S::SPLIT.is_none(), "{} {n}", S::NAME);
                    continue;
                };
                for i in 0..n {
                    let divided = pixel_centre::<S>(i, n, RootMethod::Exact);
                    assert_eq!(centres.next(), divided, "{} {i}/{n}", S::NAME);
                }
            }
        });
    }

    #[test]
    fn every_pixel_coordinate_has_a_ray_or_none() {
        for_each_format!(S, {
            let frame = Frame::new(&DESC).unwrap();
            let camera = Camera::<S>::new(&frame, 64, 8, &Methods::LECTURE).unwrap();
            for (x, y) in [(63, 7), (0, 0)] {
                assert!(camera.ray(x, y).is_some() && camera.row(y).is_some());
            }
            for (x, y) in [
                (64, 0),
                (0, 8),
                (u32::MAX, 0),
                (0, u32::MAX),
                (u32::MAX, u32::MAX),
            ] {
                assert_eq!(camera.ray(x, y), None, "{x}, {y}");
                assert_eq!(camera.ray_offset(x, y, [S::ZERO; 2]), None, "{x}, {y}");
            }
            assert_eq!(camera.row(u32::MAX), None);
            assert_eq!(camera.row(0).unwrap().ray(u32::MAX), None);
        });
    }

    #[test]
    fn an_offset_ray_passes_beside_the_centre() {
        for_each_format!(S, {
            let frame = Frame::new(&DESC).unwrap();
            let camera = Camera::<S>::new(&frame, 64, 8, &Methods::LECTURE).unwrap();
            let zero = camera.ray_offset(5, 3, [S::ZERO; 2]);
            assert_eq!(zero, camera.ray(5, 3));
            // A whole pixel across and down is the next pixel's centre.
            let beside = camera.ray_offset(5, 3, [S::ONE, S::ONE]).unwrap().dir;
            let next = camera.ray(6, 4).unwrap().dir;
            assert_close(beside.x, next.x.to_f64(), 1e-4);
            assert_close(beside.y, next.y.to_f64(), 1e-4);
        });
    }

    #[test]
    fn degenerate_frames_are_rejected() {
        let parallel = CameraDesc {
            up: [0.0, 0.0, 2.0],
            ..DESC
        };
        assert_eq!(Frame::new(&parallel), None);
        let nowhere = CameraDesc {
            look_at: DESC.eye,
            ..DESC
        };
        assert_eq!(Frame::new(&nowhere), None);
    }
}
