//! `obscura fuzz`: random scenes against every promise the harness makes (see
//! [`crate::fuzz`]), for a time budget or a number of scenes.

use crate::cli::FuzzArgs;
use crate::fuzz::{self, Tally};
use crate::output::{self, say};
use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::time::{Duration, Instant};

/// How long a run lasts that gives neither seconds nor scenes.
const DEFAULT_SECONDS: u64 = 60;

/// Scenes tried between two looks at the clock.
const BATCH: u64 = 64;

pub fn run(args: &FuzzArgs) -> Result<()> {
    output::check_dir(&args.out_dir)?;
    if let Some(path) = &args.json {
        output::check_file(path)?;
    }
    let budget = match (args.seconds, args.scenes) {
        (Some(seconds), _) => Duration::from_secs(seconds),
        (None, Some(_)) => Duration::MAX,
        (None, None) => Duration::from_secs(DEFAULT_SECONDS),
    };
    let start = Instant::now();
    let bar = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::new_spinner();
        bar.set_style(ProgressStyle::with_template("{spinner} {elapsed} {msg}")?);
        bar.enable_steady_tick(Duration::from_millis(200));
        bar
    } else {
        ProgressBar::hidden()
    };
    let pool = fuzz::pool(usize::from(args.threads))?;
    let mut tally = Tally::default();
    let mut next = 0_u64;
    while start.elapsed() < budget && args.scenes.is_none_or(|n| next < n) {
        let end = args.scenes.map_or(next + BATCH, |n| (next + BATCH).min(n));
        tally.add(fuzz::try_scenes(
            &pool,
            args.seed,
            next..end,
            fuzz::method_sets,
            Some(&args.out_dir),
        ));
        next = end;
        bar.set_message(format!(
            "{} scenes, {} builds, {} failures",
            tally.scenes,
            tally.builds,
            tally.findings.len()
        ));
    }
    bar.finish_and_clear();
    for finding in &tally.findings {
        say!(
            "scene {} in {} by {} at {}x{}: {}{}",
            finding.seed,
            finding.format,
            finding.methods,
            finding.width,
            finding.height,
            finding.failure,
            finding
                .file
                .as_ref()
                .map_or(String::new(), |f| format!(" (see {})", f.display()))
        )?;
    }
    let time = crate::timing::or_omitted(|| format!(" in {:.0} s", start.elapsed().as_secs_f64()));
    say!("fuzz seed {}{time}: {tally}", args.seed)?;
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&tally)?;
        std::fs::write(path, text + "\n")
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    if !tally.clean() {
        bail!(
            "the fuzzer found {} failures; each scene is in {}",
            tally.findings.len(),
            args.out_dir.display()
        );
    }
    Ok(())
}
