//! The Pico boards' display interface (`firmware/src/dma_display.rs`, compiled here from its
//! source) on a recording SPI: what reaches the panel, and when the CPU may reuse a buffer.
//! The recording DMA reads its buffer only when the transfer ends (at the next wait), so an
//! interface that wrote into a buffer in flight would send the wrong bytes.

#[path = "../../firmware/src/dma_display.rs"]
mod dma_display;

/// The panel's side, which the module's constants derive from: the firmware's
/// (`obscura_firmware::SIDE` is this).
use obscura_scene::firmware::SIDE;

use dma_display::{DmaInterface, DmaSpi};
use mipidsi::interface::Interface;
use std::cell::RefCell;
use std::convert::Infallible;
use std::rc::Rc;

/// What reached the panel: each byte with the data/command line's level, and each
/// transfer's length in bytes, by DMA or not.
#[derive(Debug, Default)]
struct Wire {
    /// The data/command line: high for data.
    data: bool,
    /// Bytes as the panel received them: (data?, byte).
    bytes: Vec<(bool, u8)>,
    /// Each transfer: (by DMA?, bytes).
    transfers: Vec<(bool, usize)>,
}

/// An SPI whose DMA transfer ends when it is next waited for.
struct Recorder {
    wire: Rc<RefCell<Wire>>,
    in_flight: Option<&'static mut [u8]>,
}

impl Recorder {
    fn end(&mut self) -> Option<&'static mut [u8]> {
        let buffer = self.in_flight.take()?;
        let mut wire = self.wire.borrow_mut();
        let data = wire.data;
        wire.bytes.extend(buffer.iter().map(|&b| (data, b)));
        wire.transfers.push((true, buffer.len()));
        Some(buffer)
    }
}

impl DmaSpi for Recorder {
    fn write(&mut self, bytes: &[u8]) -> Option<&'static mut [u8]> {
        let sent = self.end();
        let mut wire = self.wire.borrow_mut();
        let data = wire.data;
        wire.bytes.extend(bytes.iter().map(|&b| (data, b)));
        wire.transfers.push((false, bytes.len()));
        sent
    }

    fn send(&mut self, buffer: &'static mut [u8]) -> Option<&'static mut [u8]> {
        let sent = self.end();
        self.in_flight = Some(buffer);
        sent
    }

    fn finish(&mut self) -> Option<&'static mut [u8]> {
        self.end()
    }
}

/// The data/command line.
struct DataCommand(Rc<RefCell<Wire>>);

impl embedded_hal::digital::ErrorType for DataCommand {
    type Error = Infallible;
}

impl embedded_hal::digital::OutputPin for DataCommand {
    fn set_low(&mut self) -> Result<(), Infallible> {
        self.0.borrow_mut().data = false;
        Ok(())
    }

    fn set_high(&mut self) -> Result<(), Infallible> {
        self.0.borrow_mut().data = true;
        Ok(())
    }
}

/// An interface with two buffers of a row of `width` pixels, on the firmware's panel, and
/// what it sends.
fn interface(width: usize) -> (DmaInterface<Recorder, DataCommand>, Rc<RefCell<Wire>>) {
    let wire = Rc::new(RefCell::new(Wire::default()));
    let buffer = || Box::leak(vec![0_u8; 2 * width].into_boxed_slice());
    let recorder = Recorder {
        wire: Rc::clone(&wire),
        in_flight: None,
    };
    let interface = DmaInterface::new(
        recorder,
        DataCommand(Rc::clone(&wire)),
        [buffer(), buffer()],
        dma_display::LAST_ROW,
    );
    (interface, wire)
}

/// Addresses the rectangle (x0..=x1, y0..=y1) and sends `pixels` into it, as mipidsi does.
fn draw(
    display: &mut DmaInterface<Recorder, DataCommand>,
    (x0, x1, y0, y1): (u16, u16, u16, u16),
    pixels: &[u16],
) {
    let pair = |a: u16, b: u16| {
        let ([ah, al], [bh, bl]) = (a.to_be_bytes(), b.to_be_bytes());
        [ah, al, bh, bl]
    };
    let done = display
        .send_command(0x2a, &pair(x0, x1))
        .and_then(|()| display.send_command(0x2b, &pair(y0, y1)))
        .and_then(|()| display.send_command(0x2c, &[]))
        .and_then(|()| display.send_pixels(pixels.iter().map(|p| p.to_be_bytes())));
    assert!(done.is_ok());
}

/// A row of `width` pixels, each its column plus `y` times 1000.
fn row(y: u16, width: u16) -> Vec<u16> {
    (0..width).map(|x| 1000 * y + x).collect()
}

