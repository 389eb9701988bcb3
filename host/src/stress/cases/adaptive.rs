//! Where adaptive pixels fail: features smaller than a block that its corners cannot see, each
//! a case swept down past a pixel — a small shadow on a floor, a small ball's reflection in a
//! mirror ball, a fine checkerboard, and a checkerboard seen through a glass ball. Each scene is
//! drawn with exact pixels and with blocks of 2, 4 and 8, every image against f64 with exact
//! pixels: the PSNR is the method's cost in accuracy (a shadow, reflection or refraction lost
//! between corners is the method's known weakness, reported), and the objects the primary rays
//! show are its promise: no object vanishes, so a block's object mismatch may exceed exact
//! pixels' by at most [`VANISHING`] percentage points.

use super::{MATTE, capped};
use crate::checked::Checked;
use crate::metrics::accuracy;
use crate::render::{HostScene, Prepared, Request, exact_roots};
use crate::stress::{Case, Outcome, Row};
use anyhow::Result;
use image::RgbImage;
use obscura::methods::MethodName;
use obscura::{
    BackgroundDesc, CameraDesc, CheckerDesc, LightDesc, MaterialDesc, Methods, ObjectDesc, Pixels,
    Scalar, SceneDesc, ShapeDesc, SphereMethod,
};
use obscura_scene::FormatJob;

/// Percentage points of object mismatch a block size may add to exact pixels'.
const VANISHING: f64 = 0.1;

/// The lecture's methods with the stable sphere test, which resolves the shadow case's small
/// balls in more formats.
const METHODS: Methods = Methods {
    sphere: SphereMethod::Stable,
    ..Methods::LECTURE
};

/// The images are this many pixels square: six blocks of 8 across.
const SIZE: u32 = 48;

pub const SHADOW: Case = Case {
    name: "adaptive-shadow",
    about: "adaptive pixels: a ball's shadow on a floor, 16 pixels across to half a pixel, the ball out of view",
    x_label: "the shadow's size (pixels)",
    log_x: true,
    y_label: "PSNR against f64, exact pixels (dB)",
    run: |format| format.run::<Checked, _>(Job(shadow, PIXELS_SWEEP)),
};

pub const REFLECTION: Case = Case {
    name: "adaptive-reflection",
    about: "adaptive pixels: a ball out of view seen in a mirror ball, its radius 0.8 to 0.025",
    x_label: "the reflected ball's radius (the mirror's is 1)",
    log_x: true,
    y_label: "PSNR against f64, exact pixels (dB)",
    run: |format| format.run::<Checked, _>(Job(reflection, RADII)),
};

pub const CHECKER: Case = Case {
    name: "adaptive-checker",
    about: "adaptive pixels: a checkered floor, its squares 16 pixels to half a pixel",
    x_label: "the checker's square (pixels, near the image's centre)",
    log_x: true,
    y_label: "PSNR against f64, exact pixels (dB)",
    run: |format| format.run::<Checked, _>(Job(checker, PIXELS_SWEEP)),
};

pub const GLASS: Case = Case {
    name: "adaptive-glass",
    about: "adaptive pixels: a checkered floor seen through a glass ball, its squares 16 pixels to half a pixel",
    x_label: "the checker's square (pixels, near the image's centre, beside the ball)",
    log_x: true,
    y_label: "PSNR against f64, exact pixels (dB)",
    run: |format| format.run::<Checked, _>(Job(glass, PIXELS_SWEEP)),
};

/// The sweep of the cases measured in pixels: their feature from 16 pixels to half of one.
const PIXELS_SWEEP: &[f64] = &[16.0, 8.0, 4.0, 2.0, 1.0, 0.5];

/// The reflection case's sweep: the reflected ball's radius, its reflection from about 5 pixels
/// across to a sixth of one.
const RADII: &[f64] = &[0.8, 0.4, 0.2, 0.1, 0.05, 0.025];

/// A camera 4 above a floor looking down at it steeply: about 13 pixels to a unit of floor near
/// the image's centre at [`SIZE`].
const OVER_THE_FLOOR: CameraDesc =
    CameraDesc::pinhole([0.0, 4.0, -1.5], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], 45.0);

/// Pixels to a unit of floor near the image's centre, seen [`OVER_THE_FLOOR`].
const PIXELS_A_UNIT: f64 = 13.0;

/// A floor at height 0, matte, with a checkerboard of squares `size` wide if any.
fn floor(size: Option<f64>) -> ObjectDesc {
    ObjectDesc {
        shape: ShapeDesc::Plane {
            point: [0.0; 3],
            normal: [0.0, 1.0, 0.0],
            checker: size.map(|size| CheckerDesc {
                colour: [0.1, 0.1, 0.5],
                size: size as f32,
            }),
        },
        material: MaterialDesc::matte([0.9, 0.85, 0.6]),
    }
}

/// One case's scene at one value of its parameter.
struct Stage {
    camera: CameraDesc,
    objects: Vec<ObjectDesc>,
    lights: Vec<LightDesc>,
}

impl Stage {
    fn desc(&self) -> SceneDesc<'_> {
        SceneDesc {
            camera: self.camera,
            objects: &self.objects,
            lights: &self.lights,
            ambient: [0.15; 3],
            background: BackgroundDesc::Solid([0.1, 0.2, 0.6]),
            far: 14.0,
            max_depth: 3,
            ..SceneDesc::DEFAULT
        }
    }
}

