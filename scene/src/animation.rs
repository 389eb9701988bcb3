//! A camera path: a scene file's `[animation]` table, whose keys place the camera at some of
//! a loop's frames, and the camera of every frame between them ([`Animation::camera`]). Objects
//! and lights stay still.
//!
//! Between keys the eye, the look-at point, the up direction and the field of view each move
//! on a closed uniform Catmull–Rom spline through the keys' values (Catmull and Rom, 1974): a
//! curve through every key, smooth at each, wrapping from the last key back to the first at
//! `frames`; each segment's parameter runs evenly over the frames between its two keys.

use obscura::CameraDesc;
use serde::{Deserialize, Serialize};
use std::fmt;

/// A loop of `frames` frames, played at `fps`, through the camera keys.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Animation {
    /// Frames in the loop, at least 1.
    pub frames: u16,
    /// Frames a second the desktop plays it at, at least 1 (a board goes as fast as it can).
    pub fps: u16,
    /// The keys, at least one; the `[camera]` table is frame 0's unless a key is.
    pub keys: Vec<Key>,
}

/// The camera at one frame of the loop.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Key {
    /// The frame, from 0, below the loop's `frames`.
    pub frame: u16,
    /// The eye.
    pub eye: [f32; 3],
    /// The point in the centre of the image.
    pub look_at: [f32; 3],
    /// Which way is up; the `[camera]` table's if left out.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub up: Option<[f32; 3]>,
    /// The vertical field of view in degrees; the `[camera]` table's if left out.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vfov_degrees: Option<f32>,
}

/// What is wrong with an animation, and where: the key it is about, if one.
#[derive(Clone, Debug, PartialEq)]
pub struct AnimationError {
    /// The key at fault (its index in `keys`), or `None` for the table's own values.
    pub key: Option<usize>,
    /// The field at fault (`frames`, `fps`, `keys`, `frame`, `eye`).
    pub field: &'static str,
    /// What is wrong, and how to mend it.
    pub message: String,
}

impl fmt::Display for AnimationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for AnimationError {}

/// How close an eye may come to its look-at point, relative to their size, before the view
/// direction is lost (the core refuses the same camera).
const LEAST_VIEW: f32 = 1e-4;

impl Animation {
    /// The keys in frame order, `camera` (the `[camera]` table) as frame 0's where no key is,
    /// each key's missing values `camera`'s.
    fn points(&self, camera: &CameraDesc) -> Vec<(u16, CameraDesc)> {
        let mut points: Vec<(u16, CameraDesc)> = self
            .keys
            .iter()
            .map(|key| {
                let at = CameraDesc {
                    eye: key.eye,
                    look_at: key.look_at,
                    up: key.up.unwrap_or(camera.up),
                    vfov_degrees: key.vfov_degrees.unwrap_or(camera.vfov_degrees),
                    ..*camera
                };
                (key.frame, at)
            })
            .collect();
        if !points.iter().any(|&(frame, _)| frame == 0) {
            points.push((0, *camera));
        }
        points.sort_by_key(|&(frame, _)| frame);
        points
    }

    /// The camera of `frame` (taken modulo the loop), on the spline through the keys.
    pub fn camera(&self, camera: &CameraDesc, frame: u16) -> CameraDesc {
        let points = self.points(camera);
        let frames = u32::from(self.frames.max(1));
        let frame = u32::from(frame) % frames;
        let n = points.len();
        // The segment from key i to key i + 1 (wrapping) that holds `frame`.
        let i = points
            .iter()
            .rposition(|&(f, _)| u32::from(f) <= frame)
            .unwrap_or(0);
        let start = u32::from(points[i].0);
        let end = if i + 1 < n {
            u32::from(points[i + 1].0)
        } else {
            u32::from(points[0].0) + frames
        };
        let t = (frame - start) as f32 / (end - start).max(1) as f32;
        let at = |k: usize| &points[(i + n + k - 1) % n].1;
        let (p0, p1, p2, p3) = (at(0), at(1), at(2), at(3));
        let vector = |v: fn(&CameraDesc) -> [f32; 3]| {
            std::array::from_fn(|j| catmull_rom(v(p0)[j], v(p1)[j], v(p2)[j], v(p3)[j], t))
        };
        CameraDesc {
            eye: vector(|c| c.eye),
            look_at: vector(|c| c.look_at),
            up: vector(|c| c.up),
            vfov_degrees: catmull_rom(
                p0.vfov_degrees,
                p1.vfov_degrees,
                p2.vfov_degrees,
                p3.vfov_degrees,
                t,
            ),
            ..*camera
        }
    }

    /// Every frame's camera, in order.
    pub fn cameras(&self, camera: &CameraDesc) -> Vec<CameraDesc> {
        (0..self.frames)
            .map(|frame| self.camera(camera, frame))
            .collect()
    }

