//! `obscura bench`: host speed, as ratios measured in one run (absolute times drift between
//! machines and runs; ratios taken side by side, interleaved, do not).

use crate::cli::BenchArgs;
use crate::output::{self, say};
use crate::render::{Request, exact_roots, prepare};
use crate::timing::interleaved_median_ms;
use anyhow::{Context, Result};
use obscura::Methods;
use obscura_scene::{Format, NamedScene};
use serde::Serialize;

#[derive(Debug, Serialize)]
struct FormatTime {
    format: &'static str,
    ms_per_frame: f64,
    ratio_to_f32: f64,
}

#[derive(Debug, Serialize)]
struct ThreadTime {
    format: &'static str,
    threads: u16,
    ms_per_frame: f64,
    speedup: f64,
}

#[derive(Debug, Serialize)]
struct Bench {
    scene: String,
    width: u32,
    height: u32,
    runs: u16,
    formats: Vec<FormatTime>,
    threads: Vec<ThreadTime>,
}

/// Minutes Whitted's 512×512 image took on a VAX-11/780 (Whitted, 1980).
const VAX_MINUTES: f64 = 74.0;

pub fn run(args: &BenchArgs) -> Result<()> {
    if let Some(path) = &args.json {
        output::check_file(path)?;
    }
    super::on_scene(&args.scene, &args.sampling, |named| bench(args, named))
}

fn bench(args: &BenchArgs, named: &NamedScene) -> Result<()> {
    let methods = args.methods.methods();
    let mut jobs: Vec<(Format, Methods)> = args.formats.iter().map(|&f| (f, methods)).collect();
    if !args.formats.contains(&Format::F32) {
        // The baseline, by the same methods but for the fast roots, which f32 does not have.
        jobs.push((Format::F32, exact_roots(methods)));
    }
    let bench = time(args, named, &jobs)?;
    print(&bench, jobs.iter().any(|&(_, m)| m != methods))?;
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&bench)?;
        std::fs::write(path, text + "\n")
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}

/// Times every job on one thread and the first on each thread count asked for, all
/// interleaved; each against f32 and against one thread.
fn time(args: &BenchArgs, named: &NamedScene, jobs: &[(Format, Methods)]) -> Result<Bench> {
    let (width, height) = args.size;
    let first = *args.formats.first().context("give at least one format")?;
    let renderers = jobs
        .iter()
        .map(|&(format, methods)| {
            let request = Request::new(named.scene.desc(), args.size, methods);
            prepare(format, &request)
        })
        .collect::<Result<Vec<_>>>()?;
    let mut configs: Vec<(usize, u16)> = (0..jobs.len()).map(|i| (i, 1)).collect();
    configs.extend(args.threads.iter().filter(|&&n| n != 1).map(|&n| (0, n)));
    let tasks: Vec<Box<dyn Fn() + '_>> = configs
        .iter()
        .map(|&(i, threads)| -> Box<dyn Fn() + '_> {
            let render = &renderers[i];
            Box::new(move || drop(render.render(usize::from(threads), None)))
        })
        .collect();
    eprintln!(
        "timing {} configurations of {}, {} runs each, interleaved",
        tasks.len(),
        named.name,
        args.runs
    );
    let task_refs: Vec<&dyn Fn()> = tasks.iter().map(|task| &**task).collect();
    let times = interleaved_median_ms(usize::from(args.runs), &task_refs);
    let time_of = |format_index: usize, threads: u16| {
        configs
            .iter()
            .position(|&c| c == (format_index, threads))
            .map(|k| times[k])
    };
    let f32_index = jobs
        .iter()
        .position(|&(f, _)| f == Format::F32)
        .context("f32 is timed")?;
    let f32_ms = time_of(f32_index, 1).context("f32 is timed on one thread")?;
    let formats = args
        .formats
        .iter()
        .enumerate()
        .filter_map(|(i, format)| {
            let ms = time_of(i, 1)?;
            Some(FormatTime {
                format: format.name(),
                ms_per_frame: ms,
                ratio_to_f32: ms / f32_ms,
            })
        })
        .collect();
    let one_thread = time_of(0, 1).context("the first format is timed on one thread")?;
    let threads = args
        .threads
        .iter()
        .filter_map(|&n| {
            let ms = time_of(0, n)?;
            Some(ThreadTime {
                format: first.name(),
                threads: n,
                ms_per_frame: ms,
                speedup: one_thread / ms,
            })
        })
        .collect();
    Ok(Bench {
        scene: named.name.clone(),
        width,
        height,
        runs: args.runs,
        formats,
        threads,
    })
}

/// The two tables (`f32_by_exact_roots`: f32 was timed by exact roots, as it has no fast ones),
/// and for Whitted's own picture the VAX's 74 minutes beside it. Where times are not shown
/// ([`crate::timing::shown`]), only their ratios, measured in this run.
fn print(bench: &Bench, f32_by_exact_roots: bool) -> std::io::Result<()> {
    use crate::timing::or_omitted;
    // A time's cell, the column's heading and rule: nothing where times are not shown.
    let ms = |ms: f64| or_omitted(|| format!(" {ms:.1} |"));
    let heading = or_omitted(|| " ms/frame |".to_owned());
    let rule = or_omitted(|| "---:|".to_owned());
    say!(
        "{} {}x{}, median of {} interleaved runs:",
        bench.scene,
        bench.width,
        bench.height,
        bench.runs
    )?;
    say!("| format |{heading} time ÷ f32 (1 thread) |")?;
    say!("|---|{rule}---:|")?;
    for f in &bench.formats {
        say!(
            "| {} |{} {:.2} |",
            f.format,
            ms(f.ms_per_frame),
            f.ratio_to_f32
        )?;
    }
    if f32_by_exact_roots {
        say!("(f32, which has no fast roots, by exact roots)")?;
    }
    say!("")?;
    say!("| format | threads |{heading} speed-up over 1 thread |")?;
    say!("|---|---:|{rule}---:|")?;
    for t in &bench.threads {
        say!(
            "| {} | {} |{} {:.2} |",
            t.format,
            t.threads,
            ms(t.ms_per_frame),
            t.speedup
        )?;
    }
    // The first format on one thread.
    let one_thread = bench.formats.first();
    if let (true, Some(one)) = (
        bench.scene == "whitted" && (bench.width, bench.height) == (512, 512),
        one_thread,
    ) {
        let fastest = bench
            .threads
            .iter()
            .map(|t| t.ms_per_frame)
            .fold(one.ms_per_frame, f64::min);
        let taken = |ms: f64| or_omitted(|| format!("{ms:.1} ms, "));
        say!(
            "\nWhitted's spheres and checkerboard took {VAX_MINUTES} minutes on a VAX-11/780 in \
             1979; here {} takes {}{:.0}x less on one thread, and {}{:.0}x less on all threads \
             tried.",
            one.format,
            taken(one.ms_per_frame),
            VAX_MINUTES * 60_000.0 / one.ms_per_frame,
            taken(fastest),
            VAX_MINUTES * 60_000.0 / fastest
        )?;
    }
    Ok(())
}
