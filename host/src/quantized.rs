//! [`Quantized`]: f64 arithmetic on a format's stored numbers. Every constant a scene build
//! stores (positions, radii, the checker's 1/size, colours, tolerances, the smallest weight) is
//! the format's own value, rounded to its grid; the range proof and the features are the
//! format's; a quotient saturates at its range. The rounding of each operation is left out but
//! for the one an image is most sensitive to: a power (Phong's highlight, cosⁿ) is taken of
//! its cosine plus the format's rounding of a cosine, which an exponent n multiplies by n where
//! the highlight shows, and moved by the bound of its own products' rounding, which the
//! exponent multiplies alike. Up, mostly: xⁿ is convex, so a cosine rounded up moves it further
//! than one rounded down, and a highlight narrower than the format resolves spreads (its
//! cosines round to 1); but down within the rounding of 1, where a cosine cannot rise above 1
//! and a format's falls short of it (a light at the eye, seen in a mirror-like surface facing
//! it: 1 − ε to the power n is far below 1). So a render in it against the f64 reference shows what the format's
//! constants, tolerances and highlights do to the image, pixel by pixel, which
//! [`crate::analysis`] adds to its model of the rest of the rounding.

use obscura::Scalar;
use obscura::scalar::Precision;

/// Steps of rounding in a cosine of two unit vectors: each vector's, and the dot product's.
pub const COSINE_STEPS: f64 = 4.0;
use std::cmp::Ordering;
use std::fmt;
use std::marker::PhantomData;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// An f64 with format `S`'s constants (see the module documentation), on the grid of `G`: `S`
/// itself, or for its narrow numbers ([`Scalar::Narrow`]) its narrow format, whose constants
/// (surfaces' colours, material weights) are rounded to that format's grid and whose powers'
/// cosines are narrowed.
pub struct Quantized<S, G = S>(f64, PhantomData<(S, G)>);

impl<S, G> Quantized<S, G> {
    const fn new(x: f64) -> Self {
        Self(x, PhantomData)
    }
}

impl<S, G> Clone for Quantized<S, G> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S, G> Copy for Quantized<S, G> {}

impl<S, G> Default for Quantized<S, G> {
    fn default() -> Self {
        Self::new(0.0)
    }
}

impl<S, G> PartialEq for Quantized<S, G> {
    fn eq(&self, other: &Self) -> bool {
        self.0 == other.0
    }
}

impl<S, G> PartialOrd for Quantized<S, G> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        self.0.partial_cmp(&other.0)
    }
}

impl<S, G> fmt::Debug for Quantized<S, G> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl<S, G> Add for Quantized<S, G> {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        Self::new(self.0 + rhs.0)
    }
}

impl<S, G> Sub for Quantized<S, G> {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        Self::new(self.0 - rhs.0)
    }
}

impl<S, G> Mul for Quantized<S, G> {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        Self::new(self.0 * rhs.0)
    }
}

impl<S, G> Neg for Quantized<S, G> {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.0)
    }
}

impl<S, G: Scalar> Div for Quantized<S, G> {
    type Output = Self;
    /// Saturating at the format's range, as the format's own quotient does.
    fn div(self, rhs: Self) -> Self {
        let quotient = self.0 / rhs.0;
        Self::new(if quotient.is_nan() {
            0.0
        } else {
            quotient.clamp(-G::RANGE, G::RANGE)
        })
    }
}

impl<S: Scalar, G: Scalar> Scalar for Quantized<S, G> {
    const ZERO: Self = Self::new(0.0);
    const ONE: Self = Self::new(1.0);
    const MAX: Self = Self::new(G::RANGE);

    fn from_int(n: i32) -> Self {
        Self::new(G::from_int(n).to_f64())
    }

    type Narrow = Quantized<S, G::Narrow>;

    /// Exact: the model adds a narrowing's rounding where it matters, to a power's cosine.
    fn narrow(self) -> Self::Narrow {
        Quantized::new(self.0)
    }

    fn mul_narrow(self, k: Self::Narrow) -> Self {
        Self::new(self.0 * k.0)
    }

    fn from_q16(bits: i32) -> Self {
        Self::new(G::from_q16(bits).to_f64())
    }

    fn to_q16(self) -> i32 {
        self.0.to_q16()
    }

    fn floor_int(self) -> i32 {
        self.0.floor_int()
    }

    fn sqrt(self) -> Self {
        Self::new(self.0.sqrt())
    }

    fn ratio(num: i32, den: i32) -> Self {
        Self::new(G::ratio(num, den).to_f64())
    }

    /// The power of the base moved by its rounding as a cosine, and by the rounding of the
    /// power itself ([`power_rounding`]), the way that moves the power further: see the module
    /// documentation.
    fn powi(self, exponent: u16) -> Self {
        let n = i32::from(exponent);
        // A cosine of unit vectors narrowed to a coarser grid than the format's rounds on it.
        let cosine = COSINE_STEPS * (S::UNIT_ERROR + coarser::<S, G>());
        let exact = self.0.clamp(0.0, 1.0).powi(n);
        let (up, down) = (
            (self.0 + cosine).clamp(0.0, 1.0),
            (self.0 - cosine).clamp(0.0, 1.0),
        );
        let rounding = |base: f64| power_rounding(base, exponent, G::resolution(1.0) / 2.0);
        if up.powi(n) - exact >= exact - down.powi(n) {
            Self::new((up.powi(n) + rounding(up)).min(1.0))
        } else {
            Self::new((down.powi(n) - rounding(down)).max(0.0))
        }
    }

