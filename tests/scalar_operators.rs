//! The fixed formats' operators do what `Scalar`'s documentation says, over a sweep of operands
//! of every magnitude and the edges of the range: `+` and `−` exact while the result fits,
//! `×` the exact product rounded to nearest (half up), `/` truncated towards zero, each
//! saturating or wrapping beyond the range exactly as documented, conversions to and from
//! Q16.16 rounded down and saturated, and the overflow policy hearing of every wrap and of
//! nothing else.

use obscura::Scalar;
use obscura::scalar::{Fx, Operation, Overflow};
use std::cell::Cell;
use std::panic::Location;

/// A policy that remembers the last overflow it heard of.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
struct Heard;

thread_local! {
    static LAST: Cell<Option<Operation>> = const { Cell::new(None) };
}

impl Overflow for Heard {
    fn overflowed(operation: Operation, _at: &'static Location<'static>) {
        LAST.set(Some(operation));
    }
}

/// What the policy heard since the last call.
fn heard() -> Option<Operation> {
    LAST.take()
}

/// A pseudorandom sweep: raw values of every magnitude, with the range's edges among them.
fn operands(bits: u32, count: usize) -> Vec<i128> {
    let (min, max) = (-(1_i128 << (bits - 1)), (1_i128 << (bits - 1)) - 1);
    let mut state = 0x2545_F491_4F6C_DD1D_u64;
    let mut values = vec![min, min + 1, -1, 0, 1, max - 1, max];
    while values.len() < count {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let magnitude = (state >> 58) as u32 % bits; // 0 to bits − 1
        let raw = i128::from(state as i64) >> (64 - magnitude.max(1));
        values.push(raw.clamp(min, max));
    }
    values
}

macro_rules! sweep {
    ($name:ident, $fixed:ty, $bits:ty) => {
        #[test]
        fn $name() {
            type F = Fx<$fixed, Heard>;
            let bits = <$bits>::BITS;
            let frac = <$fixed>::FRAC_NBITS;
            let (min, max) = (i128::from(<$bits>::MIN), i128::from(<$bits>::MAX));
            let fits = |x: i128| (min..=max).contains(&x);
            let make = |raw: i128| F::new(<$fixed>::from_bits(raw as $bits));
            let raw = |x: F| i128::from(x.get().to_bits());
            let wrap = |x: i128| i128::from(x as $bits);
            let values = operands(bits, 300);
            for &a in &values {
                for &b in &values {
                    let (x, y) = (make(a), make(b));
                    let sum = a + b;
                    assert_eq!(raw(x + y), wrap(sum), "{a} + {b}");
                    assert_eq!(heard(), (!fits(sum)).then_some(Operation::Sum), "{a} + {b}");
                    let difference = a - b;
                    assert_eq!(raw(x - y), wrap(difference), "{a} − {b}");
                    assert_eq!(
                        heard(),
                        (!fits(difference)).then_some(Operation::Difference),
                        "{a} − {b}"
                    );
                    // The exact product a·b / 2^frac, rounded half up.
                    let product = (a * b + (1 << (frac - 1))) >> frac;
                    let got = raw(x * y);
                    if fits(product) {
                        assert_eq!(got, product, "{a} × {b}");
                        assert_eq!(heard(), None, "{a} × {b}");
                    } else {
                        assert_eq!(heard(), Some(Operation::Product), "{a} × {b}");
                    }
                    // The exact quotient, truncated towards zero; saturated beyond the range
                    // and for a zero divisor (zero for 0 / 0).
                    let quotient = raw(x / y);
                    let expected = if b == 0 {
                        match a.signum() {
                            1 => max,
                            -1 => min,
                            _ => 0,
                        }
                    } else {
                        ((a << frac) / b).clamp(min, max)
                    };
                    assert_eq!(quotient, expected, "{a} / {b}");
                    assert_eq!(heard(), None, "{a} / {b}");
                }
                assert_eq!(raw(-make(a)), (-a).clamp(min, max), "−{a}");
                assert_eq!(heard(), None, "−{a}");
                // Q16.16 out: a·2^(16 − frac) rounded down, saturated to i32.
                let q16 = if frac >= 16 {
                    a >> (frac - 16)
                } else {
                    a << (16 - frac)
                };
                let (q_min, q_max) = (i128::from(i32::MIN), i128::from(i32::MAX));
                assert_eq!(
                    i128::from(make(a).to_q16()),
                    q16.clamp(q_min, q_max),
                    "{a} in Q16"
                );
                assert_eq!(heard(), None, "{a} in Q16");
            }
            // Q16.16 in: q·2^(frac − 16) rounded down, saturated to the format.
            for q in operands(32, 300) {
                let exact = if frac >= 16 {
                    q << (frac - 16)
                } else {
                    q >> (16 - frac)
                };
                assert_eq!(
                    raw(F::from_q16(q as i32)),
                    exact.clamp(min, max),
                    "{q} from Q16"
                );
                assert_eq!(heard(), None, "{q} from Q16");
            }
        }
    };
}

sweep!(i16f16_operators_keep_their_word, fixed::types::I16F16, i32);
sweep!(i20f12_operators_keep_their_word, fixed::types::I20F12, i32);
sweep!(i32f32_operators_keep_their_word, fixed::types::I32F32, i64);
