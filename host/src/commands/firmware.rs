//! `obscura firmware`: the firmware under QEMU against the host, bit for bit, and what it costs.

use crate::cli::FirmwareArgs;
use crate::cost::Machine;
use crate::cycles::{self, Core};
use crate::firmware::{self, Target};
use crate::heatmap::heatmap;
use crate::operations;
use crate::output::{self, say};
use crate::profile::{self, Counts, Profile};
use crate::render::{Request, rgb565_image};
use anyhow::{Context, Result, bail};
use obscura::methods::MethodName;
use obscura::{Methods, Pixels, RowOrder};
use obscura_scene::firmware::{Configuration, SIDE, with_paths_as_frames};
use obscura_scene::{FirmwareSettings, Format, FormatChoice, Variants};
use serde::Serialize;
use std::collections::BTreeMap;
use std::io;
use std::path::Path;
use std::time::Duration;

/// The figures of one frame, as printed and written to JSON.
#[derive(Debug, Serialize)]
struct Report {
    target: &'static str,
    scene: String,
    format: String,
    methods: String,
    /// How the frame's pixels are found ([`obscura::Pixels`]).
    pixels: &'static str,
    order: &'static str,
    dither: &'static str,
    width: u32,
    height: u32,
    identical: bool,
    differing_pixels: usize,
    instructions_per_frame: u64,
    instructions_per_pixel: u64,
    /// Cycles on the board's core, estimated from the instructions ([`crate::cycles`]).
    cycles_per_frame: u64,
    cycles_per_pixel: u64,
    stack_bytes: u64,
    flash_bytes: u64,
    ram_bytes: u64,
    storage_bytes: u64,
    fixed_storage_bytes: u64,
    /// The corner rows the image keeps for adaptive samples or pixels, on the stack (0
    /// without).
    corner_rows_bytes: u64,
}

/// The firmware `args` ask for, as its build is to take it — `auto` resolved for the target
/// ([`super::firmware_format`]), each format once, scene files by their absolute paths (the
/// build finds them from the workspace) — and what it draws, every frame proven as the build
/// will prove it, so that what the build would refuse is refused before it.
fn configure(args: &FirmwareArgs) -> Result<(FirmwareSettings, Configuration)> {
    let mut settings = args.settings.clone();
    let methods = settings.methods.methods();
    let scenes = settings
        .frames
        .scene
        .iter()
        .map(|name| {
            let mut named = obscura_scene::load(name)?;
            settings.sampling.apply(&mut named.scene);
            Ok(named)
        })
        .collect::<Result<Vec<_>>>()?;
    // The build is given the scenes as they are (a scene file's path, found from anywhere);
    // the rest is about what it draws, a camera path's every frame.
    settings.frames.scene = scenes
        .iter()
        .map(|named| match named.path() {
            Some(path) => std::path::absolute(path)
                .map(|path| path.display().to_string())
                .with_context(|| format!("cannot find {}", path.display())),
            None => Ok(named.name.clone()),
        })
        .collect::<Result<_>>()?;
    let (mut scenes, loops) = with_paths_as_frames(scenes);
    // One image finds its pixels one way: `auto` chooses them only as the image's one format.
    let choose_pixels = settings.frames.format == [FormatChoice::Auto]
        && super::chooses_pixels(&settings.sampling, scenes.iter().map(|s| &s.scene));
    let mut formats = Vec::new();
    for &choice in &settings.frames.format {
        let aim = (Machine::from(args.target), args.target_psnr);
        let (format, pixels) =
            super::firmware_format(choice, &scenes, methods, aim, choose_pixels)?;
        if choose_pixels && pixels != Pixels::Exact {
            settings.sampling.pixels = Some(pixels);
            for named in &mut scenes {
                named.scene.pixels = pixels;
            }
        }
        if choice == FormatChoice::Given(format) {
            for named in &scenes {
                super::refuse_useless_unseen(
                    &args.refusal,
                    format,
                    &named.scene,
                    methods,
                    (SIDE, SIDE),
                )
                .with_context(|| named.name.clone())?;
            }
        }
        if !formats.contains(&format) {
            formats.push(format);
        }
    }
    settings.frames.format = formats.iter().copied().map(FormatChoice::Given).collect();
    let configuration = Configuration {
        scenes,
        loops,
        formats,
        methods,
        variants: settings.frames.variants == Variants::Each,
        presentation: settings.presentation.presentation(),
    };
    configuration.frames()?;
    Ok((settings, configuration))
}

