//! A huge sphere used as a floor (radius 10 to 10⁵, its top where a plane would be) against a
//! true plane. The sphere makes every number as large as its radius; a plane needs none of
//! them. Model no more than the scene needs.

use super::{MATTE, image_row, log_sweep, psnr};
use crate::checked::Checked;
use crate::stress::{Case, Row};
use anyhow::Result;
use obscura::methods::MethodName;
use obscura::{
    BackgroundDesc, CameraDesc, LightDesc, Methods, ObjectDesc, Scalar, SceneDesc, ShapeDesc,
    SphereMethod,
};
use obscura_scene::FormatJob;

pub const CASE: Case = Case {
    name: "floor",
    about: "a huge sphere as a floor, radius 1e1 to 1e5, against a true plane",
    x_label: "the floor sphere's radius",
    log_x: true,
    y_label: "PSNR against f64 (dB)",
    run: |format| format.run::<Checked, _>(Job),
};

/// The scene: the camera 2 above the floor looking down at it, one light.
fn scene(floor: ShapeDesc, far: f32, objects: &mut Vec<ObjectDesc>) -> SceneDesc<'_> {
    objects.clear();
    objects.push(ObjectDesc {
        shape: floor,
        material: MATTE,
    });
    SceneDesc {
        camera: CameraDesc::pinhole([0.0, 2.0, 0.0], [0.0, 0.0, 4.0], [0.0, 1.0, 0.0], 45.0),
        objects,
        lights: &LIGHTS,
        ambient: [0.2; 3],
        background: BackgroundDesc::Solid([0.1, 0.2, 0.6]),
        far,
        max_depth: 0,
        ..SceneDesc::DEFAULT
    }
}

const LIGHTS: [LightDesc; 1] = [LightDesc::point([3.0, 8.0, 1.0], [1.0; 3])];

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let mut rows = Vec::new();
        let mut objects = Vec::new();
        for radius in log_sweep(1e1, 1e5, 5) {
            let r = radius as f32;
            let sphere = ShapeDesc::Sphere {
                center: [0.0, -r, 0.0],
                radius: r,
            };
            let plane = ShapeDesc::Plane {
                point: [0.0; 3],
                normal: [0.0, 1.0, 0.0],
                checker: None,
            };
            // The world must hold the whole sphere; the plane gets the same world.
            let far = 2.0 * r + 4.0;
            let floors = [
                (
                    sphere,
                    SphereMethod::Quadratic.name(),
                    SphereMethod::Quadratic,
                ),
                (sphere, SphereMethod::Stable.name(), SphereMethod::Stable),
                (plane, "plane", SphereMethod::Quadratic),
            ];
            for (floor, name, method) in floors {
                let desc = scene(floor, far, &mut objects);
                let methods = Methods {
                    sphere: method,
                    ..Methods::LECTURE
                };
                rows.push(image_row::<S>(&desc, methods, name, radius, psnr));
            }
        }
        Ok(rows)
    }
}
