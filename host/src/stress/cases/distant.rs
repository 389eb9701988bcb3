//! A small or distant sphere, its radius a fraction of its distance from 10⁻¹ down to 10⁻⁴:
//! the share of rays aimed at it that are misjudged, per sphere method. The lecture's
//! quadratic computes b² − c from numbers of the size of the distance squared and loses the
//! radius to cancellation; the scene build refuses it where that happens.

use super::{MATTE, Tally, bare, log_sweep, refused, sphere_truth};
use crate::checked::Checked;
use crate::render::HostScene;
use crate::stress::check::{MODEL_ERRORS, discriminant, model_error, to_f64, towards};
use crate::stress::{Case, Row};
use anyhow::Result;
use obscura::methods::MethodName;
use obscura::{Methods, ObjectDesc, Scalar, ShapeDesc, SphereMethod};
use obscura_scene::FormatJob;

pub const CASE: Case = Case {
    name: "distant",
    about: "a small or distant sphere, r/|o − c| from 1e-1 to 1e-4: hit/miss misclassification",
    x_label: "r / |o − c|",
    log_x: true,
    y_label: "misjudged rays (%)",
    run: |format| format.run::<Checked, _>(Job),
};

const DISTANCE: f64 = 10.0;
/// Rays per side of the grid aimed across the sphere and around it.
const GRID: usize = 41;

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let mut rows = Vec::new();
        for ratio in log_sweep(1e-1, 1e-4, 7) {
            let radius = ratio * DISTANCE;
            let center = [0.0, 0.0, DISTANCE];
            let objects = [ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: center.map(|c| c as f32),
                    radius: radius as f32,
                },
                material: MATTE,
            }];
            let desc = bare(&objects, (DISTANCE * 1.1) as f32);
            let truth = sphere_truth(&desc)?;
            let radius = f64::from(radius as f32);
            for &(method, name) in SphereMethod::ALL {
                let methods = Methods {
                    sphere: method,
                    ..Methods::LECTURE
                };
                let scene = match HostScene::<S>::build_with(&desc, methods) {
                    Ok(scene) => scene,
                    Err(error) => {
                        rows.push(refused(S::NAME, name, ratio, &error));
                        continue;
                    }
                };
                let band = MODEL_ERRORS * model_error::<S>(&desc, &methods, 0);
                let mut tally = Tally::default();
                for i in 0..GRID {
                    for j in 0..GRID {
                        let across = |k: usize| radius * (4.0 * k as f64 / (GRID - 1) as f64 - 2.0);
                        let Some(ray) = towards::<S>([across(i), across(j), DISTANCE]) else {
                            continue;
                        };
                        tally.record(
                            scene.first_hit(&ray).is_some(),
                            truth.first_hit(&to_f64(&ray)).is_some(),
                            || discriminant(&ray, center, radius).abs() <= band,
                        );
                    }
                }
                rows.push(tally.row(S::NAME, name, ratio));
            }
        }
        Ok(rows)
    }
}
