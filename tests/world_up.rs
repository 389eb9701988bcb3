//! A scene's up: a scene modelled Z-up, its sky's up +z, draws what the same scene modelled
//! Y-up draws, pixel for pixel; and without an up, a gradient is as it always was (+y).

mod common;

use obscura::MeshesDesc;
use obscura::{
    BackgroundDesc, CameraDesc, I16F16, LightDesc, Methods, ObjectDesc, SceneDesc, ShapeDesc, Y_UP,
    scenes,
};

/// (x, y, z) turned a quarter about the x axis, so that +y goes to +z: exact in f32.
fn z_up(v: [f32; 3]) -> [f32; 3] {
    [v[0], -v[2], v[1]]
}

#[test]
fn a_z_up_scene_draws_what_the_y_up_one_does() {
    let y_up = scenes::WHITTED;
    // The spheres, the light and the sky of `whitted`: the checkerboard's squares follow the
    // world's axes, which a rotation relabels.
    let objects: Vec<ObjectDesc> = y_up
        .objects
        .iter()
        .filter(|o| matches!(o.shape, ShapeDesc::Sphere { .. }))
        .copied()
        .collect();
    let y_scene = SceneDesc {
        objects: &objects,
        meshes: MeshesDesc::NONE,
        ..y_up
    };
    let turned: Vec<ObjectDesc> = objects
        .iter()
        .map(|o| match o.shape {
            ShapeDesc::Sphere { center, radius } => ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: z_up(center),
                    radius,
                },
                ..*o
            },
            _ => *o,
        })
        .collect();
    let lights: Vec<LightDesc> = y_up
        .lights
        .iter()
        .map(|l| LightDesc {
            position: z_up(l.position),
            ..*l
        })
        .collect();
    let BackgroundDesc::Gradient {
        horizon,
        zenith,
        up,
    } = y_up.background
    else {
        panic!("whitted has a sky");
    };
    assert_eq!(up, Y_UP);
    let z_scene = SceneDesc {
        camera: CameraDesc {
            eye: z_up(y_up.camera.eye),
            look_at: z_up(y_up.camera.look_at),
            up: z_up(y_up.camera.up),
            ..y_up.camera
        },
        objects: &turned,
        meshes: MeshesDesc::NONE,
        lights: &lights,
        background: BackgroundDesc::Gradient {
            horizon,
            zenith,
            up: [0.0, 0.0, 1.0],
        },
        ..y_up
    };
    let (upright, _) = common::render::<I16F16>(&y_scene, 64, 48, Methods::LECTURE);
    let (turned, _) = common::render::<I16F16>(&z_scene, 64, 48, Methods::LECTURE);
    assert_eq!(turned.pixels, upright.pixels);
    // With the sky's up left at +y, the Z-up scene's sky is wrong.
    let wrong = SceneDesc {
        background: BackgroundDesc::Gradient {
            horizon,
            zenith,
            up: Y_UP,
        },
        ..z_scene
    };
    let (wrong, _) = common::render::<I16F16>(&wrong, 64, 48, Methods::LECTURE);
    assert_ne!(wrong.pixels, upright.pixels);
}
