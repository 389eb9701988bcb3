//! Which objects can shadow a point from a light, so that a shadow ray tests only those: each
//! object's [`Cone`] as seen from each light, found once when the scene is built.
//!
//! A shadow ray runs from a surface point towards a light. It can meet an object only if the
//! segment from the point to the light passes through the object's ball (a sphere, or a
//! triangle's ball about its centroid): only if the direction from the light to the point lies
//! in the cone from the light that holds the ball. At the tracer's cost of one dot product, a
//! ray outside the cone skips the object's test, which costs a sphere about seven products and a
//! triangle more, and a quotient. Möller–Trumbore's triangles have no error bound (see
//! [`crate::cull`]): their rays test them always.
//!
//! A plane has no ball, but it has sides (`Side`): a shadow ray meets it only if the ray
//! starts beyond it, or if the computed segment strays across it. Where the light, the far end
//! of every shadow ray aimed at it, and every point of every other object that a shadow ray
//! may start from lie on the light's side, clear of the plane by more than the error with
//! which a ray finds the plane, no shadow ray from that light meets it ([`Cone::NOWHERE`]):
//! the floor under a scene lit from above. The plane's own points start shadow rays on the
//! light's side alone, as Lambert's cosine is negative on its far side whatever the rounding
//! (the light is required that steep), and the surface tolerance keeps a ray from meeting the
//! surface it leaves, as on every surface. An opaque sphere that rays meet from outside alone
//! starts shadow rays from its lit cap alone, which may clear the plane where the sphere
//! itself does not: a ball resting on the floor.
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
    /// Those whose dot product with `axis` reaches `cos`; none, with a zero axis and a cosine
    /// above it ([`Self::NOWHERE`]).
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

/// The error of a shadow ray's direction as an angle: its unit vector's coordinates, and those
/// of the light less the point it starts from (exact in fixed point, to the last place of the
/// result in a float); an angle errs by at most √3 times a coordinate. [`REACH_ERRORS`] times
/// that.
fn aim<S: Scalar>() -> f64 {
    let aim = 3.0_f64.sqrt() * (S::UNIT_ERROR + 2.0 * S::resolution(1.0))
        + if S::FAST_ROOTS {
            2.0 * crate::scalar::FAST_ROOT_ERROR
        } else {
            0.0
        };
    REACH_ERRORS * aim
}

/// How far a computed shadow ray may end from the centre of a light of disc radius `radius`, in
/// a world where no shadow ray is longer than `longest`: the disc, the direction's error along
/// the ray, and the rounding of its length and of the disc's point.
pub(crate) fn end_error<S: Scalar>(radius: f64, longest: f64) -> f64 {
    let aim = aim::<S>();
    radius * (1.0 + aim) + longest * aim + 4.0 * S::resolution(longest)
}

/// How far each coordinate of a computed unit vector may be off, with the fast roots' error
/// where the format has them (whichever method the scene takes).
pub(crate) fn unit_error<S: Scalar>() -> f64 {
    S::UNIT_ERROR
        + if S::FAST_ROOTS {
            crate::scalar::FAST_ROOT_ERROR
        } else {
            0.0
        }
}

/// How far Lambert's cosine, the dot product of two unit vectors taken in the narrow format,
/// may be off: each vector's coordinates by the unit vector's error and the narrowing's, over
/// three products, and the three products' rounding; [`REACH_ERRORS`] times that.
pub(crate) fn cosine_error<S: Scalar>() -> f64 {
    let narrow = <S::Narrow as crate::scalar::Precision>::resolution(1.0);
    REACH_ERRORS * (2.0 * 3.0_f64.sqrt() * (unit_error::<S>() + narrow) + 3.0 * narrow)
}

