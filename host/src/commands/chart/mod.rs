//! `obscura chart`: speed against accuracy for every format and method variant that makes
//! sense, on both built-in scenes. Cost three ways (instructions per pixel on the Cortex-M4F and
//! the Cortex-M0, counted under QEMU; host time per pixel, timed in one run), error two ways
//! (PSNR and object mismatch against f64), and the Pareto front of each pairing. Then the
//! sampling axes ([`sampling`]): rays per pixel, fixed and adaptive, and pixels, exact and
//! adaptive, against cost.

mod sampling;

use crate::analysis::TARGET_PSNR;
use crate::cli::ChartArgs;
use crate::cost::{self, Machine};
use crate::firmware::{self, Target};
use crate::metrics::accuracy;
use crate::output::{self, say};
use crate::pareto;
use crate::plot::{self, SpeedPoint};
use crate::render::{AnyFormat, Request, all_cores, prepare, prepare_reference};
use crate::timing::frame_ms;
use anyhow::{Context, Result, bail};
use obscura::Methods;
use obscura::scenes::{self, BuiltIn};
use obscura_scene::Format;
use obscura_scene::{FirmwareSettings, FormatChoice, FrameSettings, Variants};
use std::collections::HashMap;
use std::io;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// One variant: a scene in a format by some methods.
struct Variant {
    scene: &'static BuiltIn,
    format: Format,
    methods: Methods,
}

/// Every scene × firmware format × variant of the lecture's methods that makes sense, in the
/// order the firmware draws them.
fn variants() -> Vec<Variant> {
    let base = Methods::LECTURE;
    let mut all = Vec::new();
    for scene in scenes::one_ray() {
        for &format in Format::FIRMWARE {
            for methods in base.variants() {
                if format.methods_matter(&methods, &base, scene.desc.has_triangles()) {
                    all.push(Variant {
                        scene,
                        format,
                        methods,
                    });
                }
            }
        }
    }
    all
}

pub fn run(args: &ChartArgs) -> Result<()> {
    output::check_dir(&args.out_dir)?;
    let variants = variants();
    let costs = if args.no_firmware {
        HashMap::new()
    } else {
        firmware_costs(args)?
    };
    let host = measure_on_host(args, &variants)?;
    let points = points(args, &host, &costs)?;
    let files = Files::in_dir(&args.out_dir, "speed-accuracy");
    write_csv(&points, &files.csv)
        .with_context(|| format!("cannot write {}", files.csv.display()))?;
    plot::speed_accuracy(&points, &files.svg, &files.png)?;
    print_table(&points)?;
    for (v, reason) in &host.refused {
        say!(
            "refused: {} in {} by {}: {reason}",
            v.scene.name,
            v.format,
            v.methods.to_string()
        )?;
    }
    print_recommendations(&host.measured, &points)?;
    files.say_written()?;
    sampling::SAMPLES.run(args)?;
    sampling::PIXELS.run(args)
}

/// A chart's files: its points as CSV, and its picture as SVG and PNG.
struct Files {
    csv: PathBuf,
    svg: PathBuf,
    png: PathBuf,
}

impl Files {
    /// `STEM.csv`, `STEM.svg` and `STEM.png` in `dir`.
    fn in_dir(dir: &Path, stem: &str) -> Self {
        let file = |extension| dir.join(format!("{stem}.{extension}"));
        Self {
            csv: file("csv"),
            svg: file("svg"),
            png: file("png"),
        }
    }

    /// Says they were written.
    fn say_written(&self) -> io::Result<()> {
        say!(
            "wrote {}, {} and {}",
            self.csv.display(),
            self.svg.display(),
            self.png.display()
        )
    }
}

