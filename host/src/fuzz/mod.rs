//! `obscura fuzz`: random scenes ([`generate`]) built in every firmware format by the lecture's
//! methods and random mixes of the others, each rendered small with checked arithmetic and
//! measured against f64, so that every promise the harness makes is tried against scenes
//! nobody wrote by hand:
//!
//! - no sum or product leaves its format in a scene the build accepts (an **overflow**);
//! - the core never panics on any description (a **panic**);
//! - culling never leaves out an object a primary ray meets: no ray of a pixel (its centre's,
//!   or its corners') meets an object its row's ranges skip ([`obscura::cull`]; a **skipped
//!   hit**);
//! - `analyze`'s verdict and the build agree (a **disagreement**: analyze says a format holds
//!   the scene at this size and the build refuses it, or the reverse; `--format auto` measures
//!   the format it picks, so it cannot pick one the build refuses);
//! - where the f64 image is stable (nudging the eye by one ulp of f32 keeps it within
//!   [`STABLE_PSNR_DB`]), the measured error is no worse than the prediction by more than the
//!   margin (a **false accept**): the mean squared error at most twice the predicted (3 dB),
//!   plus [`SPARE_PIXELS`] pixels wrong in every channel; the object mismatch at most twice the
//!   predicted, plus as many pixels. (The model predicts the error to expect, and in a small
//!   image a handful of pixels on an edge flip or not by chance: beyond twice the expected
//!   count plus three, chance is under 0.1 %.)
//!
//! - the picture moves with the world ([`metamorphic`]): the scene and its eye translated
//!   together draw the same frame bit for bit in every format; by the lecture's methods, in f64,
//!   a world doubled draws the same picture, a mirrored one its mirror image, and an eye nudged
//!   by an ulp changes only pixels an edge passes through; and f32's prediction for the world
//!   doubled is the original's (a **metamorphic violation**).
//!
//! - adaptive pixels show every object exact pixels show: an eighth of the scenes of one ray a
//!   pixel through a pinhole (half of them with a ball one to three pixels wide before the
//!   rest) are drawn in blocks of 2, 4 or 8 too, in every format that builds
//!   them, and the object each pixel shows is exact pixels' but in a thousandth of them (a
//!   **metamorphic violation** of "adaptive pixels"; `try_blocks`).
//!
//! A sixth of the scenes put the world's edge at one of their objects ([`generate`]), where
//! `far` cuts a small disc from a plane or a sphere reaches across the world.
//!
//! Every failure is written as a scene file whose header says what failed and the command that
//! shows it.

#[cfg(test)]
mod corpus;
pub mod generate;
pub mod metamorphic;

use crate::analysis::{Analysis, Fit, Prediction, Reference, Verdict};
use crate::checked;
use crate::metrics::{Accuracy, accuracy};
use crate::render::{AnyFormat, Request, exact_roots, prepare, prepare_reference};
use anyhow::{Context, Result};
use image::RgbImage;
use obscura::methods::MethodName;
use obscura::{
    BiasMethod, Methods, Pixels, RayMethod, RootMethod, SceneDesc, SphereMethod, TriangleMethod,
};
use obscura_scene::{Format, OwnedScene};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rayon::prelude::*;
use rayon::{ThreadPool, ThreadPoolBuilder};
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// How many times its predicted mean squared error (and object mismatch) a measurement may
/// reach, besides [`SPARE_PIXELS`], before it is a false accept: 3 dB.
pub const MARGIN: f64 = 2.0;

/// Pixels a measurement may have wrong beyond [`MARGIN`] times the prediction.
pub const SPARE_PIXELS: f64 = 3.0;

/// An f64 image is stable when nudging the eye by one ulp keeps it at least this close, in dB:
/// where it is not, f64 itself cannot say what the picture is, and no format is held to it.
pub const STABLE_PSNR_DB: f64 = 60.0;

/// The formats every scene is built in (f64 is the reference).
const FORMATS: &[Format] = Format::FIRMWARE;

/// Random method mixes tried per scene, besides the lecture's.
const MIXES: usize = 2;

