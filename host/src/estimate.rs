//! What a frame of a scene takes on a board, estimated before any firmware is built: the
//! scene's textbook operations per pixel, counted on the host ([`operations::count`]: every ray
//! it traces, with its samples, shadow samples, reflections and a mesh's box tests), times the
//! instructions an operation takes on the board's processor, at the board's clock with the rows
//! shared between its cores.
//!
//! The instructions an operation takes are those of the committed QEMU run of the built-in
//! scene most like it ([`Alike`]) — `host/scenes/teapot.toml` for a scene with a mesh, `focus`
//! with a lens, `soft` with area lights, `whitted` (the lecture's) otherwise — divided by that
//! scene's operations counted in the same format: the count weighs a product, a quotient and a
//! root alike, and box tests, a lens's and a disc's sample points change the mix. Each
//! `host/images/firmware/T-S.json` is written by `obscura firmware --target T --scene S
//! --format F,… --json host/images/firmware/T-S.json`, one scene an image, for the formats it
//! lists; a 32-bit fixed split is priced by the file's 32-bit fixed run (the same code but for
//! the shifts), a format the file lacks by `whitted`'s. `obscura firmware` measures what this
//! estimates.

use crate::firmware::{self, Board, Target};
use crate::operations;
use crate::render::Request;
use anyhow::Result;
use obscura::{Methods, SceneDesc};
use obscura_scene::firmware::SIDE;
use obscura_scene::{Format, NamedScene};
use serde::Deserialize;

/// A firmware run, as `obscura firmware --json` writes it (the fields read here).
#[derive(Debug, Deserialize)]
struct Run {
    format: String,
    instructions_per_pixel: u64,
}

/// The scenes whose firmware runs price an operation, by what a scene has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Alike {
    /// Spheres, planes and triangles lit by points: `whitted`.
    Lecture,
    /// A mesh: `host/scenes/teapot.toml`.
    Mesh,
    /// A lens: `focus`.
    Lens,
    /// Area lights: `soft`.
    AreaLights,
}

impl Alike {
    /// What `desc` is most like, the first of a mesh, a lens and area lights it has.
    fn of(desc: &SceneDesc<'_>) -> Self {
        if !desc.meshes.triangles.is_empty() {
            Self::Mesh
        } else if desc.camera.aperture > 0.0 {
            Self::Lens
        } else if desc.shadow_samples > 1 && desc.lights.iter().any(|l| l.radius > 0.0) {
            Self::AreaLights
        } else {
            Self::Lecture
        }
    }

    /// The scene's name.
    const fn name(self) -> &'static str {
        match self {
            Self::Lecture => "whitted",
            Self::Mesh => "teapot",
            Self::Lens => "focus",
            Self::AreaLights => "soft",
        }
    }

    /// The scene, loaded as `obscura firmware --scene` names it (a file from the workspace).
    fn load(self) -> Result<NamedScene> {
        if self == Self::Mesh {
            let file = firmware::workspace().join("host/scenes/teapot.toml");
            obscura_scene::load(&file.to_string_lossy())
        } else {
            obscura_scene::load(self.name())
        }
    }

    /// Its committed runs on `target`.
    fn runs(self, target: Target) -> Vec<Run> {
        let json = match (target, self) {
            (Target::M4f, Self::Lecture) => include_str!("../images/firmware/m4f-whitted.json"),
            (Target::M4f, Self::Mesh) => include_str!("../images/firmware/m4f-teapot.json"),
            (Target::M4f, Self::Lens) => include_str!("../images/firmware/m4f-focus.json"),
            (Target::M4f, Self::AreaLights) => include_str!("../images/firmware/m4f-soft.json"),
            (Target::M0, Self::Lecture) => include_str!("../images/firmware/m0-whitted.json"),
            (Target::M0, Self::Mesh) => include_str!("../images/firmware/m0-teapot.json"),
            (Target::M0, Self::Lens) => include_str!("../images/firmware/m0-focus.json"),
            (Target::M0, Self::AreaLights) => include_str!("../images/firmware/m0-soft.json"),
        };
        serde_json::from_str(json).expect("the committed firmware runs are obscura firmware's JSON")
    }

    /// The run that prices `format`: in it, else in a 32-bit fixed split when it is one.
    fn run(self, target: Target, format: Format) -> Option<(Format, u64)> {
        let runs: Vec<(Format, u64)> = self
            .runs(target)
            .iter()
            .filter_map(|r| Some((Format::from_name(&r.format)?, r.instructions_per_pixel)))
            .collect();
        let kin = |ran: Format| ran.is_fixed_32() && format.is_fixed_32();
        let find = |priced: &dyn Fn(Format) -> bool| runs.iter().copied().find(|&(f, _)| priced(f));
        find(&|ran| ran == format).or_else(|| find(&kin))
    }
}