/// How many differing pixels are listed when a frame does not match.
const LISTED: usize = 10;

pub fn run(args: &FirmwareArgs) -> Result<()> {
    let dir = args.out_dir.join(args.target.name());
    output::check_dir(&dir)?;
    if let Some(path) = &args.json {
        output::check_file(path)?;
    }
    let (settings, configuration) = configure(args)?;
    firmware::check_prerequisites(args.target)?;
    let elf = firmware::build(args.target, &settings, &dir.join("image.elf"))?;
    let size = firmware::image_size(&elf)?;
    let (frames, counts) = run_qemu(args, &elf, &dir)?;
    let (reports, mismatched) = compare(args.target, &configuration, &frames, &counts, size, &dir)?;
    print_table(args.target, &reports)?;
    if args.profile {
        print_profile(
            args.target,
            &Profile::read(&elf, &counts)?,
            &reports,
            size.flash,
        )?;
        print_cycles(args.target, &counts, &reports)?;
        for frame in configuration.frames()?.iter().filter(|f| f.proven.is_ok()) {
            let desc = frame.scene.scene.desc();
            print_operations(
                &desc,
                &frame.scene.name,
                frame.format,
                frame.methods,
                &reports,
            )?;
        }
    }
    if configuration.loops {
        print_paths(args.target, &reports)?;
        print_path_flash(args, &settings, &dir, size.flash, &reports)?;
    }
    let over = print_budget(args.target, &reports, size)?;
    if args.settings.frames.format.contains(&FormatChoice::Auto) {
        print_board_build(args, &settings)?;
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&reports)?;
        std::fs::write(path, text + "\n")
            .with_context(|| format!("cannot write {}", path.display()))?;
        say!("wrote {}", path.display())?;
    }
    if !mismatched.is_empty() {
        bail!(
            "the firmware's frames differ from the host's in fixed point: {}",
            mismatched.join(", ")
        );
    }
    if let Some(max) = args.max_flash.filter(|&max| size.flash > max) {
        bail!(
            "the firmware image takes {} bytes of flash, over the {max} of --max-flash; build \
             fewer scenes or formats into one image, or see where the flash goes with --profile",
            size.flash
        );
    }
    if let (true, Some(why)) = (args.budget, over) {
        bail!(
            "the firmware image takes {why}; build fewer scenes or formats into one image \
             (one of each is what a board needs)"
        );
    }
    Ok(())
}

/// Runs the firmware `elf` under QEMU in `dir` with the counting plugin: the frames it
/// reported, and what the plugin counted.
fn run_qemu(args: &FirmwareArgs, elf: &Path, dir: &Path) -> Result<(Vec<firmware::Frame>, Counts)> {
    eprintln!("running {} under QEMU in {}", elf.display(), dir.display());
    // QEMU runs in `dir`: the plugin names its file from there (a name only: QEMU's options
    // split at commas, which a path may hold).
    const COUNTS: &str = "counts.txt";
    let library = profile::plugin()?;
    let (begin, end) = profile::frame_markers(elf)?;
    let argument = format!("out={COUNTS},begin={begin:x},end={end:x}");
    let plugin = firmware::Plugin {
        library: &library,
        argument: &argument,
    };
    let frames = firmware::run(
        args.target,
        elf,
        dir,
        Duration::from_secs(args.timeout),
        Some(plugin),
    )?;
    let counts = Counts::read(&dir.join(COUNTS), Core::of(args.target))?;
    if counts.frames.len() != frames.len() {
        bail!(
            "QEMU's plugin counted {} frames where the firmware reported {}",
            counts.frames.len(),
            frames.len()
        );
    }
    Ok((frames, counts))
}

