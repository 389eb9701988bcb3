//! What a format costs on each machine, read off the committed speed–accuracy chart
//! (`docs/images/speed-accuracy.csv`, written by `obscura chart`): instructions per pixel on the
//! Cortex-M4F and the Cortex-M0, nanoseconds per pixel on the host; and what adaptive pixels
//! multiply them by (`docs/images/pixels-accuracy.csv`, the chart's pixels axis). `--format
//! auto` picks the cheapest format and pixels by these measurements.

use crate::firmware::Target;
use clap::ValueEnum;
use obscura::scenes::{self, BuiltIn};
use obscura::{MethodName, Methods, Pixels};
use obscura_scene::Format;
use std::fmt;
use std::sync::OnceLock;

/// The chart's measurements, as committed.
const CHART: &str = include_str!("../../docs/images/speed-accuracy.csv");

/// The chart's pixels axis, as committed: exact and adaptive pixels on `whitted` and `shapes`.
const PIXELS_CHART: &str = include_str!("../../docs/images/pixels-accuracy.csv");

/// Where the cost is paid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Machine {
    /// The Cortex-M4F (instructions per pixel).
    M4f,
    /// The Cortex-M0 (instructions per pixel).
    M0,
    /// The PC the chart ran on (nanoseconds per pixel, single thread).
    Host,
}

impl Machine {
    /// Every machine, in the chart's order.
    pub const ALL: [Self; 3] = [Self::M4f, Self::M0, Self::Host];

    /// The machines whose costs a table shows: every one, but the PC's, a time, where times are
    /// not shown ([`crate::timing::shown`]).
    #[must_use]
    pub fn shown() -> &'static [Self] {
        if crate::timing::shown() {
            &Self::ALL
        } else {
            &[Self::M4f, Self::M0]
        }
    }

    /// The heading of its cost's column in a table.
    #[must_use]
    pub const fn column(self) -> &'static str {
        match self {
            Self::M4f => "M4F instr/px",
            Self::M0 => "M0 instr/px",
            Self::Host => "host ns/px",
        }
    }

    /// The cost columns of a Markdown table, for the machines shown: their headings and their
    /// rule, each cell as ` … |`.
    #[must_use]
    pub fn columns() -> (String, String) {
        let shown = Self::shown();
        let headings = shown.iter().map(|m| format!(" {} |", m.column())).collect();
        (headings, "---:|".repeat(shown.len()))
    }

    /// A row's cost cells, for the machines shown, `cost` giving each as text.
    #[must_use]
    pub fn cells(cost: impl Fn(Self) -> String) -> String {
        Self::shown()
            .iter()
            .map(|&m| format!(" {} |", cost(m)))
            .collect()
    }
}

impl fmt::Display for Machine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::M4f => "the Cortex-M4F",
            Self::M0 => "the Cortex-M0",
            Self::Host => "the PC",
        })
    }
}

impl From<Target> for Machine {
    fn from(target: Target) -> Self {
        match target {
            Target::M4f => Self::M4f,
            Target::M0 => Self::M0,
            // Not charted: priced as the M4F, whose instruction set and FPU it shares
            // (`whitted` on both: within 2 % in i16f16 and f32).
            Target::M33 => Self::M4f,
            // Likewise priced as the M0, the other core without an FPU: the formats' order is
            // what `auto` takes from it.
            Target::Rv32 => Self::M0,
        }
    }
}

/// One row of a chart: a format and methods (or pixels) on a scene, and its cost on each
/// machine.
#[derive(Debug)]
struct Row {
    scene: String,
    format: String,
    variant: String,
    m4f: Option<f64>,
    m0: Option<f64>,
    host: Option<f64>,
}

impl Row {
    /// Its cost on `machine`, if the chart measured it there.
    fn on(&self, machine: Machine) -> Option<f64> {
        match machine {
            Machine::M4f => self.m4f,
            Machine::M0 => self.m0,
            Machine::Host => self.host,
        }
    }
}

fn rows() -> &'static [Row] {
    static ROWS: OnceLock<Vec<Row>> = OnceLock::new();
    ROWS.get_or_init(|| parse(CHART, "variant"))
}

fn pixel_rows() -> &'static [Row] {
    static ROWS: OnceLock<Vec<Row>> = OnceLock::new();
    ROWS.get_or_init(|| parse(PIXELS_CHART, "pixels"))
}

/// A chart CSV's cost columns: a point's cost on each of [`Machine::ALL`] (an empty field
/// where it was not measured).
pub const COST_COLUMNS: [&str; 3] = [
    "m4f_instructions_per_pixel",
    "m0_instructions_per_pixel",
    "host_ns_per_pixel",
];

