//! IEEE floats as scalars: `f64` is the reference every other format is measured against,
//! `f32` is what a Cortex-M4F computes in hardware.
//!
//! Square roots are IEEE's correctly rounded ones everywhere, so that a host and a
//! microcontroller compute the very same bits: `libm`'s in software, or for `f32` on a
//! Cortex-M4F the FPU's `vsqrt.f32` (a handful of instructions against several hundred).

crate::phase::declare_phase!(Some(crate::phase::Phase::Arithmetic));

use super::{Precision, Scalar};
use core::cmp::Ordering;

/// The correctly rounded square root of an `f32` by the FPU of a Cortex-M4F.
#[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
#[allow(unsafe_code, reason = "calls a leaf function written in assembly")]
mod vsqrt {
    // A leaf function in its own section; the FPU is declared for this one instruction (the
    // core does not rely on the assembler's default), and the hard-float ABI passes the
    // argument and the result in s0.
    core::arch::global_asm!(
        ".section .text.obscura_vsqrt_f32,\"ax\",%progbits",
        ".global obscura_vsqrt_f32",
        ".type obscura_vsqrt_f32,%function",
        ".fpu fpv4-sp-d16",
        ".thumb_func",
        "obscura_vsqrt_f32:",
        "vsqrt.f32 s0, s0",
        "bx lr",
    );

    unsafe extern "C" {
        fn obscura_vsqrt_f32(x: f32) -> f32;
    }

    #[inline]
    pub(super) fn sqrtf(x: f32) -> f32 {
        // SAFETY: the function reads s0, writes s0 and returns; it touches no memory.
        unsafe { obscura_vsqrt_f32(x) }
    }
}

#[cfg(not(all(target_arch = "arm", target_abi = "eabihf")))]
use libm::sqrtf;
#[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
use vsqrt::sqrtf;

macro_rules! float_scalar {
    ($($t:ident: $sqrt:path, $diff:path),*) => {$(
        impl Scalar for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const MAX: Self = $t::MAX;

            #[inline]
            #[allow(clippy::cast_precision_loss, reason = "integers here are small")]
            fn from_int(n: i32) -> Self {
                n as $t
            }

            // A float's narrow numbers are its own.
            super::narrow_is_itself!();

            #[inline]
            #[allow(clippy::cast_precision_loss, reason = "rounded as documented")]
            fn from_q16(bits: i32) -> Self {
                bits as $t / 65_536.0
            }

            #[inline]
            fn to_q16(self) -> i32 {
                (self * 65_536.0).floor_int()
            }

            /// As the default in one saturating conversion: `as u32` truncates a non-negative
            /// value to its floor and takes anything below 0 (and NaN) to 0, which is the floor
            /// of the clamped value there (0 ≤ threshold < 1), so only the top needs a clamp. On
            /// the M4F one `vcvt`, where the clamp's two comparisons cost more than the rest.
            #[inline]
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "saturating cast intended")]
            fn quantize(self, levels: u8, threshold: Self) -> u8 {
                let scaled = self * Self::from(levels) + threshold;
                u8::try_from((scaled as u32).min(u32::from(levels))).unwrap_or(levels)
            }

            #[inline]
            #[allow(clippy::cast_possible_truncation, reason = "saturating cast intended")]
            #[allow(clippy::cast_precision_loss, reason = "only compared")]
            fn floor_int(self) -> i32 {
                // `as` truncates towards zero and saturates; step down for negative fractions.
                let truncated = self as i32;
                if (truncated as $t) > self { truncated.saturating_sub(1) } else { truncated }
            }

            #[inline]
            fn sqrt(self) -> Self {
                if self > 0.0 { $sqrt(self) } else { 0.0 }
            }

            #[inline]
            fn diff_of_products(a: Self, b: Self, c: Self, d: Self) -> (Self, Ordering) {
                $diff(a, b, c, d)
            }
        }

        impl Precision for $t {
            const NAME: &'static str = stringify!($t);

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

            fn resolution(magnitude: f64) -> f64 {
                magnitude * f64::from($t::EPSILON)
            }

            /// A unit vector is its vector times a correctly rounded reciprocal of a correctly
            /// rounded root: about a unit in the last place.
            #[allow(trivial_numeric_casts, reason = "the identity cast for f64")]
            const UNIT_ERROR: f64 = $t::EPSILON as f64;
        }
    )*};
}

float_scalar!(f32: sqrtf, diff_f32, f64: libm::sqrt, diff_f64);

/// a·b − c·d for f32: the products of two f32 are exact in f64, and rounding their difference
/// keeps its sign, so the sign is exact and the value rounded twice at most.
#[inline]
#[allow(
    clippy::cast_possible_truncation,
    reason = "rounding to f32 is the point"
)]
pub(super) fn diff_f32(a: f32, b: f32, c: f32, d: f32) -> (f32, Ordering) {
    let exact = f64::from(a) * f64::from(b) - f64::from(c) * f64::from(d);
    (
        exact as f32,
        exact.partial_cmp(&0.0).unwrap_or(Ordering::Equal),
    )
}

/// a·b − c·d for f64 by Kahan's algorithm: the rounding error of c·d, recovered with a fused
/// multiply-add, is added back, so the result is within 1.5 ulp and its sign exact.
#[inline]
fn diff_f64(a: f64, b: f64, c: f64, d: f64) -> (f64, Ordering) {
    let cd = c * d;
    let error = libm::fma(-c, d, cd);
    let value = libm::fma(a, b, -cd) + error;
    (value, value.partial_cmp(&0.0).unwrap_or(Ordering::Equal))
}
