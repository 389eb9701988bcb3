//! Ray–plane intersection, and the checkerboard a plane can carry.

use crate::color::Rgb;
use crate::methods::RootMethod;
use crate::ray::{Ray, Span};
use crate::scalar::Scalar;
use crate::vec3::Vec3;

/// A plane n·p = offset, cut off at the edge of the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane<S> {
    normal: Vec3<S>,
    offset: S,
    world_radius: S,
    /// A power of two near 1/R, at least 1/(2R): scaled by it, a point within R on every axis
    /// has coordinates within 1, whose squares sum to at most 3 in any format and resolve as
    /// finely as the format allows.
    world_scale: S,
    /// (R·`world_scale`)², at most 1.
    scaled_radius_squared: S,
    checker: Option<Checker<S>>,
}

crate::words::words_of_struct!(Plane<S> {
    normal,
    offset,
    world_radius,
    world_scale,
    scaled_radius_squared,
    checker
});

/// Squares after which a checkerboard's colours repeat: a square's colour is the parity of its
/// two coordinates, so the count of squares from a plane's point matters modulo two.
pub const CHECKER_PERIOD: f64 = 2.0;

/// A checkerboard on a plane: the two in-plane axes, pre-divided by the square size, so that
/// (p − origin)·axis counts squares from the origin, where the count starts at `start`; and the
/// colour of every other square.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checker<S> {
    /// The colour of the squares whose two coordinates sum to an odd number.
    pub colour: Rgb<S>,
    /// A point on the plane: the eye's foot on it, so that the points seen are near it.
    pub origin: Vec3<S>,
    /// The first in-plane axis divided by the square size.
    pub u: Vec3<S>,
    /// The second in-plane axis divided by the square size.
    pub v: Vec3<S>,
    /// The origin's coordinates on the grid of squares anchored at the plane's point, modulo
    /// [`CHECKER_PERIOD`] (each in [0, 2)), so that a square's colour is where the plane puts it.
    pub start: [S; 2],
}

crate::words::words_of_struct!(Checker<S> {
    colour,
    origin,
    u,
    v,
    start
});

impl<S: Scalar> Plane<S> {
    /// The plane through `point` with the unit normal `normal`, seen only within
    /// `world_radius` of the origin (the eye).
    #[must_use]
    pub fn new(
        point: Vec3<S>,
        normal: Vec3<S>,
        world_radius: S,
        checker: Option<Checker<S>>,
    ) -> Self {
        // A power of two near 1/R: halved until R·scale ≤ 1 (by doubling a reach up to at most
        // 2R, a ray's length, which the scene build proved to fit), or doubled while R·scale
        // ≤ ½ (halving a reach down to R), so that a small world's squares do not vanish below
        // the format's resolution; doubling stops short of the format's range, and where the
        // reach can be halved no more.
        let (mut reach, mut world_scale) = (S::ONE, S::ONE);
        let half = S::ratio(1, 2);
        while reach < world_radius {
            reach = reach + reach;
            world_scale = world_scale * half;
        }
        let ceiling = S::MAX / S::from_int(2);
        while reach * half >= world_radius && reach * half < reach && world_scale < ceiling {
            reach = reach * half;
            world_scale = world_scale + world_scale;
        }
        let scaled_radius = world_radius * world_scale;
        Self {
            normal,
            offset: normal.dot(point),
            world_radius,
            world_scale,
            scaled_radius_squared: scaled_radius * scaled_radius,
            checker,
        }
    }

    /// The nearest t in `span` where `ray` meets the plane within the world: t = (offset − n·o)
    /// / (n·d). A ray parallel to the plane (n·d = 0) misses it.
    #[inline(always)]
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

    /// |p| ≤ R, tested as |p·s|² ≤ (R·s)² with the power of two s ≈ 1/R: each coordinate is
    /// tested first, so that the squares are of numbers within 1 (R² itself may not fit the
    /// format).
    fn inside_world(&self, p: Vec3<S>) -> bool {
        let r = self.world_radius;
        let within = |c: S| c <= r && c >= -r;
        within(p.x)
            && within(p.y)
            && within(p.z)
            && (p * self.world_scale).length_squared() <= self.scaled_radius_squared
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
    pub fn pattern_colour(&self, point: Vec3<S>) -> Option<Rgb<S>> {
        let checker = self.checker?;
        let local = point - checker.origin;
        let [start_u, start_v] = checker.start;
        let squares = (local.dot(checker.u) + start_u)
            .floor_int()
            .wrapping_add((local.dot(checker.v) + start_v).floor_int());
        (squares & 1 == 1).then_some(checker.colour)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;
    use crate::scalar::Precision;
    use crate::test_util::{assert_close, for_each_format, span, v};

    fn floor<S: Scalar>(checker: Option<Checker<S>>) -> Plane<S> {
        Plane::new(
            v(0.0, -1.0, 0.0),
            v(0.0, 1.0, 0.0),
            S::from_int(50),
            checker,
        )
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
        let plane = Plane::<I16F16>::new(
            v(0.0, -1.0, 0.0),
            v(0.0, 1.0, 0.0),
            I16F16::from_f64(world).unwrap(),
            None,
        );
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
    fn checker_alternates_by_square() {
        for_each_format!(S, {
            let colour = Rgb::WHITE;
            let checker = Checker {
                colour,
                origin: v::<S>(0.0, -1.0, 0.0),
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
