//! The scanline renderer: traces a frame row by row into a line buffer and sends each finished
//! row to an embedded-graphics [`DrawTarget`] as one rectangle, needing no frame buffer. Two
//! ways in: [`render_frame`] draws a whole frame, in the order and dither of a [`Presentation`];
//! a [`RowTracer`] traces one row at a time for a renderer that sends the rows itself.

crate::phase::declare_phase!(Some(crate::phase::Phase::Output));

use crate::adaptive::{self, Corner, CornerRows, Pixel, corners_kept};
use crate::blocks::{self, Blocks};
use crate::camera::{Camera, Row};
use crate::color::{DisplayColor, Dither, Rgb};
use crate::cull::RowRanges;
use crate::pattern::{Pattern, SampleId};
use crate::ray::Ray;
use crate::scalar::Scalar;
use crate::scene::Scene;
use crate::shade::{Task, Tracer};
use crate::words::WordsError;
use crate::shape::mesh::Meshes;
use crate::uses::{Parts, Uses};
use crate::vec3::Vec3;
use core::convert::Infallible;
use core::fmt;
use core::marker::PhantomData;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;
use heapless::{Vec, VecView};

/// Why a render stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum RenderError<E> {
    /// The line buffer is shorter than a row. Pass one of at least `needed` pixels.
    LineBufferTooSmall {
        /// The image width.
        needed: u32,
        /// The buffer's length.
        got: usize,
    },
    /// The scene takes adaptive samples or adaptive pixels and the corner rows hold fewer
    /// corners than it keeps. Pass [`SceneDesc::corner_rows`](crate::SceneDesc::corner_rows)
    /// of them, or [`corner_rows`](crate::adaptive::corner_rows)`(width)` for any scene.
    CornerRowsTooSmall {
        /// Corners the image needs.
        needed: usize,
        /// The buffer's length.
        got: usize,
    },
    /// The rows asked for end below the image. Ask for rows within `0..height`.
    RowsOutOfRange {
        /// The end of the requested rows.
        end: u32,
        /// The image height.
        height: u32,
    },
    /// The camera uses a part that the scene's tracer leaves out ([`Uses`]): a lens, or
    /// another method for its rays. Make the camera with the scene's own
    /// [`Scene::camera`](crate::Scene::camera).
    TracerLacks {
        /// The parts the tracer lacks.
        missing: Uses,
    },
    /// The proven words do not read back as the scene and camera asked for: words written by
    /// another version of obscura, or for another format or scene. Prove the scene again
    /// (`obscura_scene::build::Proof`).
    Words(WordsError),
    /// The draw target failed.
    Target(E),
}

