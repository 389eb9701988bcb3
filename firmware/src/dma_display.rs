//! A display's SPI fed by DMA: the [`mipidsi`] interface the Pico boards drive their ST7789
//! through. Commands go out as the CPU writes them; pixels are copied into one of two buffers
//! of a row each, and a full buffer is sent by DMA while the CPU goes on (tracing the next
//! rows) and fills the other, so a frame costs about the larger of tracing and sending, not
//! their sum. A command waits for the transfer in flight and for the SPI to shift out its last
//! bit before the data/command line changes. Chip select is the board's, held low throughout.
//!
//! Rows that follow one another go as one stream: the interface opens the panel's address
//! window from a rectangle's first row to the panel's last, and a rectangle that starts where
//! the stream has reached, as wide, needs no command at all (mipidsi addresses each row with
//! CASET, RASET and RAMWR, which would wait for each row's transfer before the next is copied).
//!
//! The DMA channel and SPI are the board's HAL's ([`DmaSpi`]); [`rp_spi_dma!`] implements it
//! for rp2040-hal and rp235x-hal, whose DMA and SPI modules agree.

use crate::SIDE;
use core::mem;
use embedded_hal::digital::OutputPin;
use mipidsi::interface::{Interface, InterfaceKind};

/// A row of the board's `SIDE`×`SIDE` panel, two bytes a pixel: one buffer, one transfer.
pub const ROW_BYTES: usize = 2 * SIDE as usize;

/// The panel's last row as mipidsi addresses a `SIDE`×`SIDE` panel with no offset, in its
/// default orientation ([`DmaInterface::new`]'s `last_row`).
pub const LAST_ROW: u16 = SIDE as u16 - 1;

