//! Fixed-point formats: [`Fx`], one wrapper over any signed type of the `fixed` crate, so that
//! every format is written once, with an [`Overflow`] policy that says what becomes of a sum or
//! product that does not fit.
//!
//! How each operation meets the end of the range, chosen by what the mathematics needs:
//!
//! - `+`, `−`, `×` and dot products are exact while the result fits, and the scene build
//!   ([`crate::scene::range`]) proves that every sum and product the tracer forms for a built
//!   scene fits. Outside that proof the result wraps (two's complement) and the format's
//!   [`Overflow`] policy hears of it first: [`Proven`], the firmware's, relies on the proof (it
//!   costs nothing in a release build and panics in a debug build, so that a hole in the proof
//!   fails the tests); the desktop harness's records the operation and where it happened, and
//!   stops the render with an error rather than show a wrapped number.
//! - Division, reciprocals and negation saturate: a quotient grows without bound as its
//!   divisor shrinks (a ray grazing a plane), and a saturated value reads as "beyond the
//!   world" in every comparison the tracer makes.

crate::phase::declare_phase!(Some(crate::phase::Phase::Arithmetic));

use super::isqrt::{
    MANTISSA_BITS, MANTISSA_SCALE, ROOT_SCALE, RootPair, isqrt_u64, one_step_holds_unit, root_pair,
    rsqrt_fixed, rsqrt_mantissa,
};
use super::kernels::{
    div_i32_fixed, dot3_i32_rounded_wrapping, mul_i32_i16_rounded_wrapping, mul_i32_i16_wide,
    mul_i32_rounded_wrapping, mul_i32_wide, round_shr_i64, round_shr_u64, square_u32_wide,
    square_u64_small,
};
use super::{Precision, Scalar};
use core::cmp::Ordering;
use core::fmt;
use core::hash::Hash;
use core::marker::PhantomData;
use core::ops::{Add, Div, Mul, Neg, Sub};
use core::panic::Location;
use fixed::traits::{Fixed, FixedSigned};
use fixed::types::extra::{IsLessOrEqual, LeEqU16, LeEqU32, LeEqU64, U16};
use fixed::{FixedI16, FixedI32, FixedI64};

/// Signed 16.16 fixed point on `i32`: range ±32 768, resolution 1/65 536 ≈ 1.5·10⁻⁵.
pub type I16F16 = Fx<fixed::types::I16F16>;

/// Signed 20.12 fixed point on `i32`: range ±524 288, resolution 1/4 096 ≈ 2.4·10⁻⁴.
pub type I20F12 = Fx<fixed::types::I20F12>;

/// Signed 32.32 fixed point on `i64`: range ±2.1·10⁹, resolution 2.3·10⁻¹⁰.
pub type I32F32 = Fx<fixed::types::I32F32>;

/// A sum, difference or product whose exact result does not fit its fixed format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Operation {
    /// `a + b`.
    Sum,
    /// `a − b`.
    Difference,
    /// `a × b`, rounded to the format.
    Product,
    /// `a₀b₀ + a₁b₁ + a₂b₂`, rounded once.
    DotProduct,
    /// A number rounded to the format's narrow one ([`Scalar::narrow`]).
    Narrowing,
}

impl fmt::Display for Operation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Sum => "a sum",
            Self::Difference => "a difference",
            Self::Product => "a product",
            Self::Narrowing => "a narrowing",
            Self::DotProduct => "a dot product",
        })
    }
}

/// What a fixed format does with a sum, difference or product that does not fit: the result
/// wraps (two's complement), and [`Overflow::overflowed`] hears of it first.
pub trait Overflow: Copy + Default + Eq + Ord + Hash + fmt::Debug + Send + Sync + 'static {
    /// `operation`, written at `at` in the source, overflowed.
    fn overflowed(operation: Operation, at: &'static Location<'static>);
    /// Whether the policy hears of an overflow at all. Where it does not (a proven scene's
    /// release build), a product is formed without the bits that would only say whether it
    /// fits: on the M0, from its middle 32 bits rather than all 64 ([`WideBits::mul_rounded_wrapping`]).
    const HEARS: bool = true;
}

/// The firmware's policy: the scene build's range proof keeps every sum and product in range,
/// so a release build checks nothing (and would wrap, had the proof a hole); a debug build
/// panics, so that a hole fails the tests.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Proven;

impl Overflow for Proven {
    const HEARS: bool = cfg!(debug_assertions);
    #[inline(always)]
    fn overflowed(operation: Operation, at: &'static Location<'static>) {
        debug_assert!(
            false,
            "fixed-point overflow: {operation} at {at} left the format; the scene's range proof \
             missed it"
        );
    }
}

/// A fixed-point number (see the module documentation for its overflow rules) whose sums and
/// products report an overflow to the policy `O`.
///
/// Products are formed exactly in the double-width integer and rounded once to nearest, so a
/// multiplication is correct to half an LSB.
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(transparent)]
pub struct Fx<F, O = Proven>(F, PhantomData<O>);

impl<F: Fixed, O> Fx<F, O> {
    /// Wraps a number of the `fixed` crate.
    #[inline]
    #[must_use]
    pub const fn new(value: F) -> Self {
        Self(value, PhantomData)
    }

    /// The number of the `fixed` crate inside.
    #[inline]
    #[must_use]
    pub const fn get(self) -> F {
        self.0
    }
}

impl<F: fmt::Debug, O> fmt::Debug for Fx<F, O> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl<F: fmt::Display, O> fmt::Display for Fx<F, O> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

