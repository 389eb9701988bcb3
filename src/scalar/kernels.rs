//! The exact products the fixed formats are built from, at the machine's speed and with the
//! same bits on every machine. A 32-bit format's product is 32×32→64 bits: one instruction on a
//! Cortex-M4F (`smull`) or a PC, but the Cortex-M0 has no such multiply, and for `i64::from(a) *
//! i64::from(b)` its compiler calls `__aeabi_lmul`, a full 64×64 product. There it is made from
//! four 16×16→32 partial products (`muls` each), which is the exact product again.
//!
//! A 32-bit format's quotient a·2^f / b is a 64-by-32-bit division, for which every 32-bit
//! compiler calls `__aeabi_ldivmod`, a full 64-by-64 division. [`div_u64_u32`] divides by 32-bit
//! steps instead (the M4F's `udiv`; on the M0, which has no divider, a product by the divisor's
//! reciprocal), with the same quotient.
//!
//! The M0 has no 64-bit shifts either: for a shift by an amount that is not a constant its
//! compiler calls `__aeabi_llsl`, `__aeabi_llsr` or `__aeabi_lasr`, which [`shl_u64`],
//! [`shr_u64`] and [`shr_i64`] replace by two 32-bit shifts inline.

crate::phase::declare_phase!(Some(crate::phase::Phase::Arithmetic));

/// a·b exactly.
#[inline(always)]
pub fn mul_u32_wide(a: u32, b: u32) -> u64 {
    #[cfg(armv6m)]
    {
        mul_u32_partial(a, b)
    }
    #[cfg(not(armv6m))]
    {
        u64::from(a) * u64::from(b)
    }
}

/// a² exactly: three 16×16→32 partial products on the M0, as a₁a₀ serves twice.
#[inline(always)]
pub fn square_u32_wide(a: u32) -> u64 {
    #[cfg(armv6m)]
    {
        square_u32_partial(a)
    }
    #[cfg(not(armv6m))]
    {
        u64::from(a) * u64::from(a)
    }
}

/// a² exactly, for a below 2³² held in `u64` (the roots' Newton steps): [`square_u32_wide`] of
/// its low half.
#[inline(always)]
pub fn square_u64_small(a: u64) -> u64 {
    debug_assert!(a >> 32 == 0, "{a}² : an operand above 2³²");
    square_u32_wide(a as u32)
}

/// a·b exactly, for a and b below 2³² held in `u64` (the roots' Newton steps): [`mul_u32_wide`]
/// of their low halves.
#[inline(always)]
pub fn mul_u64_small(a: u64, b: u64) -> u64 {
    debug_assert!(
        a >> 32 == 0 && b >> 32 == 0,
        "{a} × {b}: an operand above 2³²"
    );
    mul_u32_wide(a as u32, b as u32)
}

/// a·b exactly (|a·b| ≤ 2⁶², so it fits).
#[inline(always)]
pub fn mul_i32_wide(a: i32, b: i32) -> i64 {
    #[cfg(armv6m)]
    {
        mul_i32_partial(a, b)
    }
    #[cfg(not(armv6m))]
    {
        i64::from(a) * i64::from(b)
    }
}

/// a·b exactly, for a 32-bit format's number and a narrow one (a cosine, a colour, a weight):
/// two 16×16→32 partial products on the M0, not four.
#[inline(always)]
pub fn mul_i32_i16_wide(a: i32, b: i16) -> i64 {
    #[cfg(armv6m)]
    {
        mul_i32_i16_partial(a, b)
    }
    #[cfg(not(armv6m))]
    {
        i64::from(a) * i64::from(b)
    }
}

/// The most fraction bits a product may be rounded to from its middle 32 bits
/// ([`mul_i32_rounded_wrapping`]): the partial products' 2¹⁶ steps must not be cut.
#[cfg(any(armv6m, test))]
const MIDDLE_FRAC_MAX: u32 = 16;

/// (a·b + 2^(frac−1)) >> frac, a product rounded to nearest to `frac` fraction bits, mod 2³²:
/// the format's product wherever it fits, which the range proof guarantees for a proven
/// scene, without the bits that would only say whether it fits. A 64-bit product on a PC and
/// the M4F; on the M0, for `frac` ≤ 16, its middle 32 bits (`mul_i32_middle`), which need no
/// 64-bit sum.
#[inline(always)]
#[allow(clippy::cast_possible_truncation, reason = "mod 2³² is the point")]
pub fn mul_i32_rounded_wrapping(a: i32, b: i32, frac: u32) -> i32 {
    #[cfg(armv6m)]
    if frac <= MIDDLE_FRAC_MAX {
        return mul_i32_middle(a, b, frac);
    }
    round_wrapping(mul_i32_wide(a, b), frac)
}

