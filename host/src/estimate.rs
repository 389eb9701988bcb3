//! What a frame of a scene takes on a board, estimated before any firmware is built: the
//! scene's textbook operations per pixel, counted on the host ([`operations::count`]: every ray
//! it traces, with its samples, shadow samples, reflections and a mesh's box tests), times the
//! instructions and cycles an operation takes on the board's processor, at the board's clock
//! with the rows shared between its cores.
//!
//! The instructions and cycles ([`crate::cycles`]) an operation takes are those of the committed QEMU run of the built-in
//! scene most like it ([`Alike`]) — `host/scenes/teapot.toml` for a scene with a mesh, `focus`
//! with a lens, `soft` with area lights, `whitted` (the lecture's) otherwise — divided by that
//! scene's operations counted in the same format: the count weighs a product, a quotient and a
//! root alike, and box tests, a lens's and a disc's sample points change the mix. Each
//! `host/images/firmware/T-S.json` is written by `obscura firmware --target T --scene S
//! --format F,… --json host/images/firmware/T-S.json`, one scene in one image with the formats
//! it lists (a figure a percent or two from a one-format image's); a 32-bit fixed split it lacks
//! is priced by another split's run ([`Alike::run`]), a format it lacks by `whitted`'s.
//! `obscura firmware` measures what this estimates.

use crate::firmware::{self, Board, FrameTime, Target};
use crate::operations;
use crate::render::Request;
use anyhow::Result;
use obscura::{Methods, RowOrder, SceneDesc};
use obscura_scene::firmware::SIDE;
use obscura_scene::{Format, NamedScene};
use serde::Deserialize;

/// A firmware run, as `obscura firmware --json` writes it (the fields read here).
#[derive(Debug, Deserialize)]
struct Run {
    format: String,
    instructions_per_pixel: u64,
    cycles_per_pixel: u64,
}

/// What a pixel took in a run, or takes in an estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PerPixel {
    /// Instructions.
    pub instructions: f64,
    /// Cycles on the board's core.
    pub cycles: f64,
}

impl PerPixel {
    fn scaled(self, factor: f64) -> Self {
        Self {
            instructions: self.instructions * factor,
            cycles: self.cycles * factor,
        }
    }
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

    /// The scene, as `obscura firmware --scene` names it (a file from the workspace's root).
    const fn scene(self) -> &'static str {
        match self {
            Self::Lecture => "whitted",
            Self::Mesh => "host/scenes/teapot.toml",
            Self::Lens => "focus",
            Self::AreaLights => "soft",
        }
    }

    /// The scene, loaded (a file from the workspace the harness was built from).
    fn load(self) -> Result<NamedScene> {
        let file = firmware::workspace().join(self.scene());
        if file.is_file() {
            obscura_scene::load(&file.to_string_lossy())
        } else {
            obscura_scene::load(self.scene())
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
            (Target::M33, Self::Lecture) => include_str!("../images/firmware/m33-whitted.json"),
            (Target::M33, Self::Mesh) => include_str!("../images/firmware/m33-teapot.json"),
            (Target::M33, Self::Lens) => include_str!("../images/firmware/m33-focus.json"),
            (Target::M33, Self::AreaLights) => include_str!("../images/firmware/m33-soft.json"),
            (Target::Rv32, Self::Lecture) => include_str!("../images/firmware/rv32-whitted.json"),
            (Target::Rv32, Self::Mesh) => include_str!("../images/firmware/rv32-teapot.json"),
            (Target::Rv32, Self::Lens) => include_str!("../images/firmware/rv32-focus.json"),
            (Target::Rv32, Self::AreaLights) => include_str!("../images/firmware/rv32-soft.json"),
        };
        serde_json::from_str(json).expect("the committed firmware runs are obscura firmware's JSON")
    }

    /// Its run that prices `format`: the run in `format`, else for a 32-bit fixed split one in
    /// another split — `i16f16` last, whose products the M0 forms from their middle 32 bits
    /// (compare its run with `i12f20`'s in `host/images/firmware/m0-whitted.json`).
    fn run(self, target: Target, format: Format) -> Option<(Format, PerPixel)> {
        let runs: Vec<(Format, PerPixel)> = self
            .runs(target)
            .iter()
            .filter_map(|r| {
                let took = PerPixel {
                    instructions: r.instructions_per_pixel as f64,
                    cycles: r.cycles_per_pixel as f64,
                };
                Some((Format::from_name(&r.format)?, took))
            })
            .collect();
        let find = |priced: &dyn Fn(Format) -> bool| runs.iter().copied().find(|&(f, _)| priced(f));
        let split = |ran: Format| {
            ran.is_fixed_32() && format.is_fixed_32() && ran.narrow() == format.narrow()
        };
        find(&|ran| ran == format)
            .or_else(|| find(&|ran| split(ran) && ran != Format::I16f16))
            .or_else(|| find(&split))
    }
}

/// The run that prices an operation: of the scene most like the one estimated, or else of
/// `whitted`, in `format` or its kin ([`Alike::run`]).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Pricing {
    scene: Alike,
    format: Format,
    took: PerPixel,
}

