//! obscura on a Raspberry Pi Pico (RP2040: two Cortex-M0+ cores at 125 MHz) with an ST7789
//! 240×240 SPI display, wired as the Waveshare Pico-LCD-1.3 wires it:
//!
//! | display | Pico |
//! |---|---|
//! | DC (data/command) | GP8 |
//! | CS (chip select) | GP9 |
//! | CLK | GP10, SPI1 SCK |
//! | DIN | GP11, SPI1 TX |
//! | RST (reset) | GP12 |
//! | BL (backlight) | GP13 |
//!
//! Both cores trace: of each pair of rows in the frame's order, core 1 traces the second into
//! its own line buffer while core 0 traces the first into its own and sends it; core 0 then
//! sends core 1's. The cores meet through the SIO's mailboxes (FIFOs): core 0 hands core 1 the
//! frame's row tracer, then each row to trace, and core 1 answers when the row is in its line.
//! Each configured frame is drawn in turn, its time and stack written across its bottom rows.
#![no_std]
#![no_main]
#![allow(
    unsafe_code,
    reason = "the boot loader's section, core 1's stolen peripherals, and the line and the \
              row tracer the two cores share through the mailboxes"
)]

use core::cell::UnsafeCell;
use core::convert::Infallible;
use core::fmt;
use core::sync::atomic::{Ordering, fence};
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use embedded_hal_bus::spi::ExclusiveDevice;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use obscura::mesh::MeshWords;
use obscura::{Bits, Camera, Corner, Presentation, RenderError, Scene, send_row, trace_row};
use obscura_firmware::SIDE;
use obscura_firmware::clock::Clock;
use obscura_firmware::frames::{self, Backend, CORNER_ROWS, FrameError, Job, Report};
use obscura_firmware::screen::Screen;
use rp2040_hal::fugit::RateExtU32;
use rp2040_hal::gpio::{FunctionSpi, Pins};
use rp2040_hal::multicore::{Multicore, Stack};
use rp2040_hal::sio::{Sio, SioFifo};
use rp2040_hal::{Clock as _, Timer, Watchdog, clocks, pac, spi};

/// The second-stage boot loader, for the Pico's W25Q080 flash.
#[unsafe(link_section = ".boot2")]
#[used]
static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal, and the SPI clock the display runs at.
const XTAL_HZ: u32 = 12_000_000;
const SPI_MHZ: u32 = 62;

/// Core 1's stack: the tracer's ray stack and its frames (the scene itself is core 0's).
static CORE1_STACK: Stack<4096> = Stack::new();

/// Core 1's line buffer: written by core 1 between a row's word and its answer, read by core 0
/// after the answer; never by both at once.
struct Line(UnsafeCell<[Rgb565; SIDE as usize]>);

/// Core 1's corner rows for adaptive anti-aliasing: core 1's alone.
struct Corners(UnsafeCell<CornerRows>);

// SAFETY: only core 1 touches them.
unsafe impl Sync for Corners {}

static CORE1_CORNERS: Corners = Corners(UnsafeCell::new([Corner::ZERO; CORNER_ROWS]));

// SAFETY: the mailboxes order every access (see `Line`).
unsafe impl Sync for Line {}

static CORE1_LINE: Line = Line(UnsafeCell::new([Rgb565::BLACK; SIDE as usize]));

/// The word that ends a frame for core 1.
const END_OF_FRAME: u32 = u32::MAX;

/// Traces row `y` of the frame into a line: what core 0 hands core 1 for a frame.
type Trace<'a> =
    dyn Fn(u32, &mut [Rgb565], &mut CornerRows) -> Result<(), RenderError<Infallible>> + Sync + 'a;

/// A core's corner rows for adaptive anti-aliasing: an empty array, and no adaptive code in the
/// build, unless a scene takes adaptive samples.
type CornerRows = [Corner; CORNER_ROWS];

