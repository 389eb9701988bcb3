//! `obscura emulate`: the Raspberry Pi Pico's own image (`boards/pico`, as a user flashes it,
//! or one given: a copy of `templates/pico`) run in an RP2040 emulator ([`crate::rp2040`]); the
//! picture its SPI writes into the ST7789 held to the host's RGB565 frame of the same scene,
//! format, row order and dither, bit for bit, and the SPI clock it set to the one the boards
//! ask.

use crate::cli::EmulateArgs;
use crate::cost::Machine;
use crate::estimate;
use crate::firmware::{self, Target};
use crate::output::{self, say};
use crate::render::{Request, prepare, rgb565_image};
use crate::rp2040;
use anyhow::{Result, bail};
use obscura::methods::MethodName;
use obscura_scene::firmware::SIDE;
use obscura_scene::{FirmwareSettings, FormatChoice, FrameSettings, NamedScene};

/// The Pico's core, as the harness names it.
const TARGET: Target = Target::M0;

pub fn run(args: &EmulateArgs) -> Result<()> {
    output::check_dir(&args.out_dir)?;
    super::on_scene(&args.scene, &args.frame.sampling, |named| {
        emulate(args, named)
    })
}

fn emulate(args: &EmulateArgs, named: &NamedScene) -> Result<()> {
    let methods = args.frame.methods.methods();
    let still = named.at_frame(0);
    let (format, scene) = super::board_scene(&args.frame, &still, Machine::from(TARGET))?;
    let pixels = scene.pixels;
    let presentation = args.frame.presentation.presentation();
    let mut sampling = args.frame.sampling;
    sampling.pixels = Some(pixels);
    let settings = FirmwareSettings {
        frames: FrameSettings {
            scene: vec![match named.path() {
                Some(path) => std::path::absolute(path)?.display().to_string(),
                None => named.name.clone(),
            }],
            format: vec![FormatChoice::Given(format)],
            ..FrameSettings::default()
        },
        methods: args.frame.methods,
        sampling,
        presentation: args.frame.presentation,
    };
    rp2040::prepare()?;
    let board = TARGET.board();
    let elf = match &args.image {
        Some(image) if image.is_file() => image.clone(),
        Some(image) => bail!(
            "{} is not a file: give the ELF image cargo built (target/thumbv6m-none-eabi/release/NAME)",
            image.display()
        ),
        None => {
            // The Pico's image needs its Rust target, not QEMU.
            firmware::check_rust_target(TARGET)?;
            let image = args.out_dir.join("image.elf");
            firmware::build_package(board.package, TARGET.triple(), &settings, &image)?
        }
    };
    let request = Request::new(scene.desc(), (SIDE, SIDE), methods);
    let expected = prepare(format, &request)?.rgb565_frame(presentation, &mut |_, _| {})?;
    let writes: u64 = presentation
        .order
        .rows(SIDE)
        .map(|(_, rows)| u64::from(rows) * u64::from(SIDE))
        .sum();
    eprintln!("running {} in rp2040js", elf.display());
    let run = rp2040::run(&elf, &args.out_dir, writes, args.timeout, args.core1)?;
    super::save(
        &rgb565_image(&run.panel, SIDE),
        &args.out_dir.join("panel.png"),
    )?;
    let differing: Vec<usize> = (0..expected.len())
        .filter(|&i| run.panel.get(i) != expected.get(i))
        .collect();
    let pixels_count = u64::from(SIDE) * u64::from(SIDE);
    let cycles_per_pixel = run.frame_cycles.map(|c| c / pixels_count);
    let estimate = estimate::frame(TARGET, format, &request.desc, methods)?;
    say!(
        "| board | scene | format | identical to host | differing pixels | SPI clock (MHz) | bytes sent | cycles/pixel (rp2040js, one core) | frame (s) |"
    )?;
    say!("|---|---|---|---|---:|---:|---:|---:|---:|")?;
    say!(
        "| {} | {} | {} | {} | {} | {:.2} | {} | {} | {:.2} |",
        board.name,
        named.name,
        crate::analysis::with_pixels(format, pixels),
        if differing.is_empty() { "yes" } else { "no" },
        differing.len(),
        run.spi_hz / 1e6,
        run.bytes,
        cycles_per_pixel.map_or("–".to_owned(), |c| c.to_string()),
        run.frame_seconds.unwrap_or(f64::NAN),
    )?;
    say!(
        "the panel: COLMOD {}, MADCTL {}, colours {}, {}; first windows {}; rows {}, dither {}",
        run.colmod
            .map_or("unset".to_owned(), |c| format!("0x{c:02x}")),
        run.madctl
            .map_or("unset".to_owned(), |m| format!("0x{m:02x}")),
        if run.inverted { "inverted" } else { "as sent" },
        if run.on && !run.sleeping {
            "awake and on"
        } else {
            "not switched on"
        },
        run.first_windows
            .iter()
            .map(|w| format!("({}..={}, {}..={})", w.x0, w.x1, w.y0, w.y1))
            .collect::<Vec<_>>()
            .join(" "),
        presentation.order.name(),
        presentation.dither.name(),
    )?;
    say!(
        "core 1 {}: the image traced every row on core 0",
        match args.core1 {
            rp2040::Core1::Absent => "absent (its mailboxes' status reads all ones)",
            rp2040::Core1::Silent => "silent (its mailboxes take words and never answer)",
        }
    )?;
    let clock_as_documented = (run.spi_hz - f64::from(board.spi_hz)).abs() < 1.0;
    say!(
        "the SPI clock the image set: {:.2} MHz, {} the {:.2} MHz the boards ask and the docs give",
        run.spi_hz / 1e6,
        if clock_as_documented { "as" } else { "not" },
        f64::from(board.spi_hz) / 1e6
    )?;
    if let Some(e) = estimate {
        say!(
            "the harness's estimate: {:.0} cycles a pixel, {:.2} s tracing a frame on one core; \
             on both, as boards/pico shares the rows: {}",
            e.per_pixel.cycles,
            e.tracing * f64::from(e.board.cores),
            e.board.describe(e.time(presentation.order))
        )?;
    }
    if !run.unknown_commands.is_empty() || !run.warnings.is_empty() {
        say!(
            "unknown commands {:02x?}; rp2040js warned: {}",
            run.unknown_commands,
            run.warnings.join("; ")
        )?;
    }
    let wall = crate::timing::or_omitted(|| format!("; emulated in {:.1} s", run.wall_seconds));
    say!(
        "the core at {:.0} MHz{wall}; wrote {}",
        run.core_hz / 1e6,
        args.out_dir.join("panel.png").display()
    )?;
    if args.image.is_none() && !clock_as_documented {
        bail!(
            "boards/pico set its SPI to {:.2} MHz where it asks for {:.2}",
            run.spi_hz / 1e6,
            f64::from(board.spi_hz) / 1e6
        );
    }
    if !differing.is_empty() {
        let listed: Vec<String> = differing
            .iter()
            .take(10)
            .map(|&i| format!("({}, {})", i % SIDE as usize, i / SIDE as usize))
            .collect();
        bail!(
            "the panel's picture differs from the host's in {} pixels, first at {}",
            differing.len(),
            listed.join(" ")
        );
    }
    Ok(())
}
