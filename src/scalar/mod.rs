//! The number model, a trait per concern, and their implementations for fixed-point formats
//! ([`Fx`]) and IEEE floats:
//!
//! - [`Scalar`]: what every piece of geometry and shading is written against — arithmetic,
//!   roots and quotients (exact and fast), the vector kernels a fixed format computes in its
//!   wide integer, the rounding to a display's levels.
//! - [`Precision`]: what the error model knows of a format — its name, range, split,
//!   resolution and unit vectors' error, and its exact conversions from and to `f64` — which the
//!   range proof, the tolerances and the harness's analysis read, and arithmetic does not.
//! - [`Bits`], sealed: the core's own formats, whose numbers are exactly their bits, as a
//!   proven scene travels from a firmware's build to the chip.
//!
//! `Scalar` and `Precision` are sealed ([`Sealed`]): a user computes in the core's formats. The
//! workspace's tools, through the feature `instrument`, implement them for their instrumented
//! formats over the core's (an operation counter, a peak recorder, a format's constants in
//! `f64`).
//!
//! This module owns how numbers behave at the edges of their range. Every other module calls
//! only the trait, so swapping the format changes nothing but the numbers. The rules:
//!
//! - Sums and products are exact while they fit, and the scene build ([`crate::Scene::build`])
//!   proves that every sum and product the tracer forms for that scene fits the format (see
//!   [`crate::scene::range`]). A fixed format's [`Overflow`] policy says what becomes of one
//!   outside that proof (see [`Fx`]): the firmware relies on the proof, the desktop harness
//!   checks every operation. Quotients, which no bound can hold, saturate in fixed point and
//!   reach infinity in floats, and the tracer reads either as "beyond anything in the world".
//! - Nothing panics on a proven scene: the square root of a negative number is zero, a
//!   fixed-point division by zero saturates towards the sign of the numerator.
//! - Every tolerance is derived from the format through [`Precision::resolution`], never typed in.

crate::phase::declare_phase!(Some(crate::phase::Phase::Arithmetic));

pub(crate) mod approx;
pub(crate) mod bits;
pub(crate) mod fixed_point;
pub(crate) mod float;
pub(crate) mod isqrt;
pub(crate) mod kernels;

pub use approx::F32Approx;
pub use bits::{Bits, NumberBits};
pub use fixed_point::{
    Fx, I16F16, I20F12, I32F32, NarrowOf32, Narrowed, Operation, Overflow, Proven, WideBits,
};
pub(crate) use kernels::shl_u64;

/// The relative error of the 32-bit fixed formats' fast roots and quotients (14 bits, and a
/// bit to spare).
pub const FAST_ROOT_ERROR: f64 = 1.0 / 8192.0;

/// A ball is widened by this many of the errors with which a ray finds its object, and a ray's
/// direction is taken to be off by this many of its errors, wherever a test is skipped because
/// a ray cannot meet its object ([`crate::cull`], [`crate::occlusion`]): the error model's
/// errors are estimates, and a test skipped wrongly would change the picture.
pub const REACH_ERRORS: f64 = 4.0;

use core::cmp::Ordering;
use core::fmt::Debug;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// What makes a type a number format of the tracer, and so seals [`Precision`] and [`Scalar`]:
/// the core's formats, and, through the feature `instrument`, the workspace's tools'.
pub trait Sealed {}

/// What the error model knows of a format ([`crate::scene::range`], the surface tolerances,
/// the camera's aim, the harness's analysis): its name, range, split, resolution and the error
/// of its unit vectors, and its exact conversions from and to `f64`. Arithmetic callers need
/// none of it; [`Scalar`], which the tracer is written against, has it.
pub trait Precision: Sized + Sealed {
    /// The format's name as the command line spells it, e.g. `"i16f16"`.
    const NAME: &'static str;
    /// The largest finite value ([`Scalar::MAX`]) as an `f64`, for range analysis.
    const RANGE: f64;
    /// A fixed format's integer bits (the sign among them) and fraction bits; `None` for a
    /// float.
    const SPLIT: Option<(u32, u32)> = None;