/// Each frame the firmware drew against the host's, its figures, and the fixed-point frames
/// that differ (its PNG and, where it differs, its difference image written to `dir`).
fn compare(
    target: Target,
    configuration: &Configuration,
    frames: &[firmware::Frame],
    counts: &Counts,
    size: firmware::ImageSize,
    dir: &Path,
) -> Result<(Vec<Report>, Vec<String>)> {
    let presentation = configuration.presentation;
    let descs: Vec<_> = configuration
        .scenes
        .iter()
        .map(|s| s.scene.desc())
        .collect();
    let corner_rows_bytes =
        (obscura_scene::build::corners_kept(&descs, SIDE) * size_of::<obscura::Corner>()) as u64;
    let mut reports = Vec::new();
    let mut mismatched = Vec::new();
    for planned in configuration.frames()?.iter().filter(|f| f.proven.is_ok()) {
        let (scene, format, methods) = (planned.scene, planned.format, planned.methods);
        let (index, frame) = frames
            .iter()
            .enumerate()
            .find(|(_, f)| {
                f.scene == scene.name
                    && f.format == format.name()
                    && f.methods == methods
                    && f.presentation == presentation
            })
            .with_context(|| {
                format!(
                    "the firmware reported no frame of {} in {format} by {methods}",
                    scene.name
                )
            })?;
        let (device, host, differing) =
            firmware::compare_frame(&scene.scene.desc(), format, frame, dir)?;
        let stem = dir.join(&frame.file);
        crate::commands::save(
            &rgb565_image(&device, frame.width),
            &stem.with_extension("png"),
        )?;
        if !differing.is_empty() {
            let diff = heatmap(
                &rgb565_image(&device, frame.width),
                &rgb565_image(&host, frame.width),
            );
            let path = stem.with_extension("diff.png");
            crate::commands::save(&diff, &path)?;
            list_differences(
                &scene.name,
                format,
                frame.width,
                &differing,
                &device,
                &host,
                &path,
            )?;
            if format.is_fixed_point() {
                mismatched.push(format!("{} in {format} by {methods}", scene.name));
            }
        }
        let pixels = u64::from(frame.width) * u64::from(frame.height);
        let instructions = target.instructions(frame.ticks);
        let cycles = frame_cycles(target, counts, index, instructions)
            .with_context(|| format!("{} in {format} by {methods}", scene.name))?;
        reports.push(Report {
            target: target.name(),
            scene: frame.scene.clone(),
            format: frame.format.clone(),
            methods: methods.to_string(),
            pixels: scene.scene.pixels.name(),
            order: presentation.order.name(),
            dither: presentation.dither.name(),
            width: frame.width,
            height: frame.height,
            identical: differing.is_empty(),
            differing_pixels: differing.len(),
            instructions_per_frame: instructions,
            instructions_per_pixel: instructions / pixels.max(1),
            cycles_per_frame: cycles.cycles,
            cycles_per_pixel: cycles.cycles / pixels.max(1),
            stack_bytes: frame.stack_bytes,
            flash_bytes: size.flash,
            ram_bytes: size.ram,
            storage_bytes: frame.storage_bytes,
            fixed_storage_bytes: frame.fixed_storage_bytes,
            corner_rows_bytes,
        });
    }
    Ok((reports, mismatched))
}

/// How closely the plugin's count of a frame must agree with the clock's: to this fraction of
/// it (the clock counts in ticks, 50 instructions each on the M33's SysTick)…
const CLOCK_AGREEMENT: u64 = 1000;
/// …and these instructions, which the plugin's window between the frame's marks holds and the
/// clock's does not (its own reads, the frame file's opening and closing).
const OUTSIDE_THE_CLOCK: u64 = 1000;

/// The cycle estimate of frame `index` of the run `counts` counted, whose clock counted
/// `instructions`: the plugin's count of the frame must agree with the clock's.
fn frame_cycles(
    target: Target,
    counts: &Counts,
    index: usize,
    instructions: u64,
) -> Result<cycles::Estimate> {
    let counted = counts
        .frames
        .get(index)
        .with_context(|| format!("QEMU's plugin counted no frame {}", index + 1))?;
    let estimate = cycles::estimate(Core::of(target), &counts.instructions, counted);
    let tolerance = instructions / CLOCK_AGREEMENT + OUTSIDE_THE_CLOCK;
    if estimate.instructions.abs_diff(instructions) > tolerance {
        bail!(
            "QEMU's plugin counted {} instructions in the frame where its clock counted \
             {instructions}: the cycle estimate would be wrong",
            estimate.instructions
        );
    }
    Ok(estimate)
}