/// (a₀b₀ + a₁b₁ + a₂b₂ + 2^(frac−1)) >> frac, a dot product rounded once to `frac` fraction
/// bits, mod 2³²: [`mul_i32_rounded_wrapping`]'s sum of three (`dot3_i32_middle` on the M0).
#[inline(always)]
#[allow(clippy::cast_possible_truncation, reason = "mod 2³² is the point")]
pub fn dot3_i32_rounded_wrapping(a: [i32; 3], b: [i32; 3], frac: u32) -> i32 {
    #[cfg(armv6m)]
    if frac <= MIDDLE_FRAC_MAX {
        return dot3_i32_middle(a, b, frac);
    }
    let sum = mul_i32_wide(a[0], b[0])
        .wrapping_add(mul_i32_wide(a[1], b[1]))
        .wrapping_add(mul_i32_wide(a[2], b[2]));
    round_wrapping(sum, frac)
}

/// (a·k + 2^(frac−1)) >> frac for a narrow factor k, mod 2³² ([`mul_i32_rounded_wrapping`]
/// for a cosine, a colour or a weight; `mul_i32_i16_middle` on the M0).
#[inline(always)]
#[allow(clippy::cast_possible_truncation, reason = "mod 2³² is the point")]
pub fn mul_i32_i16_rounded_wrapping(a: i32, k: i16, frac: u32) -> i32 {
    #[cfg(armv6m)]
    if frac <= MIDDLE_FRAC_MAX {
        return mul_i32_i16_middle(a, k, frac);
    }
    round_wrapping(mul_i32_i16_wide(a, k), frac)
}

/// (x + 2^(frac−1)) >> frac mod 2³², for a product's exact `x`: with `smull` or `mul` and
/// `mulh`, an add with carry and a shift of each half.
#[inline(always)]
#[allow(clippy::cast_possible_truncation, reason = "mod 2³² is the point")]
fn round_wrapping(x: i64, frac: u32) -> i32 {
    (x.wrapping_add(1 << (frac - 1)) >> frac) as i32
}

/// The 16-bit halves of a, a = a₁·2¹⁶ + a₀ with a₁ = a >> 16 (arithmetic) and 0 ≤ a₀ < 2¹⁶.
#[cfg(any(armv6m, test))]
#[inline(always)]
fn halves(a: i32) -> (i32, i32) {
    (a >> 16, a & 0xFFFF)
}

/// A product's rounded middle, split from its low partial product: with the exact product
/// a·b = a₁b₁·2³² + (a₁b₀ + a₀b₁)·2¹⁶ + a₀b₀ and f ≤ 16, every term but a₀b₀ is a multiple of
/// 2^f, so (a·b + 2^(f−1)) >> f = a₁b₁·2^(32−f) + (a₁b₀ + a₀b₁)·2^(16−f) +
/// ((a₀b₀ + 2^(f−1)) >> f): this returns the first two terms mod 2³² (32-bit products, which
/// the M0's `muls` forms, wrapping where the whole would not) and a₀b₀ (below 2³² − 2¹⁷ + 2,
/// so a₀b₀ + 2¹⁵ still fits a `u32`).
#[cfg(any(armv6m, test))]
#[inline(always)]
#[allow(clippy::cast_sign_loss, reason = "0 ≤ a₀, b₀ < 2¹⁶")]
fn middle_and_low(a: i32, b: i32, frac: u32) -> (i32, u32) {
    let ((a1, a0), (b1, b0)) = (halves(a), halves(b));
    let high = (a1.wrapping_mul(b1) << (32 - frac))
        .wrapping_add(a1.wrapping_mul(b0).wrapping_add(a0.wrapping_mul(b1)) << (16 - frac));
    (high, (a0 as u32) * (b0 as u32))
}

/// [`mul_i32_rounded_wrapping`] from the product's middle 32 bits ([`middle_and_low`]): four
/// `muls` and no 64-bit sum, for f ≤ 16.
#[cfg(any(armv6m, test))]
#[inline(always)]
#[allow(clippy::cast_possible_wrap, reason = "(a₀b₀ + 2¹⁵) >> f < 2³²⁻ᶠ ≤ 2³¹ for f ≥ 1")]
fn mul_i32_middle(a: i32, b: i32, frac: u32) -> i32 {
    let (high, low) = middle_and_low(a, b, frac);
    high.wrapping_add(((low + (1 << (frac - 1))) >> frac) as i32)
}

