//! The firmware from the host's side: which microcontrollers it runs on under QEMU, how to
//! build it for a set of scenes and formats, how to run it and read what it reports, and how
//! much flash and RAM its image takes.

use anyhow::{Context, Result, bail};
use clap::ValueEnum;
use object::{Object, ObjectSection, SectionFlags, SectionKind};
use obscura::methods::MethodName;
use obscura::{Methods, Presentation, RowOrder};
use obscura_scene::FirmwareSettings;
use obscura_scene::Format;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A microcontroller the firmware is built for, with the QEMU machine that emulates it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, ValueEnum)]
pub enum Target {
    /// Cortex-M4F with a single-precision FPU (STM32F405, QEMU's netduinoplus2).
    M4f,
    /// Cortex-M0, no FPU, 16 KiB of RAM (nRF51 of the BBC micro:bit, QEMU's microbit).
    M0,
    /// Cortex-M33 with a single-precision FPU and the DSP extension, the Arm cores of the
    /// RP2350 (Raspberry Pi Pico 2), on Arm's AN505 image (QEMU's mps2-an505).
    M33,
    /// RV32IMAC without an FPU, as the RP2350's Hazard3 cores (QEMU's RISC-V `virt` machine).
    Rv32,
}

impl Target {
    /// The Rust target triple.
    pub fn triple(self) -> &'static str {
        match self {
            Self::M4f => "thumbv7em-none-eabihf",
            Self::M0 => "thumbv6m-none-eabi",
            Self::M33 => "thumbv8m.main-none-eabihf",
            Self::Rv32 => "riscv32imac-unknown-none-elf",
        }
    }

    /// The name the command line uses.
    pub fn name(self) -> &'static str {
        match self {
            Self::M4f => "m4f",
            Self::M0 => "m0",
            Self::M33 => "m33",
            Self::Rv32 => "rv32",
        }
    }

    /// The QEMU that emulates it, and the Debian package that has it.
    fn qemu(self) -> (&'static str, &'static str) {
        match self {
            Self::M4f | Self::M0 | Self::M33 => ("qemu-system-arm", "qemu-system-arm"),
            Self::Rv32 => ("qemu-system-riscv32", "qemu-system-misc"),
        }
    }

    /// QEMU's CPU and machine (on RISC-V with Hazard3's bit manipulation, and without
    /// firmware: the reset ROM jumps to the image).
    fn qemu_machine(self) -> &'static [&'static str] {
        match self {
            Self::M4f => &["-cpu", "cortex-m4", "-machine", "netduinoplus2"],
            Self::M0 => &["-cpu", "cortex-m0", "-machine", "microbit"],
            Self::M33 => &["-cpu", "cortex-m33", "-machine", "mps2-an505"],
            Self::Rv32 => &[
                "-cpu",
                "rv32,zba=true,zbb=true,zbs=true,zbkb=true,zbc=false",
                "-machine",
                "virt",
                "-bios",
                "none",
            ],
        }
    }

    /// The emulated core clock, which SysTick counts. With `-icount shift=0`, QEMU advances its
    /// virtual clock one nanosecond per instruction, so a tick is 10⁹/f instructions.
    pub fn core_hz(self) -> u64 {
        match self {
            Self::M4f => 168_000_000,
            Self::M0 => 16_000_000,
            Self::M33 => 20_000_000,
            // Its ticks are the instructions retired: as if a tick were a nanosecond.
            Self::Rv32 => 1_000_000_000,
        }
    }

    /// The formats of each firmware image the chart runs, every one with every method
    /// variant: formats of one kind together, as many as the flash holds (the M4F's 512 KiB
    /// four 32-bit fixed formats, the M0's 256 KiB two; `i32f32` alone; the two f32 formats).
    pub fn chart_images(self) -> Vec<Vec<Format>> {
        let of_kind = |kind: fn(&Format) -> bool| -> Vec<Format> {
            Format::FIRMWARE.iter().copied().filter(kind).collect()
        };
        let fixed_32_per_image = match self {
            Self::M4f | Self::M33 => 4,
            Self::M0 | Self::Rv32 => 2,
        };
        // Each kind, and how many of it one image holds.
        let kinds = [
            (of_kind(|f| f.is_fixed_32()), fixed_32_per_image),
            (of_kind(|f| f.is_fixed_point() && !f.is_fixed_32()), 1),
            (of_kind(|f| !f.is_fixed_point()), 2),
        ];
        kinds
            .iter()
            .flat_map(|(formats, per_image)| formats.chunks(*per_image).map(<[Format]>::to_vec))
            .collect()
    }

    /// What a firmware for this microcontroller may occupy: on the M4F a quarter of the F411's
    /// 512 KiB of flash, so that it shares the chip with an application; on the M0 the nRF51's
    /// 256 KiB; on the M33 and RV32 the M4F's, which the RP2350's 4 MiB of flash hold many
    /// times over; on all of them the 16 KiB of RAM of the micro:bit, stack included.
    pub fn budget(self) -> ImageSize {
        match self {
            Self::M4f | Self::M33 | Self::Rv32 => ImageSize {
                flash: 128 * 1024,
                ram: 16 * 1024,
            },
            Self::M0 => ImageSize {
                flash: 256 * 1024,
                ram: 16 * 1024,
            },
        }
    }

    /// The real board this project builds for this microcontroller, whose frame time
    /// `obscura firmware` estimates beside QEMU's.
    pub fn board(self) -> Board {
        match self {
            Self::M4f => Board {
                name: "Black Pill (STM32F411, Cortex-M4F)",
                package: "obscura-black-pill",
                core_hz: 100_000_000,
                cores: 1,
                // SPI1 from the 100 MHz APB2 clock, divided by 2 (`boards/black-pill`).
                spi_hz: 50_000_000,
                sends_by_dma: false,
            },
            Self::M0 => Board {
                name: "Raspberry Pi Pico (RP2040, Cortex-M0+)",
                package: "obscura-pico",
                core_hz: 125_000_000,
                cores: 2,
                spi_hz: rp_spi_hz(125_000_000, ST7789_SPI_HZ),
                sends_by_dma: true,
            },
            Self::M33 => Board {
                name: "Raspberry Pi Pico 2 (RP2350, Cortex-M33)",
                package: "obscura-pico2",
                core_hz: 150_000_000,
                cores: 2,
                spi_hz: rp_spi_hz(150_000_000, ST7789_SPI_HZ),
                sends_by_dma: true,
            },
            Self::Rv32 => Board {
                name: "Raspberry Pi Pico 2 (RP2350, Hazard3 RISC-V)",
                package: "obscura-pico2",
                core_hz: 150_000_000,
                cores: 2,
                spi_hz: rp_spi_hz(150_000_000, ST7789_SPI_HZ),
                sends_by_dma: true,
            },
        }
    }

    /// Instructions executed in `ticks` SysTick ticks.
    pub fn instructions(self, ticks: u64) -> u64 {
        ticks * 1_000_000_000 / self.core_hz()
    }
}