/// Each camera path's loop on the board: its frames' times added up, each traced at the board's
/// clock and sent to the display ([`firmware::Board::frame_time`]).
fn print_paths(target: Target, reports: &[Report]) -> Result<()> {
    let board = target.board();
    // Each path and format: its frames' seconds, and how many.
    let mut paths: Vec<(&str, &str, f64, u32)> = Vec::new();
    for r in reports {
        let Some((path, _)) = obscura_scene::path_frame(&r.scene) else {
            continue;
        };
        let order = RowOrder::from_name(r.order).unwrap_or_default();
        let time = board.frame_time(board.seconds(r.cycles_per_frame), order, r.width, r.height);
        match paths
            .iter_mut()
            .find(|(p, f, ..)| *p == path && *f == r.format)
        {
            Some(entry) => {
                entry.2 += time.frame;
                entry.3 += 1;
            }
            None => paths.push((path, &r.format, time.frame, 1)),
        }
    }
    for (path, format, seconds, frames) in paths {
        say!(
            "{path}'s loop of {frames} frames in {format} on a {}, estimated in cycles and the \
             display's SPI{}: {seconds:.1} s a loop, {:.2} frames a second",
            board.name,
            if board.sends_by_dma {
                " (each frame's sending overlapped by DMA)"
            } else {
                ""
            },
            f64::from(frames) / seconds
        )?;
    }
    Ok(())
}

/// What the camera paths add to the image's `flash`: the image built again with each path
/// scene as the still picture of its frame 0 (written beside the frames in `dir`), and the
/// difference, per frame.
fn print_path_flash(
    args: &FirmwareArgs,
    settings: &FirmwareSettings,
    dir: &Path,
    flash: u64,
    reports: &[Report],
) -> Result<()> {
    let mut still = settings.clone();
    for name in &mut still.frames.scene {
        let named = obscura_scene::load(name)?;
        if named.scene.animation.is_none() {
            continue;
        }
        let stem = format!("{}-still", named.name);
        let (toml, meshes) = named.scene.at_frame(0).files(&stem)?;
        for (file, text) in meshes {
            std::fs::write(dir.join(&file), text)
                .with_context(|| format!("cannot write {}", dir.join(&file).display()))?;
        }
        let path = std::path::absolute(dir.join(format!("{stem}.toml")))?;
        std::fs::write(&path, toml).with_context(|| format!("cannot write {}", path.display()))?;
        *name = path.display().to_string();
    }
    let still_image = firmware::build(args.target, &still, &dir.join("still.elf"))?;
    let still_flash = firmware::image_size(&still_image)?.flash;
    let frames = reports
        .iter()
        .filter(|r| obscura_scene::path_frame(&r.scene).is_some())
        .count() as u64;
    let added = flash.saturating_sub(still_flash);
    say!(
        "the camera path adds {added} bytes of flash to the still image of its frame 0 \
         ({still_flash} bytes): {} a frame",
        added / frames.max(1)
    )?;
    Ok(())
}

/// The command that builds what `auto` picked for the target's board: the settings given, with
/// the formats (and pixels) `auto` took, each variable that differs from its default (and the
/// scenes and formats always).
fn print_board_build(args: &FirmwareArgs, picked: &FirmwareSettings) -> Result<()> {
    say!(
        "to build it for the {}: {}",
        args.target.board().name,
        board_build(args.target, &args.settings, picked)
    )?;
    Ok(())
}

/// [`print_board_build`]'s command, for `target`'s board, from the settings `given` and those
/// `picked`.
fn board_build(target: Target, given: &FirmwareSettings, picked: &FirmwareSettings) -> String {
    let mut given = given.clone();
    given.frames.format.clone_from(&picked.frames.format);
    given.sampling.pixels = picked.sampling.pixels;
    let defaults = FirmwareSettings::default().environment();
    let variables: Vec<String> = given
        .environment()
        .into_iter()
        .filter(|(name, value)| {
            ["OBSCURA_SCENES", "OBSCURA_FORMATS"].contains(name)
                || !defaults.contains(&(*name, value.clone()))
        })
        .filter_map(|(name, value)| value.map(|value| format!("{name}={}", quoted(&value))))
        .collect();
    format!(
        "{} cargo build --release -p {} --target {}",
        variables.join(" "),
        target.board().package,
        target.triple()
    )
}