/// A frame's estimated cost on a board.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// The board.
    pub board: Board,
    /// Instructions per pixel.
    pub instructions_per_pixel: f64,
    /// Seconds per frame.
    pub seconds: f64,
    /// The scene whose firmware run priced an operation.
    pub priced_by: &'static str,
}

/// The estimate for a `SIDE`×`SIDE` frame of `desc` in `format` by `methods` on `target`'s
/// board, or `None` for a format no firmware runs (f64).
///
/// # Errors
/// Where the scene cannot be rendered in `format` (as [`operations::count`]).
pub fn frame(
    target: Target,
    format: Format,
    desc: &SceneDesc<'_>,
    methods: Methods,
) -> Result<Option<Estimate>> {
    let Some((per_operation, priced_by)) =
        instructions_per_operation(target, format, Alike::of(desc))?
    else {
        return Ok(None);
    };
    let board = target.board();
    let instructions_per_pixel = per_operation * operations_per_pixel(format, desc, methods)?;
    let pixels = f64::from(SIDE) * f64::from(SIDE);
    Ok(Some(Estimate {
        board,
        instructions_per_pixel,
        seconds: board.seconds((instructions_per_pixel * pixels) as u64),
        priced_by: priced_by.name(),
    }))
}

/// The instructions an operation of `format` takes on `target` in a scene like `alike`, by
/// its committed run (or else `whitted`'s), and the scene whose run it is; `None` without one.
fn instructions_per_operation(
    target: Target,
    format: Format,
    alike: Alike,
) -> Result<Option<(f64, Alike)>> {
    for alike in [alike, Alike::Lecture] {
        if let Some((ran, instructions_per_pixel)) = alike.run(target, format) {
            let scene = alike.load()?;
            let operations = operations_per_pixel(ran, &scene.scene.desc(), Methods::LECTURE)?;
            return Ok(Some((instructions_per_pixel as f64 / operations, alike)));
        }
    }
    Ok(None)
}

/// The textbook operations a pixel of a `SIDE`×`SIDE` frame of `desc` takes, counted.
fn operations_per_pixel(format: Format, desc: &SceneDesc<'_>, methods: Methods) -> Result<f64> {
    let request = Request {
        desc,
        width: SIDE,
        height: SIDE,
        methods,
    };
    let (count, _) = operations::count(format, &request)?;
    Ok(count.operations_per_pixel())
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALIKE: [Alike; 4] = [Alike::Lecture, Alike::Mesh, Alike::Lens, Alike::AreaLights];

    #[test]
    fn every_firmware_format_is_priced_on_both_targets_in_every_kind_of_scene() {
        for target in [Target::M4f, Target::M0] {
            for alike in ALIKE {
                for &format in Format::FIRMWARE {
                    let priced = alike
                        .run(target, format)
                        .or(Alike::Lecture.run(target, format));
                    assert!(
                        priced.is_some_and(|(_, instructions)| instructions > 0),
                        "{format} on {target:?} like {alike:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn each_kind_of_scene_is_priced_by_its_own_runs() {
        for alike in ALIKE {
            let scene = alike.load().unwrap();
            assert_eq!(Alike::of(&scene.scene.desc()), alike);
        }
    }

    #[test]
    fn a_committed_run_is_estimated_as_it_was_measured() {
        for (target, alike) in [
            (Target::M4f, Alike::Lecture),
            (Target::M0, Alike::Lecture),
            (Target::M4f, Alike::AreaLights),
        ] {
            let scene = alike.load().unwrap();
            let run = &alike.runs(target)[0];
            let format = Format::from_name(&run.format).unwrap();
            let estimate = frame(target, format, &scene.scene.desc(), Methods::LECTURE)
                .unwrap()
                .unwrap();
            let ratio = estimate.instructions_per_pixel / run.instructions_per_pixel as f64;
            assert!(
                (ratio - 1.0).abs() < 1e-9,
                "{alike:?} in {format} on {target:?}"
            );
            assert_eq!(estimate.priced_by, alike.name());
        }
    }

    #[test]
    fn every_ray_counts() {
        // Sixteen shadow rays a point, every one traced, cost more than one.
        let scene = Alike::AreaLights.load().unwrap();
        let soft = scene.scene.desc();
        let one = SceneDesc {
            shadow_samples: 1,
            ..soft
        };
        let all = SceneDesc {
            adaptive_shadows: false,
            ..soft
        };
        let cost = |desc: &SceneDesc<'_>| {
            frame(Target::M0, Format::I16f16, desc, Methods::LECTURE)
                .unwrap()
                .unwrap()
                .seconds
        };
        assert!(
            cost(&all) > 8.0 * cost(&one),
            "{} {}",
            cost(&all),
            cost(&one)
        );
    }
}
