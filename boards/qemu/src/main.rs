//! The QEMU back-end, for Arm (cortex-m-rt) and RISC-V (riscv-rt): each frame streams, row by
//! row, into a file on the host through semihosting (240×240 big-endian RGB565, row after row, in QEMU's working directory, named
//! after the scene, the format and the methods), and each report is a line on the host's
//! standard output:
//!
//! ```text
//! frame scene=whitted format=i16f16 methods=lecture dither=none order=top-down width=240 height=240 ticks=… stack_bytes=… storage_bytes=… fixed_storage_bytes=… file=…
//! ```
//!
//! A chart variant the scene build refuses is a line `refused scene=… format=… methods=…
//! message=…`, and one that fails `error …` likewise.
//!
//! The firmware then exits through semihosting: 0 when every frame was drawn, 1 otherwise, and
//! 1 on a panic (a line `error panic at FILE:LINE: MESSAGE`) or a hard fault.
//!
//! Text goes out through [`Text`], not as a `str`'s `Display`: that pads to a width, which no
//! line here asks for, and would add its padding code to every image.
#![no_std]
#![no_main]
#![allow(
    unsafe_code,
    reason = "semihosting calls are raw system calls to the debugger"
)]

use core::fmt::{self, Write as _};
#[cfg(target_arch = "arm")]
use cortex_m_rt::{ExceptionFrame, exception};
#[cfg(target_arch = "arm")]
use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};
#[cfg(target_arch = "arm")]
use cortex_m_semihosting::{hio, nr, syscall};
use embedded_graphics_core::pixelcolor::{IntoStorage, Rgb565};
use embedded_graphics_core::prelude::*;
use embedded_graphics_core::primitives::Rectangle;
use obscura::MethodName;
use obscura_firmware::SIDE;
use obscura_firmware::clock::Clock;
use obscura_firmware::frames::{self, Backend, Job, Report};
#[cfg(target_arch = "riscv32")]
use riscv_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};
#[cfg(target_arch = "riscv32")]
use riscv_semihosting::{hio, nr, syscall};

/// Renders every configured frame, then exits QEMU with the outcome.
#[cfg_attr(target_arch = "arm", cortex_m_rt::entry)]
#[cfg_attr(target_arch = "riscv32", riscv_rt::entry)]
fn main() -> ! {
    #[cfg(target_arch = "arm")]
    let clock = {
        let Some(peripherals) = cortex_m::Peripherals::take() else {
            exit(false);
        };
        Clock::start(peripherals.SYST)
    };
    #[cfg(target_arch = "riscv32")]
    let clock = Clock::start();
    let mut host = Host {
        all_drawn: true,
        file: FrameFile { handle: None },
    };
    frames::render_all(&mut host, &clock);
    exit(host.all_drawn);
}

fn exit(success: bool) -> ! {
    debug::exit(if success { EXIT_SUCCESS } else { EXIT_FAILURE });
    // Without a debugger to end it, wait for one.
    loop {
        #[cfg(target_arch = "arm")]
        cortex_m::asm::wfi();
        #[cfg(target_arch = "riscv32")]
        riscv::asm::wfi();
    }
}

/// Writes a line to the host's standard output, opened for it: without a shared handle, a panic
/// or a fault can say so at any time (and no `RefCell` adds its panic's message to the image).
fn say(line: fmt::Arguments<'_>) {
    if let Ok(mut out) = hio::hstdout() {
        let _ = out.write_fmt(line);
        let _ = out.write_str("\n");
    }
}

/// [`say`] with `format!`'s arguments.
macro_rules! say {
    ($($argument:tt)*) => {
        say(format_args!($($argument)*))
    };
}

/// Says where the firmware panicked, and exits with a failure.
#[panic_handler]
fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
    let message = info
        .message()
        .as_str()
        .unwrap_or("(a message with arguments)");
    match info.location() {
        Some(at) => say!(
            "error panic at {}:{}: {}",
            Text(at.file()),
            at.line(),
            Text(message)
        ),
        None => say!("error panic: {}", Text(message)),
    }
    exit(false);
}

/// Text, written as it is: a `str`'s own `Display` pads to a width.
struct Text<'a>(&'a str);

impl fmt::Display for Text<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0)
    }
}

#[cfg(target_arch = "arm")]
#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    say!("error hard fault at pc={:#010x}", frame.pc());
    exit(false);
}

/// Called before a frame's first row: with [`obscura_frame_ends`], a mark for QEMU's counting
/// plugin (`host/qemu/profile.c`), which counts each frame's instructions between the two, as
/// the clock does, for the cycle estimate. Out of line and named, so that the plugin finds it.
#[unsafe(no_mangle)]
#[inline(never)]
fn obscura_frame_begins() {
    // Not the same body as the other mark's, which the linker would fold into one.
    core::hint::black_box(1_u8);
}

/// Called after a frame's last row: see [`obscura_frame_begins`].
#[unsafe(no_mangle)]
#[inline(never)]
fn obscura_frame_ends() {
    core::hint::black_box(2_u8);
}

/// The host at the other end of the debugger.
struct Host {
    all_drawn: bool,
    /// The frame being drawn.
    file: FrameFile,
}

impl Backend for Host {
    type Display = FrameFile;