/// [`dot3_i32_rounded_wrapping`] from middle 32 bits: the three products' middles add mod 2³²,
/// and their low partial products, each split at bit f into ⌊a₀b₀/2^f⌋ and its remainder r,
/// round once as the sum of the quotients and (Σr + 2^(f−1)) >> f (Σr < 3·2^f: no carry is
/// lost).
#[cfg(any(armv6m, test))]
#[inline(always)]
#[allow(clippy::cast_possible_wrap, reason = "each quotient is below 2³²⁻ᶠ ≤ 2³¹")]
fn dot3_i32_middle(a: [i32; 3], b: [i32; 3], frac: u32) -> i32 {
    let mask = (1_u32 << frac) - 1;
    let mut high = 0_i32;
    let mut remainders = 1_u32 << (frac - 1);
    for (&a, &b) in a.iter().zip(&b) {
        let (middle, low) = middle_and_low(a, b, frac);
        high = high.wrapping_add(middle).wrapping_add((low >> frac) as i32);
        remainders += low & mask;
    }
    high.wrapping_add((remainders >> frac) as i32)
}

/// [`mul_i32_i16_rounded_wrapping`] from two partial products, for f ≤ 16: a·k = a₁k·2¹⁶ + a₀k,
/// so (a·k + 2^(f−1)) >> f = a₁k·2^(16−f) + ((a₀k + 2^(f−1)) >> f), and a₀k + 2¹⁵ stays
/// within ±2³¹ (|a₀k| ≤ (2¹⁶ − 1)·2¹⁵).
#[cfg(any(armv6m, test))]
#[inline(always)]
fn mul_i32_i16_middle(a: i32, k: i16, frac: u32) -> i32 {
    let (a1, a0) = halves(a);
    let k = i32::from(k);
    (a1.wrapping_mul(k) << (16 - frac)).wrapping_add((a0 * k + (1 << (frac - 1))) >> frac)
}

/// a·b exactly from two partial products, a = a₁·2¹⁶ + a₀ with a₁ = a >> 16 (arithmetic) and
/// 0 ≤ a₀ < 2¹⁶: a₁b (at most 2³⁰ in magnitude) and a₀b (within ±2³¹, an `i32`).
#[cfg(any(armv6m, test))]
#[inline(always)]
fn mul_i32_i16_partial(a: i32, b: i16) -> i64 {
    let b = i32::from(b);
    let (a1, a0) = (a >> 16, a & 0xFFFF);
    (i64::from(a1 * b) << 16) + i64::from(a0 * b)
}

/// a·b exactly from four 16×16 partial products of signed high halves and unsigned low halves,
/// a = a₁·2¹⁶ + a₀ with a₁ = a >> 16 (arithmetic) and 0 ≤ a₀ < 2¹⁶: a₁b₁ (at most 2³⁰ in
/// magnitude), a₁b₀ and a₀b₁ (each within ±2³¹, so an `i32`), a₀b₀ (below 2³², a `u32`). No
/// magnitudes to take and no sign to apply after, where the unsigned product of |a| and |b|
/// needed both: 28 instructions on the M0 against 46.
#[cfg(any(armv6m, test))]
#[inline(always)]
fn mul_i32_partial(a: i32, b: i32) -> i64 {
    let (a1, a0) = (a >> 16, a & 0xFFFF);
    let (b1, b0) = (b >> 16, b & 0xFFFF);
    let middle = i64::from(a1 * b0) + i64::from(a0 * b1);
    let low = a0.unsigned_abs() * b0.unsigned_abs();
    (i64::from(a1 * b1) << 32) + (middle << 16) + i64::from(low)
}

/// a² exactly, from the products of its 16-bit halves: a₁²·2³² + a₁a₀·2¹⁷ + a₀².
#[cfg(any(armv6m, test))]
#[inline(always)]
fn square_u32_partial(a: u32) -> u64 {
    let (a0, a1) = (a & 0xFFFF, a >> 16);
    (u64::from(a1 * a1) << 32) + (u64::from(a1 * a0) << 17) + u64::from(a0 * a0)
}