/// What went wrong with one build.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Failure {
    /// A sum or product left the format in a scene the build accepted.
    Overflow {
        /// The operation, its source line and the pixel.
        message: String,
    },
    /// The core panicked.
    Panic {
        /// The panic's message.
        message: String,
    },
    /// A primary ray meets an object that culling leaves out of its pixel, or a shadow ray one
    /// that its cone leaves out.
    SkippedHit {
        /// The pixel and the object.
        message: String,
    },
    /// `analyze` and the build disagree on whether the format holds the scene.
    Disagreement {
        /// What each said.
        message: String,
    },
    /// A picture did not move with the world as a metamorphic relation says.
    Metamorphic {
        /// The relation: translate, scale, mirror or nudge.
        relation: &'static str,
        /// What changed.
        message: String,
    },
    /// The measurement fell short of the prediction by more than the margin.
    FalseAccept {
        /// The predicted PSNR, in dB.
        predicted_psnr_db: f64,
        /// The measured PSNR, in dB.
        measured_psnr_db: f64,
        /// The predicted object mismatch, in percent.
        predicted_mismatch_pct: f64,
        /// The measured object mismatch, in percent.
        measured_mismatch_pct: f64,
    },
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Overflow { message } => write!(f, "overflow: {message}"),
            Self::Panic { message } => write!(f, "panic: {message}"),
            Self::SkippedHit { message } => write!(f, "skipped hit: {message}"),
            Self::Disagreement { message } => write!(f, "disagreement: {message}"),
            Self::Metamorphic { relation, message } => {
                write!(f, "metamorphic violation ({relation}): {message}")
            }
            Self::FalseAccept {
                predicted_psnr_db,
                measured_psnr_db,
                predicted_mismatch_pct,
                measured_mismatch_pct,
            } => write!(
                f,
                "false accept: predicted {predicted_psnr_db:.1} dB and {predicted_mismatch_pct:.3} % \
                 object mismatch, measured {measured_psnr_db:.1} dB and \
                 {measured_mismatch_pct:.3} %"
            ),
        }
    }
}

/// One failed build, with what reproduces it.
#[derive(Clone, Debug, Serialize)]
pub struct Finding {
    /// The scene's seed.
    pub seed: u64,
    /// The format.
    pub format: &'static str,
    /// The methods.
    #[serde(serialize_with = "crate::cli::serialize_display")]
    pub methods: Methods,
    /// The image size.
    pub width: u32,
    /// The image size.
    pub height: u32,
    /// What went wrong.
    pub failure: Failure,
    /// The scene file written for it.
    pub file: Option<PathBuf>,
}

/// What a run found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Tally {
    /// Scenes generated.
    pub scenes: u64,
    /// Scene × format × methods builds tried.
    pub builds: u64,
    /// Of those, the ones the build accepted (and that were rendered and measured).
    pub accepted: u64,
    /// Of those, the ones whose f64 image was stable, held to their prediction.
    pub held_to_prediction: u64,
    /// Builds that overflowed.
    pub overflows: u64,
    /// Builds that panicked.
    pub panics: u64,
    /// Builds where culling skipped an object a primary ray meets.
    pub skipped_hits: u64,
    /// Builds where analyze and the build disagreed.
    pub disagreements: u64,
    /// Metamorphic relations checked, by relation (translate counts each format).
    pub relations_checked: BTreeMap<&'static str, u64>,
    /// Of those, the ones the picture broke.
    pub metamorphic_violations: u64,
    /// Builds measured worse than predicted, beyond the margins.
    pub false_accepts: u64,
    /// The failures, each once.
    pub findings: Vec<Finding>,
}

impl Tally {
    /// Adds what another run found.
    pub fn add(&mut self, other: Self) {
        self.scenes += other.scenes;
        self.builds += other.builds;
        self.accepted += other.accepted;
        self.held_to_prediction += other.held_to_prediction;
        self.overflows += other.overflows;
        self.panics += other.panics;
        self.skipped_hits += other.skipped_hits;
        self.disagreements += other.disagreements;
        for (relation, count) in other.relations_checked {
            *self.relations_checked.entry(relation).or_default() += count;
        }
        self.metamorphic_violations += other.metamorphic_violations;
        self.false_accepts += other.false_accepts;
        self.findings.extend(other.findings);
    }

