//! Where the rays of distributed ray tracing go: a pixel's when it takes several
//! ([`SceneDesc::samples`]), a lens's ([`CameraDesc::aperture`]), an area light's when a point
//! samples it ([`SceneDesc::shadow_samples`]). A pixel's positions are the first points of
//! Sobol's sequence in its first two dimensions — van der Corput's radical inverse across,
//! Sobol's second dimension down —, and its lens positions the same points' third and fourth
//! dimensions, so that a pixel's samples spread over the pixel and the lens together (Cook's
//! four-dimensional sampling) rather than each pixel position always taking the same lens
//! position. An area light's are the first two dimensions again, for another scramble. Each
//! is scrambled by XOR with an integer hash of the pixel (and for a light, of the pixel's sample
//! and the light), all in 32-bit integers. Every format, the f64 reference and the firmware
//! compute the very same positions, so the difference between their images stays a measure of
//! their arithmetic alone.
//!
//! In the first two dimensions any 2ᵐ consecutive points from the start form a (0, m, 2)-net,
//! and XOR scrambling keeps it one: every box of the square 2⁻ᵃ wide and 2⁻ᵇ high with
//! a + b = m holds exactly one point. So 16 samples split every row of a 4×4 grid, every 16th
//! of the pixel across and every 16th down exactly once, and an edge along either axis is
//! covered to within a sample. The third and fourth form a (1, m, 2)-net from 16 points on
//! (every box holds two points where boxes of half the area would each hold one), and a
//! (2, 3, 2)-net of 8. On a lens or a light the square is mapped onto a disc keeping areas
//! ([`Pattern::disc`]), so the disc's cells are as even as the square's.
//!
//! [`SceneDesc::samples`]: crate::SceneDesc::samples
//! [`SceneDesc::shadow_samples`]: crate::SceneDesc::shadow_samples
//! [`CameraDesc::aperture`]: crate::CameraDesc::aperture

crate::phase::declare_phase!(None);

use crate::scalar::Scalar;

/// The most rays a pixel, or a point lit by an area light, may take.
pub const MAX_SAMPLES: u16 = 256;

/// Shadow rays an area light takes, with [`SceneDesc::adaptive_shadows`], before the rest are
/// spent only if they disagree. Four points of the sequence fall one in each quarter of the
/// light's square (a (0, 2, 2)-net), spread over the disc.
///
/// [`SceneDesc::adaptive_shadows`]: crate::SceneDesc::adaptive_shadows
pub const SHADOW_PROBES: u16 = 4;

/// Which ray of the image a trace follows: sample `sample` of pixel (`x`, `y`). Its shadow
/// rays take their pattern from it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SampleId {
    /// The pixel's column.
    pub x: u32,
    /// The pixel's row.
    pub y: u32,
    /// Which of the pixel's samples (0 for a one-sample image; with adaptive samples, 0 for
    /// the pixel's top left corner and 1 + a point's place on the pixel's grid for the others).
    pub sample: u16,
}

/// One scramble of two dimensions of the sequence: the sample positions of a pixel, of its
/// lens, or of an area light as one sample of a pixel sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pattern {
    /// The bits to flip, per axis.
    scramble: [u32; 2],
    /// Which two of Sobol's dimensions.
    dimensions: Dimensions,
}

/// Two dimensions of Sobol's sequence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Dimensions {
    /// The first and second: a pixel's positions, an area light's.
    FirstAndSecond,
    /// The third and fourth: a lens's.
    ThirdAndFourth,
}

impl Pattern {
    /// The pattern of pixel (`x`, `y`): the same for the same pixel on every machine.
    #[must_use]
    pub fn pixel(x: u32, y: u32) -> Self {
        Self::seeded(mix(x ^ mix(y)))
    }

    /// The lens positions of pixel (`x`, `y`)'s samples, the third and fourth dimensions of
    /// the points whose first two are [`Self::pixel`]'s, scrambled apart from them.
    #[must_use]
    pub fn lens(x: u32, y: u32) -> Self {
        let [_, seed] = Self::pixel(x, y).scramble;
        Self {
            dimensions: Dimensions::ThirdAndFourth,
            ..Self::seeded(mix(!seed))
        }
    }

    /// The pattern of light number `light` as the trace `id` sees it: another for each
    /// sample of a pixel, so that a pixel's samples together see more of the light.
    #[must_use]
    pub fn light(id: SampleId, light: u16) -> Self {
        let light = u32::from(light) << 16;
        Self::seeded(mix(
            Self::pixel(id.x, id.y).scramble[1] ^ mix(u32::from(id.sample) ^ light)
        ))
    }

