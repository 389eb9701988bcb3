//! [`OwnedScene`]: a scene description that owns its objects and lights, so that the harness
//! can make scenes at run time (scene files, stress cases, rescaled copies) and lend them to
//! the core.

use crate::animation::Animation;
use crate::mesh_file::MeshFile;
use crate::meshes::OwnedMeshes;
use crate::object::{FileObject, FileShape};
use obscura::{
    BackgroundDesc, CameraDesc, LightDesc, MethodName, ObjectDesc, Pixels, SceneDesc, ShapeDesc,
};
use serde::{Deserialize, Serialize};

/// `$To { .. }` from `$from`: the settings an [`OwnedScene`] shares with the core's
/// [`SceneDesc`] (all but the camera and the lists) copied, and `$field: $value` for the rest.
/// The one list of the shared fields: every conversion between the two is built here, and a
/// field either adds, the other lacking it, fails to compile.
macro_rules! with_shared_settings {
    ($from:ident => $To:ident { $($field:ident: $value:expr),* $(,)? }) => {
        $To {
            ambient: $from.ambient,
            background: $from.background,
            far: $from.far,
            max_depth: $from.max_depth,
            samples: $from.samples,
            adaptive_samples: $from.adaptive_samples,
            shadow_samples: $from.shadow_samples,
            adaptive_shadows: $from.adaptive_shadows,
            pixels: $from.pixels,
            $($field: $value),*
        }
    };
}

/// A scene description with owned lists; what a scene file holds (lights, ambient light,
/// background and depth may be left out), its objects `O` as the core's, or as a file gives
/// them (naming mesh files, which [`crate::load`] reads into [`OwnedScene::meshes`]).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OwnedScene<O = ObjectDesc> {
    /// See [`SceneDesc::camera`].
    pub camera: CameraDesc,
    /// See [`SceneDesc::objects`].
    pub objects: Vec<O>,
    /// See [`SceneDesc::meshes`]: not in a file, which names mesh files instead.
    #[serde(skip)]
    pub meshes: OwnedMeshes,
    /// See [`SceneDesc::lights`].
    #[serde(default)]
    pub lights: Vec<LightDesc>,
    /// See [`SceneDesc::ambient`].
    #[serde(default = "default_ambient")]
    pub ambient: [f32; 3],
    /// See [`SceneDesc::background`].
    #[serde(default = "default_background")]
    pub background: BackgroundDesc,
    /// See [`SceneDesc::far`].
    pub far: f32,
    /// See [`SceneDesc::max_depth`].
    #[serde(default = "default_max_depth")]
    pub max_depth: u8,
    /// See [`SceneDesc::samples`].
    #[serde(default = "default_samples", deserialize_with = "ray_count")]
    pub samples: u16,
    /// See [`SceneDesc::adaptive_samples`].
    #[serde(default)]
    pub adaptive_samples: bool,
    /// See [`SceneDesc::shadow_samples`].
    #[serde(default = "default_shadow_samples", deserialize_with = "ray_count")]
    pub shadow_samples: u16,
    /// See [`SceneDesc::adaptive_shadows`].
    #[serde(default)]
    pub adaptive_shadows: bool,
    /// See [`SceneDesc::pixels`]: `"exact"`, or `"adaptive:N"` (N = 2, 4 or 8).
    #[serde(default, with = "pixels_by_name")]
    pub pixels: Pixels,
    /// A camera path, the `[animation]` table: without one, the scene is a still picture.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub animation: Option<Animation>,
}

// A key left out takes the core's default ([`SceneDesc::DEFAULT`]).

const fn default_ambient() -> [f32; 3] {
    SceneDesc::DEFAULT.ambient
}

const fn default_background() -> BackgroundDesc {
    SceneDesc::DEFAULT.background
}

const fn default_max_depth() -> u8 {
    SceneDesc::DEFAULT.max_depth
}

const fn default_samples() -> u16 {
    SceneDesc::DEFAULT.samples
}

const fn default_shadow_samples() -> u16 {
    SceneDesc::DEFAULT.shadow_samples
}

/// A count of rays (`samples`, `shadow_samples`): any whole number reads, and one beyond a
/// count's type is refused as a count, not as a type (the build refuses one outside 1 to 256).
fn ray_count<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<u16, D::Error> {
    let count = i64::deserialize(deserializer)?;
    u16::try_from(count).map_err(|_| {
        serde::de::Error::custom(format!(
            "{count} is not a count of rays: give a whole number from 1 to {}",
            obscura::pattern::MAX_SAMPLES
        ))
    })
}

