//! Two cores tracing one frame, for the boards with two (the Pico's RP2040, the Pico 2's
//! RP2350): of each pair of rows in the frame's order, core 1 traces the second into its own
//! line buffer while core 0 traces the first into its own and sends it; core 0 then sends core
//! 1's. The cores meet through a pair of mailboxes ([`Mailbox`]: the SIO's FIFOs on both
//! chips): core 0 hands core 1 the frame's row tracer, then each row to trace, and core 1
//! answers when the row is in its line.
//!
//! A board asks whether core 1 answers ([`core1_answers`]), starts it in [`core1_traces_rows`]
//! and gives its display and its side of the mailboxes to [`TwoCores`], the back-end that
//! shares each frame; where core 1 does not answer, core 0 traces every row.
#![allow(
    unsafe_code,
    reason = "the line and the row tracer the two cores share through the mailboxes"
)]

use crate::SIDE;
use crate::frames::{Backend, CORNER_ROWS, FrameError, Job, Report};
use crate::screen::Screen;
use core::cell::UnsafeCell;
use core::convert::Infallible;
use core::fmt;
use core::sync::atomic::{Ordering, fence};
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use obscura::mesh::MeshWords;
use obscura::{Bits, Camera, Corner, Parts, Presentation, RenderError, RowTracer, Scene, send_row};

/// One core's side of the pair of mailboxes between the cores: words to the other core, and
/// words from it, each call waiting until it can.
pub trait Mailbox {
    /// Sends `word` to the other core.
    fn send(&mut self, word: u32);
    /// The next word from the other core.
    fn receive(&mut self) -> u32;
}

/// Core 0's side of the SIO's mailboxes as it asks whether core 1 is there, each call returning
/// at once.
pub trait Probe {
    /// Empties the mailbox from core 1.
    fn drain(&mut self);
    /// Wakes core 1 from its wait for an event.
    fn wake(&mut self);
    /// Sends `word` to core 1 if there is room.
    fn try_send(&mut self, word: u32) -> bool;
    /// The next word from core 1, if one is there.
    fn try_receive(&mut self) -> Option<u32>;
}

/// How long core 0 waits for core 1's first answer before tracing alone, in milliseconds.
pub const CORE1_ANSWER_MS: u64 = 100;

/// Whether core 1, just reset and waiting in the boot ROM, answers the first word of the ROM's
/// start sequence (a 0, which it echoes; the RP2040 datasheet, section 2.8.2, and the RP2350's,
/// 5.3) while `waiting` says to wait. Starting a core 1 that does not answer (faulted, or
/// missing from an emulator) would wait for its answer for good: the board traces on core 0.
pub fn core1_answers(mailbox: &mut impl Probe, mut waiting: impl FnMut() -> bool) -> bool {
    mailbox.drain();
    mailbox.wake();
    while !mailbox.try_send(0) {
        if !waiting() {
            return false;
        }
    }
    loop {
        if let Some(echo) = mailbox.try_receive() {
            return echo == 0;
        }
        if !waiting() {
            return false;
        }
    }
}

/// Core 1's line buffer: written by core 1 between a row's word and its answer, read by core 0
/// after the answer; never by both at once.
struct Line(UnsafeCell<[Rgb565; SIDE as usize]>);

// SAFETY: the mailboxes order every access (see `Line`).
unsafe impl Sync for Line {}

static CORE1_LINE: Line = Line(UnsafeCell::new([Rgb565::BLACK; SIDE as usize]));

/// Core 1's corner rows for adaptive anti-aliasing: core 1's alone.
struct Corners(UnsafeCell<CornerRows>);

// SAFETY: only core 1 touches them.
unsafe impl Sync for Corners {}

static CORE1_CORNERS: Corners = Corners(UnsafeCell::new([Corner::ZERO; CORNER_ROWS]));

/// A core's corner rows for adaptive anti-aliasing: an empty array, and no adaptive code in the
/// build, unless a scene takes adaptive samples.
type CornerRows = [Corner; CORNER_ROWS];

/// The word that ends a frame for core 1.
const END_OF_FRAME: u32 = u32::MAX;

/// Traces row `y` of the frame into a line: what core 0 hands core 1 for a frame.
type Trace<'a> =
    dyn Fn(u32, &mut [Rgb565], &mut CornerRows) -> Result<(), RenderError<Infallible>> + Sync + 'a;

/// Core 1, for good: for each frame, takes the row tracer core 0 hands it through `mailbox`,
/// then traces each row it is given into its line and answers (1 traced, 0 not), until the end
/// of the frame.
pub fn core1_traces_rows(mailbox: &mut impl Mailbox) -> ! {
    loop {
        let address = mailbox.receive() as usize;
        // SAFETY: core 0 sent the address of a `&Trace` that lives until it has our answer to
        // the end of the frame.
        let trace: &&Trace<'_> = unsafe { &*(address as *const &Trace<'_>) };
        loop {
            let y = mailbox.receive();
            if y == END_OF_FRAME {
                break;
            }
            // SAFETY: core 0 reads the line only after our answer (see `Line`).
            let line = unsafe { &mut *CORE1_LINE.0.get() };
            // SAFETY: only core 1 uses its corner rows.
            let corners = unsafe { &mut *CORE1_CORNERS.0.get() };
            let traced = trace(y, line, corners).is_ok();
            fence(Ordering::Release);
            mailbox.send(u32::from(traced));
        }
        mailbox.send(END_OF_FRAME);
    }
}

/// A display driven by two cores: core 0's back-end, with its side of the mailboxes to core 1
/// (which runs [`core1_traces_rows`]).
#[derive(Debug)]
pub struct TwoCores<D, M> {
    /// The display, and the clock that times its frames.
    pub screen: Screen<D>,
    /// Core 0's side of the mailboxes.
    pub mailbox: M,
}

