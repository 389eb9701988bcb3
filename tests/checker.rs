//! A plane's checkerboard is anchored in the world: moving the eye moves the picture and nothing
//! else. Each square has the colour its place on the plane gives it, wherever the eye stands,
//! and an eye nudged across a square's edge draws what it drew before.

mod common;

use common::{Frame, psnr, render};
use embedded_graphics::pixelcolor::RgbColor;
use obscura::MeshesDesc;
use obscura::{
    BackgroundDesc, CameraDesc, CheckerDesc, I16F16, MaterialDesc, Methods, ObjectDesc, Scalar,
    Scene, SceneDesc, ShapeDesc, scenes,
};

const LECTURE: Methods = Methods::LECTURE;

/// `whitted` with its eye at `eye`.
fn whitted_from(eye: [f32; 3]) -> SceneDesc<'static> {
    SceneDesc {
        camera: CameraDesc {
            eye,
            ..scenes::WHITTED.camera
        },
        ..scenes::WHITTED
    }
}

/// `whitted`'s eye stands over a square's edge (z = −6, the squares 1 wide): one ulp either side
/// of it, the pictures are the same but for rounding, in every format.
#[test]
fn an_eye_nudged_across_a_square_edge_draws_the_same_picture() {
    fn nudged<S: Scalar>() -> f64 {
        let [x, y, z] = scenes::WHITTED.camera.eye;
        assert_eq!(z, -6.0, "the eye stands over an edge");
        let (before, _) = render::<S>(&whitted_from([x, y, z.next_down()]), 64, 64, LECTURE);
        let (after, _) = render::<S>(&whitted_from([x, y, z.next_up()]), 64, 64, LECTURE);
        psnr(&before, &after)
    }
    for (format, apart) in [
        ("f64", nudged::<f64>()),
        ("f32", nudged::<f32>()),
        ("i16f16", nudged::<I16F16>()),
    ] {
        assert!(apart >= 30.0, "{format}: {apart:.2} dB apart");
    }
}

/// A square's side on the floor of the camera path.
const SQUARE: f32 = 0.5;

/// The eye's height over the floor on the camera path.
const HEIGHT: f32 = 1.5;

/// A floor of black and white squares lit by white ambient light alone, seen straight down from
/// `HEIGHT` over (x, z) by a 90° camera whose up is +z.
fn floor_from(x: f32, z: f32) -> SceneDesc<'static> {
    const FLOOR: [ObjectDesc; 1] = [ObjectDesc {
        shape: ShapeDesc::Plane {
            point: [0.0, 0.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            checker: Some(CheckerDesc {
                colour: [1.0; 3],
                size: SQUARE,
            }),
        },
        material: MaterialDesc::matte([0.0; 3]),
    }];
    SceneDesc {
        camera: CameraDesc::pinhole([x, HEIGHT, z], [x, 0.0, z], [0.0, 0.0, 1.0], 90.0),
        objects: &FLOOR,
        meshes: MeshesDesc::NONE,
        lights: &[],
        ambient: [1.0; 3],
        background: BackgroundDesc::Solid([0.5; 3]),
        far: 4.0 * HEIGHT,
        ..scenes::WHITTED
    }
}

/// Whether the point (x, z) of the floor lies on a white square, and how far it is from the
/// nearest edge, in squares. The squares' axes are +x and −z (the plane's, for a floor).
fn square_at(x: f64, z: f64) -> (bool, f64) {
    let (u, v) = (x / f64::from(SQUARE), -z / f64::from(SQUARE));
    let white = (u.floor() + v.floor()).rem_euclid(2.0) == 1.0;
    let edge = |c: f64| (c - c.round()).abs();
    (white, edge(u).min(edge(v)))
}

/// Where each pixel's primary ray meets the floor, for the camera over (x, z), row by row.
fn floor_points(x: f32, z: f32, side: u32) -> Vec<(f64, f64)> {
    let scene = Scene::<f64, 16, 4, 8>::build_with(&floor_from(x, z), LECTURE).expect("builds");
    let camera = scene.camera(side, side).expect("the size is valid");
    (0..side)
        .filter_map(|y| camera.row(y))
        .flat_map(|row| row.rays())
        .map(|ray| {
            // The ray starts at the eye, the floor HEIGHT below it.
            let t = -f64::from(HEIGHT) / ray.dir.y;
            (f64::from(x) + t * ray.dir.x, f64::from(z) + t * ray.dir.z)
        })
        .collect()
}

/// A camera path across many squares' edges: in every frame and format, each pixel whose ray
/// meets the floor clear of an edge shows that square's colour; so consecutive frames differ
/// only where an edge moved.
#[test]
fn along_a_camera_path_every_square_keeps_its_colour() {
    const SIDE: u32 = 24;
    fn misplaced<S: Scalar>(x: f32, z: f32) -> usize {
        let (frame, _): (Frame, _) = render::<S>(&floor_from(x, z), SIDE, SIDE, LECTURE);
        floor_points(x, z, SIDE)
            .into_iter()
            .zip(&frame.pixels)
            .filter(|&((px, pz), colour)| {
                let (white, clear) = square_at(px, pz);
                clear > 0.05 && (colour.r() > 127) != white
            })
            .count()
    }
    for step in 0..48_u8 {
        // Steps of a ninth of a square across and a seventh along: the eye crosses edges of
        // both axes, on odd and even squares, at many places within a square.
        let x = -0.8 + f32::from(step) * SQUARE / 9.0;
        let z = 0.3 - f32::from(step) * SQUARE / 7.0;
        for (format, wrong) in [
            ("f64", misplaced::<f64>(x, z)),
            ("f32", misplaced::<f32>(x, z)),
            ("i16f16", misplaced::<I16F16>(x, z)),
        ] {
            assert_eq!(wrong, 0, "{format}, eye over ({x}, {z}): {wrong} pixels");
        }
    }
}
