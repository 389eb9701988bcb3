//! [`Peak`]: `f64` that remembers the largest magnitude any sum, difference, product or
//! dot product reached, for the tests that hold the range analysis to the measurement (a scene
//! refused for range must really reach beyond the format's range).
//!
//! Quotients and roots are not counted: the formats saturate them by design (see the core's
//! `scalar` module), and the tracer reads a saturated quotient as "beyond the world".

use obscura::Scalar;
use obscura::scalar::Precision;
use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Sub};
use std::sync::atomic::{AtomicU64, Ordering as Atomic};

/// The largest magnitude recorded since the last [`reset`], as `f64` bits (the bits of
/// non-negative floats order as the floats do).
static LARGEST: AtomicU64 = AtomicU64::new(0);

/// Forgets what was recorded.
pub fn reset() {
    LARGEST.store(0, Atomic::SeqCst);
}

/// The largest magnitude recorded since the last [`reset`].
pub fn largest() -> f64 {
    f64::from_bits(LARGEST.load(Atomic::SeqCst))
}

fn record(x: f64) -> Peak {
    LARGEST.fetch_max(x.abs().to_bits(), Atomic::Relaxed);
    Peak(x)
}

/// An `f64` whose arithmetic is recorded.
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct Peak(pub f64);

impl Add for Peak {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        record(self.0 + rhs.0)
    }
}

impl Sub for Peak {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        record(self.0 - rhs.0)
    }
}

impl Mul for Peak {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        record(self.0 * rhs.0)
    }
}

impl Div for Peak {
    type Output = Self;
    fn div(self, rhs: Self) -> Self {
        Self(self.0 / rhs.0)
    }
}

impl Neg for Peak {
    type Output = Self;
    fn neg(self) -> Self {
        Self(-self.0)
    }
}

impl Scalar for Peak {
    const ZERO: Self = Self(0.0);
    const ONE: Self = Self(1.0);
    const MAX: Self = Self(f64::MAX);

    fn from_int(n: i32) -> Self {
        Self(f64::from(n))
    }

    /// Its narrow numbers are its own, as `f64`'s.
    type Narrow = Self;

    fn narrow(self) -> Self {
        self
    }

    fn mul_narrow(self, k: Self) -> Self {
        self * k
    }

    fn from_q16(bits: i32) -> Self {
        Self(f64::from_q16(bits))
    }

    fn to_q16(self) -> i32 {
        self.0.to_q16()
    }

    fn floor_int(self) -> i32 {
        self.0.floor_int()
    }

    fn sqrt(self) -> Self {
        Self(self.0.sqrt())
    }

    /// Like a fixed format, which adds the exact products and rounds once: only the sum must
    /// fit.
    fn dot3(a: [Self; 3], b: [Self; 3]) -> Self {
        record(a[0].0 * b[0].0 + a[1].0 * b[1].0 + a[2].0 * b[2].0)
    }

    fn diff_of_products(a: Self, b: Self, c: Self, d: Self) -> (Self, Ordering) {
        let (value, sign) = f64::diff_of_products(a.0, b.0, c.0, d.0);
        (record(value), sign)
    }
}

impl obscura::scalar::Sealed for Peak {}

impl Precision for Peak {
    const NAME: &'static str = "peak";

    const RANGE: f64 = f64::MAX;

    fn from_f64(x: f64) -> Option<Self> {
        f64::from_f64(x).map(Self)
    }

    fn to_f64(self) -> f64 {
        self.0
    }

    fn resolution(magnitude: f64) -> f64 {
        f64::resolution(magnitude)
    }

    const UNIT_ERROR: f64 = f64::UNIT_ERROR;
}
