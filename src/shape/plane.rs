//! Ray–plane intersection, and the checkerboard a plane can carry.

crate::phase::declare_phase!(Some(crate::phase::Phase::Tests));

use crate::color::Rgb;
use crate::methods::RootMethod;
use crate::ray::{Ray, Span};
use crate::scalar::Scalar;
use crate::vec3::Vec3;

/// A plane n·p = offset, cut off at the edge of the world: of the plane, the tracer sees only
/// the disc the world's ball (radius R about the eye) cuts from it, about the eye's foot on the
/// plane, of radius ρ = √(R² − h²) for a plane h from the eye.
///
/// A hit is tested against that disc, not against the ball: near the world's edge (h close to
/// R) the disc is small, and |p|² = h² + |p − foot|² would lose its radius in the rounding of
/// h², moving the rim by R/ρ times the error of |p|.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane<S: Scalar> {
    normal: Vec3<S>,
    offset: S,
    /// The eye's foot on the plane (relative to the eye): the centre of the visible disc, and
    /// the checkerboard's origin, so that the points a pattern measures are near it.
    foot: Vec3<S>,
    /// The visible disc's radius ρ.
    rim: S,
    /// A power of two near 1/ρ, at least 1/(2ρ): scaled by it, a point within ρ of the foot on
    /// every axis has coordinates within 1, whose squares sum to at most 3 in any format and
    /// resolve as finely as the format allows.
    rim_scale: S,
    /// (ρ·`rim_scale`)², at most 1.
    scaled_rim_squared: S,
    checker: Option<Checker<S>>,
}

crate::words::words_of_struct!(Plane<S> {
    normal,
    offset,
    foot,
    rim,
    rim_scale,
    scaled_rim_squared,
    checker
});

/// Squares after which a checkerboard's colours repeat: a square's colour is the parity of its
/// two coordinates, so the count of squares from a plane's point matters modulo two.
pub const CHECKER_PERIOD: f64 = 2.0;

/// A checkerboard on a plane: the two in-plane axes, pre-divided by the square size, so that
/// (p − foot)·axis counts squares from the eye's foot on the plane, where the count starts at
/// `start`; and the colour of every other square.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checker<S: Scalar> {
    /// The colour of the squares whose two coordinates sum to an odd number.
    pub colour: Rgb<S::Narrow>,
    /// The first in-plane axis divided by the square size.
    pub u: Vec3<S>,
    /// The second in-plane axis divided by the square size.
    pub v: Vec3<S>,
    /// The foot's coordinates on the grid of squares anchored at the plane's point, modulo
    /// [`CHECKER_PERIOD`] (each in [0, 2)), so that a square's colour is where the plane puts it.
    pub start: [S; 2],
}

crate::words::words_of_struct!(Checker<S> {
    colour,
    u,
    v,
    start
});

impl<S: Scalar> Plane<S> {
    /// The plane through `point` with the unit normal `normal`, of which the world cuts the
    /// disc of radius `rim` about `foot`, the eye's foot on it (both relative to the eye, as
    /// every position is).
    #[must_use]
    pub fn new(
        point: Vec3<S>,
        normal: Vec3<S>,
        foot: Vec3<S>,
        rim: S,
        checker: Option<Checker<S>>,
    ) -> Self {
        // A power of two near 1/ρ: halved until ρ·scale ≤ 1 (by doubling a reach up to at most
        // 2ρ, which the scene build proved to fit), or doubled while ρ·scale ≤ ½ (halving a
        // reach down to ρ), so that a small disc does not vanish below the format's
        // resolution; doubling stops short of the format's range (which the scene build proved
        // the scale for this ρ to stay within), and where the reach can be halved no more.
        let (mut reach, mut rim_scale) = (S::ONE, S::ONE);
        let half = S::ratio(1, 2);
        while reach < rim {
            reach = reach + reach;
            rim_scale = rim_scale * half;
        }
        let ceiling = S::MAX / S::from_int(2);
        while reach * half >= rim && reach * half < reach && rim_scale < ceiling {
            reach = reach * half;
            rim_scale = rim_scale + rim_scale;
        }
        let scaled_rim = rim * rim_scale;
        Self {
            normal,
            offset: normal.dot(point),
            foot,
            rim,
            rim_scale,
            scaled_rim_squared: scaled_rim * scaled_rim,
            checker,
        }
    }