    const fn seeded(seed: u32) -> Self {
        Self {
            scramble: [seed, mix(seed)],
            dimensions: Dimensions::FirstAndSecond,
        }
    }

    /// Point `i`'s position in the unit square (a pixel: from its top-left corner), as
    /// fractions of 2³² of its width and height.
    #[must_use]
    pub fn point(&self, i: u16) -> [u32; 2] {
        let [across, down] = self.scramble;
        let i = u32::from(i);
        let point = match self.dimensions {
            Dimensions::FirstAndSecond => [i.reverse_bits(), sobol(i, &SECOND)],
            Dimensions::ThirdAndFourth => [sobol(i, &THIRD), sobol(i, &FOURTH)],
        };
        [point[0] ^ across, point[1] ^ down]
    }

    /// Sample `i`'s offset from the pixel's centre, in pixels (across, down), each in
    /// [−½, ½) to 16 bits.
    #[must_use]
    pub fn offset<S: Scalar>(&self, i: u16) -> [S; 2] {
        self.point(i)
            .map(|u| S::from_q16((u >> 16) as i32 - 0x8000))
    }

    /// Point `i` mapped onto the unit disc (the centre at 0), each coordinate to 16 bits: a
    /// point of an area light, or of a lens.
    #[must_use]
    pub fn disc<S: Scalar>(&self, i: u16) -> [S; 2] {
        concentric(self.point(i)).map(S::from_q16)
    }
}

/// Shirley and Chiu's concentric map (1997) of a point of the unit square onto the unit disc,
/// in 16-bit fractions: each square about the centre goes to the circle of its half-side,
/// arcs in proportion to the square's perimeter, so areas are kept and cells stay compact.
/// In integers, with a polynomial for the angle's sine and cosine, alike on every machine.
fn concentric([u, v]: [u32; 2]) -> [i32; 2] {
    // From the centre, in [−1, 1) with 31 fractional bits.
    let a = (u ^ 0x8000_0000) as i32 as i64;
    let b = (v ^ 0x8000_0000) as i32 as i64;
    if a == 0 && b == 0 {
        return [0, 0];
    }
    // The larger coordinate is the radius r; the angle from the nearer axis, (π/4)·t with
    // t the smaller over the larger, in [−1, 1] with 30 fractional bits.
    let (r, t, down) = if a.abs() > b.abs() {
        (a, (b << 30) / a, false)
    } else {
        (b, (a << 30) / b, true)
    };
    let (sin, cos) = quarter_sin_cos(t);
    // r·sin and r·cos have 61 fractional bits; rounded to 16.
    let q16 = |x: i64| ((x + (1 << 44)) >> 45) as i32;
    if down {
        // Angle π/2 − (π/4)·t from the x axis.
        [q16(r * sin), q16(r * cos)]
    } else {
        [q16(r * cos), q16(r * sin)]
    }
}

/// sin and cos of (π/4)·t for t in [−1, 1], all with 30 fractional bits: Taylor polynomials to
/// the 11th and 12th powers, whose first dropped terms are below 2⁻³⁰.
fn quarter_sin_cos(t: i64) -> (i64, i64) {
    const SIN: [i64; 6] = [
        taylor(1),
        taylor(3),
        taylor(5),
        taylor(7),
        taylor(9),
        taylor(11),
    ];
    const COS: [i64; 7] = [
        taylor(0),
        taylor(2),
        taylor(4),
        taylor(6),
        taylor(8),
        taylor(10),
        taylor(12),
    ];
    let mul = |x: i64, y: i64| (x * y + (1 << 29)) >> 30;
    let t2 = mul(t, t);
    // Horner in t², the signs alternating.
    let horner = |c: &[i64]| c.iter().rev().fold(0, |sum, &c| c - mul(t2, sum));
    (mul(t, horner(&SIN)), horner(&COS))
}

/// (π/4)ᵏ/k! with 30 fractional bits.
const fn taylor(k: u32) -> i64 {
    let mut term = 1.0;
    let mut i = 1;
    while i <= k {
        term = term * core::f64::consts::FRAC_PI_4 / i as f64;
        i += 1;
    }
    (term * (1_u64 << 30) as f64 + 0.5) as i64
}

/// Sobol's second, third and fourth dimensions: the direction numbers of the primitive
/// polynomials x + 1, x² + x + 1 and x³ + x + 1 with Joe and Kuo's initial numbers (2008), one
/// per bit of a point's index (indices are 16-bit). The first dimension, van der Corput's, is
/// the index's bits reversed.
const SECOND: [u32; 16] = directions(1, 0, [1, 0, 0]);
const THIRD: [u32; 16] = directions(2, 1, [1, 3, 0]);
const FOURTH: [u32; 16] = directions(3, 1, [1, 3, 1]);

