//! The chart's samples axis: cost against accuracy of `whitted` by 1, 4 and 16 rays per pixel
//! and by adaptive samples (Whitted's corners, split to 4 and to 16 cells), in `i16f16` on both
//! microcontrollers and the host and in `f32` on the M4F and the host (soft-float `f32` on the
//! M0 costs its 3.5 times at every count, as the main chart shows). Accuracy is against an f64
//! render of [`CONVERGED`] rays per pixel: how far each image is from the converged picture,
//! its numeric error included.

use crate::cli::ChartArgs;
use crate::firmware::{self, Target};
use crate::metrics::accuracy;
use crate::output::say;
use crate::plot::{self, StabilitySeries};
use crate::render::{AnyFormat, Request, all_cores, prepare, prepare_reference};
use crate::timing::frame_ms;
use anyhow::{Context, Result, bail};
use obscura::{Methods, scenes};
use obscura_scene::{FirmwareSettings, FormatChoice, FrameSettings, Variants};
use obscura_scene::{Format, OwnedScene, Sampling};
use std::path::Path;
use std::time::Duration;

/// The scene measured.
const SCENE: &str = "whitted";

/// Rays per pixel of the f64 render the images are measured against.
const CONVERGED: u16 = 256;

/// The samplings, as (rays per pixel, adaptive): 1, 4 and 16 rays, and adaptive samples split
/// to 4 and to 16 cells.
const SAMPLINGS: [(u16, bool); 5] = [(1, false), (4, false), (16, false), (4, true), (16, true)];

/// The formats on each machine.
const FORMATS: [(Target, &[Format]); 2] = [
    (Target::M4f, &[Format::I16f16, Format::F32]),
    (Target::M0, &[Format::I16f16]),
];

/// The host's formats: the microcontrollers' together.
const HOST_FORMATS: [Format; 2] = [Format::I16f16, Format::F32];

/// One sampling of the scene in one format: its cost three ways and its distance from
/// converged.
#[derive(Debug)]
struct Point {
    format: Format,
    samples: u16,
    adaptive: bool,
    m4f_instructions_per_pixel: Option<f64>,
    m0_instructions_per_pixel: Option<f64>,
    host_ns_per_pixel: f64,
    psnr_db: f64,
}

impl Point {
    /// The sampling in words: "4" or "adaptive 16".
    fn sampling(&self) -> String {
        if self.adaptive {
            format!("adaptive {}", self.samples)
        } else {
            self.samples.to_string()
        }
    }
}

/// `whitted` with `samples` rays per pixel, adaptive or not.
fn scene((samples, adaptive): (u16, bool)) -> Result<OwnedScene> {
    let built_in = scenes::find(SCENE).context("the built-in scene is missing")?;
    let mut scene = OwnedScene::from_desc(&built_in.desc);
    scene.samples = samples;
    scene.adaptive_samples = adaptive;
    Ok(scene)
}

/// Measures every sampling, writes `samples-accuracy.csv`, `.svg` and `.png` to the chart's
/// directory and prints the table.
pub fn run(args: &ChartArgs) -> Result<()> {
    let (width, height) = args.size;
    let costs = if args.no_firmware {
        Vec::new()
    } else {
        firmware_costs(args)?
    };
    eprintln!(
        "measuring {SCENE} by {} samplings on the host at {width}x{height}, against f64 with \
         {CONVERGED} rays per pixel",
        SAMPLINGS.len()
    );
    let threads = all_cores();
    let converged_scene = scene((CONVERGED, false))?;
    let converged_request = Request::new(converged_scene.desc(), args.size, Methods::LECTURE);
    let converged =
        prepare_reference(&converged_request)?.render(threads, Some("converged f64"))?;
    let no_objects = vec![None; (width * height) as usize];
    let mut prepared: Vec<Box<dyn AnyFormat>> = Vec::new();
    let mut points = Vec::new();
    for sampling in SAMPLINGS {
        let owned = scene(sampling)?;
        let desc = owned.desc();
        for format in HOST_FORMATS {
            let request = Request::new(desc, args.size, Methods::LECTURE);
            let contender = prepare(format, &request)?;
            let image = contender.render(threads, None)?;
            let cost = |target| {
                costs
                    .iter()
                    .find(|c: &&Cost| {
                        c.target == target && c.format == format && c.sampling == sampling
                    })
                    .map(|c| c.instructions_per_pixel)
            };
            points.push(Point {
                format,
                samples: sampling.0,
                adaptive: sampling.1,
                m4f_instructions_per_pixel: cost(Target::M4f),
                m0_instructions_per_pixel: cost(Target::M0),
                host_ns_per_pixel: 0.0,
                psnr_db: accuracy(&image, &converged, &no_objects, &no_objects).psnr_db,
            });
            prepared.push(contender);
        }
    }
    let times = frame_ms(args.runs, &prepared);
    let pixels = f64::from(width) * f64::from(height);
    for (point, ms) in points.iter_mut().zip(times) {
        point.host_ns_per_pixel = ms * 1e6 / pixels;
    }
    let csv = args.out_dir.join("samples-accuracy.csv");
    write_csv(&points, &csv).with_context(|| format!("cannot write {}", csv.display()))?;
    let (svg, png) = (
        args.out_dir.join("samples-accuracy.svg"),
        args.out_dir.join("samples-accuracy.png"),
    );
    plot::stability(
        "whitted: rays per pixel, fixed and adaptive, against cost and distance from converged",
        &series(&points),
        &svg,
        &png,
    )?;
    print_table(&points)?;
    say!(
        "wrote {}, {} and {}",
        csv.display(),
        svg.display(),
        png.display()
    )?;
    Ok(())
}

