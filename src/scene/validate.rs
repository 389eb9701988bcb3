//! The checks a scene description must pass in every number format: finite values, sensible
//! intervals, non-degenerate geometry, everything inside the world.

crate::phase::declare_phase!(Some(crate::phase::Phase::Build));

use super::error::{Item, SceneError};
use super::range::{self, distance};
use crate::camera::Frame;
use crate::desc::{
    BackgroundDesc, CameraDesc, LightDesc, MaterialDesc, MeshesDesc, Pixels, SceneDesc,
    ShapeDesc, triangle_has_area,
};
use crate::pattern::MAX_SAMPLES;
use crate::shape::mesh::MAX_DEPTH;
use crate::vec3::Vec3;

/// What `samples` and `shadow_samples` must be, in words: from 1 to [`MAX_SAMPLES`].
const SAMPLES_EXPECTED: &str = "from 1 to 256";

/// Validates `desc` and returns its camera frame.
pub(super) fn validate(desc: &SceneDesc<'_>) -> Result<Frame, SceneError> {
    finite(Item::Scene, "far", &[desc.far])?;
    at_least(Item::Scene, "far", desc.far, f32::MIN_POSITIVE, "> 0")?;
    colour(Item::Scene, "ambient", desc.ambient)?;
    for (field, count) in [
        ("samples", desc.samples),
        ("shadow_samples", desc.shadow_samples),
    ] {
        if !(1..=MAX_SAMPLES).contains(&count) {
            return Err(out_of_bounds(
                Item::Scene,
                field,
                f32::from(count),
                SAMPLES_EXPECTED,
            ));
        }
    }
    match desc.background {
        BackgroundDesc::Solid(c) => colour(Item::Scene, "background.solid", c)?,
        BackgroundDesc::Gradient {
            horizon,
            zenith,
            up,
        } => {
            colour(Item::Scene, "background.gradient.horizon", horizon)?;
            colour(Item::Scene, "background.gradient.zenith", zenith)?;
            finite(Item::Scene, "background.gradient.up", &up)?;
            direction(Item::Scene, "background.gradient.up", Vec3::from_f32(up))?;
        }
    }
    let frame = camera(&desc.camera)?;
    if desc.adaptive_samples {
        adaptive(desc)?;
    }
    adaptive_pixels(desc)?;
    inside_world(Item::Camera, frame.aperture, desc.far)?;
    let eye = Vec3::from_f32(desc.camera.eye);
    for (i, object) in desc.objects.iter().enumerate() {
        material(Item::Object(i), &object.material)?;
    }
    mesh_corners(desc)?;
    for (i, object) in desc.primitives() {
        let item = Item::Object(i);
        let reach = shape(item, &object.shape, desc.camera.eye)?;
        inside_world(item, reach, desc.far)?;
        // Every lens point must be on the eye's side of every surface (the eye itself must
        // be clear of them by the format's error: the range proof's).
        let clearance = range::clearance(&object, eye);
        if frame.aperture > 0.0 && frame.aperture >= clearance {
            return Err(SceneError::LensTouches {
                object: i,
                clearance,
                aperture: desc.camera.aperture,
            });
        }
    }
    // After its triangles, so that a mesh beyond the world is said to be (its boxes are too).
    for (i, object) in desc.objects.iter().enumerate() {
        if let ShapeDesc::Mesh { root } = object.shape {
            hierarchy(Item::Object(i), &desc.meshes, root, desc)?;
        }
    }
    for (i, light) in desc.lights.iter().enumerate() {
        let item = Item::Light(i);
        let LightDesc {
            position,
            colour: c,
            radius,
        } = *light;
        finite(item, "position", &position)?;
        colour(item, "colour", c)?;
        finite(item, "radius", &[radius])?;
        at_least(item, "radius", radius, 0.0, "≥ 0")?;
        let reach = distance(position, desc.camera.eye) + f64::from(radius);
        inside_world(item, reach, desc.far)?;
    }
    Ok(frame)
}