/// The rows of a chart's CSV, read from its columns `scene`, `format`, `variant` (the one
/// that names what else the point varies) and [`COST_COLUMNS`]; further columns are ignored.
///
/// # Panics
/// Where the CSV lacks a column or a cost does not parse: the charts are compiled in as
/// committed, and a test reads them.
fn parse(csv: &str, variant: &str) -> Vec<Row> {
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    let header = reader.headers().expect("the chart has a header").clone();
    let [m4f, m0, host] = COST_COLUMNS;
    let columns = ["scene", "format", variant, m4f, m0, host];
    let at = columns.map(|name| {
        header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("the chart has no column {name}"))
    });
    reader
        .records()
        .map(|record| {
            let record = record.expect("the chart's rows are CSV");
            let text = |i: usize| record[at[i]].to_owned();
            let number = |i: usize| {
                let field = &record[at[i]];
                (!field.is_empty()).then(|| {
                    field
                        .parse::<f64>()
                        .unwrap_or_else(|_| panic!("{field:?} in {} is not a number", columns[i]))
                })
            };
            Row {
                scene: text(0),
                format: text(1),
                variant: text(2),
                m4f: number(3),
                m0: number(4),
                host: number(5),
            }
        })
        .collect()
}

/// What `format` by `methods` costs per pixel on `machine` in a scene with triangles or without,
/// as the chart measured it on the built-in scenes like it (on the others where those refused
/// the format): by these methods where they change something there and the chart ran them, by
/// the lecture's otherwise. A 32-bit fixed format the built-in scenes refuse (the narrowest and
/// coarsest splits) costs what the 32-bit formats of its narrow format the chart measured cost
/// on average, but `i16f16`: they run the same code but for their shifts ([`shifts_alike`]).
/// `None` where the chart has no measurement at all (f64, which the chart measures others
/// against).
pub fn cost(
    machine: Machine,
    format: Format,
    methods: &Methods,
    has_triangles: bool,
) -> Option<f64> {
    let label = methods.to_string();
    // The mean cost of the charted formats `priced` names, on the built-in scenes like this one
    // (or else on the others).
    let price = |priced: &dyn Fn(&str) -> bool| {
        let on = |scene: &BuiltIn| {
            let matters =
                format.methods_matter(methods, &Methods::LECTURE, scene.desc.has_triangles());
            let of = |variant: &str| {
                let costs: Vec<f64> = rows()
                    .iter()
                    .filter(|r| r.scene == scene.name && r.variant == variant && priced(&r.format))
                    .filter_map(|r| r.on(machine))
                    .collect();
                mean_of(&costs)
            };
            if matters { of(&label) } else { None }.or_else(|| of("lecture"))
        };
        let mean = |alike: bool| {
            let costs: Vec<f64> = scenes::one_ray()
                .filter(|scene| (scene.desc.has_triangles() == has_triangles) == alike)
                .filter_map(on)
                .collect();
            mean_of(&costs)
        };
        mean(true).or_else(|| mean(false))
    };
    price(&|name| name == format.name()).or_else(|| {
        format
            .is_fixed_32()
            .then(|| price(&|name| shifts_alike(format, name)))
            .flatten()
    })
}

/// What `pixels` multiply `format`'s cost on `machine` by, in a scene with triangles or
/// without, as the chart's pixels axis measured it on the built-in scene like it (`shapes`,
/// `whitted`): their cost over exact pixels' in the charted format of `format`'s kind (`f32`
/// for a float format, `i16f16` for a fixed one: blocks save the same rays in each). 1 for
/// exact pixels; `None` where the chart did not measure it (a float format on the M0, f64).
pub fn pixels_factor(
    machine: Machine,
    format: Format,
    pixels: Pixels,
    has_triangles: bool,
) -> Option<f64> {
    if pixels == Pixels::Exact {
        return Some(1.0);
    }
    let kin = match format {
        Format::F64 => return None,
        fixed if fixed.is_fixed_point() => Format::I16f16,
        _ => Format::F32,
    };
    let scene = if has_triangles { "shapes" } else { "whitted" };
    let cost = |pixels: Pixels| {
        pixel_rows()
            .iter()
            .find(|r| r.scene == scene && r.format == kin.name() && r.variant == pixels.name())
            .and_then(|r| r.on(machine))
    };
    Some(cost(pixels)? / cost(Pixels::Exact)?)
}

/// The mean of `costs`, if there are any.
fn mean_of(costs: &[f64]) -> Option<f64> {
    (!costs.is_empty()).then(|| costs.iter().sum::<f64>() / costs.len() as f64)
}