    /// Converts from `f64`, or `None` when `x` is not finite or does not fit.
    fn from_f64(x: f64) -> Option<Self>;

    /// Converts to `f64` (exactly, for every format here but `f64` itself, which is the identity).
    fn to_f64(self) -> f64;

    /// The spacing of representable numbers near `magnitude`: one LSB for a fixed format,
    /// `magnitude` times the machine epsilon for a float. Tolerances are multiples of it.
    fn resolution(magnitude: f64) -> f64;

    /// How far each coordinate of a unit vector from [`Scalar::normalize3`] may be off, with
    /// exact roots: the resolution at 1 where the format's roots are correctly rounded, more
    /// where its roots keep fewer bits than the format has. The error model's unit for every
    /// direction (the fast roots add [`crate::scalar::FAST_ROOT_ERROR`]).
    const UNIT_ERROR: f64;
}

/// A real number format the tracer can compute in.
///
/// `/` and `−x` are total: a quotient or negation that does not fit saturates (a float's
/// reaches infinity). While the result fits the format, `+` and `−` are exact in fixed point
/// and `×` is the exact product rounded to nearest (half up), `/` the exact quotient truncated
/// towards zero; a float's are correctly rounded. Beyond the range, a float's sum or product
/// reaches infinity and a fixed format's wraps (two's complement), telling its overflow policy
/// policy first: the firmware's panics in a debug build, the desktop harness's stops the render
/// with the operation. The scene build proves that no sum or product the tracer forms for a
/// built scene leaves the format (see the module documentation); `tests/scalar_operators.rs`
/// holds the fixed formats to this paragraph.
pub trait Scalar:
    Precision
    + Copy
    + Default
    + PartialEq
    + PartialOrd
    + Debug
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// The largest finite value: the format's "infinitely far".
    const MAX: Self;
    /// The integer `n` (saturating when it does not fit).
    fn from_int(n: i32) -> Self;

    /// The format's narrow numbers: what is bounded by construction within ±2 — cosines,
    /// colours of surfaces, material weights, the weights along a ray tree — stored and
    /// multiplied in the width it needs. A 32-bit fixed format of at most 16 fraction bits
    /// has signed 2.14 (a product of two is one 16×16→32 multiply, a product with one of the
    /// format's is 32×16); the finer 32-bit formats and the 64-bit one signed 2.30, which keeps
    /// their accuracy; a float the float itself.
    type Narrow: Scalar;

    /// `self` rounded to the narrow format (to nearest, ties up); exact while it fits, which
    /// the scene build proves, and like a product beyond that.
    #[must_use]
    #[track_caller]
    fn narrow(self) -> Self::Narrow;

    /// `self · k`, rounded to nearest as `×` rounds: a 32×16 product in a 32-bit fixed format.
    #[must_use]
    #[track_caller]
    fn mul_narrow(self, k: Self::Narrow) -> Self;

    /// `bits`·2⁻¹⁶, the number whose Q16.16 representation is `bits`, rounded down to the
    /// format's resolution (saturating when it does not fit): how a position that integers
    /// computed, such as a sample's within its pixel, enters the format.
    fn from_q16(bits: i32) -> Self;

    /// The Q16.16 representation of `self`: `self`·2¹⁶ rounded down (saturating), the inverse
    /// of [`Self::from_q16`] wherever the format is as fine as Q16.16.
    fn to_q16(self) -> i32;

    /// The largest integer not greater than `self`, saturated to `i32`.
    fn floor_int(self) -> i32;

    /// The square root; zero for zero and for negative inputs.
    #[must_use]
    fn sqrt(self) -> Self;

    /// `1 / self`, saturating for zero.
    #[must_use]
    fn recip(self) -> Self {
        Self::ONE / self
    }

    /// `1 / √self`, saturating for zero and negative inputs; within an LSB in fixed point,
    /// where it costs no division.
    #[must_use]
    fn rsqrt(self) -> Self {
        if self > Self::ZERO {
            self.sqrt().recip()
        } else {
            Self::MAX
        }
    }

    /// The unit vector along `v` and |v|, the roots approximate when `approx`; a zero vector
    /// gives itself and zero. Fixed formats override it to keep the unit vector to within a few
    /// steps of their resolution however long `v` is.
    #[must_use]
    #[track_caller]
    fn normalize3(v: [Self; 3], approx: bool) -> ([Self; 3], Self) {
        let squared = Self::dot3(v, v);
        if squared == Self::ZERO {
            return (v, Self::ZERO);
        }
        let inverse = if approx {
            squared.rsqrt_approx()
        } else {
            squared.rsqrt()
        };
        (v.map(|c| c * inverse), squared * inverse)
    }

    /// Whether the `_approx` operations below are faster approximations (the 32-bit fixed
    /// formats), rather than the exact operations under another name.
    const FAST_ROOTS: bool = false;

    /// √self, approximately (see [`Self::FAST_ROOTS`]).
    #[must_use]
    fn sqrt_approx(self) -> Self {
        self.sqrt()
    }

    /// 1/√self, approximately (see [`Self::FAST_ROOTS`]).
    #[must_use]
    fn rsqrt_approx(self) -> Self {
        self.rsqrt()
    }

    /// self / rhs, approximately (see [`Self::FAST_ROOTS`]); saturating like `/`.
    #[must_use]
    fn div_approx(self, rhs: Self) -> Self {
        self / rhs
    }

    /// a·b − c·d (rounded to within a couple of units in the last place), and the exact sign of
    /// the exact value: what an edge function needs to tell on which side of an edge a point
    /// lies without ever contradicting itself.
    fn diff_of_products(a: Self, b: Self, c: Self, d: Self) -> (Self, Ordering);

    /// `a₀b₀ + a₁b₁ + a₂b₂`. Fixed formats override it to add the exact products and round
    /// once, which is both faster and more precise than three rounded products.
    #[must_use]
    #[track_caller]
    fn dot3(a: [Self; 3], b: [Self; 3]) -> Self {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    /// The absolute value (saturating).
    #[must_use]
    fn abs(self) -> Self {
        if self < Self::ZERO { -self } else { self }
    }

    /// The smaller of two values.
    #[must_use]
    fn min(self, other: Self) -> Self {
        if other < self { other } else { self }
    }

    /// The larger of two values.
    #[must_use]
    fn max(self, other: Self) -> Self {
        if other > self { other } else { self }
    }

    /// `self` limited to `[lo, hi]`.
    #[must_use]
    fn clamp(self, lo: Self, hi: Self) -> Self {
        self.max(lo).min(hi)
    }

    /// `⌊clamp(self, 0, 1)·levels + threshold⌋`, at most `levels`, for a threshold in [0, 1):
    /// a colour channel on a display with `levels` + 1 levels. A fixed format computes it
    /// exactly in its wide integer, so that no intermediate need fit the format (255 does not
    /// fit i8f24).
    #[must_use]
    fn quantize(self, levels: u8, threshold: Self) -> u8 {
        quantize_by_floor(self, levels, threshold)
    }

    /// `num / den` for small integers, rounded as the format's division rounds.
    #[must_use]
    fn ratio(num: i32, den: i32) -> Self {
        Self::from_int(num) / Self::from_int(den)
    }

    /// Hears of a step of the tracer's work that no arithmetic operation shows. The
    /// formats here ignore it (it costs nothing); the desktop harness's operation counter
    /// tallies it.
    #[inline(always)]
    fn note(_work: Work) {}

    /// `self` raised to a non-negative integer power, by repeated squaring.
    #[must_use]
    #[track_caller]
    fn powi(self, exponent: u16) -> Self {
        let mut result = Self::ONE;
        let mut base = self;
        let mut e = exponent;
        while e > 0 {
            if e & 1 == 1 {
                result = result * base;
            }
            e >>= 1;
            if e > 0 {
                base = base * base;
            }
        }
        result
    }
}

