//! Relations a picture keeps however the world moves, whatever the scene: the fuzzer moves each
//! scene and checks that the picture moves with it.
//!
//! - **translate**: the scene and its eye moved together, by an amount every coordinate takes
//!   exactly, draw the same picture bit for bit in every format, and are accepted or refused
//!   alike (the core builds a scene relative to its eye, so nothing else may change);
//! - **scale**: the world, its sizes and `far` scaled by two draw the same picture in f64 (a
//!   power of two scales every product exactly), and f32 is predicted the same error for both
//!   (a float's rounding is relative: the model is scale-free for it, where a fixed format's
//!   resolution is absolute and its prediction must change);
//! - **mirror**: the scene mirrored in x (the camera's up with it) draws the picture mirrored
//!   left to right, in f64, where the scene's patterns are mirror-symmetric (no checkerboard, one
//!   ray per pixel, point lights, a pinhole);
//! - **nudge**: where an eye nudged by one ulp of f32 moves what it sees by far less than a
//!   pixel and every feature is wider than one ([`nudge_is_small`]), in f64 it changes only
//!   pixels an edge passes through: a changed pixel whose primary ray meets the
//!   same object and whose neighbours all showed that object and its colour is unexplained
//!   (the checkerboard that followed the eye swapped every square).

use crate::analysis::pixel_angle;
use image::{Rgb, RgbImage};
use obscura::scene::range;
use obscura::{ShapeDesc, Vec3};
use obscura_scene::OwnedScene;
use std::cell::{Cell, RefCell};

/// Levels of 255 by which a pixel must change, in some channel, to count as changed (and by
/// which a neighbour must differ to count as another colour): a sixteenth of full scale.
pub const CHANGED_LEVELS: u8 = 16;

/// The share of a frame's pixels whose change an ulp of the eye may leave unexplained: a
/// sub-pixel feature (a sliver, a far sphere, the shadow of one) may flip a pixel whose
/// neighbours do not show it; a board or a shading that follows the eye changes whole areas.
pub const UNEXPLAINED_SHARE: f64 = 0.05;

/// Every coordinate of the scene's positions.
fn coordinates(scene: &OwnedScene) -> Vec<[f32; 3]> {
    let all = RefCell::new(Vec::new());
    scene.transformed(
        |p| {
            all.borrow_mut().push(p);
            p
        },
        |d| d,
        |l| l,
    );
    all.into_inner()
}

/// The largest power of two, per axis and at most `limit`, by which every position of the scene
/// moves exactly in f32 (a coordinate plus it is the sum in f64); `None` where none does.
pub fn exact_translation(scene: &OwnedScene, limit: f32) -> Option<[f32; 3]> {
    let coordinates = coordinates(scene);
    let moves_exactly = |axis: usize, t: f32| {
        coordinates.iter().all(|p| {
            let moved = p[axis] + t;
            moved.is_finite() && f64::from(moved) == f64::from(p[axis]) + f64::from(t)
        })
    };
    let mut translation = [0.0; 3];
    for (axis, t) in translation.iter_mut().enumerate() {
        *t = core::iter::successors(Some(limit), |&t| Some(t / 2.0))
            .take_while(|&t| t > 0.0)
            .find(|&t| moves_exactly(axis, t))?;
    }
    Some(translation)
}

/// The scene and its eye moved by `t`, which every position takes exactly
/// ([`exact_translation`]).
pub fn translated(scene: &OwnedScene, t: [f32; 3]) -> OwnedScene {
    scene.transformed(|p| std::array::from_fn(|i| p[i] + t[i]), |d| d, |l| l)
}

/// The scene scaled by two about the world's origin (positions and lengths); `None` where a
/// value would leave f32's normal range, where it would not scale exactly.
pub fn doubled(scene: &OwnedScene) -> Option<OwnedScene> {
    let exact = Cell::new(true);
    let twice = |v: f32| {
        let doubled = 2.0 * v;
        if v != 0.0 && !(v.is_normal() && doubled.is_normal()) {
            exact.set(false);
        }
        doubled
    };
    let big = scene.transformed(|p| p.map(twice), |d| d, twice);
    exact.get().then_some(big)
}