#[rp2040_hal::entry]
fn main() -> ! {
    let (Some(mut pac), Some(core)) = (pac::Peripherals::take(), pac::CorePeripherals::take())
    else {
        halt();
    };
    let mut watchdog = Watchdog::new(pac.WATCHDOG);
    let Ok(clocks) = clocks::init_clocks_and_plls(
        XTAL_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    ) else {
        halt();
    };
    let core_mhz = clocks.system_clock.freq().to_MHz();
    let mut timer = Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let mut sio = Sio::new(pac.SIO);
    let pins = Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let mut backlight = pins.gpio13.into_push_pull_output();
    let _ = backlight.set_high();
    let data_command = pins.gpio8.into_push_pull_output();
    let chip_select = pins.gpio9.into_push_pull_output();
    let sck = pins.gpio10.into_function::<FunctionSpi>();
    let tx = pins.gpio11.into_function::<FunctionSpi>();
    let reset = pins.gpio12.into_push_pull_output();
    let bus = spi::Spi::<_, _, _, 8>::new(pac.SPI1, (tx, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        SPI_MHZ.MHz(),
        embedded_hal::spi::MODE_0,
    );
    let Ok(device) = ExclusiveDevice::new(bus, chip_select, timer);
    // mipidsi batches pixels through this buffer; it must outlive the display, which is never
    // dropped, so it lives in a static taken once.
    let Some(buffer) = cortex_m::singleton!(: [u8; 512] = [0; 512]) else {
        halt();
    };
    let interface = SpiInterface::new(device, data_command, buffer);
    let Ok(panel) = mipidsi::Builder::new(ST7789, interface)
        .display_size(240, 240)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(reset)
        .init(&mut timer)
    else {
        halt();
    };
    timer.delay_ms(10);

    let mut multicore = Multicore::new(&mut pac.PSM, &mut pac.PPB, &mut sio.fifo);
    let Some(stack) = CORE1_STACK.take() else {
        halt();
    };
    let Some(core1) = multicore.cores().get_mut(1) else {
        halt();
    };
    if core1.spawn(stack, core1_traces_rows).is_err() {
        halt();
    }
    let clock = Clock::start(core.SYST);
    let mut board = Pico {
        screen: Screen {
            display: panel,
            core_mhz,
        },
        fifo: sio.fifo,
    };
    frames::render_all(&mut board, &clock);
    halt();
}

/// Core 1: for each frame, takes the row tracer core 0 hands it, then traces each row it is
/// given into its line and answers (1 traced, 0 not), until the end of the frame.
fn core1_traces_rows() {
    // SAFETY: core 1 uses only its own side of the SIO's mailboxes, which core 0's `Sio` does
    // not touch from core 1.
    let mut fifo = Sio::new(unsafe { pac::Peripherals::steal() }.SIO).fifo;
    loop {
        let address = fifo.read_blocking() as usize;
        // SAFETY: core 0 sent the address of a `&Trace` that lives until it has our answer to
        // the end of the frame.
        let trace: &&Trace<'_> = unsafe { &*(address as *const &Trace<'_>) };
        loop {
            let y = fifo.read_blocking();
            if y == END_OF_FRAME {
                break;
            }
            // SAFETY: core 0 reads the line only after our answer (see `Line`).
            let line = unsafe { &mut *CORE1_LINE.0.get() };
            // SAFETY: only core 1 uses its corner rows.
            let corners = unsafe { &mut *CORE1_CORNERS.0.get() };
            let traced = trace(y, line, corners).is_ok();
            fence(Ordering::Release);
            fifo.write_blocking(u32::from(traced));
        }
        fifo.write_blocking(END_OF_FRAME);
    }
}

/// The Pico: its display, and core 0's side of the mailboxes to core 1.
struct Pico<D> {
    screen: Screen<D>,
    fifo: SioFifo,
}

impl<D: DrawTarget<Color = Rgb565, Error: fmt::Debug>> Backend for Pico<D> {
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
        const USES: u32,
    >(
        &mut self,
        scene: &Scene<S, OBJECTS, LIGHTS, RAYS, USES, MeshWords<S>>,
        camera: &Camera<S>,
        presentation: Presentation,
    ) -> Result<(), FrameError<Self>> {
        let dither = presentation.dither;
        let trace = |y: u32, line: &mut [Rgb565], corners: &mut CornerRows| {
            trace_row(scene, camera, y, dither, line, corners)
        };
        let shared: &Trace<'_> = &trace;
        // Core 1 holds this address until it answers the end of the frame, below.
        self.fifo.write_blocking(&raw const shared as usize as u32);
        let mut line = [Rgb565::BLACK; SIDE as usize];
        let mut corners = [Corner::ZERO; CORNER_ROWS];
        let mut order = presentation.order.rows(SIDE);
        let mut drawn = Ok(());
        while let Some((first, first_rows)) = order.next() {
            let second = order.next();
            if let Some((y, _)) = second {
                self.fifo.write_blocking(y);
            }
            let own = trace(first, &mut line, &mut corners)
                .map_err(RenderError::for_target)
                .and_then(|()| send_row(self.display(), &line, first, first_rows));
            if let Some((y, rows)) = second {
                let traced = self.fifo.read_blocking() == 1;
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
        self.fifo.write_blocking(END_OF_FRAME);
        // Core 1 answers the end of the frame: `shared` may go.
        while self.fifo.read_blocking() != END_OF_FRAME {}
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

/// Sleeps for good: the picture stays on the display.
fn halt() -> ! {
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    halt();
}
