//! Shadow acne on a lit plane: a matte floor lit from ever lower elevations and nothing to cast
//! a shadow, so that any shadowed pixel is the floor shadowing itself. Per self-intersection
//! method, the wrongly shadowed pixels.

use super::{image_row, log_sweep, wrong};
use crate::checked::Checked;
use crate::stress::{Case, Row};
use anyhow::Result;
use obscura::methods::MethodName;
use obscura::{
    BackgroundDesc, BiasMethod, CameraDesc, LightDesc, MaterialDesc, Methods, ObjectDesc, Scalar,
    SceneDesc, ShapeDesc,
};
use obscura_scene::FormatJob;

pub const CASE: Case = Case {
    name: "acne",
    about: "shadow acne on a lit plane, the light from 30° down to 0.3° above it",
    x_label: "the light's elevation (degrees)",
    log_x: true,
    y_label: "wrong pixels (%)",
    run: |format| format.run::<Checked, _>(Job),
};

const FLOOR: [ObjectDesc; 1] = [ObjectDesc {
    shape: ShapeDesc::Plane {
        point: [0.0, -1.5, 0.0],
        normal: [0.0, 1.0, 0.0],
        checker: None,
    },
    material: MaterialDesc::matte([1.0, 1.0, 1.0]),
}];

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let mut rows = Vec::new();
        for elevation in log_sweep(30.0, 0.3, 5) {
            let (sin, cos) = elevation.to_radians().sin_cos();
            // Far off in +z, bright enough that the lit floor stands well clear of the ambient.
            let light = [LightDesc::point(
                [0.0, (-1.5 + 20.0 * sin) as f32, (20.0 * cos) as f32],
                [(0.7 / sin) as f32; 3],
            )];
            let desc = SceneDesc {
                camera: CameraDesc::pinhole([0.0; 3], [0.0, -1.5, 4.0], [0.0, 1.0, 0.0], 60.0),
                objects: &FLOOR,
                lights: &light,
                ambient: [0.1; 3],
                background: BackgroundDesc::Solid([0.0; 3]),
                far: 25.0,
                max_depth: 0,
                ..SceneDesc::DEFAULT
            };
            for &(bias, name) in BiasMethod::ALL {
                let methods = Methods {
                    bias,
                    ..Methods::LECTURE
                };
                rows.push(image_row::<S>(&desc, methods, name, elevation, wrong));
            }
        }
        Ok(rows)
    }
}