    fn record(&mut self, finding: Finding) {
        match finding.failure {
            Failure::Overflow { .. } => self.overflows += 1,
            Failure::Panic { .. } => self.panics += 1,
            Failure::SkippedHit { .. } => self.skipped_hits += 1,
            Failure::Disagreement { .. } => self.disagreements += 1,
            Failure::Metamorphic { .. } => self.metamorphic_violations += 1,
            Failure::FalseAccept { .. } => self.false_accepts += 1,
        }
        self.findings.push(finding);
    }

    fn check(&mut self, relation: &'static str) {
        *self.relations_checked.entry(relation).or_default() += 1;
    }

    /// Whether nothing failed.
    pub fn clean(&self) -> bool {
        self.findings.is_empty()
    }
}

impl fmt::Display for Tally {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} scenes, {} scene × format × method builds ({} accepted and rendered, {} of them \
             held to their prediction; metamorphic relations checked: {}): {} overflows, {} \
             panics, {} skipped hits, {} disagreements with analyze, {} false accepts, {} \
             metamorphic violations",
            self.scenes,
            self.builds,
            self.accepted,
            self.held_to_prediction,
            self.relations_checked
                .iter()
                .map(|(relation, count)| format!("{relation} {count}"))
                .collect::<Vec<_>>()
                .join(", "),
            self.overflows,
            self.panics,
            self.skipped_hits,
            self.disagreements,
            self.false_accepts,
            self.metamorphic_violations
        )
    }
}

/// The seed of scene `index` of a run seeded `seed`.
pub fn scene_seed(seed: u64, index: u64) -> u64 {
    seed.wrapping_mul(0x9E37_79B9_7F4A_7C15).wrapping_add(index)
}

/// The method sets scene `seed` is built by: the lecture's, and [`MIXES`] random mixes.
pub fn method_sets(seed: u64) -> Vec<Methods> {
    let mut rng = Pcg64::seed_from_u64(seed ^ 0x5EED);
    let mut pick = |n: usize| rng.random_range(0..n);
    let mut sets = vec![Methods::LECTURE];
    for _ in 0..MIXES {
        let methods = Methods {
            sphere: SphereMethod::ALL[pick(SphereMethod::ALL.len())].0,
            triangle: TriangleMethod::ALL[pick(TriangleMethod::ALL.len())].0,
            roots: RootMethod::ALL[pick(RootMethod::ALL.len())].0,
            rays: RayMethod::ALL[pick(RayMethod::ALL.len())].0,
            bias: BiasMethod::ALL[pick(BiasMethod::ALL.len())].0,
        };
        if !sets.contains(&methods) {
            sets.push(methods);
        }
    }
    sets
}

/// Each fuzzing thread's stack: a scene's analysis renders on it, and rayon may stack one
/// scene's work on another's while it waits, each holding scenes of the host's capacities
/// (with their shadow cones, 64 objects by 16 lights: 40 KiB a scene in f64). 64 MiB
/// overflowed in the corpus test once the cones came; the pages are only reserved.
const STACK_BYTES: usize = 256 << 20;

/// The threads scenes are tried on.
///
/// # Errors
/// When the threads cannot be started.
pub fn pool(threads: usize) -> Result<ThreadPool> {
    ThreadPoolBuilder::new()
        .num_threads(threads)
        .stack_size(STACK_BYTES)
        .build()
        .context("cannot start the fuzzer's threads")
}

/// Tries scenes `indices` of the run seeded `seed` on `pool`, each by the method sets
/// `methods_of` its seed (see [`try_scene`]).
pub fn try_scenes(
    pool: &ThreadPool,
    seed: u64,
    indices: Range<u64>,
    methods_of: impl Fn(u64) -> Vec<Methods> + Sync,
    out_dir: Option<&Path>,
) -> Tally {
    pool.install(|| {
        indices
            .into_par_iter()
            .map(|index| {
                let seed = scene_seed(seed, index);
                try_scene(seed, &methods_of(seed), out_dir)
            })
            .reduce(Tally::default, |mut a, b| {
                a.add(b);
                a
            })
    })
}