/// The direction numbers of the dimension whose primitive polynomial has degree `degree` and
/// inner coefficients `a` (their bits, highest power first), from its first `degree` odd
/// numbers m: m_k = 2ˢm_(k−s) ⊕ m_(k−s) ⊕ ⊕_j 2ʲ a_j m_(k−j), the kth number m_k·2⁻ᵏ as 32
/// bits.
#[allow(
    clippy::indexing_slicing,
    reason = "evaluated by the compiler, for the constants above only: an index out of bounds \
              would fail the build"
)]
const fn directions(degree: usize, a: u32, initial: [u32; 3]) -> [u32; 16] {
    let mut m = [0_u32; 16];
    let mut k = 0;
    while k < 16 {
        m[k] = if k < degree {
            initial[k]
        } else {
            let mut next = m[k - degree] ^ (m[k - degree] << degree);
            let mut j = 1;
            while j < degree {
                if (a >> (degree - 1 - j)) & 1 != 0 {
                    next ^= m[k - j] << j;
                }
                j += 1;
            }
            next
        };
        k += 1;
    }
    let mut directions = [0_u32; 16];
    let mut k = 0;
    while k < 16 {
        directions[k] = m[k] << (31 - k);
        k += 1;
    }
    directions
}

/// Point `i` of the dimension with these direction numbers: the XOR of those of `i`'s set
/// bits.
fn sobol(mut i: u32, directions: &[u32; 16]) -> u32 {
    let mut point = 0;
    for d in directions {
        if i == 0 {
            break;
        }
        if i & 1 != 0 {
            point ^= d;
        }
        i >>= 1;
    }
    point
}

