//! Integer square roots and reciprocal square roots for the fixed-point formats, by
//! multiplication only: no division, and no bit-by-bit loop with a branch per bit.
//!
//! Both start from the reciprocal square root of a normalised value ([`rsqrt_q30`]):
//!
//! 1. Normalise: shift y left by an even amount 2k so that its top two bits are not both zero,
//!    and keep the top 32 bits as m, a Q0.32 number in [¼, 1). Then y ≈ m·2^(64 − 2k).
//! 2. Seed z ≈ 1/√m from a 384-entry table on m's top nine bits (about nine correct bits).
//! 3. Newton steps for 1/√m, z ← z·(3 − m·z²)/2, each doubling the correct bits (17 after
//!    one, [`ONE_STEP_BITS`]; the 30 of Q2.30 after two).
//!
//! Then √y = m·z·2^(32 − k) and 1/√y = z·2^(k − 32), and the two routines scale accordingly.
//! [`isqrt_u64`] finishes by stepping to the exact ⌊√y⌋, so its result is the mathematical one;
//! [`rsqrt_fixed`] rounds. Both are integer arithmetic, so every target computes the same bits;
//! every product has operands below 2³², which the Cortex-M0 multiplies without a library call
//! ([`mul_u64_small`]).

crate::phase::declare_phase!(Some(crate::phase::Phase::Arithmetic));

use super::kernels::{
    leading_zeros_u64, mul_u64_small, round_shr_u64, shl_u64, shr_u64, square_u64_small,
};

/// The bits of m that index [`RSQRT_SEEDS`].
const SEED_BITS: u32 = 9;
/// The table's first index: m ≥ ¼.
const SEED_BASE: usize = 1 << (SEED_BITS - 2);

/// ⌊2³⁰ / √((i + 128.5) / 512)⌋ = ⌊√(2⁷⁰ / (2i + 257))⌋: 1/√m in Q2.30 at the middle of each
/// of the 384 intervals of m's top nine bits (128..512, as m ≥ ¼).
#[allow(
    clippy::indexing_slicing,
    reason = "evaluated at compile time, i < 384"
)]
static RSQRT_SEEDS: [u32; 3 * SEED_BASE] = {
    let mut table = [0_u32; 3 * SEED_BASE];
    let mut i = 0;
    while i < 3 * SEED_BASE {
        // At most 2³¹: fits u32.
        table[i] =
            isqrt_bitwise((1_u128 << 70) / (2 * i as u128 + 2 * SEED_BASE as u128 + 1)) as u32;
        i += 1;
    }
    table
};

/// The bits of 1/√m one Newton step from [`RSQRT_SEEDS`] keeps: its relative error is below
/// 2⁻¹⁷ (2⁻¹⁷·⁴² at the ends of the widest interval, tested).
pub const ONE_STEP_BITS: u32 = 17;

/// Whether one Newton step keeps a unit vector in a format with `frac` fraction bits within
/// its LSB (half an LSB of rounding and 2^−[`ONE_STEP_BITS`] ≤ half an LSB): the fast unit
/// vectors take one step where it does, two where it does not, so that they are as exact as
/// the error model's unit ([`crate::scalar::Precision::UNIT_ERROR`]) in every format. Integer
/// arithmetic: it runs per vector where the compiler does not see `frac` as a constant.
#[must_use]
pub const fn one_step_holds_unit(frac: u32) -> bool {
    frac < ONE_STEP_BITS
}

