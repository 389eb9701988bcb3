//! A scene of your own on a Raspberry Pi Pico with an ST7789 240×240 SPI display, wired as the
//! Waveshare Pico-LCD-1.3 wires it: DC GP8, CS GP9, CLK GP10 (SPI1 SCK), DIN GP11 (SPI1 TX),
//! RST GP12, backlight GP13. `build.rs` proved `scene.toml` on your computer; the chip reads the
//! proven words back and traces the picture row by row, straight to the display, on one core
//! (obscura's own `boards/pico` traces on both and sends rows by DMA: about half the time).
//! `obscura emulate scene.toml --format i16f16 --image target/thumbv6m-none-eabi/release/NAME`
//! runs this image in an RP2040 emulator and checks what reaches the display, and its time.
#![no_std]
#![no_main]

use embedded_hal::digital::OutputPin;
use embedded_hal_bus::spi::ExclusiveDevice;
use mipidsi::interface::SpiInterface;
use mipidsi::{models::ST7789, options::ColorInversion};
use rp2040_hal::fugit::RateExtU32;
use rp2040_hal::gpio::{FunctionSpi, Pins};
use rp2040_hal::{Clock as _, Sio, Timer, Watchdog, clocks, pac, spi};

/// The scene `build.rs` proved, and `draw`, which draws it.
mod scene {
    include!(concat!(env!("OUT_DIR"), "/scene.rs"));
}

/// The second-stage boot loader, for the Pico's W25Q080 flash.
#[unsafe(link_section = ".boot2")]
#[used]
static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

#[rp2040_hal::entry]
fn main() -> ! {
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = Watchdog::new(pac.WATCHDOG);
    let clocks = clocks::init_clocks_and_plls(
        12_000_000, // the Pico's crystal
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .unwrap();
    let mut timer = Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let sio = Sio::new(pac.SIO);
    let pins = Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let mut backlight = pins.gpio13.into_push_pull_output();
    backlight.set_high().unwrap();
    let bus = spi::Spi::<_, _, _, 8>::new(
        pac.SPI1,
        (
            pins.gpio11.into_function::<FunctionSpi>(),
            pins.gpio10.into_function::<FunctionSpi>(),
        ),
    )
    .init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        // The ST7789's fastest clock, exactly half the 125 MHz peripheral clock (the HAL
        // never exceeds what is asked: 62 MHz would give 31.25).
        62_500_000.Hz(),
        embedded_hal::spi::MODE_0,
    );
    let device = ExclusiveDevice::new(bus, pins.gpio9.into_push_pull_output(), timer).unwrap();
    let mut buffer = [0_u8; 512];
    let interface = SpiInterface::new(device, pins.gpio8.into_push_pull_output(), &mut buffer);
    let mut display = mipidsi::Builder::new(ST7789, interface)
        .display_size(scene::WIDTH as u16, scene::HEIGHT as u16)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(pins.gpio12.into_push_pull_output())
        .init(&mut timer)
        .unwrap();

    // The chip builds and proves nothing: it reads the proven scene back and draws it.
    scene::draw(&mut display).unwrap();
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    loop {
        cortex_m::asm::wfi();
    }
}
