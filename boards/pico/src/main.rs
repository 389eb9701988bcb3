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
//! Both cores trace, sharing each frame's rows ([`obscura_firmware::two_cores`]), while DMA
//! sends the rows traced to the display ([`obscura_firmware::dma_display`]); where core 1's
//! mailboxes are missing (an emulator without core 1) or core 1 does not answer within 100 ms,
//! core 0 traces every row and says so under each frame. Each configured frame is drawn in turn, its time and stack written across its
//! bottom rows; a camera path's frames again and again, for good.
#![no_std]
#![no_main]
#![allow(
    unsafe_code,
    reason = "the boot loader's section, and core 1's stolen peripherals"
)]

use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use obscura_firmware::clock::Clock;
use obscura_firmware::dma_display::{DmaInterface, LAST_ROW, ROW_BYTES};
use obscura_firmware::frames;
use obscura_firmware::screen::Screen;
use obscura_firmware::two_cores::{self, TwoCores};
use rp2040_hal::dma::DMAExt;
use rp2040_hal::fugit::RateExtU32;
use rp2040_hal::gpio::{FunctionSpi, Pins};
use rp2040_hal::multicore::{Multicore, Stack};
use rp2040_hal::sio::{Sio, SioFifo};
use rp2040_hal::{Clock as _, Timer, Watchdog, clocks, pac, spi};

/// The second-stage boot loader, for the Pico's W25Q080 flash.
#[unsafe(link_section = ".boot2")]
#[used]
static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal, and the SPI clock asked of the display: the ST7789's fastest, 62.5 MHz,
/// which the 125 MHz peripheral clock divided by 2 gives exactly (rp2040-hal never exceeds
/// what is asked: 62 MHz would give 31.25).
const XTAL_HZ: u32 = 12_000_000;
const SPI_HZ: u32 = 62_500_000;

obscura_firmware::rp_spi_dma!(rp2040_hal);

/// Core 1's stack: the tracer's ray stack and its frames (the scene itself is core 0's).
static CORE1_STACK: Stack<4096> = Stack::new();

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
    let mut chip_select = pins.gpio9.into_push_pull_output();
    let sck = pins.gpio10.into_function::<FunctionSpi>();
    let tx = pins.gpio11.into_function::<FunctionSpi>();
    let reset = pins.gpio12.into_push_pull_output();
    let mut bus = spi::Spi::<_, _, _, 8>::new(pac.SPI1, (tx, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        SPI_HZ.Hz(),
        embedded_hal::spi::MODE_0,
    );
    // The clock the HAL set (`init` asked the same), shown under each frame.
    let spi_khz = bus
        .set_baudrate(clocks.peripheral_clock.freq(), SPI_HZ.Hz())
        .to_kHz();
    // The display is the only device on its SPI: selected for good.
    let _ = chip_select.set_low();
    let dma = pac.DMA.split(&mut pac.RESETS);
    // Two buffers of a row each, filled and sent by DMA in turn.
    let (Some(first), Some(second)) = (
        cortex_m::singleton!(: [u8; ROW_BYTES] = [0; ROW_BYTES]),
        cortex_m::singleton!(: [u8; ROW_BYTES] = [0; ROW_BYTES]),
    ) else {
        halt();
    };
    let interface = DmaInterface::new(
        SpiDma::new(dma.ch0, bus),
        data_command,
        [first, second],
        LAST_ROW,
    );
    let Ok(panel) = mipidsi::Builder::new(ST7789, interface)
        .display_size(240, 240)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(reset)
        .init(&mut timer)
    else {
        halt();
    };
    timer.delay_ms(10);

    let clock = Clock::start(core.SYST);
    let mut screen = Screen {
        display: panel,
        core_mhz,
        spi_khz: Some(spi_khz),
        note: None,
    };
    let asked = timer.get_counter();
    let missing = if !has_core1_fifo(&sio.fifo) {
        Some("one core: core 1's FIFO is missing")
    } else if !core1_answers(&mut pac.PSM, &mut sio.fifo, || {
        (timer.get_counter() - asked).to_millis()
    }) {
        Some("one core: core 1 does not answer")
    } else {
        None
    };
    if let Some(why) = missing {
        // Core 0 traces every row; the frame says why.
        screen.note = Some(why);
        frames::show(&mut screen, &clock);
        halt();
    }
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
    let mut board = TwoCores {
        screen,
        mailbox: Fifo(sio.fifo),
    };
    frames::show(&mut board, &clock);
    halt();
}

/// Whether the SIO's mailboxes to core 1 are there: their status has four bits, and the rest
/// read 0 on silicon. An emulator without a core 1 (rp2040js) reads all ones, where starting
/// core 1 would wait for its answer for good.
fn has_core1_fifo(fifo: &SioFifo) -> bool {
    fifo.status() != u32::MAX
}

/// Core 1: traces the rows core 0 hands it, for good.
fn core1_traces_rows() {
    // SAFETY: core 1 uses only its own side of the SIO's mailboxes, which core 0's `Sio` does
    // not touch from core 1.
    let fifo = Sio::new(unsafe { pac::Peripherals::steal() }.SIO).fifo;
    two_cores::core1_traces_rows(&mut Fifo(fifo));
}

obscura_firmware::rp_mailboxes!(rp2040_hal, cortex_m::asm::sev);

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