impl<E: fmt::Debug> fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::LineBufferTooSmall { needed, got } => {
                write!(
                    f,
                    "the line buffer holds {got} pixels but a row has {needed}; pass a longer one"
                )
            }
            Self::CornerRowsTooSmall { needed, got } => {
                write!(
                    f,
                    "the corner rows hold {got} corners but the scene's adaptive samples or \
                     pixels keep {needed}; pass corner_rows(width) of them"
                )
            }
            Self::RowsOutOfRange { end, height } => {
                write!(
                    f,
                    "rows up to {end} were asked for, but the image has {height}"
                )
            }
            // Without the parts' names, which a firmware would otherwise link for a camera
            // it made from its own scene.
            Self::TracerLacks { .. } => f.write_str(
                "the camera uses a part the scene's tracer leaves out (a lens, or another method \
                 for its rays); make the camera with the scene's own Scene::camera",
            ),
            Self::Words(e) => e.fmt(f),
            Self::Target(e) => write!(f, "the display failed: {e:?}"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for RenderError<E> {}

impl RenderError<Infallible> {
    /// The same error, as one of a renderer whose target fails with `E` (tracing a row alone
    /// draws nothing, so it never fails for its target).
    #[must_use]
    pub fn for_target<E>(self) -> RenderError<E> {
        match self {
            Self::LineBufferTooSmall { needed, got } => {
                RenderError::LineBufferTooSmall { needed, got }
            }
            Self::CornerRowsTooSmall { needed, got } => {
                RenderError::CornerRowsTooSmall { needed, got }
            }
            Self::RowsOutOfRange { end, height } => RenderError::RowsOutOfRange { end, height },
            Self::TracerLacks { missing } => RenderError::TracerLacks { missing },
            Self::Words(error) => RenderError::Words(error),
            Self::Target(never) => match never {},
        }
    }
}

/// A pixel's samples, each at most 2¹⁶ per channel in [`Rgb::to_q16`], sum within a `u32`; so
/// do an area light's shadow samples, each at most 2¹⁶ ([`crate::shade`]).
const _SAMPLE_SUMS_FIT: () = assert!(
    crate::pattern::MAX_SAMPLES as u64 * 0x1_0000 <= u32::MAX as u64,
    "MAX_SAMPLES samples of 2^16 overflow a pixel's sum"
);

/// Traces `row` (row `y` of the image) into `line`, each pixel quantised by `dither`: by its
/// centre's ray, or by the mean of its samples ([`PixelSamples`]), each clamped to what a
/// display shows and summed as integers, in 16-bit fractions: the sum cannot overflow however
/// many samples a pixel takes, and rounds alike in every format.
///
/// Over the tracer's slices and a ray stack rather than a scene of given capacities, and out of
/// line: a firmware holds one copy per format however many scenes it draws.
#[inline(never)]
fn trace_into<S, C, M, P: Parts>(
    mut tracer: Tracer<'_, S, M, P>,
    stack: &mut VecView<Task<S>>,
    row: &Row<S>,
    y: u32,
    dither: Dither,
    line: &mut [C],
) where
    S: Scalar,
    C: DisplayColor,
    M: Meshes<S>,
{
    let row = &row.narrowed(Tracer::<S, M, P>::USES);
    let samples = tracer.samples();
    let n = u32::from(samples);
    let sampled = samples > 1 || row.has_lens();
    let bounds = tracer.objects().iter().map(|object| &object.bound);
    let ranges = RowRanges::new(bounds, row.camera().image_plane(), y);
    let mut candidates = ranges.candidates();
    // A pixel of one ray that can meet a matte plane alone takes the row pass: shaded where
    // it finds the ray's hit, or the background beyond the world's rim.
    let plane_row = if sampled {
        None
    } else {
        tracer.plane_row(row)
    };
    let mut points = row.points();
    for (x, pixel) in (0..).zip(line.iter_mut()) {
        let point = points.next();
        let candidates = candidates.at(x);
        let passed = plane_row
            .as_ref()
            .filter(|plane| candidates == plane.candidates())
            .zip(point);
        if let Some((plane, s)) = passed {
            let colour = match plane.hit(s) {
                Some(hit) => tracer.shade_plane_row(plane, hit, SampleId { x, y, sample: 0 }),
                None => tracer.background(row.through(s).dir),
            };
            *pixel = colour.quantize_at(dither, x, y);
            continue;
        }
        // One call of the tracer for either kind of pixel: a second would change how the
        // compiler inlines it, and so the cost of the one-sample image.
        let centre = point.map(|s| row.through(s));
        let pattern = sampled.then(|| PixelSamples::new(row, x, y));
        let (mut colour, mut sum) = (Rgb::BLACK, [0_u32; 3]);
        for i in 0..samples {
            let ray = match &pattern {
                None => centre,
                Some(pattern) => pattern.ray(row, i, samples),
            };
            let Some(ray) = ray else { continue };
            colour = tracer
                .trace_ray(ray, SampleId { x, y, sample: i }, candidates, stack)
                .colour;
            if pattern.is_some() {
                let c = colour.to_q16();
                sum = [sum[0] + c[0], sum[1] + c[1], sum[2] + c[2]];
            }
        }
        if pattern.is_some() {
            colour = Rgb::from_q16(sum.map(|s| (s + n / 2) / n));
        }
        *pixel = colour.quantize_at(dither, x, y);
    }
}

/// Traces `row` into `line`: by [`trace_into`], with adaptive samples by [`adaptive_row`], or
/// with adaptive pixels by [`blocks::trace_row`], through what `kept` keeps. Corner rows of a
/// type that holds none ([`CornerRows::NONE`]) leave the adaptive code out of the build.
#[inline(always)]
fn trace_pixels<
    K,
    S,
    C,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
>(
    scene: &Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
    row: &Row<S>,
    y: u32,
    dither: Dither,
    line: &mut [C],
    kept: &mut Option<Kept<'_, S>>,
) where
    K: CornerRows + ?Sized,
    S: Scalar,
    C: DisplayColor,
{
    match kept {
        Some(Kept::Samples(window)) if !K::NONE => {
            adaptive_row(scene, row, y, dither, line, window);
        }
        Some(Kept::Blocks(blocks)) if !K::NONE => {
            blocks::trace_row(scene, row, y, dither, line, blocks);
        }
        _ => {
            let mut stack: Vec<Task<S>, RAYS> = Vec::new();
            let tracer = scene.tracer(SampleId::default());
            trace_into(tracer, stack.as_mut_view(), row, y, dither, line);
        }
    }
}

/// The buffers a render traces through, checked against the image: `line` cut to a row, and
/// for a scene with adaptive samples or pixels the corner rows ([`Kept`]). Inline, so that a
/// caller whose corner rows are an empty array leaves the adaptive code out.
#[inline(always)]
fn buffers<
    'a,
    S,
    C,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
>(
    scene: &Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
    camera: &'a Camera<S>,
    line: &'a mut [C],
    corners: &'a mut [Corner],
) -> Result<Buffers<'a, C, S>, RenderError<Infallible>>
where
    S: Scalar,
{
    let missing = P::USES.missing(camera.uses());
    if missing != Uses::NOTHING {
        return Err(RenderError::TracerLacks { missing });
    }
    let width = camera.width();
    let got = line.len();
    let line = usize::try_from(width)
        .ok()
        .and_then(|w| line.get_mut(..w))
        .ok_or(RenderError::LineBufferTooSmall { needed: width, got })?;
    let settings = &scene.settings;
    let needed = corners_kept(settings.adaptive_samples, settings.pixel_block, width);
    let got = corners.len();
    let too_small = RenderError::CornerRowsTooSmall { needed, got };
    if corners.is_empty() {
        return if needed == 0 {
            Ok((line, None))
        } else {
            Err(too_small)
        };
    }
    if needed == 0 {
        return Ok((line, None));
    }
    let corners = corners.get_mut(..needed).ok_or(too_small)?;
    let kept = if settings.adaptive_samples {
        Kept::Samples(Window {
            camera,
            corners,
            held: None,
        })
    } else {
        Kept::Blocks(Blocks::new(corners, settings.pixel_block))
    };
    Ok((line, Some(kept)))
}

/// A line cut to a row, and what adaptive samples or pixels keep.
type Buffers<'a, C, S> = (&'a mut [C], Option<Kept<'a, S>>);

/// What a render keeps between rows in its corner rows.
#[allow(
    clippy::large_enum_variant,
    reason = "one a render, on the stack beside corner rows far larger"
)]
enum Kept<'a, S> {
    /// Adaptive samples' corners.
    Samples(Window<'a, S>),
    /// Adaptive pixels' blocks.
    Blocks(Blocks<'a>),
}

/// What adaptive anti-aliasing keeps between rows ([`crate::adaptive`]): corner row cy in the
/// half cy % 2 of `corners`, and which corner row the last row traced left below it.
struct Window<'a, S> {
    camera: &'a Camera<S>,
    corners: &'a mut [Corner],
    held: Option<u32>,
}