/// Adaptive samples split a pixel into quarters, so they come in powers of 4; and they spread
/// over the pixel alone, so the camera is a pinhole.
fn adaptive(desc: &SceneDesc<'_>) -> Result<(), SceneError> {
    if !matches!(desc.samples, 4 | 16 | 64 | 256) {
        return Err(out_of_bounds(
            Item::Scene,
            "samples",
            f32::from(desc.samples),
            "4, 16, 64 or 256 with adaptive_samples (a pixel splits into 4, 16, 64 or 256 \
             cells at most)",
        ));
    }
    if desc.camera.aperture != 0.0 {
        return Err(out_of_bounds(
            Item::Camera,
            "aperture",
            desc.camera.aperture,
            "0 with adaptive_samples (they spread over the pixel, not a lens: use samples \
             alone for depth of field)",
        ));
    }
    Ok(())
}

impl SceneDesc<'_> {
    /// Whether the scene can take `pixels`: adaptive pixels take one ray a pixel through a
    /// pinhole, in blocks of 2, 4 or 8 (what building it with them checks).
    ///
    /// # Errors
    /// What it must change to take them.
    pub fn takes_pixels(&self, pixels: Pixels) -> Result<(), SceneError> {
        adaptive_pixels(&SceneDesc { pixels, ..*self })
    }
}

/// Adaptive pixels come in blocks of 2, 4 or 8, and fill a pixel from the rays of others, so
/// each takes one ray from the eye. Exact pixels take any scene.
fn adaptive_pixels(desc: &SceneDesc<'_>) -> Result<(), SceneError> {
    if desc.pixels == Pixels::Exact {
        return Ok(());
    }
    let block = desc.pixels.block();
    if !Pixels::BLOCKS.contains(&block) {
        return Err(out_of_bounds(
            Item::Scene,
            "pixels",
            f32::from(block),
            "adaptive:2, adaptive:4 or adaptive:8 (blocks of 2, 4 or 8 pixels a side)",
        ));
    }
    if desc.samples != 1 || desc.adaptive_samples {
        return Err(out_of_bounds(
            Item::Scene,
            "samples",
            f32::from(desc.samples),
            "1 with adaptive pixels (a block fills its pixels from its corners' one ray each: \
             set samples = 1 and adaptive_samples = false, or pixels = \"exact\")",
        ));
    }
    if desc.camera.aperture != 0.0 {
        return Err(out_of_bounds(
            Item::Camera,
            "aperture",
            desc.camera.aperture,
            "0 with adaptive pixels (a pixel through a lens takes its own lens point: use \
             pixels = \"exact\" for depth of field)",
        ));
    }
    Ok(())
}

fn camera(camera: &CameraDesc) -> Result<Frame, SceneError> {
    let item = Item::Camera;
    finite(item, "eye", &camera.eye)?;
    finite(item, "look_at", &camera.look_at)?;
    finite(item, "up", &camera.up)?;
    finite(item, "vfov_degrees", &[camera.vfov_degrees])?;
    let fov = camera.vfov_degrees;
    if !(fov > 0.0 && fov < 180.0) {
        return Err(out_of_bounds(
            item,
            "vfov_degrees",
            fov,
            "in (0, 180) degrees",
        ));
    }
    let view = Vec3::from_f32(camera.look_at) - Vec3::from_f32(camera.eye);
    direction(item, "look_at − eye", view)?;
    direction(item, "up", Vec3::from_f32(camera.up))?;
    finite(item, "aperture", &[camera.aperture])?;
    at_least(item, "aperture", camera.aperture, 0.0, "≥ 0")?;
    if let Some(focus) = camera.focus_distance {
        finite(item, "focus_distance", &[focus])?;
        at_least(item, "focus_distance", focus, f32::MIN_POSITIVE, "> 0")?;
    }
    Frame::new(camera).ok_or(SceneError::UpParallelToView)
}

/// Colours and weights in [0, 1], reflection + transmission ≤ 1 (a surface passes on no more
/// light than reaches it), ior ≥ 1.
fn material(item: Item, m: &MaterialDesc) -> Result<(), SceneError> {
    unit_colour(item, "material.colour", m.colour)?;
    for (field, value) in [
        ("material.diffuse", m.diffuse),
        ("material.specular", m.specular),
        ("material.reflection", m.reflection),
        ("material.transmission", m.transmission),
    ] {
        unit_interval(item, field, value)?;
    }
    let passed_on = m.reflection + m.transmission;
    if passed_on > 1.0 {
        return Err(out_of_bounds(
            item,
            "material.reflection + material.transmission",
            passed_on,
            "≤ 1",
        ));
    }
    finite(item, "material.ior", &[m.ior])?;
    at_least(item, "material.ior", m.ior, 1.0, "≥ 1")
}