/// The narrow items of [`Scalar`] for a format whose narrow numbers are its own (the floats):
/// `narrow_is_itself!();` in its `impl Scalar`.
macro_rules! narrow_is_itself {
    () => {
        type Narrow = Self;

        #[inline]
        fn narrow(self) -> Self {
            self
        }

        #[inline]
        fn mul_narrow(self, k: Self) -> Self {
            self * k
        }
    };
}
pub(crate) use narrow_is_itself;

/// [`Scalar::quantize`] as written: `⌊clamp(v, 0, 1)·levels + threshold⌋` by the format's
/// floor, at most `levels`. The default, and what a format's own version must equal.
#[inline]
pub(crate) fn quantize_by_floor<S: Scalar>(v: S, levels: u8, threshold: S) -> u8 {
    let scaled = v.clamp(S::ZERO, S::ONE) * S::from_int(i32::from(levels)) + threshold;
    u8::try_from(scaled.floor_int().clamp(0, i32::from(levels))).unwrap_or(levels)
}

/// A step of the tracer's work that [`Scalar::note`] hears of: where a ray's search for what it
/// meets starts, and each object test of the search and its outcome.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Work {
    /// A ray of this kind starts searching the scene.
    Search(RayKind),
    /// The search tests an object, or a triangle of a mesh.
    Test,
    /// The search tests a box of a mesh's hierarchy.
    Node,
    /// The object just tested is met: the nearest so far, or an occluder of a shadow ray.
    Met,
    /// The primary ray whose search follows is the row pass's ([`crate::row_pass`]): it
    /// needs no unit vector.
    RowPass,
    /// Within a mesh's search, the triangle just tested is met: the mesh's nearest so far, or
    /// an occluder of a shadow ray (the mesh is [met](Self::Met) once its search is over).
    Hit,
}