impl<S: Scalar> Cone<S> {
    /// No direction: no shadow ray meets the object (a plane the light and every shadow ray's
    /// start lie clear of, on one side). A cone of its own, where a variant of its own would
    /// cost every other cone's test a branch.
    pub const NOWHERE: Self = Self::Within {
        axis: Vec3 {
            x: S::ZERO,
            y: S::ZERO,
            z: S::ZERO,
        },
        cos: S::ONE,
    };

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
        let aim = aim::<S>();
        let reach = ball_radius + end_error::<S>(radius, longest);
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

/// A plane as the shadow rays of one light see it: a point of it and its unit normal turned
/// towards the light, relative to the eye. A shadow ray meets the plane only if it starts
/// beyond it (on the far side from the light), or if its computed segment strays across: so a
/// plane with the light and every point a shadow ray can start from clear of it on the
/// light's side, by more than the errors, shadows nothing from that light ([`Cone::NOWHERE`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Side {
    point: Vec3<f64>,
    normal: Vec3<f64>,
}

impl Side {
    /// The plane through `point` with `normal` (any length but zero), turned towards `light`;
    /// `None` where the light is on the plane.
    pub(crate) fn towards(point: Vec3<f64>, normal: Vec3<f64>, light: Vec3<f64>) -> Option<Self> {
        let length = normal.length();
        if length == 0.0 {
            return None;
        }
        let normal = normal * (1.0 / length);
        let height = normal.dot(light - point);
        if height == 0.0 {
            return None;
        }
        let normal = if height > 0.0 { normal } else { -normal };
        Some(Self { point, normal })
    }

    /// How far `p` lies on the light's side of the plane (negative beyond it).
    pub(crate) fn height(&self, p: Vec3<f64>) -> f64 {
        self.normal.dot(p - self.point)
    }

    /// The height of another plane's every point: of a plane parallel to this one, its
    /// height; `None` for one that is not, which crosses this one somewhere.
    pub(crate) fn height_of_plane(&self, point: Vec3<f64>, normal: Vec3<f64>) -> Option<f64> {
        let length = normal.length();
        let parallel = length > 0.0 && self.normal.cross(normal * (1.0 / length)).length() == 0.0;
        parallel.then(|| self.height(point))
    }

    /// The lowest point of the ball about `centre` of `radius`.
    pub(crate) fn lowest_of_ball(&self, centre: Vec3<f64>, radius: f64) -> f64 {
        self.height(centre) - radius
    }

