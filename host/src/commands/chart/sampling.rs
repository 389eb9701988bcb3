//! The chart's sampling axes: cost against accuracy of the ways a frame's rays are spent. Rays
//! per pixel ([`SAMPLES`]: 1, 4 and 16, and adaptive samples, Whitted's corners split to 4 and
//! to 16 cells) against an f64 render of [`CONVERGED`] rays per pixel, how far each image is
//! from the converged picture, its numeric error included; and pixels ([`PIXELS`]: exact, and
//! blocks of 2, 4 and 8 filled from their corners) against f64 with exact pixels, in PSNR and
//! in the objects the pixels show. Both in `i16f16` on both microcontrollers and the host and in
//! `f32` on the M4F and the host (soft-float `f32` on the M0 costs its 3.5 times at every
//! sampling, as the main chart shows).

use super::Files;
use crate::cli::ChartArgs;
use crate::cost;
use crate::firmware::{self, Target};
use crate::metrics::accuracy;
use crate::output::say;
use crate::plot::{self, StabilitySeries};
use crate::render::{AnyFormat, Request, all_cores, prepare, prepare_reference};
use crate::timing::frame_ms;
use anyhow::{Context, Result, bail};
use obscura::{Methods, Pixels, scenes};
use obscura_scene::{FirmwareSettings, FormatChoice, FrameSettings, Variants};
use obscura_scene::{Format, OwnedScene, Sampling};
use std::path::Path;
use std::time::Duration;

/// Rays per pixel of the f64 render the samples axis is measured against.
const CONVERGED: u16 = 256;

/// One axis: scenes drawn by several samplings, each a line of the chart's panels.
pub struct Axis {
    /// Its files' stem (`samples` writes `samples-accuracy.csv`) and its table's column.
    name: &'static str,
    /// The chart's title.
    title: &'static str,
    /// The scenes drawn.
    scenes: &'static [&'static str],
    /// The samplings, each with its label in the table and the line it belongs to.
    samplings: &'static [(Sampling, &'static str, &'static str)],
    /// What the images are measured against: `Some(n)`, f64 with n rays per pixel (the
    /// converged picture, against which the objects of one ray say nothing); `None`, f64 with
    /// exact pixels, objects too.
    converged: Option<u16>,
}

/// No sampling setting: the scene's own.
const OWN: Sampling = Sampling {
    samples: None,
    adaptive_samples: None,
    shadow_samples: None,
    adaptive_shadows: None,
    pixels: None,
};

/// `n` rays per pixel, every one traced or adaptive.
const fn rays(n: u16, adaptive: bool) -> Sampling {
    Sampling {
        samples: Some(n),
        adaptive_samples: Some(adaptive),
        ..OWN
    }
}

/// Pixels found `pixels`' way.
const fn pixels(pixels: Pixels) -> Sampling {
    Sampling {
        pixels: Some(pixels),
        ..OWN
    }
}

/// Rays per pixel on `whitted`: 1, 4 and 16, and adaptive samples split to 4 and 16 cells.
pub const SAMPLES: Axis = Axis {
    name: "samples",
    title: "whitted: rays per pixel, fixed and adaptive, against cost and distance from converged",
    scenes: &["whitted"],
    samplings: &[
        (rays(1, false), "1", "1, 4, 16 rays"),
        (rays(4, false), "4", "1, 4, 16 rays"),
        (rays(16, false), "16", "1, 4, 16 rays"),
        (rays(4, true), "adaptive 4", "adaptive 4, 16"),
        (rays(16, true), "adaptive 16", "adaptive 4, 16"),
    ],
    converged: Some(CONVERGED),
};