/// What a board's HAL gives a display interface: an SPI that writes bytes while the CPU waits,
/// and sends a buffer by DMA while it does not. Each call that waits for the transfer in flight
/// hands back its buffer (`None` if none was in flight).
pub trait DmaSpi {
    /// Writes `bytes` once the transfer in flight is done, returning when the SPI is idle.
    fn write(&mut self, bytes: &[u8]) -> Option<&'static mut [u8]>;
    /// Starts sending `buffer` by DMA once the transfer in flight is done.
    fn send(&mut self, buffer: &'static mut [u8]) -> Option<&'static mut [u8]>;
    /// Waits until the transfer in flight is done and the SPI is idle.
    fn finish(&mut self) -> Option<&'static mut [u8]>;
}

/// A display interface (4-wire SPI, 8-bit words) whose pixels go by DMA through two buffers.
#[derive(Debug)]
pub struct DmaInterface<B, DC> {
    /// The SPI and its DMA channel.
    bus: B,
    /// The data/command line.
    dc: DC,
    /// The buffer pixels are copied into.
    filling: &'static mut [u8],
    /// Its bytes filled.
    filled: usize,
    /// The other buffer, while no transfer holds it.
    idle: Option<&'static mut [u8]>,
    /// The address window asked and the one open.
    window: Window,
}

/// The MIPI DCS commands that address a rectangle: its columns, its rows, and the start of its
/// pixels.
const COLUMNS: u8 = 0x2a;
const ROWS: u8 = 0x2b;
const WRITE: u8 = 0x2c;

/// The address window: what mipidsi last asked (its CASET and RASET arguments), and the stream
/// open on the panel.
#[derive(Debug)]
struct Window {
    /// CASET's arguments asked: first and last column, big-endian.
    columns: [u8; 4],
    /// RASET's arguments asked: first and last row, big-endian.
    rows: [u8; 4],
    /// The panel's last row address, to which a stream's window reaches.
    last_row: u16,
    /// The stream open, if one is.
    open: Option<Stream>,
}

/// A window open on the panel, and how far its pixels have reached.
#[derive(Debug)]
struct Stream {
    /// Its columns (CASET's arguments).
    columns: [u8; 4],
    /// Its first row.
    first: u16,
    /// Its last row.
    last: u16,
    /// Bytes of pixels sent into it.
    bytes: u32,
}

impl Window {
    /// Whether the rectangle asked starts where the open stream has reached, as wide, and ends
    /// within it: its pixels can follow without a command.
    fn continues(&self) -> bool {
        let Some(stream) = &self.open else {
            return false;
        };
        let [x0h, x0l, x1h, x1l] = self.columns;
        let width =
            u32::from(u16::from_be_bytes([x1h, x1l]).wrapping_sub(u16::from_be_bytes([x0h, x0l])))
                + 1;
        let row_bytes = 2 * width;
        let [y0h, y0l, y1h, y1l] = self.rows;
        let (y0, y1) = (
            u16::from_be_bytes([y0h, y0l]),
            u16::from_be_bytes([y1h, y1l]),
        );
        stream.columns == self.columns
            && stream.bytes % row_bytes == 0
            && u32::from(y0) == u32::from(stream.first) + stream.bytes / row_bytes
            && y1 <= stream.last
    }
}

impl<B: DmaSpi, DC: OutputPin> DmaInterface<B, DC> {
    /// An interface on `bus` with data/command line `dc`, sending pixels by DMA from the two
    /// buffers `buffers` (a row of the display's pixels each, for one transfer a row), on a
    /// panel whose last row mipidsi addresses as `last_row` (its height less one, plus its
    /// offset).
    pub fn new(bus: B, dc: DC, buffers: [&'static mut [u8]; 2], last_row: u16) -> Self {
        let [filling, idle] = buffers;
        Self {
            bus,
            dc,
            filling,
            filled: 0,
            idle: Some(idle),
            window: Window {
                columns: [0; 4],
                rows: [0; 4],
                last_row,
                open: None,
            },
        }
    }

    /// Sends `command` and its `args` once the transfer in flight is done and the SPI idle.
    fn command(&mut self, command: u8, args: &[u8]) -> Result<(), DC::Error> {
        let sent = self.bus.finish();
        self.keep(sent);
        self.dc.set_low()?;
        self.write(&[command]);
        self.dc.set_high()?;
        self.write(args);
        Ok(())
    }

    /// Opens a stream for the rectangle asked: its columns, its rows from its first to the
    /// panel's last (or its own, if further), and the start of its pixels.
    fn open(&mut self) -> Result<(), DC::Error> {
        let Window {
            columns,
            rows,
            last_row,
            ..
        } = self.window;
        let [y0h, y0l, y1h, y1l] = rows;
        let (first, last) = (
            u16::from_be_bytes([y0h, y0l]),
            u16::from_be_bytes([y1h, y1l]).max(last_row),
        );
        let [lh, ll] = last.to_be_bytes();
        self.command(COLUMNS, &columns)?;
        self.command(ROWS, &[y0h, y0l, lh, ll])?;
        self.command(WRITE, &[])?;
        self.window.open = Some(Stream {
            columns,
            first,
            last,
            bytes: 0,
        });
        Ok(())
    }

    /// Keeps `sent`, the buffer of a transfer waited for, as the idle one.
    fn keep(&mut self, sent: Option<&'static mut [u8]>) {
        if let Some(buffer) = sent {
            self.idle = Some(buffer);
        }
    }

    /// Writes `bytes` while the CPU waits.
    fn write(&mut self, bytes: &[u8]) {
        let sent = self.bus.write(bytes);
        self.keep(sent);
    }

    /// Whether the buffer is full: a whole buffer to send by DMA.
    fn is_full(&self) -> bool {
        !self.filling.is_empty() && self.filled == self.filling.len()
    }

    /// Sends the full buffer by DMA and takes the other to fill.
    fn send_filled(&mut self) {
        let full = mem::take(&mut self.filling);
        let sent = self.bus.send(full);
        self.keep(sent);
        self.filling = self.idle.take().unwrap_or_default();
        self.filled = 0;
    }

    /// Writes what the buffer holds short of full while the CPU waits: the end of a rectangle
    /// of pixels that is not a whole number of buffers.
    fn write_filled(&mut self) {
        if self.filled > 0 {
            let sent = self
                .bus
                .write(self.filling.get(..self.filled).unwrap_or_default());
            self.keep(sent);
            self.filled = 0;
        }
    }
}

impl<B: DmaSpi, DC: OutputPin> Interface for DmaInterface<B, DC> {
    type Word = u8;
    type Error = DC::Error;

    const KIND: InterfaceKind = InterfaceKind::Serial4Line;

    fn send_command(&mut self, command: u8, args: &[u8]) -> Result<(), Self::Error> {
        match (command, <[u8; 4]>::try_from(args)) {
            (COLUMNS, Ok(columns)) => self.window.columns = columns,
            (ROWS, Ok(rows)) => self.window.rows = rows,
            (WRITE, _) if args.is_empty() && self.window.continues() => {}
            (WRITE, _) if args.is_empty() => self.open()?,
            _ => {
                self.window.open = None;
                self.command(command, args)?;
            }
        }
        Ok(())
    }