/// Checks a shape and returns how far from `eye` it reaches: its farthest point, or for a
/// plane, which the world cuts off, its nearest.
fn shape(item: Item, shape: &ShapeDesc, eye: [f32; 3]) -> Result<f64, SceneError> {
    match *shape {
        ShapeDesc::Sphere { center, radius } => {
            finite(item, "shape.sphere.center", &center)?;
            finite(item, "shape.sphere.radius", &[radius])?;
            at_least(
                item,
                "shape.sphere.radius",
                radius,
                f32::MIN_POSITIVE,
                "> 0",
            )?;
            Ok(distance(center, eye) + f64::from(radius))
        }
        ShapeDesc::Plane {
            point,
            normal,
            checker,
        } => {
            finite(item, "shape.plane.point", &point)?;
            finite(item, "shape.plane.normal", &normal)?;
            let n = direction(item, "shape.plane.normal", Vec3::from_f32(normal))?;
            if let Some(checker) = checker {
                unit_colour(item, "shape.plane.checker.colour", checker.colour)?;
                finite(item, "shape.plane.checker.size", &[checker.size])?;
                at_least(
                    item,
                    "shape.plane.checker.size",
                    checker.size,
                    f32::MIN_POSITIVE,
                    "> 0",
                )?;
            }
            let to_eye = Vec3::from_f32(eye) - Vec3::from_f32(point);
            Ok(n.dot(to_eye).abs())
        }
        // Checked triangle by triangle ([`SceneDesc::primitives`]), never as a whole.
        ShapeDesc::Mesh { .. } => Ok(0.0),
        ShapeDesc::Triangle { vertices } => {
            for v in &vertices {
                finite(item, "shape.triangle.vertices", v)?;
            }
            if !triangle_has_area(vertices) {
                return Err(SceneError::DegenerateTriangle { item });
            }
            Ok(vertices
                .iter()
                .map(|&v| distance(v, eye))
                .fold(0.0, f64::max))
        }
    }
}

/// Checks the hierarchy of the mesh of object `item` under node `root`: each node's triangles
/// within the scene's, its children after it and splitting its triangles between them, its box
/// finite, within the world's bounds about the eye, holding its children's boxes and a leaf's
/// triangles, and no node deeper than [`MAX_DEPTH`] below the root.
fn hierarchy(
    item: Item,
    meshes: &MeshesDesc<'_>,
    root: u32,
    desc: &SceneDesc<'_>,
) -> Result<(), SceneError> {
    let malformed = |what: &'static str| SceneError::MalformedMesh { item, what };
    let far = f64::from(desc.far);
    let eye = Vec3::from_f32(desc.camera.eye).to_f64();
    let node_at = |index: u32| meshes.nodes.get(index as usize);
    let mut waiting: heapless::Vec<(u32, usize), { MAX_DEPTH + 2 }> = heapless::Vec::new();
    let _ = waiting.push((root, 0));
    while let Some((index, depth)) = waiting.pop() {
        let node = node_at(index).ok_or(malformed("a node it names is not among the nodes"))?;
        if depth > MAX_DEPTH {
            return Err(malformed(
                "its hierarchy is deeper than obscura::mesh::MAX_DEPTH",
            ));
        }
        let corners = [node.min, node.max];
        let within = corners
            .iter()
            .flatten()
            .zip(eye.iter().cycle())
            .all(|(&x, &e)| x.is_finite() && (f64::from(x) - e).abs() <= far);
        let ordered = node
            .min
            .iter()
            .zip(node.max)
            .all(|(&low, high)| low <= high);
        if !within || !ordered {
            return Err(malformed(
                "a box is not finite, not ordered or beyond the world",
            ));
        }
        let holds = |p: [f32; 3]| {
            p.iter()
                .zip(node.min.iter().zip(&node.max))
                .all(|(x, (low, high))| low <= x && x <= high)
        };
        if node.first >= node.end || node.end as usize > meshes.triangles.len() {
            return Err(malformed(
                "a node's triangles are none or not among the triangles",
            ));
        }
        if node.right == 0 {
            let inside = meshes
                .triangles_of(index)
                .iter()
                .all(|&t| meshes.corners(t).into_iter().all(holds));
            if !inside {
                return Err(malformed("a leaf's box does not hold its triangles"));
            }
            continue;
        }
        let left = index.saturating_add(1);
        let (Some(l), Some(r)) = (node_at(left), node_at(node.right)) else {
            return Err(malformed("a node it names is not among the nodes"));
        };
        let split =
            node.right > left && l.first == node.first && l.end == r.first && r.end == node.end;
        if !split || ![l.min, l.max, r.min, r.max].into_iter().all(holds) {
            return Err(malformed(
                "a node's children do not split its triangles within its box",
            ));
        }
        let _ = waiting.push((node.right, depth + 1));
        let _ = waiting.push((left, depth + 1));
    }
    Ok(())
}

