//! The row pass: the pixels of a row whose primary rays can meet one matte plane alone (the
//! culling says which, [`crate::cull`]) are shaded where their rays meet it, found without
//! tracing them.
//!
//! With the eye at the origin, pixel x's ray runs along the image-plane point s(x), not yet a
//! unit vector, and meets the plane n·p = c at t·s(x) with t = c / (n·s(x)). Where the normal
//! lies along an axis and the camera's rows do not move along that axis (a level camera over a
//! floor: the camera's `across` is exactly 0 on it), n·s(x) is the same all along the row, and
//! so is t: one division a row, and each pixel's hit is t·s(x), its coordinate along the axis
//! the plane's own exactly. No unit vector for the primary ray, no quotient a pixel. The plane
//! must be matte (no highlight, no mirror, no transmission: each needs the ray's unit
//! direction). A pixel whose hit lies beyond the world's rim sees the background, as its
//! traced ray would; a row whose t is behind the eye or too far traces as every other row.
//!
//! The hit is found differently from the general test's, so its last bits may differ from that
//! test's: both round the same exact point. Its range is the general test's (see
//! [`crate::scene::range`]): t is at most half a ray's length T and each coordinate of s at
//! most 3 (a row whose ends reach further traces in general), so each coordinate of t·s is
//! within 3T/2, a point along a ray.

crate::phase::declare_phase!(Some(crate::phase::Phase::Camera));

use crate::camera::Row;
use crate::cull::SHARED_BIT;
use crate::color::Rgb;
use crate::methods::RootMethod;
use crate::ray::Span;
use crate::scalar::{RayKind, Scalar, Work};
use crate::scene::Object;
use crate::shape::{Plane, Shape};
use crate::vec3::Vec3;

/// The largest coordinate of an image-plane point a row pass takes (see [`crate::row_pass`]):
/// with t at most T/2, t·s stays within a point along a ray's bound P = O + T = 3T/2
/// ([`crate::scene::range`]) while each coordinate of s is within P / (T/2) = 3.
const REACH: i32 = 3;

/// One row's primary rays as they meet a matte plane along an axis (see [`crate::row_pass`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PlaneRow<'a, S: Scalar> {
    index: usize,
    object: &'a Object<S>,
    plane: &'a Plane<S>,
    axis: usize,
    /// The coordinate of every point of the plane along `axis`.
    level: S,
    /// The parameter along s at which every ray of the row meets the plane.
    t: S,
    /// The plane's normal on the side the row's rays arrive from.
    facing: Vec3<S>,
    /// `facing` in the narrow format, for Lambert's cosine.
    shading: Vec3<S::Narrow>,
}

impl<'a, S: Scalar> PlaneRow<'a, S> {
    /// The row pass of `row` for the first matte plane along an axis of `objects` (one of the
    /// first [`SHARED_BIT`], which have a culling bit of their own), whose primary rays search `span` and
    /// divide by `roots`, or `None` where no plane qualifies or the row's rays meet it behind
    /// the eye, too near or too far.
    pub(crate) fn new(
        objects: &'a [Object<S>],
        row: &Row<S>,
        span: Span<S>,
        roots: RootMethod,
    ) -> Option<Self> {
        let (index, object, plane, (axis, level)) = objects
            .iter()
            .take(SHARED_BIT)
            .enumerate()
            .find_map(|(index, object)| match &object.shape {
                Shape::Plane(plane) if object.material.is_matte() => {
                    Some((index, object, plane, plane.axis()?))
                }
                _ => None,
            })?;
        let [left, right] = row.ends();
        if left.max_abs().max(right.max_abs()) > S::from_int(REACH) {
            return None;
        }
        // s's coordinate on the axis, the same all along the row: n·s but for its sign.
        let on_axis = row.level(axis)?;
        // t = level / on_axis lies in [min, T/2] iff level lies between min·on_axis and
        // (T/2)·on_axis: tested first, so that the quotient never leaves the span.
        let (min, max) = (span.min, span.max * S::ratio(1, 2));
        let (low, high) = if on_axis > S::ZERO {
            (min * on_axis, max * on_axis)
        } else if on_axis < S::ZERO {
            (max * on_axis, min * on_axis)
        } else {
            return None;
        };
        if level < low || level > high {
            return None;
        }
        let t = roots.div(level, on_axis);
        // The rays arrive from the side n·s < 0 is on: along the axis, opposite to s.
        let normal = plane.normal();
        let facing = if normal.get(axis)? * on_axis <= S::ZERO {
            normal
        } else {
            -normal
        };
        Some(Self {
            index,
            object,
            plane,
            axis,
            level,
            t,
            facing,
            shading: facing.narrow(),
        })
    }