/// A board the firmware runs on: its core clock, how many cores trace (the Pico's two share
/// the rows, `boards/pico`) and the clock of the SPI that feeds its display.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Board {
    /// What it is called.
    pub name: &'static str,
    /// The workspace's crate that builds its firmware (`boards/`).
    pub package: &'static str,
    /// The core clock the board's firmware sets.
    pub core_hz: u64,
    /// The cores that trace rows.
    pub cores: u32,
    /// The display's SPI clock, as the board's HAL sets it from what the board asks.
    pub spi_hz: u32,
    /// Whether its display is fed by DMA while the cores trace the next rows, rows that follow
    /// one another in one address window (`obscura_firmware::dma_display`); else each row is
    /// sent, its window first, before the next is traced.
    pub sends_by_dma: bool,
}

/// A frame's seconds on a board: tracing it, sending it to the display, and the frame as the
/// board draws it ([`Board::frame_time`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameTime {
    /// Tracing, the rows shared between the cores.
    pub tracing: f64,
    /// Sending, the SPI's wire time.
    pub sending: f64,
    /// The frame: the two overlapped where the board sends by DMA, else one after the other.
    pub frame: f64,
}

impl FrameTime {
    /// Frames a second.
    pub fn per_second(self) -> f64 {
        1.0 / self.frame
    }
}

