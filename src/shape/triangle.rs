//! Ray–triangle intersection: Cramer's rule as in the lecture, Möller–Trumbore, or the
//! watertight test of Woop, Benthin and Wald.

crate::phase::declare_phase!(Some(crate::phase::Phase::Tests));

use super::Intersection;
use crate::methods::{RootMethod, TriangleMethod};
use crate::ray::{Ray, Span};
use crate::scalar::Scalar;
use crate::vec3::Vec3;
use core::cmp::Ordering;

/// A triangle a, b, c with its edges e1 = b − a, e2 = c − a and what the tests share.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle<S> {
    /// The corners, as given: the watertight test needs exactly the values a neighbour
    /// sharing an edge has.
    vertices: [Vec3<S>; 3],
    e1: Vec3<S>,
    e2: Vec3<S>,
    /// e1 × e2: shared by two of Cramer's four determinants.
    e1_cross_e2: Vec3<S>,
    normal: Vec3<S>,
    /// n·a: the triangle's plane is n·p = offset.
    offset: S,
    /// Möller–Trumbore treats a smaller |det| as parallel: below it, the products with
    /// 1/det would leave the format (the scene build derives it; for floats it is tiny).
    min_det: S,
}

crate::words::words_of_struct!(Triangle<S> {
    vertices,
    e1,
    e2,
    e1_cross_e2,
    normal,
    offset,
    min_det
});

/// det[a b c] = a · (b × c), the scalar triple product.
#[inline]
fn det3<S: Scalar>(a: Vec3<S>, b: Vec3<S>, c: Vec3<S>) -> S {
    a.dot(b.cross(c))
}

/// Whether a barycentric pair is inside the triangle, testing v ≤ 1 before the sum: a
/// saturated quotient must not reach it.
#[inline]
fn inside<S: Scalar>(u: S, v: S) -> bool {
    u >= S::ZERO && u <= S::ONE && v >= S::ZERO && v <= S::ONE && u + v <= S::ONE
}

impl<S: Scalar> Triangle<S> {
    /// The triangle with these corners; `unit_normal` is (e1 × e2) normalised and `min_det`
    /// Möller–Trumbore's parallel threshold, both from the scene build.
    #[must_use]
    pub fn new(vertices: [Vec3<S>; 3], unit_normal: Vec3<S>, min_det: S) -> Self {
        let [a, b, c] = vertices;
        let (e1, e2) = (b - a, c - a);
        Self {
            vertices,
            e1,
            e2,
            e1_cross_e2: e1.cross(e2),
            normal: unit_normal,
            offset: unit_normal.dot(a),
            min_det,
        }
    }

    /// The nearest hit in `span` by `method`.
    #[inline(always)]
    #[must_use]
    pub fn intersect(
        &self,
        ray: &Ray<S>,
        span: Span<S>,
        method: TriangleMethod,
        roots: RootMethod,
    ) -> Option<Intersection<S>> {
        self.intersect_sharing(ray, span, method, roots, &mut PerRay::new())
    }

    /// [`Self::intersect`] for one of several triangles tested against `ray`, sharing with the
    /// others what depends on the ray alone.
    #[inline(always)]
    #[must_use]
    pub fn intersect_sharing(
        &self,
        ray: &Ray<S>,
        span: Span<S>,
        method: TriangleMethod,
        roots: RootMethod,
        per_ray: &mut PerRay<S>,
    ) -> Option<Intersection<S>> {
        match method {
            TriangleMethod::Cramer => self.cramer(ray, span, roots),
            TriangleMethod::MollerTrumbore => self.moller_trumbore(ray, span, roots),
            TriangleMethod::Watertight => self.watertight(ray, span, roots, per_ray),
        }
    }

    /// Solves o + t·d = a + u·e1 + v·e2, that is [−d e1 e2]·(t, u, v)ᵀ = o − a, by Cramer's
    /// rule: with D = det[−d e1 e2] and s = o − a,
    /// t = det[s e1 e2] / D, u = det[−d s e2] / D, v = det[−d e1 s] / D.
    /// A hit needs D ≠ 0 (the ray is not parallel to the triangle), t in the span, and
    /// u, v, u + v in [0, 1]. Each quotient is formed only once the ones before it passed.
    /// The quotients saturate for a nearly parallel ray, and a saturated one fails its test.
    fn cramer(&self, ray: &Ray<S>, span: Span<S>, roots: RootMethod) -> Option<Intersection<S>> {
        let minus_d = -ray.dir;
        let det = minus_d.dot(self.e1_cross_e2);
        if det == S::ZERO {
            return None;
        }
        let s = ray.origin - self.vertices[0];
        let u = roots.div(det3(minus_d, s, self.e2), det);
        if u < S::ZERO || u > S::ONE {
            return None;
        }
        let v = roots.div(det3(minus_d, self.e1, s), det);
        if !inside(u, v) {
            return None;
        }
        let t = roots.div(s.dot(self.e1_cross_e2), det);
        span.contains(t)
            .then_some(Intersection { t, u, v, part: 0 })
    }