/// Generates the scene of `seed` and tries it in every format by each of `method_sets` (and
/// with adaptive pixels, where the generator gave it them), writing a reproducer for each
/// failure into `out_dir` (when given).
pub fn try_scene(seed: u64, method_sets: &[Methods], out_dir: Option<&Path>) -> Tally {
    let generated = generate::scene(seed);
    let size = generated.size;
    let mut tally = Tally {
        scenes: 1,
        ..Tally::default()
    };
    for &methods in method_sets {
        let scene = &generated.scene;
        let trial = |tally: &mut Tally| try_methods(scene, methods, size, tally);
        tally.add(caught(seed, methods, size, scene, out_dir, trial));
    }
    if let Some(blocks) = &generated.blocks {
        let trial = |tally: &mut Tally| try_blocks(blocks, size, tally);
        tally.add(caught(seed, Methods::LECTURE, size, blocks, out_dir, trial));
    }
    tally
}

/// What `trial` of `scene` (scene `seed`, by `methods` at `size`) found, a panic among it, each
/// finding with a reproducer of `scene` written into `out_dir` (when given).
fn caught(
    seed: u64,
    methods: Methods,
    (width, height): (u32, u32),
    scene: &OwnedScene,
    out_dir: Option<&Path>,
    trial: impl FnOnce(&mut Tally),
) -> Tally {
    let mut tally = Tally::default();
    if let Err(message) = checked::catch_any(|| trial(&mut tally)) {
        tally.record(Finding {
            seed,
            format: "f64",
            methods,
            width,
            height,
            failure: Failure::Panic { message },
            file: None,
        });
    }
    for finding in &mut tally.findings {
        finding.seed = seed;
        if let Some(dir) = out_dir {
            finding.file = write_reproducer(dir, scene, finding).ok();
        }
    }
    tally
}

