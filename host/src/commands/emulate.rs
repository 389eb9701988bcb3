//! `obscura emulate`: the Raspberry Pi Pico's own image (`boards/pico`, as a user flashes it)
//! run in an RP2040 emulator ([`crate::rp2040`]); the picture its SPI writes into the ST7789
//! held to the host's RGB565 frame of the same scene, format, row order and dither, bit for bit.

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
    // The Pico's image needs its Rust target, not QEMU.
    firmware::check_rust_target(TARGET)?;
    rp2040::prepare()?;
    let board = TARGET.board();
    let elf = firmware::build_package(board.package, TARGET.triple(), &settings)?;
    let request = Request::new(scene.desc(), (SIDE, SIDE), methods);
    let expected = prepare(format, &request)?.rgb565_frame(presentation, &mut |_, _| {})?;
    let writes: u64 = presentation
        .order
        .rows(SIDE)
        .map(|(_, rows)| u64::from(rows) * u64::from(SIDE))
        .sum();
    eprintln!("running {} in rp2040js", elf.display());
    let run = rp2040::run(&elf, &args.out_dir, writes, args.timeout)?;
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
    if let Some(e) = estimate {
        say!(
            "the harness's estimate for the Pico: {:.0} cycles a pixel on each of its {} cores \
             (the frame's rows shared), {}",
            e.per_pixel.cycles,
            e.board.cores,
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
