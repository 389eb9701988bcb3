//! Linear colour in the tracer's number format, and its quantisation to a display's pixel
//! colour. Light is in the format; what filters it — a surface's colour, a weight along the
//! ray tree — is at most 1, and is in the format's narrow numbers ([`Scalar::Narrow`]).

crate::phase::declare_phase!(Some(crate::phase::Phase::Output));

use crate::scalar::Scalar;
use core::ops::Add;
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

crate::words::words_of_struct!(Rgb<S: NumberBits> { r, g, b });

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

    /// Every channel multiplied by the narrow number `k` ([`Scalar::mul_narrow`]).
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn scale_narrow(self, k: S::Narrow) -> Self {
        Self::new(
            self.r.mul_narrow(k),
            self.g.mul_narrow(k),
            self.b.mul_narrow(k),
        )
    }

    /// Light filtered by a narrow colour (a surface's, or a weight), channel by channel.
    #[inline]
    #[must_use]
    #[track_caller]
    pub fn filter(self, by: Rgb<S::Narrow>) -> Self {
        Self::new(
            self.r.mul_narrow(by.r),
            self.g.mul_narrow(by.g),
            self.b.mul_narrow(by.b),
        )
    }

    /// What a display can show of the colour, each channel clamped to [0, 1], in 16-bit
    /// fractions (0 to 2¹⁶, rounded down): the integers a pixel's samples are summed in, the
    /// same way in every format.
    #[inline]
    #[must_use]
    pub fn to_q16(self) -> [u32; 3] {
        let unit = |c: S| c.clamp(S::ZERO, S::ONE).to_q16().unsigned_abs();
        [unit(self.r), unit(self.g), unit(self.b)]
    }

    /// The colour whose channels are these 16-bit fractions (see [`Self::to_q16`]).
    #[inline]
    #[must_use]
    pub fn from_q16([r, g, b]: [u32; 3]) -> Self {
        let channel = |c: u32| S::from_q16(i32::try_from(c).unwrap_or(i32::MAX));
        Self::new(channel(r), channel(g), channel(b))
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
        // ½ in 16-bit fractions: a shift, where a quotient cost every pixel.
        self.quantize_with(S::from_q16(1 << 15))
    }

    /// The colour on a display at pixel (`x`, `y`), by `dither`: rounded to the nearest level,
    /// or with [`Dither::Ordered`] up or down by the pixel's threshold in a 4×4 Bayer matrix, so
    /// that a gradient finer than the display's levels shows as a pattern of the two levels
    /// around it rather than as bands. The threshold comes from the position alone, in
    /// integers: the same pixel gets the same level in every format, on every machine.
    #[must_use]
    pub fn quantize_at<C: DisplayColor>(self, dither: Dither, x: u32, y: u32) -> C {
        match dither {
            Dither::None => self.quantize(),
            // (2b + 1)/32 in 16-bit fractions, likewise.
            Dither::Ordered => self.quantize_with(S::from_q16((2 * bayer(x, y) + 1) << 11)),
        }
    }

    /// Each channel `floor(clamp(v, 0, 1) · max + threshold)`, with `threshold` in (0, 1).
    fn quantize_with<C: DisplayColor>(self, threshold: S) -> C {
        C::from_channels(
            self.r.quantize(C::MAX_R, threshold),
            self.g.quantize(C::MAX_G, threshold),
            self.b.quantize(C::MAX_B, threshold),
        )
    }
}

/// How a colour is rounded to a display's levels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Dither {
    /// To the nearest level.
    #[default]
    None,
    /// Up or down by an ordered (Bayer) threshold from the pixel's position.
    Ordered,
}

impl crate::methods::MethodName for Dither {
    const ALL: &'static [(Self, &'static str)] =
        &[(Self::None, "none"), (Self::Ordered, "ordered")];
}

/// The 4×4 Bayer matrix's entry for pixel (`x`, `y`): 0 to 15, each once in every 4×4 block.
fn bayer(x: u32, y: u32) -> i32 {
    const MATRIX: [[i32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
    MATRIX
        .get((y % 4) as usize)
        .and_then(|row| row.get((x % 4) as usize))
        .copied()
        .unwrap_or(0)
}

impl<S: Scalar> Add for Rgb<S> {
    type Output = Self;
    #[inline]
    #[track_caller]
    fn add(self, rhs: Self) -> Self {
        Self::new(self.r + rhs.r, self.g + rhs.g, self.b + rhs.b)
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

    fn dither_stays_within_a_level<S: Scalar>() {
        for i in 0..=256 {
            let c = Rgb::<S>::from_f64([f64::from(i) / 256.0; 3]).unwrap();
            let plain: Rgb565 = c.quantize();
            let mut levels = [0_u32; 64];
            for (x, y) in (0..4).flat_map(|y| (0..4).map(move |x| (x, y))) {
                let dithered: Rgb565 = c.quantize_at(Dither::Ordered, x, y);
                assert!(
                    dithered.g().abs_diff(plain.g()) <= 1,
                    "{} at {i}/256",
                    S::NAME
                );
                assert!(
                    dithered.r().abs_diff(plain.r()) <= 1,
                    "{} at {i}/256",
                    S::NAME
                );
                levels[usize::from(dithered.g())] += 1;
                let again: Rgb565 = c.quantize_at(Dither::Ordered, x + 4, y + 8);
                assert_eq!(again, dithered, "the pattern repeats every 4 pixels");
            }
            // Over a 4×4 block the levels average to the colour, within a 16th of a level.
            let mean = levels
                .iter()
                .enumerate()
                .map(|(level, &n)| level as f64 * f64::from(n))
                .sum::<f64>()
                / 16.0;
            let exact = f64::from(i) / 256.0 * 63.0;
            assert!(
                (mean - exact).abs() <= 1.0 / 16.0 + 1e-9,
                "{} at {i}/256: {mean} vs {exact}",
                S::NAME
            );
        }
    }

    #[test]
    fn an_ordered_dither_averages_to_the_colour_within_one_level_of_rounding() {
        dither_stays_within_a_level::<I16F16>();
        dither_stays_within_a_level::<f32>();
        dither_stays_within_a_level::<f64>();
    }

    #[test]
    fn no_dither_rounds_to_the_nearest_level() {
        let c = Rgb::<f32>::from_f64([0.3, 0.6, 0.9]).unwrap();
        let plain: Rgb565 = c.quantize();
        assert_eq!(c.quantize_at::<Rgb565>(Dither::None, 3, 5), plain);
    }

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
    fn a_floats_quantisation_is_the_floor_of_the_default() {
        fn check<S: Scalar>(values: impl Iterator<Item = S>) {
            let thresholds = [0.0, 0.5, 1.0 / 32.0, 31.0 / 32.0, 0.999_999];
            for v in values {
                for levels in [1, 31, 63, 255] {
                    for t in thresholds.map(|t| S::from_f64(t).unwrap()) {
                        assert_eq!(
                            v.quantize(levels, t),
                            crate::scalar::quantize_by_floor(v, levels, t),
                            "{} {v:?} {levels} {t:?}",
                            S::NAME
                        );
                    }
                }
            }
        }
        let edges = [
            -1.0,
            -0.0,
            0.0,
            1e-30,
            0.5,
            1.0 - 1e-7,
            1.0,
            1.5,
            1e30,
            -1e30,
            -1e-30,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        check::<f32>(
            (0..=4096)
                .map(|i| i as f32 / 4096.0)
                .chain(edges.map(|e| e as f32)),
        );
        check::<f64>((0..=4096).map(|i| f64::from(i) / 4096.0).chain(edges));
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
