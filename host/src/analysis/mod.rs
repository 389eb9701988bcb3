//! `obscura analyze` and `--format auto`: how large and how fine a scene's numbers get, which
//! formats hold it (as it is, or rescaled about the eye), the error each is predicted to make
//! at most ([`predict`]), and the cheapest that reaches a target, measured on the host, whose
//! renders are the firmware's bits.

mod predict;

pub(crate) use predict::pixel_angle;
pub use predict::{Prediction, Reference};

use crate::checked::Checked;
use crate::cost::{Machine, cost, pixels_factor};
use crate::metrics::{Accuracy, accuracy, psnr_db};
use crate::render::{
    AnyFormat, HostScene, Request, all_cores, exact_roots, prepare, prepare_reference,
};
use anyhow::{Result, bail};
use image::RgbImage;
use obscura::methods::MethodName;
use obscura::scalar::FormatInfo;
use obscura::scene::range::{self, Feature, Magnitude};
use obscura::{
    Item, Methods, Pixels, Scalar, SceneDesc, SceneError, ShapeDesc, SphereMethod, TriangleMethod,
    Vec3,
};
use obscura_scene::firmware::SIDE;
use obscura_scene::{Format, FormatJob, NamedScene, OwnedScene};

/// The largest power of two a scene is rescaled by, either way.
const MAX_RESCALE_POWER: i32 = 24;

/// What the analysis finds.
#[derive(Debug)]
pub struct Analysis {
    /// Where things are.
    pub extents: Extents,
    /// The integer and fraction bits each kind of computation needs, per method.
    pub bits: Vec<Bits>,
    /// Each format's verdict.
    pub verdicts: Vec<Verdict>,
    /// Whether the scene has triangles (which decides the chart scene it is priced like).
    pub has_triangles: bool,
}

/// Where the scene's things are, relative to the eye.
#[derive(Debug, PartialEq)]
pub struct Extents {
    /// How many objects and lights.
    pub objects: usize,
    /// How many lights.
    pub lights: usize,
    /// The world radius `far`.
    pub world: f64,
    /// The box around the spheres and triangles (planes are unbounded), if any.
    pub bounds: Option<([f64; 3], [f64; 3])>,
    /// The nearest any surface comes to the eye (less a lens's aperture).
    pub nearest: f64,
    /// The farthest point of a bounded object from the eye (the world radius with a plane).
    pub farthest: f64,
    /// The smallest sphere radius, and its object.
    pub smallest_radius: Option<(f64, usize)>,
    /// The shortest triangle edge, and its object.
    pub shortest_edge: Option<(f64, usize)>,
    /// The smallest checker square, and its object.
    pub smallest_square: Option<(f64, usize)>,
}

/// What one kind of computation needs, by one method: the bits a fixed format must have.
#[derive(Debug)]
pub struct Bits {
    /// "sphere by quadratic", "triangle by watertight", "rays, points and colours", ...
    pub computation: String,
    /// Its largest intermediate value.
    pub largest: Option<Magnitude>,
    /// Integer bits, sign included, that hold it.
    pub integer: u32,
    /// Its most demanding feature (the one that needs the most fraction bits).
    pub finest: Option<Feature>,
    /// Fraction bits that resolve every feature.
    pub fraction: u32,
}

/// Whether a format holds the scene.
#[derive(Debug, Clone, PartialEq)]
pub enum Fit {
    /// As it is.
    Holds,
    /// Only rescaled about the eye by this factor (which leaves the image unchanged).
    Rescaled(f64),
    /// Not at all: the scene build's reason.
    Refused(String),
}

/// One format's verdict.
#[derive(Debug)]
pub struct Verdict {
    /// The format.
    pub format: Format,
    /// Whether it holds the scene.
    pub fit: Fit,
    /// What the model predicts, where it holds the scene.
    pub prediction: Option<Prediction>,
}

impl Verdict {
    /// Format `format`'s verdict on `scene` by `methods`, whose f64 `reference` is rendered at
    /// the size to analyse.
    pub fn of(format: Format, scene: &OwnedScene, methods: Methods, reference: &Reference) -> Self {
        let fit = fit(format, scene, methods, reference.image.dimensions());
        // A rescaled scene is predicted as it will be rendered: the same image, but the
        // nearest surface at another distance and the constants of another size.
        let prediction = match fit {
            Fit::Holds => predict::predict(format, &scene.desc(), methods, reference).ok(),
            Fit::Rescaled(factor) => {
                let rescaled = scene.scaled(factor as f32);
                predict::predict(format, &rescaled.desc(), methods, reference).ok()
            }
            Fit::Refused(_) => None,
        };
        Self {
            format,
            fit,
            prediction,
        }
    }
}

impl Analysis {
    /// Analyses `scene` rendered at `width × height` by `methods`.
    ///
    /// # Errors
    /// When the scene is invalid or too large even for f64: no format can hold it.
    pub fn of(scene: &OwnedScene, methods: Methods, width: u32, height: u32) -> Result<Self> {
        let desc = scene.desc();
        let reference = reference(&desc, methods, (width, height))
            .map_err(|error| error.context("no format can hold the scene"))?;
        Ok(Self::with_reference(scene, methods, &reference))
    }

