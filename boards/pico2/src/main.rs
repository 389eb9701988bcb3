//! obscura on a Raspberry Pi Pico 2 (RP2350: two Cortex-M33 cores or two Hazard3 RISC-V cores,
//! at 150 MHz) with an ST7789 240×240 SPI display, wired as on the Pico (the Waveshare
//! Pico-LCD-1.3 plugs onto both):
//!
//! | display | Pico 2 |
//! |---|---|
//! | DC (data/command) | GP8 |
//! | CS (chip select) | GP9 |
//! | CLK | GP10, SPI1 SCK |
//! | DIN | GP11, SPI1 TX |
//! | RST (reset) | GP12 |
//! | BL (backlight) | GP13 |
//!
//! One source for both architectures, which the build target picks (`thumbv8m.main-none-eabihf`
//! or `riscv32imac-unknown-none-elf`), as rp235x-hal's own examples do: the boot ROM reads which
//! from the image's IMAGE_DEF block. Both cores trace, sharing each frame's rows
//! ([`obscura_firmware::two_cores`]), while DMA sends the rows traced to the display
//! ([`obscura_firmware::dma_display`]); where core 1 does not answer within 100 ms, core 0
//! traces every row and says so under each frame. rp235x-hal starts core 1 on the Cortex-M33;
//! on Hazard3, where its multicore module does not build, [`core1`] starts it by the boot ROM's
//! protocol (the RP2350 datasheet, section 5.3). Each configured frame is drawn in turn, its time (in
//! core cycles: SysTick on the M33, `mcycle` on Hazard3) and stack written across its bottom
//! rows; a camera path's frames again and again, for good.
#![no_std]
#![no_main]
#![allow(
    unsafe_code,
    reason = "the boot ROM's block, core 1's start and its stolen peripherals"
)]

use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use hal::clocks::Clock as _;
use hal::dma::DMAExt;
use hal::fugit::RateExtU32;
use hal::gpio::{FunctionSpi, Pins};
use hal::sio::{Sio, SioFifo};
use hal::{Timer, Watchdog, clocks, pac, spi};
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use obscura_firmware::clock::Clock;
use obscura_firmware::dma_display::{DmaInterface, LAST_ROW, ROW_BYTES};
use obscura_firmware::frames;
use obscura_firmware::screen::Screen;
use obscura_firmware::two_cores::{self, TwoCores};
use rp235x_hal as hal;

/// What the boot ROM looks for in the first 4 KiB of flash: a Secure executable for the
/// architecture this image is built for. On the M33 after the vector table (the workspace's
/// `memory.x`), on Hazard3 right after `_start` (`rp2350-riscv.x`).
#[cfg_attr(target_arch = "arm", unsafe(link_section = ".start_block"))]
#[cfg_attr(target_arch = "riscv32", unsafe(link_section = ".init.rust"))]
#[used]
static IMAGE_DEF: hal::block::ImageDef = hal::block::ImageDef::secure_exe();

/// The Pico 2's crystal, and the SPI clock asked of the display: the ST7789's fastest, 62.5 MHz,
/// of which the 150 MHz peripheral clock's dividers give 37.5 (rp235x-hal never exceeds what is
/// asked).
const XTAL_HZ: u32 = 12_000_000;
const SPI_HZ: u32 = 62_500_000;

obscura_firmware::rp_spi_dma!(rp235x_hal);

