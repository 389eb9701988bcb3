//! What a format costs on each machine, read off the committed speed–accuracy chart
//! (`host/images/speed-accuracy.csv`, written by `obscura chart`): instructions per pixel on the
//! Cortex-M4F and the Cortex-M0, nanoseconds per pixel on the host. `--format auto` picks the
//! cheapest format by these measurements.

use crate::firmware::Target;
use crate::format::Format;
use crate::variant;
use clap::ValueEnum;
use obscura::Methods;
use std::fmt;
use std::sync::OnceLock;

/// The chart's measurements, as committed.
const CHART: &str = include_str!("../images/speed-accuracy.csv");

/// Where the cost is paid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Machine {
    /// The Cortex-M4F (instructions per pixel).
    M4f,
    /// The Cortex-M0 (instructions per pixel).
    M0,
    /// This computer (nanoseconds per pixel, single thread).
    Host,
}

impl Machine {
    /// Every machine, in the chart's order.
    pub const ALL: [Self; 3] = [Self::M4f, Self::M0, Self::Host];
}

impl fmt::Display for Machine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::M4f => "the Cortex-M4F",
            Self::M0 => "the Cortex-M0",
            Self::Host => "this computer",
        })
    }
}

impl From<Target> for Machine {
    fn from(target: Target) -> Self {
        match target {
            Target::M4f => Self::M4f,
            Target::M0 => Self::M0,
        }
    }
}

/// One row of the chart: a format and methods on a scene, and its cost on each machine.
#[derive(Debug)]
struct Row {
    format: String,
    variant: String,
    m4f: Option<f64>,
    m0: Option<f64>,
    host: Option<f64>,
}

fn rows() -> &'static [Row] {
    static ROWS: OnceLock<Vec<Row>> = OnceLock::new();
    ROWS.get_or_init(|| parse(CHART))
}

/// The rows of the chart's CSV (scene, format, variant, M4F, M0, host, ...); a row that does not
/// parse is left out.
fn parse(csv: &str) -> Vec<Row> {
    csv.lines()
        .skip(1)
        .filter_map(|line| {
            let fields: Vec<&str> = line.split(',').map(|f| f.trim_matches('"')).collect();
            let number = |i: usize| fields.get(i).and_then(|f| f.parse::<f64>().ok());
            Some(Row {
                format: (*fields.get(1)?).to_owned(),
                variant: (*fields.get(2)?).to_owned(),
                m4f: number(3),
                m0: number(4),
                host: number(5),
            })
        })
        .collect()
}

/// The mean cost per pixel of `format` by `methods` on `machine` over the chart's scenes (by
/// the lecture's methods where the chart has no run of these); `None` where the chart has no
/// measurement at all (f64, which the chart measures others against).
pub fn cost(machine: Machine, format: Format, methods: &Methods) -> Option<f64> {
    let of = |label: &str| {
        let costs: Vec<f64> = rows()
            .iter()
            .filter(|r| r.format == format.name() && r.variant == label)
            .filter_map(|r| match machine {
                Machine::M4f => r.m4f,
                Machine::M0 => r.m0,
                Machine::Host => r.host,
            })
            .collect();
        (!costs.is_empty()).then(|| costs.iter().sum::<f64>() / costs.len() as f64)
    };
    of(&variant::label(methods)).or_else(|| of("lecture"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_committed_chart_prices_every_firmware_format_on_every_machine() {
        for format in Format::FIRMWARE {
            for machine in Machine::ALL {
                let cost = cost(machine, format, &Methods::LECTURE);
                assert!(cost.is_some_and(|c| c > 0.0), "{format} on {machine:?}");
            }
        }
        assert_eq!(cost(Machine::M0, Format::F64, &Methods::LECTURE), None);
    }
}