/// `value` as a shell word: as it is where it holds nothing a shell reads, else in single quotes.
fn quoted(value: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_./,:=+-".contains(c);
    if !value.is_empty() && value.chars().all(plain) {
        value.to_owned()
    } else {
        format!("'{}'", value.replace('\'', r"'\''"))
    }
}

/// Says whether the image fits the target's budget with the most stack a frame took; what is
/// over it, if anything.
fn print_budget(
    target: Target,
    reports: &[Report],
    size: firmware::ImageSize,
) -> Result<Option<String>> {
    let budget = target.budget();
    let stack = reports.iter().map(|r| r.stack_bytes).max().unwrap_or(0);
    let over = size.exceeds(stack, budget);
    match &over {
        None => say!(
            "within the {} budget: {} of {} KiB flash, {} of {} KiB RAM with the stack",
            target.name(),
            size.flash,
            budget.flash / 1024,
            size.ram + stack,
            budget.ram / 1024
        )?,
        Some(why) => say!("over the {} budget: {why}", target.name())?,
    }
    Ok(over)
}

/// How many functions the profile lists.
const PROFILED_FUNCTIONS: usize = 12;

/// Where the run's instructions went, per pixel drawn: by phase, then the functions that took
/// most. Fails when the plugin counted fewer instructions than the clock did for the frames alone.
fn print_profile(target: Target, profile: &Profile, reports: &[Report], flash: u64) -> Result<()> {
    let pixels: u64 = reports
        .iter()
        .map(|r| u64::from(r.width) * u64::from(r.height))
        .sum();
    let frames: u64 = reports.iter().map(|r| r.instructions_per_frame).sum();
    if profile.total < frames {
        bail!(
            "QEMU's plugin counted {} instructions in the whole run, fewer than the clock's {frames} \
             for the frames alone: the profile is wrong",
            profile.total
        );
    }
    let per_pixel = |n: u64| n as f64 / pixels.max(1) as f64;
    let share = |n: u64| 100.0 * n as f64 / profile.total.max(1) as f64;
    say!(
        "\nwhere the instructions go on {} (QEMU's count at each address, by function; \
         per pixel of the {pixels} drawn; the frames alone, by the clock: {:.0} per pixel):\n",
        target.name(),
        per_pixel(frames)
    )?;
    say!("| phase | instructions per pixel | share |")?;
    say!("|---|---:|---:|")?;
    for &(phase, n) in &profile.phases {
        say!("| {phase} | {:.0} | {:.1} % |", per_pixel(n), share(n))?;
    }
    say!(
        "| the whole run | {:.0} | 100 % |",
        per_pixel(profile.total)
    )?;
    for (kind, functions) in [
        ("function of the image (out of line)", &profile.functions),
        (
            "function of the source (innermost inlined)",
            &profile.sources,
        ),
    ] {
        say!("\n| {kind} | instructions per pixel | share |")?;
        say!("|---|---:|---:|")?;
        for (name, n) in functions.iter().take(PROFILED_FUNCTIONS) {
            say!("| `{name}` | {:.0} | {:.1} % |", per_pixel(*n), share(*n))?;
        }
    }
    say!(
        "\nwhere the flash goes ({flash} bytes; code by the functions inlined at each halfword, \
         as the instructions above):\n"
    )?;
    say!("| phase | bytes | share |")?;
    say!("|---|---:|---:|")?;
    let flash_share = |n: u64| 100.0 * n as f64 / flash.max(1) as f64;
    let code: u64 = profile.code_bytes.iter().map(|(_, n)| n).sum();
    if code > flash {
        bail!(
            "the image's functions span {code} bytes, more than its {flash} of flash: the profile is wrong"
        );
    }
    for &(phase, n) in &profile.code_bytes {
        say!("| {phase} | {n} | {:.1} % |", flash_share(n))?;
    }
    let rest = flash - code;
    say!(
        "| constants, vector table and code no symbol covers | {rest} | {:.1} % |",
        flash_share(rest)
    )?;
    Ok(())
}