/// A 32-bit integer hash with good avalanche (Chris Wellons' "lowbias32").
const fn mix(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^ (x >> 16)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Precision;
    use core::f64::consts::FRAC_PI_4;

    /// The (0, m, 2)-net property, in every pixel tried: the first 2ᵐ samples put exactly one
    /// in each box of the pixel 2⁻ᵃ wide and 2⁻ᵇ high with a + b = m, for m up to 8.
    #[test]
    fn every_power_of_two_of_samples_is_a_net() {
        for (x, y) in (0..16).flat_map(|x| (0..16).map(move |y| (x, y))) {
            let pattern = Pattern::pixel(x, y);
            for m in 0..=8_u32 {
                for a in 0..=m {
                    let b = m - a;
                    let mut boxes = vec![0_u8; 1 << m];
                    for i in 0..1_u16 << m {
                        let [u, v] = pattern.point(i);
                        let across = if a == 0 { 0 } else { u >> (32 - a) };
                        let down = if b == 0 { 0 } else { v >> (32 - b) };
                        boxes[((across << b) | down) as usize] += 1;
                    }
                    assert!(boxes.iter().all(|&n| n == 1), "({x}, {y}) m {m} a {a}");
                }
            }
        }
    }

    /// The first points of Sobol's third and fourth dimensions (Joe and Kuo's numbers, as
    /// fractions of 2³²), and the second's recurrence (every m_k is 1).
    #[test]
    fn the_direction_numbers_are_sobols() {
        assert_eq!(
            THIRD[..6],
            [
                0x8000_0000,
                0xc000_0000,
                0x6000_0000,
                0x9000_0000,
                0xe800_0000,
                0x5c00_0000
            ]
        );
        assert_eq!(
            FOURTH[..6],
            [
                0x8000_0000,
                0xc000_0000,
                0x2000_0000,
                0x5000_0000,
                0xf800_0000,
                0x7400_0000
            ]
        );
        let mut direction = 1_u32 << 31;
        for d in SECOND {
            assert_eq!(d, direction);
            direction ^= direction >> 1;
        }
    }

    /// The lens's points: for 2ᵐ samples every box of the square of area 2ᵗ⁻ᵐ holds 2ᵗ of
    /// them, t at most 1 from 16 samples on (2 at 8); and jointly with the pixel's, each lens
    /// axis against each pixel axis is as even (so no pixel position is tied to one lens
    /// position).
    #[test]
    fn lens_points_are_a_net_and_independent_of_the_pixels() {
        let t_of = |m: u32, point: &dyn Fn(u16) -> [u32; 2]| {
            (0..=m)
                .find(|&t| {
                    (0..=m - t).all(|a| {
                        let b = m - t - a;
                        let mut boxes = vec![0_u16; 1 << (m - t)];
                        for i in 0..1_u16 << m {
                            let [u, v] = point(i);
                            let across = if a == 0 { 0 } else { u >> (32 - a) };
                            let down = if b == 0 { 0 } else { v >> (32 - b) };
                            boxes[((across << b) | down) as usize] += 1;
                        }
                        boxes.iter().all(|&n| n == 1 << t)
                    })
                })
                .unwrap_or(m)
        };
        for (x, y) in [(0, 0), (5, 9), (100, 3)] {
            let (pixel, lens) = (Pattern::pixel(x, y), Pattern::lens(x, y));
            for m in 1..=8_u32 {
                let most = if m >= 4 { 1 } else { 2 };
                assert!(t_of(m, &|i| lens.point(i)) <= most, "lens, m {m}");
                for (p, l) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                    let t = t_of(m, &|i| [pixel.point(i)[p], lens.point(i)[l]]);
                    assert!(
                        t <= 2,
                        "pixel axis {p} against lens axis {l}, m {m}: t = {t}"
                    );
                }
            }
        }
    }

    /// Neighbouring pixels take different patterns, and a pixel always the same one.
    #[test]
    fn each_pixel_has_its_own_scramble() {
        let a = Pattern::pixel(10, 20);
        assert_eq!(a, Pattern::pixel(10, 20));
        assert_eq!(a.point(0), a.scramble);
        for other in [(11, 20), (10, 21), (20, 10), (9, 20)] {
            assert_ne!(a, Pattern::pixel(other.0, other.1), "{other:?}");
        }
        let lens = Pattern::lens(10, 20);
        assert_ne!(lens.scramble, a.scramble);
        assert_ne!(lens.scramble, Pattern::lens(11, 20).scramble);
    }

    /// Shadow rays of one light take another pattern for each sample of a pixel, and each
    /// light its own.
    #[test]
    fn each_light_and_sample_has_its_own_scramble() {
        let id = SampleId {
            x: 4,
            y: 9,
            sample: 2,
        };
        let a = Pattern::light(id, 0);
        assert_eq!(a, Pattern::light(id, 0));
        for (other, light) in [
            (SampleId { sample: 3, ..id }, 0),
            (id, 1),
            (SampleId { x: 5, ..id }, 0),
        ] {
            assert_ne!(a, Pattern::light(other, light), "{other:?} light {light}");
        }
    }

    /// The concentric map in f64, from the square's centre.
    fn concentric_f64([u, v]: [u32; 2]) -> [f64; 2] {
        let [a, b] = [u, v].map(|w| f64::from(w) / 2f64.powi(31) - 1.0);
        if a == 0.0 && b == 0.0 {
            [0.0, 0.0]
        } else if a.abs() > b.abs() {
            let phi = FRAC_PI_4 * b / a;
            [a * phi.cos(), a * phi.sin()]
        } else {
            let phi = 2.0 * FRAC_PI_4 - FRAC_PI_4 * a / b;
            [b * phi.cos(), b * phi.sin()]
        }
    }

    /// The integer map is the concentric map to within its 16 bits, lands inside the disc,
    /// and keeps areas: of 4ⁿ points of a net, the share within radius ½ is a quarter.
    #[test]
    fn disc_points_are_the_concentric_map() {
        let pattern = Pattern::pixel(8, 1);
        let mut inner = 0;
        for i in 0..MAX_SAMPLES {
            let want = concentric_f64(pattern.point(i));
            let got = pattern.disc::<f64>(i);
            for (g, w) in got.into_iter().zip(want) {
                assert!(
                    (g - w).abs() <= 1.0 / 65536.0,
                    "point {i}: {got:?} against {want:?}"
                );
            }
            let r2 = got[0] * got[0] + got[1] * got[1];
            assert!(r2 <= 1.0 + 4.0 / 65536.0, "point {i}: {got:?}");
            inner += u32::from(r2 < 0.25);
        }
        assert_eq!(inner, u32::from(MAX_SAMPLES) / 4);
        for corner in [
            [0, 0],
            [u32::MAX, 0],
            [0, u32::MAX],
            [u32::MAX, u32::MAX],
            [1 << 31, 1 << 31],
        ] {
            let want = concentric_f64(corner).map(|w| (w * 65536.0).round() as i32);
            assert_eq!(concentric(corner), want, "{corner:?}");
        }
    }

    /// Offsets lie in [−½, ½) and are the points' top 16 bits, in every kind of format.
    #[test]
    fn offsets_are_within_the_pixel() {
        let pattern = Pattern::pixel(3, 7);
        for i in 0..MAX_SAMPLES {
            let [u, v] = pattern.point(i);
            let want = [u, v].map(|w| f64::from(w >> 16) / 65536.0 - 0.5);
            assert_eq!(pattern.offset::<f64>(i), want);
            let fixed = pattern.offset::<crate::I16F16>(i).map(Precision::to_f64);
            assert_eq!(fixed, want);
            assert!(want.iter().all(|w| (-0.5..0.5).contains(w)));
        }
    }
}