/// The kinds of ray, by what their search is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RayKind {
    /// From the eye (or a lens), through a pixel: the nearest object.
    Primary,
    /// Reflected or refracted: the nearest object.
    Secondary,
    /// From a surface towards a light: every occluder.
    Shadow,
}

/// What an error message needs to know of a format it cannot name by type.
#[derive(Clone, Copy, Debug)]
pub struct FormatInfo {
    /// [`Precision::NAME`].
    pub name: &'static str,
    /// [`Precision::RANGE`].
    pub range: f64,
    /// [`Precision::resolution`].
    pub resolution: fn(f64) -> f64,
    /// [`Precision::UNIT_ERROR`].
    pub unit_error: f64,
    /// [`Scalar::FAST_ROOTS`].
    pub fast_roots: bool,
}

impl FormatInfo {
    /// The description of `S`.
    #[must_use]
    pub const fn of<S: Scalar>() -> Self {
        Self {
            name: S::NAME,
            range: S::RANGE,
            resolution: S::resolution,
            unit_error: S::UNIT_ERROR,
            fast_roots: S::FAST_ROOTS,
        }
    }
}

/// A set of [`FORMATS`], by their places in that list.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FormatSet(u32);

impl FormatSet {
    /// The formats of [`FORMATS`] for which `holds` is true.
    #[must_use]
    pub fn of(holds: impl Fn(&FormatInfo) -> bool) -> Self {
        let bits = FORMATS
            .iter()
            .enumerate()
            .filter(|(_, format)| holds(format))
            .fold(0, |bits, (i, _)| bits | 1 << i);
        Self(bits)
    }

    /// The formats in the set, in the order of [`FORMATS`].
    pub fn iter(self) -> impl Iterator<Item = &'static FormatInfo> {
        FORMATS
            .iter()
            .enumerate()
            .filter(move |(i, _)| self.0 & 1 << i != 0)
            .map(|(_, format)| format)
    }

    /// Whether the set is empty.
    #[must_use]
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }
}

