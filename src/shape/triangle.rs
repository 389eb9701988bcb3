//! Ray–triangle intersection by Cramer's rule, as in the lecture.

use crate::ray::{Ray, Span};
use crate::scalar::Scalar;
use crate::vec3::Vec3;

/// A triangle a, b, c stored as a corner and two edges e1 = b − a, e2 = c − a.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle<S> {
    a: Vec3<S>,
    e1: Vec3<S>,
    e2: Vec3<S>,
    /// e1 × e2: shared by two of the four determinants.
    e1_cross_e2: Vec3<S>,
    normal: Vec3<S>,
    /// n·a: the triangle's plane is n·p = offset.
    offset: S,
}

/// Where a ray meets a triangle: the distance and the barycentric coordinates, so that the
/// point is a + u·e1 + v·e2 = (1 − u − v)·a + u·b + v·c.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit<S> {
    /// The distance along the ray.
    pub t: S,
    /// The weight of the second vertex.
    pub u: S,
    /// The weight of the third vertex.
    pub v: S,
}

/// det[a b c] = a · (b × c), the scalar triple product.
#[inline]
fn det3<S: Scalar>(a: Vec3<S>, b: Vec3<S>, c: Vec3<S>) -> S {
    a.dot(b.cross(c))
}

impl<S: Scalar> Triangle<S> {
    /// The triangle with these corners; `unit_normal` is (e1 × e2) normalised, computed by the
    /// scene build in double precision.
    #[must_use]
    pub fn new(vertices: [Vec3<S>; 3], unit_normal: Vec3<S>) -> Self {
        let [a, b, c] = vertices;
        let (e1, e2) = (b - a, c - a);
        Self {
            a,
            e1,
            e2,
            e1_cross_e2: e1.cross(e2),
            normal: unit_normal,
            offset: unit_normal.dot(a),
        }
    }

    /// Solves o + t·d = a + u·e1 + v·e2, that is [−d e1 e2]·(t, u, v)ᵀ = o − a, by Cramer's
    /// rule: with D = det[−d e1 e2] and s = o − a,
    /// t = det[s e1 e2] / D, u = det[−d s e2] / D, v = det[−d e1 s] / D.
    /// A hit needs D ≠ 0 (the ray is not parallel to the triangle), t in the span, and
    /// u, v, u + v in [0, 1]. Each quotient is formed only once the ones before it passed.
    /// The quotients saturate for a nearly parallel ray, and a saturated one fails its test.
    #[must_use]
    pub fn intersect(&self, ray: &Ray<S>, span: Span<S>) -> Option<TriangleHit<S>> {
        let minus_d = -ray.dir;
        let det = minus_d.dot(self.e1_cross_e2);
        if det == S::ZERO {
            return None;
        }
        let s = ray.origin - self.a;
        let u = det3(minus_d, s, self.e2) / det;
        if u < S::ZERO || u > S::ONE {
            return None;
        }
        let v = det3(minus_d, self.e1, s) / det;
        // v ≤ 1 first: a saturated quotient must not reach the sum.
        if v < S::ZERO || v > S::ONE || u + v > S::ONE {
            return None;
        }
        let t = s.dot(self.e1_cross_e2) / det;
        span.contains(t).then_some(TriangleHit { t, u, v })
    }

    /// The unit normal, on the side where a, b, c run anticlockwise.
    #[inline]
    #[must_use]
    pub const fn normal(&self) -> Vec3<S> {
        self.normal
    }

    /// The point of the triangle's plane nearest `point`.
    #[inline]
    #[must_use]
    pub fn project(&self, point: Vec3<S>) -> Vec3<S> {
        point.onto_plane(self.normal, self.offset)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::{assert_close, for_each_format, span, v};

    /// The triangle (0,0,4), (2,0,4), (0,2,4), facing −z towards the origin.
    fn triangle<S: Scalar>() -> Triangle<S> {
        Triangle::new(
            [v(0.0, 0.0, 4.0), v(2.0, 0.0, 4.0), v(0.0, 2.0, 4.0)],
            v(0.0, 0.0, 1.0),
        )
    }

    fn along_z<S: Scalar>(x: f64, y: f64) -> Ray<S> {
        Ray::new(v(x, y, 0.0), v(0.0, 0.0, 1.0))
    }

    #[test]
    fn interior_hit_has_known_t_and_barycentrics() {
        for_each_format!(S, {
            let hit = triangle::<S>()
                .intersect(&along_z(0.5, 1.0), span(100.0))
                .unwrap();
            assert_close(hit.t, 4.0, 1e-4);
            assert_close(hit.u, 0.25, 1e-4);
            assert_close(hit.v, 0.5, 1e-4);
        });
    }

    #[test]
    fn oblique_hit_from_the_back() {
        for_each_format!(S, {
            // From (0.5, −2.5, 8) along (0, 0.6, −0.8) the ray meets z = 4 after t = 5, at
            // (0.5, 0.5, 4): u = v = 0.25.
            let d = v::<S>(0.0, 0.6, -0.8);
            let ray = Ray::new(v(0.5, -2.5, 8.0), d);
            let hit = triangle::<S>().intersect(&ray, span(100.0)).unwrap();
            assert_close(hit.t, 5.0, 1e-3);
            assert_close(hit.u, 0.25, 1e-3);
            assert_close(hit.v, 0.25, 1e-3);
        });
    }

    #[test]
    fn vertices_and_edges_count_as_hits() {
        for_each_format!(S, {
            let tri = triangle::<S>();
            for (x, y, u, w) in [
                (0.0, 0.0, 0.0, 0.0),
                (2.0, 0.0, 1.0, 0.0),
                (0.0, 2.0, 0.0, 1.0),
                (1.0, 0.0, 0.5, 0.0),
                (0.0, 1.0, 0.0, 0.5),
                (1.0, 1.0, 0.5, 0.5),
            ] {
                let hit = tri.intersect(&along_z(x, y), span(100.0));
                let hit = hit.unwrap_or_else(|| panic!("{}: ({x}, {y}) missed", S::NAME));
                assert_close(hit.u, u, 1e-4);
                assert_close(hit.v, w, 1e-4);
            }
        });
    }

    #[test]
    fn misses_outside_each_edge_and_behind() {
        for_each_format!(S, {
            let tri = triangle::<S>();
            for (x, y) in [(-0.01, 0.5), (0.5, -0.01), (1.01, 1.0), (3.0, 3.0)] {
                assert_eq!(
                    tri.intersect(&along_z(x, y), span(100.0)),
                    None,
                    "({x}, {y})"
                );
            }
            let away = Ray::new(v(0.5, 0.5, 0.0), v(0.0, 0.0, -1.0));
            assert_eq!(
                tri.intersect(&away, span(100.0)),
                None,
                "triangle behind the origin"
            );
            assert_eq!(
                tri.intersect(&along_z(0.5, 0.5), span(3.0)),
                None,
                "beyond the span"
            );
        });
    }

    #[test]
    fn parallel_rays_miss() {
        for_each_format!(S, {
            let tri = triangle::<S>();
            let beside = Ray::new(v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0));
            assert_eq!(tri.intersect(&beside, span(100.0)), None);
            let in_plane = Ray::new(v(-1.0, 0.5, 4.0), v(1.0, 0.0, 0.0));
            assert_eq!(tri.intersect(&in_plane, span(100.0)), None);
        });
    }
}