/// [`Pixels`] in a file by its name.
mod pixels_by_name {
    use super::{MethodName, Pixels};
    use serde::{Deserialize, Deserializer, Serializer};

    pub(super) fn serialize<S: Serializer>(
        pixels: &Pixels,
        serializer: S,
    ) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(pixels.name())
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(
        deserializer: D,
    ) -> Result<Pixels, D::Error> {
        let name = String::deserialize(deserializer)?;
        Pixels::from_name(&name).ok_or_else(|| {
            let names: Vec<_> = Pixels::ALL
                .iter()
                .map(|(_, name)| format!("\"{name}\""))
                .collect();
            serde::de::Error::custom(format!(
                "`{name}` is not a way to find pixels: give {}",
                names.join(", ")
            ))
        })
    }
}

impl<O> OwnedScene<O> {
    /// The scene with other objects, as `object` makes them of its own.
    pub fn map_objects<T, E>(
        self,
        object: impl FnMut(O) -> Result<T, E>,
    ) -> Result<OwnedScene<T>, E> {
        let mapped = self
            .objects
            .into_iter()
            .map(object)
            .collect::<Result<_, _>>()?;
        Ok(with_shared_settings!(self => OwnedScene {
            camera: self.camera,
            objects: mapped,
            meshes: self.meshes,
            lights: self.lights,
            animation: self.animation,
        }))
    }

    /// The frames of its camera path (1 for a still picture).
    pub fn frames(&self) -> u16 {
        self.animation.as_ref().map_or(1, |a| a.frames)
    }

    /// The camera of `frame` of its path (the `[camera]` table's for a still picture).
    pub fn camera_at(&self, frame: u16) -> CameraDesc {
        self.animation
            .as_ref()
            .map_or(self.camera, |a| a.camera(&self.camera, frame))
    }
}

impl OwnedScene {
    /// A copy of `desc`.
    pub fn from_desc(desc: &SceneDesc<'_>) -> Self {
        with_shared_settings!(desc => Self {
            camera: desc.camera,
            objects: desc.objects.to_vec(),
            meshes: OwnedMeshes::from_desc(&desc.meshes),
            lights: desc.lights.to_vec(),
            animation: None,
        })
    }

    /// The still scene of `frame` of its camera path: that frame's camera, no path.
    #[must_use]
    pub fn at_frame(&self, frame: u16) -> Self {
        Self {
            camera: self.camera_at(frame),
            animation: None,
            ..self.clone()
        }
    }