/// Where the frames' cycles go on the target's core, by class of instruction, per pixel drawn.
fn print_cycles(target: Target, counts: &Counts, reports: &[Report]) -> Result<()> {
    let pixels: u64 = reports
        .iter()
        .map(|r| u64::from(r.width) * u64::from(r.height))
        .sum();
    let mut frames: BTreeMap<u64, cycles::Count> = BTreeMap::new();
    for (&address, count) in counts.frames.iter().flatten() {
        let all = frames.entry(address).or_default();
        all.executed += count.executed;
        all.taken += count.taken;
    }
    let core = Core::of(target);
    let estimate = cycles::estimate(core, &counts.instructions, &frames);
    let per_pixel = |n: u64| n as f64 / pixels.max(1) as f64;
    say!(
        "\nwhere the cycles go on the {} (the frames alone, each instruction weighed by {}; per \
         pixel of the {pixels} drawn), by class of instruction:\n",
        core.name(),
        core.timings()
    )?;
    say!(
        "| instructions | per pixel | cycles per pixel | cycles per instruction | share of cycles |"
    )?;
    say!("|---|---:|---:|---:|---:|")?;
    let row = |name: &str, n: u64, c: u64| {
        say!(
            "| {name} | {:.0} | {:.0} | {:.2} | {:.1} % |",
            per_pixel(n),
            per_pixel(c),
            c as f64 / n.max(1) as f64,
            100.0 * c as f64 / estimate.cycles.max(1) as f64
        )
    };
    for &(class, n, c) in &estimate.by_class {
        row(class.name(), n, c)?;
    }
    row("all", estimate.instructions, estimate.cycles)?;
    say!(
        "\n| instruction (the most cycles first) | per pixel | cycles per pixel | cycles per instruction | share of cycles |"
    )?;
    say!("|---|---:|---:|---:|---:|")?;
    for (mnemonic, n, c) in estimate.by_mnemonic.iter().take(PROFILED_FUNCTIONS) {
        row(&format!("`{mnemonic}`"), *n, *c)?;
    }
    Ok(())
}

/// The tracer's operations per pixel for `name` in `format` by `methods`, counted on the host
/// (`render --count`), beside the instructions the target took for the frame.
fn print_operations(
    desc: &obscura::SceneDesc<'_>,
    name: &str,
    format: Format,
    methods: Methods,
    reports: &[Report],
) -> Result<()> {
    let Some(report) = reports
        .iter()
        .find(|r| r.scene == name && r.format == format.name())
    else {
        return Ok(());
    };
    let request = Request::new(*desc, (report.width, report.height), methods);
    let (count, _) = operations::count(format, &request)
        .with_context(|| format!("counting the operations of {name} in {format}"))?;
    let Some(whole) = count.lines().pop() else {
        return Ok(());
    };
    let per_operation = report.instructions_per_pixel as f64 / count.operations_per_pixel();
    say!(
        "\n{name} in {format}, the tracer's operations (counted on the host, one per textbook \
         operation; `render --count`), beside the target's {} instructions per pixel: {:.1} per \
         operation, and at that rate the floor is about {:.0} instructions per pixel:\n{}",
        report.instructions_per_pixel,
        per_operation,
        per_operation * whole.floor.0.total() as f64 / count.pixels.max(1) as f64,
        count.table()
    )?;
    Ok(())
}

fn list_differences(
    scene: &str,
    format: Format,
    width: u32,
    differing: &[usize],
    device: &[u16],
    host: &[u16],
    diff: &Path,
) -> io::Result<()> {
    say!(
        "{scene} in {format}: {} pixels differ (firmware vs host, RGB565):",
        differing.len()
    )?;
    for &i in differing.iter().take(LISTED) {
        let (x, y) = (i as u32 % width, i as u32 / width);
        say!("  ({x}, {y}): {:#06x} vs {:#06x}", device[i], host[i])?;
    }
    if differing.len() > LISTED {
        say!(
            "  … and {} more; see {}",
            differing.len() - LISTED,
            diff.display()
        )?;
    }
    Ok(())
}

