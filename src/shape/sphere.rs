//! Ray–sphere intersection: the lecture's quadratic, or the stable form of Haines et al.

crate::phase::declare_phase!(Some(crate::phase::Phase::Tests));

use crate::methods::{RootMethod, SphereMethod};
use crate::ray::{Ray, Span};
use crate::scalar::Scalar;
use crate::vec3::Vec3;

/// A sphere, with the values its intersection needs precomputed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere<S> {
    center: Vec3<S>,
    radius: S,
    radius_squared: S,
}

crate::words::words_of_struct!(Sphere<S> {
    center,
    radius,
    radius_squared
});

impl<S: Scalar> Sphere<S> {
    /// A sphere; `radius` must be positive (the scene build checks it).
    #[must_use]
    pub fn new(center: Vec3<S>, radius: S) -> Self {
        Self {
            center,
            radius,
            radius_squared: radius * radius,
        }
    }

    /// Its centre.
    #[must_use]
    pub const fn center(&self) -> Vec3<S> {
        self.center
    }

    /// The nearest t in `span` where `ray` meets the sphere: the near root when it lies in the
    /// span, else the far one (a ray that starts inside).
    #[must_use]
    pub fn intersect(
        &self,
        ray: &Ray<S>,
        span: Span<S>,
        method: SphereMethod,
        roots: RootMethod,
    ) -> Option<S> {
        let (near, far) = self.roots(ray, method, roots)?;
        if span.contains(near) {
            Some(near)
        } else {
            span.contains(far).then_some(far)
        }
    }

    /// Where a ray that starts inside the sphere leaves it: the far root only.
    #[must_use]
    pub fn exit(
        &self,
        ray: &Ray<S>,
        span: Span<S>,
        method: SphereMethod,
        roots: RootMethod,
    ) -> Option<S> {
        let (_, far) = self.roots(ray, method, roots)?;
        span.contains(far).then_some(far)
    }

    /// Both roots of |o + t·d − c|² = r², nearer first, or `None` when the ray's line misses
    /// the sphere or the sphere lies wholly behind the origin.
    #[inline(always)]
    fn roots(&self, ray: &Ray<S>, method: SphereMethod, roots: RootMethod) -> Option<(S, S)> {
        match method {
            SphereMethod::Quadratic => self.quadratic(ray, roots),
            SphereMethod::Stable => self.stable(ray, roots),
        }
    }

    /// The lecture's quadratic: with a = d·d = 1 for a unit direction and the linear
    /// coefficient halved (b = d·(o − c)), t = −b ± √(b² − c) with c = |o − c|² − r².
    #[inline(always)]
    fn quadratic(&self, ray: &Ray<S>, roots: RootMethod) -> Option<(S, S)> {
        let oc = ray.origin - self.center;
        let b = ray.dir.dot(oc);
        let c = oc.length_squared() - self.radius_squared;
        // Outside (c > 0) and heading away (b > 0): both roots are negative.
        if c > S::ZERO && b > S::ZERO {
            return None;
        }
        let discriminant = b * b - c;
        if discriminant < S::ZERO {
            return None;
        }
        let root = roots.sqrt(discriminant);
        Some((-b - root, -b + root))
    }

    /// Haines et al. (Ray Tracing Gems, ch. 7), with f = o − c and b = −f·d: the discriminant
    /// r² − |f + b·d|² is r² less the squared distance of the ray's line from the centre, a
    /// difference of two numbers of the size of r² rather than of |f|²; one root is
    /// q = b + sign(b)·√Δ, a sum of two numbers of one sign, and the other c/q (their product
    /// is c = |f|² − r²), so neither root cancels.
    fn stable(&self, ray: &Ray<S>, roots: RootMethod) -> Option<(S, S)> {
        let f = ray.origin - self.center;
        let b = -ray.dir.dot(f);
        let c = f.length_squared() - self.radius_squared;
        if c > S::ZERO && b < S::ZERO {
            return None;
        }
        let discriminant = self.radius_squared - f.add_scaled(ray.dir, b).length_squared();
        if discriminant < S::ZERO {
            return None;
        }
        let root = roots.sqrt(discriminant);
        let q = if b < S::ZERO { b - root } else { b + root };
        let other = roots.div(c, q);
        Some(if q < other { (q, other) } else { (other, q) })
    }