/// [`trace_into`] for a scene with adaptive samples: traces the corner rows above (unless the
/// row before left it) and below row `y`, then each pixel from its four corners.
#[inline(never)]
fn adaptive_row<
    S,
    C,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
>(
    scene: &Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
    row: &Row<S>,
    y: u32,
    dither: Dither,
    line: &mut [C],
    window: &mut Window<'_, S>,
) where
    S: Scalar,
    C: DisplayColor,
{
    let half = window.corners.len() / 2;
    let (even, odd) = window.corners.split_at_mut(half);
    let (above, below) = if y % 2 == 0 { (even, odd) } else { (odd, even) };
    if window.held != Some(y) {
        adaptive::trace_corner_row(scene, window.camera, y, above);
    }
    adaptive::trace_corner_row(scene, window.camera, y + 1, below);
    window.held = Some(y + 1);
    let depth = adaptive::depth(scene.settings.samples);
    let edges = above.windows(2).zip(below.windows(2));
    for ((x, pixel), (top, bottom)) in (0..).zip(line.iter_mut()).zip(edges) {
        let (&[top_left, top_right], &[bottom_left, bottom_right]) = (top, bottom) else {
            continue;
        };
        let Some(centre) = row.centre(x) else {
            continue;
        };
        let pixel_cells = Pixel {
            scene,
            row,
            centre,
            x,
            y,
            depth,
        };
        let colour = pixel_cells.colour([top_left, top_right, bottom_left, bottom_right]);
        *pixel = colour.quantize_at(dither, x, y);
    }
}