/// Tries one scene by one method set in every format.
fn try_methods(
    scene: &OwnedScene,
    methods: Methods,
    (width, height): (u32, u32),
    tally: &mut Tally,
) {
    let request = Request::new(scene.desc(), (width, height), methods);
    let finding = |format: Format, failure| Finding {
        seed: 0,
        format: format.name(),
        methods,
        width,
        height,
        failure,
        file: None,
    };
    // A scene f64 refuses, every format refuses: validation is the same code for all.
    let Ok(reference) = Reference::render(&request.with_methods(exact_roots(methods))) else {
        for &format in FORMATS {
            tally.builds += 1;
            if prepare(format, &request).is_ok() {
                tally.record(finding(
                    format,
                    Failure::Disagreement {
                        message: "builds, although f64 refuses the scene".to_owned(),
                    },
                ));
            }
        }
        return;
    };
    let nudged = nudged(scene, &request);
    let stable = nudged
        .as_ref()
        .is_some_and(|(image, _)| psnr(image, &reference.image) >= STABLE_PSNR_DB);
    if methods == Methods::LECTURE {
        try_translation(scene, &request, tally, &finding);
        for (relation, broken) in
            f64_relations(scene, &request, &reference, nudged.as_ref(), stable)
        {
            tally.check(relation);
            if let Some(message) = broken {
                let failure = Failure::Metamorphic { relation, message };
                tally.record(finding(Format::F64, failure));
            }
        }
    }
    let analysis = Analysis::with_reference(scene, methods, &reference);
    if methods == Methods::LECTURE
        && stable
        && let Some(broken) = scaled_prediction(scene, &request, &analysis)
    {
        tally.check("scale prediction");
        if let Some(message) = broken {
            let relation = "scale prediction";
            tally.record(finding(
                Format::F32,
                Failure::Metamorphic { relation, message },
            ));
        }
    }
    for &format in FORMATS {
        tally.builds += 1;
        let verdict = analysis.verdicts.iter().find(|v| v.format == format);
        let predicted_holds = verdict.is_some_and(|v| v.fit == Fit::Holds);
        let prepared = match prepare(format, &request) {
            Ok(prepared) => prepared,
            Err(error) => {
                let message = format!("{error:#}");
                if message.contains("overflowed") {
                    tally.record(finding(format, Failure::Overflow { message }));
                } else if predicted_holds {
                    tally.record(finding(
                        format,
                        Failure::Disagreement {
                            message: format!("analyze says it holds; the build: {message}"),
                        },
                    ));
                }
                continue;
            }
        };
        if !predicted_holds {
            tally.record(finding(
                format,
                Failure::Disagreement {
                    message: "the build accepts what analyze refuses".to_owned(),
                },
            ));
            continue;
        }
        tally.accepted += 1;
        let measured = prepared
            .render(1, None)
            .and_then(|image| Ok((image, prepared.object_map()?)));
        let (image, format_objects) = match measured {
            Ok(measured) => measured,
            Err(error) => {
                let message = format!("{error:#}");
                tally.record(finding(format, Failure::Overflow { message }));
                continue;
            }
        };
        match prepared.skipped_hit() {
            Ok(None) => {}
            Ok(Some((x, y, object))) => {
                let message = format!("object {object} at pixel ({x}, {y})");
                tally.record(finding(format, Failure::SkippedHit { message }));
            }
            Err(error) => {
                let message = format!("{error:#}");
                tally.record(finding(format, Failure::Overflow { message }));
            }
        }
        let Some(prediction) = verdict.and_then(|v| v.prediction) else {
            continue;
        };
        if !stable {
            continue;
        }
        tally.held_to_prediction += 1;
        let measured = accuracy(
            &image,
            &reference.image,
            &format_objects,
            &reference.objects,
        );
        if false_accept(&prediction, &measured, width * height) {
            tally.record(finding(
                format,
                Failure::FalseAccept {
                    predicted_psnr_db: prediction.psnr_db,
                    measured_psnr_db: measured.psnr_db,
                    predicted_mismatch_pct: prediction.mismatch_pct,
                    measured_mismatch_pct: measured.object_mismatch_pct,
                },
            ));
        }
    }
}

/// Tries `scene`, whose pixels are adaptive, in every format that builds it with exact pixels: the
/// blocks build and draw without an overflow, and the objects their pixels show
/// ([`obscura::blocks::shown_objects`]) are those exact pixels show but in at most a thousandth
/// of the image, as the stress cases allow (no object vanishes between a block's corners: a
/// **metamorphic violation** of the relation "adaptive pixels").
fn try_blocks(scene: &OwnedScene, size: (u32, u32), tally: &mut Tally) {
    const RELATION: &str = "adaptive pixels";
    let pixels = scene.pixels;
    let blocks_request = Request::new(scene.desc(), size, Methods::LECTURE);
    let exact_desc = SceneDesc {
        pixels: Pixels::Exact,
        ..scene.desc()
    };
    let exact_request = blocks_request.with_desc(exact_desc);
    let (width, height) = size;
    for &format in FORMATS {
        let finding = |failure| Finding {
            seed: 0,
            format: format.name(),
            methods: Methods::LECTURE,
            width,
            height,
            failure,
            file: None,
        };
        let Ok(exact) = prepare(format, &exact_request) else {
            continue;
        };
        let drawn = prepare(format, &blocks_request).and_then(|blocks| {
            blocks.render(1, None)?;
            Ok((blocks.object_map()?, exact.object_map()?))
        });
        let (shown, exact_objects) = match drawn {
            Ok(maps) => maps,
            Err(error) => {
                let message = format!("{error:#}");
                tally.record(finding(if message.contains("overflowed") {
                    Failure::Overflow { message }
                } else {
                    Failure::Disagreement {
                        message: format!(
                            "builds with exact pixels, not with {}: {message}",
                            pixels.name()
                        ),
                    }
                }));
                continue;
            }
        };
        tally.check(RELATION);
        let differing: Vec<usize> = (0..shown.len())
            .filter(|&i| shown[i] != exact_objects[i])
            .collect();
        let allowed = f64::from(width * height) / 1000.0;
        if let Some(&first) = differing
            .first()
            .filter(|_| differing.len() as f64 > allowed)
        {
            let at = |i: usize| (i as u32 % width, i as u32 / width);
            let message = format!(
                "{} show another object than exact pixels in {} pixels (more than {allowed:.0}), \
                 the first at {:?}: {:?} where exact pixels show {:?}",
                pixels.name(),
                differing.len(),
                at(first),
                shown[first],
                exact_objects[first]
            );
            tally.record(finding(Failure::Metamorphic {
                relation: RELATION,
                message,
            }));
        }
    }
}

