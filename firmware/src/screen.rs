//! A real display as the firmware's back-end: each frame drawn on it in turn, and each report
//! written across its bottom rows of text (the frame's time from SysTick, which counts real
//! core cycles on a board; its stack; its scene's storage; the display's SPI clock where the
//! board's HAL says it; what the board notes of itself), or why a frame could not be drawn.

use crate::frames::{Backend, Job, Report};
use core::fmt;
use embedded_graphics::mono_font::{MonoTextStyleBuilder, ascii::FONT_6X10};
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};

/// A display, and the core clock that times its frames.
#[derive(Debug)]
pub struct Screen<D> {
    /// The display.
    pub display: D,
    /// The core clock in MHz: SysTick ticks per microsecond.
    pub core_mhz: u32,
    /// The display's SPI clock in kHz, as the board's HAL set it (`None` where the HAL does
    /// not say).
    pub spi_khz: Option<u32>,
    /// What the board says of itself under each report (`None`: nothing), such as that it
    /// traces on one core where it has two.
    pub note: Option<&'static str>,
}

impl<D: DrawTarget<Color = Rgb565, Error: fmt::Debug>> Backend for Screen<D> {
    type Display = D;

    fn begin(&mut self, _: &Job<'_>) {}

    fn display(&mut self) -> &mut D {
        &mut self.display
    }

    fn report(&mut self, r: &Report<'_>) {
        let ms = r.ticks / (u64::from(self.core_mhz) * 1000);
        let (scene, format) = (r.job.name(), r.job.format);
        let (stack, storage, fixed) = (r.stack_bytes, r.storage_bytes, r.fixed_storage_bytes);
        let white = Rgb565::WHITE;
        self.caption(1, format_args!("{scene} {format}: {ms} ms"), white);
        self.caption(
            0,
            format_args!("stack {stack} B, scene {storage} B ({fixed})"),
            white,
        );
        if let Some(khz) = self.spi_khz {
            self.caption(2, format_args!("display SPI at {khz} kHz"), white);
        }
        if let Some(note) = self.note {
            self.caption(3, format_args!("{note}"), white);
        }
    }

    fn failed(&mut self, job: &Job<'_>, why: &dyn fmt::Display) {
        self.caption(
            1,
            format_args!("{} {}:", job.name(), job.format),
            Rgb565::RED,
        );
        self.caption(0, format_args!("{why}"), Rgb565::RED);
    }

    fn refused(&mut self, job: &Job<'_>, why: &dyn fmt::Display) {
        self.failed(job, why);
    }
}

impl<D: DrawTarget<Color = Rgb565>> Screen<D> {
    /// Writes one line of text across the display, `line_from_bottom` lines up from the bottom.
    pub fn caption(&mut self, line_from_bottom: i32, text: fmt::Arguments<'_>, colour: Rgb565) {
        let mut line = heapless::String::<64>::new();
        // A longer line is cut: the display shows 40 characters anyway.
        let _ = fmt::write(&mut line, text);
        let style = MonoTextStyleBuilder::new()
            .font(&FONT_6X10)
            .text_color(colour)
            .background_color(Rgb565::BLACK)
            .build();
        let bottom = i32::try_from(crate::SIDE).unwrap_or(240) - 1 - 10 * line_from_bottom;
        let bottom_left = Point::new(2, bottom);
        let _ = Text::with_baseline(&line, bottom_left, style, Baseline::Bottom)
            .draw(&mut self.display);
    }
}
