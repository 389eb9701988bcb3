//! The scenes that broke obscura's promises before its range proof covered every operation and
//! its predictions were held to measurement (issue "Numbers you can trust"), each now refused
//! with a reason that fits, or rendered without a wrapped number and within its predicted
//! bound. Each scene is a file in `host/scenes/hostile/` whose header says what it broke; the
//! fuzzer ([`crate::fuzz`]) tries the same promises on scenes nobody wrote.

use crate::analysis::{Aim, Analysis, Choice, Fit, TARGET_PSNR, measure, pick};
use crate::cost::Machine;
use crate::fuzz::false_accept;
use crate::metrics::accuracy;
use crate::render::{Request, prepare, prepare_reference};
use obscura::{BiasMethod, Methods, RayMethod, RootMethod, SphereMethod, TriangleMethod};
use obscura_scene::{Format, OwnedScene};

/// The scene of `host/scenes/hostile/NAME.toml`, whose header says what it broke.
fn hostile(name: &str) -> OwnedScene {
    let path = format!("{}/scenes/hostile/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    obscura_scene::load(&path).expect("a scene file").scene
}

/// `scene` in `format` by `methods` at `size` (width, height): refused for a reason with one of `words` in it,
/// or rendered with no number wrapped (a wrap fails the render) and within the bound the
/// analysis predicts. Returns whether it was rendered.
fn refused_or_held(
    scene: &OwnedScene,
    format: Format,
    methods: Methods,
    (width, height): (u32, u32),
    words: &[&str],
) -> bool {
    let analysis = Analysis::of(scene, methods, width, height).expect("f64 holds the scene");
    let verdict = analysis
        .verdicts
        .iter()
        .find(|v| v.format == format)
        .expect("a verdict per format");
    let request = Request::new(scene.desc(), (width, height), methods);
    let built = prepare(format, &request);
    match (&verdict.fit, built) {
        (Fit::Holds, Ok(prepared)) => {
            let reference = prepare_reference(&request).expect("f64 holds the scene");
            let measured = accuracy(
                &prepared.render(1, None).expect("no number wraps"),
                &reference.render(1, None).expect("renders"),
                &prepared.object_map().expect("no number wraps"),
                &reference.object_map().expect("renders"),
            );
            let prediction = verdict.prediction.expect("a prediction where it holds");
            assert!(
                !false_accept(&prediction, &measured, width * height),
                "{format} by {methods}: predicted {prediction:?}, measured {measured:?}"
            );
            true
        }
        (Fit::Holds, Err(error)) => panic!("analyze holds it, the build refuses: {error:#}"),
        (_, Ok(_)) => panic!("the build holds it, analyze refuses: {:?}", verdict.fit),
        (_, Err(error)) => {
            let reason = format!("{error:#}");
            assert!(
                words.iter().any(|word| reason.contains(word)),
                "{format} by {methods}: {reason}"
            );
            false
        }
    }
}

#[test]
fn a_phong_highlight_neither_wraps_nor_lies() {
    let tiny = hostile("phong-tiny");
    refused_or_held(
        &tiny,
        Format::I16f16,
        Methods::LECTURE,
        (256, 256),
        &["make the sphere larger", "move the light"],
    );
    let shiny = hostile("phong-shiny");
    assert!(refused_or_held(
        &shiny,
        Format::I20f12,
        Methods::LECTURE,
        (256, 256),
        &[]
    ));
}

#[test]
fn a_highlight_whose_cosines_round_up_is_predicted_so() {
    let scene = hostile("highlight-rounded-up");
    for format in [Format::I16f16, Format::I20f12, Format::I22f10] {
        assert!(refused_or_held(
            &scene,
            format,
            Methods::LECTURE,
            (96, 96),
            &[]
        ));
    }
}

#[test]
fn a_sky_brighter_than_the_display_is_predicted_so() {
    let scene = hostile("bright-sky");
    let methods = Methods {
        roots: RootMethod::Approx,
        bias: BiasMethod::Exclude,
        ..Methods::LECTURE
    };
    for format in [Format::I16f16, Format::I12f20, Format::I20f12] {
        refused_or_held(&scene, format, methods, (33, 28), &["resolve"]);
    }
}

#[test]
fn a_crack_between_a_meshs_triangles_is_predicted_so() {
    let scene = hostile("mesh-crack");
    let methods = Methods {
        triangle: TriangleMethod::MollerTrumbore,
        roots: RootMethod::Approx,
        bias: BiasMethod::Exclude,
        ..Methods::LECTURE
    };
    for format in [Format::I16f16, Format::I18f14, Format::I20f12] {
        refused_or_held(&scene, format, methods, (34, 30), &["resolve"]);
    }
}

#[test]
fn a_small_triangles_numerators_are_counted_at_their_size() {
    let scene = hostile("speck-in-a-mesh");
    for format in [Format::I8f24, Format::I10f22, Format::I32f32, Format::F32] {
        refused_or_held(&scene, format, Methods::LECTURE, (30, 24), &["resolve"]);
    }
}

#[test]
fn a_highlight_at_its_peak_everywhere_is_predicted_so() {
    let scene = hostile("headlight");
    for format in [Format::I16f16, Format::I18f14, Format::F32] {
        refused_or_held(&scene, format, Methods::LECTURE, (32, 32), &[]);
    }
}

#[test]
fn a_floor_at_the_worlds_edge_is_drawn_where_it_is_or_refused() {
    let scene = hostile("worlds-edge");
    for format in [Format::I12f20, Format::I16f16, Format::F32] {
        assert!(refused_or_held(
            &scene,
            format,
            Methods::LECTURE,
            (64, 64),
            &[]
        ));
    }
    let rendered = refused_or_held(
        &scene,
        Format::I20f12,
        Methods::LECTURE,
        (64, 64),
        &["raise far well beyond the plane's distance"],
    );
    assert!(
        !rendered,
        "i20f12 cannot place a disc 0.0098 across to its steps of 0.00024"
    );
}

#[test]
fn a_silhouette_that_moves_a_hundred_pixels_is_predicted_so() {
    let narrow = hostile("narrow-view-i32f32");
    assert!(refused_or_held(
        &narrow,
        Format::I32f32,
        Methods::LECTURE,
        (1, 7645),
        &[]
    ));
}

#[test]
fn a_mirror_as_large_as_the_world_reflects_across_it() {
    let scene = hostile("across-the-world");
    let methods = Methods {
        sphere: SphereMethod::Stable,
        triangle: TriangleMethod::Watertight,
        bias: BiasMethod::Exclude,
        ..Methods::LECTURE
    };
    assert!(refused_or_held(&scene, Format::F32, methods, (32, 32), &[]));
}

#[test]
fn sphere_roots_at_the_edge_of_the_range_neither_wrap_nor_lie() {
    for format in [Format::I20f12, Format::I32f32] {
        let world = hostile(&format!("roots-{format}"));
        for sphere in [SphereMethod::Quadratic, SphereMethod::Stable] {
            let methods = Methods {
                sphere,
                rays: RayMethod::Stepped,
                ..Methods::LECTURE
            };
            refused_or_held(&world, format, methods, (64, 64), &["range"]);
        }
    }
}

#[test]
fn a_checker_too_large_for_its_reciprocal_is_refused_or_predicted_so() {
    for name in ["checker-1e6", "checker-3000"] {
        let scene = hostile(name);
        for format in [Format::I16f16, Format::I20f12] {
            refused_or_held(
                &scene,
                format,
                Methods::LECTURE,
                (256, 256),
                &["checker", "light", "resolve"],
            );
        }
        // --format auto measures what it picks.
        let analysis = Analysis::of(&scene, Methods::LECTURE, 64, 64).expect("analyses");
        let aim = Aim {
            machine: Machine::M0,
            target_psnr: TARGET_PSNR,
            rescale: true,
            choose_pixels: false,
        };
        let picked = pick(&[(&scene, &analysis)], Methods::LECTURE, (64, 64), aim);
        if let Choice::Reaches(picked) = picked.expect("renders") {
            let scene = picked.scene(&scene);
            let measured =
                measure(picked.format, &scene, Methods::LECTURE, (64, 64)).expect("renders");
            assert!(measured >= 40.0, "{picked:?} measures {measured:.1} dB");
        }
    }
}

#[test]
fn a_narrow_field_of_view_at_a_silhouette_is_refused_or_predicted_so() {
    let narrow = hostile("narrow");
    for format in [Format::I16f16, Format::I20f12] {
        let rendered = refused_or_held(
            &narrow,
            format,
            Methods::LECTURE,
            (256, 256),
            &["widen the field of view"],
        );
        assert!(!rendered, "{format} cannot aim rays 0.05°/256 apart");
    }
    assert!(refused_or_held(
        &narrow,
        Format::F32,
        Methods::LECTURE,
        (256, 256),
        &[]
    ));
}

#[test]
fn a_light_just_above_a_floor_is_refused_where_rays_cannot_tell_its_side() {
    let low = hostile("low-light");
    let rendered = refused_or_held(
        &low,
        Format::I16f16,
        Methods::LECTURE,
        (256, 256),
        &["move the light away from the surface"],
    );
    assert!(!rendered);
    assert!(refused_or_held(
        &low,
        Format::I32f32,
        Methods::LECTURE,
        (256, 256),
        &[]
    ));
}

#[test]
fn extreme_glass_is_refused_or_predicted_so() {
    for (name, format) in [("glass-1e5", Format::F32), ("glass-1e4", Format::I32f32)] {
        let glass = hostile(name);
        refused_or_held(
            &glass,
            format,
            Methods::LECTURE,
            (256, 256),
            &["lower the ior"],
        );
    }
}

#[test]
fn the_eye_on_a_triangles_edge_is_refused_in_every_format() {
    let edge = hostile("eye-on-edge");
    for &format in Format::FIRMWARE {
        let request = Request::new(edge.desc(), (64, 64), Methods::LECTURE);
        let Err(error) = prepare(format, &request) else {
            panic!("{format} holds a scene whose eye is on a triangle's edge");
        };
        // A format too small for the scene's values refuses it for that first (i8f24).
        let message = format!("{error:#}");
        assert!(
            message.contains("move the eye away from the surface")
                || message.contains(&format!("beyond {format}'s range")),
            "{format}: {message}"
        );
    }
}

#[test]
fn one_large_triangle_by_moller_trumbore_is_refused_or_predicted_so() {
    let triangle = hostile("triangle");
    let methods = Methods {
        triangle: TriangleMethod::MollerTrumbore,
        ..Methods::LECTURE
    };
    for format in [Format::I16f16, Format::I20f12] {
        refused_or_held(
            &triangle,
            format,
            methods,
            (256, 256),
            &["Möller–Trumbore", "triangle=watertight resolves it"],
        );
        refused_or_held(&triangle, format, Methods::LECTURE, (256, 256), &[]);
    }
}

#[test]
fn a_reciprocal_that_does_not_fit_is_refused() {
    let small = hostile("reciprocal");
    let methods = Methods {
        triangle: TriangleMethod::MollerTrumbore,
        ..Methods::LECTURE
    };
    for format in [Format::I8f24, Format::I10f22] {
        let rendered = refused_or_held(&small, format, methods, (12, 12), &["Möller–Trumbore's"]);
        assert!(!rendered, "{format} cannot hold 1/det up to 9 000");
    }
    // The fuzzer's, by other methods besides.
    for (name, methods) in [
        (
            "eye-on-triangle-i8f24",
            Methods {
                sphere: SphereMethod::Stable,
                triangle: TriangleMethod::MollerTrumbore,
                roots: RootMethod::Approx,
                bias: BiasMethod::Exclude,
                ..Methods::LECTURE
            },
        ),
        (
            "narrow-view-triangle-i8f24",
            Methods {
                sphere: SphereMethod::Stable,
                triangle: TriangleMethod::MollerTrumbore,
                rays: RayMethod::Stepped,
                bias: BiasMethod::Exclude,
                ..Methods::LECTURE
            },
        ),
    ] {
        let scene = hostile(name);
        let rendered = refused_or_held(
            &scene,
            Format::I8f24,
            methods,
            (16, 16),
            &["Möller–Trumbore's"],
        );
        assert!(!rendered, "{name}: i8f24 cannot hold its 1/det");
    }
}

#[test]
fn analyze_and_the_build_agree_on_a_field_of_view_of_almost_180_degrees() {
    let wide = hostile("wide");
    for size in [64, 512] {
        let analysis = Analysis::of(&wide, Methods::LECTURE, size, size).expect("f64 holds it");
        for verdict in &analysis.verdicts {
            let request = Request::new(wide.desc(), (size, size), Methods::LECTURE);
            let builds = prepare(verdict.format, &request).is_ok();
            assert_eq!(
                builds,
                verdict.fit == Fit::Holds,
                "{} at {size}: {:?}",
                verdict.format,
                verdict.fit
            );
        }
    }
}

#[test]
fn a_triangle_has_no_area_only_for_its_own_size() {
    let small = hostile("tiny-triangle");
    for scene in [small.scaled(100.0), small] {
        for format in [Format::F64, Format::F32] {
            assert!(refused_or_held(
                &scene,
                format,
                Methods::LECTURE,
                (64, 64),
                &[]
            ));
        }
    }
    let mesh = hostile("tiny-teapot");
    assert!(refused_or_held(
        &mesh,
        Format::F64,
        Methods::LECTURE,
        (64, 64),
        &[]
    ));
    for format in [Format::I16f16, Format::F32] {
        assert!(!refused_or_held(
            &mesh,
            format,
            Methods::LECTURE,
            (64, 64),
            &["twice the triangle's area"]
        ));
    }
}
