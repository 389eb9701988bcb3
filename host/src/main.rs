//! `obscura`: the desktop harness of the obscura ray tracer. It runs the very same `no_std` core
//! as the firmware, writes PNGs, and measures each number format against an f64 reference.

mod analysis;
mod canvas;
mod cli;
mod commands;
mod cost;
mod firmware;
mod format;
mod heatmap;
mod metrics;
mod owned;
mod pareto;
#[cfg(test)]
mod peak;
mod plot;
mod render;
mod scene_file;
mod stress;
mod timing;
mod variant;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    match commands::run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
