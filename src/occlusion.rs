//! Which objects can shadow a point from a light, so that a shadow ray tests only those: each
//! object's [`Cone`] as seen from each light, found once when the scene is built.
//!
//! A shadow ray runs from a surface point towards a light. It can meet an object only if the
//! segment from the point to the light passes through the object's ball (a sphere, or a
//! triangle's ball about its centroid): only if the direction from the light to the point lies
//! in the cone from the light that holds the ball. At the tracer's cost of one dot product, a
//! ray outside the cone skips the object's test, which costs a sphere about seven products and a
//! triangle more, and a quotient. Planes have no ball, Möller–Trumbore's triangles
//! no error bound (see [`crate::cull`]): their rays test them always.
//!
//! As with culling, a skipped test would change the picture, so the cone holds every ray that
//! could meet the object whatever the rounding: the ball is widened by [`REACH_ERRORS`] times
//! the error with which a ray from anywhere in the world finds it, by the disc of an area light
//! (its shadow rays aim at points of the disc), and by how far a computed shadow ray's end may
//! be from the light (its direction's error over the longest shadow ray); its angle by
//! [`REACH_ERRORS`] times that direction's error; its cosine by the dot product's rounding.

crate::phase::declare_phase!(Some(crate::phase::Phase::Cones));

use crate::scalar::REACH_ERRORS;
use crate::scalar::Scalar;
use crate::vec3::Vec3;

/// The directions from a light towards the points an object may shadow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cone<S> {
    /// Every direction: every shadow ray tests the object.
    Everywhere,
    /// Those whose dot product with `axis` reaches `cos`.
    Within {
        /// The unit vector from the object's centre towards the light.
        axis: Vec3<S>,
        /// The cosine of the cone's half-angle, less the errors.
        cos: S,
    },
}

crate::words::words_of_enum!(Cone<S> {
    Everywhere,
    Within { axis, cos }
});

impl<S: Scalar> Cone<S> {
    /// The cone of `ball` (its centre and radius relative to the eye, widened as the module
    /// documentation says), for a light at `light` (relative to the eye) of disc radius
    /// `radius`, in a world where no shadow ray is longer than `longest`; `None` where a
    /// direction does not fit the format (it does: its parts are at most 2 in size).
    #[must_use]
    pub(crate) fn of(
        ball: Option<(Vec3<f64>, f64)>,
        light: Vec3<f64>,
        radius: f64,
        longest: f64,
    ) -> Option<Self> {
        let Some((centre, ball_radius)) = ball else {
            return Some(Self::Everywhere);
        };
        // The error of a shadow ray's direction as an angle: its unit vector's coordinates,
        // and those of the light less the point it starts from (exact in fixed point, to the
        // last place of the result in a float); an angle errs by at most √3 times a
        // coordinate.
        let aim = 3.0_f64.sqrt() * (S::UNIT_ERROR + 2.0 * S::resolution(1.0))
            + if S::FAST_ROOTS {
                2.0 * crate::scalar::FAST_ROOT_ERROR
            } else {
                0.0
            };
        let aim = REACH_ERRORS * aim;
        // Where a computed shadow ray ends, against the light's centre: the disc, the
        // direction's error along the ray, and the rounding of its length and of the disc's
        // point.
        let end = radius * (1.0 + aim) + longest * aim + 4.0 * S::resolution(longest);
        let reach = ball_radius + end;
        let towards_light = light - centre;
        let distance = towards_light.length();
        if distance <= reach || distance == 0.0 {
            return Some(Self::Everywhere);
        }
        // cos(θ + aim) ≥ cos θ·(1 − aim²/2) − sin θ·aim, for sin θ = reach/distance.
        let sin = reach / distance;
        let cos = libm::sqrt(1.0 - sin * sin);
        let threshold = cos * (1.0 - 0.5 * aim * aim) - sin * aim
            // The dot product's rounding and the axis's, at a unit vector's size.
            - REACH_ERRORS * (3.0 * S::resolution(1.0) + S::UNIT_ERROR);
        if threshold <= -1.0 {
            return Some(Self::Everywhere);
        }
        Some(Self::Within {
            axis: (towards_light * (1.0 / distance)).convert()?,
            cos: S::from_f64(threshold)?,
        })
    }

    /// Whether a shadow ray whose unit direction is `l` (towards this cone's light) may meet the
    /// cone's object.
    #[inline(always)]
    #[must_use]
    pub fn admits(&self, l: Vec3<S>) -> bool {
        match *self {
            Self::Everywhere => true,
            Self::Within { axis, cos } => l.dot(axis) >= cos,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ball_off_the_line_to_the_light_is_outside_its_cone() {
        // A light 10 units up; a unit ball 5 units up: its cone's half-angle is asin(1/5).
        let light = Vec3::new(0.0, 10.0, 0.0);
        let cone =
            Cone::<f64>::of(Some((Vec3::new(0.0, 5.0, 0.0), 1.0)), light, 0.0, 20.0).expect("fits");
        let towards = |x: f64, y: f64| Vec3::new(x, y, 0.0).normalized(crate::RootMethod::Exact);
        // From straight below, and from just inside the cone's edge: admitted.
        assert!(cone.admits(towards(0.0, 1.0)));
        let edge = libm::asin(0.2);
        assert!(cone.admits(towards(-libm::sin(edge - 1e-6), libm::cos(edge - 1e-6))));
        // Well outside it: not.
        assert!(!cone.admits(towards(-libm::sin(edge + 0.01), libm::cos(edge + 0.01))));
        // A light inside the ball: every direction.
        let inside = Cone::<f64>::of(Some((light, 1.0)), light, 0.0, 20.0).expect("fits");
        assert_eq!(inside, Cone::Everywhere);
    }
}