fn print_table(target: Target, reports: &[Report]) -> io::Result<()> {
    say!(
        "| target | scene | format | identical to host | differing pixels | instructions/frame | instructions/pixel | cycles/pixel ({}) | stack (bytes) | flash (bytes) | static RAM (bytes) | RAM + stack (bytes) | scene + ray stack (bytes): sized / fixed |",
        Core::of(target).name()
    )?;
    say!("|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")?;
    let base = reports.first().map(|r| r.methods.as_str());
    for r in reports {
        // A variant's methods beside its scene (`--variants each`); the first row's below.
        let scene = if Some(r.methods.as_str()) == base {
            r.scene.clone()
        } else {
            format!("{} by {}", r.scene, r.methods)
        };
        say!(
            "| {} ({}) | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} / {} |",
            r.target,
            target.triple(),
            scene,
            r.format,
            if r.identical { "yes" } else { "no" },
            r.differing_pixels,
            r.instructions_per_frame,
            r.instructions_per_pixel,
            r.cycles_per_pixel,
            r.stack_bytes,
            r.flash_bytes,
            r.ram_bytes,
            r.ram_bytes + r.stack_bytes,
            r.storage_bytes,
            r.fixed_storage_bytes
        )?;
    }
    if let Some(first) = reports.first() {
        let pixels = if first.pixels == Pixels::Exact.name() {
            String::new()
        } else {
            format!("; pixels {}", first.pixels)
        };
        say!(
            "methods: {}{pixels}; rows {}; dither {}",
            first.methods,
            first.order,
            first.dither
        )?;
    }
    if let Some(bytes) = reports
        .first()
        .map(|r| r.corner_rows_bytes)
        .filter(|&b| b > 0)
    {
        say!(
            "adaptive samples or pixels keep {} corners, {bytes} bytes, on the stack (within \
             the stack column)",
            bytes / size_of::<obscura::Corner>() as u64
        )?;
    }
    say!(
        "(instructions: QEMU's exact count; cycles: an estimate, each instruction weighed by {} \
         with no wait states; \"fixed\": the host's capacities of 64 objects, 16 lights, 16 rays)",
        Core::of(target).timings()
    )?;
    let board = target.board();
    for r in reports {
        let frame_pixels = u64::from(r.width) * u64::from(r.height);
        let tracing = board.seconds(r.cycles_per_frame);
        let order = RowOrder::from_name(r.order).unwrap_or_default();
        let time = board.frame_time(tracing, order, r.width, r.height);
        say!(
            "{} in {} on a {}, {} core{} at {} MHz, estimated in cycles for a {}x{} frame: {}; \
             {:.1} s tracing 512x512",
            r.scene,
            r.format,
            board.name,
            board.cores,
            if board.cores == 1 { "" } else { "s" },
            board.core_hz / 1_000_000,
            r.width,
            r.height,
            board.describe(time),
            tracing * (512 * 512) as f64 / frame_pixels.max(1) as f64
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_board_build_names_what_auto_picked_and_what_differs_from_the_defaults() {
        let mut given = FirmwareSettings::default();
        given.frames.scene = vec!["host/scenes/pyramid.toml".to_owned()];
        given.frames.format = vec![FormatChoice::Auto];
        given.presentation.dither = obscura::Dither::Ordered;
        let mut picked = given.clone();
        picked.frames.format = vec![FormatChoice::Given(Format::I16f16)];
        picked.sampling.pixels = Some(Pixels::Adaptive(4));
        assert_eq!(
            board_build(Target::M0, &given, &picked),
            "OBSCURA_SCENES=host/scenes/pyramid.toml OBSCURA_FORMATS=i16f16 \
             OBSCURA_PIXELS=adaptive:4 OBSCURA_DITHER=ordered cargo build --release -p \
             obscura-pico --target thumbv6m-none-eabi"
        );
        // A scene file's path with a space in it stays one word.
        given.frames.scene = vec!["my scenes/it's.toml".to_owned()];
        assert!(
            board_build(Target::M33, &given, &picked)
                .starts_with(r"OBSCURA_SCENES='my scenes/it'\''s.toml' OBSCURA_FORMATS=i16f16")
        );
    }
}