    /// [`Self::of`] for the f64 `reference` of the scene, already rendered at the size to
    /// analyse.
    pub fn with_reference(scene: &OwnedScene, methods: Methods, reference: &Reference) -> Self {
        Self::with_verdicts(scene, methods, |format| {
            Verdict::of(format, scene, methods, reference)
        })
    }

    /// [`Self::of`] without the model's predictions, which cost several renders of the scene:
    /// which formats hold it, for `--format auto`, which measures what it picks.
    ///
    /// # Errors
    /// As [`Self::of`].
    pub fn fits(scene: &OwnedScene, methods: Methods, width: u32, height: u32) -> Result<Self> {
        let size = (width, height);
        builds(Format::F64, &scene.desc(), methods, size)
            .map_err(|error| anyhow::Error::new(error).context("no format can hold the scene"))?;
        Ok(Self::with_verdicts(scene, methods, |format| Verdict {
            format,
            fit: fit(format, scene, methods, size),
            prediction: None,
        }))
    }

    /// The analysis of `scene` by `methods` with each format's `verdict`.
    fn with_verdicts(
        scene: &OwnedScene,
        methods: Methods,
        verdict: impl Fn(Format) -> Verdict,
    ) -> Self {
        let desc = scene.desc();
        Self {
            extents: extents(&desc),
            bits: bits(&desc, methods),
            verdicts: Format::ALL.iter().map(|&format| verdict(format)).collect(),
            has_triangles: desc.has_triangles(),
        }
    }

    /// The scene's 32-bit split: of the 32-bit fixed formats that hold it as it is (or, with
    /// `rescaled`, rescaled about the eye), the one with the most fraction bits, which gives the
    /// scene the integer bits its largest intermediate needs (as the range proof counts them)
    /// and the rest to the fraction.
    pub fn split(&self, rescaled: bool) -> Option<Format> {
        split(&[self], rescaled)
    }

    /// What `format` by `methods` costs per pixel on `machine` in this scene with `pixels`, by
    /// the charts ([`cost`] times [`pixels_factor`]).
    pub fn cost(
        &self,
        machine: Machine,
        format: Format,
        methods: &Methods,
        pixels: Pixels,
    ) -> Option<f64> {
        let factor = pixels_factor(machine, format, pixels, self.has_triangles)?;
        Some(cost(machine, format, methods, self.has_triangles)? * factor)
    }
}

/// The 32-bit fixed format with the most fraction bits that holds every scene analysed as it
/// is, or with `rescaled` also rescaled about the eye.
fn split(analyses: &[&Analysis], rescaled: bool) -> Option<Format> {
    let holds = |format: Format| {
        analyses.iter().all(|analysis| {
            analysis.verdicts.iter().any(|v| {
                v.format == format
                    && match v.fit {
                        Fit::Holds => true,
                        Fit::Rescaled(_) => rescaled,
                        Fit::Refused(_) => false,
                    }
            })
        })
    };
    Format::ALL
        .iter()
        .copied()
        .filter(|&format| format.is_fixed_32() && holds(format))
        .max_by_key(|format| format.split().map(|(_, fraction)| fraction))
}

/// A format `--format auto` measured, and what it measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Pick {
    /// The format.
    pub format: Format,
    /// The pixels: the scenes' own, or those `auto` chose ([`Aim::choose_pixels`]).
    pub pixels: Pixels,
    /// The factor the scene is rescaled by about the eye, when the format holds it only so.
    pub rescaled: Option<f64>,
    /// Its PSNR against f64, measured on the host (which computes the firmware's bits), in dB:
    /// the lowest over the scenes.
    pub psnr_db: f64,
    /// The PSNR against f64 the model predicts it to reach at least, in dB: the lowest over the
    /// scenes (`None` where it predicts none).
    pub predicted_db: Option<f64>,
}

impl Pick {
    /// `scene` as the pick renders it: rescaled about the eye where the format holds it only so,
    /// with the pixels picked.
    #[must_use]
    pub fn scene(&self, scene: &OwnedScene) -> OwnedScene {
        let mut scene = self
            .rescaled
            .map_or_else(|| scene.clone(), |factor| scene.scaled(factor as f32));
        scene.pixels = self.pixels;
        scene
    }

    /// The format, and the pixels where they are adaptive ([`with_pixels`]).
    #[must_use]
    pub fn named(&self) -> String {
        with_pixels(self.format, self.pixels)
    }
}

/// `format`, and `pixels` where they are adaptive: `i16f16 with adaptive:4 pixels`.
#[must_use]
pub fn with_pixels(format: Format, pixels: Pixels) -> String {
    match pixels {
        Pixels::Exact => format.to_string(),
        pixels => format!("{format} with {} pixels", pixels.name()),
    }
}

/// What `--format auto` aims at.
#[derive(Clone, Copy, Debug)]
pub struct Aim {
    /// The machine whose cost it minimises, as the charts measured it.
    pub machine: Machine,
    /// The PSNR against f64, in dB, it must reach on every scene.
    pub target_psnr: f64,
    /// Whether a format that holds a scene only rescaled about the eye may render it so (a
    /// firmware, whose scenes are built in, cannot).
    pub rescale: bool,
    /// Whether it may pick adaptive pixels (`adaptive:2`, `4`, `8`, where every scene takes
    /// them), priced by the chart's pixels axis; otherwise each scene keeps its own.
    pub choose_pixels: bool,
}

