//! Where a pixel's rays go when it takes several ([`SceneDesc::samples`]): the first points of
//! Sobol's (0, 2)-sequence — van der Corput's radical inverse across, Sobol's second dimension
//! down —, scrambled per pixel by XOR with an integer hash, all in 32-bit integers. Every
//! format, the f64 reference and the firmware compute the very same positions, so the
//! difference between their images stays a measure of their arithmetic alone.
//!
//! Any 2ᵐ consecutive points from the start form a (0, m, 2)-net, and XOR scrambling keeps it
//! one: every box of the pixel 2⁻ᵃ wide and 2⁻ᵇ high with a + b = m holds exactly one sample.
//! So 16 samples split every row of a 4×4 grid, every 16th of the pixel across and every 16th
//! down exactly once, and an edge along either axis is covered to within a sample.
//!
//! [`SceneDesc::samples`]: crate::SceneDesc::samples

use crate::scalar::Scalar;

/// The most rays a pixel may take.
pub const MAX_SAMPLES: u16 = 256;

/// The sample positions of one pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelPattern {
    /// The pixel's scramble of the sequence, per axis: bits to flip.
    scramble: [u32; 2],
}

impl PixelPattern {
    /// The pattern of pixel (`x`, `y`): the same for the same pixel on every machine.
    #[must_use]
    pub fn of(x: u32, y: u32) -> Self {
        let seed = mix(x ^ mix(y));
        Self {
            scramble: [seed, mix(seed)],
        }
    }

    /// Sample `i`'s position in the pixel, as fractions of 2³² of its width and height from
    /// its top-left corner.
    #[must_use]
    pub fn point(&self, i: u16) -> [u32; 2] {
        let [across, down] = self.scramble;
        let i = u32::from(i);
        [i.reverse_bits() ^ across, sobol_second(i) ^ down]
    }

    /// Sample `i`'s offset from the pixel's centre, in pixels (across, down), each in
    /// [−½, ½) to 16 bits.
    #[must_use]
    pub fn offset<S: Scalar>(&self, i: u16) -> [S; 2] {
        self.point(i)
            .map(|u| S::from_q16((u >> 16) as i32 - 0x8000))
    }
}

/// The second dimension of Sobol's sequence: the XOR of the direction numbers of `i`'s set
/// bits, each the one before shifted right and XORed with itself (all its m_k are 1).
const fn sobol_second(mut i: u32) -> u32 {
    let (mut direction, mut point) = (1_u32 << 31, 0);
    while i != 0 {
        if i & 1 != 0 {
            point ^= direction;
        }
        i >>= 1;
        direction ^= direction >> 1;
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

    /// The (0, m, 2)-net property, in every pixel tried: the first 2ᵐ samples put exactly one
    /// in each box of the pixel 2⁻ᵃ wide and 2⁻ᵇ high with a + b = m, for m up to 8.
    #[test]
    fn every_power_of_two_of_samples_is_a_net() {
        for (x, y) in (0..16).flat_map(|x| (0..16).map(move |y| (x, y))) {
            let pattern = PixelPattern::of(x, y);
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

    /// Neighbouring pixels take different patterns, and a pixel always the same one.
    #[test]
    fn each_pixel_has_its_own_scramble() {
        let a = PixelPattern::of(10, 20);
        assert_eq!(a, PixelPattern::of(10, 20));
        assert_eq!(a.point(0), a.scramble);
        for other in [(11, 20), (10, 21), (20, 10), (9, 20)] {
            assert_ne!(a, PixelPattern::of(other.0, other.1), "{other:?}");
        }
    }

    /// Offsets lie in [−½, ½) and are the points' top 16 bits, in every kind of format.
    #[test]
    fn offsets_are_within_the_pixel() {
        let pattern = PixelPattern::of(3, 7);
        for i in 0..MAX_SAMPLES {
            let [u, v] = pattern.point(i);
            let want = [u, v].map(|w| f64::from(w >> 16) / 65536.0 - 0.5);
            assert_eq!(pattern.offset::<f64>(i), want);
            let fixed = pattern.offset::<crate::I16F16>(i).map(Scalar::to_f64);
            assert_eq!(fixed, want);
            assert!(want.iter().all(|w| (-0.5..0.5).contains(w)));
        }
    }
}
