//! [`Bits`]: the core's formats, whose numbers are exactly their bits: how a number leaves the
//! core and comes back unchanged, as a proven scene does on its way from a firmware's build to
//! the chip ([`crate::words`]).

crate::phase::declare_phase!(Some(crate::phase::Phase::Arithmetic));

use super::fixed_point::{Fx, Narrowed, Overflow, WideBits};
use super::{F32Approx, Scalar};

/// A format of the core's own, with its narrow format ([`Scalar::Narrow`]), whose numbers are
/// their bits. Sealed: the harness's instrumented formats wrap these and have
/// no bits of their own.
pub trait Bits: NumberBits<Narrow: NumberBits> {}

impl<S: NumberBits<Narrow: NumberBits>> Bits for S {}

/// A number that is its bits: written as [`NumberBits::to_bits`] and read back by
/// [`NumberBits::from_bits`], it is the same number. The core's formats and their narrow ones.
pub trait NumberBits: Scalar + sealed::Sealed {
    /// The 32-bit words a number takes: 1, or 2 for a 64-bit format.
    const WORDS: usize;
    /// The number's bits, in the low 32 × [`Self::WORDS`] bits.
    fn to_bits(self) -> u64;
    /// The number whose bits are the low 32 × [`Self::WORDS`] bits of `bits`.
    fn from_bits(bits: u64) -> Self;
}

mod sealed {
    pub trait Sealed {}
}

impl<F, O> super::Sealed for Fx<F, O> {}
impl super::Sealed for f32 {}
impl super::Sealed for f64 {}
impl super::Sealed for F32Approx {}

impl<F, O> sealed::Sealed for Fx<F, O> {}
impl sealed::Sealed for f32 {}
impl sealed::Sealed for f64 {}
impl sealed::Sealed for F32Approx {}

impl<F, O> NumberBits for Fx<F, O>
where
    F: Narrowed,
    O: Overflow,
{
    const WORDS: usize = <F::Bits as WideBits>::WORDS;

    fn to_bits(self) -> u64 {
        self.get().to_bits().to_u64()
    }

    fn from_bits(bits: u64) -> Self {
        Self::new(F::from_bits(F::Bits::from_u64(bits)))
    }
}

impl NumberBits for f32 {
    const WORDS: usize = 1;

    fn to_bits(self) -> u64 {
        u64::from(Self::to_bits(self))
    }

    #[allow(
        clippy::cast_possible_truncation,
        reason = "the low word is the number"
    )]
    fn from_bits(bits: u64) -> Self {
        Self::from_bits(bits as u32)
    }
}

impl NumberBits for f64 {
    const WORDS: usize = 2;

    fn to_bits(self) -> u64 {
        Self::to_bits(self)
    }

    fn from_bits(bits: u64) -> Self {
        Self::from_bits(bits)
    }
}

impl NumberBits for F32Approx {
    const WORDS: usize = 1;

    fn to_bits(self) -> u64 {
        NumberBits::to_bits(self.0)
    }

    fn from_bits(bits: u64) -> Self {
        Self(NumberBits::from_bits(bits))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::{F32, F32Approx, I8f24, I16f16, I24f8, I32f32};

    fn round_trip<S: Bits>(values: &[f64]) {
        for &x in values {
            let Some(number) = S::from_f64(x) else {
                continue;
            };
            let bits = number.to_bits();
            assert!(S::WORDS == 2 || bits >> 32 == 0 || bits >> 31 == u64::MAX >> 31);
            assert_eq!(S::from_bits(bits), number, "{} {x}", S::NAME);
            assert_eq!(
                S::from_bits(bits & (u64::MAX >> (64 - 32 * S::WORDS))),
                number
            );
        }
    }

    #[test]
    fn every_number_reads_back_from_its_bits() {
        let values = [
            0.0, -0.0, 1.0, -1.0, 0.1, -3.75, 100.5, -127.9, 1e-7, 3e4, -3e9, 1e30,
        ];
        round_trip::<I8f24>(&values);
        round_trip::<I16f16>(&values);
        round_trip::<I24f8>(&values);
        round_trip::<I32f32>(&values);
        round_trip::<F32>(&values);
        round_trip::<F32Approx>(&values);
        round_trip::<f64>(&values);
    }
}
