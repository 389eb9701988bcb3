//! The formats the tracer is built for, listed once: [`for_each_format!`](crate::for_each_format)
//! hands the list to a macro, from which the core builds [`FORMATS`](crate::scalar::FORMATS) and the
//! [`formats`](crate::formats) type names, and the desktop harness its command-line formats.

crate::phase::declare_phase!(Some(crate::phase::Phase::Build));

/// Calls `$then!` with every format the tracer is built for, from the smallest range to the
/// largest: the 32-bit fixed formats as `Variant => RawType` (a type of `fixed::types`), then
/// the 64-bit one, then the floats as `Variant => Type`. The 32-bit formats are the even
/// splits from i8f24 to i24f8.
///
/// ```
/// macro_rules! count {
///     (fixed { $($f:ident => $raw:ident,)* } float { $($v:ident => $t:ty,)* }) => {
///         [$(stringify!($f),)* $(stringify!($v),)*].len()
///     };
/// }
/// assert_eq!(obscura::for_each_format!(count), obscura::scalar::FORMATS.len());
/// ```
#[macro_export]
#[doc(hidden)]
macro_rules! for_each_format {
    ($then:ident) => {
        $then! {
            fixed {
                I8f24 => I8F24,
                I10f22 => I10F22,
                I12f20 => I12F20,
                I14f18 => I14F18,
                I16f16 => I16F16,
                I18f14 => I18F14,
                I20f12 => I20F12,
                I22f10 => I22F10,
                I24f8 => I24F8,
                I32f32 => I32F32,
            }
            float {
                F32Approx => $crate::F32Approx,
                F32 => f32,
                F64 => f64,
            }
        }
    };
}
