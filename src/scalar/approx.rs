//! [`F32Approx`]: `f32` whose square roots, reciprocal square roots and divisions come from
//! micromath's fast approximations instead of correctly rounded operations, called explicitly
//! so that a host (where `std`'s exact `f32::sqrt` would otherwise shadow them) and a
//! microcontroller compute the same bits.

crate::phase::declare_phase!(Some(crate::phase::Phase::Arithmetic));

use super::float::diff_f32;
use super::{Precision, Scalar};
use core::cmp::Ordering;
use core::ops::{Add, Div, Mul, Neg, Sub};
use micromath::F32;

/// An `f32` with micromath's approximations: 1/x by micromath's `recip` (a bit trick and a
/// polynomial, about 10⁻⁵ off) refined by one Newton step, and a division as a product with it;
/// 1/√x by micromath's `invsqrt` bit trick refined by three Newton steps, and √x as x·(1/√x).
/// Sums and products are IEEE's. What is left is a few units in the last place: the cost of an
/// approximation made as precise as f32 without a divider or a square-root unit.
///
/// The refinement is not optional: the bare bit trick is 5 % off, and a ray direction 5 % short
/// misses every sphere further away than a few radii (the tracer's quadratic takes d·d = 1); a
/// quotient 10⁻⁵ off puts a plane's hit 10⁻⁵·t off along the ray, which at the far end of a
/// world is more than a surface tolerance of f32's.
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
#[repr(transparent)]
pub struct F32Approx(pub f32);

impl Add for F32Approx {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        Self(self.0 + rhs.0)
    }
}

impl Sub for F32Approx {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        Self(self.0 - rhs.0)
    }
}

impl Mul for F32Approx {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        Self(self.0 * rhs.0)
    }
}

impl Neg for F32Approx {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self(-self.0)
    }
}

impl Div for F32Approx {
    type Output = Self;
    /// A product with micromath's reciprocal.
    #[inline]
    #[allow(
        clippy::suspicious_arithmetic_impl,
        reason = "that product is the approximation"
    )]
    fn div(self, rhs: Self) -> Self {
        let y = F32(rhs.0).recip().0;
        if !y.is_finite() {
            // A zero or subnormal divisor: the quotient is as infinite as the reciprocal (a
            // Newton step would turn it into NaN, or flip its sign).
            return Self(self.0 * y);
        }
        // Newton for 1/x: y ← y·(2 − x·y), squaring the relative error.
        Self(self.0 * (y * (2.0 - rhs.0 * y)))
    }
}

/// Newton steps after micromath's `invsqrt`: each squares the relative error (times 3/2), from
/// 5 % to 4·10⁻³, 2·10⁻⁵, then f32's own rounding.
const NEWTON_STEPS: usize = 3;

/// How many of f32's units in the last place the refined approximations may be off.
const ULPS: f64 = 4.0;

impl Scalar for F32Approx {
    const ZERO: Self = Self(0.0);
    const ONE: Self = Self(1.0);
    const MAX: Self = Self(f32::MAX);

    #[inline]
    fn from_int(n: i32) -> Self {
        Self(f32::from_int(n))
    }

    // Its narrow numbers are its own, as `f32`'s.
    super::narrow_is_itself!();

    #[inline]
    fn from_q16(bits: i32) -> Self {
        Self(f32::from_q16(bits))
    }

    #[inline]
    fn to_q16(self) -> i32 {
        self.0.to_q16()
    }

    #[inline]
    fn floor_int(self) -> i32 {
        self.0.floor_int()
    }

    #[inline]
    fn sqrt(self) -> Self {
        if self.0 > 0.0 {
            self * self.rsqrt()
        } else {
            Self::ZERO
        }
    }

    #[inline]
    fn rsqrt(self) -> Self {
        if self.0 <= 0.0 {
            return Self::MAX;
        }
        // Newton for 1/√x: y ← y·(3/2 − x/2·y²), each step squaring the relative error.
        let half = 0.5 * self.0;
        let mut y = F32(self.0).invsqrt().0;
        for _ in 0..NEWTON_STEPS {
            y *= 1.5 - half * y * y;
        }
        Self(y)
    }

    #[inline]
    fn diff_of_products(a: Self, b: Self, c: Self, d: Self) -> (Self, Ordering) {
        let (value, sign) = diff_f32(a.0, b.0, c.0, d.0);
        (Self(value), sign)
    }
}

impl Precision for F32Approx {
    const NAME: &'static str = "f32-approx";

    const RANGE: f64 = f32::RANGE;

    #[inline]
    fn from_f64(x: f64) -> Option<Self> {
        f32::from_f64(x).map(Self)
    }

    #[inline]
    fn to_f64(self) -> f64 {
        f64::from(self.0)
    }

    /// A few of f32's steps: the refined approximations' error.
    fn resolution(magnitude: f64) -> f64 {
        ULPS * f32::resolution(magnitude)
    }

    const UNIT_ERROR: f64 = ULPS * f32::UNIT_ERROR;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_and_quotients_are_within_the_resolution_but_not_exact() {
        let mut inexact = 0;
        let within = |got: f32, want: f64| {
            (f64::from(got) - want).abs() <= F32Approx::resolution(want.abs())
        };
        for x in [0.01_f32, 0.5, 1.0, 2.0, 3.0, 9.0, 1234.5, 7.7e6, 3.3e-7] {
            let v = F32Approx(x);
            let exact = f64::from(x);
            assert!(within(v.sqrt().0, exact.sqrt()), "√{x}");
            assert!(within(v.rsqrt().0, 1.0 / exact.sqrt()), "1/√{x}");
            assert!(within((F32Approx(3.0) / v).0, 3.0 / exact), "3/{x}");
            inexact += usize::from(v.sqrt().0 != x.sqrt())
                + usize::from((F32Approx(3.0) / v).0 != 3.0 / x);
        }
        assert!(
            inexact > 0,
            "the approximations are not the exact operations"
        );
        assert_eq!(F32Approx(-4.0).sqrt(), F32Approx::ZERO);
        assert_eq!(F32Approx(0.0).rsqrt(), F32Approx::MAX);
    }

    #[test]
    fn a_quotient_by_zero_or_a_subnormal_is_infinite_with_the_right_sign() {
        let (two, minus_two) = (F32Approx(2.0), F32Approx(-2.0));
        assert_eq!((two / F32Approx(0.0)).0, f32::INFINITY);
        assert_eq!((minus_two / F32Approx(0.0)).0, f32::NEG_INFINITY);
        let tiny = F32Approx(f32::MIN_POSITIVE / 4.0);
        assert!((two / tiny).0 > 0.0 && (minus_two / tiny).0 < 0.0);
        assert!(!(two / tiny).0.is_nan());
    }
}