/// What `--format auto` found.
#[derive(Clone, Debug, PartialEq)]
pub enum Choice {
    /// The cheapest format that reaches the target.
    Reaches(Pick),
    /// No format reaches the target: the one that comes closest.
    Closest(Pick),
    /// No format holds every scene.
    Nothing,
}

impl Choice {
    /// Why no format is picked for `target_psnr` dB: the one that comes closest, what it is
    /// predicted and measured to reach, and the `--target-psnr` that would take it; or that
    /// no format holds the scenes. `None` when one reaches it.
    #[must_use]
    pub fn shortfall(&self, target_psnr: f64) -> Option<String> {
        match self {
            Self::Reaches(_) => None,
            Self::Nothing => Some(format!(
                "no format holds the scene and reaches {target_psnr} dB; change the scene as \
                 `obscura analyze` says"
            )),
            Self::Closest(pick) => {
                let predicted = pick.predicted_db.map_or(String::new(), |db| {
                    format!("predicted to reach at least {db:.1} dB and ")
                });
                let how = pick.rescaled.map_or(String::new(), |factor| {
                    format!(" rescaled ×{factor} about the eye")
                });
                // Rounded down, so that the target it names takes the format; the measurement
                // to a digit more, so that it never reads as less than that target.
                let accepting = (pick.psnr_db * 10.0).floor() / 10.0;
                Some(format!(
                    "no format reaches {target_psnr} dB; the closest is {}{how}, {predicted}\
                     measured at {:.2} dB: --target-psnr {accepting:.1} accepts it",
                    pick.named(),
                    pick.psnr_db
                ))
            }
        }
    }
}

/// The cheapest format on `aim`'s machine (by the committed charts) that holds every one of
/// `scenes` (each with its analysis at `size` by `methods`) and, rendered on the host, reaches
/// the target PSNR against f64 on each: the formats, and where `aim` chooses pixels each with
/// exact and adaptive pixels, are measured cheapest first, and the first that reaches it is
/// taken. Where none reaches it, every candidate has been measured, and the one measured
/// closest is said.
///
/// # Errors
/// When a render fails.
pub fn pick(
    scenes: &[(&OwnedScene, &Analysis)],
    methods: Methods,
    size: (u32, u32),
    aim: Aim,
) -> Result<Choice> {
    let own = scenes
        .first()
        .map_or(Pixels::Exact, |(scene, _)| scene.pixels);
    let pixels: Vec<Pixels> = if aim.choose_pixels {
        Pixels::ALL
            .iter()
            .map(|&(pixels, _)| pixels)
            .filter(|&pixels| {
                scenes
                    .iter()
                    .all(|(scene, _)| scene.desc().takes_pixels(pixels).is_ok())
            })
            .collect()
    } else {
        vec![own]
    };
    // Every format is priced by what it costs itself: the 32-bit splits run the same code but
    // for their shifts, which a machine folds into its products for one split and not for
    // another (the M0's partial products, for i16f16). Where the chart prices two alike, the
    // more precise, earlier in `Format::ALL`, stays first; of a format's pixels, exact.
    let mut candidates: Vec<(f64, Format, Pixels)> = Format::ALL
        .iter()
        .flat_map(|&format| pixels.iter().map(move |&pixels| (format, pixels)))
        .filter_map(|(format, pixels)| {
            let costs = scenes
                .iter()
                .map(|(_, analysis)| {
                    let verdict = analysis.verdicts.iter().find(|v| v.format == format)?;
                    let usable = match verdict.fit {
                        Fit::Holds => true,
                        Fit::Rescaled(_) => aim.rescale,
                        Fit::Refused(_) => false,
                    };
                    // Pixels kept as the scenes have them leave the formats' order as it is.
                    let priced = if aim.choose_pixels {
                        pixels
                    } else {
                        Pixels::Exact
                    };
                    usable
                        .then(|| analysis.cost(aim.machine, format, &methods, priced))
                        .flatten()
                })
                .collect::<Option<Vec<f64>>>()?;
            Some((costs.iter().sum(), format, pixels))
        })
        .collect();
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut closest: Option<Pick> = None;
    for (_, format, pixels) in candidates {
        let mut measured = Pick {
            format,
            pixels,
            rescaled: None,
            psnr_db: f64::INFINITY,
            predicted_db: None,
        };
        for &(_, analysis) in scenes {
            let verdict = analysis.verdicts.iter().find(|v| v.format == format);
            // The model bounds a format's rounding, not what blocks fill in.
            let prediction = verdict.and_then(|v| v.prediction);
            if let Some(p) = prediction.filter(|_| pixels == Pixels::Exact) {
                let db = measured
                    .predicted_db
                    .map_or(p.psnr_db, |db| db.min(p.psnr_db));
                measured.predicted_db = Some(db);
            }
            if let Some(Fit::Rescaled(factor)) = verdict.map(|v| &v.fit) {
                measured.rescaled = Some(*factor);
            }
        }
        for &(scene, _) in scenes {
            let db = measure(format, &measured.scene(scene), methods, size)?;
            measured.psnr_db = measured.psnr_db.min(db);
        }
        if measured.psnr_db >= aim.target_psnr {
            return Ok(Choice::Reaches(measured));
        }
        if closest
            .as_ref()
            .is_none_or(|c| measured.psnr_db > c.psnr_db)
        {
            closest = Some(measured);
        }
    }
    let Some(mut closest) = closest else {
        return Ok(Choice::Nothing);
    };
    if closest.predicted_db.is_none() {
        closest.predicted_db = predicted_worst(&closest, scenes, methods, size);
    }
    Ok(Choice::Closest(closest))
}

