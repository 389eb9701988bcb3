//! The exact products the fixed formats are built from, at the machine's speed and with the
//! same bits on every machine. A 32-bit format's product is 32×32→64 bits: one instruction on a
//! Cortex-M4F (`smull`) or a PC, but the Cortex-M0 has no such multiply, and for `i64::from(a) *
//! i64::from(b)` its compiler calls `__aeabi_lmul`, a full 64×64 product. There it is made from
//! four 16×16→32 partial products (`muls` each), which is the exact product again.

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
        // |a|·|b| ≤ 2⁶² fits i64, and so does its negation.
        let magnitude = mul_u32_partial(a.unsigned_abs(), b.unsigned_abs()) as i64;
        if (a < 0) == (b < 0) {
            magnitude
        } else {
            -magnitude
        }
    }
    #[cfg(not(armv6m))]
    {
        i64::from(a) * i64::from(b)
    }
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

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn partial_products_are_the_exact_product() {
        let all = operands();
        for &a in &all {
            for &b in &all {
                assert_eq!(
                    mul_u32_partial(a, b),
                    u64::from(a) * u64::from(b),
                    "{a} × {b}"
                );
            }
        }
    }

    #[test]
    fn signed_products_are_exact() {
        let all = operands();
        for &a in &all {
            for &b in &all {
                let (a, b) = (a as i32, b as i32);
                assert_eq!(mul_i32_wide(a, b), i64::from(a) * i64::from(b), "{a} × {b}");
                // The M0's path, exercised here too.
                let magnitude = mul_u32_partial(a.unsigned_abs(), b.unsigned_abs()) as i64;
                let signed = if (a < 0) == (b < 0) {
                    magnitude
                } else {
                    -magnitude
                };
                assert_eq!(signed, i64::from(a) * i64::from(b), "{a} × {b}");
            }
        }
    }
}