/// Checks that every corner of every mesh triangle is one of the meshes' vertices, and that
/// the vertices' normals, if any, are one per vertex, each unit or zero.
fn mesh_corners(desc: &SceneDesc<'_>) -> Result<(), SceneError> {
    let meshes = &desc.meshes;
    let malformed = |what| {
        Err(SceneError::MalformedMesh {
            item: Item::Scene,
            what,
        })
    };
    let unit_or_zero = |n: &[f32; 3]| {
        let length = Vec3::from_f32(*n).length();
        length == 0.0 || (length - 1.0).abs() <= NORMAL_LENGTH_TOLERANCE
    };
    if meshes
        .triangles
        .iter()
        .any(|t| t.iter().any(|&i| meshes.vertices.get(i as usize).is_none()))
    {
        malformed("a triangle names a corner that is not among the vertices")
    } else if !(meshes.normals.is_empty() || meshes.normals.len() == meshes.vertices.len()) {
        malformed("its vertices' normals are not one per vertex (give one for each, or none)")
    } else if !meshes.normals.iter().all(unit_or_zero) {
        malformed("a vertex normal is neither of length 1 nor 0 (normalise it, or give 0 for none)")
    } else {
        Ok(())
    }
}

/// How far from 1 a vertex normal's length may be: f32's rounding of a unit vector (a few of
/// its epsilons), a thousand times over.
const NORMAL_LENGTH_TOLERANCE: f64 = 1024.0 * f32::EPSILON as f64;

fn inside_world(item: Item, reach: f64, far: f32) -> Result<(), SceneError> {
    if reach > f64::from(far) {
        return Err(SceneError::OutsideWorld {
            item,
            distance: reach,
            far,
        });
    }
    Ok(())
}

fn unit_colour(item: Item, field: &'static str, c: [f32; 3]) -> Result<(), SceneError> {
    for channel in c {
        unit_interval(item, field, channel)?;
    }
    Ok(())
}

fn unit_interval(item: Item, field: &'static str, value: f32) -> Result<(), SceneError> {
    finite(item, field, &[value])?;
    if (0.0..=1.0).contains(&value) {
        Ok(())
    } else {
        Err(out_of_bounds(item, field, value, "in [0, 1]"))
    }
}

fn colour(item: Item, field: &'static str, c: [f32; 3]) -> Result<(), SceneError> {
    finite(item, field, &c)?;
    for channel in c {
        at_least(item, field, channel, 0.0, "≥ 0 on every channel")?;
    }
    Ok(())
}

/// `v`'s direction, where it is long enough to give one ([`Vec3::direction`]); one no longer
/// than [`crate::vec3::SHORTEST_DIRECTION`] is refused as too short.
pub(super) fn direction(
    item: Item,
    field: &'static str,
    v: Vec3<f64>,
) -> Result<Vec3<f64>, SceneError> {
    v.direction().ok_or(SceneError::TooShort {
        item,
        field,
        length: v.length(),
    })
}

fn finite(item: Item, field: &'static str, values: &[f32]) -> Result<(), SceneError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(SceneError::NotFinite { item, field })
    }
}

fn at_least(
    item: Item,
    field: &'static str,
    value: f32,
    min: f32,
    expected: &'static str,
) -> Result<(), SceneError> {
    if value >= min {
        Ok(())
    } else {
        Err(out_of_bounds(item, field, value, expected))
    }
}

fn out_of_bounds(
    item: Item,
    field: &'static str,
    value: f32,
    expected: &'static str,
) -> SceneError {
    SceneError::OutOfBounds {
        item,
        field,
        value,
        expected,
    }
}
