//! The host's fixed-point formats: the firmware's, with every sum, difference, product and dot
//! product checked. One that leaves its format stops the computation where it happened (it
//! unwinds, carrying an [`Overflowed`]), so that no figure the harness prints can come from a
//! wrapped number; [`catch`] turns it back into an error. The bits are the firmware's wherever
//! nothing overflows.

use obscura::scalar::{Operation, Overflow};
use std::fmt;
use std::panic::{self, AssertUnwindSafe, Location};
use std::sync::Once;

/// The host's policy: an overflow stops the computation (see the module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Checked;

/// A sum or product that left its format, and where in the core's source it was formed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Overflowed {
    /// What overflowed.
    pub operation: Operation,
    /// The source line that formed it.
    pub at: &'static Location<'static>,
}

impl fmt::Display for Overflowed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} at {} overflowed", self.operation, self.at)
    }
}

impl std::error::Error for Overflowed {}

impl Overflow for Checked {
    #[cold]
    fn overflowed(operation: Operation, at: &'static Location<'static>) {
        quiet_overflows();
        panic::panic_any(Overflowed { operation, at });
    }
}

/// `fixed`'s type `F` with checked arithmetic (what [`obscura_scene::Format::run`] runs a fixed
/// format in, with [`Checked`]).
#[cfg(test)]
pub type CheckedFx<F> = obscura::scalar::Fx<F, Checked>;

/// Runs `work`, and returns the overflow that stopped it, if one did. Other panics go on.
pub fn catch<T>(work: impl FnOnce() -> T) -> Result<T, Overflowed> {
    match panic::catch_unwind(AssertUnwindSafe(work)) {
        Ok(value) => Ok(value),
        Err(payload) => match payload.downcast::<Overflowed>() {
            Ok(overflowed) => Err(*overflowed),
            Err(other) => panic::resume_unwind(other),
        },
    }
}

/// Runs `work`, and returns what stopped it if anything did: an overflow, or any other panic,
/// as its message.
pub fn catch_any<T>(work: impl FnOnce() -> T) -> Result<T, String> {
    quiet_overflows();
    match panic::catch_unwind(AssertUnwindSafe(work)) {
        Ok(value) => Ok(value),
        Err(payload) => Err(
            if let Some(overflowed) = payload.downcast_ref::<Overflowed>() {
                overflowed.to_string()
            } else if let Some(text) = payload.downcast_ref::<&str>() {
                (*text).to_owned()
            } else if let Some(text) = payload.downcast_ref::<String>() {
                text.clone()
            } else {
                "a panic without a message".to_owned()
            },
        ),
    }
}

/// Keeps the panic hook from printing an overflow as a crash: it is reported as an error by
/// whoever catches it (or by `main`).
fn quiet_overflows() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let default = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if info.payload().downcast_ref::<Overflowed>().is_none() {
                default(info);
            }
        }));
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use obscura::Scalar;

    type Checked16 = CheckedFx<fixed::types::I16F16>;

    #[test]
    fn an_overflow_stops_the_work_and_says_what_and_where() {
        let line = line!() + 1;
        let overflowed = catch(|| Checked16::MAX * Checked16::from_int(2)).unwrap_err();
        assert_eq!(overflowed.operation, Operation::Product);
        assert_eq!(overflowed.at.line(), line);
        assert!(overflowed.at.file().ends_with("checked.rs"));
        assert!(overflowed.to_string().starts_with("a product at "));
        assert_eq!(
            catch(|| Checked16::ONE + Checked16::ONE),
            Ok(Checked16::from_int(2))
        );
    }

    #[test]
    #[should_panic(expected = "not an overflow")]
    fn other_panics_go_on() {
        let _ = catch(|| panic!("not an overflow"));
    }
}