/// The lowest PSNR the model predicts for `pick`'s format over `scenes` at `size` by `methods`
/// (each rescaled as the pick renders it), for analyses made without predictions; `None` where
/// it predicts none, or the pick's pixels are adaptive (the model bounds a format's rounding,
/// not what blocks fill in).
fn predicted_worst(
    pick: &Pick,
    scenes: &[(&OwnedScene, &Analysis)],
    methods: Methods,
    size: (u32, u32),
) -> Option<f64> {
    if pick.pixels != Pixels::Exact {
        return None;
    }
    scenes
        .iter()
        .map(|&(scene, _)| {
            let reference = reference(&scene.desc(), methods, size).ok()?;
            let scene = pick.scene(scene);
            let prediction = predict::predict(pick.format, &scene.desc(), methods, &reference);
            prediction.ok().map(|p| p.psnr_db)
        })
        .try_fold(f64::INFINITY, |worst, db| db.map(|db| worst.min(db)))
}

/// The PSNR against f64, in dB, that `--format auto` and `analyze` aim for unless told.
pub const TARGET_PSNR: f64 = 40.0;

/// The PSNR against f64, in dB, below which `render`, `compare`, `preview` and `obscura
/// firmware` refuse a format given that measures there, unless told to draw it anyway: a
/// picture that far from f64 is no longer the scene's. (`chart`, `stress` and `fuzz` measure
/// such formats on purpose.)
pub const USELESS_PSNR: f64 = 20.0;

/// Refuses `drawn`, `format`'s image of `scene` by `methods`, where it measures below `floor`
/// dB against `truth`, f64's image of it: with the measurement, the formats the model
/// predicts to reach `floor` as the scene is, and the changes of one method that it predicts
/// make `format` reach it. (The model is consulted only to refuse: a measurement costs one f64
/// render, a prediction several.)
///
/// # Errors
/// The refusal.
pub fn refuse_useless(
    format: Format,
    scene: &OwnedScene,
    methods: Methods,
    [drawn, truth]: [&RgbImage; 2],
    floor: f64,
) -> Result<()> {
    let psnr = psnr_db(drawn, truth);
    if psnr >= floor {
        return Ok(());
    }
    let desc = scene.desc();
    let size = drawn.dimensions();
    let predicted = |format: Format, methods: Methods, reference: &Reference| {
        predict::predict(format, &desc, methods, reference).map_or(f64::INFINITY, |p| p.psnr_db)
    };
    let formats: Vec<&str> = match reference(&desc, methods, size) {
        Ok(f64s) => Analysis::with_reference(scene, methods, &f64s)
            .verdicts
            .into_iter()
            .filter(|v| v.fit == Fit::Holds && v.prediction.is_some_and(|p| p.psnr_db >= floor))
            .map(|v| v.format.name())
            .collect(),
        Err(_) => Vec::new(),
    };
    let changes: Vec<String> = one_change(methods)
        .into_iter()
        .filter(|&other| {
            builds(format, &desc, other, size).is_ok()
                && reference(&desc, other, size)
                    .is_ok_and(|f64s| predicted(format, other, &f64s) >= floor)
        })
        .filter_map(|other| other.changed_from(&methods))
        .map(|(question, name)| format!("--{question} {name}"))
        .collect();
    let (width, height) = size;
    let mut message = format!(
        "{format} by {methods} measures only {psnr:.1} dB against f64 at {width}x{height}, \
         below the {floor} dB of --refuse-below (`obscura analyze` says why)"
    );
    if !formats.is_empty() {
        message += &format!("; formats predicted to reach it: {}", formats.join(" "));
    }
    if !changes.is_empty() {
        message += &format!("; in {format}, {}", changes.join(" or "));
    }
    message += "; or give --force to draw it anyway";
    bail!(message)
}

/// Every choice of methods that differs from `methods` in exactly one.
fn one_change(methods: Methods) -> Vec<Methods> {
    fn others<M: MethodName + PartialEq>(of: M) -> impl Iterator<Item = M> {
        M::ALL.iter().map(|&(m, _)| m).filter(move |&m| m != of)
    }
    let sphere = others(methods.sphere).map(|sphere| Methods { sphere, ..methods });
    let triangle = others(methods.triangle).map(|triangle| Methods {
        triangle,
        ..methods
    });
    let roots = others(methods.roots).map(|roots| Methods { roots, ..methods });
    let rays = others(methods.rays).map(|rays| Methods { rays, ..methods });
    let bias = others(methods.bias).map(|bias| Methods { bias, ..methods });
    sphere
        .chain(triangle)
        .chain(roots)
        .chain(rays)
        .chain(bias)
        .collect()
}