/// The raw integer of a fixed format, with the double-width and root operations the format's
/// arithmetic is built from.
pub trait WideBits: Copy + Ord {
    /// An integer twice as wide as `Self`.
    type Wide: Copy;
    /// The exact product. It cannot overflow: |a·b| ≤ 2^(2n−2) for n-bit inputs.
    fn wide_mul(self, rhs: Self) -> Self::Wide;
    /// The sum of two products, and whether it wrapped.
    fn wide_add(a: Self::Wide, b: Self::Wide) -> (Self::Wide, bool);
    /// self·2^frac / rhs truncated towards zero, or `None` when rhs is zero or the quotient
    /// does not fit (what `fixed`'s `checked_div` gives, without a 64-bit division where the
    /// machine lacks one).
    fn div_fixed(self, rhs: Self, frac: u32) -> Option<Self>;
    /// `wide / 2^frac` rounded to nearest (ties up), and whether it wrapped.
    fn narrow(wide: Self::Wide, frac: u32) -> (Self, bool);
    /// `self·rhs / 2^frac` rounded to nearest (ties up), wrapped: [`Self::narrow`] of
    /// [`Self::wide_mul`] where it fits, without the bits that would only say whether it does.
    #[inline]
    fn mul_rounded_wrapping(self, rhs: Self, frac: u32) -> Self {
        Self::narrow(self.wide_mul(rhs), frac).0
    }
    /// `Σ aᵢ·bᵢ / 2^frac` rounded once to nearest, wrapped: [`Self::mul_rounded_wrapping`]'s
    /// dot product.
    #[inline]
    fn dot3_rounded_wrapping(a: [Self; 3], b: [Self; 3], frac: u32) -> Self {
        let (partial, _) = Self::wide_add(a[0].wide_mul(b[0]), a[1].wide_mul(b[1]));
        let (sum, _) = Self::wide_add(partial, a[2].wide_mul(b[2]));
        Self::narrow(sum, frac).0
    }
    /// `wide / 2^frac` rounded to nearest (ties up), saturated to `Self`.
    fn narrow_saturating(wide: Self::Wide, frac: u32) -> Self;
    /// a·b − c·d exactly in the wide integer (it cannot overflow), with its sign.
    fn wide_diff_of_products(a: Self, b: Self, c: Self, d: Self) -> (Self::Wide, Ordering);
    /// Whether the fast roots below are approximations (true for the 32-bit formats).
    const FAST_ROOTS: bool;
    /// The relative error of [`Self::normalize_raw`]'s roots, where they keep fewer bits than
    /// the format has (0 where they are correctly rounded).
    const ROOT_ERROR: f64;
    /// ⌊√(self · 2^frac)⌋ for `self` > 0: the square root of a fixed-point number with `frac`
    /// fraction bits, in raw units (it always fits); to 17 bits when `fast` and the
    /// format has [`Self::FAST_ROOTS`].
    fn sqrt_raw(self, frac: u32, fast: bool) -> Self;
    /// 1/√self in raw units of a format with `frac` fraction bits, within one unit, saturated;
    /// for `self` > 0; to 17 bits when `fast` and the format has [`Self::FAST_ROOTS`].
    fn rsqrt_raw(self, frac: u32, fast: bool) -> Self;
    /// The unit vector along `v` and its length (saturated), in raw units of a format with
    /// `frac` fraction bits; `None` for the zero vector. |v|² is summed exactly in the wide
    /// integer, so a short vector normalises as precisely as a long one, and no |v|² need fit
    /// the format.
    fn normalize_raw(v: [Self; 3], frac: u32, fast: bool) -> Option<([Self; 3], Self)>;
    /// ⌊self·levels + threshold⌋ in raw units of a format with `frac` fraction bits, clamped to
    /// [0, levels], for 0 ≤ self ≤ 2^frac (one) and 0 ≤ threshold < 2^frac: exact, the sum
    /// below (levels + 1)·2^frac in the wide integer.
    fn quantize_raw(self, levels: u8, threshold: Self, frac: u32) -> u8;
    /// self/b for b > 0, in raw units with `frac` fraction bits ≤ 28, from the fast reciprocal
    /// square root as a mantissa and an exponent: about 14 correct bits whatever the size of b.
    fn div_raw_fast(self, b: Self, frac: u32) -> Self;
    /// The 32-bit words the integer takes ([`super::NumberBits::WORDS`]).
    const WORDS: usize;
    /// The integer's bits, sign-extended to 64.
    fn to_u64(self) -> u64;
    /// The integer whose bits are the low bits of `bits`.
    fn from_u64(bits: u64) -> Self;
}

macro_rules! wide_bits {
    ($($bits:ident => $wide:ident, mul: $mul:path, mul_level: $mul_level:path, div: $div:path, fast: $fast:literal, root_error: $root_error:expr, roots: $sqrt:path, $rsqrt:path, $normalize:path $(, rounded: $mul_rounded:path, $dot_rounded:path)?);*) => {$(
        impl WideBits for $bits {
            type Wide = $wide;
            $(
                #[inline]
                fn mul_rounded_wrapping(self, rhs: Self, frac: u32) -> Self {
                    $mul_rounded(self, rhs, frac)
                }
                #[inline]
                fn dot3_rounded_wrapping(a: [Self; 3], b: [Self; 3], frac: u32) -> Self {
                    $dot_rounded(a, b, frac)
                }
            )?
            const WORDS: usize = <$bits>::BITS.div_ceil(32) as usize;
            #[inline]
            #[allow(clippy::cast_sign_loss, reason = "the bits, sign-extended")]
            fn to_u64(self) -> u64 {
                i64::from(self) as u64
            }
            #[inline]
            #[allow(
                clippy::cast_possible_truncation,
                clippy::cast_possible_wrap,
                reason = "the low bits are the integer's"
            )]
            fn from_u64(bits: u64) -> Self {
                bits as Self
            }
            const FAST_ROOTS: bool = $fast;
            const ROOT_ERROR: f64 = $root_error;
            #[inline]
            fn wide_mul(self, rhs: Self) -> $wide {
                $mul(self, rhs)
            }
            #[inline]
            fn div_fixed(self, rhs: Self, frac: u32) -> Option<Self> {
                $div(self, rhs, frac)
            }
            #[inline]
            fn wide_add(a: $wide, b: $wide) -> ($wide, bool) {
                a.overflowing_add(b)
            }
            #[inline]
            #[allow(clippy::cast_possible_truncation, reason = "wrapping is the point")]
            fn narrow(wide: $wide, frac: u32) -> (Self, bool) {
                let (biased, wrapped) = wide.overflowing_add(1 << (frac - 1));
                let rounded = biased >> frac;
                (rounded as $bits, wrapped || <$bits>::try_from(rounded).is_err())
            }
            #[inline]
            fn narrow_saturating(wide: $wide, frac: u32) -> Self {
                let rounded = wide.saturating_add((1 << frac) >> 1) >> frac;
                <$bits>::try_from(rounded)
                    .unwrap_or(if rounded < 0 { <$bits>::MIN } else { <$bits>::MAX })
            }
            #[inline]
            fn wide_diff_of_products(a: Self, b: Self, c: Self, d: Self) -> ($wide, Ordering) {
                // Each product is below 2^(2n−2) in magnitude, so the difference fits.
                let difference = a.wide_mul(b) - c.wide_mul(d);
                (difference, difference.cmp(&0))
            }
            #[inline]
            fn quantize_raw(self, levels: u8, threshold: Self, frac: u32) -> u8 {
                let scaled = ($mul_level(self, levels) + <$wide>::from(threshold)) >> frac;
                u8::try_from(scaled.clamp(0, <$wide>::from(levels))).unwrap_or(levels)
            }
            #[inline]
            fn normalize_raw(v: [Self; 3], frac: u32, fast: bool) -> Option<([Self; 3], Self)> {
                $normalize(v, frac, fast)
            }
            /// With 1/√b = z·2^(s − 62) (`rsqrt_mantissa`), 1/b = z²·2^(2s − 124); keeping the
            /// top 31 bits of z² as r, the raw quotient self·2^f/b is self·r >> (93 − 2s − f).
            /// As b ≥ 1 (raw), s ≤ 32 and the shift is at least 93 − 64 − 28 = 1.
            #[inline]
            fn div_raw_fast(self, b: Self, frac: u32) -> Self {
                let (z, s) = rsqrt_mantissa(b.unsigned_abs().into(), true);
                // r < 2³¹ fits every signed raw type here.
                let r = <$bits>::try_from(square_u64_small(z) >> MANTISSA_BITS).unwrap_or(<$bits>::MAX);
                let right = 2 * MANTISSA_SCALE - MANTISSA_BITS - 2 * s - frac;
                Self::narrow_saturating(self.wide_mul(r), right)
            }
            #[inline]
            fn sqrt_raw(self, frac: u32, fast: bool) -> Self {
                $sqrt(self, frac, fast)
            }
            #[inline]
            fn rsqrt_raw(self, frac: u32, fast: bool) -> Self {
                $rsqrt(self, frac, fast)
            }
        }
    )*};
}
wide_bits!(
    // The 16-bit narrow format: its roots and quotients are the 32-bit ones', narrowed.
    i16 => i32, mul: mul_i16_wide, mul_level: mul_level_16, div: div_i16_fixed, fast: false, root_error: 0.0, roots: sqrt_raw_16, rsqrt_raw_16, normalize_raw_16;
    i32 => i64, mul: mul_i32_wide, mul_level: mul_level_32, div: div_i32_fixed, fast: true, root_error: 0.0, roots: sqrt_raw_32, rsqrt_raw_32, normalize_raw_32, rounded: mul_i32_rounded_wrapping, dot3_i32_rounded_wrapping;
    // The root pair keeps about 30 bits, short of the 64-bit formats' fraction.
    i64 => i128, mul: mul_i64_wide, mul_level: mul_level_64, div: div_i64_fixed, fast: false, root_error: 1.0 / (1_u64 << 29) as f64, roots: sqrt_raw_64, rsqrt_raw_64, normalize_raw_64
);

