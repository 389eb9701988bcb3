//! Every way a scene description can be refused, asserted by variant, with messages that say
//! what is wrong and how to fix it.

use obscura::scalar::FormatSet;
use obscura::{
    BackgroundDesc, CameraDesc, CheckerDesc, I16F16, Item, LightDesc, MaterialDesc, Methods,
    ObjectDesc, Remedy, Scene, SceneDesc, SceneError, ShapeDesc, TriangleMethod,
};

type Small<S> = Scene<S, 4, 2, 4>;

const CAMERA: CameraDesc =
    CameraDesc::pinhole([0.0, 1.0, -5.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0], 45.0);
const MATTE: MaterialDesc = MaterialDesc::matte([0.5, 0.5, 0.5]);
const BALL: ObjectDesc = ObjectDesc {
    shape: ShapeDesc::Sphere {
        center: [0.0, 1.0, 0.0],
        radius: 1.0,
    },
    material: MATTE,
};
const LIGHT: LightDesc = LightDesc::point([2.0, 5.0, -3.0], [1.0, 1.0, 1.0]);

fn scene<'a>(objects: &'a [ObjectDesc], lights: &'a [LightDesc]) -> SceneDesc<'a> {
    SceneDesc {
        camera: CAMERA,
        objects,
        lights,
        ambient: [0.1; 3],
        background: BackgroundDesc::Solid([0.0, 0.0, 0.3]),
        far: 20.0,
        max_depth: 3,
        ..SceneDesc::DEFAULT
    }
}

fn build(desc: &SceneDesc<'_>) -> Result<Small<I16F16>, SceneError> {
    Small::<I16F16>::build(desc)
}

fn sphere(center: [f32; 3], radius: f32) -> ObjectDesc {
    ObjectDesc {
        shape: ShapeDesc::Sphere { center, radius },
        material: MATTE,
    }
}

fn triangle(vertices: [[f32; 3]; 3]) -> ObjectDesc {
    ObjectDesc {
        shape: ShapeDesc::Triangle { vertices },
        material: MATTE,
    }
}

fn plane(normal: [f32; 3], checker: Option<CheckerDesc>) -> ObjectDesc {
    ObjectDesc {
        shape: ShapeDesc::Plane {
            point: [0.0, 0.0, 0.0],
            normal,
            checker,
        },
        material: MATTE,
    }
}

#[test]
fn a_valid_scene_builds() {
    assert!(build(&scene(&[BALL, plane([0.0, 1.0, 0.0], None)], &[LIGHT])).is_ok());
}

#[test]
fn nan_and_infinite_values() {
    let objects = [sphere([0.0, 1.0, 0.0], f32::NAN)];
    assert_eq!(
        build(&scene(&objects, &[])).unwrap_err(),
        SceneError::NotFinite {
            item: Item::Object(0),
            field: "shape.sphere.radius"
        }
    );
    let mut desc = scene(&[], &[]);
    desc.camera.eye[1] = f32::INFINITY;
    assert_eq!(
        build(&desc).unwrap_err(),
        SceneError::NotFinite {
            item: Item::Camera,
            field: "eye"
        }
    );
    let lights = [LightDesc {
        position: [f32::NAN, 0.0, 0.0],
        ..LIGHT
    }];
    assert_eq!(
        build(&scene(&[], &lights)).unwrap_err(),
        SceneError::NotFinite {
            item: Item::Light(0),
            field: "position"
        }
    );
    let mut desc = scene(&[], &[]);
    desc.far = f32::INFINITY;
    assert_eq!(
        build(&desc).unwrap_err(),
        SceneError::NotFinite {
            item: Item::Scene,
            field: "far"
        }
    );
}

#[test]
fn zero_and_negative_radius() {
    for radius in [0.0, -1.0] {
        let objects = [sphere([0.0, 1.0, 0.0], radius)];
        let error = build(&scene(&objects, &[])).unwrap_err();
        assert!(
            matches!(
                error,
                SceneError::OutOfBounds {
                    item: Item::Object(0),
                    field: "shape.sphere.radius",
                    ..
                }
            ),
            "{error:?}"
        );
        assert!(error.to_string().contains("must be > 0"), "{error}");
    }
}

