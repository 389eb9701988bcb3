//! Grazing and tangent rays at a sphere's silhouette: rays along the line of sight at impact
//! parameters r·(1 ± δ), all around the silhouette. A ray may be misjudged (hit for miss or
//! miss for hit) only within a few of the error model's discriminant errors of tangency.

use super::{MATTE, Tally, bare, log_sweep, refused, sphere_truth};
use crate::checked::Checked;
use crate::render::HostScene;
use crate::stress::check::{MODEL_ERRORS, discriminant, model_error, to_f64};
use crate::stress::{Case, Row};
use anyhow::Result;
use obscura::methods::MethodName;
use obscura::{Methods, ObjectDesc, Ray, Scalar, ShapeDesc, SphereMethod, Vec3};
use obscura_scene::FormatJob;

pub const CASE: Case = Case {
    name: "grazing",
    about: "grazing and tangent rays at a sphere's silhouette: is each ray's hit or miss right?",
    x_label: "δ: the ray's distance from tangency, over the radius",
    log_x: true,
    y_label: "misjudged rays (%)",
    run: |format| format.run::<Checked, _>(Job),
};

const CENTER: [f64; 3] = [0.0, 0.0, 8.0];
/// Rays per δ: both sides of the silhouette at this many angles around it.
const AROUND: usize = 16;

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let center = CENTER.map(|c| c as f32);
        let objects = [ObjectDesc {
            shape: ShapeDesc::Sphere {
                center,
                radius: 1.0,
            },
            material: MATTE,
        }];
        let desc = bare(&objects, 10.0);
        let truth = sphere_truth(&desc)?;
        let deltas = log_sweep(1e-1, 1e-7, 13);
        let mut rows = Vec::new();
        for &(method, name) in SphereMethod::ALL {
            let methods = Methods {
                sphere: method,
                ..Methods::LECTURE
            };
            let scene = match HostScene::<S>::build_with(&desc, methods) {
                Ok(scene) => scene,
                Err(error) => {
                    rows.extend(deltas.iter().map(|&x| refused(S::NAME, name, x, &error)));
                    continue;
                }
            };
            let band = MODEL_ERRORS * model_error::<S>(&desc, &methods, 0);
            for &delta in &deltas {
                let mut tally = Tally::default();
                for k in 0..AROUND {
                    let angle = std::f64::consts::TAU * k as f64 / AROUND as f64 + 0.1;
                    for side in [-1.0, 1.0] {
                        let h = 1.0 + side * delta;
                        let origin = [h * angle.cos(), h * angle.sin(), 0.0];
                        let (Some(origin), Some(dir)) =
                            (Vec3::<S>::from_f64(origin), Vec3::from_f64([0.0, 0.0, 1.0]))
                        else {
                            continue;
                        };
                        let ray = Ray::new(origin, dir);
                        tally.record(
                            scene.first_hit(&ray).is_some(),
                            truth.first_hit(&to_f64(&ray)).is_some(),
                            || discriminant(&ray, CENTER, 1.0).abs() <= band,
                        );
                    }
                }
                rows.push(tally.row(S::NAME, name, delta));
            }
        }
        Ok(rows)
    }
}