/// a·b exactly, from the products of their 16-bit halves: (a₁b₁·2³² + (a₁b₀ + a₀b₁)·2¹⁶ + a₀b₀),
/// each partial product below 2³².
#[cfg(any(armv6m, test))]
#[inline(always)]
fn mul_u32_partial(a: u32, b: u32) -> u64 {
    let (a0, a1) = (a & 0xFFFF, a >> 16);
    let (b0, b1) = (b & 0xFFFF, b >> 16);
    let middle = u64::from(a1 * b0) + u64::from(a0 * b1);
    (u64::from(a1 * b1) << 32) + (middle << 16) + u64::from(a0 * b0)
}

/// x >> n (arithmetic), for n < 64. The M0 has no 64-bit shifts, and for a shift by an amount
/// that is not a constant its compiler calls `__aeabi_lasr`; inline, it is two 32-bit shifts
/// (`shr_i64_halves`).
#[inline(always)]
pub fn shr_i64(x: i64, n: u32) -> i64 {
    debug_assert!(n < 64, "a shift by {n}");
    #[cfg(armv6m)]
    {
        shr_i64_halves(x, n)
    }
    #[cfg(not(armv6m))]
    {
        x >> n
    }
}

/// x >> n (logical), for n < 64: [`shr_i64`]'s unsigned twin (`__aeabi_llsr` on the M0).
#[inline(always)]
pub fn shr_u64(x: u64, n: u32) -> u64 {
    debug_assert!(n < 64, "a shift by {n}");
    #[cfg(armv6m)]
    {
        shr_u64_halves(x, n)
    }
    #[cfg(not(armv6m))]
    {
        x >> n
    }
}

/// x << n, for n < 64 (`__aeabi_llsl` on the M0).
#[inline(always)]
pub fn shl_u64(x: u64, n: u32) -> u64 {
    debug_assert!(n < 64, "a shift by {n}");
    #[cfg(armv6m)]
    {
        shl_u64_halves(x, n)
    }
    #[cfg(not(armv6m))]
    {
        x << n
    }
}

/// x >> n (arithmetic) in 32-bit halves: the high half shifted, and the bits it passes to the
/// low half, (high << 1) << (31 − n), which is also right for n = 0. (By the logical shift of
/// x ^ sign, which would share [`shr_u64_halves`], it costs the M0's `whitted` 100 instructions
/// a pixel more.)
#[cfg(any(armv6m, test))]
#[inline(always)]
#[allow(
    clippy::cast_possible_truncation,
    clippy::cast_possible_wrap,
    clippy::cast_sign_loss,
    reason = "the halves of a 64-bit integer"
)]
fn shr_i64_halves(x: i64, n: u32) -> i64 {
    let (high, low) = ((x >> 32) as i32, x as u32);
    if n >= 32 {
        i64::from(high >> (n - 32))
    } else {
        let carried = ((high as u32) << 1) << (31 - n);
        (i64::from(high >> n) << 32) | i64::from((low >> n) | carried)
    }
}

/// [`shr_i64_halves`], logical.
#[cfg(any(armv6m, test))]
#[inline(always)]
#[allow(
    clippy::cast_possible_truncation,
    reason = "the halves of a 64-bit integer"
)]
fn shr_u64_halves(x: u64, n: u32) -> u64 {
    let (high, low) = ((x >> 32) as u32, x as u32);
    if n >= 32 {
        u64::from(high >> (n - 32))
    } else {
        let carried = (high << 1) << (31 - n);
        (u64::from(high >> n) << 32) | u64::from((low >> n) | carried)
    }
}

/// x << n in 32-bit halves, as [`shr_u64_halves`] the other way.
#[cfg(any(armv6m, test))]
#[inline(always)]
#[allow(
    clippy::cast_possible_truncation,
    reason = "the halves of a 64-bit integer"
)]
fn shl_u64_halves(x: u64, n: u32) -> u64 {
    let (high, low) = ((x >> 32) as u32, x as u32);
    if n >= 32 {
        u64::from(low << (n - 32)) << 32
    } else {
        let carried = (low >> 1) >> (31 - n);
        (u64::from((high << n) | carried) << 32) | u64::from(low << n)
    }
}

/// (x + 2^(n−1)) >> n, x/2ⁿ rounded to nearest (ties up), for 1 ≤ n < 64, without the sum
/// that could overflow: ((x >> (n − 1)) + 1) >> 1 is the same number (with x = q·2^(n−1) + r,
/// r < 2^(n−1), both are ⌊(q + 1)/2⌋), for every x but the largest when n = 1.
#[inline(always)]
pub fn round_shr_i64(x: i64, n: u32) -> i64 {
    (shr_i64(x, n - 1) + 1) >> 1
}

