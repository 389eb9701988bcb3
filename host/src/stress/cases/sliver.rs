//! Degenerate and sliver triangles: a triangle one unit wide and h high, h from 10⁻¹ down to
//! 10⁻⁸ (where, at the f32 precision of a description, its corners are collinear). A ray may be
//! misjudged only within a few of the error model's errors of an edge; a sliver thinner than
//! the format resolves is refused.

use super::{MATTE, Tally, bare, log_sweep, refused};
use crate::checked::Checked;
use crate::render::HostScene;
use crate::stress::check::{MODEL_ERRORS, model_error, to_f64, towards};
use crate::stress::{Case, Row};
use anyhow::{Context, Result};
use obscura::methods::MethodName;
use obscura::{Methods, ObjectDesc, Scalar, ShapeDesc, TriangleMethod};
use obscura_scene::FormatJob;

pub const CASE: Case = Case {
    name: "sliver",
    about: "degenerate and sliver triangles, 1 wide and 1e-1 to 1e-8 high",
    x_label: "the triangle's height over its width",
    log_x: true,
    y_label: "misjudged rays (%)",
    run: |format| format.run::<Checked, _>(Job),
};

const DEPTH: f64 = 5.0;
/// Rays per side of the grid over the triangle.
const GRID: usize = 33;

/// The distance from (x, y) to the segment from a to b.
fn to_segment(x: f64, y: f64, a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let along = (((x - a[0]) * dx + (y - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    ((x - a[0] - along * dx).powi(2) + (y - a[1] - along * dy).powi(2)).sqrt()
}

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let mut rows = Vec::new();
        for height in log_sweep(1e-1, 1e-8, 8) {
            let h = height as f32;
            let z = DEPTH as f32;
            let corners = [[-0.5, 0.0], [0.5, 0.0], [0.0, f64::from(h)]];
            let objects = [ObjectDesc {
                shape: ShapeDesc::Triangle {
                    vertices: [[-0.5, 0.0, z], [0.5, 0.0, z], [0.0, h, z]],
                },
                material: MATTE,
            }];
            let desc = bare(&objects, 8.0);
            for &(method, name) in TriangleMethod::ALL {
                let methods = Methods {
                    triangle: method,
                    ..Methods::LECTURE
                };
                let scene = match HostScene::<S>::build_with(&desc, methods) {
                    Ok(scene) => scene,
                    Err(error) => {
                        rows.push(refused(S::NAME, name, height, &error));
                        continue;
                    }
                };
                let truth = HostScene::<f64>::build_with(&desc, methods)
                    .context("the f64 reference builds")?;
                // The model's error in twice the area, over the longest edge (1): a distance
                // from the edges.
                let band = MODEL_ERRORS * model_error::<S>(&desc, &methods, 0);
                let mut tally = Tally::default();
                for i in 0..GRID {
                    for j in 0..GRID {
                        let x = -0.6 + 1.2 * i as f64 / (GRID - 1) as f64;
                        let y = f64::from(h) * (-0.5 + 2.0 * j as f64 / (GRID - 1) as f64);
                        let Some(ray) = towards::<S>([x, y, DEPTH]) else {
                            continue;
                        };
                        let exact = to_f64(&ray);
                        tally.record(
                            scene.first_hit(&ray).is_some(),
                            truth.first_hit(&exact).is_some(),
                            || {
                                // Where the ray as held crosses the triangle's plane, and how far
                                // that is from the nearest edge.
                                let reach = DEPTH / exact.dir.z;
                                let (px, py) = (exact.dir.x * reach, exact.dir.y * reach);
                                let edge = (0..3)
                                    .map(|k| to_segment(px, py, corners[k], corners[(k + 1) % 3]))
                                    .fold(f64::INFINITY, f64::min);
                                edge <= band
                            },
                        );
                    }
                }
                rows.push(tally.row(S::NAME, name, height));
            }
        }
        Ok(rows)
    }
}
