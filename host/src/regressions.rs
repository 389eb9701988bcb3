//! The scenes that broke obscura's promises before its range proof covered every operation and
//! its predictions were held to measurement (issue "Numbers you can trust"), each now refused
//! with a reason that fits, or rendered without a wrapped number and within its predicted
//! bound. The fuzzer ([`crate::fuzz`]) tries the same promises on scenes nobody wrote.

use crate::analysis::{Analysis, Fit, measure, pick};
use crate::cost::Machine;
use crate::format::Format;
use crate::fuzz::false_accept;
use crate::metrics::accuracy;
use crate::owned::OwnedScene;
use crate::render::{Request, exact_roots, prepare, prepare_reference};
use crate::scene_file;
use obscura::{Methods, RayMethod, SphereMethod, TriangleMethod};

/// A scene file's text, with a camera at `eye` looking at `look_at` through `fov` degrees.
fn scene(far: f64, eye: [f64; 3], look_at: [f64; 3], fov: f64, body: &str) -> OwnedScene {
    let text = format!(
        "far = {far}\ncamera = {{ eye = {eye:?}, look_at = {look_at:?}, up = [0.0, 1.0, 0.0], \
         vfov_degrees = {fov} }}\n{body}"
    );
    scene_file::parse(std::path::Path::new("regression.toml"), &text).expect("a scene file")
}

/// A ball on a checkered floor under one light, the usual test scene, with these changes.
fn ball_on_floor(checker: f64, light: [f64; 3], ball: &str) -> OwnedScene {
    scene(
        30.0,
        [0.0, 1.0, -5.0],
        [0.0, 1.0, 0.0],
        50.0,
        &format!(
            "[[objects]]\nshape.plane = {{ point = [0.0, 0.0, 0.0], normal = [0.0, 1.0, 0.0], \
             checker = {{ colour = [0.1, 0.1, 0.1], size = {checker} }} }}\n\
             material = {{ colour = [0.9, 0.9, 0.9] }}\n\
             [[objects]]\nshape.sphere = {{ center = [0.0, 1.0, 0.0], radius = 1.0 }}\n{ball}\n\
             [[lights]]\nposition = {light:?}\ncolour = [1.0, 1.0, 1.0]\n"
        ),
    )
}