    /// Möller and Trumbore (1997): with p = d × e2, det = e1·p, s = o − a and q = s × e1,
    /// u = (s·p)/det, v = (d·q)/det, t = (e2·q)/det, all three through one reciprocal.
    fn moller_trumbore(
        &self,
        ray: &Ray<S>,
        span: Span<S>,
        roots: RootMethod,
    ) -> Option<Intersection<S>> {
        let p = ray.dir.cross(self.e2);
        let det = self.e1.dot(p);
        if det.abs() <= self.min_det || det == S::ZERO {
            return None;
        }
        let inverse = roots.div(S::ONE, det);
        let s = ray.origin - self.vertices[0];
        let u = s.dot(p) * inverse;
        if u < S::ZERO || u > S::ONE {
            return None;
        }
        let q = s.cross(self.e1);
        let v = ray.dir.dot(q) * inverse;
        if !inside(u, v) {
            return None;
        }
        let t = self.e2.dot(q) * inverse;
        span.contains(t)
            .then_some(Intersection { t, u, v, part: 0 })
    }

    /// Woop, Benthin and Wald (2013). The vertices are moved to the ray's origin and sheared so
    /// that the ray runs along the new z axis; the ray hits the triangle iff the 2D edge
    /// functions U, V, W of the sheared vertices share a sign. Their signs are computed exactly
    /// ([`Scalar::diff_of_products`]), and a vertex shared by two triangles is sheared into the
    /// same numbers for both, so the two tests of a shared edge can never both say "outside":
    /// no ray slips through. The distance is then the plane's, t = (n·a − n·o)/(n·d).
    fn watertight(
        &self,
        ray: &Ray<S>,
        span: Span<S>,
        roots: RootMethod,
        per_ray: &mut PerRay<S>,
    ) -> Option<Intersection<S>> {
        let shear = *per_ray.shear.get_or_insert_with(|| Shear::of(ray, roots));
        let [a, b, c] = self.vertices.map(|vertex| shear.apply(vertex - ray.origin));
        let (u_edge, u_sign) = S::diff_of_products(c[0], b[1], c[1], b[0]);
        let (v_edge, v_sign) = S::diff_of_products(a[0], c[1], a[1], c[0]);
        let (w_edge, w_sign) = S::diff_of_products(b[0], a[1], b[1], a[0]);
        let signs = [u_sign, v_sign, w_sign];
        let negative = signs.contains(&Ordering::Less);
        let positive = signs.contains(&Ordering::Greater);
        if negative && positive || !negative && !positive {
            return None;
        }
        let det = u_edge + v_edge + w_edge;
        let along = self.normal.dot(ray.dir);
        if det == S::ZERO || along == S::ZERO {
            return None;
        }
        let t = roots.div(self.offset - self.normal.dot(ray.origin), along);
        if !span.contains(t) {
            return None;
        }
        Some(Intersection {
            t,
            u: roots.div(v_edge, det),
            v: roots.div(w_edge, det),
            part: 0,
        })
    }

    /// The unit normal, on the side where a, b, c run anticlockwise.
    #[inline]
    #[must_use]
    pub const fn normal(&self) -> Vec3<S> {
        self.normal
    }

    /// The point with barycentric coordinates (u, v): a + u·e1 + v·e2. For a hit (u, v and
    /// u + v in [0, 1]) it is a convex combination of the corners, so within the triangle
    /// whatever the rounding of the distance along the ray.
    #[inline]
    #[must_use]
    pub fn at(&self, u: S, v: S) -> Vec3<S> {
        self.vertices[0]
            .add_scaled(self.e1, u)
            .add_scaled(self.e2, v)
    }
}

/// What the tests of one ray against several triangles share, computed by the first test that
/// needs it: the watertight test's shear, which costs two divisions.
#[derive(Clone, Copy, Debug)]
pub struct PerRay<S> {
    shear: Option<Shear<S>>,
}

impl<S> PerRay<S> {
    /// Nothing computed yet, for a new ray.
    #[must_use]
    pub const fn new() -> Self {
        Self { shear: None }
    }
}