#[test]
fn a_direction_too_short_to_give_one_is_refused_as_such() {
    let objects = [plane([0.0, 1e-30, 0.0], None)];
    let error = build(&scene(&objects, &[])).unwrap_err();
    assert_eq!(
        error.to_string(),
        "object 0: shape.plane.normal is 1.000e-30 long, too short to give a direction (it must \
         be longer than f32's epsilon, 1.192e-7); give it a direction of length 1"
    );
    let mut desc = scene(&[], &[]);
    desc.camera.up = [0.0, 1e-9, 0.0];
    assert_eq!(
        build(&desc).unwrap_err(),
        SceneError::TooShort {
            item: Item::Camera,
            field: "up",
            length: f64::from(1e-9_f32)
        }
    );
    let mut desc = scene(&[], &[]);
    desc.background = BackgroundDesc::Gradient {
        horizon: [1.0; 3],
        zenith: [0.0, 0.0, 1.0],
        up: [0.0, 1e-9, 0.0],
    };
    assert!(matches!(
        build(&desc).unwrap_err(),
        SceneError::TooShort {
            item: Item::Scene,
            field: "background.gradient.up",
            ..
        }
    ));
}

#[test]
fn a_huge_number_is_printed_in_scientific_notation() {
    let mut desc = scene(&[], &[]);
    desc.camera.aperture = 1e30;
    let message = build(&desc).unwrap_err().to_string();
    assert!(
        message.contains("reaches 1.000e30 from the eye") && message.len() < 160,
        "{message}"
    );
}

#[test]
fn zero_length_normal_view_and_up() {
    let objects = [plane([0.0, 0.0, 0.0], None)];
    assert_eq!(
        build(&scene(&objects, &[])).unwrap_err(),
        SceneError::TooShort {
            item: Item::Object(0),
            field: "shape.plane.normal",
            length: 0.0
        }
    );
    let mut desc = scene(&[], &[]);
    desc.camera.look_at = desc.camera.eye;
    assert!(matches!(
        build(&desc).unwrap_err(),
        SceneError::TooShort {
            item: Item::Camera,
            ..
        }
    ));
    let mut desc = scene(&[], &[]);
    desc.camera.up = [0.0; 3];
    assert_eq!(
        build(&desc).unwrap_err(),
        SceneError::TooShort {
            item: Item::Camera,
            field: "up",
            length: 0.0
        }
    );
}

