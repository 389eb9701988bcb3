//! The desktop harness of the obscura ray tracer: the `obscura` command ([`main`]), which runs
//! the very same `no_std` core as the firmware, writes PNGs, measures each number format
//! against an f64 reference and picks one (`--format auto`). Scene files, the formats by name
//! and the firmware's configuration are the `obscura-scene` crate's, which the firmware's build
//! reads them with too.

mod analysis;
mod canvas;
mod checked;
mod cli;
mod commands;
mod cost;
mod counted;
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
mod stress;
mod timing;

use clap::Parser;
use std::process::ExitCode;

/// Runs the `obscura` command line on this process's arguments.
#[must_use]
pub fn main() -> ExitCode {
    let cli = match cli::Cli::try_parse() {
        Ok(cli) => cli,
        Err(asked) => return answer(&asked),
    };
    // A command that does not catch an overflow itself (to say at which pixel of which scene)
    // still ends with it as an error, never with a wrapped number.
    let outcome = checked::catch(|| commands::run(cli.command).and_then(|()| Ok(output::flush()?)))
        .unwrap_or_else(|overflowed| {
            Err(anyhow::anyhow!(
                "{overflowed}: the scene build's range proof missed it (a bug in obscura: please \
             report it with the scene)"
            ))
        });
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

/// What the command line asked that is not a command: help or the version, written to
/// standard output (a failure to write it, to a full disk, is a failure), or a mistake in it,
/// written to standard error as clap words it.
fn answer(asked: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    use std::io::{IsTerminal, Write};
    if matches!(
        asked.kind(),
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion
    ) {
        let mut stdout = std::io::stdout().lock();
        let text = asked.render();
        let written = if stdout.is_terminal() {
            write!(stdout, "{}", text.ansi())
        } else {
            write!(stdout, "{text}")
        }
        .and_then(|()| stdout.flush());
        return match written {
            Ok(()) => ExitCode::SUCCESS,
            Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
            Err(error) => {
                eprintln!("error: cannot write to standard output: {error}");
                ExitCode::FAILURE
            }
        };
    }
    let _ = asked.print();
    ExitCode::from(u8::try_from(asked.exit_code()).unwrap_or(2))
}