    /// The culling's candidates of a pixel whose primary ray can meet the plane alone.
    pub(crate) const fn candidates(&self) -> u32 {
        1 << self.index
    }

    /// The plane's object and its index.
    pub(crate) const fn object(&self) -> (usize, &'a Object<S>) {
        (self.index, self.object)
    }

    /// The plane's normal on the side the row's rays arrive from, in the format and in the
    /// narrow format.
    pub(crate) const fn facing(&self) -> (Vec3<S>, Vec3<S::Narrow>) {
        (self.facing, self.shading)
    }

    /// The plane's colour at `point`, one of its points: its material's, or its checker's.
    pub(crate) fn surface_colour(&self, point: Vec3<S>) -> Rgb<S::Narrow> {
        let colour = self.object.material.colour;
        self.plane.pattern_colour(point).unwrap_or(colour)
    }

    /// The checker's square at `point`, one of the plane's points ([`Plane::square`]).
    pub(crate) fn square(&self, point: Vec3<S>) -> Option<[i32; 2]> {
        self.plane.square(point)
    }

    /// Where the primary ray through the image-plane point `s` of the row meets the plane, or
    /// `None` beyond the world's rim: a primary ray's search, which tests the plane alone.
    pub(crate) fn hit(&self, s: Vec3<S>) -> Option<Vec3<S>> {
        S::note(Work::RowPass);
        S::note(Work::Search(RayKind::Primary));
        S::note(Work::Test);
        let hit = self.plane.hit_along(s, self.t, (self.axis, self.level));
        if hit.is_some() {
            S::note(Work::Met);
        }
        hit
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cull::RowRanges;
    use crate::desc::{ObjectDesc, SceneDesc};
    use crate::methods::RootMethod;
    use crate::pattern::SampleId;
    use crate::scalar::FAST_ROOT_ERROR;
    use crate::scene::Scene;
    use crate::scenes::{SHAPES, WHITTED};
    use crate::test_util::{FormatCheck, each_built_in_scene, for_every_format};

    const SIDE: u32 = 40;

    /// The row pass's hits of `scene`'s rows through `camera`, each with the image-plane point
    /// it is of and the row pass itself.
    fn hits<S: Scalar>(
        scene: &Scene<S, 8, 4, 8>,
        camera: &crate::camera::Camera<S>,
        mut each: impl FnMut(&PlaneRow<'_, S>, Vec3<S>, Option<Vec3<S>>),
    ) -> usize {
        let tracer = scene.tracer(SampleId::default());
        let mut found = 0;
        for y in 0..camera.height() {
            let row = camera.row(y).expect("a row");
            let Some(plane) = tracer.plane_row(&row) else {
                continue;
            };
            let bounds = tracer.objects().iter().map(|object| &object.bound);
            let ranges = RowRanges::new(bounds, camera.image_plane(), y);
            let mut candidates = ranges.candidates();
            for (x, s) in (0..).zip(row.points()) {
                if candidates.at(x) == plane.candidates() {
                    let hit = plane.hit(s);
                    found += usize::from(hit.is_some());
                    each(&plane, s, hit);
                }
            }
        }
        found
    }

    /// Every built-in scene that the format holds, by every method: each hit of the row pass
    /// lies on the plane, within the rounding of one quotient and two products of the exact
    /// point where the pixel's ray meets it, and the rays arrive from the side it faces.
    struct HitsAreThePlanes;

    impl FormatCheck for HitsAreThePlanes {
        fn check<S: Scalar>(&self) {
            each_built_in_scene::<S>(SIDE, |name, methods, scene, camera| {
                hits(scene, camera, |plane, s, hit| {
                    let s = Vec3::from_f64(s.to_f64()).expect("an f64 point");
                    let facing = Vec3::<f64>::from_f64(plane.facing.to_f64()).expect("f64");
                    assert!(facing.dot(s) < 0.0, "{name} in {}: facing", S::NAME);
                    let Some(hit) = hit else { return };
                    let level = plane.level.to_f64();
                    let t = level / s.get(plane.axis).expect("an axis");
                    // Along the axis the point is the plane's level exactly.
                    let exact = (s * t).with(plane.axis, level);
                    let divided = if methods.roots == RootMethod::Approx {
                        t * FAST_ROOT_ERROR
                    } else {
                        0.0
                    };
                    let step = S::resolution(t) + divided;
                    let hit = Vec3::<f64>::from_f64(hit.to_f64()).expect("f64");
                    for axis in 0..3 {
                        let (got, want) = (hit.get(axis), exact.get(axis));
                        let (got, want) = (got.expect("axis"), want.expect("axis"));
                        let reach = s.get(axis).expect("axis").abs();
                        let tolerance = if axis == plane.axis {
                            0.0
                        } else {
                            step * reach + S::resolution(want.abs())
                        };
                        assert!(
                            (got - want).abs() <= tolerance * (1.0 + 1e-9),
                            "{name} in {} by {methods:?}: {got} for {want} on axis {axis}",
                            S::NAME
                        );
                    }
                });
            });
        }
    }

    #[test]
    fn the_row_pass_finds_the_planes_hits_in_every_format() {
        for_every_format(&HitsAreThePlanes);
    }

    /// Every built-in scene that the format holds, by every method: a pixel the row pass
    /// shades shows what its traced ray shows, to within a level of 8 bits, but for a share
    /// where the two points' last bits fall on two sides of an edge (a checker square's, a
    /// shadow's, the world's rim).
    struct ShadesAsTraced;

    impl FormatCheck for ShadesAsTraced {
        fn check<S: Scalar>(&self) {
            let (mut shaded, mut differing) = (0, 0);
            each_built_in_scene::<S>(SIDE, |_, _, scene, camera| {
                let mut tracer = scene.tracer(SampleId::default());
                let mut stack: heapless::Vec<crate::shade::Task<S>, 8> = heapless::Vec::new();
                for y in 0..SIDE {
                    let row = camera.row(y).expect("a row");
                    let Some(plane) = tracer.plane_row(&row) else {
                        continue;
                    };
                    for (x, s) in (0..).zip(row.points()) {
                        let Some(hit) = plane.hit(s) else { continue };
                        let id = SampleId { x, y, sample: 0 };
                        let passed = tracer.shade_plane_row(&plane, hit, id).to_f64();
                        let ray = row.through(s);
                        let traced = tracer
                            .trace_ray(ray, id, plane.candidates(), stack.as_mut_view())
                            .colour
                            .to_f64();
                        shaded += 1;
                        let level = |c: f64| (c.clamp(0.0, 1.0) * 255.0).round();
                        let apart = passed
                            .iter()
                            .zip(traced)
                            .any(|(a, b)| (level(*a) - level(b)).abs() > 1.0);
                        differing += usize::from(apart);
                    }
                }
            });
            assert!(
                differing * 1000 <= shaded,
                "{differing} of {shaded} pixels in {}",
                S::NAME
            );
        }
    }

    #[test]
    fn the_row_pass_shades_as_the_traced_rays_in_every_format() {
        for_every_format(&ShadesAsTraced);
    }

    /// The scene with its camera turned about its line of sight by the world's up leaning
    /// right, or its floor's material changed.
    fn whitted_with(up: [f32; 3], floor: Option<crate::desc::MaterialDesc>) -> usize {
        let mut objects: [ObjectDesc; 3] = WHITTED.objects.try_into().expect("three objects");
        if let Some(material) = floor {
            objects[0].material = material;
        }
        let desc = SceneDesc {
            camera: crate::desc::CameraDesc { up, ..WHITTED.camera },
            objects: &objects,
            ..WHITTED
        };
        let scene = Scene::<crate::scalar::I16F16, 8, 4, 8>::build(&desc).expect("a scene");
        let camera = scene.camera(SIDE, SIDE).expect("a camera");
        hits(&scene, &camera, |_, _, _| {})
    }

    #[test]
    fn a_level_camera_over_a_matte_floor_alone_takes_the_row_pass() {
        let level = whitted_with([0.0, 1.0, 0.0], None);
        assert!(level > 200, "{level} pixels of whitted by the row pass");
        assert_eq!(whitted_with([0.1, 1.0, 0.0], None), 0, "a rolled camera");
        let mirror = crate::desc::MaterialDesc {
            reflection: 0.2,
            ..WHITTED.objects[0].material
        };
        assert_eq!(whitted_with([0.0, 1.0, 0.0], Some(mirror)), 0, "a mirror");
        let shiny = crate::desc::MaterialDesc {
            specular: 0.2,
            ..WHITTED.objects[0].material
        };
        assert_eq!(whitted_with([0.0, 1.0, 0.0], Some(shiny)), 0, "a highlight");
        let scene = Scene::<f32, 8, 4, 8>::build(&SHAPES).expect("shapes");
        let camera = scene.camera(SIDE, SIDE).expect("a camera");
        assert!(hits(&scene, &camera, |_, _, _| {}) > 0, "shapes' floor");
    }
}