/// Instructions per pixel of a variant on a microcontroller.
type Costs = HashMap<(Target, &'static str, Format, Methods), f64>;

/// The microcontrollers' costs: one firmware image per flash-full of formats, each drawing every
/// variant; each run is also held to the host's frames, bit for bit in fixed point.
fn firmware_costs(args: &ChartArgs) -> Result<Costs> {
    let mut costs = Costs::new();
    for target in [Target::M4f, Target::M0] {
        firmware::check_prerequisites(target)?;
        for (i, formats) in target.chart_images().iter().enumerate() {
            let settings = FirmwareSettings {
                frames: FrameSettings {
                    scene: scenes::one_ray().map(|s| s.name.to_owned()).collect(),
                    format: formats.iter().copied().map(FormatChoice::Given).collect(),
                    variants: Variants::Each,
                },
                ..FirmwareSettings::default()
            };
            let dir = args.frames_dir.join(format!("{}-{i}", target.name()));
            std::fs::create_dir_all(&dir)
                .with_context(|| format!("cannot create {}", dir.display()))?;
            let elf = firmware::build(target, &settings, &dir.join("image.elf"))?;
            eprintln!(
                "running the chart firmware for {} ({}) under QEMU; this takes minutes",
                target.name(),
                formats
                    .iter()
                    .map(|f| f.name())
                    .collect::<Vec<_>>()
                    .join(", ")
            );
            let frames =
                firmware::run(target, &elf, &dir, Duration::from_secs(args.timeout), None)?;
            for frame in &frames {
                let (scene, format) = find(&frame.scene, &frame.format)?;
                let (_, _, differing) = firmware::compare_frame(&scene.desc, format, frame, &dir)?;
                if format.is_fixed_point() && !differing.is_empty() {
                    bail!(
                        "{} in {format} by {}: the firmware's frame differs from the host's in {} pixels",
                        scene.name,
                        frame.methods,
                        differing.len()
                    );
                }
                let pixels = f64::from(frame.width) * f64::from(frame.height);
                costs.insert(
                    (target, scene.name, format, frame.methods),
                    target.instructions(frame.ticks) as f64 / pixels,
                );
            }
        }
    }
    Ok(costs)
}

/// What the host measured of the variants: those the format holds, with their accuracy and
/// single-thread time per frame, and those it refuses with the reason.
struct HostMeasurements<'a> {
    measured: Vec<&'a Variant>,
    accuracies: Vec<crate::metrics::Accuracy>,
    times_ms: Vec<f64>,
    refused: Vec<(&'a Variant, String)>,
}

/// Accuracy against f64 (same methods, exact roots), and single-thread time per frame, all
/// variants timed in one interleaved run.
fn measure_on_host<'a>(args: &ChartArgs, variants: &'a [Variant]) -> Result<HostMeasurements<'a>> {
    let (width, height) = args.size;
    eprintln!(
        "measuring {} variants on the host at {width}x{height}",
        variants.len()
    );
    let threads = all_cores();
    let mut prepared: Vec<Box<dyn AnyFormat>> = Vec::new();
    let mut host = HostMeasurements {
        measured: Vec::new(),
        accuracies: Vec::new(),
        times_ms: Vec::new(),
        refused: Vec::new(),
    };
    for variant in variants {
        let request = Request::new(variant.scene.desc, args.size, variant.methods);
        // The scene build refuses what the format cannot hold by these methods (the firmware
        // refuses the same, by the same code): an outcome to show, not a point to plot.
        let contender = match prepare(variant.format, &request) {
            Ok(contender) => contender,
            Err(error) => {
                host.refused.push((variant, format!("{error:#}")));
                continue;
            }
        };
        let reference = prepare_reference(&request)?;
        let label = || {
            format!(
                "{} in {} by {}",
                variant.scene.name, variant.format, variant.methods
            )
        };
        let image = contender.render(threads, None).with_context(label)?;
        let truth = reference.render(threads, None).with_context(label)?;
        host.accuracies.push(accuracy(
            &image,
            &truth,
            &contender.object_map().with_context(label)?,
            &reference.object_map().with_context(label)?,
        ));
        prepared.push(contender);
        host.measured.push(variant);
    }
    host.times_ms = frame_ms(args.runs, &prepared);
    Ok(host)
}