impl<S> Default for PerRay<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// The shear of Woop et al. that turns a ray into the +z axis: kz is the axis along which the
/// ray runs fastest, kx and ky the others (swapped when the ray runs backwards, to keep the
/// triangles' winding), and (x, y, z) ↦ (x − Sx·z, y − Sy·z) with Sx = d_kx/d_kz,
/// Sy = d_ky/d_kz, whose magnitudes are at most 1.
#[derive(Clone, Copy, Debug)]
struct Shear<S> {
    kx: usize,
    ky: usize,
    kz: usize,
    sx: S,
    sy: S,
}

impl<S: Scalar> Shear<S> {
    fn of(ray: &Ray<S>, roots: RootMethod) -> Self {
        let d = [ray.dir.x, ray.dir.y, ray.dir.z];
        let [x, y, z] = d.map(S::abs);
        let kz = if x >= y && x >= z {
            0
        } else if y >= z {
            1
        } else {
            2
        };
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        let along = component(d, kz);
        if along < S::ZERO {
            core::mem::swap(&mut kx, &mut ky);
        }
        Self {
            kx,
            ky,
            kz,
            sx: roots.div(component(d, kx), along),
            sy: roots.div(component(d, ky), along),
        }
    }

    /// A point relative to the ray's origin, sheared: its 2D position seen down the ray.
    fn apply(&self, p: Vec3<S>) -> [S; 2] {
        let p = [p.x, p.y, p.z];
        let z = component(p, self.kz);
        [
            component(p, self.kx) - self.sx * z,
            component(p, self.ky) - self.sy * z,
        ]
    }
}