    /// The surface point nearest `point` and the outward unit normal there: n = (p − c)/|p − c|
    /// and c + r·n. A hit point computed as o + t·d lies off the surface by the error in t,
    /// which the quadratic amplifies near the silhouette; starting secondary rays from the
    /// surface itself keeps them from hitting it again.
    #[inline]
    #[must_use]
    pub fn surface(&self, point: Vec3<S>, roots: RootMethod) -> (Vec3<S>, Vec3<S>) {
        let normal = (point - self.center).normalized(roots);
        (self.center.add_scaled(normal, self.radius), normal)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::MethodName;
    use crate::test_util::{assert_close, for_each_format, span, v};

    /// Runs `check` with every sphere method and exact roots.
    fn each_method<S: Scalar>(
        check: impl Fn(&dyn Fn(&Sphere<S>, &Ray<S>, Span<S>) -> Option<S>, &str),
    ) {
        for &(method, name) in SphereMethod::ALL {
            check(
                &|sphere, ray, span| sphere.intersect(ray, span, method, RootMethod::Exact),
                name,
            );
        }
    }

    #[test]
    fn hits_head_on_at_the_near_surface() {
        for_each_format!(S, {
            each_method::<S>(|hit, method| {
                let sphere = Sphere::new(v::<S>(0.0, 0.0, 5.0), S::from_int(1));
                let ray = Ray::new(v(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0));
                let t = hit(&sphere, &ray, span(100.0)).unwrap_or_else(|| panic!("{method}"));
                assert_close(t, 4.0, 1e-4);
                let (p, n) = sphere.surface(ray.at(t), RootMethod::Exact);
                assert_close(n.z, -1.0, 1e-4);
                assert_close(n.x, 0.0, 1e-4);
                assert_close(p.z, 4.0, 1e-4);
            });
        });
    }

    #[test]
    fn known_oblique_hit_point_and_normal() {
        for_each_format!(S, {
            each_method::<S>(|hit, method| {
                // A ray along +z at x = 0.6 meets the unit sphere at z = c − 0.8, normal
                // (0.6, 0, −0.8).
                let sphere = Sphere::new(v::<S>(0.0, 0.0, 3.0), S::from_int(1));
                let ray = Ray::new(v(0.6, 0.0, 0.0), v(0.0, 0.0, 1.0));
                let t = hit(&sphere, &ray, span(100.0)).unwrap_or_else(|| panic!("{method}"));
                assert_close(t, 2.2, 1e-4);
                let (_, n) = sphere.surface(ray.at(t), RootMethod::Exact);
                assert_close(n.x, 0.6, 1e-4);
                assert_close(n.z, -0.8, 1e-4);
            });
        });
    }

    #[test]
    fn a_ray_from_inside_hits_the_far_side_and_exit_finds_it() {
        for_each_format!(S, {
            each_method::<S>(|hit, method| {
                let sphere = Sphere::new(v::<S>(0.0, 0.0, 0.0), S::from_int(2));
                let ray = Ray::new(v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0));
                let t = hit(&sphere, &ray, span(100.0)).unwrap_or_else(|| panic!("{method}"));
                assert_close(t, 2.0, 1e-4);
                assert_close(sphere.surface(ray.at(t), RootMethod::Exact).1.x, 1.0, 1e-4);
            });
            for &(method, _) in SphereMethod::ALL {
                // From the near surface inwards, the exit is the far surface, 2r away.
                let sphere = Sphere::new(v::<S>(0.0, 0.0, 5.0), S::from_int(1));
                let ray = Ray::new(v(0.0, 0.0, 4.0), v(0.0, 0.0, 1.0));
                let zero = Span {
                    min: S::ZERO,
                    max: S::from_int(100),
                };
                let t = sphere.exit(&ray, zero, method, RootMethod::Exact);
                assert_close(t.unwrap(), 2.0, 1e-4);
            }
        });
    }

    #[test]
    fn misses_beside_behind_and_beyond() {
        for_each_format!(S, {
            each_method::<S>(|hit, method| {
                let sphere = Sphere::new(v::<S>(0.0, 0.0, 5.0), S::from_int(1));
                let beside = Ray::new(v(1.01, 0.0, 0.0), v(0.0, 0.0, 1.0));
                assert_eq!(hit(&sphere, &beside, span(100.0)), None, "{method}");
                let away = Ray::new(v(0.0, 0.0, 0.0), v(0.0, 0.0, -1.0));
                assert_eq!(hit(&sphere, &away, span(100.0)), None, "{method}: behind");
                let toward = Ray::new(v(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0));
                assert_eq!(
                    hit(&sphere, &toward, span(3.9)),
                    None,
                    "{method}: beyond the span"
                );
            });
        });
    }

    #[test]
    fn tangent_ray_touches_once() {
        for_each_format!(S, {
            each_method::<S>(|hit, method| {
                let sphere = Sphere::new(v::<S>(0.0, 0.0, 5.0), S::from_int(1));
                let ray = Ray::new(v(1.0, 0.0, 0.0), v(0.0, 0.0, 1.0));
                let t = hit(&sphere, &ray, span(100.0)).unwrap_or_else(|| panic!("{method}"));
                assert_close(t, 5.0, 1e-2);
            });
        });
    }

    #[test]
    fn the_stable_form_resolves_a_small_distant_sphere_the_quadratic_cannot() {
        // r/|oc| = 1/10 000 in f32: b² − c loses every bit of r²; r² − |f + b·d|² keeps them.
        let sphere = Sphere::new(v::<f32>(0.0, 0.0, 10_000.0), 1.0);
        let ray = Ray::new(v(0.5, 0.0, 0.0), v(0.0, 0.0, 1.0));
        let stable = sphere.intersect(
            &ray,
            span(20_000.0),
            SphereMethod::Stable,
            RootMethod::Exact,
        );
        let exact = 10_000.0 - 0.75_f64.sqrt();
        assert_close(stable.unwrap(), exact, 2e-3);
        let lecture = sphere.intersect(
            &ray,
            span(20_000.0),
            SphereMethod::Quadratic,
            RootMethod::Exact,
        );
        assert!(
            lecture.is_none_or(|t| (f64::from(t) - exact).abs() > 0.5),
            "{lecture:?}"
        );
    }

    #[test]
    fn approximate_roots_stay_close() {
        type S = crate::scalar::I16F16;
        let sphere = Sphere::new(v::<S>(0.0, 0.0, 3.0), S::from_int(1));
        let ray = Ray::new(v(0.6, 0.0, 0.0), v(0.0, 0.0, 1.0));
        for &(method, _) in SphereMethod::ALL {
            let t = sphere.intersect(&ray, span(100.0), method, RootMethod::Approx);
            assert_close(t.unwrap(), 2.2, 1e-3);
        }
    }
}