/// The chart's points: each measured variant's costs and accuracy. Fails when a firmware ran
/// but reported no frame of a variant the host measured.
fn points(args: &ChartArgs, host: &HostMeasurements<'_>, costs: &Costs) -> Result<Vec<SpeedPoint>> {
    let pixels = f64::from(args.size.0) * f64::from(args.size.1);
    let points: Vec<SpeedPoint> = host
        .measured
        .iter()
        .zip(&host.accuracies)
        .zip(&host.times_ms)
        .map(|((v, acc), ms)| SpeedPoint {
            scene: v.scene.name.to_owned(),
            format: v.format.name().to_owned(),
            variant: v.methods.to_string(),
            m4f_instructions_per_pixel: costs
                .get(&(Target::M4f, v.scene.name, v.format, v.methods))
                .copied(),
            m0_instructions_per_pixel: costs
                .get(&(Target::M0, v.scene.name, v.format, v.methods))
                .copied(),
            host_ns_per_pixel: ms * 1e6 / pixels,
            psnr_db: acc.psnr_db,
            object_mismatch_pct: acc.object_mismatch_pct,
        })
        .collect();
    if !args.no_firmware
        && let Some(missing) = points.iter().find(|p| {
            p.m4f_instructions_per_pixel.is_none() || p.m0_instructions_per_pixel.is_none()
        })
    {
        bail!(
            "the firmware reported no frame of {} in {} by {}",
            missing.scene,
            missing.format,
            missing.variant
        );
    }
    Ok(points)
}

fn find(scene: &str, format: &str) -> Result<(&'static BuiltIn, Format)> {
    let built_in = scenes::find(scene)
        .with_context(|| format!("the firmware drew an unknown scene `{scene}`"))?;
    let format = Format::FIRMWARE
        .iter()
        .copied()
        .find(|f| f.name() == format)
        .with_context(|| format!("the firmware drew an unknown format `{format}`"))?;
    Ok((built_in, format))
}

/// The cost columns: a name and how to read the cost off a point.
type CostAxis = (&'static str, fn(&SpeedPoint) -> Option<f64>);

const COSTS: [CostAxis; 3] = [
    ("m4f", |p| p.m4f_instructions_per_pixel),
    ("m0", |p| p.m0_instructions_per_pixel),
    ("host", |p| Some(p.host_ns_per_pixel)),
];

/// Whether each point is on the Pareto front of its scene for `cost` against PSNR (when
/// `psnr`) or object mismatch.
fn fronts(points: &[SpeedPoint], cost: fn(&SpeedPoint) -> Option<f64>, psnr: bool) -> Vec<bool> {
    let mut on_front = vec![false; points.len()];
    let mut scenes: Vec<&str> = points.iter().map(|p| p.scene.as_str()).collect();
    scenes.dedup();
    for scene in scenes {
        let (members, pairs): (Vec<usize>, Vec<(f64, f64)>) = (0..points.len())
            .filter(|&i| points[i].scene == scene)
            .filter_map(|i| {
                let p = &points[i];
                let error = if psnr {
                    -p.psnr_db
                } else {
                    p.object_mismatch_pct
                };
                Some((i, (cost(p)?, error)))
            })
            .unzip();
        for (&i, front) in members.iter().zip(pareto::front(&pairs)) {
            on_front[i] = front;
        }
    }
    on_front
}

/// Writes the chart's points as CSV to `path`: the columns [`cost`] reads back, then each
/// point's accuracy, its format's narrow format, and whether it lies on each machine's Pareto
/// fronts (1 or 0).
fn write_csv(points: &[SpeedPoint], path: &Path) -> Result<()> {
    let mut all_fronts = Vec::new();
    let mut header: Vec<String> = ["scene", "format", "variant"]
        .into_iter()
        .chain(cost::COST_COLUMNS)
        .map(str::to_owned)
        .collect();
    header.extend(["psnr_db", "object_mismatch_pct", "narrow"].map(str::to_owned));
    for (name, cost) in COSTS {
        for (metric, psnr) in [("psnr", true), ("mismatch", false)] {
            header.push(format!("pareto_{name}_{metric}"));
            all_fronts.push(fronts(points, cost, psnr));
        }
    }
    let mut writer = csv::Writer::from_path(path)?;
    writer.write_record(&header)?;
    let number = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x:.4}"));
    for (i, p) in points.iter().enumerate() {
        let mut record = vec![
            p.scene.clone(),
            p.format.to_string(),
            p.variant.clone(),
            number(p.m4f_instructions_per_pixel),
            number(p.m0_instructions_per_pixel),
            format!("{:.3}", p.host_ns_per_pixel),
            if p.psnr_db.is_infinite() {
                "inf".to_owned()
            } else {
                format!("{:.3}", p.psnr_db)
            },
            format!("{:.4}", p.object_mismatch_pct),
            narrow_of(&p.format).to_owned(),
        ];
        record.extend(
            all_fronts
                .iter()
                .map(|front| u8::from(front[i]).to_string()),
        );
        writer.write_record(&record)?;
    }
    writer.flush()?;
    Ok(())
}