impl<D: DrawTarget<Color = Rgb565, Error: fmt::Debug>, M: Mailbox> Backend for TwoCores<D, M> {
    type Display = D;

    fn begin(&mut self, job: &Job<'_>) {
        self.screen.begin(job);
    }

    fn display(&mut self) -> &mut D {
        &mut self.screen.display
    }

    /// Shares the rows with core 1: of each pair in the frame's order, core 1 traces the second
    /// while this core traces and sends the first; then this core sends core 1's.
    fn draw_frame<
        S: Bits,
        const OBJECTS: usize,
        const LIGHTS: usize,
        const RAYS: usize,
        P: Parts,
    >(
        &mut self,
        scene: &Scene<S, OBJECTS, LIGHTS, RAYS, P, MeshWords<S>>,
        camera: &Camera<S>,
        presentation: Presentation,
    ) -> Result<(), FrameError<Self>> {
        let dither = presentation.dither;
        let trace = |y: u32, line: &mut [Rgb565], corners: &mut CornerRows| {
            // Each row on its own: the cores' rows do not follow one another.
            RowTracer::new(scene, camera, dither, line, corners)?
                .trace(y)
                .map(drop)
        };
        let shared: &Trace<'_> = &trace;
        // Core 1 holds this address until it answers the end of the frame, below.
        self.mailbox.send(&raw const shared as usize as u32);
        let mut line = [Rgb565::BLACK; SIDE as usize];
        let mut corners = [Corner::ZERO; CORNER_ROWS];
        let mut order = presentation.order.rows(SIDE);
        let mut drawn = Ok(());
        while let Some((first, first_rows)) = order.next() {
            let second = order.next();
            if let Some((y, _)) = second {
                self.mailbox.send(y);
            }
            let own = trace(first, &mut line, &mut corners)
                .map_err(RenderError::for_target)
                .and_then(|()| send_row(self.display(), &line, first, first_rows));
            if let Some((y, rows)) = second {
                let traced = self.mailbox.receive() == 1;
                fence(Ordering::Acquire);
                // SAFETY: core 1 has answered: it is done with its line until the next row.
                let theirs = unsafe { &*CORE1_LINE.0.get() };
                let sent = if traced {
                    send_row(self.display(), theirs, y, rows)
                } else {
                    Err(RenderError::RowsOutOfRange {
                        end: y.saturating_add(1),
                        height: SIDE,
                    })
                };
                drawn = drawn.and(own).and(sent);
            } else {
                drawn = drawn.and(own);
            }
        }
        self.mailbox.send(END_OF_FRAME);
        // Core 1 answers the end of the frame: `shared` may go.
        while self.mailbox.receive() != END_OF_FRAME {}
        drawn
    }

    fn report(&mut self, report: &Report<'_>) {
        self.screen.report(report);
    }

    fn failed(&mut self, job: &Job<'_>, why: &dyn fmt::Display) {
        self.screen.failed(job, why);
    }

    fn refused(&mut self, job: &Job<'_>, why: &dyn fmt::Display) {
        self.screen.refused(job, why);
    }
}

/// Defines the board's sides of the SIO's mailboxes for the HAL `$hal` (`rp2040_hal` or
/// `rp235x_hal`, whose `SioFifo`s agree), `$sev` waking the other core: `Fifo`, a core's side
/// ([`Mailbox`]), `Asking`, core 0's as it asks whether core 1 answers ([`Probe`]), and
/// `core1_answers`, which resets core 1 and asks.
#[macro_export]
macro_rules! rp_mailboxes {
    ($hal:ident, $sev:path) => {
        /// A core's side of the SIO's mailboxes (`obscura_firmware::rp_mailboxes`).
        struct Fifo($hal::sio::SioFifo);

        impl $crate::two_cores::Mailbox for Fifo {
            fn send(&mut self, word: u32) {
                self.0.write_blocking(word);
            }

            fn receive(&mut self) -> u32 {
                self.0.read_blocking()
            }
        }

        /// Resets core 1 and asks whether it answers within
        /// [`CORE1_ANSWER_MS`]($crate::two_cores::CORE1_ANSWER_MS), `elapsed_ms` counting the
        /// milliseconds since it was called (`obscura_firmware::rp_mailboxes`).
        fn core1_answers(
            psm: &mut $hal::pac::PSM,
            fifo: &mut $hal::sio::SioFifo,
            mut elapsed_ms: impl FnMut() -> u64,
        ) -> bool {
            psm.frce_off().modify(|_, w| w.proc1().set_bit());
            while !psm.frce_off().read().proc1().bit_is_set() {}
            psm.frce_off().modify(|_, w| w.proc1().clear_bit());
            $crate::two_cores::core1_answers(&mut Asking(fifo), || {
                elapsed_ms() < $crate::two_cores::CORE1_ANSWER_MS
            })
        }

        /// Core 0's side of the SIO's mailboxes, asking whether core 1 answers
        /// (`obscura_firmware::rp_mailboxes`).
        struct Asking<'a>(&'a mut $hal::sio::SioFifo);

        impl $crate::two_cores::Probe for Asking<'_> {
            fn drain(&mut self) {
                self.0.drain();
            }

            fn wake(&mut self) {
                $sev();
            }

            fn try_send(&mut self, word: u32) -> bool {
                let ready = self.0.is_write_ready();
                if ready {
                    self.0.write(word);
                }
                ready
            }

            fn try_receive(&mut self) -> Option<u32> {
                self.0.read()
            }
        }
    };
}
