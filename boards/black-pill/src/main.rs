//! The hardware back-end: an ST7789 240×240 SPI display (the common 1.3" IPS module) on an
//! STM32F411 "Black Pill", driven by mipidsi. Each configured frame is drawn in turn, and its
//! time (SysTick counts real core cycles here) is written across its bottom row; then the
//! core sleeps, or with a camera path draws the frames again, for good.
//!
//! Wiring (3.3 V logic; see the README for the table):
//!
//! | display | Black Pill |
//! |---|---|
//! | GND, VCC | GND, 3V3 |
//! | SCL (clock) | PA5, SPI1 SCK |
//! | SDA (data) | PA7, SPI1 MOSI |
//! | RES (reset) | PA2 |
//! | DC (data/command) | PA3 |
//! | BLK (backlight) | PA1 |
//!
//! Modules without a chip-select pin listen all the time and need SPI mode 3; a module with
//! CS has it tied to GND.
#![no_std]
#![no_main]

use embedded_hal_bus::spi::ExclusiveDevice;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use obscura_firmware::clock::Clock;
use obscura_firmware::frames;
use obscura_firmware::screen::Screen;
use stm32f4xx_hal::pac;
use stm32f4xx_hal::prelude::*;
use stm32f4xx_hal::rcc::Config;
use stm32f4xx_hal::spi::{Mode, Phase, Polarity};

/// The Black Pill's crystal, and the core clock and SPI clock the firmware runs them at.
const HSE_MHZ: u32 = 25;
const SYSCLK_MHZ: u32 = 100;
const SPI_MHZ: u32 = 50;

/// Brings up the clocks, the SPI bus and the display, draws every configured frame, and sleeps.
#[cortex_m_rt::entry]
fn main() -> ! {
    let (Some(dp), Some(cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else {
        halt();
    };
    let mut rcc = dp
        .RCC
        .freeze(Config::hse(HSE_MHZ.MHz()).sysclk(SYSCLK_MHZ.MHz()));
    let gpioa = dp.GPIOA.split(&mut rcc);
    let mut backlight = gpioa.pa1.into_push_pull_output();
    backlight.set_high();
    let reset = gpioa.pa2.into_push_pull_output();
    let data_command = gpioa.pa3.into_push_pull_output();
    let mode = Mode {
        polarity: Polarity::IdleHigh,
        phase: Phase::CaptureOnSecondTransition,
    };
    let spi = dp.SPI1.spi_bidi(
        (Some(gpioa.pa5), Some(gpioa.pa7)),
        mode,
        SPI_MHZ.MHz(),
        &mut rcc,
    );
    let Ok(device) = ExclusiveDevice::new_no_delay(spi, NoChipSelect);
    let mut delay = dp.TIM2.delay_us(&mut rcc);
    // mipidsi batches pixels through this buffer; it must outlive the display, which is never
    // dropped, so it lives in a static taken once.
    let buffer = cortex_m::singleton!(: [u8; 512] = [0; 512]);
    let Some(buffer) = buffer else { halt() };
    let interface = SpiInterface::new(device, data_command, buffer);
    let panel = mipidsi::Builder::new(ST7789, interface)
        .display_size(240, 240)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(reset)
        .init(&mut delay);
    let Ok(panel) = panel else { halt() };
    let clock = Clock::start(cp.SYST);
    let mut screen = Screen {
        display: panel,
        core_mhz: SYSCLK_MHZ,
        // stm32f4xx-hal does not say which divider it took.
        spi_khz: None,
        note: None,
    };
    frames::show(&mut screen, &clock);
    halt();
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

/// The chip select of a module that has none: always selected.
struct NoChipSelect;

impl stm32f4xx_hal::hal::digital::ErrorType for NoChipSelect {
    type Error = core::convert::Infallible;
}

impl stm32f4xx_hal::hal::digital::OutputPin for NoChipSelect {
    fn set_low(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}
