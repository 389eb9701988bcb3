//! IEEE floats as scalars: `f64` is the reference every other format is measured against,
//! `f32` is what a Cortex-M4F computes in hardware.
//!
//! Square roots come from `libm` (correctly rounded, pure Rust), so that a host and a
//! microcontroller compute the very same bits.

use super::Scalar;

macro_rules! float_scalar {
    ($($t:ident: $sqrt:path),*) => {$(
        impl Scalar for $t {
            const NAME: &'static str = stringify!($t);
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const MAX: Self = $t::MAX;
            #[allow(trivial_numeric_casts, reason = "the identity cast for f64")]
            const RANGE: f64 = $t::MAX as f64;

            #[inline]
            #[allow(trivial_numeric_casts, clippy::cast_possible_truncation, reason = "range checked")]
            fn from_f64(x: f64) -> Option<Self> {
                (x.is_finite() && x.abs() <= Self::RANGE).then_some(x as $t)
            }

            #[inline]
            fn to_f64(self) -> f64 {
                f64::from(self)
            }

            #[inline]
            #[allow(clippy::cast_precision_loss, reason = "integers here are small")]
            fn from_int(n: i32) -> Self {
                n as $t
            }

            #[inline]
            #[allow(clippy::cast_possible_truncation, reason = "saturating cast intended")]
            #[allow(clippy::cast_precision_loss, reason = "only compared")]
            fn floor_int(self) -> i32 {
                // `as` truncates towards zero and saturates; step down for negative fractions.
                let truncated = self as i32;
                if (truncated as $t) > self { truncated.saturating_sub(1) } else { truncated }
            }

            fn resolution(magnitude: f64) -> f64 {
                magnitude * f64::from($t::EPSILON)
            }

            #[inline]
            fn sqrt(self) -> Self {
                if self > 0.0 { $sqrt(self) } else { 0.0 }
            }
        }
    )*};
}

float_scalar!(f32: libm::sqrtf, f64: libm::sqrt);