    /// The nearest t in `span` where `ray` meets the plane within the world: t = (offset − n·o)
    /// / (n·d). A ray parallel to the plane (n·d = 0) misses it.
    ///
    /// Out of line on the M0, where a copy inlined into each search (primary, secondary,
    /// shadow) costs flash a one-scene image cannot spare, and the call costs fewer cycles than
    /// the copies' register spills (`whitted` in `i16f16`: about a hundred instructions a pixel
    /// fewer out of line); inlined on the other cores, where it is the cheaper.
    #[cfg_attr(armv6m, inline(never))]
    #[cfg_attr(not(armv6m), inline(always))]
    #[must_use]
    pub fn intersect(&self, ray: &Ray<S>, span: Span<S>, roots: RootMethod) -> Option<S> {
        let denominator = self.normal.dot(ray.dir);
        if denominator == S::ZERO {
            return None;
        }
        let numerator = self.offset - self.normal.dot(ray.origin);
        // t lies in the span iff the numerator lies between min·(n·d) and max·(n·d): testing
        // that first spares the division for every ray that points away from the plane or
        // meets it beyond the nearest hit so far.
        let (low, high) = if denominator > S::ZERO {
            (span.min * denominator, span.max * denominator)
        } else {
            (span.max * denominator, span.min * denominator)
        };
        if numerator < low || numerator > high {
            return None;
        }
        let t = roots.div(numerator, denominator);
        if !span.contains(t) {
            return None;
        }
        self.inside_world(ray.at(t)).then_some(t)
    }

    /// Where the ray from the eye along the image-plane point `s` meets the plane, for the `t`
    /// at which it does (the row pass's, [`crate::row_pass`]): t·s, its coordinate on the
    /// plane's `axis` the plane's `level` exactly ([`Self::axis`]), or `None` beyond the
    /// world's rim.
    #[inline(always)]
    pub(crate) fn hit_along(&self, s: Vec3<S>, t: S, (axis, level): (usize, S)) -> Option<Vec3<S>> {
        let point = (s * t).with(axis, level);
        self.inside_world(point).then_some(point)
    }

    /// Whether `p`, a point of the plane, lies in the visible disc: |q| ≤ ρ for q = p − foot,
    /// tested as |q·s|² ≤ (ρ·s)² with the power of two s ≈ 1/ρ. Each coordinate of q is tested
    /// against ρ first, so that the squares are of numbers within 1 (ρ² itself may not fit the
    /// format, or resolve in it).
    fn inside_world(&self, p: Vec3<S>) -> bool {
        let q = p - self.foot;
        let rim = self.rim;
        let within = |c: S| c <= rim && c >= -rim;
        within(q.x)
            && within(q.y)
            && within(q.z)
            && (q * self.rim_scale).length_squared() <= self.scaled_rim_squared
    }

    /// The axis (0, 1, 2: x, y, z) the normal lies along exactly, if it does, and the
    /// coordinate every point of the plane has on it: n·p is then ± that coordinate.
    #[must_use]
    pub(crate) fn axis(&self) -> Option<(usize, S)> {
        let Vec3 { x, y, z } = self.normal;
        let zero = S::ZERO;
        let (axis, along) = match (x == zero, y == zero, z == zero) {
            (false, true, true) => (0, x),
            (true, false, true) => (1, y),
            (true, true, false) => (2, z),
            _ => return None,
        };
        if along == S::ONE {
            Some((axis, self.offset))
        } else if along == -S::ONE {
            Some((axis, -self.offset))
        } else {
            None
        }
    }

    /// The unit normal (the same everywhere).
    #[inline]
    #[must_use]
    pub const fn normal(&self) -> Vec3<S> {
        self.normal
    }

    /// The point of the plane nearest `point`.
    #[inline]
    #[must_use]
    pub fn project(&self, point: Vec3<S>) -> Vec3<S> {
        point.onto_plane(self.normal, self.offset)
    }

    /// The checker colour at a point, where the point falls on a square of the second colour.
    #[must_use]
    pub fn pattern_colour(&self, point: Vec3<S>) -> Option<Rgb<S::Narrow>> {
        let checker = self.checker?;
        let [u, v] = self.square(point)?;
        (u.wrapping_add(v) & 1 == 1).then_some(checker.colour)
    }