    fn diff_of_products(a: Self, b: Self, c: Self, d: Self) -> (Self, Ordering) {
        let (value, sign) = f64::diff_of_products(a.0, b.0, c.0, d.0);
        (Self::new(value), sign)
    }
}

impl<S: Scalar, G: Scalar> obscura::scalar::Sealed for Quantized<S, G> {}

impl<S: Scalar, G: Scalar> Precision for Quantized<S, G> {
    const NAME: &'static str = G::NAME;

    const RANGE: f64 = G::RANGE;

    fn from_f64(x: f64) -> Option<Self> {
        G::from_f64(x).map(|stored| Self::new(stored.to_f64()))
    }

    fn to_f64(self) -> f64 {
        self.0
    }

    fn resolution(magnitude: f64) -> f64 {
        G::resolution(magnitude)
    }

    const UNIT_ERROR: f64 = S::UNIT_ERROR;
}

/// How much coarser format `G` is than `S` at 1 — for `S`'s narrow format ([`Scalar::Narrow`]),
/// the step a narrowing may add to a number's rounding: nothing where `G` is the finer, or `S`
/// itself.
pub fn coarser<S: Scalar, G: Scalar>() -> f64 {
    (G::resolution(1.0) - S::resolution(1.0)).max(0.0)
}

/// How far [`Scalar::powi`]'s products, each rounded by up to `rounding`, may move xⁿ for x in
/// [0, 1]. By repeated squaring xⁿ is the product of the squares x^(2ʲ) for the bits j of n; the
/// rounding of the square x^(2ʲ⁺¹) reaches the power multiplied by the derivative of xⁿ with
/// respect to that square, at most (n/2ʲ⁺¹)·x^(n − 2ʲ⁺¹), and each multiplication into the
/// result passes its own rounding on times factors below 1. So near x = 1, where the highlight
/// is brightest, the bound is about n times the rounding, and far below it about one rounding
/// per bit of n.
fn power_rounding(x: f64, exponent: u16, rounding: f64) -> f64 {
    let n = f64::from(exponent);
    let squares: f64 = (1..=u16::BITS)
        .map(|j| f64::from(1_u32 << j))
        .take_while(|&square| square <= n)
        .map(|square| n / square * x.powf(n - square))
        .sum();
    rounding * (squares + f64::from(exponent.count_ones()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::checked::CheckedFx;

    type Q16 = Quantized<CheckedFx<fixed::types::I16F16>>;

    #[test]
    fn constants_are_the_formats_and_arithmetic_is_f64s() {
        let third = Q16::from_f64(1.0 / 3.0).unwrap();
        assert_eq!(third.to_f64(), 21_845.0 / 65_536.0);
        // No rounding of the product: it is f64's.
        assert_eq!((third * third).to_f64(), (21_845.0_f64 / 65_536.0).powi(2));
        assert_eq!(Q16::from_f64(40_000.0), None);
        assert_eq!((Q16::ONE / Q16::ZERO).to_f64(), Q16::RANGE);
        assert_eq!(Q16::ratio(1, 3).to_f64(), 21_845.0 / 65_536.0);
        assert_eq!(Q16::resolution(1.0), 1.0 / 65_536.0);
    }

    #[test]
    fn narrow_constants_are_on_the_narrow_formats_grid() {
        type Narrow = <Q16 as Scalar>::Narrow;
        let third = Narrow::from_f64(1.0 / 3.0).unwrap();
        assert_eq!(third.to_f64(), 5_461.0 / 16_384.0);
        assert_eq!(Narrow::RANGE, 2.0 - 1.0 / 16_384.0);
        assert_eq!(coarser::<Q16, Narrow>(), 3.0 / 65_536.0);
        assert_eq!(coarser::<f32, f32>(), 0.0);
        // A cosine narrowed is rounded once more before its power: the power moves further.
        let cosine = 1.0 - 1.0 / 64.0;
        let wide = Q16::from_f64(cosine).unwrap().powi(40).to_f64();
        let narrow = Narrow::from_f64(cosine).unwrap().powi(40).to_f64();
        let exact = cosine.powi(40);
        assert!((narrow - exact).abs() > (wide - exact).abs());
    }

    /// The bound holds for the formats' own powers, of cosines they hold exactly.
    #[test]
    fn the_power_rounding_bounds_the_formats_powers() {
        fn check<S: Scalar>() {
            let rounding = S::resolution(1.0) / 2.0;
            for exponent in [1, 2, 3, 7, 40, 255, 2461, 65_535] {
                for step in 0..=1000 {
                    let x = S::from_f64(1.0 - f64::from(step) * f64::from(step) / 1e6).unwrap();
                    let exact = x.to_f64().powi(i32::from(exponent));
                    let error = (x.powi(exponent).to_f64() - exact).abs();
                    let bound = power_rounding(x.to_f64(), exponent, rounding);
                    assert!(
                        error <= bound,
                        "{}: {}^{exponent}: off by {error:e}, bound {bound:e}",
                        S::NAME,
                        x.to_f64()
                    );
                }
            }
        }
        check::<obscura::formats::I16f16>();
        check::<obscura::formats::I22f10>();
        check::<obscura::formats::I12f20>();
        check::<f32>();
    }
}