/// Coordinate `k` (0, 1 or 2) of a vector.
#[inline]
fn component<S: Scalar>(v: [S; 3], k: usize) -> S {
    v.get(k).copied().unwrap_or(S::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::MethodName;
    use crate::scalar::Precision;
    use crate::test_util::{assert_close, for_each_format, span, v};

    /// The triangle (0,0,4), (2,0,4), (0,2,4), facing −z towards the origin.
    fn triangle<S: Scalar>() -> Triangle<S> {
        Triangle::new(
            [v(0.0, 0.0, 4.0), v(2.0, 0.0, 4.0), v(0.0, 2.0, 4.0)],
            v(0.0, 0.0, 1.0),
            S::ZERO,
        )
    }

    fn along_z<S: Scalar>(x: f64, y: f64) -> Ray<S> {
        Ray::new(v(x, y, 0.0), v(0.0, 0.0, 1.0))
    }

    /// Runs `check` once per triangle method, exact roots.
    fn each_method(mut check: impl FnMut(TriangleMethod, &str)) {
        for &(method, name) in TriangleMethod::ALL {
            check(method, name);
        }
    }

    #[test]
    fn interior_hit_has_known_t_and_barycentrics() {
        for_each_format!(S, {
            each_method(|method, name| {
                let hit = triangle::<S>().intersect(
                    &along_z(0.5, 1.0),
                    span(100.0),
                    method,
                    RootMethod::Exact,
                );
                let hit = hit.unwrap_or_else(|| panic!("{name}"));
                assert_close(hit.t, 4.0, 1e-4);
                assert_close(hit.u, 0.25, 1e-4);
                assert_close(hit.v, 0.5, 1e-4);
            });
        });
    }

    #[test]
    fn triangles_tested_against_one_ray_share_its_shear() {
        for_each_format!(S, {
            let near = triangle::<S>();
            let far = Triangle::new(
                [v(0.0, -2.0, 6.0), v(3.0, -2.0, 6.0), v(0.0, 1.0, 6.0)],
                v(0.0, 0.0, 1.0),
                S::ZERO,
            );
            let ray = Ray::new(v(0.5, -2.5, 8.0), v::<S>(0.0, 0.6, -0.8));
            let mut per_ray = PerRay::new();
            for tri in [near, far] {
                let (watertight, exact) = (TriangleMethod::Watertight, RootMethod::Exact);
                let shared =
                    tri.intersect_sharing(&ray, span(100.0), watertight, exact, &mut per_ray);
                let alone = tri.intersect(&ray, span(100.0), watertight, exact);
                assert_eq!(shared.map(|h| h.t), alone.map(|h| h.t));
                assert!(shared.is_some());
            }
        });
    }

    #[test]
    fn oblique_hit_from_the_back() {
        for_each_format!(S, {
            each_method(|method, name| {
                // From (0.5, −2.5, 8) along (0, 0.6, −0.8) the ray meets z = 4 after t = 5, at
                // (0.5, 0.5, 4): u = v = 0.25.
                let ray = Ray::new(v(0.5, -2.5, 8.0), v::<S>(0.0, 0.6, -0.8));
                let hit = triangle::<S>().intersect(&ray, span(100.0), method, RootMethod::Exact);
                let hit = hit.unwrap_or_else(|| panic!("{name}"));
                assert_close(hit.t, 5.0, 1e-3);
                assert_close(hit.u, 0.25, 1e-3);
                assert_close(hit.v, 0.25, 1e-3);
            });
        });
    }

    #[test]
    fn vertices_and_edges_count_as_hits() {
        for_each_format!(S, {
            each_method(|method, name| {
                let tri = triangle::<S>();
                for (x, y, u, w) in [
                    (0.0, 0.0, 0.0, 0.0),
                    (2.0, 0.0, 1.0, 0.0),
                    (0.0, 2.0, 0.0, 1.0),
                    (1.0, 0.0, 0.5, 0.0),
                    (0.0, 1.0, 0.0, 0.5),
                    (1.0, 1.0, 0.5, 0.5),
                ] {
                    let hit = tri.intersect(&along_z(x, y), span(100.0), method, RootMethod::Exact);
                    let hit =
                        hit.unwrap_or_else(|| panic!("{}, {name}: ({x}, {y}) missed", S::NAME));
                    assert_close(hit.u, u, 1e-4);
                    assert_close(hit.v, w, 1e-4);
                }
            });
        });
    }

    #[test]
    fn misses_outside_each_edge_and_behind() {
        for_each_format!(S, {
            each_method(|method, name| {
                let tri = triangle::<S>();
                let hit =
                    |ray: &Ray<S>, max| tri.intersect(ray, span(max), method, RootMethod::Exact);
                for (x, y) in [(-0.01, 0.5), (0.5, -0.01), (1.01, 1.0), (3.0, 3.0)] {
                    assert_eq!(hit(&along_z(x, y), 100.0), None, "{name}: ({x}, {y})");
                }
                let away = Ray::new(v(0.5, 0.5, 0.0), v(0.0, 0.0, -1.0));
                assert_eq!(
                    hit(&away, 100.0),
                    None,
                    "{name}: triangle behind the origin"
                );
                assert_eq!(
                    hit(&along_z(0.5, 0.5), 3.0),
                    None,
                    "{name}: beyond the span"
                );
            });
        });
    }

    #[test]
    fn parallel_rays_miss() {
        for_each_format!(S, {
            each_method(|method, name| {
                let tri = triangle::<S>();
                let beside = Ray::new(v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0));
                assert_eq!(
                    tri.intersect(&beside, span(100.0), method, RootMethod::Exact),
                    None,
                    "{name}"
                );
                let in_plane = Ray::new(v(-1.0, 0.5, 4.0), v(1.0, 0.0, 0.0));
                assert_eq!(
                    tri.intersect(&in_plane, span(100.0), method, RootMethod::Exact),
                    None,
                    "{name}"
                );
            });
        });
    }

    #[test]
    fn a_ray_through_a_shared_edge_hits_one_of_the_two_triangles() {
        // Two triangles sharing the diagonal of a square; rays along the diagonal at odd
        // angles. The watertight test must never let one through.
        type S = crate::scalar::I16F16;
        let corners = [
            v::<S>(-1.3, -0.7, 5.0),
            v(1.1, -0.9, 5.3),
            v(0.9, 1.2, 4.8),
            v(-1.0, 1.0, 5.1),
        ];
        let first = Triangle::new(
            [corners[0], corners[1], corners[2]],
            v(0.0, 0.0, -1.0),
            S::ZERO,
        );
        let second = Triangle::new(
            [corners[0], corners[2], corners[3]],
            v(0.0, 0.0, -1.0),
            S::ZERO,
        );
        for i in 0..=200 {
            let f = f64::from(i) / 200.0;
            let target = [-1.3 + 2.2 * f, -0.7 + 1.9 * f, 5.0 - 0.2 * f];
            let origin = [0.37, -0.21, 0.0];
            let d = [
                target[0] - origin[0],
                target[1] - origin[1],
                target[2] - origin[2],
            ];
            let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let ray = Ray::new(
                v(origin[0], origin[1], origin[2]),
                v(d[0] / length, d[1] / length, d[2] / length),
            );
            let hit = |tri: &Triangle<S>| {
                tri.intersect(
                    &ray,
                    span(100.0),
                    TriangleMethod::Watertight,
                    RootMethod::Exact,
                )
            };
            assert!(
                hit(&first).is_some() || hit(&second).is_some(),
                "slipped through at {f}"
            );
        }
    }
}
