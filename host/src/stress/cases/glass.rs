//! Rays starting inside a glass sphere: the eye inside it, ever nearer its surface, looking at
//! a checkered floor and a red ball through it; the rays that meet the surface beyond the
//! critical angle are totally reflected. Per self-intersection method.

use super::{image_row, wrong};
use crate::checked::Checked;
use crate::stress::{Case, Row};
use anyhow::Result;
use obscura::methods::MethodName;
use obscura::{
    BackgroundDesc, BiasMethod, CameraDesc, CheckerDesc, LightDesc, MaterialDesc, Methods,
    ObjectDesc, Scalar, SceneDesc, ShapeDesc, Y_UP,
};
use obscura_scene::FormatJob;

pub const CASE: Case = Case {
    name: "glass",
    about: "rays starting inside a glass sphere, total internal reflection",
    x_label: "the eye's distance from the sphere's centre, over its radius",
    log_x: false,
    y_label: "wrong pixels (%)",
    run: |format| format.run::<Checked, _>(Job),
};

const OFFSETS: [f64; 5] = [0.0, 0.3, 0.6, 0.9, 0.99];

/// Clear glass, a little reflective.
pub(super) const GLASS: MaterialDesc = MaterialDesc {
    colour: [1.0; 3],
    diffuse: 0.0,
    specular: 0.0,
    shininess: 1,
    reflection: 0.1,
    transmission: 0.9,
    ior: 1.5,
};

const OBJECTS: [ObjectDesc; 3] = [
    ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [0.0, 0.0, 0.0],
            radius: 1.0,
        },
        material: GLASS,
    },
    ObjectDesc {
        shape: ShapeDesc::Plane {
            point: [0.0, -2.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            checker: Some(CheckerDesc {
                colour: [0.1, 0.1, 0.8],
                size: 0.5,
            }),
        },
        material: MaterialDesc::matte([0.9, 0.9, 0.2]),
    },
    ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [0.0, 0.0, 4.0],
            radius: 1.0,
        },
        material: MaterialDesc::matte([0.9, 0.1, 0.1]),
    },
];

const LIGHTS: [LightDesc; 1] = [LightDesc::point([3.0, 5.0, -2.0], [1.0; 3])];

/// The case's scene with the eye `offset` radii from the sphere's centre.
fn scene(offset: f64) -> SceneDesc<'static> {
    SceneDesc {
        camera: CameraDesc::pinhole(
            [offset as f32, 0.0, 0.0],
            [offset as f32, -0.3, 1.0],
            [0.0, 1.0, 0.0],
            90.0,
        ),
        objects: &OBJECTS,
        lights: &LIGHTS,
        ambient: [0.15; 3],
        background: BackgroundDesc::Gradient {
            up: Y_UP,
            horizon: [0.6, 0.7, 0.9],
            zenith: [0.1, 0.2, 0.6],
        },
        far: 12.0,
        max_depth: 4,
        ..SceneDesc::DEFAULT
    }
}

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let mut rows = Vec::new();
        for offset in OFFSETS {
            for &(bias, name) in BiasMethod::ALL {
                let methods = Methods {
                    bias,
                    ..Methods::LECTURE
                };
                rows.push(image_row::<S>(&scene(offset), methods, name, offset, wrong));
            }
        }
        Ok(rows)
    }
}

#[cfg(test)]
mod tests {
    use super::super::SIZE;
    use super::*;
    use crate::render::HostScene;
    use crate::stress::check::{self, TOLERANCE};
    use obscura::formats::I18f14;
    use obscura::pattern::SampleId;
    use obscura::scalar::FormatInfo;

    /// At 0.9 radii, i18f14's surface tolerances are what decide a chain of internal
    /// reflections near the critical angle: f64 started as far off the surfaces draws pixels
    /// the ideal f64 image does not, and the check excuses i18f14's by them and nothing else.
    #[test]
    fn i18f14s_offsets_change_the_chain_and_excuse_its_pixels() {
        let desc = scene(0.9);
        let methods = Methods {
            rays: obscura::RayMethod::PerPixel,
            roots: obscura::methods::RootMethod::Exact,
            ..Methods::LECTURE
        };
        let ideal = HostScene::<f64>::build_with(&desc, methods).unwrap();
        let offset =
            HostScene::<f64>::build_with_tolerances_of(&desc, methods, &FormatInfo::of::<I18f14>())
                .unwrap();
        let camera = ideal.camera(SIZE, SIZE).unwrap();
        let changed = (0..SIZE)
            .flat_map(|y| (0..SIZE).map(move |x| (x, y)))
            .filter_map(|(x, y)| camera.ray(x, y))
            .filter(|&ray| {
                let [a, b] = [&ideal, &offset]
                    .map(|s| check::colour(s.trace(ray, SampleId::default()).colour));
                check::off(a, b) > TOLERANCE
            })
            .count();
        assert!(changed > 0, "the offsets changed no pixel");
        let checked = check::image::<I18f14>(&desc, Methods::LECTURE, SIZE).unwrap();
        assert!(checked.wrong_pct > 0.0);
        assert_eq!(checked.unexcused, 0);
    }
}