/// ⌊√y⌋ one bit at a time: slow, obviously right, and usable at compile time.
const fn isqrt_bitwise(y: u128) -> u128 {
    let mut remainder = y;
    let mut root = 0;
    let mut bit = 1 << 126;
    while bit > remainder {
        bit >>= 2;
    }
    while bit != 0 {
        if remainder >= root + bit {
            remainder -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    root
}

/// Newton steps for the exact routines: all the bits of Q2.30.
const FULL: u32 = 2;
/// Newton steps for the fast ones: [`ONE_STEP_BITS`] correct bits.
const FAST: u32 = 1;

/// Normalises y > 0 to (m, 2k) with y ≈ m·2^(64 − 2k), m in [2³⁰, 2³²), and returns
/// (m, z ≈ 2³⁰/√(m/2³²), 2k) after `steps` Newton steps.
#[inline]
fn rsqrt_q30(y: u64, steps: u32) -> (u64, u64, u32) {
    let shift = leading_zeros_u64(y) & !1;
    let m = shl_u64(y, shift) >> 32;
    // m ≥ 2³⁰, so m >> 23 is in 128..512.
    let index = usize::try_from(m >> (32 - SEED_BITS))
        .unwrap_or(usize::MAX)
        .wrapping_sub(SEED_BASE);
    let mut z = u64::from(RSQRT_SEEDS.get(index).copied().unwrap_or(1 << 30));
    for _ in 0..steps {
        // z < 2³¹ and m·z² < 3·2⁶², so every product fits u64.
        let z_squared = square_u64_small(z) >> 30;
        let m_z_squared = mul_u64_small(m, z_squared) >> 32;
        z = mul_u64_small(z, (3 << 30) - m_z_squared) >> 31;
    }
    (m, z, shift)
}

/// The Newton steps of the exact routines, or of the `fast` ones.
#[inline]
const fn steps(fast: bool) -> u32 {
    if fast { FAST } else { FULL }
}

/// ⌊√y⌋ for y < 2⁶², exactly; to 17 bits when `fast` (one Newton step and no final
/// correction).
#[inline]
#[must_use]
pub fn isqrt_u64(y: u64, fast: bool) -> u64 {
    if y == 0 {
        return 0;
    }
    let (m, z, shift) = rsqrt_q30(y, steps(fast));
    let mut root = shr_u64(mul_u64_small(m, z) >> 30, shift / 2);
    if !fast {
        // root < 2³¹, so its square and its successor's fit u32 products.
        while square_u64_small(root) > y {
            root -= 1;
        }
        while square_u64_small(root + 1) <= y {
            root += 1;
        }
    }
    root
}

/// 2^(3f/2)/√x, for x > 0 and an even f ≤ 30: the reciprocal square root of a fixed-point
/// number with f fraction bits, in raw units. Within one unit of the exact value, or 2⁻²² of
/// it where that is more (the large roots of the smallest inputs); saturated to `u32::MAX`
/// where it does not fit (the smallest x, for f > 20).
/// To 17 bits when `fast`.
#[inline]
#[must_use]
pub fn rsqrt_fixed(x: u32, frac: u32, fast: bool) -> u32 {
    if x == 0 {
        return u32::MAX;
    }
    // x = (m/2³²)·2^(64 − 2k), so 2^(3f/2)/√x = z·2^(3f/2 + k − 62) with z in Q2.30, z ≤ 2³¹;
    // the exponent is at most 36 + 31 − 62 = 5 for f ≤ 24, and z shifted left so stays below 2⁶⁴.
    let (_, z, shift) = rsqrt_q30(u64::from(x), steps(fast));
    let exponent = 3 * frac / 2 + shift / 2;
    let raw = match 62_u32.checked_sub(exponent) {
        None | Some(0) => shl_u64(z, (exponent - 62).min(32)),
        Some(right) => round_shr_u64(z, right),
    };
    u32::try_from(raw).unwrap_or(u32::MAX)
}

/// The exponent of [`rsqrt_mantissa`]'s scale: 1/√y ≈ z·2^(s − `MANTISSA_SCALE`).
pub const MANTISSA_SCALE: u32 = 62;

/// The bits of [`rsqrt_mantissa`]'s mantissa: z < 2^`MANTISSA_BITS`.
pub const MANTISSA_BITS: u32 = 31;

/// The reciprocal square root of y > 0 as a mantissa and an exponent: (z, s) with
/// 1/√y ≈ z·2^(s − 62), z < 2³¹ carrying about 30 correct bits (17 when `fast`) whatever the size
/// of y — which a fixed-point result alone cannot do for large y.
#[inline]
#[must_use]
pub fn rsqrt_mantissa(y: u64, fast: bool) -> (u64, u32) {
    let (_, z, shift) = rsqrt_q30(y, steps(fast));
    // 1/√y = (z/2³⁰)·2^(k − 32) with 2k = shift; z reaches 2³¹ only for m = ¼ exactly.
    (z.min((1 << MANTISSA_BITS) - 1), shift / 2)
}

/// The bits of [`RootPair::root`] below the binary point of its exponent: √y ≈ root·2^−(30 + s).
pub const ROOT_SCALE: u32 = 30;

/// 1/√y and √y of one y > 0, from one normalisation and one seed: what a unit vector and its
/// length need.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RootPair {
    /// z < 2^[`MANTISSA_BITS`] with 1/√y ≈ z·2^(s − [`MANTISSA_SCALE`]): about 30 correct bits
    /// (17 when fast).
    pub inverse: u64,
    /// m·z < 2⁶³ with √y ≈ (m·z)·2^−([`ROOT_SCALE`] + s), m the top 32 bits of y.
    pub root: u64,
    /// The exponent s, at most 31.
    pub s: u32,
}

/// [`RootPair`] of y > 0 (any u64): to about 30 bits, or 17 when `fast`.
#[inline]
#[must_use]
pub fn root_pair(y: u64, fast: bool) -> RootPair {
    let (m, z, shift) = rsqrt_q30(y, steps(fast));
    let inverse = z.min((1 << MANTISSA_BITS) - 1);
    RootPair {
        inverse,
        // m < 2³² and z < 2³¹.
        root: mul_u64_small(m, inverse),
        s: shift / 2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_on_every_small_input() {
        for y in 0..1_u64 << 20 {
            assert_eq!(isqrt_u64(y, false), y.isqrt(), "{y}");
        }
    }

    #[test]
    fn exact_around_every_power_of_two_and_square() {
        for bits in 20..62 {
            let p = 1_u64 << bits;
            for y in [p - 1, p, p + 1] {
                assert_eq!(isqrt_u64(y, false), y.isqrt(), "{y}");
            }
            let r = p.isqrt();
            for y in [r * r - 1, r * r, r * r + 1, (r + 1) * (r + 1) - 1] {
                assert_eq!(isqrt_u64(y, false), y.isqrt(), "{y}");
            }
        }
    }

    #[test]
    fn exact_on_a_pseudorandom_sweep() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        for _ in 0..2_000_000 {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let y = state >> (2 + state % 40);
            assert_eq!(isqrt_u64(y, false), y.isqrt(), "{y}");
        }
    }

    #[test]
    fn reciprocal_root_is_within_one_unit() {
        // Every even fraction of the 32-bit formats, i8f24 to i24f8; what does not fit u32
        // saturates.
        for frac in (8..=24).step_by(2) {
            let mut x = 1_u32;
            while x < u32::MAX / 2 {
                let exact = ((1_u64 << (3 * frac / 2)) as f64 / f64::from(x).sqrt())
                    .min(f64::from(u32::MAX));
                let got = f64::from(rsqrt_fixed(x, frac, false));
                let tolerance = (exact / f64::from(1 << 22)).max(1.0);
                assert!(
                    (got - exact).abs() <= tolerance,
                    "frac {frac}, x {x}: {got} vs {exact}"
                );
                x = x + x / 97 + 1;
            }
        }
    }

    #[test]
    fn fast_routines_hold_fourteen_bits() {
        let mut y = 1_u64;
        while y < 1 << 61 {
            let exact = (y as f64).sqrt();
            let got = isqrt_u64(y, true) as f64;
            assert!(
                (got - exact).abs() <= exact / 16384.0 + 1.0,
                "{y}: {got} vs {exact}"
            );
            y = y * 3 / 2 + 1;
        }
        for frac in (8..=24).step_by(2) {
            let mut x = 1_u32;
            while x < u32::MAX / 2 {
                let exact = ((1_u64 << (3 * frac / 2)) as f64 / f64::from(x).sqrt())
                    .min(f64::from(u32::MAX));
                let got = f64::from(rsqrt_fixed(x, frac, true));
                assert!(
                    (got - exact).abs() <= exact / 16384.0 + 1.0,
                    "frac {frac}, x {x}"
                );
                x = x + x / 97 + 1;
            }
        }
    }

    #[test]
    fn a_root_pair_holds_thirty_bits_of_both_roots() {
        let mut y = 1_u64;
        while y < u64::MAX / 3 {
            for y in [y, y / 2 * 3 + 7, u64::MAX - y] {
                let RootPair { inverse, root, s } = root_pair(y, false);
                let exact = (y as f64).sqrt();
                let inverse = inverse as f64 * 2f64.powi(s as i32 - MANTISSA_SCALE as i32);
                let root = root as f64 * 2f64.powi(-((ROOT_SCALE + s) as i32));
                assert!((inverse * exact - 1.0).abs() < 2e-9, "1/√{y}");
                assert!((root / exact - 1.0).abs() < 2e-9, "√{y}");
            }
            y += y / 4 + 1;
        }
    }

    #[test]
    fn seeds_are_the_reciprocal_square_roots() {
        for (i, &seed) in RSQRT_SEEDS.iter().enumerate() {
            let m = (i as f64 + 128.5) / 512.0;
            let exact = f64::from(1_u32 << 30) / m.sqrt();
            assert!((f64::from(seed) - exact).abs() <= 1.0, "{i}");
        }
    }

    /// Every interval of the table, at its ends (where the seed is worst) and between.
    #[test]
    fn one_step_is_within_its_bound() {
        let bound = 1.0 / f64::from(1_u32 << ONE_STEP_BITS);
        let mut worst = 0.0_f64;
        for top in 128_u64..512 {
            for eighth in 0..=8 {
                let m = ((top << 23) + eighth * (1 << 20)).min(u64::from(u32::MAX));
                let (_, z, shift) = rsqrt_q30(m << 32, FAST);
                assert_eq!(shift, 0);
                let exact = f64::from(1_u32 << 30) / (m as f64 / 2f64.powi(32)).sqrt();
                worst = worst.max((z as f64 / exact - 1.0).abs());
            }
        }
        assert!(worst <= bound, "{worst:e}");
        assert!(worst > bound / 2.0, "the bound is loose: {worst:e}");
    }

    #[test]
    fn one_step_holds_unit_vectors_to_sixteen_fraction_bits() {
        assert!(one_step_holds_unit(16));
        assert!(!one_step_holds_unit(18));
    }
}
