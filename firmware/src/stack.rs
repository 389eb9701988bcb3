//! The stack's high-water mark: paint the free stack with a pattern before a frame, and after
//! it find the lowest word the frame overwrote.
#![allow(
    unsafe_code,
    reason = "reads and writes the free stack below the stack pointer"
)]

use core::ptr::{addr_of, read_volatile, write_volatile};

/// What free stack words hold until something overwrites them.
const PATTERN: u32 = 0xC0DE_CAFE;
/// Words just below the stack pointer left alone, for `paint`'s own calls.
const MARGIN_WORDS: usize = 32;

unsafe extern "C" {
    /// The top of the stack (the end of RAM), from cortex-m-rt's linker script.
    static _stack_start: u32;
    /// The lowest address the stack may grow to (the end of the statics).
    static _stack_end: u32;
}

/// The lowest and the highest address of the stack (only the symbols' addresses are taken).
fn bounds() -> (usize, usize) {
    (
        addr_of!(_stack_end) as usize,
        addr_of!(_stack_start) as usize,
    )
}

/// The stack pointer.
#[cfg(target_arch = "arm")]
fn stack_pointer() -> usize {
    cortex_m::register::msp::read() as usize
}

/// The stack pointer.
#[cfg(target_arch = "riscv32")]
fn stack_pointer() -> usize {
    let sp: usize;
    // SAFETY: reads the stack pointer into a register, nothing else.
    unsafe { core::arch::asm!("mv {}, sp", out(reg) sp) };
    sp
}

/// Paints the free stack, from its lowest address to just below the current stack pointer.
pub fn paint() {
    let (bottom, _) = bounds();
    let sp = stack_pointer();
    let mut word = bottom;
    while word + 4 * MARGIN_WORDS < sp {
        // SAFETY: `word` lies between the end of the statics and the stack pointer, memory that
        // nothing uses now; it is 4-aligned because `_stack_end` is.
        unsafe { write_volatile(word as *mut u32, PATTERN) };
        word += 4;
    }
}

/// The most stack used since `paint`, in bytes: from the top of the stack down to the lowest
/// word no longer holding the pattern.
pub fn high_water() -> u32 {
    let (bottom, top) = bounds();
    let mut word = bottom;
    // SAFETY: reads 4-aligned words of RAM between the statics and the top of the stack.
    while word < top && unsafe { read_volatile(word as *const u32) } == PATTERN {
        word += 4;
    }
    u32::try_from(top - word).unwrap_or(u32::MAX)
}