/// [`round_shr_i64`] for an unsigned x.
#[inline(always)]
pub fn round_shr_u64(x: u64, n: u32) -> u64 {
    (shr_u64(x, n - 1) + 1) >> 1
}

/// The leading zeros of `x` (32 for 0). The M0 has no `clz`, and for `leading_zeros` its
/// compiler calls `__clzsi2`, a branching search; inline, the bits below the top one are set,
/// which leaves one of 32 values, and a multiplication by a de Bruijn constant names it (Leiserson,
/// Prokop and Randall, "Using de Bruijn sequences to index a 1 in a computer word", 1998).
#[inline(always)]
pub fn leading_zeros_u32(x: u32) -> u32 {
    #[cfg(armv6m)]
    {
        leading_zeros_de_bruijn(x)
    }
    #[cfg(not(armv6m))]
    {
        x.leading_zeros()
    }
}

/// The leading zeros of `x` (64 for 0), from its halves' ([`leading_zeros_u32`]).
#[inline(always)]
pub fn leading_zeros_u64(x: u64) -> u32 {
    let high = (x >> 32) as u32;
    if high == 0 {
        32 + leading_zeros_u32(x as u32)
    } else {
        leading_zeros_u32(high)
    }
}

/// [`leading_zeros_u32`] by a de Bruijn multiplication: with every bit below the top one set,
/// `x` is 2^(k+1) − 1 for the top bit k, and the top five bits of its product with 0x07C4ACDD
/// differ for each k.
#[cfg(any(armv6m, test))]
#[inline(always)]
fn leading_zeros_de_bruijn(x: u32) -> u32 {
    const TOP_BIT: [u8; 32] = [
        0, 9, 1, 10, 13, 21, 2, 29, 11, 14, 16, 18, 22, 25, 3, 30, 8, 12, 20, 28, 15, 17, 24, 7,
        19, 27, 23, 6, 26, 5, 4, 31,
    ];
    if x == 0 {
        return 32;
    }
    let mut v = x;
    v |= v >> 1;
    v |= v >> 2;
    v |= v >> 4;
    v |= v >> 8;
    v |= v >> 16;
    let index = (v.wrapping_mul(0x07C4_ACDD) >> 27) as usize;
    31 - u32::from(TOP_BIT.get(index).copied().unwrap_or(0))
}

/// ⌊n / d⌋ for d > 0, or `None` when it does not fit 32 bits: long division in 16-bit digits by
/// 32-bit divisions (Warren, Hacker's Delight, 2nd ed., §9-4, `divlu`).
#[inline]
pub fn div_u64_u32(n: u64, d: u32) -> Option<u32> {
    const DIGIT: u32 = 1 << 16;
    let (high, low) = ((n >> 32) as u32, n as u32);
    if d == 0 || high >= d {
        return None;
    }
    // Normalise: the divisor's top bit set, the dividend shifted alike (it still fits, as
    // high < d).
    let s = leading_zeros_u32(d);
    let d = d << s;
    let (d1, d0) = (d >> 16, d & 0xFFFF);
    let high = if s == 0 {
        high
    } else {
        (high << s) | (low >> (32 - s))
    };
    let low = low << s;
    let (n1, n0) = (low >> 16, low & 0xFFFF);
    #[cfg(armv6m)]
    let inverse = digit_inverse(d1);
    let div_rem = |upper: u32| {
        #[cfg(armv6m)]
        {
            div_rem_by_inverse(upper, d1, inverse)
        }
        #[cfg(not(armv6m))]
        {
            (upper / d1, upper % d1)
        }
    };
    // Each quotient digit, estimated from the top digits and corrected at most twice.
    let digit = |upper: u32, next: u32| {
        let (mut q, mut r) = div_rem(upper);
        while q >= DIGIT || mul_u32_wide(q, d0) > (u64::from(r) << 16) + u64::from(next) {
            q -= 1;
            r += d1;
            if r >= DIGIT {
                break;
            }
        }
        q
    };
    let q1 = digit(high, n1);
    let middle = high
        .wrapping_mul(DIGIT)
        .wrapping_add(n1)
        .wrapping_sub(q1.wrapping_mul(d));
    let q0 = digit(middle, n0);
    Some(q1 * DIGIT + q0)
}