/// What a firmware run measured of one sampling in one format.
#[derive(Debug)]
struct Cost {
    target: Target,
    format: Format,
    sampling: (u16, bool),
    instructions_per_pixel: f64,
}

/// Instructions per pixel of every sampling on each microcontroller: one firmware image per
/// target and sampling, its frames held to the host's bit for bit.
fn firmware_costs(args: &ChartArgs) -> Result<Vec<Cost>> {
    let mut costs = Vec::new();
    for (target, formats) in FORMATS {
        firmware::check_prerequisites(target)?;
        for sampling in SAMPLINGS {
            let (samples, adaptive) = sampling;
            let settings = FirmwareSettings {
                frames: FrameSettings {
                    scene: vec![SCENE.to_owned()],
                    format: formats.iter().copied().map(FormatChoice::Given).collect(),
                    variants: Variants::None,
                },
                sampling: Sampling {
                    samples: Some(samples),
                    adaptive_samples: Some(adaptive),
                    ..Sampling::default()
                },
                ..FirmwareSettings::default()
            };
            let elf = firmware::build(target, &settings)?;
            let dir = args.frames_dir.join(format!(
                "{}-samples-{samples}{}",
                target.name(),
                if adaptive { "-adaptive" } else { "" }
            ));
            std::fs::create_dir_all(&dir)
                .with_context(|| format!("cannot create {}", dir.display()))?;
            eprintln!(
                "running {SCENE} by {samples} samples{} on the {} under QEMU",
                if adaptive { ", adaptive," } else { "" },
                target.name()
            );
            let frames =
                firmware::run(target, &elf, &dir, Duration::from_secs(args.timeout), None)?;
            let desc = scene(sampling)?;
            for &format in formats {
                let frame = frames
                    .iter()
                    .find(|f| f.format == format.name())
                    .with_context(|| format!("the firmware reported no frame in {format}"))?;
                let (_, _, differing) = firmware::compare_frame(&desc.desc(), format, frame, &dir)?;
                if format.is_fixed_point() && !differing.is_empty() {
                    bail!(
                        "{SCENE} by {samples} samples in {format}: the firmware's frame differs \
                         from the host's in {} pixels",
                        differing.len()
                    );
                }
                let pixels = f64::from(frame.width) * f64::from(frame.height);
                costs.push(Cost {
                    target,
                    format,
                    sampling,
                    instructions_per_pixel: target.instructions(frame.ticks) as f64 / pixels,
                });
            }
        }
    }
    Ok(costs)
}

/// The chart's lines: a panel per machine, a line per format and kind of sampling through its
/// sample counts.
fn series(points: &[Point]) -> Vec<StabilitySeries> {
    type Cost = fn(&Point) -> Option<f64>;
    let machines: [(&str, &str, Cost); 3] = [
        ("Cortex-M4F", "instructions / pixel", |p| {
            p.m4f_instructions_per_pixel
        }),
        ("Cortex-M0", "instructions / pixel", |p| {
            p.m0_instructions_per_pixel
        }),
        ("host", "ns / pixel (1 thread)", |p| {
            Some(p.host_ns_per_pixel)
        }),
    ];
    let mut all = Vec::new();
    for (machine, unit, cost) in machines {
        for format in HOST_FORMATS {
            for adaptive in [false, true] {
                let line: Vec<(f64, Option<f64>)> = points
                    .iter()
                    .filter(|p| p.format == format && p.adaptive == adaptive)
                    .filter_map(|p| Some((cost(p)?, Some(p.psnr_db))))
                    .collect();
                if line.is_empty() {
                    continue;
                }
                all.push(StabilitySeries {
                    case: format!("{SCENE} on the {machine}"),
                    x_label: unit.to_owned(),
                    y_label: format!("PSNR vs f64 with {CONVERGED} rays/pixel (dB)"),
                    log_x: true,
                    format: format.name().to_owned(),
                    method: if adaptive {
                        "adaptive 4, 16"
                    } else {
                        "1, 4, 16 rays"
                    }
                    .to_owned(),
                    points: line,
                });
            }
        }
    }
    all
}

/// Writes the points as CSV to `path`.
fn write_csv(points: &[Point], path: &Path) -> Result<()> {
    let mut writer = csv::Writer::from_path(path)?;
    writer.write_record([
        "scene",
        "format",
        "samples",
        "adaptive",
        "m4f_instructions_per_pixel",
        "m0_instructions_per_pixel",
        "host_ns_per_pixel",
        "psnr_converged_db",
    ])?;
    let number = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x:.1}"));
    for p in points {
        writer.write_record([
            SCENE.to_owned(),
            p.format.name().to_owned(),
            p.samples.to_string(),
            p.adaptive.to_string(),
            number(p.m4f_instructions_per_pixel),
            number(p.m0_instructions_per_pixel),
            format!("{:.1}", p.host_ns_per_pixel),
            format!("{:.2}", p.psnr_db),
        ])?;
    }
    writer.flush()?;
    Ok(())
}

fn print_table(points: &[Point]) -> std::io::Result<()> {
    say!("\n{SCENE}, rays per pixel against cost (against f64 with {CONVERGED} rays per pixel):")?;
    let (cost_headings, cost_rule) = crate::cost::Machine::columns();
    say!("| format | samples |{cost_headings} PSNR (dB) |")?;
    say!("|---|---|{cost_rule}---:|")?;
    for p in points {
        let costs = super::cost_cells(
            p.m4f_instructions_per_pixel,
            p.m0_instructions_per_pixel,
            p.host_ns_per_pixel,
        );
        say!(
            "| {} | {} |{costs} {:.2} |",
            p.format,
            p.sampling(),
            p.psnr_db
        )?;
    }
    Ok(())
}
