//! The obscura firmware: renders the built-in scenes chosen at build time, in the number
//! formats chosen at build time, at 240×240 RGB565, scanline by scanline through one line
//! buffer into an embedded-graphics display, and reports for each frame how many SysTick ticks
//! it took and how much stack it used.
//!
//! Features choose everything: one back-end, `qemu` (frames streamed to host files over
//! semihosting) or `st7789` (an SPI display on an STM32F411 "Black Pill"); one or more scenes,
//! `scene-whitted`, `scene-shapes`; one or more formats, `format-i16f16`, `format-i20f12`,
//! `format-i32f32`, `format-f32-approx`, `format-f32`; the methods (`sphere-stable`,
//! `triangle-moller-trumbore` or `triangle-watertight`, `sqrt-approx`, `rays-stepped`,
//! `bias-exclude`; the lecture's by default); and `chart` to draw every variant that changes
//! one method as well. For example, on QEMU's Cortex-M4F:
//!
//! ```sh
//! cargo run --release --bin firmware --target thumbv7em-none-eabihf \
//!     --features qemu,scene-whitted,format-i16f16
//! ```
#![no_std]
#![no_main]

#[cfg(all(feature = "qemu", feature = "st7789"))]
compile_error!("choose one display back-end: the `qemu` feature or the `st7789` feature");
#[cfg(not(any(feature = "qemu", feature = "st7789")))]
compile_error!("choose a display back-end: add the `qemu` or the `st7789` feature");
#[cfg(not(any(feature = "scene-whitted", feature = "scene-shapes")))]
compile_error!("choose a scene: add `scene-whitted` and/or `scene-shapes` to the features");
#[cfg(not(any(
    feature = "format-i16f16",
    feature = "format-i20f12",
    feature = "format-i32f32",
    feature = "format-f32-approx",
    feature = "format-f32"
)))]
compile_error!(
    "choose a format: add one or more of `format-i16f16`, `format-i20f12`, `format-i32f32`, \
     `format-f32-approx` and `format-f32`"
);

mod clock;
mod frames;
#[cfg(feature = "qemu")]
mod qemu;
#[cfg(feature = "st7789")]
mod st7789;
mod stack;

/// The side of the square display, in pixels.
const SIDE: u32 = 240;

#[cortex_m_rt::entry]
fn main() -> ! {
    #[cfg(feature = "qemu")]
    qemu::run();
    #[cfg(feature = "st7789")]
    st7789::run();
}