/// Pixels on both built-in scenes: exact, and blocks of 2, 4 and 8.
pub const PIXELS: Axis = Axis {
    name: "pixels",
    title: "whitted and shapes: exact pixels and adaptive blocks of 2, 4, 8, against cost and f64",
    scenes: &["whitted", "shapes"],
    samplings: &[
        (pixels(Pixels::Exact), "exact", "exact, adaptive:2, 4, 8"),
        (
            pixels(Pixels::Adaptive(2)),
            "adaptive:2",
            "exact, adaptive:2, 4, 8",
        ),
        (
            pixels(Pixels::Adaptive(4)),
            "adaptive:4",
            "exact, adaptive:2, 4, 8",
        ),
        (
            pixels(Pixels::Adaptive(8)),
            "adaptive:8",
            "exact, adaptive:2, 4, 8",
        ),
    ],
    converged: None,
};

/// The formats on each machine.
const FORMATS: [(Target, &[Format]); 2] = [
    (Target::M4f, &[Format::I16f16, Format::F32]),
    (Target::M0, &[Format::I16f16]),
];

/// The host's formats: the microcontrollers' together.
const HOST_FORMATS: [Format; 2] = [Format::I16f16, Format::F32];

/// One scene by one sampling in one format: its cost three ways and its accuracy.
#[derive(Debug)]
struct Point {
    scene: &'static str,
    format: Format,
    /// The sampling's index in its axis.
    sampling: usize,
    m4f_instructions_per_pixel: Option<f64>,
    m0_instructions_per_pixel: Option<f64>,
    host_ns_per_pixel: f64,
    psnr_db: f64,
    /// Pixels showing another object than f64's, in percent (0 where the axis measures no
    /// objects, [`Axis::shows_objects`]).
    object_mismatch_pct: f64,
}

/// `name` with `sampling` applied.
fn scene(name: &str, sampling: &Sampling) -> Result<OwnedScene> {
    let built_in = scenes::find(name).with_context(|| format!("no built-in scene {name}"))?;
    let mut scene = OwnedScene::from_desc(&built_in.desc);
    sampling.apply(&mut scene);
    Ok(scene)
}

impl Axis {
    /// Measures every scene by every sampling, writes `NAME-accuracy.csv`, `.svg` and `.png`
    /// to the chart's directory and prints the table.
    pub fn run(&self, args: &ChartArgs) -> Result<()> {
        let (width, height) = args.size;
        let costs = if args.no_firmware {
            Vec::new()
        } else {
            self.firmware_costs(args)?
        };
        eprintln!(
            "measuring {} by {} samplings on the host at {width}x{height}",
            self.scenes.join(", "),
            self.samplings.len()
        );
        let threads = all_cores();
        let mut prepared: Vec<Box<dyn AnyFormat>> = Vec::new();
        let mut points = Vec::new();
        for &name in self.scenes {
            let reference = self.reference(name, args.size)?;
            let truth = reference.render(threads, Some("f64"))?;
            let truth_objects = self.objects(&*reference, args.size)?;
            for (index, (sampling, ..)) in self.samplings.iter().enumerate() {
                let owned = scene(name, sampling)?;
                for format in HOST_FORMATS {
                    let request = Request::new(owned.desc(), args.size, Methods::LECTURE);
                    let contender = prepare(format, &request)?;
                    let image = contender.render(threads, None)?;
                    let objects = self.objects(&*contender, args.size)?;
                    let measured = accuracy(&image, &truth, &objects, &truth_objects);
                    let cost = |target| {
                        costs
                            .iter()
                            .find(|c: &&Cost| {
                                c.target == target
                                    && c.scene == name
                                    && c.format == format
                                    && c.sampling == index
                            })
                            .map(|c| c.instructions_per_pixel)
                    };
                    points.push(Point {
                        scene: name,
                        format,
                        sampling: index,
                        m4f_instructions_per_pixel: cost(Target::M4f),
                        m0_instructions_per_pixel: cost(Target::M0),
                        host_ns_per_pixel: 0.0,
                        psnr_db: measured.psnr_db,
                        object_mismatch_pct: measured.object_mismatch_pct,
                    });
                    prepared.push(contender);
                }
            }
        }
        let times = frame_ms(args.runs, &prepared);
        let pixels = f64::from(width) * f64::from(height);
        for (point, ms) in points.iter_mut().zip(times) {
            point.host_ns_per_pixel = ms * 1e6 / pixels;
        }
        let files = Files::in_dir(&args.out_dir, &format!("{}-accuracy", self.name));
        self.write_csv(&points, &files.csv)
            .with_context(|| format!("cannot write {}", files.csv.display()))?;
        plot::stability(self.title, &self.series(&points), &files.svg, &files.png)?;
        self.print_table(&points)?;
        files.say_written()?;
        Ok(())
    }

