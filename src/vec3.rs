//! [`Vec3`]: a point or direction in three dimensions, generic over the number format.

crate::phase::declare_phase!(Some(crate::phase::Phase::Arithmetic));

use crate::methods::RootMethod;
use crate::scalar::Scalar;
use core::ops::{Add, Mul, Neg, Sub};

/// The length a vector must exceed to give a direction at the precision descriptions are
/// written in: f32's epsilon.
pub const SHORTEST_DIRECTION: f64 = f32::EPSILON as f64;

/// A point or direction.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3<S> {
    /// The x coordinate (right, in the built-in scenes).
    pub x: S,
    /// The y coordinate (up, in the built-in scenes).
    pub y: S,
    /// The z coordinate.
    pub z: S,
}

crate::words::words_of_struct!(Vec3<S> { x, y, z });

impl<S: Scalar> Vec3<S> {
    /// The origin.
    pub const ZERO: Self = Self::new(S::ZERO, S::ZERO, S::ZERO);

    /// A vector from its coordinates.
    #[inline]
    #[must_use]
    pub const fn new(x: S, y: S, z: S) -> Self {
        Self { x, y, z }
    }

    /// Converts from `f64` coordinates, or `None` when one does not fit the format.
    #[must_use]
    pub fn from_f64(v: [f64; 3]) -> Option<Self> {
        Some(Self::new(
            S::from_f64(v[0])?,
            S::from_f64(v[1])?,
            S::from_f64(v[2])?,
        ))
    }

    /// The coordinates as `f64`.
    #[must_use]
    pub fn to_f64(self) -> [f64; 3] {
        [self.x.to_f64(), self.y.to_f64(), self.z.to_f64()]
    }

    /// A unit vector in the narrow format ([`Scalar::Narrow`]), each coordinate rounded to
    /// nearest: what the cosines of shading are taken of.
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn narrow(self) -> Vec3<S::Narrow> {
        Vec3::new(self.x.narrow(), self.y.narrow(), self.z.narrow())
    }

    /// The dot product, rounded once in fixed point (see [`Scalar::dot3`]).
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn dot(self, rhs: Self) -> S {
        S::dot3([self.x, self.y, self.z], [rhs.x, rhs.y, rhs.z])
    }

    /// The cross product.
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn cross(self, rhs: Self) -> Self {
        Self::new(
            self.y * rhs.z - self.z * rhs.y,
            self.z * rhs.x - self.x * rhs.z,
            self.x * rhs.y - self.y * rhs.x,
        )
    }

    /// The squared length.
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn length_squared(self) -> S {
        self.dot(self)
    }

    /// The length.
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn length(self) -> S {
        self.length_squared().sqrt()
    }

    /// The unit vector in the same direction, by one reciprocal square root. The zero vector
    /// stays zero.
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn normalized(self, roots: RootMethod) -> Self {
        self.normalized_with_length(roots).0
    }

    /// The unit vector in the same direction and the length, from one reciprocal square root
    /// ([`Scalar::normalize3`]). The zero vector gives (zero, zero).
    #[inline(always)]
    #[must_use]
    #[track_caller]
    pub fn normalized_with_length(self, roots: RootMethod) -> (Self, S) {
        let ([x, y, z], length) =
            S::normalize3([self.x, self.y, self.z], roots == RootMethod::Approx);
        (Self::new(x, y, z), length)
    }

    /// The point of the plane n·p = `offset` nearest `self`, for a unit normal n:
    /// p − n·(n·p − offset).
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn onto_plane(self, normal: Self, offset: S) -> Self {
        self.add_scaled(normal, offset - normal.dot(self))
    }

    /// The largest magnitude of a coordinate: the vector's size in the maximum norm.
    #[inline]
    #[must_use]
    pub fn max_abs(self) -> S {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }

    /// Coordinate `axis` (0, 1, 2: x, y, z), or `None` beyond z.
    #[inline]
    #[must_use]
    pub(crate) const fn get(self, axis: usize) -> Option<S> {
        match axis {
            0 => Some(self.x),
            1 => Some(self.y),
            2 => Some(self.z),
            _ => None,
        }
    }