/// a·b exactly, for the narrow formats (one `muls` on the M0).
#[inline]
fn mul_i16_wide(a: i16, b: i16) -> i32 {
    i32::from(a) * i32::from(b)
}

/// a times a display's levels (at most 255, a 16-bit factor), exactly: one product on the M0
/// for a narrow number, two partial products for a 32-bit one.
#[inline]
fn mul_level_16(a: i16, levels: u8) -> i32 {
    mul_i16_wide(a, i16::from(levels))
}

#[inline]
fn mul_level_32(a: i32, levels: u8) -> i64 {
    mul_i32_i16_wide(a, i16::from(levels))
}

#[inline]
fn mul_level_64(a: i64, levels: u8) -> i128 {
    mul_i64_wide(a, i64::from(levels))
}

/// a·2^frac / b truncated towards zero for the narrow formats, by the 32-bit formats' division.
#[inline]
fn div_i16_fixed(a: i16, b: i16, frac: u32) -> Option<i16> {
    div_i32_fixed(a.into(), b.into(), frac).and_then(|q| i16::try_from(q).ok())
}

/// The narrow formats' roots and unit vectors: the 32-bit formats', saturated to 16 bits.
#[inline]
fn sqrt_raw_16(x: i16, frac: u32, fast: bool) -> i16 {
    i16::try_from(sqrt_raw_32(x.into(), frac, fast)).unwrap_or(i16::MAX)
}

#[inline]
fn rsqrt_raw_16(x: i16, frac: u32, fast: bool) -> i16 {
    i16::try_from(rsqrt_raw_32(x.into(), frac, fast)).unwrap_or(i16::MAX)
}

#[inline]
fn normalize_raw_16(v: [i16; 3], frac: u32, fast: bool) -> Option<([i16; 3], i16)> {
    let (unit, length) = normalize_raw_32(v.map(i32::from), frac, fast)?;
    let narrow = |x: i32| i16::try_from(x).unwrap_or(if x < 0 { i16::MIN } else { i16::MAX });
    Some((unit.map(narrow), narrow(length)))
}

/// A fixed format and its narrow format ([`Scalar::Narrow`]), chosen by the fraction bits it
/// has to keep: signed 2.14 (16 bits) for a 32-bit format of at most 16 fraction bits, whose own
/// step is no finer (i16f16 to i24f8); signed 2.30 for the finer 32-bit formats (i8f24 to
/// i14f18) and the 64-bit one, whose accuracy 14 bits would cut. A narrow format is its own.
pub trait Narrowed:
    FixedSigned<Bits: WideBits> + fmt::Debug + Default + Send + Sync + 'static
{
    /// The narrow format.
    type Narrow: Narrowed;
    /// The exact product of a number's bits and a narrow number's.
    fn wide_mul_narrow(
        a: Self::Bits,
        k: <Self::Narrow as Fixed>::Bits,
    ) -> <Self::Bits as WideBits>::Wide;
    /// The product of a number's bits and a narrow number's, rounded to `frac` fraction bits
    /// and wrapped ([`WideBits::mul_rounded_wrapping`] for a narrow factor).
    #[inline]
    fn mul_narrow_rounded_wrapping(
        a: Self::Bits,
        k: <Self::Narrow as Fixed>::Bits,
        frac: u32,
    ) -> Self::Bits {
        <Self::Bits as WideBits>::narrow(Self::wide_mul_narrow(a, k), frac).0
    }
}

/// A 32-bit format's narrow format, by whether its fraction has at most 16 bits
/// (`typenum::B1`) or more (`B0`).
pub trait NarrowOf32 {
    /// 2.14 or 2.30.
    type Narrow: Narrowed;
    /// The exact product of a 32-bit number and a narrow one.
    fn wide_mul(a: i32, k: <Self::Narrow as Fixed>::Bits) -> i64;
    /// The product of a 32-bit number and a narrow one, rounded to `frac` fraction bits and
    /// wrapped.
    fn mul_rounded_wrapping(a: i32, k: <Self::Narrow as Fixed>::Bits, frac: u32) -> i32;
}

impl NarrowOf32 for typenum::B1 {
    type Narrow = fixed::types::I2F14;
    #[inline]
    fn wide_mul(a: i32, k: i16) -> i64 {
        mul_i32_i16_wide(a, k)
    }
    #[inline]
    fn mul_rounded_wrapping(a: i32, k: i16, frac: u32) -> i32 {
        mul_i32_i16_rounded_wrapping(a, k, frac)
    }
}

impl NarrowOf32 for typenum::B0 {
    type Narrow = fixed::types::I2F30;
    #[inline]
    fn wide_mul(a: i32, k: i32) -> i64 {
        mul_i32_wide(a, k)
    }
    #[inline]
    fn mul_rounded_wrapping(a: i32, k: i32, frac: u32) -> i32 {
        mul_i32_rounded_wrapping(a, k, frac)
    }
}

/// Whether `Frac` is at most 16: `B1` or `B0`.
type AtMost16<Frac> = <Frac as IsLessOrEqual<U16>>::Output;

impl<Frac> Narrowed for FixedI32<Frac>
where
    Frac: LeEqU32 + IsLessOrEqual<U16> + Send + Sync + 'static,
    AtMost16<Frac>: NarrowOf32,
{
    type Narrow = <AtMost16<Frac> as NarrowOf32>::Narrow;
    #[inline]
    fn wide_mul_narrow(a: i32, k: <Self::Narrow as Fixed>::Bits) -> i64 {
        <AtMost16<Frac> as NarrowOf32>::wide_mul(a, k)
    }
    #[inline]
    fn mul_narrow_rounded_wrapping(a: i32, k: <Self::Narrow as Fixed>::Bits, frac: u32) -> i32 {
        <AtMost16<Frac> as NarrowOf32>::mul_rounded_wrapping(a, k, frac)
    }
}

impl<Frac: LeEqU16 + Send + Sync + 'static> Narrowed for FixedI16<Frac> {
    type Narrow = fixed::types::I2F14;
    #[inline]
    fn wide_mul_narrow(a: i16, k: i16) -> i32 {
        mul_i16_wide(a, k)
    }
}

impl<Frac: LeEqU64 + Send + Sync + 'static> Narrowed for FixedI64<Frac> {
    type Narrow = fixed::types::I2F30;
    #[inline]
    fn wide_mul_narrow(a: i64, k: i32) -> i128 {
        i128::from(a) * i128::from(k)
    }
}

/// a·b exactly, for the 64-bit format (in 128 bits, a library call on every 32-bit machine).
#[inline]
fn mul_i64_wide(a: i64, b: i64) -> i128 {
    i128::from(a) * i128::from(b)
}