/// Whether `measured` is worse than `prediction` by more than the margin (see the module
/// documentation), on an image of `pixels` pixels.
pub fn false_accept(prediction: &Prediction, measured: &Accuracy, pixels: u32) -> bool {
    let pixels = f64::from(pixels.max(1));
    let mse = |psnr_db: f64| 255.0 * 255.0 / 10_f64.powf(psnr_db / 10.0);
    let spare_mse = SPARE_PIXELS * 255.0 * 255.0 / pixels;
    let spare_pct = SPARE_PIXELS * 100.0 / pixels;
    mse(measured.psnr_db) > MARGIN * mse(prediction.psnr_db) + spare_mse
        || measured.object_mismatch_pct > MARGIN * prediction.mismatch_pct + spare_pct
}

/// `scene`, a moved copy of the request's, built in f64 at the request's size and methods.
fn reference_of(scene: &OwnedScene, request: &Request<'_>) -> Result<Box<dyn AnyFormat>> {
    prepare_reference(&request.with_desc(scene.desc()))
}

/// The f64 image and object map with the eye nudged by one ulp of f32 (`None` where that
/// scene is refused).
fn nudged(scene: &OwnedScene, request: &Request<'_>) -> Option<(RgbImage, Vec<Option<usize>>)> {
    let mut nudged = scene.clone();
    nudged.camera.eye = nudged.camera.eye.map(f32::next_up);
    let prepared = reference_of(&nudged, request).ok()?;
    Some((prepared.render(1, None).ok()?, prepared.object_map().ok()?))
}

/// The PSNR between two images of the same size, in dB.
fn psnr(image: &RgbImage, reference: &RgbImage) -> f64 {
    let (width, height) = reference.dimensions();
    let none = vec![None; (width * height) as usize];
    accuracy(image, reference, &none, &none).psnr_db
}

/// The largest translation tried: moved by up to this, a scene on a grid of powers of two still
/// moves exactly.
const TRANSLATION_LIMIT: f32 = 1_048_576.0;

/// The scene and its eye translated together ([`metamorphic::exact_translation`]) are accepted
/// or refused alike and draw the same frame in every format.
fn try_translation(
    scene: &OwnedScene,
    request: &Request<'_>,
    tally: &mut Tally,
    finding: &impl Fn(Format, Failure) -> Finding,
) {
    let Some(t) = metamorphic::exact_translation(scene, TRANSLATION_LIMIT) else {
        return;
    };
    let moved = metamorphic::translated(scene, t);
    let moved_request = request.with_desc(moved.desc());
    let draw = |request: &Request<'_>, format| {
        prepare(format, request).and_then(|prepared| prepared.render(1, None))
    };
    for &format in std::iter::once(&Format::F64).chain(FORMATS) {
        tally.check("translate");
        let message = match (draw(request, format), draw(&moved_request, format)) {
            (Ok(here), Ok(there)) if here == there => continue,
            (Err(_), Err(_)) => continue,
            (Ok(here), Ok(there)) => {
                let differing = here
                    .pixels()
                    .zip(there.pixels())
                    .filter(|(a, b)| a != b)
                    .count();
                format!("moved by {t:?}, {differing} pixels differ")
            }
            (Ok(_), Err(error)) => format!("refused when moved by {t:?}: {error:#}"),
            (Err(error), Ok(_)) => {
                format!("accepted when moved by {t:?}, refused where it was: {error:#}")
            }
        };
        let relation = "translate";
        tally.record(finding(format, Failure::Metamorphic { relation, message }));
    }
}