    /// The object each pixel of `prepared` shows, where this axis measures objects; none
    /// where it measures against a converged picture.
    fn objects(
        &self,
        prepared: &dyn AnyFormat,
        (width, height): (u32, u32),
    ) -> Result<Vec<Option<usize>>> {
        match self.converged {
            Some(_) => Ok(vec![None; (width * height) as usize]),
            None => prepared.object_map(),
        }
    }

    /// Whether this axis shows the objects' mismatch: against f64 with exact pixels.
    fn shows_objects(&self) -> bool {
        self.converged.is_none()
    }

    /// The f64 render scene `name` is measured against.
    fn reference(&self, name: &str, size: (u32, u32)) -> Result<Box<dyn AnyFormat>> {
        let reference = match self.converged {
            Some(n) => scene(name, &rays(n, false))?,
            None => scene(name, &OWN)?,
        };
        prepare_reference(&Request::new(reference.desc(), size, Methods::LECTURE))
    }

    /// What the images are measured against, in words.
    fn against(&self) -> String {
        match self.converged {
            Some(n) => format!("f64 with {n} rays per pixel"),
            None => "f64 with exact pixels".to_owned(),
        }
    }

    /// Instructions per pixel of every scene by every sampling on each microcontroller: one
    /// firmware image per target and sampling, its frames held to the host's bit for bit.
    fn firmware_costs(&self, args: &ChartArgs) -> Result<Vec<Cost>> {
        let mut costs = Vec::new();
        for (target, formats) in FORMATS {
            firmware::check_prerequisites(target)?;
            for (index, &(sampling, label, _)) in self.samplings.iter().enumerate() {
                let settings = FirmwareSettings {
                    frames: FrameSettings {
                        scene: self.scenes.iter().map(|&s| s.to_owned()).collect(),
                        format: formats.iter().copied().map(FormatChoice::Given).collect(),
                        variants: Variants::None,
                    },
                    sampling,
                    ..FirmwareSettings::default()
                };
                let dir = args.frames_dir.join(format!(
                    "{}-{}-{}",
                    target.name(),
                    self.name,
                    label.replace([' ', ':'], "-")
                ));
                std::fs::create_dir_all(&dir)
                    .with_context(|| format!("cannot create {}", dir.display()))?;
                let elf = firmware::build(target, &settings, &dir.join("image.elf"))?;
                eprintln!(
                    "running {} by {} {label} on the {} under QEMU",
                    self.scenes.join(", "),
                    self.name,
                    target.name()
                );
                let frames =
                    firmware::run(target, &elf, &dir, Duration::from_secs(args.timeout), None)?;
                for &name in self.scenes {
                    let desc = scene(name, &sampling)?;
                    for &format in formats {
                        let frame = frames
                            .iter()
                            .find(|f| f.scene == name && f.format == format.name())
                            .with_context(|| {
                                format!("the firmware reported no frame of {name} in {format}")
                            })?;
                        let (_, _, differing) =
                            firmware::compare_frame(&desc.desc(), format, frame, &dir)?;
                        if format.is_fixed_point() && !differing.is_empty() {
                            bail!(
                                "{name} by {} {label} in {format}: the firmware's frame differs \
                                 from the host's in {} pixels",
                                self.name,
                                differing.len()
                            );
                        }
                        let pixels = f64::from(frame.width) * f64::from(frame.height);
                        costs.push(Cost {
                            target,
                            scene: name,
                            format,
                            sampling: index,
                            instructions_per_pixel: target.instructions(frame.ticks) as f64
                                / pixels,
                        });
                    }
                }
            }
        }
        Ok(costs)
    }