/// a·2^frac / b truncated towards zero, for the 64-bit format (in 128 bits).
#[inline]
fn div_i64_fixed(a: i64, b: i64, frac: u32) -> Option<i64> {
    if b == 0 {
        return None;
    }
    i64::try_from((i128::from(a) << frac) / i128::from(b)).ok()
}

/// The 32-bit formats' unit vectors. With y = Σvᵢ² exact in u64 (each below 2⁶², three below
/// 2⁶⁴) and its [`RootPair`] (1/√y = z·2^(s − 62), √y = r·2^−(30 + s)): the unit vector's raw
/// coordinates are vᵢ·2^f/√y = vᵢ·z >> (62 − s − f), the shift at least 62 − 31 − 30 = 1, and
/// the length's raw value √y = r >> (30 + s), rounded. When `fast`, one Newton step where it
/// keeps the coordinates within the format's LSB ([`one_step_holds_unit`]: to 16 fraction bits),
/// else the two of the exact vectors.
#[inline]
fn normalize_raw_32(v: [i32; 3], frac: u32, fast: bool) -> Option<([i32; 3], i32)> {
    let y: u64 = v.iter().map(|&c| square_u32_wide(c.unsigned_abs())).sum();
    if y == 0 {
        return None;
    }
    let RootPair { inverse, root, s } = root_pair(y, fast && one_step_holds_unit(frac));
    // inverse < 2³¹: a 32×32→64 product, not a 64×64 one (a library call on the M0).
    let z = i32::try_from(inverse).unwrap_or(i32::MAX);
    let right = MANTISSA_SCALE - s - frac;
    // |vᵢ·z| ≤ 2⁶², and the coordinate |vᵢ|/√y·2^f at most 2^f (1 + 2⁻²⁹) (z is 1/√y's
    // mantissa to 30 bits), within i32 for f ≤ 30.
    let unit =
        v.map(|c| i32::try_from(round_shr_i64(mul_i32_wide(c, z), right)).unwrap_or(i32::MAX));
    let length = round_shr_u64(root, ROOT_SCALE + s);
    let length = i32::try_from(length).unwrap_or(i32::MAX);
    Some((unit, length))
}

/// The 64-bit formats' unit vectors, as [`normalize_raw_32`] with y = Σvᵢ² exact in u128 and
/// brought below 2⁶² by an even shift 2j (dropping bits far below the 30 the roots keep):
/// 1/√y = z·2^(s − j − 62), so the raw coordinates are 2·vᵢ·z >> (63 + j − s − f) (doubled
/// first, as the shift would be −1 for f = 32 and s = 31), and √y = r·2^(j − 30 − s).
#[inline]
fn normalize_raw_64(v: [i64; 3], frac: u32, fast: bool) -> Option<([i64; 3], i64)> {
    let y: u128 = v
        .iter()
        .map(|&c| u128::from(c.unsigned_abs()) * u128::from(c.unsigned_abs()))
        .sum();
    if y == 0 {
        return None;
    }
    let j = (u128::BITS - y.leading_zeros())
        .saturating_sub(62)
        .div_ceil(2);
    let RootPair { inverse, root, s } = root_pair(u64::try_from(y >> (2 * j)).ok()?, fast);
    let z = i128::from(inverse);
    let right = MANTISSA_SCALE + 1 + j - s - frac;
    let unit = v.map(|c| i64::narrow_saturating(2 * i128::from(c) * z, right));
    let shift = ROOT_SCALE + s;
    let length = ((u128::from(root) << j) + (1 << (shift - 1))) >> shift;
    let length = i64::try_from(length).unwrap_or(i64::MAX);
    Some((unit, length))
}

/// The 32-bit formats' roots: the division-free routines (x·2^frac < 2⁶² for frac ≤ 30).
#[inline]
fn sqrt_raw_32(x: i32, frac: u32, fast: bool) -> i32 {
    i32::try_from(isqrt_u64(u64::from(x.unsigned_abs()) << frac, fast)).unwrap_or(i32::MAX)
}

#[inline]
fn rsqrt_raw_32(x: i32, frac: u32, fast: bool) -> i32 {
    i32::try_from(rsqrt_fixed(x.unsigned_abs(), frac, fast)).unwrap_or(i32::MAX)
}

/// The 64-bit formats' roots, exact whether `fast` or not (they have no fast ones): core's
/// exact integer root on u128, and for the reciprocal one division, as
/// ⌊√⌊2^(3f)/x⌋⌋ = ⌊2^(3f/2)/√x⌋.
#[inline]
fn sqrt_raw_64(x: i64, frac: u32, _fast: bool) -> i64 {
    i64::try_from((u128::from(x.unsigned_abs()) << frac).isqrt()).unwrap_or(i64::MAX)
}

#[inline]
fn rsqrt_raw_64(x: i64, frac: u32, _fast: bool) -> i64 {
    let quotient = (1_u128 << (3 * frac)) / u128::from(x.unsigned_abs());
    i64::try_from(quotient.isqrt()).unwrap_or(i64::MAX)
}

impl<F, O> Fx<F, O>
where
    F: FixedSigned,
    F::Bits: WideBits,
{
    /// One, which every format used here has (at least two integer bits are required).
    const ONE_VALUE: Self = match F::TRY_ONE {
        Some(one) => Self::new(one),
        None => panic!("a tracing format needs integer bits"),
    };

    #[inline]
    fn saturate_towards(sign: Ordering) -> Self {
        match sign {
            Ordering::Less => Self::new(F::MIN),
            Ordering::Equal => Self::new(F::ZERO),
            Ordering::Greater => Self::new(F::MAX),
        }
    }

    #[inline]
    fn from_raw(bits: F::Bits) -> Self {
        Self::new(F::from_bits(bits))
    }

    #[inline]
    fn raw(self) -> F::Bits {
        self.get().to_bits()
    }
}

impl<F: FixedSigned, O: Overflow> Add for Fx<F, O> {
    type Output = Self;
    /// Exact while the sum fits (see the module documentation).
    #[inline]
    #[track_caller]
    fn add(self, rhs: Self) -> Self {
        let (sum, wrapped) = self.0.overflowing_add(rhs.0);
        if wrapped {
            O::overflowed(Operation::Sum, Location::caller());
        }
        Self::new(sum)
    }
}

impl<F: FixedSigned, O: Overflow> Sub for Fx<F, O> {
    type Output = Self;
    /// Exact while the difference fits (see the module documentation).
    #[inline]
    #[track_caller]
    fn sub(self, rhs: Self) -> Self {
        let (difference, wrapped) = self.0.overflowing_sub(rhs.0);
        if wrapped {
            O::overflowed(Operation::Difference, Location::caller());
        }
        Self::new(difference)
    }
}

impl<F: FixedSigned, O> Neg for Fx<F, O> {
    type Output = Self;
    /// Saturating: −MIN is the one negation that does not fit.
    #[inline]
    fn neg(self) -> Self {
        Self::new(self.0.saturating_neg())
    }
}

impl<F, O> Mul for Fx<F, O>
where
    F: FixedSigned,
    F::Bits: WideBits,
    O: Overflow,
{
    type Output = Self;
    /// Rounded to nearest; exact while the product fits (see the module documentation).
    #[inline]
    #[track_caller]
    fn mul(self, rhs: Self) -> Self {
        if !O::HEARS {
            return Self::from_raw(self.raw().mul_rounded_wrapping(rhs.raw(), F::FRAC_NBITS));
        }
        let wide = self.raw().wide_mul(rhs.raw());
        let (product, wrapped) = F::Bits::narrow(wide, F::FRAC_NBITS);
        if wrapped {
            O::overflowed(Operation::Product, Location::caller());
        }
        Self::from_raw(product)
    }
}