    /// The description, borrowing the lists: frame 0's, for a scene with a camera path.
    pub fn desc(&self) -> SceneDesc<'_> {
        with_shared_settings!(self => SceneDesc {
            camera: self.camera_at(0),
            objects: &self.objects,
            meshes: self.meshes.desc(),
            lights: &self.lights,
        })
    }

    /// The scene as the files that say it: the scene file's TOML, whose mesh objects name
    /// the files `{stem}-mesh-{k}.obj` (k counting the mesh objects from 0), and each of those
    /// as its name and OBJ text ([`crate::obj_text`]). Read back ([`crate::load`]), the mesh
    /// files give the same triangles, though their hierarchies are built again.
    ///
    /// # Errors
    /// When a value cannot be written as TOML.
    pub fn files(&self, stem: &str) -> Result<(String, Vec<(String, String)>), toml::ser::Error> {
        let mut meshes = Vec::new();
        let file_form = self.clone().map_objects(|object| {
            let shape = match object.shape {
                ShapeDesc::Mesh { root } => {
                    let file = format!("{stem}-mesh-{}.obj", meshes.len());
                    let desc = self.meshes.desc();
                    let triangles = desc.triangles_of(root);
                    let normals = crate::CornerNormals {
                        normals: desc.normals,
                        corners: triangles,
                    };
                    let text = crate::obj_text(desc.vertices, triangles, Some(normals));
                    meshes.push((file.clone(), text));
                    FileShape::Mesh {
                        mesh: MeshFile::at(file),
                    }
                }
                shape => FileShape::Shape(shape),
            };
            Ok::<_, std::convert::Infallible>(FileObject {
                shape,
                material: object.material,
            })
        });
        let Ok(file_form) = file_form;
        Ok((toml::to_string(&file_form)?, meshes))
    }

    /// The scene scaled by `s` about the eye: every position moved to eye + s·(p − eye), every
    /// length multiplied by s. The camera sees the very same image.
    pub fn scaled(&self, s: f32) -> Self {
        let eye = self.camera.eye;
        self.transformed(
            |p| std::array::from_fn(|i| eye[i] + s * (p[i] - eye[i])),
            |d| d,
            |length| s * length,
        )
    }

    /// The scene moved by a map of the world: every position (the eye, where it looks, the
    /// objects' and the lights' places) through `position`, every direction (the camera's up,
    /// a plane's normal, the sky's up) through `direction`, and every length (a radius, a
    /// square's size, `far`, the lens's aperture and focus distance) through `length`.
    pub fn transformed(
        &self,
        position: impl Fn([f32; 3]) -> [f32; 3],
        direction: impl Fn([f32; 3]) -> [f32; 3],
        length: impl Fn(f32) -> f32,
    ) -> Self {
        let objects = self
            .objects
            .iter()
            .map(|object| {
                let shape = match object.shape {
                    ShapeDesc::Sphere { center, radius } => ShapeDesc::Sphere {
                        center: position(center),
                        radius: length(radius),
                    },
                    ShapeDesc::Plane {
                        point,
                        normal,
                        checker,
                    } => ShapeDesc::Plane {
                        point: position(point),
                        normal: direction(normal),
                        checker: checker.map(|c| obscura::CheckerDesc {
                            size: length(c.size),
                            ..c
                        }),
                    },
                    ShapeDesc::Triangle { vertices } => ShapeDesc::Triangle {
                        vertices: vertices.map(&position),
                    },
                    mesh @ ShapeDesc::Mesh { .. } => mesh,
                };
                ObjectDesc { shape, ..*object }
            })
            .collect();
        let lights = self
            .lights
            .iter()
            .map(|light| LightDesc {
                position: position(light.position),
                radius: length(light.radius),
                ..*light
            })
            .collect();
        let background = match self.background {
            BackgroundDesc::Gradient {
                horizon,
                zenith,
                up,
            } => BackgroundDesc::Gradient {
                horizon,
                zenith,
                up: direction(up),
            },
            solid @ BackgroundDesc::Solid(_) => solid,
        };
        let animation = self.animation.as_ref().map(|animation| Animation {
            keys: animation
                .keys
                .iter()
                .map(|key| crate::Key {
                    eye: position(key.eye),
                    look_at: position(key.look_at),
                    up: key.up.map(&direction),
                    ..*key
                })
                .collect(),
            ..animation.clone()
        });
        Self {
            camera: CameraDesc {
                eye: position(self.camera.eye),
                look_at: position(self.camera.look_at),
                up: direction(self.camera.up),
                aperture: length(self.camera.aperture),
                focus_distance: self.camera.focus_distance.map(&length),
                ..self.camera
            },
            animation,
            objects,
            meshes: self.meshes.moved(&position, &direction),
            lights,
            background,
            far: length(self.far),
            ..self.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use obscura::scenes;

    #[test]
    fn scaling_moves_everything_about_the_eye() {
        let whitted = OwnedScene::from_desc(&scenes::WHITTED);
        assert_eq!(whitted.desc(), scenes::WHITTED);
        let half = whitted.scaled(0.5);
        assert_eq!(half.camera.eye, scenes::WHITTED.camera.eye);
        assert_eq!(half.far, 15.0);
        let ShapeDesc::Sphere { center, radius } = half.objects[1].shape else {
            panic!()
        };
        // (−1.2, 1.0, 3.2) about the eye (0, 3, −6), halved.
        let want = [-0.6, 2.0, -1.4];
        assert!(
            center.iter().zip(want).all(|(c, w)| (c - w).abs() < 1e-6),
            "{center:?}"
        );
        assert_eq!(radius, 0.5);
        // Scaling back restores every position, up to f32's rounding.
        for (back, original) in half.scaled(2.0).objects.iter().zip(&whitted.objects) {
            if let (
                ShapeDesc::Sphere {
                    center: b,
                    radius: rb,
                },
                ShapeDesc::Sphere {
                    center: o,
                    radius: ro,
                },
            ) = (back.shape, original.shape)
            {
                assert!((rb - ro).abs() < 1e-6);
                assert!(
                    b.iter().zip(o).all(|(b, o)| (b - o).abs() < 1e-6),
                    "{b:?} {o:?}"
                );
            }
        }
    }
}
