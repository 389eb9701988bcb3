//! `obscura stress`: named cases where the literature says methods fail, each run for every
//! format and the methods it concerns across a stressed parameter, each ending in a verdict:
//! **within its error bound**, or **refused up front** by the scene build with the reason —
//! never silent garbage.
//!
//! Two kinds of bound are used:
//! - where one intersection is stressed, the error model of the range analysis
//!   ([`obscura::scene::range::Feature::error`]) must hold: a ray may be misjudged only within
//!   a few of those errors of the boundary it crosses;
//! - where a whole image is stressed, no pixel may be off by more than [`check::TOLERANCE`]
//!   levels unless a quarter-pixel nudge of its ray changes the f64 reference by as much: an
//!   error nobody can see at that resolution.

mod cases;
mod check;

pub use cases::CASES;

use anyhow::Result;
use obscura_scene::Format;
use serde::Serialize;
use std::fmt;

/// A stress case.
#[derive(Debug)]
pub struct Case {
    /// Its name on the command line.
    pub name: &'static str,
    /// What it stresses.
    pub about: &'static str,
    /// The stressed parameter.
    pub x_label: &'static str,
    /// Whether the parameter is swept on a log scale.
    pub log_x: bool,
    /// What is plotted against it.
    pub y_label: &'static str,
    /// Runs the case in one format.
    pub run: fn(Format) -> Result<Vec<Row>>,
}

/// One measurement: a format and method at one value of the stressed parameter.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The format.
    pub format: &'static str,
    /// The method the case compares ("" where it compares none).
    pub method: &'static str,
    /// The stressed parameter.
    pub x: f64,
    /// What is plotted; `None` when refused.
    pub y: Option<f64>,
    /// The verdict.
    pub outcome: Outcome,
}

/// How a measurement ended.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "verdict", rename_all = "snake_case")]
pub enum Outcome {
    /// The error stayed within its bound.
    Within {
        /// The measured error.
        value: f64,
        /// Its bound.
        bound: f64,
    },
    /// Measured, with no bound to hold it to: a method's known weakness, shown as a number
    /// (the cracks of a test that is not watertight).
    Reported {
        /// The measured count.
        value: f64,
    },
    /// The scene build refused it up front.
    Refused {
        /// What did not hold: "range", "resolution", "degenerate" or "invalid".
        kind: &'static str,
        /// The build's reason.
        reason: String,
    },
    /// The error exceeded its bound: silent garbage, and a bug.
    Failed {
        /// The measured error.
        value: f64,
        /// Its bound.
        bound: f64,
    },
}

impl Outcome {
    /// Within when `value ≤ bound`, failed otherwise.
    pub fn bounded(value: f64, bound: f64) -> Self {
        if value <= bound {
            Self::Within { value, bound }
        } else {
            Self::Failed { value, bound }
        }
    }
}

impl fmt::Display for Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Within { value, bound } => write!(f, "within bound ({value} ≤ {bound})"),
            Self::Reported { value } => write!(f, "reported ({value})"),
            Self::Refused { reason, .. } => write!(f, "refused: {reason}"),
            Self::Failed { value, bound } => write!(f, "FAILED ({value} > {bound})"),
        }
    }
}

/// Runs `case` in every format the firmware or the host computes in.
pub fn run_case(case: &Case) -> Result<Vec<Row>> {
    let mut rows = Vec::new();
    for &format in Format::ALL {
        rows.extend((case.run)(format)?);
    }
    Ok(rows)
}

