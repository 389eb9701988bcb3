//! The obscura firmware's render loop, shared by every display it drives: the frames the build
//! configured (each scene in each format, by the chosen methods; see `build.rs`), drawn at
//! 240×240 RGB565 scanline by scanline through one line buffer into an embedded-graphics
//! display, each reported with the SysTick ticks it took and the stack it used.
//!
//! Its binary `qemu` streams the frames to the host over semihosting; the boards' crates
//! (`boards/`) draw them on a real display ([`screen::Screen`]), those with two cores tracing
//! on both ([`two_cores`]), the Pico boards feeding it by DMA ([`dma_display`]).
#![no_std]

pub mod clock;
pub mod dma_display;
pub mod frames;
pub mod screen;
pub mod stack;
pub mod two_cores;

/// The side of the square display, in pixels: the build's (`obscura_scene::firmware::SIDE`).
pub use frames::SIDE;