    /// The lowest point a shadow ray towards a point light at `light` can start from on an
    /// opaque sphere (`centre`, `radius`) met from outside alone: the cap where Lambert's
    /// cosine can be positive. A point X = c + r·m of the sphere faces the light when
    /// m·(L − X) > 0, that is m·ŵ > r/|w| for w = L − c. A shaded point may be `off` the
    /// surface, and a cosine computed as positive may be `cosine_error` below the true one at
    /// it, which widens the cap to m·ŵ ≥ (r − off − ε·(|w| + r + off))/|w|. The lowest point of
    /// a cap of half-angle α about ŵ is at −1 where the cap holds −n, else at −cos(β − α), β the
    /// angle between ŵ and −n; a start point may be `off` below it.
    pub(crate) fn lowest_of_lit_cap(
        &self,
        (centre, radius): (Vec3<f64>, f64),
        off: f64,
        light: Vec3<f64>,
        cosine_error: f64,
    ) -> f64 {
        let w = light - centre;
        let distance = w.length();
        if distance <= radius + off {
            return self.lowest_of_ball(centre, radius + off);
        }
        let k = (radius - off - cosine_error * (distance + radius + off)) / distance;
        let alpha = libm::acos(k.clamp(-1.0, 1.0));
        let beta = libm::acos((-self.normal.dot(w) / distance).clamp(-1.0, 1.0));
        let lowest_cosine = if beta <= alpha {
            -1.0
        } else {
            -libm::cos(beta - alpha)
        };
        self.height(centre) + radius * lowest_cosine - off
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

    #[test]
    fn the_lit_cap_of_a_ball_on_the_floor_clears_it() {
        // A unit ball resting on the floor y = 0, a light 9 above its centre: the lit cap is
        // the part above the tangent circle, 1/9 above the centre; lit from the side (far
        // away, level with the centre), the half that reaches the ball's bottom; with a cosine
        // error of 2, the whole ball; a start point off the surface, lower.
        let floor = Side::towards(Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0), Vec3::new(0.0, 10.0, 0.0))
            .expect("the light is off the floor");
        let centre = Vec3::new(0.0, 1.0, 0.0);
        let ball = (centre, 1.0);
        let above = floor.lowest_of_lit_cap(ball, 0.0, Vec3::new(0.0, 10.0, 0.0), 0.0);
        assert!((above - (1.0 + 1.0 / 9.0)).abs() < 1e-12, "{above}");
        let beside = floor.lowest_of_lit_cap(ball, 0.0, Vec3::new(1e9, 1.0, 0.0), 0.0);
        assert!(beside.abs() < 1e-6, "{beside}");
        assert_eq!(floor.lowest_of_lit_cap(ball, 0.0, Vec3::new(0.0, 10.0, 0.0), 2.0), 0.0);
        let off = floor.lowest_of_lit_cap(ball, 0.01, Vec3::new(0.0, 10.0, 0.0), 0.0);
        assert!(off < above - 0.01, "{off}");
        assert_eq!(floor.lowest_of_ball(centre, 1.0), 0.0);
        // A plane parallel to the floor, and one that crosses it.
        let shelf = Vec3::new(0.0, -3.0, 0.0);
        assert_eq!(floor.height_of_plane(Vec3::new(5.0, 4.0, 0.0), shelf), Some(4.0));
        assert_eq!(floor.height_of_plane(Vec3::new(5.0, 4.0, 0.0), Vec3::new(1.0, 1.0, 0.0)), None);
        // Turned towards a light below it, the floor's side is the other one.
        let under = Side::towards(Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, -5.0, 0.0))
            .expect("the light is off the floor");
        assert_eq!(under.height(centre), -1.0);
    }

    /// Object 0 of `desc`, a plane, from light 0 of it, in format `S`.
    fn plane_cone<S: Scalar>(desc: &crate::SceneDesc<'_>) -> Cone<S> {
        let scene = crate::Scene::<S, 8, 2, 6>::build(desc).expect("the scene builds");
        scene.cones[0][0]
    }

    #[test]
    fn the_floor_under_whitteds_light_shadows_nothing_and_a_floor_that_may_does() {
        use crate::desc::{LightDesc, ObjectDesc, ShapeDesc};
        use crate::scalar::{I16F16, I20F12};
        use crate::scenes::WHITTED;
        // The checkerboard, lit from high above, with a mirror ball resting on it.
        assert_eq!(plane_cone::<f64>(&WHITTED), Cone::NOWHERE);
        assert_eq!(plane_cone::<f32>(&WHITTED), Cone::NOWHERE);
        assert_eq!(plane_cone::<I16F16>(&WHITTED), Cone::NOWHERE);
        // The light under the floor: the floor shadows everything above it.
        let under = [LightDesc::point([-5.0, -12.0, -8.0], [1.0, 1.0, 1.0])];
        let lit_from_below = crate::SceneDesc { lights: &under, ..WHITTED };
        assert_eq!(plane_cone::<f64>(&lit_from_below), Cone::Everywhere);
        // A ball sunk halfway into the floor: its lit cap reaches below it.
        let mut objects: [ObjectDesc; 3] = WHITTED.objects.try_into().expect("three objects");
        objects[1].shape = ShapeDesc::Sphere { center: [-1.2, 0.0, 3.2], radius: 1.0 };
        let sunk = crate::SceneDesc { objects: &objects, ..WHITTED };
        assert_eq!(plane_cone::<f64>(&sunk), Cone::Everywhere);
        // A format whose errors reach the ball's clearance (i20f12's error in finding the floor
        // is sixteen times i16f16's) does not skip.
        assert_eq!(plane_cone::<I20F12>(&WHITTED), Cone::Everywhere);
    }
}
