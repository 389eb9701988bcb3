//! The command line: what each subcommand takes.

use crate::analysis::{TARGET_PSNR, USELESS_PSNR};
use crate::cost::Machine;
use crate::firmware::Target;
use clap::{Args, Parser, Subcommand};
use obscura::pattern::MAX_SAMPLES;
use obscura_scene::{
    FirmwareSettings, Format, FormatChoice, MethodSettings, PresentationSettings, Sampling,
};
use std::path::PathBuf;

/// Ray traces in fixed point the way a microcontroller would, and measures what that costs
/// against a floating-point reference.
#[derive(Debug, Parser)]
#[command(name = "obscura", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// List the built-in scenes (every command takes a scene file as well).
    Scenes,
    /// List the settings every command's flags and the firmware's build take, each with its
    /// environment variable and default (a Markdown table, as the book shows it).
    Settings,
    /// Range analysis of a scene: its extents and finest features, the bits each method needs,
    /// which formats hold it, the PSNR each is predicted to reach, and the cheapest that meets
    /// the target.
    Analyze(AnalyzeArgs),
    /// Render a scene to a PNG file.
    Render(RenderArgs),
    /// Render a scene in a format and in f64, and report how far apart they are.
    Compare(CompareArgs),
    /// Render a scene's camera path (its `[animation]` table) to an animated GIF, every frame
    /// built and proven for its own camera and measured against f64.
    Animate(AnimateArgs),
    /// Time single-thread renders per format against f32, and the speed-up of more threads.
    Bench(BenchArgs),
    /// Build the firmware, run it under QEMU, and check its frames against the host's, bit for
    /// bit; report instructions, stack, flash and RAM.
    Firmware(FirmwareArgs),
    /// Run the firmware's render loop on the desktop: the display's size, RGB565, its row order
    /// and dither, live in a window (or, with --headless, the final frame as a PNG).
    Preview(PreviewArgs),
    /// Build the Raspberry Pi Pico's own image, run it in an RP2040 emulator (rp2040js), decode
    /// what its SPI sends the ST7789 and check the panel's picture against the host's, bit for
    /// bit; report the SPI clock, the bytes sent and the frame's cycles.
    Emulate(EmulateArgs),
    /// Chart speed against accuracy for every format and method variant, on both scenes.
    Chart(ChartArgs),
    /// Run the stress cases where methods fail, each ending in a verdict.
    Stress(StressArgs),
    /// Try random scenes in every format and method: overflows, panics, analyze against the
    /// build, predictions against measurements; each failure written as a scene file.
    Fuzz(FuzzArgs),
    /// Write the Utah teapot as a Wavefront OBJ mesh, tessellated from Newell's Bézier patches
    /// (host/scenes/teapot.obj is --steps 3): a model of any size for a scene's `shape.mesh`.
    Teapot(TeapotArgs),
    /// Run the command of every generated block of the README and the book and write what it
    /// prints into the block (or with --check, name each block that differs).
    Book(BookArgs),
}

/// What `book` runs, and whether it writes or checks.
#[derive(Debug, Args)]
pub struct BookArgs {
    /// Write nothing: exit non-zero naming each block whose command prints something else, or
    /// writes another picture, than the page holds.
    #[arg(long)]
    pub check: bool,
    /// Leave out the blocks marked `slow` (the firmware under QEMU, the chart).
    #[arg(long)]
    pub quick: bool,
    /// Only the blocks whose page or command contains this text.
    #[arg(long)]
    pub only: Option<String>,
}

/// What `teapot` writes.
#[derive(Debug, Args)]
pub struct TeapotArgs {
    /// Quads along each side of each of the 32 patches: about 64·steps² triangles.
    #[arg(long, default_value_t = crate::teapot::SHIPPED_STEPS, value_parser = clap::value_parser!(u16).range(1..=1000))]
    pub steps: u16,
    /// The OBJ file to write.
    #[arg(short, long, default_value = "teapot.obj")]
    pub output: PathBuf,
}

/// Serializes a value by its `Display`.
pub fn serialize_display<T: std::fmt::Display, S: serde::Serializer>(
    value: &T,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.collect_str(value)
}

/// How `--format auto` chooses.
#[derive(Clone, Copy, Debug, Args)]
pub struct AutoArgs {
    /// The PSNR against f64, in dB, that `--format auto` and `analyze` aim for.
    #[arg(long, default_value_t = TARGET_PSNR, value_parser = parse_psnr)]
    pub target_psnr: f64,
    /// The machine whose cost `--format auto` and `analyze` minimise, as the chart
    /// measured it.
    #[arg(long, value_enum, default_value_t = Machine::M4f)]
    pub cost_on: Machine,
}