impl Pricing {
    fn of(target: Target, format: Format, alike: Alike) -> Option<Self> {
        [alike, Alike::Lecture].into_iter().find_map(|scene| {
            let (format, took) = scene.run(target, format)?;
            Some(Self {
                scene,
                format,
                took,
            })
        })
    }

    /// The instructions and cycles an operation takes: the run's, over its scene's operations
    /// counted.
    fn per_operation(self) -> Result<PerPixel> {
        let scene = self.scene.load()?;
        let operations = operations_per_pixel(self.format, &scene.scene.desc(), Methods::LECTURE)?;
        Ok(self.took.scaled(1.0 / operations))
    }
}

/// A frame's estimated cost on a board.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// The board.
    pub board: Board,
    /// Instructions and cycles per pixel.
    pub per_pixel: PerPixel,
    /// Seconds tracing a frame.
    pub tracing: f64,
    /// The scene whose firmware run priced an operation, as `obscura firmware --scene` names it.
    pub priced_by: &'static str,
    /// The format of that run.
    pub priced_in: Format,
}

impl Estimate {
    /// The frame drawn in `order` as the board draws it: tracing, sending, and both
    /// ([`Board::frame_time`]).
    pub fn time(&self, order: RowOrder) -> FrameTime {
        self.board.frame_time(self.tracing, order, SIDE, SIDE)
    }
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
    let Some(pricing) = Pricing::of(target, format, Alike::of(desc)) else {
        return Ok(None);
    };
    let board = target.board();
    let per_pixel = pricing
        .per_operation()?
        .scaled(operations_per_pixel(format, desc, methods)?);
    let pixels = f64::from(SIDE) * f64::from(SIDE);
    Ok(Some(Estimate {
        board,
        per_pixel,
        tracing: board.seconds((per_pixel.cycles * pixels) as u64),
        priced_by: pricing.scene.scene(),
        priced_in: pricing.format,
    }))
}

/// The textbook operations a pixel of a `SIDE`×`SIDE` frame of `desc` takes, counted.
fn operations_per_pixel(format: Format, desc: &SceneDesc<'_>, methods: Methods) -> Result<f64> {
    let request = Request::new(*desc, (SIDE, SIDE), methods);
    let (count, _) = operations::count(format, &request)?;
    Ok(count.operations_per_pixel())
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALIKE: [Alike; 4] = [Alike::Lecture, Alike::Mesh, Alike::Lens, Alike::AreaLights];

    #[test]
    fn every_firmware_format_is_priced_on_both_targets_in_every_kind_of_scene() {
        for target in [Target::M4f, Target::M0, Target::M33, Target::Rv32] {
            for alike in ALIKE {
                for &format in Format::FIRMWARE {
                    let pricing = Pricing::of(target, format, alike);
                    assert!(
                        pricing.is_some_and(|p| p.took.instructions > 0.0
                            && p.took.cycles >= p.took.instructions
                            && (p.format == format
                                || p.format.is_fixed_32()
                                    && format.is_fixed_32()
                                    && p.format.narrow() == format.narrow())),
                        "{format} on {target:?} like {alike:?}: {pricing:?}"
                    );
                }
            }
        }
        // A split is priced by another split before i16f16, whose shift the M0 folds.
        let pricing = Pricing::of(Target::M0, Format::I14f18, Alike::Lecture).unwrap();
        assert_eq!(pricing.format, Format::I12f20);
    }

    #[test]
    fn each_kind_of_scene_is_priced_by_its_own_runs() {
        for alike in ALIKE {
            let scene = alike.load().unwrap();
            assert_eq!(Alike::of(&scene.scene.desc()), alike);
            for target in [Target::M4f, Target::M0, Target::M33, Target::Rv32] {
                for run in alike.runs(target) {
                    let format = Format::from_name(&run.format).unwrap();
                    assert_eq!(Pricing::of(target, format, alike).unwrap().scene, alike);
                }
            }
        }
    }

    /// The estimate of `scene` against what `obscura firmware --target T --scene S --format F`
    /// measured under QEMU, within `tolerance`.
    fn near(target: Target, scene: &str, format: Format, measured: f64, tolerance: f64) {
        let named = obscura_scene::load(scene).unwrap();
        let estimate = frame(target, format, &named.scene.desc(), Methods::LECTURE)
            .unwrap()
            .unwrap();
        let ratio = estimate.per_pixel.instructions / measured;
        assert!(
            (ratio - 1.0).abs() < tolerance,
            "{scene} in {format} on {target:?}: {:.0} estimated, {measured} measured",
            estimate.per_pixel.instructions
        );
    }

    #[test]
    fn a_scene_like_its_pricing_scene_is_estimated_within_ten_per_cent() {
        near(Target::M4f, "shapes", Format::I16f16, 1577.0, 0.1);
        near(Target::M0, "shapes", Format::I16f16, 3548.0, 0.1);
        near(Target::M0, "shapes", Format::I12f20, 4991.0, 0.1);
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
                .tracing
        };
        assert!(
            cost(&all) > 8.0 * cost(&one),
            "{} {}",
            cost(&all),
            cost(&one)
        );
    }
}