/// The name of the narrow format of the format named `format` (its cosines, colours and
/// weights: [`Format::narrow`]), or "–" for a name that is none of the formats.
fn narrow_of(format: &str) -> &'static str {
    Format::from_name(format).map_or("–", Format::narrow)
}

/// A row's cost cells for the machines shown ([`Machine::cells`]): instructions per pixel on the
/// M4F and the M0 ("–" where not measured), nanoseconds per pixel on the host.
fn cost_cells(m4f: Option<f64>, m0: Option<f64>, host_ns: f64) -> String {
    let count = |x: Option<f64>| x.map_or("–".to_owned(), |x| format!("{x:.0}"));
    Machine::cells(|machine| match machine {
        Machine::M4f => count(m4f),
        Machine::M0 => count(m0),
        Machine::Host => format!("{host_ns:.0}"),
    })
}

fn print_table(points: &[SpeedPoint]) -> io::Result<()> {
    let (cost_headings, cost_rule) = Machine::columns();
    say!("| scene | format | narrow | methods |{cost_headings} PSNR (dB) | object mismatch |")?;
    say!("|---|---|---|---|{cost_rule}---:|---:|")?;
    for p in points {
        let psnr = if p.psnr_db.is_infinite() {
            "∞".to_owned()
        } else {
            format!("{:.2}", p.psnr_db)
        };
        let costs = cost_cells(
            p.m4f_instructions_per_pixel,
            p.m0_instructions_per_pixel,
            p.host_ns_per_pixel,
        );
        say!(
            "| {} | {} | {} | {} |{costs} {psnr} | {:.4} % |",
            p.scene,
            p.format,
            narrow_of(&p.format),
            p.variant,
            p.object_mismatch_pct
        )?;
    }
    Ok(())
}

/// For each cost axis, the cheapest format and methods that reach [`TARGET_PSNR`] on every
/// scene (cost summed over the scenes). On a scene where the methods change nothing (a triangle
/// method, and no triangles) the lecture's run stands in for them; a scene they are refused on
/// rules them out.
fn print_recommendations(measured: &[&Variant], points: &[SpeedPoint]) -> io::Result<()> {
    say!("\nthe cheapest to reach {TARGET_PSNR} dB on every scene:")?;
    let point = |scene: &str, format: Format, methods: &Methods| {
        measured
            .iter()
            .zip(points)
            .find(|(v, _)| v.scene.name == scene && v.format == format && v.methods == *methods)
            .map(|(_, p)| p)
    };
    for (name, cost) in COSTS {
        let mut best: Option<(f64, Format, Methods)> = None;
        for candidate in measured {
            let (format, methods) = (candidate.format, candidate.methods);
            let runs: Option<Vec<&SpeedPoint>> = scenes::one_ray()
                .map(|scene| {
                    let applies = format.methods_matter(
                        &methods,
                        &Methods::LECTURE,
                        scene.desc.has_triangles(),
                    );
                    let stand_in = if applies { methods } else { Methods::LECTURE };
                    point(scene.name, format, &stand_in)
                })
                .collect();
            let Some(runs) = runs else { continue };
            let total: Option<f64> = runs.iter().map(|p| cost(p)).sum();
            let good = runs.iter().all(|p| p.psnr_db >= TARGET_PSNR);
            if let (Some(total), true) = (total, good)
                && best.is_none_or(|(b, _, _)| total < b)
            {
                best = Some((total, format, methods));
            }
        }
        match best {
            Some((_, format, methods)) => {
                say!("  {name}: {format} by {}", methods)?;
            }
            None => say!("  {name}: no measurement")?,
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_names_each_formats_narrow_format() {
        assert_eq!(narrow_of("i16f16"), "i2f14");
        assert_eq!(narrow_of("i24f8"), "i2f14");
        assert_eq!(narrow_of("i12f20"), "i2f30");
        assert_eq!(narrow_of("i32f32"), "i2f30");
        assert_eq!(narrow_of("f32"), "f32");
        assert_eq!(narrow_of("no such format"), "–");
    }
}
