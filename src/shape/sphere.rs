//! Ray–sphere intersection by the lecture's quadratic.

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

    /// The nearest t in `span` where `ray` meets the sphere.
    ///
    /// The lecture's quadratic |o + t·d − c|² = r²: with a = d·d = 1 for a unit direction and
    /// the linear coefficient halved (b = d·(o − c)), the roots are t = −b ± √(b² − c) with
    /// c = |o − c|² − r². The near root is taken when it lies in the span, else the far one
    /// (a ray that starts inside the sphere).
    #[must_use]
    pub fn intersect(&self, ray: &Ray<S>, span: Span<S>) -> Option<S> {
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
        let root = discriminant.sqrt();
        let near = -b - root;
        if span.contains(near) {
            return Some(near);
        }
        let far = -b + root;
        span.contains(far).then_some(far)
    }

    /// The surface point nearest `point` and the outward unit normal there: n = (p − c)/|p − c|
    /// and c + r·n. A hit point computed as o + t·d lies off the surface by the error in t,
    /// which the quadratic amplifies near the silhouette; starting secondary rays from the
    /// surface itself keeps them from hitting it again.
    #[inline]
    #[must_use]
    pub fn surface(&self, point: Vec3<S>) -> (Vec3<S>, Vec3<S>) {
        let normal = (point - self.center).normalized();
        (self.center.add_scaled(normal, self.radius), normal)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::{assert_close, for_each_format, span, v};

    #[test]
    fn hits_head_on_at_the_near_surface() {
        for_each_format!(S, {
            let sphere = Sphere::new(v::<S>(0.0, 0.0, 5.0), S::from_int(1));
            let ray = Ray::new(v(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0));
            let t = sphere.intersect(&ray, span(100.0)).unwrap();
            assert_close(t, 4.0, 1e-4);
            let (p, n) = sphere.surface(ray.at(t));
            assert_close(n.z, -1.0, 1e-4);
            assert_close(n.x, 0.0, 1e-4);
            assert_close(p.z, 4.0, 1e-4);
        });
    }

    #[test]
    fn known_oblique_hit_point_and_normal() {
        for_each_format!(S, {
            // A ray along +z at x = 0.6 meets the unit sphere at z = c − 0.8, normal (0.6, 0, −0.8).
            let sphere = Sphere::new(v::<S>(0.0, 0.0, 3.0), S::from_int(1));
            let ray = Ray::new(v(0.6, 0.0, 0.0), v(0.0, 0.0, 1.0));
            let t = sphere.intersect(&ray, span(100.0)).unwrap();
            assert_close(t, 2.2, 1e-4);
            let (_, n) = sphere.surface(ray.at(t));
            assert_close(n.x, 0.6, 1e-4);
            assert_close(n.z, -0.8, 1e-4);
        });
    }

    #[test]
    fn a_ray_from_inside_hits_the_far_side() {
        for_each_format!(S, {
            let sphere = Sphere::new(v::<S>(0.0, 0.0, 0.0), S::from_int(2));
            let ray = Ray::new(v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0));
            let t = sphere.intersect(&ray, span(100.0)).unwrap();
            assert_close(t, 2.0, 1e-4);
            assert_close(sphere.surface(ray.at(t)).1.x, 1.0, 1e-4);
        });
    }

    #[test]
    fn misses_beside_behind_and_beyond() {
        for_each_format!(S, {
            let sphere = Sphere::new(v::<S>(0.0, 0.0, 5.0), S::from_int(1));
            let beside = Ray::new(v(1.01, 0.0, 0.0), v(0.0, 0.0, 1.0));
            assert_eq!(sphere.intersect(&beside, span(100.0)), None);
            let away = Ray::new(v(0.0, 0.0, 0.0), v(0.0, 0.0, -1.0));
            assert_eq!(
                sphere.intersect(&away, span(100.0)),
                None,
                "sphere behind the origin"
            );
            let toward = Ray::new(v(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0));
            assert_eq!(
                sphere.intersect(&toward, span(3.9)),
                None,
                "beyond the span"
            );
        });
    }

    #[test]
    fn surface_snaps_a_point_onto_the_sphere() {
        for_each_format!(S, {
            let sphere = Sphere::new(v::<S>(1.0, 2.0, 3.0), S::from_int(2));
            // 0.01 outside along (0.6, 0, 0.8).
            let (p, n) = sphere.surface(v(1.0 + 0.6 * 2.01, 2.0, 3.0 + 0.8 * 2.01));
            assert_close(p.x, 1.0 + 1.2, 1e-4);
            assert_close(p.z, 3.0 + 1.6, 1e-4);
            assert_close(n.x, 0.6, 1e-4);
            assert_close(n.length_squared(), 1.0, 1e-4);
        });
    }

    #[test]
    fn tangent_ray_touches_once() {
        for_each_format!(S, {
            let sphere = Sphere::new(v::<S>(0.0, 0.0, 5.0), S::from_int(1));
            let ray = Ray::new(v(1.0, 0.0, 0.0), v(0.0, 0.0, 1.0));
            let t = sphere.intersect(&ray, span(100.0)).unwrap();
            assert_close(t, 5.0, 1e-2);
        });
    }
}