/// The bits of a divisor digit (2¹⁵ ≤ d < 2¹⁶) below its top one that index
/// [`DIGIT_INVERSES`].
#[cfg(any(armv6m, test))]
const INVERSE_INDEX_BITS: u32 = 8;

/// The shift that leaves a digit's top bit and its [`INVERSE_INDEX_BITS`].
#[cfg(any(armv6m, test))]
const INVERSE_INDEX_SHIFT: u32 = 15 - INVERSE_INDEX_BITS;

/// ⌊2³¹/d⌋ from below for d in each of the 2⁸ intervals [(i + 2⁸)·2⁷, (i + 2⁸ + 1)·2⁷) of the
/// divisor digits 2¹⁵ ≤ d < 2¹⁶: 2³¹⁻⁷/(i + 2⁸ + 1), within 2⁻⁸ of 2³¹/d across the interval.
#[cfg(any(armv6m, test))]
#[allow(
    clippy::indexing_slicing,
    clippy::cast_possible_truncation,
    reason = "evaluated at compile time: i < 2⁸, and 2²⁴/(2⁸ + 1) < 2¹⁶"
)]
static DIGIT_INVERSES: [u16; 1 << INVERSE_INDEX_BITS] = {
    const FIRST: u32 = 1 << INVERSE_INDEX_BITS;
    let mut table = [0_u16; 1 << INVERSE_INDEX_BITS];
    let mut i = 0;
    while i < table.len() {
        table[i] = ((1 << (31 - INVERSE_INDEX_SHIFT)) / (i as u32 + FIRST + 1)) as u16;
        i += 1;
    }
    table
};

/// v ≤ 2³¹/d, at most 2 below it, for a divisor digit 2¹⁵ ≤ d < 2¹⁶: [`DIGIT_INVERSES`]'
/// estimate v₀ from below and one Newton step v₀ + v₀·e/2³¹, e = 2³¹ − d·v₀ < 2²⁴, which
/// stays below 1/d (the step's error is d·(1/d − v₀)² ≥ 0) and squares the error to 2⁻¹⁶.
/// e's low [`INVERSE_INDEX_BITS`] bits are dropped so that v₀·e fits 32 bits (costing under a
/// unit).
#[cfg(any(armv6m, test))]
#[inline(always)]
fn digit_inverse(d: u32) -> u32 {
    let index = usize::try_from((d >> INVERSE_INDEX_SHIFT).wrapping_sub(1 << INVERSE_INDEX_BITS))
        .unwrap_or(usize::MAX);
    let v = u32::from(DIGIT_INVERSES.get(index).copied().unwrap_or(0));
    let e = (1_u32 << 31).wrapping_sub(d.wrapping_mul(v));
    v + (v.wrapping_mul(e >> INVERSE_INDEX_BITS) >> (31 - INVERSE_INDEX_BITS))
}

/// ⌊u/d⌋ and u mod d for a divisor digit 2¹⁵ ≤ d < 2¹⁶ with its [`digit_inverse`] v: the
/// estimate u·v/2³¹ is at most 4 short (tested on every d), and steps up to the quotient.
#[cfg(any(armv6m, test))]
#[inline(always)]
#[allow(clippy::cast_possible_truncation, reason = "u·v/2³¹ ≤ u/d < 2¹⁷")]
fn div_rem_by_inverse(u: u32, d: u32, v: u32) -> (u32, u32) {
    let mut q = (mul_u32_wide(u, v) >> 31) as u32;
    let mut r = u.wrapping_sub(q.wrapping_mul(d));
    while r >= d {
        q += 1;
        r -= d;
    }
    (q, r)
}

