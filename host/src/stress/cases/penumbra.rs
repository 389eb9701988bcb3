//! A ball's soft shadow on a floor under a disc light whose radius shrinks from 1 to 10⁻⁶, lit
//! from high above and at a grazing angle (the light 5° above the horizon, the penumbra
//! stretched across the floor). 16 shadow rays a point, every one traced: a format must draw
//! what f64 draws aiming at the same points of the disc, however small the disc, where its
//! points crowd within a few steps of the centre and finally round onto it.

use super::{MATTE, image_row, log_sweep, psnr};
use crate::checked::Checked;
use crate::stress::{Case, Row};
use anyhow::Result;
use obscura::{
    BackgroundDesc, CameraDesc, LightDesc, Methods, ObjectDesc, Scalar, SceneDesc, ShapeDesc,
};
use obscura_scene::FormatJob;

pub const CASE: Case = Case {
    name: "penumbra",
    about: "a ball's soft shadow under a disc light of radius 1 to 1e-6, from overhead and at 5° above the horizon",
    x_label: "the light's radius",
    log_x: true,
    y_label: "PSNR against f64 (dB)",
    run: |format| format.run::<Checked, _>(Job),
};

/// The floor, and the ball whose shadow is the penumbra.
const OBJECTS: [ObjectDesc; 2] = [
    ObjectDesc {
        shape: ShapeDesc::Plane {
            point: [0.0; 3],
            normal: [0.0, 1.0, 0.0],
            checker: None,
        },
        material: MATTE,
    },
    ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [0.0, 1.2, 0.0],
            radius: 1.0,
        },
        material: MATTE,
    },
];

/// Where the light stands: overhead, or 5° above the horizon, both 6 from the ball.
const LIGHTS: [(&str, [f32; 3]); 2] = [
    ("overhead", [-1.0, 7.1, -0.5]),
    ("grazing", [-5.977, 1.723, 0.0]),
];

/// The scene: the ball on the floor seen from above and in front, under `light`.
fn scene(light: &[LightDesc]) -> SceneDesc<'_> {
    SceneDesc {
        camera: CameraDesc::pinhole([0.0, 4.0, -4.5], [0.0, 0.0, 0.5], [0.0, 1.0, 0.0], 60.0),
        objects: &OBJECTS,
        lights: light,
        ambient: [0.15; 3],
        background: BackgroundDesc::Solid([0.1, 0.2, 0.6]),
        far: 12.0,
        max_depth: 0,
        shadow_samples: 16,
        ..SceneDesc::DEFAULT
    }
}

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let mut rows = Vec::new();
        for radius in log_sweep(1.0, 1e-6, 7) {
            for (name, position) in LIGHTS {
                let light = [LightDesc {
                    radius: radius as f32,
                    ..LightDesc::point(position, [0.9; 3])
                }];
                let desc = scene(&light);
                rows.push(image_row::<S>(&desc, Methods::LECTURE, name, radius, psnr));
            }
        }
        Ok(rows)
    }
}
