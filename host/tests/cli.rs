//! The `obscura` command as a user runs it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn obscura(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn scenes_lists_the_built_in_scenes() {
    let output = obscura(&["scenes"]);
    assert!(output.status.success());
    let text = stdout(&output);
    assert!(
        text.contains("whitted") && text.contains("shapes"),
        "{text}"
    );
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let dir = scratch("render");
    let file = dir.join("shapes.png");
    let file = file.to_str().unwrap();
    let output = obscura(&[
        "render", "shapes", "--format", "i16f16", "--size", "40x24", "-o", file,
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let image = image::open(file).unwrap();
    assert_eq!((image.width(), image.height()), (40, 24));
}

#[test]
fn compare_writes_three_images_a_table_and_json() {
    let dir = scratch("compare");
    let json = dir.join("report.json");
    let output = obscura(&[
        "compare",
        "whitted",
        "--format",
        "i16f16",
        "--size",
        "48x32",
        "--runs",
        "1",
        "--out-dir",
        dir.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    for name in ["i16f16.png", "f64.png", "diff.png"] {
        assert!(dir.join(name).exists(), "{name} missing");
    }
    assert!(
        stdout(&output).contains("| whitted | 48x32 | i16f16 |"),
        "{}",
        stdout(&output)
    );
    let report = read_json(&json);
    for key in [
        "format",
        "reference",
        "scene",
        "width",
        "height",
        "psnr_db",
        "mean_abs_error",
        "max_abs_error",
        "differing_pixels_pct",
        "object_mismatch_pct",
        "ms_per_frame",
        "reference_ms_per_frame",
    ] {
        assert!(report.get(key).is_some(), "no {key} in {report}");
    }
    assert_eq!(report["format"], "i16f16");
    assert_eq!(report["reference"], "f64");
    assert_eq!(
        (report["width"].as_u64(), report["height"].as_u64()),
        (Some(48), Some(32))
    );
    assert!(report["psnr_db"].as_f64().unwrap() > 30.0, "{report}");
    assert!(
        report["object_mismatch_pct"].as_f64().unwrap() < 1.0,
        "{report}"
    );
}

#[test]
fn compare_measures_the_samples_against_a_converged_render() {
    let dir = scratch("converged");
    let json = dir.join("report.json");
    let converged = |samples: &str| {
        let output = obscura(&[
            "compare",
            "shapes",
            "--format",
            "f64",
            "--size",
            "16x16",
            "--runs",
            "1",
            "--samples",
            samples,
            "--converged",
            "64",
            "--out-dir",
            dir.to_str().unwrap(),
            "--json",
            json.to_str().unwrap(),
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        assert!(
            stdout(&output).contains(&format!("how far {samples} are from converged")),
            "{}",
            stdout(&output)
        );
        read_json(&json)["converged"].clone()
    };
    // Four samples are some way from 64; the format is f64 itself, so both images measure alike.
    let four = converged("4");
    assert_eq!(
        (four["samples"].as_u64(), four["scene_samples"].as_u64()),
        (Some(64), Some(4))
    );
    let psnr = four["psnr_db"].as_f64().unwrap();
    assert!((10.0..60.0).contains(&psnr), "{four}");
    assert_eq!(four["reference_psnr_db"], four["psnr_db"]);
    // 64 samples are the converged render.
    assert!(converged("64")["psnr_db"].is_null());
}

#[test]
fn comparing_f64_with_itself_is_identical() {
    let dir = scratch("identical");
    let json = dir.join("report.json");
    let output = obscura(&[
        "compare",
        "shapes",
        "--format",
        "f64",
        "--size",
        "16x16",
        "--runs",
        "1",
        "--out-dir",
        dir.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stdout(&output).contains("identical"));
    let report = read_json(&json);
    assert!(
        report["psnr_db"].is_null(),
        "infinite PSNR is null in JSON: {report}"
    );
    assert_eq!(report["max_abs_error"], 0);
}

#[test]
fn bench_reports_ratios_and_thread_speedup() {
    let output = obscura(&[
        "bench",
        "shapes",
        "--size",
        "16x16",
        "--runs",
        "1",
        "--formats",
        "i16f16",
        "--threads",
        "1,2",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains("| i16f16 |"), "{text}");
    assert!(
        text.contains("time ÷ f32") && text.contains("| i16f16 | 2 |"),
        "{text}"
    );
}

#[test]
fn bad_arguments_fail_with_a_clear_message() {
    let cases: [(&[&str], &str); 11] = [
        (
            &["render", "teapot"],
            "give a built-in scene (whitted, shapes, soft, focus) or a scene file",
        ),
        (
            &["analyze", "whitted", "--target-psnr", "lots"],
            "not a PSNR to aim for",
        ),
        (
            &[
                "firmware",
                "--target",
                "m0",
                "--scene",
                "no-such-scene.toml",
            ],
            "there is no scene `no-such-scene.toml`",
        ),
        (&["render", "whitted", "--size", "512"], "WIDTHxHEIGHT"),
        (&["render", "whitted", "--size", "0x10"], "1 to 8192"),
        (&["render", "whitted", "--format", "q15"], "i16f16"),
        (&["compare", "whitted", "--runs", "0"], "runs"),
        (
            &["compare", "whitted", "--samples", "0"],
            "from 1 to 256, not `0`",
        ),
        (
            &["compare", "soft", "--shadow-samples", "300"],
            "from 1 to 256, not `300`",
        ),
        (&["compare", "soft", "--adaptive-shadows", "maybe"], "true"),
        (&["compare", "whitted", "--converged", "257"], "1..=256"),
    ];
    for (args, expected) in cases {
        let output = obscura(args);
        assert!(!output.status.success(), "{args:?} succeeded");
        let message = stderr(&output);
        assert!(message.contains(expected), "{args:?}: {message}");
    }
}

#[test]
fn an_unwritable_output_is_reported() {
    let dir = scratch("unwritable");
    std::fs::write(dir.join("a-file"), b"").unwrap();
    let path = dir.join("a-file/x.png");
    let path = path.to_str().unwrap();
    let output = obscura(&["render", "shapes", "--size", "8x8", "-o", path]);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains(&format!("cannot write {path}")),
        "{message}"
    );
}

#[test]
fn firmware_refuses_f64_and_unknown_targets() {
    let output = obscura(&["firmware", "--target", "m4f", "--format", "f64"]);
    assert!(!output.status.success());
    assert!(stderr(&output).contains("not f64"), "{}", stderr(&output));
    let output = obscura(&["firmware", "--target", "riscv"]);
    assert!(!output.status.success());
    assert!(stderr(&output).contains("m4f"), "{}", stderr(&output));
}

#[test]
fn bench_times_fast_roots_against_f32_by_exact_roots() {
    let output = obscura(&[
        "bench",
        "whitted",
        "--size",
        "16x16",
        "--formats",
        "i16f16",
        "--sqrt",
        "approx",
        "--runs",
        "1",
        "--threads",
        "1",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(
        stdout(&output).contains("by exact roots"),
        "{}",
        stdout(&output)
    );
    let output = obscura(&["bench", "whitted", "--threads", "0"]);
    assert!(!output.status.success());
    assert!(stderr(&output).contains("--threads"), "{}", stderr(&output));
}

#[test]
fn firmware_refuses_what_it_cannot_draw_before_building() {
    // No cargo on the PATH: the refusal must come before any build.
    let output = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args([
            "firmware", "--target", "m0", "--scene", "shapes", "--format", "i20f12",
        ])
        .env("PATH", scratch("no-cargo"))
        .output()
        .unwrap();
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("cannot draw shapes in i20f12") && message.contains("below the"),
        "{message}"
    );
    let output = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args([
            "firmware", "--target", "m4f", "--format", "f32", "--sqrt", "approx",
        ])
        .env("PATH", scratch("no-cargo"))
        .output()
        .unwrap();
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(message.contains("f32-approx"), "{message}");
    // A scene file's refusal is placed at its line and column, the line shown.
    let low_light = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/hostile/low-light.toml");
    let output = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(["firmware", "--target", "m0", "--scene", low_light])
        .args(["--format", "i16f16"])
        .env("PATH", scratch("no-cargo"))
        .output()
        .unwrap();
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("low-light.toml:14:1: the scene cannot be built in i16f16")
            && message.contains("14 | [[lights]]"),
        "{message}"
    );
}

#[test]
fn a_format_measured_useless_is_refused_unless_forced() {
    let checker = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/hostile/checker-1e6.toml"
    );
    let dir = scratch("useless");
    let file = dir.join("checker.png");
    let file = file.to_str().unwrap();
    let render = [
        "render", checker, "--format", "i16f16", "--size", "64x64", "-o", file,
    ];
    let output = obscura(&render);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("i16f16 by lecture measures only")
            && message.contains("below the 20 dB of --refuse-below")
            && message.contains("formats predicted to reach it: i32f32")
            && message.contains("--force"),
        "{message}"
    );
    assert!(!Path::new(file).exists(), "nothing is drawn");
    let output = obscura(&[&render[..], &["--force"]].concat());
    assert!(output.status.success(), "{}", stderr(&output));
    // The floor is the user's: whitted in i16f16, about 41 dB, passes 20 and not 60.
    let whitted = [
        "render", "whitted", "--format", "i16f16", "--size", "64x64", "-o", file,
    ];
    assert!(obscura(&whitted).status.success());
    let output = obscura(&[&whitted[..], &["--refuse-below", "60"]].concat());
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("below the 60 dB of --refuse-below"),
        "{}",
        stderr(&output)
    );
    // The display's commands refuse it too, before building or drawing anything.
    let output = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(["firmware", "--target", "m4f", "--scene", checker])
        .args(["--format", "i16f16"])
        .env("PATH", scratch("no-cargo-useless"))
        .output()
        .unwrap();
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("checker-1e6: i16f16 by lecture measures only"),
        "{message}"
    );
    let preview = dir.join("preview.png");
    let output = obscura(&[
        "preview",
        checker,
        "--format",
        "i16f16",
        "--headless",
        "-o",
        preview.to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    assert!(stderr(&output).contains("--force"), "{}", stderr(&output));
}

#[test]
fn a_format_the_reference_cannot_check_is_refused_unless_forced() {
    let tilt = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/hostile/tilt-beyond-f64.toml"
    );
    let dir = scratch("unchecked");
    let file = dir.join("tilt.png");
    let file = file.to_str().unwrap();
    let render = [
        "render", tilt, "--format", "i32f32", "--size", "64x64", "-o", file,
    ];
    let output = obscura(&render);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("tilt-beyond-f64.toml:12:1: i32f32 by lecture holds the scene, but the f64 reference does not, so nothing can check what i32f32 draws")
            && message.contains("the scene cannot be built in f64: the camera")
            && message.contains("--force"),
        "{message}"
    );
    assert!(!Path::new(file).exists(), "nothing is drawn");
    // analyze agrees: no format can hold what f64 cannot.
    let output = obscura(&["analyze", tilt, "--size", "64x64"]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("no format can hold the scene"),
        "{}",
        stderr(&output)
    );
    let output = obscura(&[&render[..], &["--force"]].concat());
    assert!(output.status.success(), "{}", stderr(&output));
}

#[test]
fn firmware_without_qemu_says_how_to_install_it() {
    // A PATH with rustc on it and nothing else: no QEMU (and perhaps no thumb target).
    let dir = scratch("no-qemu");
    let rustc = Command::new("sh")
        .args(["-c", "command -v rustc"])
        .output()
        .unwrap();
    let rustc = String::from_utf8_lossy(&rustc.stdout).trim().to_owned();
    std::os::unix::fs::symlink(&rustc, dir.join("rustc")).unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(["firmware", "--target", "m0"])
        .env("PATH", &dir)
        .output()
        .unwrap();
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("apt-get install qemu-system-arm")
            || message.contains("rustup target add thumbv6m-none-eabi"),
        "{message}"
    );
}

#[test]
fn analyze_tables_the_bits_the_formats_and_the_cheapest() {
    let output = obscura(&["analyze", "shapes", "--size", "64x64", "--cost-on", "m0"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    for expected in [
        "smallest sphere radius",
        "| triangles, by watertight |",
        "| i20f12 | i2f14 | no: object 2: radius² seen from the eye",
        "| i12f20 | i2f30 | yes |",
        "the cheapest on the Cortex-M0 that reaches 40 dB:",
    ] {
        assert!(text.contains(expected), "{expected}: {text}");
    }
    // The chart prices one ray per pixel and per light: said where a scene takes more.
    let one_ray = "The chart measures one ray per pixel and one shadow ray per light";
    assert!(!text.contains(one_ray), "{text}");
    let output = obscura(&["analyze", "soft", "--size", "16x16"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(
        text.contains(one_ray) && text.contains("up to 16 shadow rays per area light"),
        "{text}"
    );
}

#[test]
fn format_auto_rescales_a_scene_file_when_only_that_fits_and_picks_its_pixels() {
    let dir = scratch("auto");
    let marbles = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/marbles.toml");
    let compare = |pixels: &[&str]| {
        let mut args = vec![
            "compare",
            marbles,
            "--format",
            "auto",
            "--cost-on",
            "m0",
            "--target-psnr",
            "35",
            "--size",
            "64x64",
            "--runs",
            "1",
            "--out-dir",
            dir.to_str().unwrap(),
        ];
        args.extend(pixels);
        let output = obscura(&args);
        assert!(output.status.success(), "{}", stderr(&output));
        (stderr(&output), stdout(&output))
    };
    // marbles is too large for every 32-bit split; the cheapest on the M0, i16f16, holds it
    // rescaled, and its adaptive pixels are cheaper there and reach 35 dB: auto takes them.
    let (message, table) = compare(&[]);
    assert!(
        message.contains("--format auto: i16f16 with adaptive:")
            && message.contains("rescaled by 0.0625"),
        "{message}"
    );
    assert!(table.contains("| marbles, adaptive:"), "{table}");
    // Pixels given are kept.
    let (message, table) = compare(&["--pixels", "exact"]);
    assert!(
        message.contains("--format auto: i16f16 is the cheapest"),
        "{message}"
    );
    assert!(table.contains("| marbles | 64x64 | i16f16 |"), "{table}");
}

#[test]
fn a_malformed_scene_file_says_where() {
    let dir = scratch("malformed");
    let file = dir.join("broken.toml");
    std::fs::write(&file, "far = 10.0\ncamera = { eye = [0.0, 0.0] }\n").unwrap();
    let output = obscura(&["render", file.to_str().unwrap(), "--size", "8x8"]);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("broken.toml:2:18: camera.eye has 2 numbers")
            && message.contains("2 | camera = { eye = [0.0, 0.0] }")
            && message.contains("  |                  ^^^^^^^^^^"),
        "{message}"
    );
}

#[test]
fn a_refused_value_is_named_by_its_line_and_column() {
    let dir = scratch("refused");
    let marbles =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/marbles.toml"))
            .unwrap();
    let file = dir.join("marbles.toml");
    let line = marbles
        .lines()
        .position(|l| l.contains("ior = 1.5"))
        .unwrap();
    std::fs::write(&file, marbles.replace("ior = 1.5", "ior = 0.5")).unwrap();
    for command in ["render", "analyze", "compare"] {
        let output = obscura(&[command, file.to_str().unwrap(), "--size", "8x8"]);
        assert!(!output.status.success());
        let message = stderr(&output);
        assert!(
            message.contains(&format!("marbles.toml:{}:", line + 1))
                && message.contains("object 2: material.ior is 0.5, but it must be ≥ 1"),
            "{command}: {message}"
        );
    }
}

#[test]
fn a_directory_or_an_outsize_file_is_not_read_as_a_scene() {
    let dir = scratch("not-a-scene");
    let output = obscura(&["render", dir.to_str().unwrap()]);
    assert!(
        stderr(&output).contains("is a directory"),
        "{}",
        stderr(&output)
    );
    let big = dir.join("big.toml");
    std::fs::write(&big, "# padding\n".repeat(200_000)).unwrap();
    let output = obscura(&["analyze", big.to_str().unwrap()]);
    assert!(
        stderr(&output).contains("larger than a scene file may be"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn a_reader_that_stops_early_ends_the_command_quietly() {
    // The reader has gone before the first line, as in `obscura scenes | head -0`.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let output = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .arg("scenes")
        .stdout(writer)
        .output()
        .unwrap();
    let message = stderr(&output);
    assert!(output.status.success(), "{message}");
    assert!(message.is_empty(), "{message}");
}

/// `obscura ARGS` writing its standard output into a full disk (`None` off Linux).
fn into_a_full_disk(args: &[&str]) -> Option<Output> {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .ok()?;
    let output = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(args)
        .stdout(full)
        .output()
        .unwrap();
    Some(output)
}

#[test]
fn a_full_disk_on_standard_output_is_an_error_not_a_panic() {
    // Help and the version are output like any other.
    for args in [&["scenes"][..], &["--help"], &["--version"]] {
        let Some(output) = into_a_full_disk(args) else {
            return; // not a Linux machine
        };
        assert!(!output.status.success(), "{args:?}");
        let message = stderr(&output);
        assert!(
            message.starts_with("error: cannot write standard output")
                && !message.contains("panicked"),
            "{args:?}: {message}"
        );
    }
}

#[test]
fn a_target_psnr_no_image_can_reach_is_refused_briefly() {
    let output = obscura(&[
        "compare",
        "whitted",
        "--format",
        "auto",
        "--target-psnr",
        "1e308",
    ]);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("`1e308` is not a PSNR to aim for") && message.len() < 400,
        "{message}"
    );
}

#[test]
fn outputs_are_checked_before_any_work() {
    let dir = scratch("outputs");
    let images = dir.join("images");
    // The JSON report cannot be written (its directory would be in a file), so no image is
    // rendered either.
    std::fs::write(dir.join("a-file"), b"").unwrap();
    let output = obscura(&[
        "compare",
        "whitted",
        "--size",
        "64x64",
        "--out-dir",
        images.to_str().unwrap(),
        "--json",
        dir.join("a-file/report.json").to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("report.json"),
        "{}",
        stderr(&output)
    );
    assert!(!images.join("diff.png").exists());

    let unknown = obscura(&[
        "render",
        "shapes",
        "-o",
        dir.join("x.jpeg2").to_str().unwrap(),
    ]);
    assert!(
        stderr(&unknown).contains("name it .png"),
        "{}",
        stderr(&unknown)
    );
    let directory = obscura(&["render", "shapes", "-o", dir.to_str().unwrap()]);
    assert!(
        stderr(&directory).contains("is a directory"),
        "{}",
        stderr(&directory)
    );
}

#[test]
fn fuzz_tries_a_given_number_of_scenes_and_tallies_them() {
    let dir = scratch("fuzz");
    let json = dir.join("tally.json");
    let output = obscura(&[
        "fuzz",
        "--scenes",
        "6",
        "--seed",
        "3",
        "--out-dir",
        dir.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(
        stdout(&output).contains("fuzz seed 3"),
        "{}",
        stdout(&output)
    );
    let tally = read_json(&json);
    assert_eq!(tally["scenes"], 6);
    assert!(tally["builds"].as_u64().unwrap() >= 6 * 5, "{tally}");
    assert_eq!(tally["findings"].as_array().unwrap().len(), 0, "{tally}");
}

#[test]
fn preview_writes_the_display_frame_headless_and_says_when_it_has_no_window() {
    let path = scratch("preview").join("frame.png");
    let output = obscura(&[
        "preview",
        "whitted",
        "--format",
        "i16f16",
        "--headless",
        "-o",
        path.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let frame = image::open(&path).unwrap();
    assert_eq!((frame.width(), frame.height()), (240, 240));
    if !cfg!(feature = "window") {
        let output = obscura(&["preview", "whitted", "-o", path.to_str().unwrap()]);
        assert!(!output.status.success());
        assert!(
            stderr(&output).contains("--headless"),
            "{}",
            stderr(&output)
        );
    }
}

#[test]
fn every_example_scene_file_renders_in_the_format_auto_picks() {
    let dir = scratch("examples");
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&examples)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 4, "{files:?}");
    for file in files {
        let out = dir.join(file.file_stem().unwrap()).with_extension("png");
        let output = obscura(&[
            "render",
            file.to_str().unwrap(),
            "--format",
            "auto",
            // The files' build and render, not their accuracy, which a picture this small
            // cannot show: at 48×32 no format is predicted 40 dB on tinyraytracer's (each pixel
            // is most of a checker square far off, and i32f32 measures 26 dB).
            "--target-psnr",
            "15",
            "--size",
            "48x32",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(
            output.status.success(),
            "{}: {}",
            file.display(),
            stderr(&output)
        );
        assert!(out.is_file(), "{}", file.display());
    }
}

#[test]
fn every_command_writes_into_out_unless_told_otherwise() {
    let dir = scratch("defaults");
    for args in [
        &["render", "shapes", "--size", "8x8"][..],
        &["compare", "shapes", "--size", "8x8", "--runs", "1"][..],
        &["preview", "shapes", "--headless"][..],
    ] {
        let output = Command::new(env!("CARGO_BIN_EXE_obscura"))
            .args(args)
            .current_dir(&dir)
            .output()
            .expect("the binary runs");
        assert!(output.status.success(), "{args:?}: {}", stderr(&output));
    }
    for written in [
        "render.png",
        "i16f16.png",
        "f64.png",
        "diff.png",
        "preview.png",
    ] {
        assert!(dir.join("out").join(written).is_file(), "out/{written}");
    }
}

#[test]
fn animate_writes_a_looping_gif_and_a_row_per_frame_the_worst_last() {
    let dir = scratch("animate");
    let (gif, json) = (dir.join("orbit.gif"), dir.join("orbit.json"));
    let orbit = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/orbit.toml");
    let output = obscura(&[
        "animate",
        orbit,
        "--format",
        "i16f16",
        "--size",
        "48x48",
        "-o",
        gif.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(
        std::fs::File::open(&gif).unwrap(),
    ))
    .unwrap();
    let frames = image::AnimationDecoder::into_frames(decoder)
        .collect_frames()
        .unwrap();
    assert_eq!(frames.len(), 16);
    assert_eq!(frames[0].buffer().dimensions(), (48, 48));
    let rows = read_json(&json);
    let rows = rows.as_array().unwrap();
    assert_eq!(rows.len(), 16);
    let worst = rows
        .iter()
        .min_by(|a, b| {
            a["psnr_db"]
                .as_f64()
                .unwrap()
                .total_cmp(&b["psnr_db"].as_f64().unwrap())
        })
        .unwrap();
    let text = stdout(&output);
    let last = text.lines().rfind(|l| !l.starts_with("wrote")).unwrap();
    assert!(
        last.starts_with(&format!("the worst frame: {} of orbit", worst["frame"])),
        "{text}"
    );
    // A scene without a path says how to give it one; a frame the format cannot hold is named.
    let still = obscura(&["animate", "whitted", "-o", gif.to_str().unwrap()]);
    assert!(
        stderr(&still).contains("has no camera path"),
        "{}",
        stderr(&still)
    );
    let coarse = obscura(&[
        "animate",
        orbit,
        "--format",
        "i20f12",
        "--size",
        "48x48",
        "-o",
        gif.to_str().unwrap(),
    ]);
    assert!(!coarse.status.success());
    assert!(
        stderr(&coarse)
            .contains("frame 0 of orbit's 16 frames: the scene cannot be built in i20f12"),
        "{}",
        stderr(&coarse)
    );
    // At a board's pace: each frame held as long as the Pico takes to draw it, the loop printed.
    let paced = obscura(&[
        "animate",
        orbit,
        "--format",
        "i16f16",
        "--size",
        "48x48",
        "--pace-of",
        "m0",
        "-o",
        gif.to_str().unwrap(),
    ]);
    assert!(paced.status.success(), "{}", stderr(&paced));
    let text = stdout(&paced);
    let prefix = "on the Raspberry Pi Pico (RP2040, Cortex-M0+) (estimated, 240x240): ";
    let line = text.lines().find(|l| l.starts_with(prefix)).expect(&text);
    let loop_seconds: f64 = line[prefix.len()..]
        .split(" s a loop")
        .next()
        .and_then(|s| s.parse().ok())
        .expect(line);
    let held: f64 = gif_delays(&gif).iter().sum();
    assert!(
        (held - loop_seconds).abs() < 0.01 * 16.0,
        "{held} s held, {line}"
    );
    assert!(loop_seconds > 16.0 * 0.5, "{line}");
}

/// Each frame's delay in the GIF at `path`, in seconds.
fn gif_delays(path: &Path) -> Vec<f64> {
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(
        std::fs::File::open(path).unwrap(),
    ))
    .unwrap();
    image::AnimationDecoder::into_frames(decoder)
        .collect_frames()
        .unwrap()
        .iter()
        .map(|f| {
            let (numer, denom) = f.delay().numer_denom_ms();
            f64::from(numer) / f64::from(denom) / 1000.0
        })
        .collect()
}

#[test]
fn preview_plays_a_camera_path_headless_into_a_gif() {
    let dir = scratch("preview-path");
    let png = dir.join("orbit.png");
    let orbit = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/orbit.toml");
    let output = obscura(&[
        "preview",
        orbit,
        "--target",
        "m0",
        "--format",
        "i16f16",
        "--headless",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(
        stdout(&output).contains("orbit's 16 frames in i16f16"),
        "{}",
        stdout(&output)
    );
    let gif = std::fs::File::open(dir.join("orbit.gif")).unwrap();
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(gif)).unwrap();
    let frames = image::AnimationDecoder::into_frames(decoder)
        .collect_frames()
        .unwrap();
    assert_eq!(frames.len(), 16);
    assert_eq!(frames[0].buffer().dimensions(), (240, 240));
    // At the board's pace, over a second a frame in i16f16 on the Pico, not the path's own.
    let delays = gif_delays(&dir.join("orbit.gif"));
    assert!(delays.iter().all(|&d| d > 1.0), "{delays:?}");
}

#[test]
fn analyze_takes_every_frame_of_a_camera_path() {
    let orbit = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/orbit.toml");
    let output = obscura(&["analyze", orbit, "--size", "32x32"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(
        text.contains("orbit's camera path has 16 frames, each analysed for its own camera"),
        "{text}"
    );
    assert!(
        text.contains("the cheapest on the Cortex-M4F that reaches 40 dB"),
        "{text}"
    );
}

/// `obscura book` in `dir` with `args`.
fn book(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_obscura"))
        .arg("book")
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

#[test]
fn book_writes_each_figure_and_its_check_names_each_that_drifted() {
    let dir = scratch("book");
    std::fs::create_dir_all(dir.join("docs/images")).unwrap();
    std::fs::write(dir.join("docs/SUMMARY.md"), "# Summary\n").unwrap();
    let page = "# Page\n\n<!-- book: obscura scenes | head -n 1 -->\n<!-- /book -->\n\n\
                <!-- book slow: printf 'a picture' > docs/images/a.txt; echo wrote it -->\n<!-- /book -->\n";
    std::fs::write(dir.join("README.md"), page).unwrap();
    let written = book(&dir, &[]);
    assert!(written.status.success(), "{}", stderr(&written));
    let readme = std::fs::read_to_string(dir.join("README.md")).unwrap();
    assert!(
        readme.contains("```text\n$ obscura scenes | head -n 1\nwhitted ")
            && readme.contains("$ printf 'a picture' > docs/images/a.txt; echo wrote it\nwrote it\n```\n<!-- /book -->"),
        "{readme}"
    );
    assert!(book(&dir, &["--check"]).status.success());

    // A figure edited by hand, and a picture that is not what its command writes.
    std::fs::write(
        dir.join("README.md"),
        readme.replace("wrote it\n```", "wrote that\n```"),
    )
    .unwrap();
    std::fs::write(dir.join("docs/images/a.txt"), "another picture").unwrap();
    let checked = book(&dir, &["--check"]);
    assert!(!checked.status.success());
    let said = stdout(&checked);
    assert!(
        said.contains("README.md:")
            && said.contains("prints something else; line 3 of the block")
            && said.contains("writes docs/images/a.txt other than the repository's"),
        "{said}"
    );
    // The check writes nothing: the page's picture is back.
    assert_eq!(
        std::fs::read_to_string(dir.join("docs/images/a.txt")).unwrap(),
        "another picture"
    );
    // --quick leaves the slow block out, so only what is quick is checked.
    assert!(book(&dir, &["--check", "--quick"]).status.success());

    // A marker that does not parse is placed at its line and column.
    std::fs::write(
        dir.join("README.md"),
        "<!-- book soon: echo -->\n<!-- /book -->\n",
    )
    .unwrap();
    let refused = book(&dir, &[]);
    assert!(
        stderr(&refused).contains("README.md:1:11: `soon` is not a word a book marker takes"),
        "{}",
        stderr(&refused)
    );
    // A command that must fail but does not.
    std::fs::write(
        dir.join("README.md"),
        "<!-- book fails: true -->\n<!-- /book -->\n",
    )
    .unwrap();
    let refused = book(&dir, &[]);
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("README.md:1"),
        "{}",
        stderr(&refused)
    );
}