/// `--format auto` for a firmware: the cheapest format (and pixels, where `aim` chooses them)
/// on `aim`'s machine that holds every scene as it is (a firmware's scenes are built in: it
/// cannot rescale them) and reaches the target on each at the display's size, measured on the
/// host, whose frames are the firmware's.
///
/// # Errors
/// When no format does, or a render fails.
pub fn firmware_format(scenes: &[NamedScene], methods: Methods, aim: Aim) -> Result<Pick> {
    let analyses = scenes
        .iter()
        .map(|named| {
            Analysis::fits(&named.scene, methods, SIDE, SIDE).map_err(|error| named.locate(error))
        })
        .collect::<Result<Vec<_>>>()?;
    let pairs: Vec<_> = scenes.iter().map(|s| &s.scene).zip(&analyses).collect();
    let aim = Aim {
        rescale: false,
        ..aim
    };
    match pick(&pairs, methods, (SIDE, SIDE), aim)? {
        Choice::Reaches(pick) => Ok(pick),
        choice => bail!(
            "for a firmware: {}",
            choice.shortfall(aim.target_psnr).unwrap_or_default()
        ),
    }
}

/// The PSNR of `format` against f64 on `scene` at `size` by `methods`, measured.
///
/// # Errors
/// When either cannot build the scene, or a render fails.
pub fn measure(
    format: Format,
    scene: &OwnedScene,
    methods: Methods,
    size: (u32, u32),
) -> Result<f64> {
    let [contender, reference] = prepare_both(format, scene, methods, size)?;
    let threads = all_cores();
    Ok(psnr_db(
        &contender.render(threads, None)?,
        &reference.render(threads, None)?,
    ))
}

/// [`measure`], with the object mismatch and the other errors beside the PSNR.
///
/// # Errors
/// When either cannot build the scene, or a render fails.
pub fn measure_accuracy(
    format: Format,
    scene: &OwnedScene,
    methods: Methods,
    size: (u32, u32),
) -> Result<Accuracy> {
    let [contender, reference] = prepare_both(format, scene, methods, size)?;
    let threads = all_cores();
    Ok(accuracy(
        &contender.render(threads, None)?,
        &reference.render(threads, None)?,
        &contender.object_map()?,
        &reference.object_map()?,
    ))
}

/// `scene` at `size` by `methods` prepared in `format` and in f64, the reference: what
/// [`measure`] and [`measure_accuracy`] draw.
fn prepare_both(
    format: Format,
    scene: &OwnedScene,
    methods: Methods,
    size: (u32, u32),
) -> Result<[Box<dyn AnyFormat>; 2]> {
    let request = Request::new(scene.desc(), size, methods);
    Ok([prepare(format, &request)?, prepare_reference(&request)?])
}

/// The f64 reference of `desc` at `size` by `methods` (exact roots).
///
/// # Errors
/// When f64 cannot build the scene, or the render fails.
pub fn reference(desc: &SceneDesc<'_>, methods: Methods, size: (u32, u32)) -> Result<Reference> {
    Reference::render(&Request::new(*desc, size, exact_roots(methods)))
}

/// Whether `format` holds `scene` for `methods` at `size`: as it is, or rescaled about the eye
/// by the power of two nearest 1 that makes it fit, or not at all.
pub fn fit(format: Format, scene: &OwnedScene, methods: Methods, size: (u32, u32)) -> Fit {
    let reason = match builds(format, &scene.desc(), methods, size) {
        Ok(()) => return Fit::Holds,
        Err(error) => error,
    };
    if !matches!(
        reason,
        SceneError::OutOfRange { .. } | SceneError::BelowResolution { .. }
    ) {
        return Fit::Refused(reason.to_string());
    }
    (1..=MAX_RESCALE_POWER)
        .flat_map(|power| [power, -power])
        .map(|power| 2.0_f64.powi(power))
        .find(|&factor| builds(format, &scene.scaled(factor as f32).desc(), methods, size).is_ok())
        .map_or_else(
            || Fit::Refused(format!("{reason}; no rescaling helps")),
            Fit::Rescaled,
        )
}

/// Whether format `format` builds `desc` for `methods` and places its camera for an image of
/// `size`: what `render` needs.
fn builds(
    format: Format,
    desc: &SceneDesc<'_>,
    methods: Methods,
    (width, height): (u32, u32),
) -> Result<(), SceneError> {
    struct Build<'a>(&'a SceneDesc<'a>, Methods, u32, u32);
    impl FormatJob for Build<'_> {
        type Output = Result<(), SceneError>;
        fn run<S: Scalar>(self) -> Self::Output {
            HostScene::<S>::build_with(self.0, self.1)?.camera(self.2, self.3)?;
            Ok(())
        }
    }
    format.run::<Checked, _>(Build(desc, methods, width, height))
}