    /// The chart's lines: a panel per scene and machine, a line per format and line of
    /// samplings.
    fn series(&self, points: &[Point]) -> Vec<StabilitySeries> {
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
        let mut lines: Vec<&str> = self.samplings.iter().map(|&(_, _, line)| line).collect();
        lines.dedup();
        let mut all = Vec::new();
        for &scene in self.scenes {
            for (machine, unit, cost) in machines {
                for format in HOST_FORMATS {
                    for &line in &lines {
                        let points: Vec<(f64, Option<f64>)> = points
                            .iter()
                            .filter(|p| {
                                p.scene == scene
                                    && p.format == format
                                    && self.samplings[p.sampling].2 == line
                            })
                            .filter_map(|p| Some((cost(p)?, Some(p.psnr_db))))
                            .collect();
                        if points.is_empty() {
                            continue;
                        }
                        all.push(StabilitySeries {
                            case: format!("{scene} on the {machine}"),
                            x_label: unit.to_owned(),
                            y_label: format!("PSNR vs {} (dB)", self.against()),
                            log_x: true,
                            format: format.name().to_owned(),
                            method: line.to_owned(),
                            points,
                        });
                    }
                }
            }
        }
        all
    }

    /// Writes the points as CSV to `path`.
    fn write_csv(&self, points: &[Point], path: &Path) -> Result<()> {
        let mut writer = csv::Writer::from_path(path)?;
        let [m4f, m0, host] = cost::COST_COLUMNS;
        writer.write_record([
            "scene",
            "format",
            self.name,
            m4f,
            m0,
            host,
            "psnr_db",
            "object_mismatch_pct",
        ])?;
        let number = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x:.1}"));
        for p in points {
            writer.write_record([
                p.scene.to_owned(),
                p.format.name().to_owned(),
                self.samplings[p.sampling].1.to_owned(),
                number(p.m4f_instructions_per_pixel),
                number(p.m0_instructions_per_pixel),
                format!("{:.1}", p.host_ns_per_pixel),
                format!("{:.2}", p.psnr_db),
                if self.shows_objects() {
                    format!("{:.4}", p.object_mismatch_pct)
                } else {
                    String::new()
                },
            ])?;
        }
        writer.flush()?;
        Ok(())
    }

    fn print_table(&self, points: &[Point]) -> std::io::Result<()> {
        say!(
            "\n{}, {} against cost (against {}):",
            self.scenes.join(" and "),
            self.name,
            self.against()
        )?;
        let (cost_headings, cost_rule) = cost::Machine::columns();
        let (mismatch_heading, mismatch_rule) = if self.shows_objects() {
            (" object mismatch (%) |", "---:|")
        } else {
            ("", "")
        };
        say!(
            "| scene | format | {} |{cost_headings} PSNR (dB) |{mismatch_heading}",
            self.name
        )?;
        say!("|---|---|---|{cost_rule}---:|{mismatch_rule}")?;
        for p in points {
            let costs = super::cost_cells(
                p.m4f_instructions_per_pixel,
                p.m0_instructions_per_pixel,
                p.host_ns_per_pixel,
            );
            let mismatch = if self.shows_objects() {
                format!(" {:.4} |", p.object_mismatch_pct)
            } else {
                String::new()
            };
            say!(
                "| {} | {} | {} |{costs} {:.2} |{mismatch}",
                p.scene,
                p.format,
                self.samplings[p.sampling].1,
                p.psnr_db
            )?;
        }
        Ok(())
    }
}

/// What a firmware run measured of one scene by one sampling in one format.
#[derive(Debug)]
struct Cost {
    target: Target,
    scene: &'static str,
    format: Format,
    /// The sampling's index in its axis.
    sampling: usize,
    instructions_per_pixel: f64,
}
