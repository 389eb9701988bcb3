//! The whole `whitted` scene scaled uniformly about the eye, from 10⁻³ to 10³: the same image
//! in every format that holds it, refused by those that cannot.

use super::{image_row, log_sweep, psnr};
use crate::checked::Checked;
use crate::stress::{Case, Row};
use anyhow::Result;
use obscura::methods::MethodName;
use obscura::{Methods, Scalar, SphereMethod, scenes};
use obscura_scene::{FormatJob, OwnedScene};

pub const CASE: Case = Case {
    name: "scale",
    about: "the whole whitted scene scaled uniformly from 1e-3 to 1e3",
    x_label: "scale",
    log_x: true,
    y_label: "PSNR against f64 (dB)",
    run: |format| format.run::<Checked, _>(Job),
};

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let whitted = OwnedScene::from_desc(&scenes::WHITTED);
        let mut rows = Vec::new();
        for scale in log_sweep(1e-3, 1e3, 7) {
            let scaled = whitted.scaled(scale as f32);
            let desc = scaled.desc();
            for &(sphere, name) in SphereMethod::ALL {
                let methods = Methods {
                    sphere,
                    ..Methods::LECTURE
                };
                rows.push(image_row::<S>(&desc, methods, name, scale, psnr));
            }
        }
        Ok(rows)
    }
}
