//! Which objects a primary ray can meet, so that each pixel tests only those: each object's
//! [`Bound`] on the camera's image plane (the rectangle about the disc a sphere's or a
//! triangle's ball projects to, the side of its horizon a plane lies on), found once when the
//! scene is built, and for each row the [`RowRanges`] of pixels whose rays reach each bound.
//!
//! The image plane is the one a unit ahead of the eye, with coordinates (a, b) along the
//! camera's right and up from its centre: the direction forward + a·right + b·up. A bound is
//! widened until no ray outside it can meet the object whatever the tracer's rounding: a ball by
//! [`REACH_ERRORS`] of the errors with which a ray finds its object (the range proof's
//! `locating`), and every bound, row by row, by the error of a primary ray's direction (its
//! unit vector's, the image plane's rounding, fast roots', stepping's: the camera works it out
//! for its [`ImagePlane`]) and to the whole of each pixel, which its samples may reach. A lens
//! starts rays away from the eye: its rows test every object.
//!
//! The bounds are worked out in `f64` when the scene is built and kept as integers
//! ([`Coordinate`]), each rounded outwards; the rows' ranges come from them by integer
//! arithmetic alone, exact and the same on every machine, so that the host and a firmware skip
//! the same tests and a firmware needs no floating point for them.

crate::phase::declare_phase!(Some(crate::phase::Phase::Culling));

use crate::camera::{
    COORDINATE_LIMIT, Coordinate, Frame, ImagePlane, MAX_IMAGE_SIDE, coordinate, outwards,
};
use crate::desc::{MeshesDesc, ShapeDesc};
use crate::scalar::REACH_ERRORS;
use crate::vec3::Vec3;

/// Where on the camera's image plane (see [`crate::cull`]) primary rays can meet an object.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bound {
    /// Anywhere: the object surrounds the eye, or reaches beside or behind it.
    Everywhere,
    /// Nowhere: the object is behind the eye.
    Nowhere,
    /// Within the rectangle a ∈ `right`, b ∈ `up` (each a closed interval).
    Rectangle {
        /// The range of a.
        right: [Coordinate; 2],
        /// The range of b.
        up: [Coordinate; 2],
    },
    /// Where `forward` + a·`right` + b·`up` ≥ 0, less a ray's error (a and b in half heights,
    /// the terms in [`Coordinate`] units): the side of its horizon a plane lies on (n·d ≥ 0, n
    /// its normal turned to face the eye's rays towards it, divided by h).
    Side {
        /// n·forward / h, widened by the rounding of the other two.
        forward: Coordinate,
        /// n·right.
        right: Coordinate,
        /// n·up.
        up: Coordinate,
    },
}

crate::words::words_of_enum!(Bound {
    Everywhere,
    Nowhere,
    Rectangle { right, up },
    Side { forward, right, up }
});

impl Bound {
    /// The bound of `shape` for a camera at `eye` of `frame`, a sphere or a triangle widened by
    /// [`REACH_ERRORS`] times `error` (the error with which a primary ray finds it).
    #[must_use]
    pub(crate) fn of(
        shape: &ShapeDesc,
        meshes: &MeshesDesc<'_>,
        eye: Vec3<f64>,
        error: f64,
        frame: &Frame,
    ) -> Self {
        match (*shape, ball(shape, meshes, eye)) {
            (_, Some((centre, radius))) => Self::ball(centre, radius, error, frame),
            (ShapeDesc::Plane { point, normal, .. }, None) => {
                match Vec3::from_f32(normal).direction() {
                    Some(n) => Self::plane(n, n.dot(Vec3::from_f32(point) - eye), frame),
                    None => Self::Everywhere,
                }
            }
            (_, None) => Self::Everywhere,
        }
    }

    /// The bound of the ball about `centre` (relative to the eye) of `radius` plus
    /// [`REACH_ERRORS`] times `error`, as the camera of `frame` sees it.
    fn ball(centre: Vec3<f64>, radius: f64, error: f64, frame: &Frame) -> Self {
        let radius = radius + REACH_ERRORS * error;
        let (f, r, u) = (
            centre.dot(frame.forward),
            centre.dot(frame.right),
            centre.dot(frame.up),
        );
        // The direction s = forward + a·right + b·up meets the ball where s·c > 0 and
        // (s·c)² ≥ k·|s|², k = |c|² − radius² (|s|² = 1 + a² + b²: the frame is orthonormal).
        // Over b, the most a row of constant a reaches is (f + a·r)² ≥ (k − u²)(1 + a²): a
        // quadratic in a, and alike in b.
        let k = centre.dot(centre) - radius * radius;
        let (Some(right), Some(up)) = (extent(f, r, k - u * u), extent(f, u, k - r * r)) else {
            return Self::Everywhere;
        };
        match (right, up) {
            (Some(right), Some(up)) => {
                // The rectangle's centre is the ellipse's: the cone's front half, or its back.
                let middle = |[low, high]: [f64; 2]| 0.5 * (low + high);
                let h = frame.half_height;
                if f + middle(right) * r + middle(up) * u > 0.0 {
                    Self::Rectangle {
                        right: outwards(right.map(|a| a / h)),
                        up: outwards(up.map(|b| b / h)),
                    }
                } else {
                    Self::Nowhere
                }
            }
            _ => Self::Nowhere,
        }
    }