/// One pixel's samples: its centre on the image plane, and the patterns of their points of
/// the pixel and, with a lens, of their lens points ([`Pattern::lens`]).
struct PixelSamples<S> {
    centre: Option<Vec3<S>>,
    pixel: Pattern,
    lens: Option<Pattern>,
}

impl<S: Scalar> PixelSamples<S> {
    /// Out of line, as [`Self::ray`] is, so that the loop over a pinhole's one-sample pixels
    /// stays as small as it is.
    #[inline(never)]
    fn new(row: &Row<S>, x: u32, y: u32) -> Self {
        Self {
            centre: row.centre(x),
            pixel: Pattern::pixel(x, y),
            lens: row.has_lens().then(|| Pattern::lens(x, y)),
        }
    }

    /// The ray of sample `i` of `samples` in `row`: through its point of the pixel (the
    /// centre, for one sample), and through a lens from its lens point.
    #[inline(never)]
    fn ray(&self, row: &Row<S>, i: u16, samples: u16) -> Option<Ray<S>> {
        let offset = if samples > 1 {
            self.pixel.offset(i)
        } else {
            [S::ZERO; 2]
        };
        let lens = self.lens.map_or([S::ZERO; 2], |lens| lens.disc(i));
        Some(row.sample(self.centre?, offset, lens))
    }
}

/// Sends `line` to `rows` rows of `target` from row `y` down, as one rectangle: a traced row,
/// or in a progressive frame the block it stands for.
///
/// # Errors
/// [`RenderError::Target`] when the target fails.
pub fn send_row<C: DisplayColor, D: DrawTarget<Color = C>>(
    target: &mut D,
    line: &[C],
    y: u32,
    rows: u32,
) -> Result<(), RenderError<D::Error>> {
    // All fit i32 and u32: they are at most MAX_IMAGE_SIDE.
    let top = i32::try_from(y).unwrap_or(i32::MAX);
    let width = u32::try_from(line.len()).unwrap_or(u32::MAX);
    let area = Rectangle::new(Point::new(0, top), Size::new(width, rows));
    let pixels = line
        .iter()
        .copied()
        .cycle()
        .take(line.len() * rows as usize);
    target
        .fill_contiguous(&area, pixels)
        .map_err(RenderError::Target)
}

/// Traces the rows of the image that `camera` sees of `scene` one at a time into `line` (its
/// first `width` pixels), each pixel rounded by `dither`, for a renderer that sends each row
/// itself ([`send_row`]): to a display that takes a row at a time, or with a frame's rows
/// shared among cores, as the Pico's firmware shares them. [`render_frame`] draws a whole frame
/// through one. A scene with adaptive samples or adaptive pixels keeps its corner rows in
/// `corners` ([`SceneDesc::corner_rows`](crate::SceneDesc::corner_rows) of them, or
/// [`corner_rows`](crate::adaptive::corner_rows)`(width)` for any scene; else `&mut []`), and
/// rows traced top to bottom share them.
pub struct RowTracer<
    'a,
    S: Scalar,
    C,
    K: ?Sized,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
> {
    scene: &'a Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
    camera: Camera<S>,
    dither: Dither,
    line: &'a mut [C],
    kept: Option<Kept<'a, S>>,
    corners: PhantomData<fn(&K)>,
}

impl<
    'a,
    S: Scalar,
    C: DisplayColor,
    K: CornerRows + ?Sized,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