impl<F, O> Div for Fx<F, O>
where
    F: FixedSigned,
    F::Bits: WideBits,
{
    type Output = Self;
    /// Truncating division; division by zero and overflow saturate towards the sign of the
    /// true quotient (zero for 0/0).
    #[inline]
    fn div(self, rhs: Self) -> Self {
        match self.0.to_bits().div_fixed(rhs.0.to_bits(), F::FRAC_NBITS) {
            Some(q) => Self::new(F::from_bits(q)),
            None => {
                let sign = if rhs.0 == F::ZERO {
                    self.0.cmp(&F::ZERO)
                } else if (self.0 < F::ZERO) == (rhs.0 < F::ZERO) {
                    Ordering::Greater
                } else {
                    Ordering::Less
                };
                Self::saturate_towards(sign)
            }
        }
    }
}

impl<F, O> Scalar for Fx<F, O>
where
    F: Narrowed,
    O: Overflow,
{
    const ZERO: Self = Self::new(F::ZERO);
    const ONE: Self = Self::ONE_VALUE;
    const MAX: Self = Self::new(F::MAX);

    #[inline]
    fn from_int(n: i32) -> Self {
        Self::new(F::saturating_from_num(n))
    }

    type Narrow = Fx<F::Narrow, O>;

    /// To nearest by adding half the narrow format's step and dropping the bits below it
    /// (`fixed`'s conversions round down); exact where the format is the coarser.
    #[inline]
    #[track_caller]
    fn narrow(self) -> Self::Narrow {
        let (biased, carried) = if F::FRAC_NBITS > F::Narrow::FRAC_NBITS {
            let half = F::DELTA << (F::FRAC_NBITS - F::Narrow::FRAC_NBITS - 1);
            self.0.overflowing_add(half)
        } else {
            (self.0, false)
        };
        let (narrow, wrapped) = F::Narrow::overflowing_from_num(biased);
        if carried || wrapped {
            O::overflowed(Operation::Narrowing, Location::caller());
        }
        Fx::new(narrow)
    }

    /// The exact product, rounded once.
    #[inline]
    #[track_caller]
    fn mul_narrow(self, k: Self::Narrow) -> Self {
        if !O::HEARS {
            let (a, k) = (self.raw(), k.get().to_bits());
            return Self::from_raw(F::mul_narrow_rounded_wrapping(a, k, F::Narrow::FRAC_NBITS));
        }
        let wide = F::wide_mul_narrow(self.raw(), k.get().to_bits());
        let (product, wrapped) = F::Bits::narrow(wide, F::Narrow::FRAC_NBITS);
        if wrapped {
            O::overflowed(Operation::Product, Location::caller());
        }
        Self::from_raw(product)
    }

    #[inline]
    fn from_q16(bits: i32) -> Self {
        Self::new(F::saturating_from_num(fixed::types::I16F16::from_bits(
            bits,
        )))
    }

    #[inline]
    fn to_q16(self) -> i32 {
        fixed::types::I16F16::saturating_from_num(self.0).to_bits()
    }

    #[inline]
    fn floor_int(self) -> i32 {
        self.0.floor().saturating_to_num::<i32>()
    }

    /// Exact, in the wide integer.
    #[inline]
    fn quantize(self, levels: u8, threshold: Self) -> u8 {
        let unit = Scalar::clamp(self, Self::ZERO, Self::ONE).raw();
        F::Bits::quantize_raw(unit, levels, threshold.raw(), F::FRAC_NBITS)
    }

    #[inline]
    fn rsqrt(self) -> Self {
        if self.0 <= F::ZERO {
            Self::MAX
        } else {
            Self::from_raw(self.raw().rsqrt_raw(F::FRAC_NBITS, false))
        }
    }

    const FAST_ROOTS: bool = F::Bits::FAST_ROOTS;

    #[inline]
    fn sqrt_approx(self) -> Self {
        if self.0 <= F::ZERO {
            Self::ZERO
        } else {
            Self::from_raw(self.raw().sqrt_raw(F::FRAC_NBITS, true))
        }
    }

    #[inline]
    fn rsqrt_approx(self) -> Self {
        if self.0 <= F::ZERO {
            Self::MAX
        } else {
            Self::from_raw(self.raw().rsqrt_raw(F::FRAC_NBITS, true))
        }
    }

    #[inline]
    #[track_caller]
    fn normalize3(v: [Self; 3], approx: bool) -> ([Self; 3], Self) {
        match F::Bits::normalize_raw(v.map(Self::raw), F::FRAC_NBITS, approx) {
            Some((unit, length)) => (unit.map(Self::from_raw), Self::from_raw(length)),
            None => (v, Self::ZERO),
        }
    }

    /// a/b = a·(1/√|b|)²·sign(b), the reciprocal square root a fast mantissa and exponent
    /// (a reciprocal's table and a Newton step): no division, and as many correct bits for a large b as
    /// for a small one. The formats without fast roots divide.
    #[inline]
    fn div_approx(self, rhs: Self) -> Self {
        if !F::Bits::FAST_ROOTS || rhs.0 == F::ZERO {
            return self / rhs;
        }
        let quotient = Self::from_raw(self.raw().div_raw_fast(rhs.raw(), F::FRAC_NBITS));
        if rhs.0 < F::ZERO { -quotient } else { quotient }
    }

    #[inline]
    fn diff_of_products(a: Self, b: Self, c: Self, d: Self) -> (Self, Ordering) {
        let [a, b, c, d] = [a, b, c, d].map(Self::raw);
        let (wide, sign) = F::Bits::wide_diff_of_products(a, b, c, d);
        (
            Self::from_raw(F::Bits::narrow_saturating(wide, F::FRAC_NBITS)),
            sign,
        )
    }

    #[inline]
    fn sqrt(self) -> Self {
        if self.0 <= F::ZERO {
            Self::ZERO
        } else {
            Self::from_raw(self.raw().sqrt_raw(F::FRAC_NBITS, false))
        }
    }

    /// The three exact products added in the double-width integer and rounded once; exact
    /// while the sum fits (see the module documentation).
    #[inline]
    #[track_caller]
    fn dot3(a: [Self; 3], b: [Self; 3]) -> Self {
        if !O::HEARS {
            let (a, b) = (a.map(Self::raw), b.map(Self::raw));
            return Self::from_raw(F::Bits::dot3_rounded_wrapping(a, b, F::FRAC_NBITS));
        }
        let p0 = a[0].raw().wide_mul(b[0].raw());
        let p1 = a[1].raw().wide_mul(b[1].raw());
        let p2 = a[2].raw().wide_mul(b[2].raw());
        let (partial, first) = F::Bits::wide_add(p0, p1);
        let (sum, second) = F::Bits::wide_add(partial, p2);
        let (rounded, narrowed) = F::Bits::narrow(sum, F::FRAC_NBITS);
        if first || second || narrowed {
            O::overflowed(Operation::DotProduct, Location::caller());
        }
        Self::from_raw(rounded)
    }
}