    /// The bound of the plane n·p = `offset` (relative to the eye; `normal` a unit vector), as
    /// the camera of `frame` sees it.
    fn plane(normal: Vec3<f64>, offset: f64, frame: &Frame) -> Self {
        // A ray from the eye meets the plane at t = offset / (n·d) > 0: where n·d has the
        // offset's sign.
        let n = if offset > 0.0 {
            normal
        } else if offset < 0.0 {
            -normal
        } else {
            return Self::Everywhere;
        };
        // Rounded to nearest, right and up are off by at most half a unit each, which H·a and
        // H·b (at most W and H within an image) multiply; forward, which H multiplies, is
        // widened by half of the widest image's W/H + 1 units, and one more for its quotient.
        let widening = Coordinate::from(MAX_IMAGE_SIDE / 2 + 2);
        Self::Side {
            forward: (coordinate(n.dot(frame.forward) / frame.half_height, libm::ceil) + widening)
                .min(COORDINATE_LIMIT),
            right: coordinate(n.dot(frame.right), libm::round),
            up: coordinate(n.dot(frame.up), libm::round),
        }
    }
}

/// The ball that holds `shape` (a mesh's among `meshes`), its centre relative to `eye`: a
/// sphere itself, a triangle's about its centroid through its farthest corner, a mesh's about
/// its box's centre through its farthest corner; `None` for a plane.
pub(crate) fn ball(
    shape: &ShapeDesc,
    meshes: &MeshesDesc<'_>,
    eye: Vec3<f64>,
) -> Option<(Vec3<f64>, f64)> {
    let from_eye = |p| Vec3::from_f32(p) - eye;
    match *shape {
        ShapeDesc::Sphere { center, radius } => Some((from_eye(center), f64::from(radius))),
        ShapeDesc::Triangle { vertices } => {
            let corners = vertices.map(from_eye);
            let [a, b, c] = corners;
            let centre = (a + b + c) * (1.0 / 3.0);
            let radius = corners
                .iter()
                .map(|&corner| (corner - centre).length())
                .fold(0.0, f64::max);
            Some((centre, radius))
        }
        ShapeDesc::Mesh { root } => {
            let node = meshes.nodes.get(root as usize)?;
            let (low, high) = (from_eye(node.min), from_eye(node.max));
            let centre = (low + high) * 0.5;
            let corners = meshes
                .triangles_of(root)
                .iter()
                .flat_map(|&t| meshes.corners(t));
            let radius = corners
                .map(|corner| (from_eye(corner) - centre).length())
                .fold(0.0, f64::max);
            Some((centre, radius))
        }
        ShapeDesc::Plane { .. } => None,
    }
}

/// The range of x where (f + x·g)² ≥ h·(1 + x²): `None` when it is unbounded (test
/// everywhere), `Some(None)` when it is empty.
fn extent(f: f64, g: f64, h: f64) -> Option<Option<[f64; 2]>> {
    // (g² − h)·x² + 2fg·x + (f² − h) ≥ 0.
    let (a, b, c) = (g * g - h, f * g, f * f - h);
    if h <= 0.0 || a >= 0.0 {
        return None;
    }
    let discriminant = b * b - a * c;
    if discriminant < 0.0 {
        return Some(None);
    }
    let root = libm::sqrt(discriminant);
    // a < 0: non-negative between the roots.
    Some(Some([(-b + root) / a, (-b - root) / a]))
}

/// The bit of a candidate mask ([`Candidates::at`]) that the objects from this index on share:
/// the last of a `u32`. The objects before it have a bit of their own.
pub const SHARED_BIT: usize = 31;

/// For each object of a scene, the pixels of one row whose primary rays may meet it: one range
/// per bit of [`Candidates::at`], the objects from [`SHARED_BIT`] on sharing the last.
#[derive(Clone, Debug)]
pub struct RowRanges {
    /// The first and the last pixel of each range (first > last: none).
    ranges: [(u32, u32); SHARED_BIT + 1],
    /// How many ranges are in use.
    len: usize,
}

