//! The desktop harness of the obscura ray tracer: the `obscura` command ([`main`]), which runs
//! the very same `no_std` core as the firmware, writes PNGs, measures each number format
//! against an f64 reference and picks one (`--format auto`). Scene files, the formats by name
//! and the firmware's configuration are the `obscura-scene` crate's, which the firmware's build
//! reads them with too.

mod analysis;
mod book;
mod canvas;
mod checked;
mod cli;
mod commands;
mod cost;
mod counted;
mod cycles;
mod estimate;
mod firmware;
mod fuzz;
mod heatmap;
mod metrics;
mod operations;
mod output;
mod pareto;
#[cfg(test)]
mod peak;
mod plot;
mod profile;
mod quantized;
#[cfg(test)]
mod regressions;
mod render;
mod rp2040;
mod stress;
pub mod teapot;
mod timing;

use clap::Parser;
use std::process::ExitCode;

/// Runs the `obscura` command line on this process's arguments.
#[must_use]
pub fn main() -> ExitCode {
    let outcome = match cli::Cli::try_parse() {
        Ok(cli) => run(cli),
        // Help and the version are written as any output is (a full disk is an error).
        Err(asked) if !asked.use_stderr() => shown(&asked),
        // A mistake in the command line, as clap words it.
        Err(mistake) => {
            let _ = mistake.print();
            return ExitCode::from(u8::try_from(mistake.exit_code()).unwrap_or(2));
        }
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        // `obscura scenes | head -1`: the reader has what it wanted.
        Err(error) if output::is_closed_pipe(&error) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("{}", obscura_scene::error_text(&error));
            ExitCode::FAILURE
        }
    }
}

/// Runs a command. One that does not catch an overflow itself (to say at which pixel of which
/// scene) still ends with it as an error, never with a wrapped number.
fn run(cli: cli::Cli) -> anyhow::Result<()> {
    checked::catch(|| commands::run(cli.command).and_then(|()| Ok(output::flush()?)))
        .unwrap_or_else(|overflowed| {
            Err(anyhow::anyhow!(
                "{overflowed}: the scene build's range proof missed it (a bug in obscura: please \
             report it with the scene)"
            ))
        })
}

/// Help or the version on standard output, in colour on a terminal.
fn shown(asked: &clap::Error) -> anyhow::Result<()> {
    use std::io::IsTerminal;
    let text = asked.render();
    if std::io::stdout().is_terminal() {
        output::text(format_args!("{}", text.ansi()))?;
    } else {
        output::text(format_args!("{text}"))?;
    }
    Ok(output::flush()?)
}