/// The scene's extents, relative to the eye.
pub fn extents(desc: &SceneDesc<'_>) -> Extents {
    let eye = Vec3::from_f32(desc.camera.eye);
    let mut bounds: Option<([f64; 3], [f64; 3])> = None;
    let mut grow = |p: Vec3<f64>, pad: f64| {
        let (lo, hi) = bounds.get_or_insert(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]));
        for (i, c) in [p.x, p.y, p.z].into_iter().enumerate() {
            lo[i] = lo[i].min(c - pad);
            hi[i] = hi[i].max(c + pad);
        }
    };
    let mut farthest: f64 = 0.0;
    let smallest = |best: &mut Option<(f64, usize)>, value: f64, i: usize| {
        if best.is_none_or(|(b, _)| value < b) {
            *best = Some((value, i));
        }
    };
    let (mut smallest_radius, mut shortest_edge, mut smallest_square) = (None, None, None);
    for (i, object) in desc.primitives() {
        match object.shape {
            ShapeDesc::Sphere { center, radius } => {
                let (c, r) = (Vec3::from_f32(center), f64::from(radius));
                grow(c, r);
                farthest = farthest.max((c - eye).length() + r);
                smallest(&mut smallest_radius, r, i);
            }
            ShapeDesc::Triangle { vertices } => {
                let corners = vertices.map(Vec3::from_f32);
                for (k, &p) in corners.iter().enumerate() {
                    grow(p, 0.0);
                    farthest = farthest.max((p - eye).length());
                    smallest(&mut shortest_edge, (corners[(k + 1) % 3] - p).length(), i);
                }
            }
            ShapeDesc::Plane { checker, .. } => {
                farthest = f64::from(desc.far);
                if let Some(checker) = checker {
                    smallest(&mut smallest_square, f64::from(checker.size), i);
                }
            }
            // Never a primitive: its triangles are.
            ShapeDesc::Mesh { .. } => {}
        }
    }
    // A lens's rays start up to its aperture nearer.
    let nearest = desc
        .primitives()
        .map(|(_, object)| range::clearance(&object, eye) - f64::from(desc.camera.aperture))
        .fold(f64::INFINITY, f64::min);
    Extents {
        objects: desc.objects.len(),
        lights: desc.lights.len(),
        world: f64::from(desc.far),
        bounds,
        nearest,
        farthest,
        smallest_radius,
        shortest_edge,
        smallest_square,
    }
}

/// The bits each kind of computation needs: the spheres by each sphere method, the triangles
/// by each triangle method (when there are any), and everything else.
fn bits(desc: &SceneDesc<'_>, methods: Methods) -> Vec<Bits> {
    let kind = |item: Item| match item {
        Item::Object(i) => desc.objects.get(i).map(|o| match o.shape {
            ShapeDesc::Sphere { .. } => "sphere",
            ShapeDesc::Plane { .. } => "plane",
            ShapeDesc::Triangle { .. } | ShapeDesc::Mesh { .. } => "triangle",
        }),
        _ => None,
    };
    let has = |shape: &str| {
        desc.objects
            .iter()
            .enumerate()
            .any(|(i, _)| kind(Item::Object(i)) == Some(shape))
    };
    let mut rows = Vec::new();
    let mut row = |computation: String, methods: Methods, of: &dyn Fn(Item) -> bool| {
        // The bounds as a format that rounds as finely as f64 would need them.
        let slack = range::origin_slack(desc, &methods, &FormatInfo::of::<f64>());
        let largest = range::magnitudes(desc, &methods, slack)
            .filter(|m| of(m.item))
            .max_by(|a, b| a.value.total_cmp(&b.value));
        let finest = range::features(desc, &methods)
            .filter(|f| of(f.item))
            .max_by(|a, b| fraction_bits(a).total_cmp(&fraction_bits(b)));
        rows.push(Bits {
            computation,
            integer: largest.map_or(1, |m| integer_bits(m.value)),
            largest,
            fraction: finest.map_or(0, |f| fraction_bits(&f).ceil().max(0.0) as u32),
            finest,
        });
    };
    if has("sphere") {
        for &(sphere, name) in SphereMethod::ALL {
            let by = Methods { sphere, ..methods };
            row(format!("spheres, by {name}"), by, &|item| {
                kind(item) == Some("sphere")
            });
        }
    }
    if has("triangle") {
        for &(triangle, name) in TriangleMethod::ALL {
            let by = Methods {
                triangle,
                ..methods
            };
            row(format!("triangles, by {name}"), by, &|item| {
                kind(item) == Some("triangle")
            });
        }
    }
    row(
        "everything else: rays, planes, lights, colours".to_owned(),
        methods,
        &|item| !matches!(kind(item), Some("sphere" | "triangle")),
    );
    rows
}

/// Integer bits, sign included, that hold `value` with [`range::RANGE_HEADROOM`] (saturating
/// for a value no format holds: Möller–Trumbore's quotient by a determinant of 0).
fn integer_bits(value: f64) -> u32 {
    ((value * range::RANGE_HEADROOM).log2().floor().max(0.0) as u32).saturating_add(2)
}