    fn begin(&mut self, job: &Job<'_>) {
        self.file = FrameFile::create(job);
        obscura_frame_begins();
    }

    fn display(&mut self) -> &mut FrameFile {
        &mut self.file
    }

    fn end(&mut self) {
        obscura_frame_ends();
        self.file.close();
    }

    fn report(&mut self, r: &Report<'_>) {
        let job = r.job;
        say!(
            "frame scene={} format={} methods={} dither={} order={} width={SIDE} height={SIDE} ticks={} stack_bytes={} storage_bytes={} fixed_storage_bytes={} file={}",
            job.name(),
            Text(job.format),
            Text(job.methods),
            Text(job.presentation.dither.name()),
            Text(job.presentation.order.name()),
            r.ticks,
            r.stack_bytes,
            r.storage_bytes,
            r.fixed_storage_bytes,
            FileName(job)
        );
    }

    fn failed(&mut self, job: &Job<'_>, why: &dyn fmt::Display) {
        self.all_drawn = false;
        say!(
            "error scene={} format={} methods={} message={why}",
            job.name(),
            Text(job.format),
            Text(job.methods)
        );
    }

    fn refused(&mut self, job: &Job<'_>, why: &dyn fmt::Display) {
        say!(
            "refused scene={} format={} methods={} message={why}",
            job.name(),
            Text(job.format),
            Text(job.methods)
        );
    }
}

/// The frame file's name: `SCENE-FORMAT-METHODS.rgb565`, the methods as they are spelled
/// everywhere (`lecture`, `sphere=stable,bias=exclude`).
struct FileName<'a>(&'a Job<'a>);

impl fmt::Display for FileName<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let job = self.0;
        write!(
            f,
            "{}-{}-{}.rgb565",
            job.name(),
            Text(job.format),
            Text(job.methods)
        )
    }
}

/// A frame file on the host, written as a 240×240 RGB565 display.
struct FrameFile {
    /// The host's file handle, or `None` when it could not be opened.
    handle: Option<usize>,
}

/// Why a frame could not be written.
#[derive(Debug)]
struct HostFileError;

impl FrameFile {
    /// Creates (or truncates) the job's frame file on the host.
    fn create(job: &Job<'_>) -> Self {
        let mut name = heapless::String::<128>::new();
        let named = write!(name, "{}\0", FileName(job)).is_ok();
        let handle = named.then(|| {
            let length = name.len() - 1;
            // SAFETY: OPEN reads `length` bytes of the NUL-terminated name, which outlives it.
            unsafe { syscall!(OPEN, name.as_ptr(), nr::open::W_TRUNC_BINARY, length) }
        });
        Self {
            handle: handle.filter(|&h| h as isize != -1),
        }
    }

    /// Writes `bytes` at byte offset `at`.
    fn write_at(&mut self, at: usize, bytes: &[u8]) -> Result<(), HostFileError> {
        let handle = self.handle.ok_or(HostFileError)?;
        // SAFETY: SEEK and WRITE read only their arguments and `bytes`, which outlives them.
        let sought = unsafe { syscall!(SEEK, handle, at) };
        let unwritten = unsafe { syscall!(WRITE, handle, bytes.as_ptr(), bytes.len()) };
        if sought == 0 && unwritten == 0 {
            Ok(())
        } else {
            Err(HostFileError)
        }
    }

    /// Closes the file; the frame is then a file with no handle, which draws nothing.
    fn close(&mut self) {
        if let Some(handle) = self.handle.take() {
            // SAFETY: CLOSE takes the handle OPEN returned, once.
            unsafe { syscall!(CLOSE, handle) };
        }
    }
}

impl OriginDimensions for FrameFile {
    fn size(&self) -> Size {
        Size::new(SIDE, SIDE)
    }
}

impl DrawTarget for FrameFile {
    type Color = Rgb565;
    type Error = HostFileError;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), HostFileError> {
        for Pixel(point, colour) in pixels {
            if let Some(offset) = offset(point) {
                self.write_at(offset, &colour.into_storage().to_be_bytes())?;
            }
        }
        Ok(())
    }

    /// Each row of the area (clipped to the display) is one seek and one write.
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colours: I,
    ) -> Result<(), HostFileError> {
        let mut colours = colours.into_iter();
        let mut row = [0_u8; 2 * SIDE as usize];
        for y in area.rows() {
            let mut start = None;
            let mut length = 0;
            for (x, colour) in area.columns().zip(&mut colours) {
                let Some(offset) = offset(Point::new(x, y)) else {
                    continue;
                };
                start.get_or_insert(offset);
                if let Some(pair) = row.get_mut(length..length + 2) {
                    pair.copy_from_slice(&colour.into_storage().to_be_bytes());
                    length += 2;
                }
            }
            if let (Some(start), Some(bytes)) = (start, row.get(..length)) {
                self.write_at(start, bytes)?;
            }
        }
        Ok(())
    }
}

/// The byte offset of a pixel in the frame file, or `None` outside the display.
fn offset(point: Point) -> Option<usize> {
    let (x, y) = (u32::try_from(point.x).ok()?, u32::try_from(point.y).ok()?);
    (x < SIDE && y < SIDE).then(|| 2 * (y * SIDE + x) as usize)
}
