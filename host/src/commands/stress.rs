//! `obscura stress`: the stress cases, their verdicts in a table, and the stability chart.

use crate::cli::StressArgs;
use crate::output::{self, say};
use crate::plot::{self, StabilitySeries};
use crate::stress::{self, CASES, Case, Outcome, Row};
use anyhow::{Context, Result, bail};
use serde::Serialize;
use std::fmt::Write as _;
use std::io;

#[derive(Serialize)]
struct CaseReport<'a> {
    case: &'static str,
    about: &'static str,
    x: &'static str,
    y: &'static str,
    rows: &'a [Row],
}

pub fn run(args: &StressArgs) -> Result<()> {
    output::check_dir(&args.out_dir)?;
    if let Some(path) = &args.json {
        output::check_file(path)?;
    }
    let chosen: Vec<&Case> = if args.case.is_empty() {
        CASES.iter().collect()
    } else {
        args.case
            .iter()
            .map(|name| {
                CASES.iter().find(|c| c.name == name).with_context(|| {
                    let names: Vec<_> = CASES.iter().map(|c| c.name).collect();
                    format!(
                        "there is no stress case `{name}`; the cases are: {}",
                        names.join(", ")
                    )
                })
            })
            .collect::<Result<_>>()?
    };
    let mut results = Vec::new();
    for case in chosen {
        eprintln!("stress case {}: {}", case.name, case.about);
        let rows = stress::run_case(case)?;
        print_case(case, &rows)?;
        results.push((case, rows));
    }
    let count = |f: fn(&Outcome) -> bool| {
        results
            .iter()
            .flat_map(|(_, rows)| rows)
            .filter(|r| f(&r.outcome))
            .count()
    };
    let failed = count(|o| matches!(o, Outcome::Failed { .. }));
    say!(
        "verdicts: {} within their error bound, {} refused up front, {} reported, {failed} failed",
        count(|o| matches!(o, Outcome::Within { .. })),
        count(|o| matches!(o, Outcome::Refused { .. })),
        count(|o| matches!(o, Outcome::Reported { .. })),
    )?;

    let series: Vec<StabilitySeries> = results
        .iter()
        .flat_map(|(case, rows)| to_series(case, rows))
        .collect();
    let (svg, png) = (
        args.out_dir.join("stability.svg"),
        args.out_dir.join("stability.png"),
    );
    plot::stability(
        "Stability under stress (× at the bottom: scene refused up front by the tracer)",
        &series,
        &svg,
        &png,
    )?;
    say!("wrote {} and {}", svg.display(), png.display())?;
    if let Some(path) = &args.json {
        let reports: Vec<CaseReport<'_>> = results
            .iter()
            .map(|(case, rows)| CaseReport {
                case: case.name,
                about: case.about,
                x: case.x_label,
                y: case.y_label,
                rows,
            })
            .collect();
        std::fs::write(path, serde_json::to_string_pretty(&reports)? + "\n")
            .with_context(|| format!("cannot write {}", path.display()))?;
        say!("wrote {}", path.display())?;
    }
    if failed > 0 {
        bail!("{failed} measurements exceeded their error bound (marked FAILED above)");
    }
    Ok(())
}

/// One line per format and method, one column per value of the stressed parameter.
fn print_case(case: &Case, rows: &[Row]) -> io::Result<()> {
    let mut xs: Vec<f64> = Vec::new();
    for row in rows {
        if !xs.contains(&row.x) {
            xs.push(row.x);
        }
    }
    say!("\n### {}: {}\n", case.name, case.about)?;
    say!(
        "{} against {}; a cell is the measurement, or why the scene was refused.\n",
        case.y_label,
        case.x_label
    )?;
    let mut header = String::from("| format | method |");
    let mut rule = String::from("|---|---|");
    for x in &xs {
        let _ = write!(header, " {x:.3e} |");
        rule.push_str("---:|");
    }
    say!("{header}\n{rule}")?;
    let mut lines: Vec<(&str, &str)> = Vec::new();
    for row in rows {
        if !lines.contains(&(row.format, row.method)) {
            lines.push((row.format, row.method));
        }
    }
    for (format, method) in lines {
        let mut line = format!(
            "| {format} | {} |",
            if method.is_empty() { "–" } else { method }
        );
        for x in &xs {
            let cell = rows
                .iter()
                .find(|r| r.format == format && r.method == method && r.x == *x);
            let text = match cell.map(|r| (&r.outcome, r.y)) {
                None => "".to_owned(),
                Some((Outcome::Refused { kind, .. }, _)) => format!("refused ({kind})"),
                Some((Outcome::Failed { value, bound }, _)) => {
                    format!("**FAILED** {value} > {bound}")
                }
                Some((_, Some(y))) => format!("{y:.3}"),
                Some((_, None)) => "–".to_owned(),
            };
            let _ = write!(line, " {text} |");
        }
        say!("{line}")?;
    }
    Ok(())
}

fn to_series(case: &Case, rows: &[Row]) -> Vec<StabilitySeries> {
    let mut series: Vec<StabilitySeries> = Vec::new();
    for row in rows {
        let point = (row.x, row.y);
        match series
            .iter_mut()
            .find(|s| s.format == row.format && s.method == row.method)
        {
            Some(s) => s.points.push(point),
            None => series.push(StabilitySeries {
                case: case.name.to_owned(),
                x_label: case.x_label.to_owned(),
                y_label: case.y_label.to_owned(),
                log_x: case.log_x,
                format: row.format.to_owned(),
                method: row.method.to_owned(),
                points: vec![point],
            }),
        }
    }
    series
}