/// When a format given that strays far from f64 is refused.
#[derive(Clone, Copy, Debug, Args)]
pub struct RefusalArgs {
    /// Refuse a format given whose image measures below this PSNR against f64's, in dB (drawn
    /// on the host), naming the formats and methods the model (`obscura analyze`'s) predicts
    /// to reach it.
    #[arg(long, value_name = "DB", default_value_t = USELESS_PSNR, value_parser = parse_psnr)]
    pub refuse_below: f64,
    /// Draw in the format given even where it measures below --refuse-below, or f64 cannot
    /// draw the scene to check it by.
    #[arg(long)]
    pub force: bool,
}

/// What to render, at what size, in which format, by which methods.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// A built-in scene (see `obscura scenes`) or a scene file (see host/scenes/).
    pub scene: String,
    /// The number format.
    #[arg(long, value_enum, default_value = "i16f16")]
    pub format: FormatChoice,
    /// The image size, WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size, default_value = "512x512")]
    pub size: (u32, u32),
    #[command(flatten)]
    pub methods: MethodSettings,
    #[command(flatten)]
    pub sampling: Sampling,
    #[command(flatten)]
    pub auto: AutoArgs,
    #[command(flatten)]
    pub refusal: RefusalArgs,
}

/// `obscura analyze`.
#[derive(Debug, Args)]
pub struct AnalyzeArgs {
    /// A built-in scene (see `obscura scenes`) or a scene file (see host/scenes/).
    pub scene: String,
    /// The image size the PSNR is predicted for, WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size, default_value = "512x512")]
    pub size: (u32, u32),
    #[command(flatten)]
    pub methods: MethodSettings,
    #[command(flatten)]
    pub sampling: Sampling,
    #[command(flatten)]
    pub auto: AutoArgs,
}

/// `obscura render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The PNG file to write (its directory made if missing); in `out/`, where every command
    /// writes unless told otherwise.
    #[arg(short, long, default_value = "out/render.png")]
    pub output: PathBuf,
    /// Threads to render on (rows are shared out one at a time).
    #[arg(long, default_value_t = default_threads(), value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: u16,
    /// Also count the tracer's operations per pixel and phase (products, quotients, roots,
    /// sums, object tests) and print them beside the floor the scene needs.
    #[arg(long)]
    pub count: bool,
}

/// `obscura compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Where to write FORMAT.png, f64.png and diff.png.
    #[arg(long, default_value = "out")]
    pub out_dir: PathBuf,
    /// Also write the figures as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Single-thread renders to time per format; the median is reported.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u16).range(1..=1000))]
    pub runs: u16,
    /// Also measure both images against an f64 render with this many rays per pixel and
    /// shadow rays per disc light, all of them traced (such as 256): how far the scene's
    /// samples are from the converged image, beside the format's numeric error.
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=i64::from(MAX_SAMPLES)))]
    pub converged: Option<u16>,
}

/// `obscura animate`.
#[derive(Debug, Args)]
pub struct AnimateArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The animated GIF to write, looping at the path's `fps` (or `--pace-of` a board's).
    #[arg(short, long, default_value = "out/animation.gif")]
    pub output: PathBuf,
    /// Also write one row per frame (its PSNR against f64 and the other figures `compare
    /// --json` gives of accuracy) as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Play the path as this microcontroller's board would draw it (m0: the Pico, m4f: the
    /// Black Pill, m33 or rv32: the Pico 2): each frame's time estimated there for a 240×240
    /// frame in the format drawn (tracing and sending, overlapped where the board sends by
    /// DMA), printed, and the GIF's frames held that long.
    #[arg(long, value_enum)]
    pub pace_of: Option<Target>,
}

/// `obscura bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// A built-in scene (see `obscura scenes`) or a scene file (see host/scenes/).
    pub scene: String,
    /// The image size, WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size, default_value = "512x512")]
    pub size: (u32, u32),
    /// The formats to time; each is compared with f32.
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = [Format::I16f16, Format::I32f32, Format::F32, Format::F64])]
    pub formats: Vec<Format>,
    /// Renders per measurement; the median is reported.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u16).range(1..=1000))]
    pub runs: u16,
    /// The thread counts to time the first format with.
    #[arg(long, value_delimiter = ',', default_values_t = [1_u16, 2], value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Vec<u16>,
    /// Also write the figures as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
    #[command(flatten)]
    pub methods: MethodSettings,
    #[command(flatten)]
    pub sampling: Sampling,
}

