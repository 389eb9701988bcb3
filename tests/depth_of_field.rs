//! Depth of field (`CameraDesc::aperture`, `focus_distance`): through the thin lens, the focal
//! plane stays sharp, every other depth blurs by the circle the thin-lens equation gives, and
//! a vanishing aperture is the pinhole.

mod common;

use common::{psnr, render};
use obscura::formats::I12f20;
use obscura::pattern::Pattern;
use obscura::{CameraDesc, I16F16, Methods, Scalar, Scene, SceneDesc, Vec3, scenes};

/// The image's side in pixels.
const SIDE: u32 = 64;

/// Lens samples tried per pixel.
const LENS_SAMPLES: u16 = 64;

/// The focus scene's camera, in f64: forward, right and up, and the image plane's half height
/// one unit ahead.
struct Frame {
    forward: Vec3<f64>,
    right: Vec3<f64>,
    up: Vec3<f64>,
    half: f64,
}

fn frame(camera: &CameraDesc) -> Frame {
    let forward = (Vec3::from_f32(camera.look_at) - Vec3::from_f32(camera.eye))
        .direction()
        .expect("the camera looks somewhere");
    let right = forward
        .cross(Vec3::from_f32(camera.up))
        .direction()
        .expect("up is not the view direction");
    Frame {
        forward,
        right,
        up: right.cross(forward),
        half: (f64::from(camera.vfov_degrees).to_radians() / 2.0).tan(),
    }
}

/// Where a ray meets the plane `depth` ahead of the eye, seen through the pinhole: in pixels
/// (across, down) of a square image of `SIDE`.
fn seen_at(frame: &Frame, origin: Vec3<f64>, dir: Vec3<f64>, depth: f64) -> [f64; 2] {
    let t = (depth - frame.forward.dot(origin)) / frame.forward.dot(dir);
    let s = origin.add_scaled(dir, t) * (1.0 / depth);
    let pitch = 2.0 * frame.half / f64::from(SIDE);
    [
        (s.dot(frame.right) + frame.half) / pitch,
        (frame.half - s.dot(frame.up)) / pitch,
    ]
}

/// Every ray a pixel's lens samples send passes through the point its pinhole ray meets on the
/// focal plane, so that point lands on that pixel from every lens point; a point at depth d
/// lands off it by the thin lens's A·(1/d − 1/f) times the lens point (a, b), in pixels: the
/// circle of confusion. In f64, f32 and the 32-bit fixed formats the focus scene holds.
#[test]
fn the_focal_plane_is_sharp_and_other_depths_blur_as_the_thin_lens_says() {
    fn check<S: Scalar>(tolerance: f64) {
        let desc = scenes::FOCUS;
        let scene = Scene::<S, 8, 2, 4>::build(&desc).expect("the focus scene builds");
        let camera = scene.camera(SIDE, SIDE).expect("the size is valid");
        let frame = frame(&desc.camera);
        let aperture = f64::from(desc.camera.aperture);
        let focus = (Vec3::from_f32(desc.camera.look_at) - Vec3::from_f32(desc.camera.eye))
            .dot(frame.forward);
        assert!(camera.lens().is_some(), "{}", S::NAME);
        for (x, y) in [(0, 0), (31, 17), (63, 63), (40, 5), (7, 50)] {
            let lens = Pattern::lens(x, y);
            for i in 0..LENS_SAMPLES {
                let [a, b] = lens.disc::<S>(i);
                let ray = camera
                    .ray_through_lens(x, y, [S::ZERO; 2], [a, b])
                    .expect("the pixel is in the image");
                let [origin, dir] = [ray.origin, ray.dir]
                    .map(|v| Vec3::from_f64(v.to_f64()).expect("a ray is finite"));
                let centre = [f64::from(x) + 0.5, f64::from(y) + 0.5];
                for depth in [focus, focus / 2.0, 2.0 * focus] {
                    let blur = aperture * (1.0 / depth - 1.0 / focus) / (2.0 * frame.half)
                        * f64::from(SIDE);
                    let want = [centre[0] + a.to_f64() * blur, centre[1] - b.to_f64() * blur];
                    let got = seen_at(&frame, origin, dir, depth);
                    for (g, w) in got.into_iter().zip(want) {
                        assert!(
                            (g - w).abs() < tolerance,
                            "{}: pixel ({x}, {y}), lens sample {i} at depth {depth}: lands at \
                             {got:?}, not {want:?}",
                            S::NAME
                        );
                    }
                }
            }
        }
    }
    check::<f64>(1e-9);
    check::<f32>(1e-3);
    check::<I12f20>(2e-3);
    check::<I16F16>(2e-2);
}

/// The focus scene at `aperture`.
fn focus_at(aperture: f32) -> SceneDesc<'static> {
    SceneDesc {
        camera: CameraDesc {
            aperture,
            ..scenes::FOCUS.camera
        },
        ..scenes::FOCUS
    }
}

/// As the aperture shrinks to 0 the image converges to the pinhole's with the same samples:
/// each halving of the lens brings it closer, to within a level or so at the smallest; in f64
/// and in i12f20, down to the smallest lens i12f20 can focus.
#[test]
fn a_vanishing_aperture_converges_to_the_pinhole_image() {
    fn check<S: Scalar>(apertures: &[f32], closest_db: f64) {
        let side = 48;
        let (pinhole, _) = render::<S>(&focus_at(0.0), side, side, Methods::LECTURE);
        let mut last = 0.0;
        for &aperture in apertures {
            let (lens, _) = render::<S>(&focus_at(aperture), side, side, Methods::LECTURE);
            let db = psnr(&lens, &pinhole);
            assert!(
                db > last,
                "{}: aperture {aperture} is {db:.2} dB from the pinhole, no closer than the \
                 larger one's {last:.2}",
                S::NAME
            );
            last = db;
        }
        assert!(
            last >= closest_db,
            "{}: the smallest lens is {last:.2} dB from the pinhole",
            S::NAME
        );
    }
    check::<f64>(&[0.2, 0.05, 0.0125, 0.003, 0.0008], 50.0);
    check::<I12f20>(&[0.2, 0.05, 0.0125, 0.003], 45.0);
}

/// A lens the format cannot focus is refused, with the remedy, rather than drawn focused
/// somewhere else: one whose points round coarsely (their rounding moves every ray's meeting
/// point), and one whose tilt A/f is lost in the rounding of a direction (a far focus), even
/// where the tilt alone would be large.
#[test]
fn a_lens_the_format_cannot_focus_is_refused() {
    let lens = |aperture, focus_distance| SceneDesc {
        camera: CameraDesc {
            aperture,
            focus_distance,
            ..scenes::FOCUS.camera
        },
        ..scenes::FOCUS
    };
    let cases = [
        (lens(1e-4, None), "aperture, the lens's radius"),
        (lens(5e-6, Some(1e-5)), "aperture, the lens's radius"),
        (lens(0.01, Some(400.0)), "aperture / focus_distance"),
    ];
    for (desc, quantity) in cases {
        let error = Scene::<I16F16, 8, 2, 4>::build(&desc)
            .and_then(|scene| scene.camera(SIDE, SIDE))
            .expect_err("i16f16 cannot focus it");
        let message = error.to_string();
        assert!(
            message.contains(quantity) && message.contains("open the aperture"),
            "{message}"
        );
        assert!(
            Scene::<f64, 8, 2, 4>::build(&desc)
                .and_then(|scene| scene.camera(SIDE, SIDE))
                .is_ok(),
            "{quantity}"
        );
    }
}
