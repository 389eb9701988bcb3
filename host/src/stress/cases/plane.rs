//! Rays nearly parallel to a plane, meeting it far away: the eye one unit above the plane, rays
//! that meet it from a quarter of the world's radius to four times it, for worlds from 10 to
//! 10⁵. A hit beyond the world's edge is a miss; a ray may be misjudged only within a few
//! errors of that edge, and a world larger than the format holds is refused.

use super::{MATTE, Tally, bare, log_sweep, refused};
use crate::checked::Checked;
use crate::render::HostScene;
use crate::stress::check::{MODEL_ERRORS, to_f64};
use crate::stress::{Case, Row};
use anyhow::Result;
use obscura::{Methods, ObjectDesc, Ray, Scalar, ShapeDesc, Vec3};
use obscura_scene::FormatJob;

pub const CASE: Case = Case {
    name: "plane",
    about: "rays nearly parallel to a plane, hits near the world's edge, worlds up to the format's range",
    x_label: "the world's radius (far)",
    log_x: true,
    y_label: "misjudged rays (%)",
    run: |format| format.run::<Checked, _>(Job),
};

/// Rays per world, their hits log-spaced from far/4 to 4·far.
const RAYS: usize = 33;

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let objects = [ObjectDesc {
            shape: ShapeDesc::Plane {
                point: [0.0, -1.0, 0.0],
                normal: [0.0, 1.0, 0.0],
                checker: None,
            },
            material: MATTE,
        }];
        let mut rows = Vec::new();
        for far in log_sweep(1e1, 1e5, 5) {
            let desc = bare(&objects, far as f32);
            let scene = match HostScene::<S>::build_with(&desc, Methods::LECTURE) {
                Ok(scene) => scene,
                Err(error) => {
                    rows.push(refused(S::NAME, "", far, &error));
                    continue;
                }
            };
            let mut tally = Tally::default();
            for t in log_sweep(far / 4.0, far * 4.0, RAYS) {
                // From one above the plane, a hit t away: down by 1, forward by √(t² − 1).
                let dir = [0.0, -1.0 / t, (t * t - 1.0).sqrt() / t];
                let Some(dir) = Vec3::<S>::from_f64(dir) else {
                    continue;
                };
                let ray = Ray::new(Vec3::ZERO, dir);
                let exact = to_f64(&ray);
                // Where the ray as held meets the plane, and whether that is inside the world.
                let reach = 1.0 / -exact.dir.y;
                tally.record(
                    scene.first_hit(&ray).is_some(),
                    reach > 0.0 && reach <= far,
                    || {
                        // The hit's distance errs by the rounding of the direction, magnified
                        // by the grazing angle, and by the rounding of the world's radius.
                        let error = reach * S::UNIT_ERROR / -exact.dir.y + S::resolution(far);
                        (reach - far).abs() <= MODEL_ERRORS * error
                    },
                );
            }
            rows.push(tally.row(S::NAME, "", far));
        }
        Ok(rows)
    }
}