/// `obscura firmware`.
#[derive(Debug, Args)]
pub struct FirmwareArgs {
    /// The microcontroller: m4f (Cortex-M4F, QEMU's netduinoplus2), m0 (Cortex-M0, QEMU's
    /// microbit), m33 (the Pico 2's Cortex-M33, QEMU's mps2-an505) or rv32 (the Pico 2's
    /// Hazard3 RISC-V cores, QEMU's virt).
    #[arg(long, value_enum)]
    pub target: Target,
    /// What the firmware draws: the scenes, formats, methods, sampling and presentation (see
    /// `obscura settings`).
    #[command(flatten)]
    pub settings: FirmwareSettings,
    /// The PSNR against f64, in dB, that `--format auto` aims for.
    #[arg(long, default_value_t = TARGET_PSNR, value_parser = parse_psnr)]
    pub target_psnr: f64,
    #[command(flatten)]
    pub refusal: RefusalArgs,
    /// Also write the figures as JSON (an array, one object per frame) to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Where QEMU runs: the firmware's frames land here as raw RGB565 and as PNG.
    #[arg(long, default_value = "out/firmware")]
    pub out_dir: PathBuf,
    /// Seconds QEMU may run before it is stopped.
    #[arg(long, default_value_t = 900)]
    pub timeout: u64,
    /// Fail unless the image fits the target's budget: flash ≤ 128 KiB on the M4F (256 KiB on
    /// the M0), RAM with the measured stack ≤ 16 KiB on both.
    #[arg(long)]
    pub budget: bool,
    /// Fail when the image takes more than this many bytes of flash (a one-scene, one-format
    /// image of spheres and a plane is to fit 32768).
    #[arg(long, value_name = "BYTES")]
    pub max_flash: Option<u64>,
    /// Also count the run's instructions by function under QEMU (a TCG plugin, built from
    /// host/qemu/profile.c by the system's C compiler) and print where they go per pixel
    /// drawn: by phase of the tracer, and the functions that take most.
    #[arg(long)]
    pub profile: bool,
}

/// A board's frame, as `preview` and `emulate` draw it: the format, the methods, the sampling and
/// the presentation.
#[derive(Debug, Args)]
pub struct BoardFrameArgs {
    /// The format (the same default as every command's and the firmware's); `auto` is the
    /// cheapest on the board's core that holds the scene and reaches --target-psnr, as `obscura
    /// firmware --format auto` picks it.
    #[arg(long, value_enum, default_value = "i16f16")]
    pub format: FormatChoice,
    /// The PSNR against f64, in dB, that `--format auto` aims for.
    #[arg(long, default_value_t = TARGET_PSNR, value_parser = parse_psnr)]
    pub target_psnr: f64,
    #[command(flatten)]
    pub methods: MethodSettings,
    #[command(flatten)]
    pub sampling: Sampling,
    #[command(flatten)]
    pub presentation: PresentationSettings,
}

/// `obscura preview`.
#[derive(Debug, Args)]
pub struct PreviewArgs {
    /// A built-in scene or a scene file.
    pub scene: String,
    /// The microcontroller whose firmware is previewed: its pace, and `auto`'s pick.
    #[arg(long, value_enum, default_value = "m4f")]
    pub target: Target,
    #[command(flatten)]
    pub frame: BoardFrameArgs,
    #[command(flatten)]
    pub refusal: RefusalArgs,
    /// No window: write the final frame as a PNG and exit (for CI, where there is no display).
    #[arg(long)]
    pub headless: bool,
    /// Where the final frame is written (always with --headless; in a window, when it closes).
    #[arg(short, long, default_value = "out/preview.png")]
    pub output: PathBuf,
}

/// `obscura emulate`: the Raspberry Pi Pico's image, whose core `auto` prices as the M0.
#[derive(Debug, Args)]
pub struct EmulateArgs {
    /// A built-in scene or a scene file (a still scene: a camera path's frame 0).
    pub scene: String,
    #[command(flatten)]
    pub frame: BoardFrameArgs,
    /// Where the panel's picture is written (panel.raw, panel.png).
    #[arg(long, default_value = "out/emulate")]
    pub out_dir: PathBuf,
    /// Seconds the emulator may run.
    #[arg(long, default_value_t = 600)]
    pub timeout: u64,
    /// What the image finds of core 1, which rp2040js does not emulate: `absent` (mailboxes
    /// whose status reads all ones, as rp2040js reads them) or `silent` (mailboxes that take
    /// words and never answer, as from a core 1 that faulted). Either way the board traces on
    /// core 0 alone.
    #[arg(long, value_enum, default_value = "absent")]
    pub core1: crate::rp2040::Core1,
    /// Check this Pico image instead of building `boards/pico`: your copy of `templates/pico`
    /// (`target/thumbv6m-none-eabi/release/NAME`), or any image that draws the scene on the
    /// Waveshare Pico-LCD-1.3's ST7789 (SPI1, data/command GP8, chip select GP9) in the
    /// format, pixels, row order and dither given.
    #[arg(long)]
    pub image: Option<PathBuf>,
}