/// The scene mirrored in x (positions, normals and ups), where its picture is the mirror image
/// of the original's: `None` for a checkerboard (a square's colour is the parity of its place,
/// which a mirror about a square's edge swaps), several rays per pixel or per area light, or a
/// lens (their sample patterns are not mirror-symmetric).
pub fn mirrored(scene: &OwnedScene) -> Option<OwnedScene> {
    let checkered = scene.objects.iter().any(|o| {
        matches!(
            o.shape,
            ShapeDesc::Plane {
                checker: Some(_),
                ..
            }
        )
    });
    if checkered || scene.samples > 1 || area_lights(scene) || scene.camera.aperture > 0.0 {
        return None;
    }
    let flip = |[x, y, z]: [f32; 3]| [-x, y, z];
    Some(scene.transformed(flip, flip, |l| l))
}

/// Whether the scene's area lights take several shadow rays, patterned by the point they leave
/// from (neither mirror-symmetric nor still under a nudge).
fn area_lights(scene: &OwnedScene) -> bool {
    scene.shadow_samples > 1 && scene.lights.iter().any(|l| l.radius > 0.0)
}

/// The image mirrored left to right.
pub fn mirror_image(image: &RgbImage) -> RgbImage {
    image::imageops::flip_horizontal(image)
}

/// The most pixels an ulp of the eye may move what it sees by, for the nudge relation to apply.
pub const NUDGE_PIXELS: f64 = 0.01;

/// Whether nudging the eye by an ulp of f32 (on every axis) moves what it sees by less than
/// [`NUDGE_PIXELS`] in an image of `width` × `height` pixels: the nudge against a pixel's width at the
/// nearest surface and at the nearest plane of a surface (an eye crossing a triangle's plane
/// sees its other side: another picture, though no edge is near). With a narrow field of view
/// or a far eye, an ulp is a pixel or more, and the relation says nothing; nor where area
/// lights take several shadow rays, a sphere encloses the eye, or a checkerboard's squares are
/// narrower than a pixel at the world's edge.
pub fn nudge_is_small(scene: &OwnedScene, width: u32, height: u32) -> bool {
    let eye = Vec3::from_f32(scene.camera.eye);
    // A sphere around the eye mirrors its rays back through it (a caustic at the eye).
    let enclosed = scene.objects.iter().any(|o| match o.shape {
        ShapeDesc::Sphere { center, radius } => {
            (Vec3::from_f32(center) - eye).length() < f64::from(radius)
        }
        ShapeDesc::Plane { .. } | ShapeDesc::Triangle { .. } | ShapeDesc::Mesh { .. } => false,
    });
    if area_lights(scene) || enclosed {
        return false;
    }
    let nudge = (Vec3::from_f32(scene.camera.eye.map(f32::next_up)) - eye).length();
    let pixel = pixel_angle(&scene.desc(), width, height);
    let nearest = scene
        .desc()
        .primitives()
        .map(|(_, object)| {
            let plane = match object.shape {
                ShapeDesc::Triangle { vertices } => {
                    let [a, b, c] = vertices.map(Vec3::from_f32);
                    (b - a)
                        .cross(c - a)
                        .direction()
                        .map_or(0.0, |n| n.dot(eye - a).abs())
                }
                ShapeDesc::Sphere { .. } | ShapeDesc::Plane { .. } | ShapeDesc::Mesh { .. } => {
                    f64::INFINITY
                }
            };
            range::clearance(&object, eye).min(plane)
        })
        .fold(f64::INFINITY, f64::min);
    // Squares narrower than a pixel at the world's edge alias there: every pixel has edges
    // through it, which any nudge moves.
    let fine_squares = scene.objects.iter().any(|o| match o.shape {
        ShapeDesc::Plane {
            checker: Some(checker),
            ..
        } => f64::from(checker.size) < f64::from(scene.far) * pixel,
        ShapeDesc::Plane { checker: None, .. }
        | ShapeDesc::Sphere { .. }
        | ShapeDesc::Triangle { .. }
        | ShapeDesc::Mesh { .. } => false,
    });
    !fine_squares && nudge < NUDGE_PIXELS * pixel * nearest
}

/// How many pixels of `moved` differ from `reference` by at least [`CHANGED_LEVELS`].
pub fn changed_pixels(reference: &RgbImage, moved: &RgbImage) -> usize {
    reference
        .pixels()
        .zip(moved.pixels())
        .filter(|&(&a, &b)| differs(a, b))
        .count()
}