    /// The vector with coordinate `axis` (0, 1, 2: x, y, z) set to `value`; itself beyond z.
    #[inline]
    #[must_use]
    pub(crate) const fn with(self, axis: usize, value: S) -> Self {
        match axis {
            0 => Self { x: value, ..self },
            1 => Self { y: value, ..self },
            2 => Self { z: value, ..self },
            _ => self,
        }
    }

    /// `self + d·t`: the point at parameter `t` along a ray.
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn add_scaled(self, d: Self, t: S) -> Self {
        Self::new(self.x + d.x * t, self.y + d.y * t, self.z + d.z * t)
    }
}

/// Build-time geometry of a scene description, in double precision.
impl Vec3<f64> {
    /// A point or direction of a description, exactly.
    #[must_use]
    pub fn from_f32([x, y, z]: [f32; 3]) -> Self {
        Self::new(f64::from(x), f64::from(y), f64::from(z))
    }

    /// The unit vector, or `None` for a vector too short to have a direction in the format.
    #[must_use]
    pub fn direction(self) -> Option<Self> {
        let length = self.length();
        (length > SHORTEST_DIRECTION).then(|| self * length.recip())
    }

    /// Converts to format `S`, or `None` when a coordinate does not fit.
    #[must_use]
    pub fn convert<S: Scalar>(self) -> Option<Vec3<S>> {
        Vec3::from_f64(self.to_f64())
    }
}

impl<S: Scalar> Add for Vec3<S> {
    type Output = Self;
    #[inline]
    #[track_caller]
    fn add(self, rhs: Self) -> Self {
        Self::new(self.x + rhs.x, self.y + rhs.y, self.z + rhs.z)
    }
}

impl<S: Scalar> Sub for Vec3<S> {
    type Output = Self;
    #[inline]
    #[track_caller]
    fn sub(self, rhs: Self) -> Self {
        Self::new(self.x - rhs.x, self.y - rhs.y, self.z - rhs.z)
    }
}

impl<S: Scalar> Neg for Vec3<S> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

impl<S: Scalar> Mul<S> for Vec3<S> {
    type Output = Self;
    #[inline]
    #[track_caller]
    fn mul(self, k: S) -> Self {
        Self::new(self.x * k, self.y * k, self.z * k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;

    fn v<S: Scalar>(x: i32, y: i32, z: i32) -> Vec3<S> {
        Vec3::new(S::from_int(x), S::from_int(y), S::from_int(z))
    }

    fn check<S: Scalar>() {
        let a = v::<S>(1, 2, 3);
        let b = v::<S>(4, -5, 6);
        assert_eq!(a.dot(b).to_f64(), 12.0);
        assert_eq!(a.cross(b), v(27, 6, -13));
        assert_eq!(v::<S>(3, 4, 0).length().to_f64(), 5.0);
        let (n, length) = v::<S>(0, 3, 4).normalized_with_length(RootMethod::Exact);
        let n = n.to_f64();
        assert!(
            (n[1] - 0.6).abs() < 1e-4 && (n[2] - 0.8).abs() < 1e-4,
            "{n:?}"
        );
        assert!((length.to_f64() - 5.0).abs() < 1e-3);
        assert_eq!(Vec3::<S>::ZERO.normalized(RootMethod::Exact), Vec3::ZERO);
        assert_eq!(a.add_scaled(b, S::from_int(2)), v(9, -8, 15));
        assert_eq!(a.onto_plane(v(0, 1, 0), S::from_int(-4)), v(1, -4, 3));
        assert_eq!(a - b + b, a);
        assert_eq!(-a * S::from_int(2), v(-2, -4, -6));
    }

    #[test]
    fn vector_algebra_in_every_format() {
        check::<I16F16>();
        check::<crate::scalar::I32F32>();
        check::<f32>();
        check::<f64>();
    }
}