impl<F, O> Precision for Fx<F, O>
where
    F: Narrowed,
    O: Overflow,
{
    const NAME: &'static str = FixedName::<F>::NAME;

    const SPLIT: Option<(u32, u32)> = Some((F::INT_NBITS, F::FRAC_NBITS));

    const RANGE: f64 = {
        // MAX = 2^(INT_NBITS − 1) − 2^−FRAC_NBITS, exact in f64 for the formats used here.
        let int = (1_u64 << (F::INT_NBITS - 1)) as f64;
        int - 1.0 / (1_u64 << F::FRAC_NBITS) as f64
    };

    #[inline]
    fn from_f64(x: f64) -> Option<Self> {
        if x.is_finite() {
            F::checked_from_num(x).map(Self::new)
        } else {
            None
        }
    }

    #[inline]
    fn to_f64(self) -> f64 {
        self.0.to_num::<f64>()
    }

    fn resolution(_magnitude: f64) -> f64 {
        F::DELTA.to_num::<f64>()
    }

    /// Correctly rounded (half an LSB) where the roots have the format's bits, else the
    /// roots' relative error.
    const UNIT_ERROR: f64 = {
        let lsb = 1.0 / (1_u64 << F::FRAC_NBITS) as f64;
        if F::Bits::ROOT_ERROR > lsb {
            F::Bits::ROOT_ERROR
        } else {
            lsb
        }
    };
}

/// `"i16f16"` for `I16F16`: the lowercase name of a `fixed` type, spelled at compile time from
/// its integer and fraction bits (each below 100).
struct FixedName<F>(PhantomData<F>);