impl Board {
    /// `time` in words: tracing, sending at the board's SPI clock, how the two combine, the
    /// frame and frames a second.
    pub fn describe(self, time: FrameTime) -> String {
        format!(
            "{:.2} s tracing {} {:.1} ms sending at {:.2} MHz SPI{}: {:.2} s a frame, {:.2} frames \
             a second",
            time.tracing,
            if self.sends_by_dma { "and" } else { "then" },
            1e3 * time.sending,
            f64::from(self.spi_hz) / 1e6,
            if self.sends_by_dma {
                ", overlapped by DMA"
            } else {
                ""
            },
            time.frame,
            time.per_second()
        )
    }
}

/// The SPI clock the Pico boards ask for the ST7789 (`boards/pico`, `boards/pico2`,
/// `templates/pico`): its fastest write clock, 62.5 MHz.
pub const ST7789_SPI_HZ: u32 = 62_500_000;

/// Bytes the ST7789 is sent for each rectangle besides its pixels: CASET and RASET, a command
/// byte and four bytes of addresses each, and RAMWR's command byte (mipidsi's address window).
const WINDOW_BYTES: u32 = 11;

/// The SPI clock rp2040-hal's and rp235x-hal's `Spi::set_baudrate` set for `asked` from a
/// peripheral clock of `peri_hz`, by their own search: the smallest even prescale from 2 to 254
/// that leaves the post-divider room, then the post-divide (1 to 256) that gives the fastest
/// clock at or below `asked`. Not the nearest: 62 MHz of 125 gives 31.25.
#[must_use]
pub const fn rp_spi_hz(peri_hz: u32, asked: u32) -> u32 {
    let mut prescale = 2;
    while prescale < 254 && (peri_hz as u64) >= (prescale as u64 + 2) * 256 * asked as u64 {
        prescale += 2;
    }
    let mut post = 255;
    while post > 0 && peri_hz / (prescale * post) <= asked {
        post -= 1;
    }
    peri_hz / (prescale * (1 + post))
}

impl Board {
    /// The seconds tracing a frame of `cycles` takes, with the rows shared evenly between the
    /// cores.
    pub fn seconds(self, cycles: u64) -> f64 {
        cycles as f64 / f64::from(self.cores) / self.core_hz as f64
    }

    /// The seconds the display's SPI takes to send a frame `width` pixels wide drawn in
    /// `order` (`height` rows): two bytes a pixel, and an address window for each row (or
    /// progressive block), or where the board sends by DMA for each that does not follow the
    /// one before, at the SPI clock. The wire's time alone, without the CPU's between the
    /// bytes: a bound below the transfer.
    pub fn sending_seconds(self, order: RowOrder, width: u32, height: u32) -> f64 {
        let mut bytes = 0;
        let mut next = None;
        for (y, rows) in order.rows(height) {
            if !(self.sends_by_dma && next == Some(y)) {
                bytes += u64::from(WINDOW_BYTES);
            }
            bytes += 2 * u64::from(width) * u64::from(rows);
            next = Some(y + rows);
        }
        (8 * bytes) as f64 / f64::from(self.spi_hz)
    }