impl RowRanges {
    /// The ranges of row `y` of the image on `plane` (`None`: every pixel may meet every
    /// object, as through a lens) for objects of `bounds`.
    #[must_use]
    pub fn new<'a>(
        bounds: impl IntoIterator<Item = &'a Bound>,
        plane: Option<&ImagePlane>,
        y: u32,
    ) -> Self {
        let mut ranges = [NONE; SHARED_BIT + 1];
        let mut len = 0;
        for (i, bound) in bounds.into_iter().enumerate() {
            let range = plane.map_or(ALL, |plane| plane.row_range(bound, y));
            // The objects from SHARED_BIT on share the last range: the span of theirs.
            if let Some(slot) = ranges.get_mut(i.min(SHARED_BIT)) {
                *slot = if i <= SHARED_BIT { range } else { hull(*slot, range) };
            }
            len = (i + 1).min(SHARED_BIT + 1);
        }
        Self { ranges, len }
    }

    /// Widens each range to hold `other`'s too: the ranges of a band of rows.
    pub(crate) fn widen(&mut self, other: &Self) {
        for (range, &wider) in self.ranges.iter_mut().zip(&other.ranges) {
            *range = hull(*range, wider);
        }
        self.len = self.len.max(other.len);
    }

    /// The objects whose ranges reach any pixel from `first` to `last`, as [`Candidates::at`]
    /// gives them.
    pub(crate) fn within(&self, first: u32, last: u32) -> u32 {
        let ranges = self.ranges.iter().take(self.len);
        (0..).zip(ranges).fold(0, |mask, (i, &(low, high))| {
            if low <= last && first <= high && low <= high {
                mask | 1 << i
            } else {
                mask
            }
        })
    }

    /// The candidates of the row's pixels from left to right: see [`Candidates`].
    #[must_use]
    pub fn candidates(&self) -> Candidates<'_> {
        Candidates {
            ranges: self.ranges.get(..self.len).unwrap_or(&[]),
            mask: 0,
            next: 0,
        }
    }
}

/// The smallest range that holds both.
fn hull(a: (u32, u32), b: (u32, u32)) -> (u32, u32) {
    match (a.0 > a.1, b.0 > b.1) {
        (true, _) => b,
        (_, true) => a,
        _ => (a.0.min(b.0), a.1.max(b.1)),
    }
}

/// A pixel range that holds every pixel.
const ALL: (u32, u32) = (0, u32::MAX);

/// A pixel range that holds none.
const NONE: (u32, u32) = (1, 0);

/// The objects each pixel of a row may meet, for pixels taken left to right: worked out again
/// only where a range starts or ends.
#[derive(Clone, Debug)]
pub struct Candidates<'a> {
    ranges: &'a [(u32, u32)],
    mask: u32,
    /// The next pixel where a range starts or ends.
    next: u32,
}

impl Candidates<'_> {
    /// The objects pixel `x`'s rays may meet: bit i for object i, objects 31 and beyond
    /// sharing bit 31 (a 32-bit mask, which the Cortex-M0 shifts in one instruction); `x` at
    /// least the last one asked for.
    #[inline]
    pub fn at(&mut self, x: u32) -> u32 {
        if x >= self.next {
            self.mask = 0;
            self.next = u32::MAX;
            for (i, &(first, last)) in self.ranges.iter().enumerate() {
                if first <= x && x <= last {
                    self.mask |= 1 << i.min(SHARED_BIT);
                    self.next = self.next.min(last.saturating_add(1));
                } else if first > x {
                    self.next = self.next.min(first);
                }
            }
        }
        self.mask
    }
}

/// ⌊n / d⌋ for d > 0.
const fn floor_div(n: i64, d: i64) -> i64 {
    n.div_euclid(d)
}

/// ⌈n / d⌉ for d > 0.
const fn ceil_div(n: i64, d: i64) -> i64 {
    -(-n).div_euclid(d)
}