/// Fraction bits a fixed format needs to resolve `feature` (whose error in a fixed format is
/// the sum of its terms' coefficients, in LSBs).
fn fraction_bits(feature: &Feature) -> f64 {
    let lsbs: f64 = feature
        .terms
        .iter()
        .map(|(coefficient, _)| coefficient)
        .sum();
    (feature.steps * lsbs / feature.value).log2()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fuzz::false_accept;
    use crate::metrics::{Accuracy, accuracy};
    use crate::peak::{self, Peak};
    use crate::render::{Prepared, prepare};
    use obscura::{BiasMethod, RayMethod, RootMethod, SphereMethod, scenes};

    #[test]
    fn a_firmwares_auto_format_is_priced_for_its_machine() {
        let whitted = [obscura_scene::load("whitted").unwrap()];
        let picked = |machine, target_psnr, choose_pixels| {
            let aim = Aim {
                machine,
                target_psnr,
                rescale: false,
                choose_pixels,
            };
            let pick = firmware_format(&whitted, Methods::default(), aim).unwrap();
            (pick.format, pick.pixels)
        };
        // On the M4F adaptive pixels cost more in f32 (the chart's pixels axis): f32 exact.
        assert_eq!(
            picked(Machine::M4f, TARGET_PSNR, true),
            (Format::F32, Pixels::Exact)
        );
        // i16f16, whose shift by 16 the M0 gets free, is the cheapest there that reaches 40 dB;
        // its adaptive pixels are cheaper still but reach only 38.7 dB.
        assert_eq!(
            picked(Machine::M0, TARGET_PSNR, true),
            (Format::I16f16, Pixels::Exact)
        );
        // At 35 dB they are taken (blocks of 8, 6 % cheaper on the chart), where auto may.
        assert_eq!(
            picked(Machine::M0, 35.0, true),
            (Format::I16f16, Pixels::Adaptive(8))
        );
        assert_eq!(
            picked(Machine::M0, 35.0, false),
            (Format::I16f16, Pixels::Exact)
        );
    }

    #[test]
    fn where_no_format_reaches_the_target_the_closest_is_said_and_its_target_takes_it() {
        let scene = obscura_scene::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/scenes/tinyraytracer.toml"
        ))
        .unwrap()
        .scene;
        let size = (48, 48);
        let analysis = Analysis::of(&scene, Methods::LECTURE, size.0, size.1).unwrap();
        let choose = |target_psnr| {
            let aim = Aim {
                machine: Machine::M4f,
                target_psnr,
                rescale: true,
                choose_pixels: false,
            };
            pick(&[(&scene, &analysis)], Methods::LECTURE, size, aim).unwrap()
        };
        // Every format's checker edges differ from f64's somewhere: none reaches 90 dB.
        let short = choose(90.0);
        let Choice::Closest(closest) = &short else {
            panic!("{short:?}")
        };
        let said = short.shortfall(90.0).unwrap();
        assert!(
            said.contains(&format!("the closest is {}", closest.format)),
            "{said}"
        );
        let target: f64 = said
            .rsplit_once("--target-psnr ")
            .and_then(|(_, rest)| rest.split(' ').next())
            .and_then(|number| number.parse().ok())
            .unwrap();
        assert!(target <= closest.psnr_db && closest.psnr_db < target + 0.1);
        // That target takes the closest format, or a cheaper one that reaches it too.
        let Choice::Reaches(taken) = choose(target) else {
            panic!("--target-psnr {target} takes nothing")
        };
        assert!(taken.psnr_db >= target, "{taken:?}");
    }

    #[test]
    fn integer_bits_count_the_sign() {
        assert_eq!(integer_bits(f64::INFINITY), u32::MAX);
        // i16f16 holds up to 32768 (exclusive) in 16 integer bits.
        assert_eq!(integer_bits(30_000.0), 16);
        assert_eq!(integer_bits(33_000.0), 17);
        assert_eq!(integer_bits(0.5), 2);
    }

    #[test]
    fn the_lecture_scene_needs_no_more_than_i16f16_has() {
        let whitted = OwnedScene::from_desc(&scenes::WHITTED);
        let analysis = Analysis::of(&whitted, Methods::LECTURE, 64, 64).expect("analyses");
        for row in &analysis.bits {
            assert!(row.integer <= 16 && row.fraction <= 16, "{row:?}");
        }
        let extents = &analysis.extents;
        assert_eq!(extents.smallest_radius, Some((1.0, 1)));
        assert_eq!(extents.smallest_square, Some((1.0, 0)));
        // The floor is 3 below the eye.
        assert!((extents.nearest - 3.0).abs() < 1e-9, "{extents:?}");
    }

    /// The scenes the analysis is held to: the built-in ones of one ray per pixel and light, as
    /// they are and scaled.
    fn scenes() -> Vec<(String, OwnedScene)> {
        let mut all = Vec::new();
        for built_in in scenes::one_ray() {
            let scene = OwnedScene::from_desc(&built_in.desc);
            for factor in [0.25, 1.0, 4.0] {
                all.push((format!("{} ×{factor}", built_in.name), scene.scaled(factor)));
            }
        }
        all
    }

    /// `format` against f64 (exact roots, same methods) on `scene`, measured.
    fn measured(format: Format, scene: &OwnedScene, methods: Methods, size: u32) -> Accuracy {
        let request = Request::new(scene.desc(), (size, size), methods);
        let (contender, reference) = (
            prepare(format, &request).expect("builds"),
            prepare_reference(&request).expect("builds"),
        );
        let threads = all_cores();
        accuracy(
            &contender.render(threads, None).expect("renders"),
            &reference.render(threads, None).expect("renders"),
            &contender.object_map().expect("renders"),
            &reference.object_map().expect("renders"),
        )
    }

    #[test]
    fn every_prediction_on_the_built_in_scenes_holds_and_tells_formats_apart() {
        let variants = [
            (Methods::LECTURE, 240),
            (
                Methods {
                    sphere: SphereMethod::Stable,
                    ..Methods::LECTURE
                },
                160,
            ),
            (
                Methods {
                    bias: BiasMethod::Exclude,
                    ..Methods::LECTURE
                },
                160,
            ),
            (
                Methods {
                    roots: RootMethod::Approx,
                    ..Methods::LECTURE
                },
                160,
            ),
            (
                Methods {
                    rays: RayMethod::Stepped,
                    ..Methods::LECTURE
                },
                160,
            ),
        ];
        let mut gaps = Vec::new();
        for (name, scene) in scenes() {
            for (methods, size) in variants {
                let analysis = Analysis::of(&scene, methods, size, size).expect("analyses");
                for verdict in &analysis.verdicts {
                    let format = verdict.format;
                    let (Fit::Holds, Some(prediction)) = (&verdict.fit, verdict.prediction) else {
                        continue;
                    };
                    if format == Format::F64 {
                        continue;
                    }
                    let measured = measured(format, &scene, methods, size);
                    assert!(
                        !false_accept(&prediction, &measured, size * size),
                        "{name} in {format} by {methods} at {size}: predicted {prediction:?}, \
                         measured {measured:?}"
                    );
                    if format.is_fixed_point() && measured.psnr_db.is_finite() {
                        gaps.push(measured.psnr_db - prediction.psnr_db);
                    }
                }
            }
        }
        // The model errs on the safe side (every pixel within the bound of an edge counts as
        // wrong, where on average half of them are), by little enough to tell formats apart
        // where their errors show (in the fixed formats; a float's error is a pixel or two,
        // which flip by chance).
        gaps.sort_by(f64::total_cmp);
        let median = gaps[gaps.len() / 2];
        assert!(
            gaps.len() >= 30 && median < 15.0,
            "{} measured; the median is {median:.1} dB above the prediction",
            gaps.len()
        );
    }

    #[test]
    fn every_scene_refused_for_range_really_overflows() {
        let mut refused = 0;
        for (name, scene) in scenes() {
            for power in 0..8 {
                let scaled = scene.scaled(2.0_f32.powi(power));
                let request = Request::new(scaled.desc(), (96, 96), Methods::LECTURE);
                peak::reset();
                drop(
                    Prepared::<Peak>::new(&request)
                        .expect("builds")
                        .render(1, None)
                        .expect("renders"),
                );
                let reached = peak::largest();
                for format in [Format::I16f16, Format::I20f12, Format::I32f32] {
                    let range = format.run::<Checked, _>(Range);
                    match builds(format, &request.desc, Methods::LECTURE, (96, 96)) {
                        Err(SceneError::OutOfRange { .. }) => {
                            refused += 1;
                            assert!(
                                reached > range,
                                "{name} ×2^{power} refused in {format}, but reaches only \
                                 {reached:.0} of its {range:.0}"
                            );
                        }
                        Ok(()) => assert!(
                            reached <= range,
                            "{name} ×2^{power} held in {format}, but reaches {reached:.0}"
                        ),
                        Err(_) => {}
                    }
                }
            }
        }
        assert!(refused >= 10, "only {refused} refusals were checked");
    }

    #[test]
    fn a_scene_that_fits_only_rescaled_is_rescaled_and_looks_the_same() {
        let whitted = OwnedScene::from_desc(&scenes::WHITTED);
        let tiny = whitted.scaled(1.0 / 1024.0);
        assert!(matches!(
            builds(Format::I16f16, &tiny.desc(), Methods::LECTURE, (64, 64)),
            Err(SceneError::BelowResolution { .. })
        ));
        // The smallest rescaling that fits: whitted at a sixteenth of its size is fine.
        assert_eq!(
            fit(Format::I16f16, &tiny, Methods::LECTURE, (64, 64)),
            Fit::Rescaled(64.0)
        );
        // Rescaling about the eye leaves the image as it was.
        let image = |scene: &OwnedScene| {
            let request = Request::new(scene.desc(), (64, 64), Methods::LECTURE);
            prepare(Format::F64, &request)
                .expect("builds")
                .render(1, None)
                .expect("renders")
        };
        let (before, after) = (image(&whitted), image(&tiny.scaled(64.0)));
        let none = vec![None; 64 * 64];
        // Up to the rounding of the rescaled description to f32, which moves a few pixels by a
        // level and tips one or two on an edge seen in a mirror.
        let error = accuracy(&after, &before, &none, &none);
        assert!(
            error.differing_pixels_pct < 1.0 && error.mean_abs_error < 0.1,
            "{error:?}"
        );
    }

    #[test]
    fn a_scene_no_format_holds_is_refused_with_the_reason() {
        let mut speck = OwnedScene::from_desc(&scenes::WHITTED);
        speck.objects.truncate(1);
        speck.objects.push(obscura::ObjectDesc {
            shape: ShapeDesc::Sphere {
                center: [0.0, 3.0, 10.0],
                radius: 1e-18,
            },
            material: obscura::MaterialDesc::default(),
        });
        let error = Analysis::of(&speck, Methods::LECTURE, 32, 32).expect_err("refused");
        let message = format!("{error:#}");
        assert!(
            message.contains("no format can hold") && message.contains("object 1: radius²"),
            "{message}"
        );
        for &format in Format::ALL {
            assert!(matches!(
                fit(format, &speck, Methods::LECTURE, (32, 32)),
                Fit::Refused(_)
            ));
        }
    }

    struct Range;
    impl FormatJob for Range {
        type Output = f64;
        fn run<S: Scalar>(self) -> f64 {
            S::RANGE
        }
    }
}
