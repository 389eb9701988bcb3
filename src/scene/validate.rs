//! The checks a scene description must pass in every number format: finite values, sensible
//! intervals, non-degenerate geometry, everything inside the world.

use super::error::{Item, SceneError};
use super::range::{self, distance};
use crate::camera::Frame;
use crate::desc::{BackgroundDesc, CameraDesc, LightDesc, MaterialDesc, SceneDesc, ShapeDesc};
use crate::pattern::MAX_SAMPLES;
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
    inside_world(Item::Camera, frame.aperture, desc.far)?;
    let eye = Vec3::from_f32(desc.camera.eye);
    for (i, object) in desc.objects.iter().enumerate() {
        let item = Item::Object(i);
        material(item, &object.material)?;
        let reach = shape(item, &object.shape, desc.camera.eye)?;
        inside_world(item, reach, desc.far)?;
        // Every lens point must be on the eye's side of every surface (the eye itself must
        // be clear of them by the format's error: the range proof's).
        let clearance = range::clearance(object, eye);
        if frame.aperture > 0.0 && frame.aperture >= clearance {
            return Err(SceneError::LensTouches {
                object: i,
                clearance,
                aperture: desc.camera.aperture,
            });
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
        ShapeDesc::Triangle { vertices } => {
            for v in &vertices {
                finite(item, "shape.triangle.vertices", v)?;
            }
            let [a, b, c] = vertices.map(Vec3::from_f32);
            let (e1, e2) = (b - a, c - a);
            if e1.cross(e2).length() <= f64::from(f32::EPSILON) * e1.length() * e2.length() {
                return Err(SceneError::DegenerateTriangle { item });
            }
            Ok(vertices
                .iter()
                .map(|&v| distance(v, eye))
                .fold(0.0, f64::max))
        }
    }
}

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