impl<F: Fixed> FixedName<F> {
    /// The name's bytes and its length.
    #[allow(
        clippy::indexing_slicing,
        clippy::cast_possible_truncation,
        reason = "evaluated at compile time: at most six bytes, each digit below 10"
    )]
    const SPELLED: ([u8; 6], usize) = {
        let mut bytes = [0_u8; 6];
        let mut len = 0;
        let parts = [(b'i', F::INT_NBITS), (b'f', F::FRAC_NBITS)];
        let mut part = 0;
        while part < parts.len() {
            let (letter, bits) = parts[part];
            bytes[len] = letter;
            len += 1;
            if bits >= 10 {
                bytes[len] = b'0' + (bits / 10) as u8;
                len += 1;
            }
            bytes[len] = b'0' + (bits % 10) as u8;
            len += 1;
            part += 1;
        }
        (bytes, len)
    };

    const NAME: &'static str =
        match core::str::from_utf8(Self::SPELLED.0.split_at(Self::SPELLED.1).0) {
            Ok(name) => name,
            Err(_) => panic!("a fixed format's name is ASCII"),
        };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_64_bit_formats_division_is_fixeds() {
        use fixed::types::I32F32 as Raw;
        let edges = [
            0,
            1,
            -1,
            2,
            -2,
            1 << 32,
            -(1 << 32),
            i64::MAX,
            i64::MIN,
            i64::MAX - 1,
        ];
        let sweep = (0..500_i64).map(|i| i.wrapping_mul(0x9E37_79B9_7F4A_7C15_u64 as i64));
        let all: Vec<i64> = edges.into_iter().chain(sweep).collect();
        for &a in &all {
            for &b in &all {
                let expected = Raw::from_bits(a)
                    .checked_div(Raw::from_bits(b))
                    .map(Raw::to_bits);
                assert_eq!(div_i64_fixed(a, b, 32), expected, "{a} / {b}");
            }
        }
    }

    fn fx(x: f64) -> I16F16 {
        I16F16::from_f64(x).unwrap()
    }

    #[test]
    fn long_vectors_normalise_to_the_last_bit() {
        // A normalised vector of length 100 through a 16.16 reciprocal root (0.01, 655 raw)
        // would err by 1/655 relative; the mantissa keeps it within a few LSB.
        for (x, y, z) in [(60.0, 0.0, 80.0), (0.3, -0.4, 0.0), (100.0, 120.0, -50.0)] {
            let v = [fx(x), fx(y), fx(z)];
            let (unit, length) = I16F16::normalize3(v, false);
            let exact = (x * x + y * y + z * z).sqrt();
            for (c, e) in unit.iter().zip([x, y, z]) {
                assert!(
                    (c.to_f64() - e / exact).abs() <= 2.0 / 65_536.0,
                    "{x} {y} {z}: {c:?}"
                );
            }
            assert!(
                (length.to_f64() - exact).abs() <= exact * 1e-8 + 2.0 / 65_536.0,
                "{length:?}"
            );
        }
    }

    /// A policy that keeps what it hears, so that a test can see an overflow reported.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
    struct Recording;

    std::thread_local! {
        static HEARD: std::cell::RefCell<Vec<(Operation, u32)>> = const {
            std::cell::RefCell::new(Vec::new())
        };
    }

    impl Overflow for Recording {
        fn overflowed(operation: Operation, at: &'static Location<'static>) {
            HEARD.with(|heard| heard.borrow_mut().push((operation, at.line())));
        }
    }

    fn heard() -> Vec<(Operation, u32)> {
        HEARD.with(|heard| heard.take())
    }

    type Recorded = Fx<fixed::types::I16F16, Recording>;

    #[test]
    fn an_overflow_wraps_and_the_policy_hears_what_and_where() {
        let (max, one) = (Recorded::MAX, Recorded::ONE);
        let min = Recorded::new(fixed::types::I16F16::MIN);
        let big = Recorded::from_int(30_000);
        let line = line!();
        let sum = max + one;
        let difference = min - one;
        let product = big * big;
        let dot = Recorded::dot3([big; 3], [one; 3]);
        assert_eq!(sum.to_f64(), -32_767.0 - 1.0 / 65_536.0);
        assert_eq!(difference.to_f64(), 32_767.0);
        let exact = |x: f64| x.rem_euclid(65_536.0);
        assert_eq!(exact(product.to_f64()), exact(9e8));
        assert_eq!(exact(dot.to_f64()), exact(90_000.0));
        assert_eq!(
            heard(),
            [
                (Operation::Sum, line + 1),
                (Operation::Difference, line + 2),
                (Operation::Product, line + 3),
                (Operation::DotProduct, line + 4),
            ]
        );
        // What fits is exact, and nobody hears of it.
        assert_eq!(big + one - one, big * one);
        assert_eq!(heard(), []);
    }

    /// A policy that hears of nothing: the proven firmware's in a release build.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
    struct Deaf;

    impl Overflow for Deaf {
        const HEARS: bool = false;
        fn overflowed(_: Operation, _: &'static Location<'static>) {}
    }

    /// Products, dot products and products by a narrow number formed without the bits that
    /// say whether they fit are the heard ones wherever they fit, in a format whose narrow
    /// format is 2.14 (16 fraction bits) and one whose is 2.30 (20).
    fn unheard_products_are_the_heard_ones<F: Narrowed<Bits = i32>>() {
        let operands: Vec<i32> = [0, 1, -1, 3, 255, -4_096, 65_535, 65_536, -65_537, 1 << 20]
            .into_iter()
            .chain((0..200).map(|i: i32| i.wrapping_mul(0x9E37_79B9_u32 as i32) >> 12))
            .collect();
        for &a in &operands {
            for &b in &operands {
                let listened = [a, b].map(|x| Fx::<F, Recording>::new(F::from_bits(x)));
                let deaf = [a, b].map(|x| Fx::<F, Deaf>::new(F::from_bits(x)));
                let product = listened[0] * listened[1];
                let narrow_factor = listened[1].narrow();
                let scaled = listened[0].mul_narrow(narrow_factor);
                let dot = Scalar::dot3([listened[0]; 3], [listened[1], listened[0], listened[1]]);
                let fits = heard().is_empty();
                let narrow_factor = Fx::<F::Narrow, Deaf>::new(narrow_factor.get());
                if fits {
                    assert_eq!((deaf[0] * deaf[1]).raw(), product.raw(), "{a} × {b}");
                    assert_eq!(deaf[0].mul_narrow(narrow_factor).raw(), scaled.raw());
                    let deaf_dot = Scalar::dot3([deaf[0]; 3], [deaf[1], deaf[0], deaf[1]]);
                    assert_eq!(deaf_dot.raw(), dot.raw(), "{a}·{b}");
                }
            }
        }
    }

    #[test]
    fn products_that_fit_are_the_same_heard_or_not() {
        unheard_products_are_the_heard_ones::<fixed::types::I16F16>();
        unheard_products_are_the_heard_ones::<fixed::types::I12F20>();
    }

    #[test]
    #[cfg(debug_assertions)]
    #[should_panic(expected = "range proof missed it")]
    fn the_firmware_policy_panics_on_overflow_in_debug_builds() {
        let _ = I16F16::MAX + I16F16::ONE;
    }

    #[test]
    fn short_vectors_normalise_to_the_last_bit_too() {
        // |v|² of a vector a few LSB long rounds to nothing in the format; summed in the wide
        // integer it is exact, and so is the direction: within two LSB, or the 30 bits of the
        // roots where the format has more.
        fn check<S: Scalar>(raw: [i64; 3], from_raw: impl Fn(i64) -> S) {
            let v = raw.map(&from_raw);
            let (unit, length) = S::normalize3(v, false);
            let exact = raw.map(|c| c as f64);
            let norm = exact.iter().map(|c| c * c).sum::<f64>().sqrt();
            let lsb = S::resolution(1.0);
            let tolerance = (2.0 * lsb).max(2f64.powi(-29));
            for (c, e) in unit.iter().zip(exact) {
                assert!(
                    (c.to_f64() - e / norm).abs() <= tolerance,
                    "{}: {raw:?}",
                    S::NAME
                );
            }
            // A length beyond the format saturates.
            let want = (norm * lsb).min(S::RANGE);
            let length_tolerance = tolerance * want + lsb;
            assert!(
                (length.to_f64() - want).abs() <= length_tolerance,
                "{}: {raw:?}",
                S::NAME
            );
        }
        for raw in [[3, 4, 0], [1, 1, 1], [-7, 2, 5], [1, 0, 0], [40_000, -1, 3]] {
            check::<I16F16>(raw, |c| {
                I16F16::new(fixed::types::I16F16::from_bits(c as i32))
            });
            check::<I32F32>(raw, |c| I32F32::new(fixed::types::I32F32::from_bits(c)));
        }
        let huge = [i32::MAX, i32::MAX, i32::MIN + 1].map(i64::from);
        check::<I16F16>(huge, |c| {
            I16F16::new(fixed::types::I16F16::from_bits(c as i32))
        });
        let huge = [i64::MAX, -i64::MAX, i64::MAX];
        check::<I32F32>(huge, |c| I32F32::new(fixed::types::I32F32::from_bits(c)));
    }

    /// `x` rounded to a grid of `step`, to nearest, ties up: what every narrowing and product
    /// with a narrow number must give.
    fn to_nearest(x: f64, step: f64) -> f64 {
        (x / step + 0.5).floor() * step
    }

    /// Numbers of a format within the narrow range, at every edge: 0, ±1, the ends of ±2, a
    /// tie between two narrow steps, and a sweep.
    fn narrow_range<S: Scalar>() -> Vec<S> {
        let lsb = S::resolution(1.0);
        let mut all: Vec<f64> = vec![0.0, 1.0, -1.0, 2.0 - lsb, -2.0, 0.5 + 2f64.powi(-15)];
        all.extend((0..4000).map(|i| -2.0 + f64::from(i) * 1.0009765625e-3));
        all.into_iter().filter_map(|x| S::from_f64(x)).collect()
    }

    fn narrowing_rounds_to_nearest<S: Scalar>() {
        let step = S::Narrow::resolution(1.0);
        for x in narrow_range::<S>() {
            let want = to_nearest(x.to_f64(), step);
            if want < S::Narrow::RANGE {
                assert_eq!(x.narrow().to_f64(), want, "{}: {x:?}", S::NAME);
            }
            for k in narrow_range::<S::Narrow>().into_iter().step_by(7) {
                let want = to_nearest(x.to_f64() * k.to_f64(), S::resolution(1.0));
                if want < S::RANGE && want >= -S::RANGE {
                    let product = x.mul_narrow(k).to_f64();
                    assert_eq!(product, want, "{}: {x:?} × {k:?}", S::NAME);
                }
            }
        }
    }

    #[test]
    fn narrow_numbers_round_to_nearest_in_every_format() {
        narrowing_rounds_to_nearest::<crate::formats::I8f24>();
        narrowing_rounds_to_nearest::<I16F16>();
        narrowing_rounds_to_nearest::<crate::formats::I18f14>();
        narrowing_rounds_to_nearest::<I20F12>();
        narrowing_rounds_to_nearest::<crate::formats::I24f8>();
        narrowing_rounds_to_nearest::<I32F32>();
        narrowing_rounds_to_nearest::<<I16F16 as Scalar>::Narrow>();
        assert_eq!(<I16F16 as Scalar>::Narrow::NAME, "i2f14");
        assert_eq!(<crate::formats::I24f8 as Scalar>::Narrow::NAME, "i2f14");
        assert_eq!(<crate::formats::I14f18 as Scalar>::Narrow::NAME, "i2f30");
        assert_eq!(<I32F32 as Scalar>::Narrow::NAME, "i2f30");
    }

    #[test]
    fn a_number_beyond_the_narrow_range_is_told_as_a_narrowing() {
        let two = Recorded::from_int(2);
        let _ = two.narrow();
        assert_eq!(heard(), [(Operation::Narrowing, line!() - 1)]);
        let almost = Recorded::from_f64(2.0 - 2f64.powi(-16)).unwrap();
        let _ = almost.narrow();
        assert_eq!(heard(), [(Operation::Narrowing, line!() - 1)]);
        let big = Recorded::from_int(30_000);
        let k = Recorded::from_f64(1.5).unwrap().narrow();
        let _ = big.mul_narrow(k);
        assert_eq!(heard(), [(Operation::Product, line!() - 1)]);
    }

    /// The error model's unit (one LSB at 1, [`Precision::UNIT_ERROR`]) holds for the fast unit
    /// vectors as for the exact ones, at every binary point a 32-bit format may have.
    #[test]
    fn unit_vectors_are_within_the_unit_error_at_every_binary_point() {
        let mut state = 0x2545_F491_4F6C_DD1D_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for frac in (8..=24).step_by(2) {
            let lsb = 2f64.powi(-frac);
            let mut worst = [0.0_f64; 2];
            for _ in 0..20_000 {
                let magnitude = next() % 31;
                let raw = [(); 3].map(|()| (next() as i32) >> magnitude);
                let exact = raw.map(f64::from);
                let norm = exact.iter().map(|c| c * c).sum::<f64>().sqrt();
                for (fast, worst) in [false, true].into_iter().zip(&mut worst) {
                    let Some((unit, _)) = normalize_raw_32(raw, frac as u32, fast) else {
                        continue;
                    };
                    for (c, e) in unit.iter().zip(exact) {
                        *worst = worst.max((f64::from(*c) * lsb - e / norm).abs() / lsb);
                    }
                }
            }
            assert!(
                worst.iter().all(|&w| w <= 1.0),
                "frac {frac}: {worst:?} LSB"
            );
        }
    }

    #[test]
    fn negation_saturates() {
        assert_eq!(-I16F16::new(fixed::types::I16F16::MIN), I16F16::MAX);
    }

    #[test]
    #[cfg(debug_assertions)]
    #[should_panic(expected = "overflow")]
    fn an_overflowing_dot_product_is_caught_in_debug_builds() {
        let big = fx(200.0);
        let _ = I16F16::dot3([big; 3], [big; 3]);
    }

    #[test]
    #[cfg(debug_assertions)]
    #[should_panic(expected = "overflow")]
    fn an_overflowing_product_is_caught_in_debug_builds() {
        let big = fx(30_000.0);
        let _ = big * big;
    }

    #[test]
    #[cfg(debug_assertions)]
    #[should_panic(expected = "overflow")]
    fn an_overflowing_sum_is_caught_in_debug_builds() {
        let big = fx(30_000.0);
        let _ = big + big;
    }

    #[test]
    fn reciprocal_square_root_is_within_one_lsb() {
        // Within one LSB, or 2⁻²² of the value for the large roots of tiny inputs.
        fn check<S: Scalar>(x: f64) {
            let x = S::from_f64(x).unwrap();
            let got = x.rsqrt().to_f64();
            let exact = 1.0 / x.to_f64().sqrt();
            let tolerance = S::resolution(1.0).max(exact / f64::from(1 << 22));
            assert!(
                (got - exact).abs() <= tolerance,
                "{}: {x:?} gave {got}",
                S::NAME
            );
        }
        for x in [1e-4, 0.01, 0.5, 1.0, 1.0001, 2.0, 3.7, 100.0, 30_000.0] {
            check::<I16F16>(x);
            check::<I32F32>(x);
        }
        assert_eq!(I16F16::ZERO.rsqrt(), I16F16::MAX);
    }

    #[test]
    fn division_by_zero_saturates_towards_the_numerator() {
        assert_eq!(fx(2.0) / I16F16::ZERO, I16F16::MAX);
        assert_eq!(
            fx(-2.0) / I16F16::ZERO,
            I16F16::new(fixed::types::I16F16::MIN)
        );
        assert_eq!(I16F16::ZERO / I16F16::ZERO, I16F16::ZERO);
        assert_eq!(
            fx(30_000.0) / fx(-0.001),
            I16F16::new(fixed::types::I16F16::MIN)
        );
        assert_eq!(fx(-30_000.0) / fx(-0.001), I16F16::MAX);
    }

    #[test]
    fn products_round_to_nearest() {
        // Exhaustive over a window of small raw values: the product is the exact product of the
        // raw integers divided by 2^16, rounded half up.
        for a in -300_i32..300 {
            for b in [-70_000_i32, -65_536, -1, 1, 3, 32_768, 65_535, 100_000] {
                let got = (I16F16::new(fixed::types::I16F16::from_bits(a))
                    * I16F16::new(fixed::types::I16F16::from_bits(b)))
                .0
                .to_bits();
                let exact = f64::from(a) * f64::from(b) / 65_536.0;
                let expected = (exact + 0.5).floor() as i32;
                assert_eq!(got, expected, "{a} * {b}");
            }
        }
    }

    #[test]
    fn dot3_rounds_once() {
        // Three products of 0.5 LSB each: rounded separately they give 3 LSB, exactly 1.5 LSB
        // rounds to 2.
        let half_lsb = I16F16::new(fixed::types::I16F16::from_bits(1 << 8));
        let a = [half_lsb; 3];
        let b = [I16F16::new(fixed::types::I16F16::from_bits(1 << 7)); 3];
        assert_eq!(I16F16::dot3(a, b).get().to_bits(), 2);
        assert_eq!((a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).get().to_bits(), 3);
    }

    #[test]
    fn sqrt_brackets_the_true_root() {
        // sqrt(x)² ≤ x < (sqrt(x) + δ)² for a sweep of raw values.
        let mut raw = 1_i32;
        while raw < i32::MAX / 3 {
            let x = I16F16::new(fixed::types::I16F16::from_bits(raw));
            let r = x.sqrt().to_f64();
            let delta = I16F16::resolution(1.0);
            assert!(r * r <= x.to_f64(), "{raw}");
            assert!((r + delta) * (r + delta) > x.to_f64(), "{raw}");
            raw = raw * 3 / 2 + 1;
        }
    }

    #[test]
    fn approximations_hold_fourteen_bits_and_division_saturates() {
        for x in [0.01, 0.5, 1.0, 2.0, 3.7, 100.0, 480.0, 1000.0, 20_000.0] {
            let v = fx(x);
            let tolerance = |exact: f64| exact / 8192.0 + 2.0 / 65_536.0;
            assert!(
                (v.sqrt_approx().to_f64() - x.sqrt()).abs() <= tolerance(x.sqrt()),
                "{x}"
            );
            let exact = 1.0 / v.to_f64().sqrt();
            assert!(
                (v.rsqrt_approx().to_f64() - exact).abs() <= tolerance(exact),
                "{x}"
            );
            // A quotient keeps its 14 bits however large the divisor (pixel centres divide
            // by twice the image size), up to the rounding of the result.
            for a in [-3.0, 0.25, 7.0, 479.0] {
                let q = fx(a).div_approx(v).to_f64();
                let exact = a / v.to_f64();
                if exact.abs() < 30_000.0 {
                    assert!(
                        (q - exact).abs() <= exact.abs() / 8192.0 + 1.0 / 65_536.0,
                        "{a}/{x}: {q}"
                    );
                }
            }
        }
        assert_eq!(fx(2.0).div_approx(I16F16::ZERO), I16F16::MAX);
        assert_eq!(
            fx(-2.0).div_approx(fx(1e-5)),
            I16F16::new(fixed::types::I16F16::MIN)
        );
        const { assert!(I16F16::FAST_ROOTS && !I32F32::FAST_ROOTS) };
    }

    #[test]
    fn difference_of_products_has_an_exact_sign() {
        let lsb = I16F16::new(fixed::types::I16F16::from_bits(1));
        // 3·LSB · LSB − LSB · 2·LSB is 2⁻³² (positive) but rounds to 0 in 16.16.
        let three = I16F16::new(fixed::types::I16F16::from_bits(3));
        let two = I16F16::new(fixed::types::I16F16::from_bits(2));
        let (value, sign) = I16F16::diff_of_products(three, lsb, lsb, two);
        assert_eq!((value, sign), (I16F16::ZERO, Ordering::Greater));
        let (value, sign) = I16F16::diff_of_products(fx(3.0), fx(2.0), fx(1.5), fx(4.0));
        assert_eq!((value, sign), (I16F16::ZERO, Ordering::Equal));
        let (value, sign) = I16F16::diff_of_products(fx(1.0), fx(2.0), fx(1.5), fx(4.0));
        assert_eq!((value.to_f64(), sign), (-4.0, Ordering::Less));
    }

    #[test]
    fn names_follow_the_format() {
        assert_eq!(I16F16::NAME, "i16f16");
        assert_eq!(I32F32::NAME, "i32f32");
        assert_eq!(I20F12::NAME, "i20f12");
        assert_eq!(I16F16::RANGE, 32_768.0 - 1.0 / 65_536.0);
    }
}
