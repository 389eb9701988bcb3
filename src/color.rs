//! Linear colour in the tracer's number format, and its quantisation to a display's pixel
//! colour.

use crate::scalar::Scalar;
use core::ops::{Add, Mul};
use embedded_graphics_core::pixelcolor::{Bgr565, Bgr888, Rgb555, Rgb565, Rgb888, RgbColor};

/// A linear RGB colour; 1.0 is full intensity on a channel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rgb<S> {
    /// Red.
    pub r: S,
    /// Green.
    pub g: S,
    /// Blue.
    pub b: S,
}

impl<S: Scalar> Rgb<S> {
    /// Black: no light.
    pub const BLACK: Self = Self::new(S::ZERO, S::ZERO, S::ZERO);
    /// White: every channel at full intensity.
    pub const WHITE: Self = Self::new(S::ONE, S::ONE, S::ONE);

    /// A colour from its channels.
    #[inline]
    #[must_use]
    pub const fn new(r: S, g: S, b: S) -> Self {
        Self { r, g, b }
    }

    /// Converts from `f64` channels, or `None` when one does not fit the format.
    #[must_use]
    pub fn from_f64(c: [f64; 3]) -> Option<Self> {
        Some(Self::new(
            S::from_f64(c[0])?,
            S::from_f64(c[1])?,
            S::from_f64(c[2])?,
        ))
    }

    /// The channels as `f64`.
    #[must_use]
    pub fn to_f64(self) -> [f64; 3] {
        [self.r.to_f64(), self.g.to_f64(), self.b.to_f64()]
    }

    /// Every channel multiplied by `k`.
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn scale(self, k: S) -> Self {
        Self::new(self.r * k, self.g * k, self.b * k)
    }

    /// The brightest channel.
    #[inline]
    #[must_use]
    pub fn max_channel(self) -> S {
        self.r.max(self.g).max(self.b)
    }

    /// The colour on a display: each channel clamped to [0, 1] and rounded to the nearest of
    /// the display's levels.
    #[must_use]
    pub fn quantize<C: DisplayColor>(self) -> C {
        C::from_channels(
            quantize_channel(self.r, C::MAX_R),
            quantize_channel(self.g, C::MAX_G),
            quantize_channel(self.b, C::MAX_B),
        )
    }
}

/// `round(clamp(v, 0, 1) · max)`.
#[inline]
fn quantize_channel<S: Scalar>(v: S, max: u8) -> u8 {
    let scaled = v.clamp(S::ZERO, S::ONE) * S::from_int(i32::from(max)) + S::ratio(1, 2);
    u8::try_from(scaled.floor_int().clamp(0, i32::from(max))).unwrap_or(max)
}

impl<S: Scalar> Add for Rgb<S> {
    type Output = Self;
    #[inline]
    #[track_caller]
    fn add(self, rhs: Self) -> Self {
        Self::new(self.r + rhs.r, self.g + rhs.g, self.b + rhs.b)
    }
}

/// Channel by channel: a filter applied to light.
impl<S: Scalar> Mul for Rgb<S> {
    type Output = Self;
    #[inline]
    #[track_caller]
    fn mul(self, rhs: Self) -> Self {
        Self::new(self.r * rhs.r, self.g * rhs.g, self.b * rhs.b)
    }
}

/// A display colour the renderer can produce: an embedded-graphics RGB colour that can be
/// built from its channels (each in `0..=MAX_*`).
pub trait DisplayColor: RgbColor {
    /// The colour with these channel values.
    fn from_channels(r: u8, g: u8, b: u8) -> Self;
}

macro_rules! display_color {
    ($($t:ty),*) => {$(
        impl DisplayColor for $t {
            #[inline]
            fn from_channels(r: u8, g: u8, b: u8) -> Self {
                Self::new(r, g, b)
            }
        }
    )*};
}
display_color!(Rgb565, Bgr565, Rgb555, Rgb888, Bgr888);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::I16F16;

    fn quantize_every_format<S: Scalar>() {
        let c = Rgb::<S>::from_f64([0.5, 1.5, -0.2]).unwrap();
        let q: Rgb888 = c.quantize();
        assert_eq!((q.r(), q.g(), q.b()), (128, 255, 0), "{}", S::NAME);
        let q: Rgb565 = c.quantize();
        assert_eq!((q.r(), q.g(), q.b()), (16, 63, 0), "{}", S::NAME);
    }

    #[test]
    fn quantisation_rounds_and_clamps() {
        quantize_every_format::<I16F16>();
        quantize_every_format::<f32>();
        quantize_every_format::<f64>();
    }

    #[test]
    fn quantisation_matches_the_integer_formula_for_every_level() {
        // For every 8-bit level v, the colour v/255 lands exactly on level v, and on the 5- and
        // 6-bit level round(v·31/255), round(v·63/255).
        for v in 0_u8..=255 {
            let x = I16F16::ratio(i32::from(v), 255);
            let c: Rgb888 = Rgb::new(x, x, x).quantize();
            assert_eq!(c.r(), v);
            let c: Rgb565 = Rgb::new(x, x, x).quantize();
            let expect5 = ((u32::from(v) * 31 * 2 + 255) / 510) as u8;
            let expect6 = ((u32::from(v) * 63 * 2 + 255) / 510) as u8;
            assert!(
                c.r().abs_diff(expect5) <= 1 && c.g().abs_diff(expect6) <= 1,
                "{v}"
            );
        }
    }
}
