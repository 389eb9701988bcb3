//! A lens focused 8 or 0.5 ahead whose radius shrinks from 0.5 to 10⁻⁶, until its tilt A/f,
//! which places the focal plane, is lost in the format's rounding of a ray's direction (far
//! focus), or its lens points in their own rounding (near focus). Every ray a
//! pixel sends through its lens points must meet the others on the focal plane: each one's
//! miss there, over the lens's radius, is the error of the focus distance at the lens's edge,
//! and a format that accepts the lens must keep it within a sixteenth (the range proof's
//! [`MIN_FEATURE_STEPS`]); below that it must refuse.

use super::{CAMERA, MATTE, SIZE, bare, log_sweep, refused};
use crate::checked::Checked;
use crate::render::HostScene;
use crate::stress::{Case, Outcome, Row};
use anyhow::{Context as _, Result};
use obscura::pattern::Pattern;
use obscura::scene::range::MIN_FEATURE_STEPS;
use obscura::{CameraDesc, ObjectDesc, Scalar, SceneDesc, ShapeDesc, Vec3};
use obscura_scene::FormatJob;

pub const CASE: Case = Case {
    name: "focal-plane",
    about: "a lens focused 8 or 0.5 ahead, its radius from 0.5 to 1e-6: where its rays meet",
    x_label: "the lens's radius (aperture)",
    log_x: true,
    y_label: "largest miss on the focal plane (% of the aperture)",
    run: |format| format.run::<Checked, _>(Job),
};

/// How far ahead the lens focuses: far, where its tilt is small, and near, where its tilt is
/// large and its points' own rounding is what remains.
const FOCI: [(&str, f32); 2] = [("focus 8", 8.0), ("focus 0.5", 0.5)];

/// Lens points tried per pixel.
const LENS_SAMPLES: u16 = 16;

/// A floor 1 below the eye, which keeps every lens of the sweep clear of it.
const FLOOR: [ObjectDesc; 1] = [ObjectDesc {
    shape: ShapeDesc::Plane {
        point: [0.0, -1.0, 0.0],
        normal: [0.0, 1.0, 0.0],
        checker: None,
    },
    material: MATTE,
}];

/// The floor seen from the origin along +z through a lens of radius `aperture`, focused `focus`
/// ahead.
fn scene(aperture: f32, focus: f32) -> SceneDesc<'static> {
    SceneDesc {
        camera: CameraDesc {
            aperture,
            focus_distance: Some(focus),
            ..CAMERA
        },
        ..bare(&FLOOR, 20.0)
    }
}

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let mut rows = Vec::new();
        for aperture in log_sweep(0.5, 1e-6, 13) {
            for (method, focus) in FOCI {
                rows.push(focal_row::<S>(aperture, method, focus)?);
            }
        }
        Ok(rows)
    }
}

/// The largest miss on the focal plane, as a share of the aperture, of a lens of radius
/// `aperture` focused `focus` ahead, in format `S`; or the build's refusal.
fn focal_row<S: Scalar>(aperture: f64, method: &'static str, focus: f32) -> Result<Row> {
    let desc = scene(aperture as f32, focus);
    let camera = match HostScene::<S>::build(&desc).and_then(|scene| scene.camera(SIZE, SIZE)) {
        Ok(camera) => camera,
        Err(error) => return Ok(refused(S::NAME, method, aperture, &error)),
    };
    let reference = HostScene::<f64>::build(&desc)
        .and_then(|scene| scene.camera(SIZE, SIZE))
        .context("the f64 reference builds")?;
    let focus = f64::from(focus);
    let mut miss = 0.0_f64;
    let pixels = (0..SIZE)
        .step_by(7)
        .flat_map(|x| (0..SIZE).step_by(5).map(move |y| (x, y)));
    for (x, y) in pixels {
        // The pinhole's ray through the pixel's centre meets the focal plane at f·s.
        let pinhole = reference
            .ray_through_lens(x, y, [0.0; 2], [0.0; 2])
            .context("the pixel is in the image")?;
        let focal = pinhole.dir * (focus / pinhole.dir.z);
        let lens = Pattern::lens(x, y);
        for i in 0..LENS_SAMPLES {
            let ray = camera
                .ray_through_lens(x, y, [S::ZERO; 2], lens.disc(i))
                .context("the pixel is in the image")?;
            let [o, d] = [ray.origin, ray.dir].map(|v| Vec3::<f64>::from_f64(v.to_f64()));
            let (Some(o), Some(d)) = (o, d) else { continue };
            let met = o.add_scaled(d, (focus - o.z) / d.z);
            miss = miss.max((met - focal).length() / aperture);
        }
    }
    let bound = 100.0 / MIN_FEATURE_STEPS;
    Ok(Row {
        format: S::NAME,
        method,
        x: aperture,
        y: Some(100.0 * miss),
        outcome: Outcome::bounded(100.0 * miss, bound),
    })
}