/// Whether the chart's format name is a 32-bit fixed format's that runs `format`'s code but for
/// its shifts: of the same narrow format, and not `i16f16`, whose shift by 16 the M0 gets free
/// where its partial products meet (so that it prices no other split).
fn shifts_alike(format: Format, name: &str) -> bool {
    Format::ALL.iter().any(|&other| {
        other.name() == name
            && other.is_fixed_32()
            && other.narrow() == format.narrow()
            && other != Format::I16f16
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use obscura::TriangleMethod;

    #[test]
    fn the_committed_chart_prices_every_firmware_format_on_every_machine() {
        for &format in Format::FIRMWARE {
            for machine in Machine::ALL {
                for triangles in [false, true] {
                    let cost = cost(machine, format, &Methods::LECTURE, triangles);
                    assert!(cost.is_some_and(|c| c > 0.0), "{format} on {machine:?}");
                }
            }
        }
        assert_eq!(
            cost(Machine::M0, Format::F64, &Methods::LECTURE, false),
            None
        );
    }

    /// The chart's cost of a run on the M4F, read off its CSV directly.
    fn charted(scene: &str, format: &str, variant: &str) -> f64 {
        charted_on(Machine::M4f, scene, format, variant)
    }

    /// The chart's cost of a run on `machine`, read off its CSV directly.
    fn charted_on(machine: Machine, scene: &str, format: &str, variant: &str) -> f64 {
        rows()
            .iter()
            .find(|r| r.scene == scene && r.format == format && r.variant == variant)
            .and_then(|r| r.on(machine))
            .expect("charted")
    }

    #[test]
    fn a_format_is_priced_on_the_built_in_scene_like_the_one_analysed() {
        let lecture = Methods::LECTURE;
        // Without triangles, as whitted; with them, as shapes.
        assert_eq!(
            cost(Machine::M4f, Format::I16f16, &lecture, false),
            Some(charted("whitted", "i16f16", "lecture"))
        );
        assert_eq!(
            cost(Machine::M4f, Format::I16f16, &lecture, true),
            Some(charted("shapes", "i16f16", "lecture"))
        );
        // A triangle method changes nothing without triangles: the lecture's run stands in.
        let watertight = Methods {
            triangle: TriangleMethod::Watertight,
            ..lecture
        };
        assert_eq!(
            cost(Machine::M4f, Format::F32, &watertight, false),
            Some(charted("whitted", "f32", "lecture"))
        );
        assert_eq!(
            cost(Machine::M4f, Format::F32, &watertight, true),
            Some(charted("shapes", "f32", "triangle=watertight"))
        );
        // shapes refuses i20f12 by the lecture's methods: priced on whitted instead.
        assert_eq!(
            cost(Machine::M4f, Format::I20f12, &lecture, true),
            Some(charted("whitted", "i20f12", "lecture"))
        );
        // i24f8 holds neither scene: priced as the 32-bit formats the chart ran on whitted
        // with its narrow format that shift as it does (not i16f16, whose shift the M0 gets
        // free); i8f24 as those with its own.
        for machine in [Machine::M4f, Machine::M0] {
            let mean = |kin: [&str; 2]| {
                let costs = kin.map(|f| charted_on(machine, "whitted", f, "lecture"));
                Some(costs.iter().sum::<f64>() / 2.0)
            };
            assert_eq!(
                cost(machine, Format::I24f8, &lecture, false),
                mean(["i18f14", "i20f12"])
            );
            assert_eq!(
                cost(machine, Format::I8f24, &lecture, false),
                mean(["i12f20", "i14f18"])
            );
        }
    }

    #[test]
    fn adaptive_pixels_are_priced_by_the_pixels_axis_in_the_formats_kind() {
        let charted = |machine, scene: &str, format: &str, pixels: &str| {
            pixel_rows()
                .iter()
                .find(|r| r.scene == scene && r.format == format && r.variant == pixels)
                .and_then(|r| r.on(machine))
                .expect("charted")
        };
        let ratio = |machine, scene, format| {
            charted(machine, scene, format, "adaptive:4") / charted(machine, scene, format, "exact")
        };
        let four = Pixels::Adaptive(4);
        // A fixed format as i16f16 on the scene like it; a float format as f32.
        assert_eq!(
            pixels_factor(Machine::M0, Format::I18f14, four, false),
            Some(ratio(Machine::M0, "whitted", "i16f16"))
        );
        assert_eq!(
            pixels_factor(Machine::M4f, Format::F32Approx, four, true),
            Some(ratio(Machine::M4f, "shapes", "f32"))
        );
        // Not measured: f32 on the M0; f64 anywhere. Exact pixels cost what the format does.
        assert_eq!(pixels_factor(Machine::M0, Format::F32, four, false), None);
        assert_eq!(pixels_factor(Machine::M4f, Format::F64, four, false), None);
        assert_eq!(
            pixels_factor(Machine::M0, Format::F32, Pixels::Exact, false),
            Some(1.0)
        );
    }

    #[test]
    fn a_quoted_variant_may_hold_commas() {
        let csv = "scene,format,variant,m4f_instructions_per_pixel,\
                   m0_instructions_per_pixel,host_ns_per_pixel,psnr_db\n\
                   whitted,i16f16,\"sphere=stable,bias=exclude\",1.5,2,3,40\n";
        let rows = parse(csv, "variant");
        assert_eq!(rows.len(), 1);
        assert_eq!(rows[0].variant, "sphere=stable,bias=exclude");
        assert_eq!(
            (rows[0].m4f, rows[0].m0, rows[0].host),
            (Some(1.5), Some(2.0), Some(3.0))
        );
    }
}