/// Whether two colours differ by at least [`CHANGED_LEVELS`] in some channel.
fn differs(a: Rgb<u8>, b: Rgb<u8>) -> bool {
    a.0.iter()
        .zip(b.0)
        .any(|(&x, y)| x.abs_diff(y) >= CHANGED_LEVELS)
}

/// The pixels of `nudged` that changed from `reference` without an edge to explain it: each
/// meets the same object as before, and so did its eight neighbours in the reference, in a
/// colour of its own.
pub fn unexplained_changes(
    reference: &RgbImage,
    reference_objects: &[Option<usize>],
    nudged: &RgbImage,
    nudged_objects: &[Option<usize>],
) -> usize {
    let (width, height) = reference.dimensions();
    let index = |x: u32, y: u32| (y * width + x) as usize;
    let edge_near = |x: u32, y: u32| {
        let (colour, object) = (*reference.get_pixel(x, y), reference_objects[index(x, y)]);
        (-1_i64..=1)
            .flat_map(|dy| (-1_i64..=1).map(move |dx| (dx, dy)))
            .filter_map(|(dx, dy)| {
                let (nx, ny) = (i64::from(x) + dx, i64::from(y) + dy);
                let inside =
                    (0..i64::from(width)).contains(&nx) && (0..i64::from(height)).contains(&ny);
                inside.then_some((nx as u32, ny as u32))
            })
            .any(|(nx, ny)| {
                reference_objects[index(nx, ny)] != object
                    || differs(*reference.get_pixel(nx, ny), colour)
            })
    };
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            differs(*reference.get_pixel(x, y), *nudged.get_pixel(x, y))
                && reference_objects[index(x, y)] == nudged_objects[index(x, y)]
                && !edge_near(x, y)
        })
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use obscura::scenes;

    fn whitted() -> OwnedScene {
        OwnedScene::from_desc(&scenes::WHITTED)
    }

    #[test]
    fn a_translation_moves_every_position_exactly_or_is_not_offered() {
        let scene = whitted();
        let t = exact_translation(&scene, 1024.0).expect("whitted's coordinates are short");
        let moved = translated(&scene, t);
        assert!(t.iter().all(|&c| c >= 1.0 / 64.0), "{t:?}");
        for (moved, original) in coordinates(&moved).iter().zip(coordinates(&scene)) {
            for axis in 0..3 {
                assert_eq!(moved[axis] - t[axis], original[axis]);
            }
        }
        // 0.1 + 2⁻⁵ leaves 0.1's binade, whose last bit (0.1 is odd in f32) the next one cannot
        // hold: 2⁻⁶ is the largest power that moves it exactly.
        let mut fine = scene.clone();
        fine.camera.eye = [0.1, 0.1, 0.1];
        let t = exact_translation(&fine, 1024.0).unwrap();
        assert_eq!(t, [2f32.powi(-6); 3]);
    }

    #[test]
    fn doubling_scales_sizes_and_refuses_what_would_leave_the_normal_range() {
        let scene = whitted();
        let big = doubled(&scene).unwrap();
        assert_eq!(big.far, 2.0 * scene.far);
        let mut huge = scene;
        huge.far = f32::MAX;
        assert!(doubled(&huge).is_none());
    }

    #[test]
    fn a_mirror_is_offered_only_where_the_patterns_are_symmetric() {
        assert!(mirrored(&whitted()).is_none(), "whitted has a checkerboard");
        let mut plain = whitted();
        plain
            .objects
            .retain(|o| matches!(o.shape, ShapeDesc::Sphere { .. }));
        let mirror = mirrored(&plain).unwrap();
        assert_eq!(mirror.camera.eye[0], -plain.camera.eye[0]);
    }

    #[test]
    fn a_changed_pixel_inside_a_region_is_unexplained_and_one_on_an_edge_is_not() {
        let mut reference = RgbImage::from_pixel(5, 5, Rgb([10, 10, 10]));
        let objects = vec![Some(0); 25];
        let mut nudged = reference.clone();
        nudged.put_pixel(2, 2, Rgb([200, 10, 10]));
        assert_eq!(
            unexplained_changes(&reference, &objects, &nudged, &objects),
            1
        );
        reference.put_pixel(3, 2, Rgb([200, 10, 10]));
        nudged.put_pixel(3, 2, Rgb([200, 10, 10]));
        assert_eq!(
            unexplained_changes(&reference, &objects, &nudged, &objects),
            0
        );
    }
}
