//! Whether culling ([`crate::cull`]), the shadow cones ([`crate::occlusion`]) or the lone balls
//! (`Settings::lone_balls`) ever skip a test that would meet its object: each traced against
//! the tracer with every object tested. What the tests and the fuzzer hold them to; the tracer
//! itself never calls them.

crate::phase::declare_phase!(Some(crate::phase::Phase::Build));

use crate::camera::Camera;
use crate::cull::RowRanges;
use crate::pattern::SampleId;
use crate::ray::{Ray, Span};
use crate::scalar::Scalar;
use crate::scene::{Object, Scene};
use crate::shade::Task;
use crate::shape::PerRay;
use crate::shape::mesh::{Meshes, Search};
use crate::uses::{Everything, Uses};
use heapless::Vec;

/// The first pixel of row `y` one of whose rays meets an object its row's ranges leave out,
/// with that object's index; `None` when the ranges keep every hit. The rays tried are the
/// pixel's primary ray as the renderer makes it, and the rays through its four corners, the
/// farthest a pixel's samples reach. What the tests and the fuzzer hold culling to.
#[must_use]
pub fn first_skipped_hit<
    S: Scalar,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    M: Meshes<S>,
>(
    scene: &Scene<S, OBJECTS, LIGHTS, RAYS, Everything, M>,
    camera: &Camera<S>,
    y: u32,
) -> Option<(u32, usize)> {
    let row = camera.row(y)?;
    let bounds = scene.objects.iter().map(|object| &object.bound);
    let ranges = RowRanges::new(bounds, camera.image_plane(), y);
    let mut candidates = ranges.candidates();
    let half = S::ratio(1, 2);
    let corners = [[-half, -half], [half, -half], [-half, half], [half, half]];
    let settings = &scene.settings;
    let span = Span {
        min: settings.tolerance_base,
        max: settings.ray_length,
    };
    let search = Search {
        meshes: &scene.meshes,
        slack: settings.box_slack,
        skip: None,
        any: true,
    };
    let meets = |object: &Object<S>, ray: &Ray<S>| {
        let mut per_ray = PerRay::new();
        object
            .shape
            .intersect(
                ray,
                span,
                &settings.methods,
                Uses::EVERYTHING,
                &mut per_ray,
                &search,
            )
            .is_some()
    };
    for (x, centre) in (0..).zip(row.rays()) {
        let candidates = candidates.at(x);
        let rays = corners
            .iter()
            .filter_map(|&offset| row.ray_offset(x, offset))
            .chain([centre]);
        for ray in rays {
            for (i, object) in scene.objects.iter().enumerate() {
                let candidate = candidates & (1 << i.min(31)) != 0;
                if !candidate && meets(object, &ray) {
                    return Some((x, i));
                }
            }
        }
    }
    None
}

/// The first pixel whose centre's ray tree, traced with the shadow cones and the lone balls
/// (whose inside rays test their wall alone), differs from the one traced testing every
/// object, as (x, y, object): the object whose shadow or hit differs (the lowest in
/// [`crate::Sample::met`] that does), or the one the primary ray meets. `None` when none
/// differs. What the tests and the fuzzer hold the cones and the lone balls to.
#[must_use]
pub fn first_skipped_secondary<
    S: Scalar,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    M: Meshes<S>,
>(
    scene: &Scene<S, OBJECTS, LIGHTS, RAYS, Everything, M>,
    camera: &Camera<S>,
) -> Option<(u32, u32, usize)> {
    let mut stack: Vec<Task<S>, RAYS> = Vec::new();
    for y in 0..camera.height() {
        let row = camera.row(y)?;
        for (x, ray) in (0..).zip(row.rays()) {
            let id = SampleId { x, y, sample: 0 };
            let skipping = scene.trace(ray, id);
            let open = scene.tracer(id).testing_everything().trace_ray(
                ray,
                id,
                u32::MAX,
                stack.as_mut_view(),
            );
            if skipping != open {
                let differing = skipping.met ^ open.met;
                let object = if differing == 0 {
                    open.object.unwrap_or(0)
                } else {
                    differing.trailing_zeros() as usize
                };
                return Some((x, y, object));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::{FormatCheck, each_built_in_scene, for_every_format};

    /// Every built-in scene that the format holds, by the lecture's methods and each variant,
    /// at a small size: no ray of any pixel meets an object its row leaves out.
    struct CullingKeepsEveryHit;

    impl FormatCheck for CullingKeepsEveryHit {
        fn check<S: Scalar>(&self) {
            const SIDE: u32 = 40;
            each_built_in_scene::<S>(SIDE, |name, methods, scene, camera| {
                for y in 0..SIDE {
                    assert_eq!(
                        first_skipped_hit(scene, camera, y),
                        None,
                        "{name} in {} by {methods:?}, row {y}",
                        S::NAME
                    );
                }
            });
        }
    }

    #[test]
    fn culling_keeps_every_hit_of_the_built_in_scenes_in_every_format() {
        for_every_format(&CullingKeepsEveryHit);
    }

    /// Every built-in scene that the format holds, by the lecture's methods and each variant,
    /// at a small size: no pixel's ray tree changes when its shadow rays skip what the cones
    /// rule out and rays inside a lone ball test its wall alone.
    struct ConesAndLoneBallsKeepEveryTree;

    impl FormatCheck for ConesAndLoneBallsKeepEveryTree {
        fn check<S: Scalar>(&self) {
            each_built_in_scene::<S>(40, |name, methods, scene, camera| {
                assert_eq!(
                    first_skipped_secondary(scene, camera),
                    None,
                    "{name} in {} by {methods:?}",
                    S::NAME
                );
            });
        }
    }

    #[test]
    fn cones_and_lone_balls_keep_every_ray_tree_of_the_built_in_scenes_in_every_format() {
        for_every_format(&ConesAndLoneBallsKeepEveryTree);
    }
}