/// The verdicts the suite stands on, asserted so that a regression fails CI.
#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::OnceLock;

    /// The rows of the case named `name`; every case runs once for all the tests.
    fn rows(name: &str) -> &'static [Row] {
        static ALL: OnceLock<Vec<(&'static str, Vec<Row>)>> = OnceLock::new();
        let all = ALL.get_or_init(|| {
            CASES
                .iter()
                .map(|case| (case.name, run_case(case).expect("the case runs")))
                .collect()
        });
        all.iter()
            .find(|(case, _)| *case == name)
            .map(|(_, rows)| rows.as_slice())
            .expect("a case of that name")
    }

    /// The verdict of `case` for `format` and `method` where its parameter is `x`.
    fn verdict(case: &str, format: &str, method: &str, x: f64) -> &'static Outcome {
        rows(case)
            .iter()
            .find(|r| r.format == format && r.method == method && (r.x / x - 1.0).abs() < 1e-9)
            .map(|r| &r.outcome)
            .unwrap_or_else(|| panic!("no row {case} {format} {method} {x}"))
    }

    fn refused_because(outcome: &Outcome, why: &str) -> bool {
        matches!(outcome, Outcome::Refused { reason, .. } if reason.contains(why))
    }

    #[test]
    fn no_measurement_exceeds_its_bound() {
        for case in &CASES {
            let failed: Vec<_> = rows(case.name)
                .iter()
                .filter(|r| matches!(r.outcome, Outcome::Failed { .. }))
                .map(|r| format!("{} {} {:e}: {}", r.format, r.method, r.x, r.outcome))
                .collect();
            assert!(failed.is_empty(), "{}: {failed:#?}", case.name);
        }
    }

    /// Each case measures something in every format with at least 10 integer and 12 fraction
    /// bits; the narrowest split (i8f24, ±128) and the coarsest (i22f10, i24f8) may refuse a
    /// whole case, but only as too large or too fine for them (or degenerate in every format).
    #[test]
    fn every_case_measures_something_in_every_format_but_the_extreme_splits() {
        let extreme = |format: Format| {
            format
                .split()
                .is_some_and(|(int, frac)| int < 10 || frac < 12)
        };
        for case in &CASES {
            for &format in Format::ALL {
                let of_format = || rows(case.name).iter().filter(|r| r.format == format.name());
                let measures = of_format().any(|r| r.y.is_some());
                let refused_for_size = of_format().all(|r| {
                    matches!(
                        r.outcome,
                        Outcome::Refused {
                            kind: "range" | "resolution" | "degenerate",
                            ..
                        }
                    )
                });
                assert!(
                    measures || (extreme(format) && refused_for_size),
                    "{}: {} refuses everything",
                    case.name,
                    format.name()
                );
            }
        }
    }

    #[test]
    fn no_ray_slips_through_the_watertight_mesh_and_some_slip_through_the_others() {
        let mesh = rows("mesh");
        // As eight triangles and as one mesh through its hierarchy.
        let watertight: Vec<_> = mesh
            .iter()
            .filter(|r| r.method.starts_with("watertight"))
            .collect();
        assert!(watertight.iter().any(|r| r.method == "watertight, mesh"));
        for row in watertight {
            assert!(
                matches!(row.outcome, Outcome::Within { value, .. } if value == 0.0)
                    || matches!(row.outcome, Outcome::Refused { .. }),
                "{} at {}: {}",
                row.format,
                row.x,
                row.outcome
            );
        }
        for form in ["cramer", "cramer, mesh"] {
            assert!(
                mesh.iter().any(|r| r.method == form
                    && matches!(r.outcome, Outcome::Reported { value } if value > 0.0)),
                "the case no longer finds the cracks of the tests that are not watertight ({form})"
            );
        }
    }

    /// Adaptive pixels lose a shadow, a reflection and a refracted checker that fall between a
    /// block's corners (f32 in blocks of 8 20 dB and more below exact pixels at some size), and
    /// hold a fine checker (above 60 dB against f64 at every size: each corner knows its
    /// square); no case's object mismatch exceeds its bound (above).
    #[test]
    fn adaptive_pixels_lose_what_falls_between_corners_and_hold_the_checker() {
        let f32_rows = |case, method| {
            rows(case)
                .iter()
                .filter(move |r| r.format == "f32" && r.method == method)
        };
        for case in ["adaptive-shadow", "adaptive-reflection", "adaptive-glass"] {
            let loss = f32_rows(case, "adaptive:8")
                .zip(f32_rows(case, "exact"))
                .filter_map(|(adaptive, exact)| Some(exact.y? - adaptive.y?))
                .fold(f64::NEG_INFINITY, f64::max);
            assert!(loss > 20.0, "{case}: {loss} dB");
        }
        let checker = f32_rows("adaptive-checker", "adaptive:8")
            .filter_map(|r| r.y)
            .fold(f64::INFINITY, f64::min);
        assert!(checker > 60.0, "{checker} dB");
    }

    #[test]
    fn what_a_format_cannot_hold_is_refused_with_the_reason() {
        // A sphere 10⁴ times smaller than its distance is below i16f16's resolution...
        let distant = verdict("distant", "i16f16", "quadratic", 1e-4);
        assert!(
            refused_because(distant, "radius² seen from the eye"),
            "{distant}"
        );
        // ... a world 10³ times larger beyond its range ...
        let scaled = verdict("scale", "i16f16", "quadratic", 1e3);
        assert!(refused_because(scaled, "beyond i16f16's range"), "{scaled}");
        // ... and an eye a tenth of a radius inside a glass sphere too near its surface for
        // i20f12's tolerance.
        let glass = verdict("glass", "i20f12", "epsilon", 0.9);
        assert!(refused_because(glass, "the eye's distance"), "{glass}");
    }

    #[test]
    fn the_stable_form_holds_smaller_spheres_than_the_quadratic() {
        let smallest = |format: &str, method: &str| {
            rows("distant")
                .iter()
                .filter(|r| r.format == format && r.method == method && r.y.is_some())
                .map(|r| r.x)
                .fold(f64::INFINITY, f64::min)
        };
        for format in ["i16f16", "f32-approx", "f32"] {
            assert!(
                smallest(format, "stable") < smallest(format, "quadratic"),
                "{format}"
            );
        }
    }

    #[test]
    fn floats_hold_the_whitted_scene_at_every_scale_and_the_plane_at_every_distance() {
        for format in ["f32", "f64"] {
            for row in rows("scale").iter().filter(|r| r.format == format) {
                assert!(
                    matches!(row.outcome, Outcome::Within { .. }),
                    "{format} {}",
                    row.x
                );
            }
            for row in rows("floor")
                .iter()
                .filter(|r| r.format == format && r.method == "plane")
            {
                assert!(
                    matches!(row.outcome, Outcome::Within { .. }),
                    "{format} {}",
                    row.x
                );
            }
        }
    }
}