    /// The time of a frame `width`×`height` drawn in `order` whose tracing takes `tracing`
    /// seconds: where the board sends by DMA, a row is sent while the next is traced, so the
    /// frame takes the larger of tracing and sending and one row's share of the smaller (the
    /// first row's tracing, or the last's sending); else their sum.
    pub fn frame_time(self, tracing: f64, order: RowOrder, width: u32, height: u32) -> FrameTime {
        let sending = self.sending_seconds(order, width, height);
        let frame = if self.sends_by_dma {
            let rows = order.rows(height).count().max(1) as f64;
            tracing.max(sending) + tracing.min(sending) / rows
        } else {
            tracing + sending
        };
        FrameTime {
            tracing,
            sending,
            frame,
        }
    }
}

/// The workspace the harness was built from, which holds the firmware's sources.
pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// Fails with the command that installs it unless the Rust target and QEMU are there.
pub fn check_prerequisites(target: Target) -> Result<()> {
    check_rust_target(target)?;
    let (qemu, package) = target.qemu();
    let found = Command::new(qemu)
        .arg("--version")
        .stdout(Stdio::null())
        .status();
    if !found.is_ok_and(|status| status.success()) {
        bail!(
            "{qemu} is not installed; install it with: sudo apt-get install {package} (Debian, \
             Ubuntu), or see https://www.qemu.org/download/"
        );
    }
    Ok(())
}

/// Fails with the command that installs it unless the Rust target of `target` is there.
pub fn check_rust_target(target: Target) -> Result<()> {
    let sysroot = Command::new("rustc")
        .args(["--print", "sysroot"])
        .output()
        .context("cannot run rustc")?;
    let sysroot = String::from_utf8_lossy(&sysroot.stdout).trim().to_owned();
    if !Path::new(&sysroot)
        .join("lib/rustlib")
        .join(target.triple())
        .exists()
    {
        bail!(
            "the Rust target {triple} is not installed; install it with: rustup target add {triple}",
            triple = target.triple()
        );
    }
    Ok(())
}

/// Builds the QEMU firmware for `target` to draw what `settings` say (every format given, none
/// `auto`) and copies its ELF image to `image` ([`build_package`]), whose absolute path it
/// returns. Its build script proves every scene in every format (by the core's own scene
/// build, as the host does) and writes them as words.
pub fn build(target: Target, settings: &FirmwareSettings, image: &Path) -> Result<PathBuf> {
    build_package("obscura-qemu", target.triple(), settings, image)
}

/// Builds the workspace's firmware crate `package` for `triple` to draw what `settings` say,
/// and copies its ELF image to `image` (the run's own, which no other run replaces), whose
/// absolute path it returns (QEMU runs in the frames' directory). Cargo
/// writes each package's image for a target at one path, so the build and the copy hold a lock
/// (`target/.obscura-build.lock`) that every run of the harness in the workspace takes: a second
/// run started meanwhile (another terminal, a CI job beside) waits, and cannot put its image
/// in place of this one before it is copied.
pub fn build_package(
    package: &str,
    triple: &str,
    settings: &FirmwareSettings,
    image: &Path,
) -> Result<PathBuf> {
    let image =
        std::path::absolute(image).with_context(|| format!("cannot place {}", image.display()))?;
    let workspace = workspace();
    let target_dir = workspace.join("target");
    std::fs::create_dir_all(&target_dir)
        .with_context(|| format!("cannot create {}", target_dir.display()))?;
    let lock_path = target_dir.join(".obscura-build.lock");
    let lock = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&lock_path)
        .with_context(|| format!("cannot open {}", lock_path.display()))?;
    lock.lock()
        .with_context(|| format!("cannot lock {}", lock_path.display()))?;
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut command = Command::new(cargo);
    command
        .current_dir(&workspace)
        .args(["build", "--release", "-p", package])
        .args(["--target", triple]);
    for (name, value) in settings.environment() {
        match value {
            Some(value) => command.env(name, value),
            None => command.env_remove(name),
        };
    }
    let status = command.status().context("cannot run cargo")?;
    if !status.success() {
        bail!("building {package} for {triple} failed (see cargo's messages above)");
    }
    let built = target_dir.join(triple).join("release").join(package);
    std::fs::copy(&built, &image)
        .with_context(|| format!("cannot copy {} to {}", built.display(), image.display()))?;
    // Dropping the file releases the lock.
    drop(lock);
    Ok(image)
}