    fn send_pixels<const N: usize>(
        &mut self,
        pixels: impl IntoIterator<Item = [u8; N]>,
    ) -> Result<(), Self::Error> {
        let mut pixels = pixels.into_iter().peekable();
        let mut bytes = 0;
        while pixels.peek().is_some() {
            let room = self.filling.get_mut(self.filled..).unwrap_or_default();
            if room.len() < N {
                // Full: by DMA if it is, else (a buffer that is not a whole number of pixels)
                // while the CPU waits.
                if self.is_full() {
                    self.send_filled();
                } else {
                    self.write_filled();
                }
                if self.filling.len() < N {
                    // No buffer to fill (both held by a transfer: never, by construction): the
                    // pixels go as the CPU writes them.
                    for pixel in pixels.by_ref() {
                        self.write(&pixel);
                        bytes += N;
                    }
                }
                continue;
            }
            for (slot, pixel) in room.chunks_exact_mut(N).zip(&mut pixels) {
                slot.copy_from_slice(&pixel);
                self.filled += N;
                bytes += N;
            }
        }
        if self.is_full() {
            self.send_filled();
        }
        self.write_filled();
        if let Some(stream) = &mut self.window.open {
            stream.bytes = stream
                .bytes
                .saturating_add(u32::try_from(bytes).unwrap_or(u32::MAX));
        }
        Ok(())
    }

    fn send_repeated_pixel<const N: usize>(
        &mut self,
        pixel: [u8; N],
        count: u32,
    ) -> Result<(), Self::Error> {
        self.send_pixels(core::iter::repeat_n(pixel, count as usize))
    }
}

/// Implements [`DmaSpi`] for `SpiDma<CH, S>`, a DMA channel `CH` of the HAL `$hal` (`rp2040_hal`
/// or `rp235x_hal`) and its enabled 8-bit SPI `S`, in the board crate that invokes it:
/// `SpiDma::new(channel, spi)`. After a transfer it drains what the SPI received meanwhile
/// (the display answers nothing; the HAL's blocking writes read one word for each sent).
#[macro_export]
macro_rules! rp_spi_dma {
    ($hal:ident) => {
        /// The display's SPI and the DMA channel that feeds it (`obscura_firmware::rp_spi_dma`).
        struct SpiDma<CH, S>(Option<SpiDmaState<CH, S>>)
        where
            CH: $hal::dma::SingleChannel,
            S: $hal::dma::WriteTarget<TransmittedWord = u8>;

        /// Idle, or sending a buffer.
        enum SpiDmaState<CH, S>
        where
            CH: $hal::dma::SingleChannel,
            S: $hal::dma::WriteTarget<TransmittedWord = u8>,
        {
            Idle(CH, S),
            Sending($hal::dma::single_buffer::Transfer<CH, &'static mut [u8], S>),
        }

        impl<CH, S> SpiDma<CH, S>
        where
            CH: $hal::dma::SingleChannel,
            S: $hal::dma::WriteTarget<TransmittedWord = u8>
                + embedded_hal::spi::SpiBus<u8>
                + embedded_hal_nb::spi::FullDuplex<u8>,
        {
            /// The SPI `spi`, fed by DMA channel `channel`.
            fn new(channel: CH, spi: S) -> Self {
                Self(Some(SpiDmaState::Idle(channel, spi)))
            }

            /// Waits for the transfer in flight: the channel and SPI, idle, and its buffer.
            fn idle(&mut self) -> Option<(CH, S, Option<&'static mut [u8]>)> {
                match self.0.take()? {
                    SpiDmaState::Idle(channel, spi) => Some((channel, spi, None)),
                    SpiDmaState::Sending(transfer) => {
                        let (channel, buffer, mut spi) = transfer.wait();
                        let _ = embedded_hal::spi::SpiBus::flush(&mut spi);
                        while embedded_hal_nb::spi::FullDuplex::read(&mut spi).is_ok() {}
                        Some((channel, spi, Some(buffer)))
                    }
                }
            }
        }

        impl<CH, S> $crate::dma_display::DmaSpi for SpiDma<CH, S>
        where
            CH: $hal::dma::SingleChannel,
            S: $hal::dma::WriteTarget<TransmittedWord = u8>
                + embedded_hal::spi::SpiBus<u8>
                + embedded_hal_nb::spi::FullDuplex<u8>,
        {
            fn write(&mut self, bytes: &[u8]) -> Option<&'static mut [u8]> {
                let (channel, mut spi, previous) = self.idle()?;
                let _ = embedded_hal::spi::SpiBus::write(&mut spi, bytes);
                let _ = embedded_hal::spi::SpiBus::flush(&mut spi);
                self.0 = Some(SpiDmaState::Idle(channel, spi));
                previous
            }

            fn send(&mut self, buffer: &'static mut [u8]) -> Option<&'static mut [u8]> {
                let (channel, spi, previous) = self.idle()?;
                let transfer = $hal::dma::single_buffer::Config::new(channel, buffer, spi).start();
                self.0 = Some(SpiDmaState::Sending(transfer));
                previous
            }

            fn finish(&mut self) -> Option<&'static mut [u8]> {
                let (channel, spi, previous) = self.idle()?;
                self.0 = Some(SpiDmaState::Idle(channel, spi));
                previous
            }
        }
    };
}