impl ImagePlane {
    /// The pixels of row `y` whose rays may meet within `bound`, by integers alone: every
    /// term below is at most a side (2¹³) times a few [`COORDINATE_LIMIT`]s (2⁴⁸), well within an
    /// `i64`.
    pub(crate) fn row_range(&self, bound: &Bound, y: u32) -> (u32, u32) {
        let (w, h, slack) = (i64::from(self.width), i64::from(self.height), self.slack);
        // H·b at the row's top and bottom edges, in units.
        let unit = 1_i64 << 32;
        let top = (h - 2 * i64::from(y)) * unit;
        let bottom = top - 2 * unit;
        // The pixels whose span of a reaches [from, to], each H·a in units: pixel x spans H·a
        // from (2x − W) to (2x + 2 − W) units.
        let (first, last) = match *bound {
            Bound::Everywhere => return ALL,
            Bound::Nowhere => return NONE,
            Bound::Rectangle { right, up } => {
                if bottom > h * (up[1] + slack) || top < h * (up[0] - slack) {
                    return NONE;
                }
                let (from, to) = (h * (right[0] - slack), h * (right[1] + slack));
                (
                    ceil_div(from + (w - 2) * unit, 2 * unit),
                    floor_div(to + w * unit, 2 * unit),
                )
            }
            Bound::Side { forward, right, up } => {
                // H·(forward + slack + b·up) for the row's most favourable b; then the pixels
                // where adding a·right, at the pixel's most favourable edge, keeps it ≥ 0.
                let edge = if up > 0 { top } else { bottom };
                let constant = h * (forward + slack) + (edge / unit) * up;
                match right.signum() {
                    1 => (ceil_div((w - 2) * right - constant, 2 * right), w - 1),
                    -1 => (0, floor_div(constant + w * -right, 2 * -right)),
                    _ if constant >= 0 => return ALL,
                    _ => return NONE,
                }
            }
        };
        match (u32::try_from(first.max(0)), u32::try_from(last.min(w - 1))) {
            (Ok(first), Ok(last)) if first <= last => (first, last),
            _ => NONE,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::UNITS;
    use crate::desc::CameraDesc;

    /// A camera at the origin looking down +z, x to the left (right = forward × up = −x).
    fn frame() -> Frame {
        let desc = CameraDesc::pinhole([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 90.0);
        Frame::new(&desc).unwrap()
    }

    #[test]
    fn a_ball_ahead_bounds_the_disc_it_projects_to() {
        // A ball of radius 1 ten units ahead subtends asin(0.1): its disc on the image plane
        // has the radius tan(asin 0.1).
        let edge = libm::tan(libm::asin(0.1));
        let Bound::Rectangle { right, up } =
            Bound::ball(Vec3::new(0.0, 0.0, 10.0), 1.0, 0.0, &frame())
        else {
            panic!("no rectangle");
        };
        // In half heights (h = 1 at 90°), rounded outwards by at most two units.
        let half_heights = |c: Coordinate| c as f64 / UNITS;
        for [low, high] in [right, up] {
            let (low, high) = (half_heights(low), half_heights(high));
            assert!(low <= -edge && low > -edge - 1e-9, "{low}");
            assert!(high >= edge && high < edge + 1e-9, "{high}");
        }
        // Two units to the left (right = −x), its disc is offset along a by about −0.2.
        let Bound::Rectangle { right, .. } =
            Bound::ball(Vec3::new(2.0, 0.0, 10.0), 1.0, 0.0, &frame())
        else {
            panic!("no rectangle");
        };
        let [low, high] = right.map(half_heights);
        assert!(low < -0.2 && high > -0.2 && high < 0.0, "{right:?}");
    }

    #[test]
    fn a_ball_behind_is_nowhere_and_one_about_the_eye_everywhere() {
        let frame = frame();
        assert_eq!(
            Bound::ball(Vec3::new(0.0, 0.0, -10.0), 1.0, 0.0, &frame),
            Bound::Nowhere
        );
        assert_eq!(
            Bound::ball(Vec3::new(0.0, 0.0, 1.0), 0.5, 0.2, &frame),
            Bound::Everywhere
        );
        // Beside the eye, its cone reaches beyond any rectangle.
        assert_eq!(
            Bound::ball(Vec3::new(3.0, 0.0, 0.0), 1.0, 0.0, &frame),
            Bound::Everywhere
        );
    }

    #[test]
    fn a_floor_is_reached_below_its_horizon() {
        // The floor y = −1: rays meet it where they point down (b < 0).
        let floor = Bound::plane(Vec3::new(0.0, 1.0, 0.0), -1.0, &frame());
        let plane = ImagePlane::new(1.0, 4, 4, |_| 0.0);
        // Rows 0 and 1 lie above the horizon (b from 1 down to 0), rows 2 and 3 below; row 1's
        // bottom edge touches it.
        let rows = [0, 1, 2, 3].map(|y| plane.row_range(&floor, y));
        assert_eq!(rows, [NONE, ALL, ALL, ALL]);
    }

    #[test]
    fn candidates_change_where_a_range_starts_or_ends() {
        let mut ranges = RowRanges {
            ranges: [NONE; 32],
            len: 2,
        };
        ranges.ranges[..2].copy_from_slice(&[(2, 4), (3, 3)]);
        let mut candidates = ranges.candidates();
        let seen: Vec<u32> = (0..6).map(|x| candidates.at(x)).collect();
        assert_eq!(seen, [0, 0, 0b01, 0b11, 0b01, 0]);
    }
}