/// Builds [`FORMATS`] and the [`formats`](crate::formats) type names from the one list.
macro_rules! format_table {
    (fixed { $($fixed:ident => $raw:ident,)* } float { $($float:ident => $ty:ty,)* }) => {
        /// Every format the tracer is built for, from the smallest range to the largest.
        pub const FORMATS: [FormatInfo; [$(stringify!($fixed),)* $(stringify!($float),)*].len()] = [
            $(FormatInfo::of::<Fx<fixed::types::$raw>>(),)*
            $(FormatInfo::of::<$ty>(),)*
        ];

        /// Each format's type, by the name the command line gives it: what a firmware
        /// configured with a format computes in.
        pub mod names {
            $(
                #[doc = concat!("`", stringify!($raw), "` fixed point.")]
                pub type $fixed = super::Fx<fixed::types::$raw>;
            )*
            $(
                #[doc = concat!("`", stringify!($ty), "`.")]
                pub type $float = $ty;
            )*
        }
    };
}
crate::for_each_format!(format_table);

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact arithmetic, and roots within `root_tolerance` (relative).
    fn check_basics<S: Scalar>(root_tolerance: f64) {
        let two = S::from_int(2);
        assert_eq!((two * two).to_f64(), 4.0, "{}", S::NAME);
        assert_eq!(S::from_int(-3).abs().to_f64(), 3.0, "{}", S::NAME);
        assert_eq!(S::from_int(-7).floor_int(), -7, "{}", S::NAME);
        assert_eq!(S::from_f64(-0.5).map(S::floor_int), Some(-1), "{}", S::NAME);
        assert_eq!(S::from_f64(2.5).map(S::floor_int), Some(2), "{}", S::NAME);
        assert!(
            (S::ratio(1, 4).to_f64() - 0.25).abs() <= 1e-5,
            "{}",
            S::NAME
        );
        assert_eq!(two.powi(6).to_f64(), 64.0, "{}", S::NAME);
        assert_eq!(two.powi(0).to_f64(), 1.0, "{}", S::NAME);
        assert!(
            (S::from_int(9).sqrt().to_f64() - 3.0).abs() <= 3.0 * root_tolerance,
            "{}",
            S::NAME
        );
        assert_eq!(S::from_int(-9).sqrt(), S::ZERO, "{}", S::NAME);
        assert_eq!(
            S::dot3([S::ONE, two, two], [two, two, S::ONE]).to_f64(),
            8.0
        );
        assert!(S::from_f64(f64::NAN).is_none(), "{}", S::NAME);
        assert!(S::from_f64(f64::INFINITY).is_none(), "{}", S::NAME);
        assert!(S::MAX.to_f64() == S::RANGE, "{}", S::NAME);
        assert!(
            // The coarsest format here, i24f8, has eight fraction bits.
            S::resolution(1.0) > 0.0 && S::resolution(1.0) <= 1.0 / 256.0,
            "{}",
            S::NAME
        );
    }

    #[test]
    fn every_format_does_basic_arithmetic() {
        check_basics::<I16F16>(0.0);
        check_basics::<I20F12>(0.0);
        check_basics::<I32F32>(0.0);
        check_basics::<names::I8f24>(0.0);
        check_basics::<names::I24f8>(0.0);
        check_basics::<f32>(0.0);
        check_basics::<f64>(0.0);
        check_basics::<F32Approx>(0.07);
    }

    #[test]
    fn a_format_set_lists_its_formats_in_order() {
        let wide = FormatSet::of(|f| f.range > 1e8);
        let names: Vec<_> = wide.iter().map(|f| f.name).collect();
        assert_eq!(names, ["i32f32", "f32-approx", "f32", "f64"]);
        assert!(FormatSet::of(|_| false).is_empty());
        assert_eq!((FORMATS[0].resolution)(1.0), names::I8f24::resolution(1.0));
    }

    #[test]
    fn formats_are_distinct_and_ordered_by_range() {
        for (i, a) in FORMATS.iter().enumerate() {
            for b in &FORMATS[i + 1..] {
                assert_ne!(a.name, b.name);
                assert!(a.range <= b.range, "{} before {}", a.name, b.name);
            }
        }
    }
}