    /// The checker's square a point falls on, as its whole coordinates along the checker's
    /// two directions; `None` without a checker.
    #[inline]
    #[must_use]
    pub(crate) fn square(&self, point: Vec3<S>) -> Option<[i32; 2]> {
        let checker = self.checker?;
        let local = point - self.foot;
        let [start_u, start_v] = checker.start;
        Some([
            (local.dot(checker.u) + start_u).floor_int(),
            (local.dot(checker.v) + start_v).floor_int(),
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;
    use crate::scalar::Precision;
    use crate::test_util::{assert_close, for_each_format, span, v};

    /// The floor y = −h in a world of radius `world` about the origin (the eye).
    fn floor_at<S: Scalar>(h: f64, world: f64, checker: Option<Checker<S>>) -> Plane<S> {
        let rim = (world * world - h * h).sqrt();
        Plane::new(
            v(0.0, -h, 0.0),
            v(0.0, 1.0, 0.0),
            v(0.0, -h, 0.0),
            S::from_f64(rim).unwrap(),
            checker,
        )
    }

    fn floor<S: Scalar>(checker: Option<Checker<S>>) -> Plane<S> {
        floor_at(1.0, 50.0, checker)
    }

    #[test]
    fn hits_the_floor_at_the_known_point() {
        for_each_format!(S, {
            let plane = floor::<S>(None);
            let d = v::<S>(0.0, -0.6, 0.8);
            let ray = Ray::new(v(0.0, 2.0, 0.0), d);
            let t = plane
                .intersect(&ray, span(100.0), RootMethod::Exact)
                .unwrap();
            assert_close(t, 5.0, 1e-3);
            let p = ray.at(t);
            assert_close(p.y, -1.0, 1e-3);
            assert_close(p.z, 4.0, 1e-3);
            assert_close(plane.normal().y, 1.0, 0.0);
            let snapped = plane.project(v(0.3, -0.98, 4.0));
            assert_close(snapped.y, -1.0, 1e-4);
            assert_close(snapped.x, 0.3, 1e-4);
        });
    }

    #[test]
    fn hits_from_below_too() {
        for_each_format!(S, {
            let plane = floor::<S>(None);
            let ray = Ray::new(v(0.0, -3.0, 0.0), v(0.0, 1.0, 0.0));
            assert_close(
                plane
                    .intersect(&ray, span(100.0), RootMethod::Exact)
                    .unwrap(),
                2.0,
                1e-4,
            );
        });
    }

    #[test]
    fn misses_parallel_receding_and_beyond_the_world() {
        for_each_format!(S, {
            let plane = floor::<S>(None);
            let parallel = Ray::new(v(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0));
            assert_eq!(
                plane.intersect(&parallel, span(100.0), RootMethod::Exact),
                None
            );
            let parallel_in_plane = Ray::new(v(0.0, -1.0, 0.0), v(1.0, 0.0, 0.0));
            assert_eq!(
                plane.intersect(&parallel_in_plane, span(100.0), RootMethod::Exact),
                None
            );
            let up = Ray::new(v(0.0, 0.0, 0.0), v(0.0, 1.0, 0.0));
            assert_eq!(
                plane.intersect(&up, span(100.0), RootMethod::Exact),
                None,
                "plane behind the origin"
            );
            // Grazing: it meets the plane 100 units away, outside the world of radius 50.
            let d = v::<S>(0.0, -0.01, 0.99995);
            let grazing = Ray::new(v(0.0, 0.0, 0.0), d);
            assert_eq!(
                plane.intersect(&grazing, span(1000.0), RootMethod::Exact),
                None
            );
        });
    }

    #[test]
    fn the_world_test_holds_a_world_whose_radius_squared_does_not_fit() {
        // R = 12 000 in 16.16: R² is far beyond its range of 32 768, a ray's length 2R is not.
        let world = 12_000.0;
        let plane = floor_at::<I16F16>(1.0, world, None);
        // Points on the floor along the diagonal of the xz plane, at distance √2·c.
        let at = |c: f64| plane.inside_world(v(c, -1.0, c));
        assert!(at(8000.0), "11 314 away: inside");
        assert!(at(8480.0), "11 992 away: just inside");
        assert!(!at(8520.0), "12 049 away: just outside");
        assert!(!at(12_500.0), "beyond R on an axis");
        // And a ray that meets the floor inside the world is seen there.
        let ray = Ray::new(v(0.0, 0.0, 0.0), v(0.0, -0.6, 0.8));
        let t = plane.intersect(&ray, span(2.0 * world), RootMethod::Exact);
        assert_close(t.unwrap(), 1.0 / 0.6, 1e-3);
    }

    #[test]
    fn at_the_worlds_edge_the_visible_disc_keeps_its_radius() {
        // A floor 10 below the eye in a world of radius 10.000 05: the world cuts a disc of
        // radius 0.0316 from it, which testing |p|² against R² (|p|² = 100 + ρ², rounded at
        // 100) would place only to within ρ's own size.
        for_each_format!(S, {
            let (h, world) = (10.0, 10.000_05);
            let rim = (world * world - h * h).sqrt();
            let plane = floor_at::<S>(h, world, None);
            // A few steps of the format at the world's size, and of the rim's.
            let steps = 4.0 * (S::resolution(world) + S::resolution(rim));
            for angle in [0.0_f64, 0.7, 2.0, 4.0] {
                let at = |r: f64| plane.inside_world(v(r * angle.cos(), -h, r * angle.sin()));
                assert!(at(rim - steps), "{}: inside at {angle}", S::NAME);
                assert!(!at(rim + steps), "{}: outside at {angle}", S::NAME);
            }
        });
    }

    #[test]
    fn checker_alternates_by_square() {
        for_each_format!(S, {
            let colour = Rgb::WHITE;
            let checker = Checker {
                colour,
                u: v(0.5, 0.0, 0.0),
                v: v(0.0, 0.0, 0.5),
                start: [S::ZERO; 2],
            };
            let plane = floor(Some(checker));
            assert_eq!(plane.pattern_colour(v(0.5, -1.0, 0.5)), None);
            assert_eq!(plane.pattern_colour(v(2.5, -1.0, 0.5)), Some(colour));
            assert_eq!(plane.pattern_colour(v(-0.5, -1.0, 0.5)), Some(colour));
            assert_eq!(plane.pattern_colour(v(-0.5, -1.0, -0.5)), None);
            assert_eq!(floor::<S>(None).pattern_colour(v(2.5, -1.0, 0.5)), None);
        });
    }
}
