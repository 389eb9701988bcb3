//! `obscura`: the desktop harness of the obscura ray tracer. It runs the very same `no_std` core
//! as the firmware, writes PNGs, and measures each number format against an f64 reference.

mod canvas;
mod cli;
mod commands;
mod firmware;
mod format;
mod heatmap;
mod metrics;
mod render;
mod timing;

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
