//! The prediction-versus-measurement corpus: a fixed seed's generated scenes, plausible and
//! extreme, each built in every firmware format by the lecture's methods and by every variant
//! that changes one of them, and held to every promise the fuzzer checks (see [`super`]): no
//! overflow, no panic, analyze and the build agreeing, and, where f64 is stable, no measurement
//! worse than its prediction beyond [`super::MARGIN`] and [`super::SPARE_PIXELS`]. Then
//! `--format auto`'s pick for each scene builds.

use super::{Tally, generate, pool, try_scenes};
use crate::analysis::{Aim, Analysis, Choice, pick};
use crate::cost::Machine;
use crate::render::{Request, prepare};
use obscura::Methods;

/// The corpus's seed and size.
const SEED: u64 = 8;
const SCENES: u64 = 1500;

/// The lecture's methods and each variant that changes one of them.
fn every_method() -> Vec<Methods> {
    let mut all = Vec::new();
    for methods in Methods::LECTURE.variants() {
        if !all.contains(&methods) {
            all.push(methods);
        }
    }
    all
}

#[test]
fn the_corpus_holds_every_promise() {
    let pool = pool(std::thread::available_parallelism().map_or(2, usize::from)).unwrap();
    let tally: Tally = try_scenes(&pool, SEED, 0..SCENES, |_| every_method(), None);
    assert!(tally.clean(), "{tally}\n{:#?}", tally.findings);
    // The corpus is not all refusals: one build in ten at least is rendered and held to its
    // prediction.
    assert!(
        tally.held_to_prediction * 10 >= tally.builds,
        "too few builds held to their prediction: {tally}"
    );
}

#[test]
fn auto_picks_a_format_the_build_accepts() {
    let mut picked = 0;
    for index in 0..SCENES / 4 {
        let generated = generate::scene(super::scene_seed(SEED, index));
        let (width, height) = generated.size;
        let methods = Methods::LECTURE;
        let Ok(analysis) = Analysis::of(&generated.scene, methods, width, height) else {
            continue; // f64 refuses it: so does every format, and auto says so
        };
        for machine in Machine::ALL {
            let aim = Aim {
                machine,
                target_psnr: 30.0,
                rescale: true,
                choose_pixels: true,
            };
            let choice = pick(
                &[(&generated.scene, &analysis)],
                methods,
                generated.size,
                aim,
            );
            let Choice::Reaches(choice) = choice.unwrap() else {
                continue;
            };
            let scene = choice.scene(&generated.scene);
            let request = Request::new(scene.desc(), generated.size, methods);
            assert!(
                prepare(choice.format, &request).is_ok(),
                "scene {index}: auto picked {} on {machine}, which refuses it",
                choice.format
            );
            picked += 1;
        }
    }
    assert!(picked > 0, "auto picked nothing in the corpus");
}