/// The wire's bytes as commands, each with the data that follows it.
fn commands(wire: &Wire) -> Vec<(u8, Vec<u8>)> {
    let mut commands: Vec<(u8, Vec<u8>)> = Vec::new();
    for &(data, byte) in &wire.bytes {
        match commands.last_mut() {
            Some((_, args)) if data => args.push(byte),
            _ => commands.push((byte, Vec::new())),
        }
    }
    commands
}

fn bytes_of(pixels: impl IntoIterator<Item = u16>) -> Vec<u8> {
    pixels.into_iter().flat_map(u16::to_be_bytes).collect()
}

#[test]
fn rows_that_follow_one_another_go_by_dma_in_one_window() {
    let (mut display, wire) = interface(240);
    for y in 10..14 {
        draw(&mut display, (0, 239, y, y), &row(y, 240));
    }
    // A command ends the last transfer.
    assert!(display.send_command(0x21, &[]).is_ok());
    let wire = wire.borrow();
    let sent = commands(&wire);
    let expected_rows = bytes_of((10..14).flat_map(|y| row(y, 240)));
    assert_eq!(
        sent,
        [
            (0x2a, vec![0, 0, 0, 239]),
            (0x2b, vec![0, 10, 0, 239]),
            (0x2c, expected_rows),
            (0x21, vec![]),
        ]
    );
    let by_dma: Vec<usize> = wire
        .transfers
        .iter()
        .filter(|(dma, _)| *dma)
        .map(|&(_, n)| n)
        .collect();
    assert_eq!(by_dma, [dma_display::ROW_BYTES; 4]);
}

#[test]
fn a_rectangle_that_does_not_follow_opens_its_own_window_and_a_short_one_is_written() {
    let (mut display, wire) = interface(240);
    draw(&mut display, (0, 239, 0, 0), &row(0, 240));
    // Not the next row: a window of its own.
    draw(&mut display, (0, 239, 5, 5), &row(5, 240));
    // Narrower (a caption's glyph), a third of a buffer: written while the CPU waits.
    draw(&mut display, (2, 7, 220, 229), &row(1, 60));
    // The row after row 5, in a window no longer open: addressed again.
    draw(&mut display, (0, 239, 6, 6), &row(6, 240));
    assert!(display.send_command(0x29, &[]).is_ok());
    let wire = wire.borrow();
    let sent = commands(&wire);
    let windows: Vec<&(u8, Vec<u8>)> = sent.iter().filter(|(c, _)| *c == 0x2b).collect();
    assert_eq!(
        windows,
        [
            &(0x2b, vec![0, 0, 0, 239]),
            &(0x2b, vec![0, 5, 0, 239]),
            &(0x2b, vec![0, 220, 0, 239]),
            &(0x2b, vec![0, 6, 0, 239]),
        ]
    );
    let pixels: Vec<&Vec<u8>> = sent
        .iter()
        .filter(|(c, _)| *c == 0x2c)
        .map(|(_, data)| data)
        .collect();
    assert_eq!(
        pixels,
        [
            &bytes_of(row(0, 240)),
            &bytes_of(row(5, 240)),
            &bytes_of(row(1, 60)),
            &bytes_of(row(6, 240)),
        ]
    );
    assert!(wire.transfers.contains(&(false, 120)));
}

#[test]
fn a_block_of_rows_goes_as_whole_buffers_and_its_rest_while_the_cpu_waits() {
    // A progressive block: one row's pixels repeated over 8 rows, from buffers of 100 pixels.
    let (mut display, wire) = interface(100);
    let block: Vec<u16> = row(3, 240).repeat(8);
    draw(&mut display, (0, 239, 8, 15), &block);
    draw(&mut display, (0, 239, 16, 16), &row(16, 240));
    assert!(display.send_command(0x00, &[]).is_ok());
    let wire = wire.borrow();
    let sent = commands(&wire);
    assert_eq!(
        sent.len(),
        4,
        "{:?}",
        sent.iter().map(|c| c.0).collect::<Vec<_>>()
    );
    let mut expected = bytes_of(block);
    expected.extend(bytes_of(row(16, 240)));
    assert_eq!(sent.get(2), Some(&(0x2c, expected)));
    // 1920 pixels: 19 buffers and 20 pixels written; 240: 2 buffers and 40 pixels.
    let by_dma = wire.transfers.iter().filter(|(dma, _)| *dma).count();
    assert_eq!(by_dma, 21);
    assert!(wire.transfers.contains(&(false, 40)) && wire.transfers.contains(&(false, 80)));
}