/// a·2^`frac` / b truncated towards zero, for the 32-bit formats' division, or `None` when b is
/// zero or the quotient does not fit (as `fixed`'s `checked_div`).
#[inline]
pub fn div_i32_fixed(a: i32, b: i32, frac: u32) -> Option<i32> {
    let quotient = div_u64_u32(u64::from(a.unsigned_abs()) << frac, b.unsigned_abs())?;
    if (a < 0) == (b < 0) {
        i32::try_from(quotient).ok()
    } else {
        0_i32.checked_sub_unsigned(quotient)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fixed::traits::Fixed;

    /// Operands at every edge of the range and in between: 0, ±1, powers of two and their
    /// neighbours, the extremes, and a sweep by a large odd step.
    fn operands() -> Vec<u32> {
        let mut all = vec![0, 1, 2, 0xFFFF, 0x1_0000, 0x1_0001, u32::MAX, u32::MAX - 1];
        for k in 0..32 {
            let p = 1_u32 << k;
            all.extend([p, p - 1, p.wrapping_add(1), !p]);
        }
        all.extend((0..2_000_u32).map(|i| i.wrapping_mul(0x9E37_79B9)));
        all
    }

    /// Calls `check` with every pair of [`operands`].
    fn for_each_pair(mut check: impl FnMut(u32, u32)) {
        let all = operands();
        for &a in &all {
            for &b in &all {
                check(a, b);
            }
        }
    }

    #[test]
    fn long_division_is_the_exact_quotient() {
        for_each_pair(|a, d| {
            for shift in [0, 12, 16, 31, 32] {
                let n = u64::from(a) << shift;
                let exact = if d == 0 {
                    None
                } else {
                    u32::try_from(n / u64::from(d)).ok()
                };
                assert_eq!(div_u64_u32(n, d), exact, "{n} / {d}");
            }
        });
    }

    #[test]
    fn digits_divide_by_their_inverses() {
        let mut worst = 0;
        for d in 1_u32 << 15..1 << 16 {
            let v = digit_inverse(d);
            assert!(
                u64::from(v) * u64::from(d) <= 1 << 31,
                "{d}: {v} above 2³¹/d"
            );
            assert!((1 << 31) / d - v <= 2, "{d}: {v} more than 2 below 2³¹/d");
            let sweep = d.wrapping_mul(0x9E37_79B9);
            for u in [0, 1, d - 1, d, u32::MAX, u32::MAX - d, sweep, sweep / d * d] {
                assert_eq!(div_rem_by_inverse(u, d, v), (u / d, u % d), "{u} / {d}");
                let estimate = ((u64::from(u) * u64::from(v)) >> 31) as u32;
                worst = worst.max(u / d - estimate);
            }
        }
        assert!(worst <= 4, "the estimate is {worst} short");
    }

    /// [`div_i32_fixed`] against `fixed`'s `checked_div` in the 32-bit format `F`.
    fn division_is_fixeds<F: Fixed<Bits = i32>>(a: i32, b: i32) {
        let expected = F::from_bits(a).checked_div(F::from_bits(b)).map(F::to_bits);
        assert_eq!(
            div_i32_fixed(a, b, F::FRAC_NBITS),
            expected,
            "{a} / {b} with {} fraction bits",
            F::FRAC_NBITS
        );
    }

    #[test]
    fn fixed_division_is_the_formats_own() {
        use fixed::types::{I16F16, I20F12};
        for_each_pair(|a, b| {
            let (a, b) = (a as i32, b as i32);
            division_is_fixeds::<I16F16>(a, b);
            division_is_fixeds::<I20F12>(a, b);
        });
    }

    #[test]
    fn partial_products_are_the_exact_product() {
        for_each_pair(|a, b| {
            assert_eq!(
                mul_u32_partial(a, b),
                u64::from(a) * u64::from(b),
                "{a} × {b}"
            );
        });
    }

    #[test]
    fn shifts_are_the_machines() {
        for a in operands() {
            for b in [0, 1, a, !a, u32::MAX] {
                let x = u64::from(a) << 32 | u64::from(b);
                for n in 0..64 {
                    assert_eq!(shr_u64(x, n), x >> n, "{x} >> {n}");
                    assert_eq!(shr_u64_halves(x, n), x >> n, "{x} >> {n} in halves");
                    assert_eq!(shl_u64(x, n), x << n, "{x} << {n}");
                    assert_eq!(shl_u64_halves(x, n), x << n, "{x} << {n} in halves");
                    let signed = x as i64;
                    assert_eq!(shr_i64(signed, n), signed >> n, "{signed} >> {n}");
                    assert_eq!(shr_i64_halves(signed, n), signed >> n, "{signed} >> {n}");
                    // Rounded, for every x but the largest when n = 1.
                    let bias = 1_u128 << n >> 1;
                    if n > 1 || (n == 1 && signed < i64::MAX) {
                        let rounded = (i128::from(signed) + bias as i128) >> n;
                        assert_eq!(i128::from(round_shr_i64(signed, n)), rounded, "{signed}");
                    }
                    if n > 1 || (n == 1 && x < u64::MAX) {
                        let rounded = (u128::from(x) + bias) >> n;
                        assert_eq!(u128::from(round_shr_u64(x, n)), rounded, "{x}");
                    }
                }
            }
        }
    }

    #[test]
    fn leading_zeros_are_counted() {
        for a in operands() {
            assert_eq!(leading_zeros_u32(a), a.leading_zeros(), "{a}");
            assert_eq!(leading_zeros_de_bruijn(a), a.leading_zeros(), "{a}");
            for b in [0, 1, a, u32::MAX] {
                let x = u64::from(a) << 32 | u64::from(b);
                assert_eq!(leading_zeros_u64(x), x.leading_zeros(), "{x}");
                assert_eq!(
                    leading_zeros_u64(u64::from(a)),
                    u64::from(a).leading_zeros()
                );
            }
        }
    }

    #[test]
    fn squares_are_exact() {
        for a in operands() {
            let exact = u64::from(a) * u64::from(a);
            assert_eq!(square_u32_wide(a), exact, "{a}²");
            assert_eq!(square_u32_partial(a), exact, "{a}² by partial products");
            assert_eq!(square_u64_small(u64::from(a)), exact, "{a}²");
        }
    }

    #[test]
    fn narrow_products_are_exact() {
        let narrow: Vec<i16> = operands()
            .iter()
            .flat_map(|&b| [b as i16, (b >> 16) as i16])
            .collect();
        for &a in &operands() {
            for &b in &narrow {
                let exact = i64::from(a as i32) * i64::from(b);
                assert_eq!(mul_i32_i16_wide(a as i32, b), exact, "{a} × {b}");
                assert_eq!(mul_i32_i16_partial(a as i32, b), exact, "{a} × {b}");
            }
        }
    }

    /// The fraction bits the rounded products are tested with: every 32-bit format's, and the
    /// narrow 2.14's.
    const FRACS: [u32; 9] = [1, 8, 12, 14, 16, 18, 20, 24, 30];

    /// (x + 2^(f−1)) >> f mod 2³², from the exact x.
    #[allow(clippy::cast_possible_truncation, reason = "mod 2³² is the point")]
    fn rounded(x: i128, frac: u32) -> i32 {
        ((x + (1 << (frac - 1))) >> frac) as i32
    }

    #[test]
    fn rounded_products_are_the_exact_products_rounded_mod_2_32() {
        for_each_pair(|a, b| {
            let (a, b) = (a as i32, b as i32);
            for frac in FRACS {
                let expected = rounded(i128::from(a) * i128::from(b), frac);
                assert_eq!(mul_i32_rounded_wrapping(a, b, frac), expected, "{a} × {b}, {frac}");
                if frac <= MIDDLE_FRAC_MAX {
                    assert_eq!(mul_i32_middle(a, b, frac), expected, "{a} × {b} by its middle");
                }
                let k = b as i16;
                let expected = rounded(i128::from(a) * i128::from(k), frac);
                assert_eq!(mul_i32_i16_rounded_wrapping(a, k, frac), expected, "{a} × {k}");
                if frac <= MIDDLE_FRAC_MAX {
                    assert_eq!(mul_i32_i16_middle(a, k, frac), expected, "{a} × {k} by its middle");
                }
            }
        });
    }

    #[test]
    fn rounded_dot_products_round_once_mod_2_32() {
        for_each_pair(|a, b| {
            let (a, b) = (a as i32, b as i32);
            // Three products whose low partial products carry into each other as well as not.
            let left = [a, b, a ^ b];
            let right = [b, a, !a];
            let exact: i128 = left
                .iter()
                .zip(&right)
                .map(|(&x, &y)| i128::from(x) * i128::from(y))
                .sum();
            for frac in FRACS {
                let expected = rounded(exact, frac);
                assert_eq!(dot3_i32_rounded_wrapping(left, right, frac), expected, "{left:?}·{right:?}");
                if frac <= MIDDLE_FRAC_MAX {
                    assert_eq!(dot3_i32_middle(left, right, frac), expected, "{left:?}·{right:?} by middles");
                }
            }
        });
    }

    #[test]
    fn signed_products_are_exact() {
        for_each_pair(|a, b| {
            let (a, b) = (a as i32, b as i32);
            let exact = i64::from(a) * i64::from(b);
            assert_eq!(mul_i32_wide(a, b), exact, "{a} × {b}");
            // The M0's path, exercised here too.
            assert_eq!(
                mul_i32_partial(a, b),
                exact,
                "{a} × {b} by partial products"
            );
        });
    }
}