/// A small ball 2 above the floor, beside the eye's view, under a light low to its side: its
/// shadow, `pixels` across, falls 3 pixels right of and below the image's centre, where no
/// block's corner lies.
fn shadow(pixels: f64) -> Stage {
    const LIGHT: [f64; 3] = [-8.0, 6.0, 0.0];
    const SHADOW: [f64; 3] = [3.0 / PIXELS_A_UNIT, 0.0, -3.0 / PIXELS_A_UNIT];
    const HEIGHT: f64 = 2.0;
    let centre =
        std::array::from_fn(|i| (SHADOW[i] + (LIGHT[i] - SHADOW[i]) * HEIGHT / LIGHT[1]) as f32);
    // The shadow is the ball's size magnified by the light's height over its height above the
    // ball.
    let radius = pixels / PIXELS_A_UNIT / 2.0 * (LIGHT[1] - HEIGHT) / LIGHT[1];
    Stage {
        camera: OVER_THE_FLOOR,
        objects: vec![
            floor(None),
            ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: centre,
                    radius: radius as f32,
                },
                material: MATTE,
            },
        ],
        lights: vec![LightDesc::point(LIGHT.map(|c| c as f32), [1.0; 3])],
    }
}

/// A mirror ball of radius 1 on the floor seen from in front, and a matte red ball of `radius`
/// to the side, out of the eye's view, which only the mirror shows.
fn reflection(radius: f64) -> Stage {
    const MIRROR: MaterialDesc = MaterialDesc {
        colour: [0.7; 3],
        diffuse: 0.2,
        specular: 0.5,
        shininess: 40,
        reflection: 0.7,
        transmission: 0.0,
        ior: 1.0,
    };
    Stage {
        camera: CameraDesc::pinhole([0.0, 1.5, -5.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0], 30.0),
        objects: vec![
            floor(None),
            ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: [0.0, 1.0, 0.0],
                    radius: 1.0,
                },
                material: MIRROR,
            },
            ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: [2.6, 2.4, -1.5],
                    radius: radius as f32,
                },
                material: MaterialDesc::matte([0.95, 0.1, 0.05]),
            },
        ],
        lights: vec![LightDesc::point([3.0, 6.0, -4.0], [1.0; 3])],
    }
}

/// A checkered floor of squares `pixels` wide near the image's centre.
fn checker(pixels: f64) -> Stage {
    Stage {
        camera: OVER_THE_FLOOR,
        objects: vec![floor(Some(pixels / PIXELS_A_UNIT))],
        lights: vec![LightDesc::point([2.0, 8.0, -3.0], [1.0; 3])],
    }
}

/// The checkered floor of [`checker`] under a glass ball of radius 1 standing on it.
fn glass(pixels: f64) -> Stage {
    let mut stage = checker(pixels);
    stage.objects.push(ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [0.0, 1.0, 0.0],
            radius: 1.0,
        },
        material: super::glass::GLASS,
    });
    stage
}

/// Runs a case's sweep in one format: its scene at each value of its parameter.
struct Job(fn(f64) -> Stage, &'static [f64]);

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let mut rows = Vec::new();
        for &x in self.1 {
            let stage = (self.0)(x);
            rows.extend(pixels_rows::<S>(&stage.desc(), x)?);
        }
        Ok(rows)
    }
}

/// A row for each way of finding pixels: `desc` drawn in `S` that way, against f64 with exact
/// pixels; or the build's refusal.
fn pixels_rows<S: Scalar>(desc: &SceneDesc<'_>, x: f64) -> Result<Vec<Row>> {
    let methods = METHODS;
    if let Err(error) = HostScene::<S>::build_with(desc, methods) {
        return Ok(Pixels::ALL
            .iter()
            .map(|&(_, name)| super::refused(S::NAME, name, x, &error))
            .collect());
    }
    let with = |pixels| SceneDesc { pixels, ..*desc };
    let (truth, truth_objects) = draw::<f64>(with(Pixels::Exact), exact_roots(methods))?;
    let mut rows = Vec::new();
    let mut exact_mismatch = 0.0;
    for &(pixels, name) in Pixels::ALL {
        let (image, objects) = draw::<S>(with(pixels), methods)?;
        let measured = accuracy(&image, &truth, &objects, &truth_objects);
        if pixels == Pixels::Exact {
            exact_mismatch = measured.object_mismatch_pct;
        }
        rows.push(Row {
            format: S::NAME,
            method: name,
            x,
            y: Some(capped(measured.psnr_db)),
            outcome: Outcome::bounded(measured.object_mismatch_pct - exact_mismatch, VANISHING),
        });
    }
    Ok(rows)
}

/// `desc` drawn in `S` by `methods` at [`SIZE`], and the object each pixel shows.
fn draw<S: Scalar>(
    desc: SceneDesc<'_>,
    methods: Methods,
) -> Result<(RgbImage, Vec<Option<usize>>)> {
    let prepared = Prepared::<S>::new(&Request::new(desc, (SIZE, SIZE), methods))?;
    Ok((prepared.render(1, None)?, prepared.object_map()?))
}