/// One frame as the firmware reported it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    /// The scene's name.
    pub scene: String,
    /// The format's name.
    pub format: String,
    /// The methods.
    pub methods: Methods,
    /// The order of its rows and its dither.
    pub presentation: Presentation,
    /// The image width.
    pub width: u32,
    /// The image height.
    pub height: u32,
    /// SysTick ticks of the core clock the frame took.
    pub ticks: u64,
    /// The stack's high-water mark, in bytes.
    pub stack_bytes: u64,
    /// Bytes of the scene and its ray stack, sized to the scene.
    pub storage_bytes: u64,
    /// The same with the host's fixed capacities.
    pub fixed_storage_bytes: u64,
    /// The frame file, in QEMU's working directory.
    pub file: String,
}

/// A QEMU plugin to load for a run: the shared library, and its argument.
#[derive(Clone, Copy, Debug)]
pub struct Plugin<'a> {
    /// The plugin.
    pub library: &'a Path,
    /// Its argument, `name=value`.
    pub argument: &'a str,
}

/// Runs `elf` under QEMU in `dir` (where the frames land), with `plugin` loaded if given,
/// waiting at most `timeout`, and returns the frames it reported.
pub fn run(
    target: Target,
    elf: &Path,
    dir: &Path,
    timeout: Duration,
    plugin: Option<Plugin<'_>>,
) -> Result<Vec<Frame>> {
    let plugin_args = plugin.map(|plugin| {
        let mut option = plugin.library.as_os_str().to_owned();
        option.push(",");
        option.push(plugin.argument);
        [OsString::from("-plugin"), option]
    });
    let (qemu, _) = target.qemu();
    let mut child = Command::new(qemu)
        .current_dir(dir)
        .args(target.qemu_machine())
        .args(["-nographic", "-monitor", "none", "-serial", "none"])
        .args([
            "-semihosting-config",
            "enable=on,target=native",
            "-icount",
            "shift=0",
        ])
        .args(plugin_args.iter().flatten())
        .arg("-kernel")
        .arg(elf)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .with_context(|| format!("cannot start {qemu}"))?;
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait()? {
            break status;
        }
        if start.elapsed() > timeout {
            let _ = child.kill();
            bail!(
                "the firmware did not finish within {} s under QEMU (raise --timeout?)",
                timeout.as_secs()
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let output = child.wait_with_output()?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    let errors: Vec<&str> = stdout
        .lines()
        .filter(|line| line.starts_with("error "))
        .collect();
    if !status.success() || !errors.is_empty() {
        bail!(
            "the firmware failed under QEMU ({status}):\n{}{}",
            stdout.trim_end(),
            String::from_utf8_lossy(&output.stderr)
        );
    }
    stdout
        .lines()
        .filter(|line| line.starts_with("frame "))
        .map(parse_frame)
        .collect()
}

/// Parses `frame scene=… format=… methods=… dither=… order=… width=… height=… ticks=… stack_bytes=…
/// storage_bytes=… fixed_storage_bytes=… file=…`.
fn parse_frame(line: &str) -> Result<Frame> {
    let field = |key: &str| {
        line.split_whitespace()
            .find_map(|pair| {
                pair.strip_prefix(key)
                    .and_then(|rest| rest.strip_prefix('='))
            })
            .with_context(|| format!("no {key} in the firmware's line `{line}`"))
    };
    let number = |key: &str| -> Result<u64> {
        field(key)?
            .parse()
            .with_context(|| format!("{key} is not a number in `{line}`"))
    };
    Ok(Frame {
        scene: field("scene")?.to_owned(),
        format: field("format")?.to_owned(),
        methods: field("methods")?
            .parse()
            .map_err(|e| anyhow::anyhow!("{e} in `{line}`"))?,
        presentation: Presentation {
            dither: named(field("dither")?)?,
            order: named(field("order")?)?,
        },
        width: u32::try_from(number("width")?)?,
        height: u32::try_from(number("height")?)?,
        ticks: number("ticks")?,
        stack_bytes: number("stack_bytes")?,
        storage_bytes: number("storage_bytes")?,
        fixed_storage_bytes: number("fixed_storage_bytes")?,
        file: field("file")?.to_owned(),
    })
}

/// The choice called `name`.
fn named<M: MethodName + PartialEq>(name: &str) -> Result<M> {
    M::from_name(name).with_context(|| {
        format!(
            "`{name}` is not one of {}",
            M::ALL
                .iter()
                .map(|(_, n)| *n)
                .collect::<Vec<_>>()
                .join(", ")
        )
    })
}

/// What an image occupies: flash (code, constants and the initial values of data) and static
/// RAM (data and zeroed data; the stack comes on top).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ImageSize {
    /// Bytes of flash.
    pub flash: u64,
    /// Bytes of statically allocated RAM.
    pub ram: u64,
}

impl ImageSize {
    /// Why this image, with `stack` bytes of stack on top of its static RAM, does not fit
    /// `budget`; `None` when it does.
    pub fn exceeds(self, stack: u64, budget: ImageSize) -> Option<String> {
        let ram = self.ram + stack;
        let mut over = Vec::new();
        if self.flash > budget.flash {
            over.push(format!(
                "{} bytes of flash, over the {} KiB budget",
                self.flash,
                budget.flash / 1024
            ));
        }
        if ram > budget.ram {
            over.push(format!(
                "{ram} bytes of RAM with the stack, over the {} KiB budget",
                budget.ram / 1024
            ));
        }
        (!over.is_empty()).then(|| over.join(" and "))
    }
}

/// The host's RGB565 rendering of a frame the firmware reported, and the indices of the pixels
/// where the firmware's frame (read from `dir`) differs from it.
pub fn compare_frame(
    desc: &obscura::SceneDesc<'_>,
    format: Format,
    frame: &Frame,
    dir: &Path,
) -> Result<(Vec<u16>, Vec<u16>, Vec<usize>)> {
    let request = crate::render::Request::new(*desc, (frame.width, frame.height), frame.methods);
    let host = crate::render::prepare(format, &request)?
        .rgb565_frame(frame.presentation, &mut |_, _| {})?;
    let device = read_frame(&dir.join(&frame.file), host.len())?;
    let differing = (0..host.len()).filter(|&i| host[i] != device[i]).collect();
    Ok((device, host, differing))
}

/// Reads a frame file of `pixels` big-endian RGB565 values.
fn read_frame(path: &Path, pixels: usize) -> Result<Vec<u16>> {
    let bytes = std::fs::read(path)
        .with_context(|| format!("cannot read the firmware's frame {}", path.display()))?;
    if bytes.len() != 2 * pixels {
        bail!(
            "{} holds {} bytes, not the {} of a whole frame",
            path.display(),
            bytes.len(),
            2 * pixels
        );
    }
    Ok(bytes
        .chunks_exact(2)
        .map(|pair| u16::from_be_bytes([pair[0], pair[1]]))
        .collect())
}

/// Sizes an ELF image from its allocated sections, as `size` does.
pub fn image_size(elf: &Path) -> Result<ImageSize> {
    let data = std::fs::read(elf).with_context(|| format!("cannot read {}", elf.display()))?;
    let file = object::File::parse(&*data).context("the firmware image is not an ELF file")?;
    let mut size = ImageSize { flash: 0, ram: 0 };
    for section in file.sections() {
        let allocated = matches!(section.flags(), SectionFlags::Elf { sh_flags } if sh_flags & u64::from(object::elf::SHF_ALLOC) != 0);
        // riscv-rt reserves the rest of RAM for the stack as a section; the stack is measured.
        if !allocated || section.name() == Ok(".stack") {
            continue;
        }
        match section.kind() {
            // Zero-initialised and uninitialised data take RAM only.
            SectionKind::UninitializedData | SectionKind::UninitializedTls => {
                size.ram += section.size()
            }
            // Initialised data takes RAM, and its initial values take flash.
            SectionKind::Data | SectionKind::Tls => {
                size.ram += section.size();
                size.flash += section.size();
            }
            _ => size.flash += section.size(),
        }
    }
    Ok(size)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_budget_counts_the_stack_with_the_ram_and_names_what_is_over() {
        let budget = Target::M4f.budget();
        let image = ImageSize {
            flash: 100_000,
            ram: 20,
        };
        assert_eq!(image.exceeds(4_500, budget), None);
        assert_eq!(image.exceeds(16 * 1024 - 20, budget), None);
        let ram = image.exceeds(16 * 1024 - 19, budget).unwrap();
        assert!(
            ram.contains("16385 bytes of RAM") && !ram.contains("flash"),
            "{ram}"
        );
        let big = ImageSize {
            flash: 128 * 1024 + 1,
            ram: 20,
        };
        let flash = big.exceeds(0, budget).unwrap();
        assert!(
            flash.contains("131073 bytes of flash, over the 128 KiB"),
            "{flash}"
        );
        assert_eq!(big.exceeds(0, Target::M0.budget()), None);
    }

    #[test]
    fn frame_lines_parse_and_bad_ones_say_why() {
        let line = "frame scene=whitted format=i16f16 methods=sphere=stable,bias=exclude \
                    dither=ordered order=progressive width=240 height=240 ticks=22633551 stack_bytes=4568 storage_bytes=488 \
                    fixed_storage_bytes=9000 file=whitted-i16f16.rgb565";
        let frame = parse_frame(line).unwrap();
        assert_eq!(frame.scene, "whitted");
        assert_eq!(
            (frame.width, frame.ticks, frame.stack_bytes),
            (240, 22_633_551, 4568)
        );
        assert_eq!(
            (frame.storage_bytes, frame.fixed_storage_bytes),
            (488, 9000)
        );
        assert_eq!(frame.file, "whitted-i16f16.rgb565");
        let expected = Methods {
            sphere: obscura::SphereMethod::Stable,
            bias: obscura::BiasMethod::Exclude,
            ..Methods::LECTURE
        };
        assert_eq!(frame.methods, expected);
        assert_eq!(
            frame.presentation,
            Presentation {
                dither: obscura::Dither::Ordered,
                order: RowOrder::Progressive
            }
        );
        let sideways = line.replace("bias=exclude", "rays=sideways");
        let error = parse_frame(&sideways).unwrap_err().to_string();
        assert!(
            error.contains("the rays method is per-pixel or stepped"),
            "{error}"
        );
        let error = parse_frame("frame scene=whitted").unwrap_err().to_string();
        assert!(error.contains("no format"), "{error}");
    }

    #[test]
    fn the_spi_clock_is_what_the_rp_hals_set_from_what_the_boards_ask() {
        // Half the Pico's 125 MHz exactly, where 62 MHz gets a quarter; the Pico 2's 150 MHz
        // divides to 75 (above the ST7789's 62.5) or 37.5.
        assert_eq!(rp_spi_hz(125_000_000, 62_500_000), 62_500_000);
        assert_eq!(rp_spi_hz(125_000_000, 62_000_000), 31_250_000);
        assert_eq!(rp_spi_hz(150_000_000, 62_500_000), 37_500_000);
        assert_eq!(rp_spi_hz(150_000_000, 75_000_000), 75_000_000);
        // 1 MHz: a prescale of 2 and a post-divide of 63.
        assert_eq!(rp_spi_hz(125_000_000, 1_000_000), 125_000_000 / 126);
        assert_eq!(Target::M0.board().spi_hz, 62_500_000);
        assert_eq!(Target::M33.board().spi_hz, 37_500_000);
    }

    #[test]
    fn a_frame_is_sent_as_its_rows_windows_and_pixels_at_the_spi_clock() {
        let black_pill = Target::M4f.board();
        // 240 rows of an address window (11 bytes) and 480 bytes of pixels, at 50 MHz.
        let top_down = black_pill.sending_seconds(RowOrder::TopDown, 240, 240);
        assert!(
            (top_down - 8.0 * 240.0 * 491.0 / 50e6).abs() < 1e-12,
            "{top_down}"
        );
        // A progressive frame sends each row once and each pass's blocks besides: 600 rows of
        // pixels in all.
        let progressive = black_pill.sending_seconds(RowOrder::Progressive, 240, 240);
        let expected = 8.0 * (240.0 * 11.0 + 600.0 * 480.0) / 50e6;
        assert!((progressive - expected).abs() < 1e-12, "{progressive}");
        // The Pico streams rows that follow one another through one window: one a frame top
        // down; progressively, one for the first pass's blocks of 8, which follow one another,
        // and one for each block of the others (30 of 4, 60 of 2, 120 rows).
        let pico = Target::M0.board();
        let top_down = pico.sending_seconds(RowOrder::TopDown, 240, 240);
        assert!((top_down - 8.0 * (11.0 + 240.0 * 480.0) / 62.5e6).abs() < 1e-12);
        let progressive = pico.sending_seconds(RowOrder::Progressive, 240, 240);
        let expected = 8.0 * (211.0 * 11.0 + 600.0 * 480.0) / 62.5e6;
        assert!((progressive - expected).abs() < 1e-12, "{progressive}");
    }

    #[test]
    fn a_board_that_sends_by_dma_overlaps_sending_with_tracing() {
        let (pico, black_pill) = (Target::M0.board(), Target::M4f.board());
        let sending = pico.sending_seconds(RowOrder::TopDown, 240, 240);
        // Tracing longer than sending: tracing, and the last row's sending.
        let slow = pico.frame_time(1.0, RowOrder::TopDown, 240, 240);
        assert_eq!((slow.tracing, slow.sending), (1.0, sending));
        assert!((slow.frame - (1.0 + sending / 240.0)).abs() < 1e-12);
        assert!((slow.per_second() - 1.0 / slow.frame).abs() < 1e-12);
        // Tracing shorter: sending, and the first row's tracing.
        let fast = pico.frame_time(0.001, RowOrder::TopDown, 240, 240);
        assert!((fast.frame - (sending + 0.001 / 240.0)).abs() < 1e-12);
        // Without DMA, one after the other.
        let blocking = black_pill.frame_time(1.0, RowOrder::TopDown, 240, 240);
        assert!((blocking.frame - (1.0 + blocking.sending)).abs() < 1e-12);
    }

    #[test]
    fn a_board_shares_a_frame_between_its_cores() {
        // 10 000 instructions a pixel at 240x240: 4.608 s on one core at 125 MHz, half on two.
        let pico = Target::M0.board();
        assert!((pico.seconds(10_000 * 240 * 240) - 2.304).abs() < 1e-9);
        let black_pill = Target::M4f.board();
        assert!((black_pill.seconds(100_000_000) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn ticks_convert_to_instructions_by_the_core_clock() {
        // 168 MHz: a tick is 1000/168 ≈ 5.95 instructions; 16 MHz: 62.5.
        assert_eq!(Target::M4f.instructions(168), 1000);
        assert_eq!(Target::M0.instructions(16), 1000);
    }
}