> RowTracer<'a, S, C, K, OBJECTS, LIGHTS, RAYS, P, M>
{
    /// A tracer of the rows of the image `camera` sees of `scene`, through `line` and
    /// `corners`, rounding by `dither`.
    ///
    /// # Errors
    /// [`RenderError`] for a short line buffer or corner rows, or a camera that uses a part the
    /// scene's tracer leaves out.
    #[inline(always)]
    pub fn new(
        scene: &'a Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
        camera: &'a Camera<S>,
        dither: Dither,
        line: &'a mut [C],
        corners: &'a mut K,
    ) -> Result<Self, RenderError<Infallible>> {
        let (line, kept) = buffers(scene, camera, line, corners.rows())?;
        Ok(Self {
            scene,
            camera: camera.narrowed(P::USES),
            dither,
            line,
            kept,
            corners: PhantomData,
        })
    }

    /// Traces row `y` and gives its pixels.
    ///
    /// # Errors
    /// [`RenderError::RowsOutOfRange`] for a row beyond the image.
    #[inline(always)]
    pub fn trace(&mut self, y: u32) -> Result<&[C], RenderError<Infallible>> {
        let row = self.camera.row(y).ok_or(RenderError::RowsOutOfRange {
            end: y.saturating_add(1),
            height: self.camera.height(),
        })?;
        trace_pixels::<K, _, _, OBJECTS, LIGHTS, RAYS, P, M>(
            self.scene,
            &row,
            y,
            self.dither,
            self.line,
            &mut self.kept,
        );
        Ok(self.line)
    }
}

impl<
    S: Scalar,
    C,
    K: ?Sized,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
> fmt::Debug for RowTracer<'_, S, C, K, OBJECTS, LIGHTS, RAYS, P, M>
{
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RowTracer")
            .field("width", &self.line.len())
            .field("height", &self.camera.height())
            .field("dither", &self.dither)
            .finish_non_exhaustive()
    }
}

/// How a frame goes to the display: in which order its rows are traced, and how its colours
/// are rounded to the display's levels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Presentation {
    /// The order of the rows.
    pub order: RowOrder,
    /// The rounding of the colours.
    pub dither: Dither,
}

/// The order in which a frame's rows are traced and drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RowOrder {
    /// Top to bottom.
    #[default]
    TopDown,
    /// Every 8th row first, each drawn as a block down to the next, then the rows halfway
    /// between them as blocks of 4, then of 2, then the rest: a coarse picture of the whole
    /// frame after an eighth of it, finer with each pass. Each row is traced once, and the
    /// final frame is the top-down one.
    Progressive,
}

impl crate::methods::MethodName for RowOrder {
    const ALL: &'static [(Self, &'static str)] = &[
        (Self::TopDown, "top-down"),
        (Self::Progressive, "progressive"),
    ];
}

impl RowOrder {
    /// The rows to trace, in order, each with how many rows from it down its pixels fill.
    pub fn rows(self, height: u32) -> impl Iterator<Item = (u32, u32)> {
        // Passes as (first row, step, block).
        const TOP_DOWN: &[(u32, usize, u32)] = &[(0, 1, 1)];
        const PROGRESSIVE: &[(u32, usize, u32)] = &[(0, 8, 8), (4, 8, 4), (2, 4, 2), (1, 2, 1)];
        let passes = match self {
            Self::TopDown => TOP_DOWN,
            Self::Progressive => PROGRESSIVE,
        };
        passes.iter().flat_map(move |&(first, step, block)| {
            (first..height)
                .step_by(step)
                .map(move |y| (y, block.min(height - y)))
        })
    }
}

/// Renders the whole image that `camera` sees of `scene` onto `target`, its rows in
/// `presentation`'s order and its colours rounded by its dither, through `line`, which must
/// hold a row, and `corners` (see [`RowTracer`]).
///
/// # Errors
/// [`RenderError`] for a short line buffer or corner rows, or a failing target.
pub fn render_frame<
    S,
    C,
    D,
    K,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
>(
    scene: &Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
    camera: &Camera<S>,
    presentation: Presentation,
    line: &mut [C],
    corners: &mut K,
    target: &mut D,
) -> Result<(), RenderError<D::Error>>
where
    S: Scalar,
    C: DisplayColor,
    D: DrawTarget<Color = C>,
    K: CornerRows + ?Sized,
{
    let mut rows = RowTracer::new(scene, camera, presentation.dither, line, corners)
        .map_err(RenderError::for_target)?;
    for (y, block) in presentation.order.rows(camera.height()) {
        let line = rows.trace(y).map_err(RenderError::for_target)?;
        send_row(target, line, y, block)?;
    }
    Ok(())
}