/// Sets up the clocks, the display and core 1, then draws every configured frame.
#[hal::entry]
fn main() -> ! {
    let Some(mut pac) = pac::Peripherals::take() else {
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
    let mut timer = Timer::new_timer0(pac.TIMER0, &mut pac.RESETS, &clocks);
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
        hal::singleton!(: [u8; ROW_BYTES] = [0; ROW_BYTES]),
        hal::singleton!(: [u8; ROW_BYTES] = [0; ROW_BYTES]),
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

    // Else core 0 traces every row.
    let asked = timer.get_counter();
    let answers = core1_answers(&mut pac.PSM, &mut sio.fifo, || {
        (timer.get_counter() - asked).to_millis()
    });
    if answers && core1::start(&mut pac.PSM, &mut pac.PPB, &mut sio.fifo).is_err() {
        halt();
    }
    #[cfg(target_arch = "arm")]
    let clock = {
        let Some(core) = cortex_m::Peripherals::take() else {
            halt();
        };
        Clock::start(core.SYST)
    };
    #[cfg(target_arch = "riscv32")]
    let clock = Clock::start();
    let mut screen = Screen {
        display: panel,
        core_mhz,
        spi_khz: Some(spi_khz),
        note: None,
    };
    if !answers {
        screen.note = Some("one core: core 1 does not answer");
        frames::show(&mut screen, &clock);
        halt();
    }
    let mut board = TwoCores {
        screen,
        mailbox: Fifo(sio.fifo),
    };
    frames::show(&mut board, &clock);
    halt();
}

/// Core 1: traces the rows core 0 hands it, for good.
fn core1_traces_rows() -> ! {
    // SAFETY: core 1 uses only its own side of the SIO's mailboxes, which core 0's `Sio` does
    // not touch from core 1.
    let fifo = Sio::new(unsafe { pac::Peripherals::steal() }.SIO).fifo;
    two_cores::core1_traces_rows(&mut Fifo(fifo))
}

/// Starting core 1 on the Cortex-M33: rp235x-hal's multicore support.
#[cfg(target_arch = "arm")]
mod core1 {
    use super::{SioFifo, core1_traces_rows, pac};
    use rp235x_hal::multicore::{Multicore, Stack};

    /// Core 1's stack: the tracer's ray stack and its frames (the scene itself is core 0's).
    static STACK: Stack<4096> = Stack::new();

    /// Starts core 1 tracing rows.
    pub fn start(psm: &mut pac::PSM, ppb: &mut pac::PPB, fifo: &mut SioFifo) -> Result<(), ()> {
        let mut multicore = Multicore::new(psm, ppb, fifo);
        let stack = STACK.take().ok_or(())?;
        let core1 = multicore.cores().get_mut(1).ok_or(())?;
        core1.spawn(stack, || core1_traces_rows()).map_err(|_| ())
    }
}

/// Starting core 1 on Hazard3, where rp235x-hal's multicore module does not build: core 1
/// is reset, then woken by the boot ROM's sequence through the mailboxes (the RP2350
/// datasheet, section 5.3): 0, 0, 1, the trap vector (`mtvec`, core 0's), the stack pointer and
/// the entry, each echoed back, the sequence begun again on a wrong echo. The entry sets the
/// global pointer, which the boot ROM does not, before the Rust code runs.
#[cfg(target_arch = "riscv32")]
mod core1 {
    use super::{SioFifo, core1_traces_rows, pac};
    use core::cell::UnsafeCell;

    /// Core 1's stack, in 16-byte units (the RISC-V ABI's alignment): 4 KiB, as on the M33.
    #[repr(C, align(16))]
    struct Stack(UnsafeCell<[u8; 4096]>);

    // SAFETY: only core 1 uses it, as its stack.
    unsafe impl Sync for Stack {}

    static STACK: Stack = Stack(UnsafeCell::new([0; 4096]));

    core::arch::global_asm!(
        ".section .text.obscura_core1_entry, \"ax\"",
        ".global obscura_core1_entry",
        ".align 2",
        "obscura_core1_entry:",
        ".option push",
        ".option norelax",
        "la gp, __global_pointer$",
        ".option pop",
        "j {main}",
        main = sym core1_main,
    );

    unsafe extern "C" {
        /// Where core 1 starts: sets the global pointer, then runs [`core1_main`].
        fn obscura_core1_entry() -> !;
    }

    /// Core 1's Rust entry.
    extern "C" fn core1_main() -> ! {
        core1_traces_rows()
    }

    /// Starts core 1 tracing rows.
    pub fn start(psm: &mut pac::PSM, _: &mut pac::PPB, fifo: &mut SioFifo) -> Result<(), ()> {
        psm.frce_off().modify(|_, w| w.proc1().set_bit());
        while !psm.frce_off().read().proc1().bit_is_set() {}
        psm.frce_off().modify(|_, w| w.proc1().clear_bit());
        let stack_top = STACK.0.get() as usize + size_of::<Stack>();
        let entry = obscura_core1_entry as *const () as usize;
        let vector = riscv::register::mtvec::read().bits();
        let sequence = [0, 0, 1, vector, stack_top, entry].map(|word| word as u32);
        let mut next = 0;
        while let Some(&word) = sequence.get(next) {
            if word == 0 {
                // Core 1 may be waiting to send: empty its mailbox and wake it.
                fifo.drain();
                rp235x_hal::arch::sev();
            }
            fifo.write_blocking(word);
            next = if fifo.read_blocking() == word {
                next + 1
            } else {
                0
            };
        }
        Ok(())
    }
}

obscura_firmware::rp_mailboxes!(rp235x_hal, rp235x_hal::arch::sev);

/// Sleeps for good: the picture stays on the display.
fn halt() -> ! {
    loop {
        hal::arch::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    halt();
}