#[test]
fn zero_area_triangles() {
    let collinear = [triangle([
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 1.0],
        [2.0, 2.0, 2.0],
    ])];
    assert_eq!(
        build(&scene(&collinear, &[])).unwrap_err(),
        SceneError::DegenerateTriangle {
            item: Item::Object(0)
        }
    );
    let repeated = [
        BALL,
        triangle([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
    ];
    assert_eq!(
        build(&scene(&repeated, &[])).unwrap_err(),
        SceneError::DegenerateTriangle {
            item: Item::Object(1)
        }
    );
}

/// A lens must be a non-negative radius clear of every surface, focused a positive distance
/// ahead; its error names the surface it reaches.
#[test]
fn lenses_that_reach_a_surface_or_focus_nowhere() {
    let objects = [BALL, plane([0.0, 1.0, 0.0], None)];
    let lens = |aperture, focus_distance| SceneDesc {
        camera: CameraDesc {
            aperture,
            focus_distance,
            ..CAMERA
        },
        ..scene(&objects, &[LIGHT])
    };
    assert!(build(&lens(0.5, Some(3.0))).is_ok());
    // The eye is 1 above the floor (object 1).
    assert!(matches!(
        build(&lens(1.0, None)).unwrap_err(),
        SceneError::LensTouches { object: 1, clearance, aperture: 1.0 } if clearance == 1.0
    ));
    let bounds = [
        (lens(-0.1, None), "aperture"),
        (lens(0.1, Some(0.0)), "focus_distance"),
        (lens(0.1, Some(-2.0)), "focus_distance"),
    ];
    for (desc, field) in bounds {
        assert!(
            matches!(build(&desc).unwrap_err(), SceneError::OutOfBounds { item: Item::Camera, field: f, .. } if f == field),
            "{field}"
        );
    }
    assert_eq!(
        build(&lens(f32::NAN, None)).unwrap_err(),
        SceneError::NotFinite {
            item: Item::Camera,
            field: "aperture"
        }
    );
    let message = build(&lens(2.0, None)).unwrap_err().to_string();
    assert!(
        message.contains("object 1") && message.contains("make the aperture smaller"),
        "{message}"
    );
}

#[test]
fn up_parallel_to_the_view() {
    let mut desc = scene(&[], &[]);
    desc.camera.up = [0.0, 0.0, -3.0];
    assert_eq!(build(&desc).unwrap_err(), SceneError::UpParallelToView);
}

#[test]
fn field_of_view_far_and_materials_out_of_bounds() {
    for fov in [0.0, 180.0, -10.0] {
        let mut desc = scene(&[], &[]);
        desc.camera.vfov_degrees = fov;
        assert!(matches!(
            build(&desc).unwrap_err(),
            SceneError::OutOfBounds {
                field: "vfov_degrees",
                ..
            }
        ));
    }
    let mut desc = scene(&[], &[]);
    desc.far = 0.0;
    assert!(matches!(
        build(&desc).unwrap_err(),
        SceneError::OutOfBounds { field: "far", .. }
    ));
    let bad = |material| [ObjectDesc { material, ..BALL }];
    for (material, field) in [
        (
            MaterialDesc {
                reflection: 1.5,
                ..MATTE
            },
            "material.reflection",
        ),
        (
            MaterialDesc {
                diffuse: -0.1,
                ..MATTE
            },
            "material.diffuse",
        ),
        (
            MaterialDesc {
                reflection: 0.6,
                transmission: 0.6,
                ..MATTE
            },
            "material.reflection + material.transmission",
        ),
        (MaterialDesc { ior: 0.5, ..MATTE }, "material.ior"),
        (
            MaterialDesc {
                colour: [1.2, 0.0, 0.0],
                ..MATTE
            },
            "material.colour",
        ),
    ] {
        let error = build(&scene(&bad(material), &[])).unwrap_err();
        assert!(
            matches!(error, SceneError::OutOfBounds { item: Item::Object(0), field: f, .. } if f == field),
            "{error:?}"
        );
    }
    let checker = [plane(
        [0.0, 1.0, 0.0],
        Some(CheckerDesc {
            colour: [1.0; 3],
            size: 0.0,
        }),
    )];
    assert!(matches!(
        build(&scene(&checker, &[])).unwrap_err(),
        SceneError::OutOfBounds {
            field: "shape.plane.checker.size",
            ..
        }
    ));
    let dark = [LightDesc {
        colour: [-1.0, 0.0, 0.0],
        ..LIGHT
    }];
    assert!(matches!(
        build(&scene(&[], &dark)).unwrap_err(),
        SceneError::OutOfBounds {
            item: Item::Light(0),
            ..
        }
    ));
}

#[test]
fn more_objects_lights_or_depth_than_the_capacity() {
    let objects = [BALL; 5];
    assert_eq!(
        build(&scene(&objects, &[])).unwrap_err(),
        SceneError::TooMany {
            what: "objects",
            count: 5,
            capacity: 4
        }
    );
    let lights = [LIGHT; 3];
    assert_eq!(
        build(&scene(&[], &lights)).unwrap_err(),
        SceneError::TooMany {
            what: "lights",
            count: 3,
            capacity: 2
        }
    );
    let mut desc = scene(&[], &[]);
    desc.max_depth = 4;
    assert_eq!(
        build(&desc).unwrap_err(),
        SceneError::DepthExceedsStack {
            max_depth: 4,
            capacity: 4
        }
    );
}

#[test]
fn anything_outside_the_world() {
    let far_ball = [sphere([0.0, 1.0, 14.0], 2.0)];
    let error = build(&scene(&far_ball, &[])).unwrap_err();
    assert!(
        matches!(error, SceneError::OutsideWorld { item: Item::Object(0), far, .. } if far == 20.0),
        "{error:?}"
    );
    assert!(error.to_string().contains("raise far"), "{error}");
    let far_corner = [triangle([
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 30.0],
    ])];
    assert!(matches!(
        build(&scene(&far_corner, &[])).unwrap_err(),
        SceneError::OutsideWorld { .. }
    ));
    let far_light = [LightDesc {
        position: [0.0, 30.0, 0.0],
        ..LIGHT
    }];
    assert!(matches!(
        build(&scene(&[], &far_light)).unwrap_err(),
        SceneError::OutsideWorld {
            item: Item::Light(0),
            ..
        }
    ));
    let far_plane = [ObjectDesc {
        shape: ShapeDesc::Plane {
            point: [0.0, -50.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            checker: None,
        },
        material: MATTE,
    }];
    assert!(matches!(
        build(&scene(&far_plane, &[])).unwrap_err(),
        SceneError::OutsideWorld { .. }
    ));
}

#[test]
fn a_world_too_large_for_the_format_names_the_value_and_the_formats_that_fit() {
    let objects = [sphere([0.0, 1.0, 100.0], 1.0)];
    let mut desc = scene(&objects, &[]);
    desc.far = 200.0;
    let error = build(&desc).unwrap_err();
    assert!(
        matches!(error, SceneError::OutOfRange { format: "i16f16", quantity, .. } if quantity.contains("b² − c")),
        "{error:?}"
    );
    let message = error.to_string();
    assert!(
        message.contains("formats that hold it: i18f14 i20f12 i22f10 i24f8 i32f32"),
        "{message}"
    );
    assert!(Small::<f32>::build(&desc).is_ok(), "f32 holds it");
    assert!(
        Small::<obscura::I32F32>::build(&desc).is_ok(),
        "i32f32 holds it"
    );
}

#[test]
fn a_feature_below_the_format_resolution() {
    let objects = [sphere([0.0, 1.0, 0.0], 0.01)];
    let error = build(&scene(&objects, &[])).unwrap_err();
    assert!(
        matches!(
            error,
            SceneError::BelowResolution {
                item: Item::Object(0),
                format: "i16f16",
                ..
            }
        ),
        "{error:?}"
    );
    assert!(Small::<f64>::build(&scene(&objects, &[])).is_ok());
}

#[test]
fn image_sizes_and_extreme_fields_of_view() {
    let scene_ok = build(&scene(&[BALL], &[])).unwrap();
    assert_eq!(
        scene_ok.camera(0, 10).unwrap_err(),
        SceneError::ImageSize {
            width: 0,
            height: 10
        }
    );
    assert_eq!(
        scene_ok.camera(10, 9000).unwrap_err(),
        SceneError::ImageSize {
            width: 10,
            height: 9000
        }
    );
    let mut desc = scene(&[BALL], &[]);
    desc.camera.vfov_degrees = 179.9;
    let wide = build(&desc).unwrap();
    assert!(matches!(
        wide.camera(8192, 1).unwrap_err(),
        SceneError::OutOfRange {
            item: Item::Camera,
            ..
        }
    ));
}

#[test]
fn every_message_says_what_to_do() {
    let errors = [
        SceneError::NotFinite {
            item: Item::Object(1),
            field: "shape.sphere.radius",
        },
        SceneError::DegenerateTriangle {
            item: Item::Object(0),
        },
        SceneError::UpParallelToView,
        SceneError::LensTouches {
            object: 2,
            clearance: 0.5,
            aperture: 0.75,
        },
        SceneError::TooMany {
            what: "objects",
            count: 9,
            capacity: 8,
        },
        SceneError::DepthExceedsStack {
            max_depth: 9,
            capacity: 6,
        },
        SceneError::BelowResolution {
            item: Item::Object(0),
            quantity: "radius²",
            value: 1e-4,
            format: "i16f16",
            minimum: 2e-4,
            remedy: Remedy::LargerSphere,
            holds: FormatSet::default(),
            method: None,
        },
    ];
    let advice = ["give", "move", "choose", "raise", "lower", "model", "make"];
    for error in errors {
        let message = error.to_string();
        assert!(
            advice.iter().any(|word| message.contains(word)),
            "no advice in: {message}"
        );
    }
}

#[test]
fn messages_carry_their_figures() {
    let cases = [
        (
            SceneError::OutOfBounds {
                item: Item::Camera,
                field: "vfov_degrees",
                value: 270.5,
                expected: "in (0, 180)",
            },
            "270.5",
        ),
        (
            SceneError::OutsideWorld {
                item: Item::Light(0),
                distance: 123.25,
                far: 100.0,
            },
            "123.25",
        ),
        (
            SceneError::LensTouches {
                object: 0,
                clearance: 0.5,
                aperture: 0.75,
            },
            "0.75",
        ),
        (
            SceneError::OutOfRange {
                item: Item::Scene,
                quantity: "|o − c|²",
                value: 4.5e9,
                format: "i16f16",
                range: 32768.0,
                remedy: Remedy::ShrinkWorld,
                holds: FormatSet::of(|f| f.range > 4.5e9),
            },
            "4.500000e9",
        ),
        (
            SceneError::BelowResolution {
                item: Item::Scene,
                quantity: "radius²",
                value: 1.25e-4,
                format: "i16f16",
                minimum: 2e-4,
                remedy: Remedy::LargerSphere,
                holds: FormatSet::of(|f| f.name == "f64"),
                method: Some(("sphere", "stable")),
            },
            "1.250e-4",
        ),
    ];
    for (error, figure) in cases {
        let message = error.to_string();
        assert!(message.contains(figure), "{figure} not in: {message}");
    }
}

#[test]
fn a_sliver_triangle_is_refused_as_too_thin_whatever_else_it_inflates() {
    // 1 wide and a millionth high: its tolerance (the rounding of the distance it finds, over
    // its area) would start rays far beyond the world, but the cause is its thinness.
    for height in [1e-6, 1e-7] {
        let objects = [triangle([
            [-0.5, 1.0, 2.0],
            [0.5, 1.0, 2.0],
            [0.0, 1.0 + height, 2.0],
        ])];
        for triangle in [TriangleMethod::Cramer, TriangleMethod::Watertight] {
            let methods = Methods {
                triangle,
                ..Methods::LECTURE
            };
            let error = Small::<I16F16>::build_with(&scene(&objects, &[]), methods).unwrap_err();
            assert!(
                matches!(
                    error,
                    SceneError::BelowResolution {
                        remedy: Remedy::FatterTriangle,
                        ..
                    }
                ),
                "{triangle:?}: {error:?}"
            );
            assert!(error.to_string().contains("move a corner away"), "{error}");
        }
    }
}