/// `scene` in `format` by `methods` at `size`: refused for a reason with one of `words` in it,
/// or rendered with no number wrapped (a wrap fails the render) and within the bound the
/// analysis predicts. Returns whether it was rendered.
fn refused_or_held(
    scene: &OwnedScene,
    format: Format,
    methods: Methods,
    size: u32,
    words: &[&str],
) -> bool {
    let analysis = Analysis::of(scene, methods, size, size).expect("f64 holds the scene");
    let verdict = analysis
        .verdicts
        .iter()
        .find(|v| v.format == format)
        .expect("a verdict per format");
    let desc = scene.desc();
    let request = Request {
        desc: &desc,
        width: size,
        height: size,
        methods,
    };
    let built = prepare(format, &request);
    match (&verdict.fit, built) {
        (Fit::Holds, Ok(prepared)) => {
            let reference = prepare_reference(&Request {
                methods: exact_roots(methods),
                ..request
            })
            .expect("f64 holds the scene");
            let measured = accuracy(
                &prepared.render(1, None).expect("no number wraps"),
                &reference.render(1, None).expect("renders"),
                &prepared.object_map().expect("no number wraps"),
                &reference.object_map().expect("renders"),
            );
            let prediction = verdict.prediction.expect("a prediction where it holds");
            assert!(
                !false_accept(&prediction, &measured, size * size),
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
    // Ordinary materials in a world 1.8 cm across, the light near the surface; and one sphere
    // of the largest exponent a file accepts.
    let tiny = scene(
        0.012,
        [0.0, 0.004, -0.004],
        [0.0, 0.002, 0.004],
        50.0,
        "[[objects]]\nshape.sphere = { center = [0.0, 0.003, 0.004], radius = 0.002 }\n\
         material = { colour = [0.8, 0.3, 0.2], specular = 0.6, shininess = 162, \
         transmission = 0.3, ior = 1.3 }\n\
         [[objects]]\nshape.plane = { point = [0.0, 0.0, 0.0], normal = [0.0, 1.0, 0.0] }\n\
         material = { colour = [0.5, 0.5, 0.5], specular = 0.5, shininess = 162 }\n\
         [[lights]]\nposition = [0.002, 0.0053, 0.004]\ncolour = [1.0, 1.0, 1.0]\n",
    );
    refused_or_held(
        &tiny,
        Format::I16f16,
        Methods::LECTURE,
        256,
        &["make the sphere larger", "move the light"],
    );
    let shiny = ball_on_floor(
        1.0,
        [-3.0, 6.0, -4.0],
        "material = { colour = [0.9, 0.2, 0.1], specular = 0.9, shininess = 65535 }",
    );
    assert!(refused_or_held(
        &shiny,
        Format::I20f12,
        Methods::LECTURE,
        256,
        &[]
    ));
}

#[test]
fn sphere_roots_at_the_edge_of_the_range_neither_wrap_nor_lie() {
    // A sphere at the far side of a world as large as i20f12 and i32f32 can hold, by both
    // forms, with rays stepped along the rows.
    for (format, far) in [(Format::I20f12, 330.0), (Format::I32f32, 22_000.0)] {
        let edge = far * 0.9;
        let world = scene(
            far,
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            40.0,
            &format!(
                "[[objects]]\nshape.sphere = {{ center = [0.0, 0.0, {edge}], radius = {r} }}\n\
                 [[lights]]\nposition = [0.0, {r}, 0.0]\ncolour = [1.0, 1.0, 1.0]\n",
                r = far * 0.09
            ),
        );
        for sphere in [SphereMethod::Quadratic, SphereMethod::Stable] {
            let methods = Methods {
                sphere,
                rays: RayMethod::Stepped,
                ..Methods::LECTURE
            };
            refused_or_held(&world, format, methods, 64, &["range"]);
        }
    }
}

#[test]
fn a_checker_too_large_for_its_reciprocal_is_refused_or_predicted_so() {
    for size in [1e6, 3000.0] {
        let scene = ball_on_floor(size, [-3.0, 6.0, -4.0], "");
        for format in [Format::I16f16, Format::I20f12] {
            refused_or_held(
                &scene,
                format,
                Methods::LECTURE,
                256,
                &["checker", "light", "resolve"],
            );
        }
        // --format auto measures what it picks.
        let analysis = Analysis::of(&scene, Methods::LECTURE, 64, 64).expect("analyses");
        let picked = pick(
            &[(&scene, &analysis)],
            Methods::LECTURE,
            (64, 64),
            Machine::M0,
            40.0,
            true,
        )
        .expect("renders");
        if let Some(picked) = picked {
            let measured =
                measure(picked.format, &scene, Methods::LECTURE, (64, 64)).expect("renders");
            assert!(measured >= 40.0, "{picked:?} measures {measured:.1} dB");
        }
    }
}

#[test]
fn a_narrow_field_of_view_at_a_silhouette_is_refused_or_predicted_so() {
    let narrow = scene(
        20.0,
        [0.0, 1.0, -5.0],
        [1.0, 1.0, 0.0],
        0.05,
        "[[objects]]\nshape.sphere = { center = [0.0, 1.0, 0.0], radius = 1.0 }\n\
         material = { colour = [0.8, 0.2, 0.1] }\n\
         [[lights]]\nposition = [-3.0, 6.0, -4.0]\ncolour = [1.0, 1.0, 1.0]\n",
    );
    for format in [Format::I16f16, Format::I20f12] {
        let rendered = refused_or_held(
            &narrow,
            format,
            Methods::LECTURE,
            256,
            &["widen the field of view"],
        );
        assert!(!rendered, "{format} cannot aim rays 0.05°/256 apart");
    }
    assert!(refused_or_held(
        &narrow,
        Format::F32,
        Methods::LECTURE,
        256,
        &[]
    ));
}

#[test]
fn a_light_just_above_a_floor_is_refused_where_rays_cannot_tell_its_side() {
    let low = ball_on_floor(1.0, [1.5, 0.001, -1.0], "");
    let rendered = refused_or_held(
        &low,
        Format::I16f16,
        Methods::LECTURE,
        256,
        &["move the light away from the surface"],
    );
    assert!(!rendered);
    assert!(refused_or_held(
        &low,
        Format::I32f32,
        Methods::LECTURE,
        256,
        &[]
    ));
}

#[test]
fn extreme_glass_is_refused_or_predicted_so() {
    for (ior, format) in [("1e5", Format::F32), ("1e4", Format::I32f32)] {
        let glass = ball_on_floor(
            1.0,
            [-3.0, 6.0, -4.0],
            &format!(
                "material = {{ colour = [1.0, 1.0, 1.0], diffuse = 0.05, reflection = 0.1, \
                 transmission = 0.85, ior = {ior} }}"
            ),
        );
        refused_or_held(&glass, format, Methods::LECTURE, 256, &["lower the ior"]);
    }
}

#[test]
fn the_eye_on_a_triangles_edge_is_refused_in_every_format() {
    let edge = scene(
        20.0,
        [0.0, 1.0, -5.0],
        [0.0, 1.0, 0.0],
        50.0,
        "[[objects]]\nshape.triangle = { vertices = [[-1.0, 1.0, -5.0], [1.0, 1.0, -5.0], \
         [0.0, 2.0, 3.0]] }\n\
         [[lights]]\nposition = [-3.0, 6.0, -4.0]\ncolour = [1.0, 1.0, 1.0]\n",
    );
    for format in Format::FIRMWARE {
        let desc = edge.desc();
        let request = Request {
            desc: &desc,
            width: 64,
            height: 64,
            methods: Methods::LECTURE,
        };
        let Err(error) = prepare(format, &request) else {
            panic!("{format} holds a scene whose eye is on a triangle's edge");
        };
        assert!(
            format!("{error:#}").contains("move the eye away from the surface"),
            "{format}: {error:#}"
        );
    }
}

#[test]
fn one_large_triangle_by_moller_trumbore_is_refused_or_predicted_so() {
    let triangle = scene(
        30.0,
        [0.0, 1.0, -5.0],
        [0.0, 1.0, 0.0],
        50.0,
        "[[objects]]\nshape.triangle = { vertices = [[-8.0, 0.0, 4.0], [8.0, 0.0, 4.0], \
         [0.0, 9.0, 6.0]] }\nmaterial = { colour = [0.2, 0.8, 0.2] }\n\
         [[lights]]\nposition = [-3.0, 6.0, -4.0]\ncolour = [1.0, 1.0, 1.0]\n",
    );
    let methods = Methods {
        triangle: TriangleMethod::MollerTrumbore,
        ..Methods::LECTURE
    };
    for format in [Format::I16f16, Format::I20f12] {
        refused_or_held(
            &triangle,
            format,
            methods,
            256,
            &["Möller–Trumbore", "triangle=watertight resolves it"],
        );
        refused_or_held(&triangle, format, Methods::LECTURE, 256, &[]);
    }
}

#[test]
fn analyze_and_the_build_agree_on_a_field_of_view_of_almost_180_degrees() {
    let wide = scene(
        20.0,
        [0.0, 1.0, -5.0],
        [0.0, 1.0, 0.0],
        179.9999,
        "[[objects]]\nshape.sphere = { center = [0.0, 1.0, 0.0], radius = 1.0 }\n",
    );
    for size in [64, 512] {
        let analysis = Analysis::of(&wide, Methods::LECTURE, size, size).expect("f64 holds it");
        for verdict in &analysis.verdicts {
            let desc = wide.desc();
            let request = Request {
                desc: &desc,
                width: size,
                height: size,
                methods: Methods::LECTURE,
            };
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
