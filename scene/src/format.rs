//! [`Format`]: the core's number formats, chosen at run time by name, each run in its type
//! ([`Format::run`]) with the fixed formats' overflow policy the caller's: the core's own
//! ([`Proven`]) where a firmware's build proves its scenes, a checked one in the harness.

use obscura::scalar::{Fx, Overflow, Proven};
use obscura::{Bits, Methods, Scalar};
use std::fmt;

/// Builds [`Format`] from the core's one list of formats ([`obscura::for_each_format!`]).
macro_rules! format_enum {
    (fixed { $($fixed:ident => $raw:ident,)* } float { $($float:ident => $ty:ty,)* }) => {
        /// A number format of the core, by its command-line name ([`obscura::scalar::Precision::NAME`]).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Format {
            $(
                #[doc = concat!("Signed fixed point, `", stringify!($raw), "`.")]
                $fixed,
            )*
            $(
                #[doc = concat!("`", stringify!($ty), "`.")]
                $float,
            )*
        }

        impl Format {
            /// Every format, from the smallest range to the largest: the 32-bit fixed formats
            /// from the most fraction bits to the fewest, the 64-bit fixed format, then the
            /// floats, f64 last.
            pub const ALL: &'static [Self] = &[$(Self::$fixed,)* $(Self::$float,)*];

            /// Runs `job` in this format, a fixed format with the overflow policy `O`.
            pub fn run<O: Overflow, J: FormatJob>(self, job: J) -> J::Output {
                match self {
                    $(Self::$fixed => job.run::<Fx<obscura::fixed::types::$raw, O>>(),)*
                    $(Self::$float => job.run::<$ty>(),)*
                }
            }

            /// The core's type for the format, as Rust source (what a firmware computes in).
            pub fn rust_type(self) -> &'static str {
                match self {
                    $(Self::$fixed => concat!("obscura::formats::", stringify!($fixed)),)*
                    $(Self::$float => concat!("obscura::formats::", stringify!($float)),)*
                }
            }
        }
    };
}
obscura::for_each_format!(format_enum);

/// Work that is generic over the number format: [`Format::run`] picks the instantiation.
pub trait FormatJob {
    /// What the work produces.
    type Output;
    /// Does the work in format `S`.
    fn run<S: Bits>(self) -> Self::Output;
}

impl Format {
    /// Every format a firmware can compute in (f64 stays on the host).
    pub const FIRMWARE: &'static [Self] = Self::ALL.split_last().expect("f64 is listed").1;

    /// The firmware's formats' names, comma-separated: what a message lists where another was
    /// given.
    #[must_use]
    pub fn firmware_names() -> String {
        let names: Vec<_> = Self::FIRMWARE.iter().map(|f| f.name()).collect();
        names.join(", ")
    }

    /// The format called `name` ([`obscura::scalar::Precision::NAME`]), if there is one.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|f| f.name() == name)
    }

    /// The name the core gives the format.
    pub fn name(self) -> &'static str {
        struct Name;
        impl FormatJob for Name {
            type Output = &'static str;
            fn run<S: Scalar>(self) -> &'static str {
                S::NAME
            }
        }
        self.run::<Proven, _>(Name)
    }

    /// Whether `methods` differ meaningfully from `base` in this format for a scene with or
    /// without triangles ([`obscura::Methods::matter`]).
    pub fn methods_matter(self, methods: &Methods, base: &Methods, has_triangles: bool) -> bool {
        struct Matter<'a>(&'a Methods, &'a Methods, bool);
        impl FormatJob for Matter<'_> {
            type Output = bool;
            fn run<S: Scalar>(self) -> bool {
                self.0.matter::<S>(self.1, self.2)
            }
        }
        self.run::<Proven, _>(Matter(methods, base, has_triangles))
    }

    /// The fixed format's integer and fraction bits (the sign among the integer's); `None` for
    /// a float.
    pub fn split(self) -> Option<(u32, u32)> {
        struct Split;
        impl FormatJob for Split {
            type Output = Option<(u32, u32)>;
            fn run<S: Scalar>(self) -> Option<(u32, u32)> {
                S::SPLIT
            }
        }
        self.run::<Proven, _>(Split)
    }

    /// The name of the format's narrow format ([`obscura::Scalar::Narrow`]): `i2f14` for the
    /// 32-bit formats of at most 16 fraction bits, `i2f30` for the finer ones and `i32f32`, a
    /// float's own name for a float.
    pub fn narrow(self) -> &'static str {
        struct Narrow;
        impl FormatJob for Narrow {
            type Output = &'static str;
            fn run<S: Scalar>(self) -> &'static str {
                <S::Narrow as obscura::scalar::Precision>::NAME
            }
        }
        self.run::<Proven, _>(Narrow)
    }

    /// Whether the format is fixed point (whose firmware frames must match the host's bit for
    /// bit, and which has fast approximate roots when it is 32 bits wide).
    pub fn is_fixed_point(self) -> bool {
        self.split().is_some()
    }

    /// Whether the format is fixed point on 32 bits: the formats that differ only in where
    /// their binary point sits, and so cost the same where their narrow formats are the same
    /// ([`Self::narrow`]).
    pub fn is_fixed_32(self) -> bool {
        self.split().is_some_and(|(int, frac)| int + frac == 32)
    }
}

#[cfg(feature = "clap")]
impl clap::ValueEnum for Format {
    fn value_variants<'a>() -> &'a [Self] {
        Self::ALL
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        Some(clap::builder::PossibleValue::new(self.name()))
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_formats_are_the_cores_in_its_order_f64_last() {
        let names: Vec<&str> = Format::ALL.iter().map(|f| f.name()).collect();
        let core: Vec<&str> = obscura::scalar::FORMATS.iter().map(|f| f.name).collect();
        assert_eq!(names, core);
        assert_eq!(Format::ALL.last(), Some(&Format::F64));
        assert!(!Format::FIRMWARE.contains(&Format::F64));
        assert_eq!(Format::from_name("i20f12"), Some(Format::I20f12));
        assert_eq!(Format::from_name("i17f15"), None);
        assert_eq!(Format::I20f12.split(), Some((20, 12)));
        assert!(Format::I20f12.is_fixed_32() && !Format::I32f32.is_fixed_32());
        assert_eq!(Format::F32Approx.split(), None);
    }
}
