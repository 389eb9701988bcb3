//! The number formats the harness can run the core in, chosen at run time. The fixed formats
//! are the firmware's with checked arithmetic ([`crate::checked`]).

use crate::checked::CheckedFx;
use clap::ValueEnum;
use obscura::{Methods, Scalar};
use std::fmt;

/// A number format of the core, by its command-line name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, ValueEnum)]
pub enum Format {
    /// Signed 16.16 fixed point (32-bit): the firmware's default.
    I16f16,
    /// Signed 20.12 fixed point (32-bit): four more integer bits, four fewer fraction bits.
    I20f12,
    /// Signed 32.32 fixed point (64-bit).
    I32f32,
    /// IEEE single precision with micromath's approximate roots and reciprocals.
    #[value(name = "f32-approx")]
    F32Approx,
    /// IEEE single precision.
    F32,
    /// IEEE double precision: the reference.
    F64,
}

/// Work that is generic over the number format: `Format::run` picks the instantiation.
pub trait FormatJob {
    /// What the work produces.
    type Output;
    /// Does the work in format `S`.
    fn run<S: Scalar>(self) -> Self::Output;
}

impl Format {
    /// Runs `job` in this format.
    pub fn run<J: FormatJob>(self, job: J) -> J::Output {
        match self {
            Self::I16f16 => job.run::<CheckedFx<fixed::types::I16F16>>(),
            Self::I20f12 => job.run::<CheckedFx<fixed::types::I20F12>>(),
            Self::I32f32 => job.run::<CheckedFx<fixed::types::I32F32>>(),
            Self::F32Approx => job.run::<obscura::F32Approx>(),
            Self::F32 => job.run::<f32>(),
            Self::F64 => job.run::<f64>(),
        }
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
        self.run(Name)
    }
}

impl Format {
    /// Every format, smallest first.
    pub const ALL: [Self; 6] = [
        Self::I16f16,
        Self::I20f12,
        Self::I32f32,
        Self::F32Approx,
        Self::F32,
        Self::F64,
    ];

    /// Every format a firmware can compute in, smallest first (f64 stays on the host).
    pub const FIRMWARE: [Self; 5] = [
        Self::I16f16,
        Self::I20f12,
        Self::I32f32,
        Self::F32Approx,
        Self::F32,
    ];

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
        self.run(Matter(methods, base, has_triangles))
    }

    /// The core's type for the format, as Rust source (what a firmware computes in).
    pub fn rust_type(self) -> &'static str {
        match self {
            Self::I16f16 => "obscura::I16F16",
            Self::I20f12 => "obscura::I20F12",
            Self::I32f32 => "obscura::I32F32",
            Self::F32Approx => "obscura::F32Approx",
            Self::F32 => "f32",
            Self::F64 => "f64",
        }
    }

    /// Whether the format is fixed point (whose firmware frames must match the host's bit for
    /// bit, and which has fast approximate roots when it is 32 bits wide).
    pub fn is_fixed_point(self) -> bool {
        matches!(self, Self::I16f16 | Self::I20f12 | Self::I32f32)
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
    fn command_line_names_are_the_core_names() {
        for format in Format::value_variants() {
            let cli = format.to_possible_value().unwrap();
            assert_eq!(cli.get_name(), format.name());
        }
    }
}
