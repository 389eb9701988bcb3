//! The stress cases, one file each, and the scene pieces they share.

mod acne;
mod adaptive;
mod distant;
mod floor;
mod focal;
mod glass;
mod grazing;
mod mesh;
mod penumbra;
mod plane;
mod scale;
mod sliver;

use super::check::{ImageCheck, image};
use super::{Case, Outcome, Row};
use crate::render::HostScene;
use anyhow::Context as _;
use obscura::{BackgroundDesc, CameraDesc, MaterialDesc, Methods, Scalar, SceneDesc, SceneError};

/// Every case, in the order they run.
pub static CASES: [Case; 15] = [
    grazing::CASE,
    distant::CASE,
    floor::CASE,
    plane::CASE,
    sliver::CASE,
    mesh::CASE,
    acne::CASE,
    glass::CASE,
    scale::CASE,
    penumbra::CASE,
    focal::CASE,
    adaptive::SHADOW,
    adaptive::REFLECTION,
    adaptive::CHECKER,
    adaptive::GLASS,
];

/// A camera at the origin looking along +z, for cases that shoot their own rays.
const CAMERA: CameraDesc =
    CameraDesc::pinhole([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 45.0);

/// A grey matte surface.
const MATTE: MaterialDesc = MaterialDesc::matte([0.7, 0.7, 0.7]);

/// A scene with these objects and nothing else, seen from the origin, within `far`.
fn bare<'a>(objects: &'a [obscura::ObjectDesc], far: f32) -> SceneDesc<'a> {
    SceneDesc {
        camera: CAMERA,
        objects,
        lights: &[],
        ambient: [0.2; 3],
        background: BackgroundDesc::Solid([0.0; 3]),
        far,
        max_depth: 0,
        ..SceneDesc::DEFAULT
    }
}

/// A row for a scene the build refused.
fn refused(format: &'static str, method: &'static str, x: f64, error: &SceneError) -> Row {
    Row {
        format,
        method,
        x,
        y: None,
        outcome: Outcome::Refused {
            kind: match error {
                SceneError::OutOfRange { .. } => "range",
                SceneError::BelowResolution { .. } => "resolution",
                SceneError::DegenerateTriangle { .. } => "degenerate",
                _ => "invalid",
            },
            reason: error.to_string(),
        },
    }
}

/// The rays of one measurement: how many were shot, how many the format judged otherwise than
/// f64, and how many of those the error model does not excuse.
#[derive(Debug, Default)]
struct Tally {
    shot: u32,
    misjudged: u32,
    unexcused: u32,
}

impl Tally {
    /// Counts a ray the format judged `got` and f64 `want` (a hit, or the right face);
    /// `excused` says whether a misjudgement lies within the error model's band.
    fn record(&mut self, got: bool, want: bool, excused: impl FnOnce() -> bool) {
        self.shot += 1;
        if got != want {
            self.misjudged += 1;
            self.unexcused += u32::from(!excused());
        }
    }

    /// The row: the share of rays misjudged, in percent, within its bound when the model
    /// excuses every one.
    fn row(&self, format: &'static str, method: &'static str, x: f64) -> Row {
        Row {
            format,
            method,
            x,
            y: Some(100.0 * f64::from(self.misjudged) / f64::from(self.shot.max(1))),
            outcome: Outcome::bounded(f64::from(self.unexcused), 0.0),
        }
    }
}

/// The f64 reference for a sphere's hit or miss: the stable form, whose discriminant does not
/// cancel.
fn sphere_truth(desc: &SceneDesc<'_>) -> anyhow::Result<HostScene<f64>> {
    let stable = Methods {
        sphere: obscura::SphereMethod::Stable,
        ..Methods::LECTURE
    };
    HostScene::<f64>::build_with(desc, stable).context("the f64 reference builds")
}

/// The images the cases compare are this many pixels square.
pub(super) const SIZE: u32 = 48;

/// The row of `desc` in format `S` by `methods` ([`image()`]) where the stressed parameter is
/// `x`: `y` of the check, within its bound when no pixel is off unexcused; or the build's
/// refusal.
fn image_row<S: Scalar>(
    desc: &SceneDesc<'_>,
    methods: Methods,
    method: &'static str,
    x: f64,
    y: fn(&ImageCheck) -> f64,
) -> Row {
    match image::<S>(desc, methods, SIZE) {
        Ok(check) => Row {
            format: S::NAME,
            method,
            x,
            y: Some(y(&check)),
            outcome: Outcome::bounded(check.unexcused as f64, 0.0),
        },
        Err(error) => refused(S::NAME, method, x, &error),
    }
}

/// An image's PSNR, with identical images drawn at 100 dB.
fn psnr(check: &ImageCheck) -> f64 {
    capped(check.psnr_db)
}

/// A PSNR drawn at 100 dB where it is infinite (identical images).
fn capped(psnr_db: f64) -> f64 {
    psnr_db.min(100.0)
}

/// An image's share of wrong pixels, in percent.
fn wrong(check: &ImageCheck) -> f64 {
    check.wrong_pct
}

/// `count` values from `first` to `last`, evenly spaced on a log scale.
fn log_sweep(first: f64, last: f64, count: usize) -> Vec<f64> {
    let step = (last / first).ln() / (count - 1).max(1) as f64;
    (0..count)
        .map(|i| first * (step * i as f64).exp())
        .collect()
}