/// A relation checked, and what broke it (if it broke).
type Checked = (&'static str, Option<String>);

/// In f64: an eye nudged by an ulp changes only pixels an edge passes through; where that keeps
/// the image stable, a world doubled draws the same picture, and a mirrored one its mirror image.
fn f64_relations(
    scene: &OwnedScene,
    request: &Request<'_>,
    reference: &Reference,
    nudged: Option<&(RgbImage, Vec<Option<usize>>)>,
    stable: bool,
) -> Vec<Checked> {
    let mut checked = Vec::new();
    let pixels = f64::from(request.width * request.height);
    let small = metamorphic::nudge_is_small(scene, request.width, request.height);
    if let (Some((image, objects)), true) = (nudged, small) {
        let unexplained =
            metamorphic::unexplained_changes(&reference.image, &reference.objects, image, objects);
        let broken = (unexplained as f64 > SPARE_PIXELS + metamorphic::UNEXPLAINED_SHARE * pixels)
            .then(|| format!("{unexplained} of {pixels} pixels changed with no edge near them"));
        checked.push(("nudge", broken));
    }
    if stable {
        checked.extend(mirror_and_scale(scene, request, reference));
    }
    checked
}

/// Where an ulp of the eye keeps the f64 image stable: the world doubled draws the same
/// picture, and mirrored its mirror image — within [`STABLE_PSNR_DB`], or but for
/// [`SPARE_PIXELS`] pixels: a ray that grazes a surface within f64's own rounding of its test
/// goes either way, and moving the world rounds it anew (a shadow ray passing 7.5·10⁻⁹ inside
/// a sphere of radius 1.7·10⁻⁶, 15 units from the point it leaves, where the discriminant
/// rounds at 7.7·10⁻⁹, turned one pixel of 116 when mirrored: 40.8 dB). What the relations
/// catch, a pattern or a shading that does not move with the world, changes areas.
fn mirror_and_scale(
    scene: &OwnedScene,
    request: &Request<'_>,
    reference: &Reference,
) -> Vec<Checked> {
    let draw = |moved: &OwnedScene| {
        reference_of(moved, request).and_then(|prepared| prepared.render(1, None))
    };
    let relations = [
        ("scale", metamorphic::doubled(scene), false),
        ("mirror", metamorphic::mirrored(scene), true),
    ];
    relations
        .into_iter()
        .filter_map(|(relation, moved, mirror)| {
            let broken = match draw(&moved?) {
                Ok(image) => {
                    let image = if mirror {
                        metamorphic::mirror_image(&image)
                    } else {
                        image
                    };
                    let apart = psnr(&image, &reference.image);
                    let changed = metamorphic::changed_pixels(&reference.image, &image);
                    (apart < STABLE_PSNR_DB && changed as f64 > SPARE_PIXELS).then(|| {
                        format!(
                            "{apart:.1} dB from the picture ({changed} pixels changed), where an \
                             ulp of the eye keeps {STABLE_PSNR_DB} dB"
                        )
                    })
                }
                Err(error) => Some(format!("refused: {error:#}")),
            };
            Some((relation, broken))
        })
        .collect()
}

/// How far, in dB, f32's prediction for the world doubled may stray from the original's: the
/// model is scale-free for a float (its rounding is relative), and the doubled scene's values
/// are the original's doubled exactly, so only the model's own f64 arithmetic may differ.
const SCALED_PREDICTION_DB: f64 = 1e-6;

/// Where f32 holds both the scene and the world doubled ([`metamorphic::doubled`]), whether
/// its prediction for the doubled world is the original's (`None` where the relation does not
/// apply).
fn scaled_prediction(
    scene: &OwnedScene,
    request: &Request<'_>,
    analysis: &Analysis,
) -> Option<Option<String>> {
    let original = analysis
        .verdicts
        .iter()
        .find(|v| v.format == Format::F32 && v.fit == Fit::Holds)?
        .prediction?;
    let doubled = metamorphic::doubled(scene)?;
    let request = request
        .with_desc(doubled.desc())
        .with_methods(exact_roots(request.methods));
    let reference = Reference::render(&request).ok()?;
    let verdict = Verdict::of(Format::F32, &doubled, request.methods, &reference);
    let predicted = match (verdict.fit, verdict.prediction) {
        (Fit::Holds, Some(prediction)) => prediction,
        (fit, _) => return Some(Some(format!("f32 holds the scene, not doubled: {fit:?}"))),
    };
    let apart = (predicted.psnr_db - original.psnr_db).abs();
    let same = apart <= SCALED_PREDICTION_DB || predicted.psnr_db == original.psnr_db;
    Some((!same).then(|| {
        format!(
            "f32 is predicted {:.3} dB for the world doubled, {:.3} dB for the original",
            predicted.psnr_db, original.psnr_db
        )
    }))
}

/// Writes the scene of a finding as a scene file whose header says what failed and how to
/// see it again.
fn write_reproducer(dir: &Path, scene: &OwnedScene, finding: &Finding) -> Result<PathBuf> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let stem = format!(
        "fuzz-{}-{}-{}",
        finding.seed,
        finding.format,
        finding.methods.to_string().replace([',', '='], "-")
    );
    let path = dir.join(format!("{stem}.toml"));
    let (body, meshes) = scene
        .files(&stem)
        .context("the scene cannot be written as TOML")?;
    for (file, text) in meshes {
        let mesh = dir.join(file);
        std::fs::write(&mesh, text).with_context(|| format!("cannot write {}", mesh.display()))?;
    }
    let header = format!(
        "# obscura fuzz: scene {} in {} by {} at {}x{}\n# {}\n# obscura compare {} --format {} --size {}x{} {}\n\n",
        finding.seed,
        finding.format,
        finding.methods,
        finding.width,
        finding.height,
        finding.failure,
        path.display(),
        finding.format,
        finding.width,
        finding.height,
        obscura_scene::MethodSettings::of(&finding.methods).flags(),
    );
    std::fs::write(&path, header + &body)
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reproducer_is_the_scene_with_what_failed_and_the_command_that_shows_it() {
        let dir = std::env::temp_dir().join("obscura-fuzz-reproducer");
        let _ = std::fs::remove_dir_all(&dir);
        let generated = generate::scene(11);
        let finding = Finding {
            seed: 11,
            format: "i20f12",
            methods: Methods {
                bias: BiasMethod::Exclude,
                ..Methods::LECTURE
            },
            width: 24,
            height: 16,
            failure: Failure::Panic {
                message: "for the test".to_owned(),
            },
            file: None,
        };
        let path = write_reproducer(&dir, &generated.scene, &finding).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.contains("# obscura fuzz: scene 11 in i20f12"),
            "{text}"
        );
        assert!(
            text.contains("--format i20f12 --size 24x16") && text.contains("--bias exclude"),
            "{text}"
        );
        let loaded = obscura_scene::load(path.to_str().unwrap()).unwrap();
        // The scene, and its mesh's triangles (the hierarchy is built again, and may order
        // them otherwise).
        let without_meshes = |scene: &OwnedScene| OwnedScene {
            meshes: obscura_scene::OwnedMeshes::default(),
            ..scene.clone()
        };
        assert_eq!(
            without_meshes(&loaded.scene),
            without_meshes(&generated.scene)
        );
        let corners = |scene: &OwnedScene| {
            let meshes = scene.meshes.desc();
            let mut corners: Vec<_> = meshes
                .triangles
                .iter()
                .map(|&t| meshes.corners(t).map(|c| c.map(f32::to_bits)))
                .collect();
            corners.sort_unstable();
            corners
        };
        assert!(
            !generated.scene.meshes.triangles.is_empty(),
            "scene 11 has a mesh"
        );
        assert_eq!(corners(&loaded.scene), corners(&generated.scene));
    }
}