/// `obscura chart`.
#[derive(Debug, Args)]
pub struct ChartArgs {
    /// Where to write speed-accuracy.csv, .svg and .png, and samples-accuracy's and
    /// pixels-accuracy's.
    #[arg(long, default_value = "out/chart")]
    pub out_dir: PathBuf,
    /// Where to write the frames the firmware drew under QEMU, a directory a run.
    #[arg(long, default_value = "out/chart/firmware")]
    pub frames_dir: PathBuf,
    /// The host's image size for accuracy and timing (the firmware draws 240x240).
    #[arg(long, value_parser = parse_size, default_value = "240x240")]
    pub size: (u32, u32),
    /// Single-thread renders to time per variant on the host; the median is reported.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u16).range(1..=1000))]
    pub runs: u16,
    /// Seconds each QEMU run may take before it is stopped.
    #[arg(long, default_value_t = 3600)]
    pub timeout: u64,
    /// Leave out the microcontrollers (no QEMU): host cost and accuracy only.
    #[arg(long)]
    pub no_firmware: bool,
}

/// `obscura stress`.
#[derive(Debug, Args)]
pub struct StressArgs {
    /// Cases to run (all when none is named).
    #[arg(long, value_delimiter = ',')]
    pub case: Vec<String>,
    /// Where to write stability.svg and stability.png.
    #[arg(long, default_value = "out/stress")]
    pub out_dir: PathBuf,
    /// Also write every measurement and verdict as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// `obscura fuzz`.
#[derive(Debug, Args)]
pub struct FuzzArgs {
    /// Stop starting new scenes after this many seconds (by default 60, or none with
    /// `--scenes`).
    #[arg(long)]
    pub seconds: Option<u64>,
    /// Stop after this many scenes (sooner if `--seconds` run out): the same seed and count try
    /// the same builds on any machine.
    #[arg(long)]
    pub scenes: Option<u64>,
    /// The run's seed: the same seed tries the same scenes.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Where to write a scene file for each failure.
    #[arg(long, default_value = "out/fuzz")]
    pub out_dir: PathBuf,
    /// Also write the tally and every failure as JSON to this file.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Threads to try scenes on.
    #[arg(long, default_value_t = default_threads(), value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: u16,
}

fn default_threads() -> u16 {
    std::thread::available_parallelism().map_or(1, |n| u16::try_from(n.get()).unwrap_or(u16::MAX))
}

/// Parses a PSNR target in dB: a finite positive number.
/// The highest PSNR a target may ask for: above it only identical images measure (one level
/// off in one channel of 2²⁴ RGB888 pixels is 125 dB).
const MAX_TARGET_PSNR: f64 = 200.0;

fn parse_psnr(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(db) if db > 0.0 && db <= MAX_TARGET_PSNR => Ok(db),
        _ => Err(format!(
            "`{text}` is not a PSNR to aim for: give a number of dB above 0 and at most \
             {MAX_TARGET_PSNR} (above it only identical images measure), e.g. 40"
        )),
    }
}

/// Parses "WIDTHxHEIGHT".
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let usage = || format!("`{text}` is not a size; write WIDTHxHEIGHT, e.g. 512x512");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(usage)?;
    let side = |s: &str| -> Result<u32, String> {
        let n: u32 = s.trim().parse().map_err(|_| usage())?;
        if (1..=obscura::MAX_IMAGE_SIDE).contains(&n) {
            Ok(n)
        } else {
            Err(format!(
                "each side must be 1 to {} pixels, not {n}",
                obscura::MAX_IMAGE_SIDE
            ))
        }
    };
    Ok((side(w)?, side(h)?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_bad_ones_say_why() {
        assert_eq!(parse_size("512x384"), Ok((512, 384)));
        assert_eq!(parse_size("64X64"), Ok((64, 64)));
        assert!(parse_size("512").unwrap_err().contains("WIDTHxHEIGHT"));
        assert!(parse_size("0x5").unwrap_err().contains("1 to 8192"));
        assert!(parse_size("axb").unwrap_err().contains("not a size"));
        assert!(parse_size("9000x5").unwrap_err().contains("1 to 8192"));
    }
}