    /// Checks the table against what a loop needs: frames and pace of at least 1, at least one
    /// key, each within the loop and on a frame of its own, and on every frame an eye away from
    /// its look-at point.
    ///
    /// # Errors
    /// The first fault, with the key and field it is at.
    pub fn check(&self, camera: &CameraDesc) -> Result<(), AnimationError> {
        let table = |field, message: String| AnimationError {
            key: None,
            field,
            message,
        };
        if self.frames == 0 {
            return Err(table(
                "frames",
                "a loop of 0 frames: give at least 1".into(),
            ));
        }
        if self.fps == 0 {
            return Err(table("fps", "0 frames a second: give at least 1".into()));
        }
        if self.keys.is_empty() {
            return Err(table(
                "keys",
                "an animation without keys: add at least one [[animation.keys]] with its frame, \
                 eye and look_at"
                    .into(),
            ));
        }
        for (i, key) in self.keys.iter().enumerate() {
            let at = |field, message: String| AnimationError {
                key: Some(i),
                field,
                message,
            };
            if key.frame >= self.frames {
                return Err(at(
                    "frame",
                    format!(
                        "a key at frame {} of a loop of {} frames: frames run from 0 to {}",
                        key.frame,
                        self.frames,
                        self.frames - 1
                    ),
                ));
            }
            if let Some(first) = self.keys[..i].iter().position(|k| k.frame == key.frame) {
                return Err(at(
                    "frame",
                    format!(
                        "a second key at frame {} (key {} is there already): give each key a \
                         frame of its own",
                        key.frame,
                        first + 1
                    ),
                ));
            }
        }
        for frame in 0..self.frames {
            let c = self.camera(camera, frame);
            let view: f32 = (0..3)
                .map(|j| (c.look_at[j] - c.eye[j]).powi(2))
                .sum::<f32>()
                .sqrt();
            let size = (0..3)
                .map(|j| c.eye[j].abs().max(c.look_at[j].abs()))
                .fold(1.0_f32, f32::max);
            if view <= LEAST_VIEW * size {
                let key = self.keys.iter().position(|k| k.frame == frame);
                return Err(AnimationError {
                    key,
                    field: if key.is_some() { "eye" } else { "keys" },
                    message: format!(
                        "at frame {frame} the eye ({:?}) is on its look-at point ({:?}): move \
                         the keys' eyes or look-at points apart",
                        c.eye, c.look_at
                    ),
                });
            }
        }
        Ok(())
    }
}

/// The uniform Catmull–Rom spline through p1 (t = 0) and p2 (t = 1), p0 before and p3 after.
fn catmull_rom(p0: f32, p1: f32, p2: f32, p3: f32, t: f32) -> f32 {
    let (t2, t3) = (t * t, t * t * t);
    0.5 * (2.0 * p1
        + (p2 - p0) * t
        + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2
        + (3.0 * (p1 - p2) + p3 - p0) * t3)
}

#[cfg(test)]
mod tests {
    use super::*;
    use obscura::scenes;

    fn key(frame: u16, eye: [f32; 3]) -> Key {
        Key {
            frame,
            eye,
            look_at: [0.0, 0.0, 0.0],
            up: None,
            vfov_degrees: None,
        }
    }

    fn orbit() -> Animation {
        Animation {
            frames: 16,
            fps: 8,
            keys: vec![
                key(0, [0.0, 1.0, -5.0]),
                key(4, [5.0, 1.0, 0.0]),
                key(8, [0.0, 1.0, 5.0]),
                key(12, [-5.0, 1.0, 0.0]),
            ],
        }
    }

    #[test]
    fn the_path_passes_through_every_key_and_wraps_smoothly() {
        let camera = scenes::WHITTED.camera;
        let orbit = orbit();
        orbit.check(&camera).unwrap();
        for k in &orbit.keys {
            assert_eq!(orbit.camera(&camera, k.frame).eye, k.eye);
        }
        // Frame 16 is frame 0 again; frame 2 lies between the first two keys, out on the
        // curve (farther from the axis than the chord's midpoint).
        assert_eq!(orbit.camera(&camera, 16), orbit.camera(&camera, 0));
        let mid = orbit.camera(&camera, 2).eye;
        assert!(mid[0] > 2.5 && mid[2] < -2.5, "{mid:?}");
        // Symmetric keys, symmetric path: frame 14 mirrors frame 2.
        let back = orbit.camera(&camera, 14).eye;
        assert!((back[0] + mid[0]).abs() < 1e-5 && (back[2] - mid[2]).abs() < 1e-5);
        // The field of view and up are the camera's where no key gives them.
        assert_eq!(orbit.camera(&camera, 5).vfov_degrees, camera.vfov_degrees);
    }

    #[test]
    fn the_camera_table_is_frame_zero_unless_a_key_is() {
        let camera = scenes::WHITTED.camera;
        let one = Animation {
            frames: 8,
            fps: 4,
            keys: vec![key(4, [1.0, 2.0, 3.0])],
        };
        assert_eq!(one.camera(&camera, 0), camera);
        assert_eq!(one.camera(&camera, 4).eye, [1.0, 2.0, 3.0]);
    }

    #[test]
    fn faults_name_their_key_and_field() {
        let camera = scenes::WHITTED.camera;
        let mut late = orbit();
        late.keys[2].frame = 16;
        let error = late.check(&camera).unwrap_err();
        assert_eq!((error.key, error.field), (Some(2), "frame"));
        assert!(error.message.contains("frames run from 0 to 15"), "{error}");
        let mut twice = orbit();
        twice.keys[3].frame = 4;
        let error = twice.check(&camera).unwrap_err();
        assert_eq!((error.key, error.field), (Some(3), "frame"));
        let mut blind = orbit();
        blind.keys[1].eye = blind.keys[1].look_at;
        let error = blind.check(&camera).unwrap_err();
        assert_eq!((error.key, error.field), (Some(1), "eye"));
        assert!(error.message.contains("at frame 4"), "{error}");
        let none = Animation {
            keys: Vec::new(),
            ..orbit()
        };
        assert_eq!(none.check(&camera).unwrap_err().field, "keys");
        let empty = Animation {
            frames: 0,
            ..orbit()
        };
        assert_eq!(empty.check(&camera).unwrap_err().field, "frames");
    }
}
