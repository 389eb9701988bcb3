//! Whole frames on the desktop: the core's scanline renderer run band by band of rows on a
//! thread pool, into an image, with every fixed-point sum and product checked ([`crate::checked`]).

use crate::checked::{self, Checked, Overflowed};
use anyhow::{Context, Result, anyhow};
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::{IntoStorage, Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use image::RgbImage;
use indicatif::{ProgressBar, ProgressStyle};
use obscura::blocks;
use obscura::pattern::{Pattern, SampleId};
use obscura::skips::{first_skipped_hit, first_skipped_secondary};
use obscura::{
    Camera, Corner, Dither, Methods, Pixels, Presentation, Ray, RenderError, Rgb, RootMethod,
    RowTracer, Scalar, SceneDesc, SceneError, corner_rows, render_frame, send_row,
};
pub use obscura_scene::HostScene;
use obscura_scene::{Format, FormatJob};
use rayon::prelude::*;
use std::convert::Infallible;
use std::io::IsTerminal;
use std::ops::Range;

/// Every core of this machine: the threads of a render that is not timed.
pub fn all_cores() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZero::get)
}

/// The threads a render of the harness's own may take: every core, or one within a thread
/// pool's task (the fuzzer's, the analyses'), whose pool keeps the cores busy already.
pub fn threads_here() -> usize {
    if rayon::current_thread_index().is_some() {
        1
    } else {
        all_cores()
    }
}

/// `methods` with exact roots and quotients: what a format without fast roots (f64, f32)
/// computes by the same methods.
pub fn exact_roots(methods: Methods) -> Methods {
    Methods {
        roots: RootMethod::Exact,
        ..methods
    }
}

/// The f64 reference a format is measured against: the same scene, size and methods, with
/// exact roots (f64 has no others) and exact pixels (every pixel by its own ray), so that a
/// difference is the format's numeric error and what adaptive pixels fill in.
///
/// # Errors
/// When the scene is invalid or too large even for f64.
pub fn prepare_reference(request: &Request<'_>) -> Result<Box<dyn AnyFormat>> {
    let exact = SceneDesc {
        pixels: Pixels::Exact,
        ..request.desc
    };
    prepare(
        Format::F64,
        &request
            .with_desc(exact)
            .with_methods(exact_roots(request.methods)),
    )
}

/// Rows a thread renders at a time: a band shares its corner rows between its rows (adaptive
/// anti-aliasing traces one more corner row a band than in one pass over the frame).
const BAND: usize = 8;

/// A render request: a scene, an image size and the methods.
#[derive(Clone, Copy, Debug)]
pub struct Request<'a> {
    /// The scene.
    pub desc: SceneDesc<'a>,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The numerical methods.
    pub methods: Methods,
}

impl<'a> Request<'a> {
    /// A request for `desc` at `width`×`height` pixels by `methods`.
    pub fn new(desc: SceneDesc<'a>, (width, height): (u32, u32), methods: Methods) -> Self {
        Self {
            desc,
            width,
            height,
            methods,
        }
    }

    /// The same request for another scene (a moved, doubled or pared copy of this one).
    pub fn with_desc(self, desc: SceneDesc<'a>) -> Self {
        Self { desc, ..self }
    }

    /// The same request by other methods.
    pub fn with_methods(self, methods: Methods) -> Self {
        Self { methods, ..self }
    }
}

/// A scene built and a camera placed for one request.
#[derive(Debug)]
pub struct Prepared<S: Scalar> {
    scene: HostScene<S>,
    camera: Camera<S>,
}

impl<S: Scalar> Prepared<S> {
    /// Builds the scene in format `S` and its camera.
    pub fn new(request: &Request<'_>) -> Result<Self> {
        let built = checked::catch(|| {
            let scene = HostScene::<S>::build_with(&request.desc, request.methods)?;
            let camera = scene.camera(request.width, request.height)?;
            Ok((scene, camera))
        })
        .map_err(|overflowed| {
            anyhow!(
                "{overflowed} while building the scene in {}: the scene build's range proof \
                 missed it (a bug in obscura: please report it with the scene)",
                S::NAME
            )
        })?;
        let (scene, camera) = built
            .map_err(|error: SceneError| anyhow::Error::new(error))
            .with_context(|| format!("the scene cannot be built in {}", S::NAME))?;
        Ok(Self { scene, camera })
    }

    /// Renders the frame, its rows shared out over `threads` threads, with a progress bar
    /// labelled `progress` on a terminal.
    ///
    /// # Errors
    /// When a sum or product leaves the format (a hole in the scene build's range proof): which
    /// one, where in the core, and at which pixel.
    pub fn render(&self, threads: usize, progress: Option<&str>) -> Result<RgbImage> {
        let (width, height) = (self.camera.width(), self.camera.height());
        let row_bytes = 3 * width as usize;
        let mut pixels = vec![0_u8; row_bytes * height as usize];
        let bar = progress_bar(progress, height);
        let render_band = |buffers: &mut Buffers, (band, pixels): (usize, &mut [u8])| {
            let top = u32::try_from(band * BAND).context("an image row beyond u32")?;
            let rows = top..top + u32::try_from(pixels.len() / row_bytes)?;
            let count = u64::from(rows.end - rows.start);
            self.render_band(rows, buffers, &mut BandTarget { top, width, pixels })?;
            bar.inc(count);
            Ok::<_, anyhow::Error>(())
        };
        let new_buffers = || Buffers {
            line: vec![Rgb888::BLACK; width as usize],
            corners: vec![Corner::ZERO; corner_rows(width)],
        };
        if threads <= 1 {
            let mut buffers = new_buffers();
            pixels
                .chunks_mut(row_bytes * BAND)
                .enumerate()
                .try_for_each(|band| render_band(&mut buffers, band))?;
        } else {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .context("cannot start the render threads")?
                .install(|| {
                    pixels
                        .par_chunks_mut(row_bytes * BAND)
                        .enumerate()
                        .try_for_each_init(new_buffers, render_band)
                })?;
        }
        bar.finish_and_clear();
        RgbImage::from_raw(width, height, pixels).context("the image buffer has the wrong size")
    }

    /// Renders `rows` through `buffers` into `target`, with every sum and product checked.
    fn render_band<D>(&self, rows: Range<u32>, buffers: &mut Buffers, target: &mut D) -> Result<()>
    where
        D: DrawTarget<Color = Rgb888, Error = Infallible>,
    {
        let Buffers { line, corners } = buffers;
        let rendered = checked::catch(|| {
            let corners = corners.as_mut_slice();
            let mut tracer = RowTracer::new(&self.scene, &self.camera, Dither::None, line, corners)
                .map_err(RenderError::for_target)?;
            rows.clone().try_for_each(|y| {
                let line = tracer.trace(y).map_err(RenderError::for_target)?;
                send_row(target, line, y, 1)
            })
        });
        match rendered {
            Ok(drawn) => drawn.map_err(|error| anyhow!("rows {rows:?}: {error}")),
            Err(overflowed) => Err(self.overflow_at(rows, overflowed)),
        }
    }

    /// The error for an overflow in `rows`, naming the first pixel of them whose trace
    /// overflows.
    fn overflow_at(&self, rows: Range<u32>, overflowed: Overflowed) -> anyhow::Error {
        let (first, pixel) = rows
            .clone()
            .find_map(|y| {
                (0..self.camera.width())
                    .zip(self.primary_rays(y))
                    .find_map(|(x, ray)| {
                        checked::catch(|| self.scene.trace(ray, SampleId { x, y, sample: 0 }))
                            .err()
                            .map(|o| (o, (x, y)))
                    })
            })
            .map_or((overflowed, None), |(o, pixel)| (o, Some(pixel)));
        let place = pixel.map_or_else(
            || format!("rows {rows:?}"),
            |(x, y)| format!("pixel ({x}, {y})"),
        );
        anyhow!(
            "{} while tracing {place} in {}: the scene build's range proof missed it (a bug in \
             obscura: please report it with the scene)",
            first,
            S::NAME
        )
    }

    /// The frame in RGB565, as a display receives it by `presentation` (its rows' order and its
    /// dither), rendered on one thread through the same scanline renderer as the firmware's.
    ///
    /// # Errors
    /// As [`Self::render`].
    /// `watch` sees the frame after each rectangle the renderer sends it, with the rows it
    /// covered: what a display shows as the frame builds up.
    pub fn rgb565_frame(&self, presentation: Presentation, watch: Watch<'_>) -> Result<Vec<u16>> {
        let (width, height) = (self.camera.width(), self.camera.height());
        let mut frame = Rgb565Frame {
            width,
            pixels: vec![0; (width * height) as usize],
            watch,
        };
        let mut line = vec![Rgb565::BLACK; width as usize];
        let mut corners = vec![Corner::ZERO; corner_rows(width)];
        let drawn = checked::catch(|| {
            render_frame(
                &self.scene,
                &self.camera,
                presentation,
                &mut line,
                corners.as_mut_slice(),
                &mut frame,
            )
        });
        match drawn {
            Ok(drawn) => drawn.map_err(|error| anyhow!("{error}"))?,
            Err(overflowed) => return Err(self.overflow_at(0..height, overflowed)),
        }
        Ok(frame.pixels)
    }

    /// The index of the object each pixel's primary ray hits first, row by row, the rays made
    /// as the renderer makes them ([`Self::primary_rays`]). With adaptive pixels, the object
    /// each pixel shows: its block's corners' where it is filled from them
    /// ([`obscura::blocks::shown_objects`]), so that an object that vanished between corners is
    /// a mismatch.
    ///
    /// # Errors
    /// As [`Self::render`].
    pub fn object_map(&self) -> Result<Vec<Option<usize>>> {
        if let Pixels::Adaptive(block) = self.scene.pixels() {
            let width = self.camera.width();
            let rows: Vec<Result<Vec<_>, Overflowed>> = (0..self.camera.height())
                .into_par_iter()
                .map(|y| {
                    let mut nodes = vec![Corner::ZERO; corner_rows(width)];
                    checked::catch(|| {
                        blocks::shown_objects(&self.scene, &self.camera, &mut nodes, block, y)
                            .collect()
                    })
                })
                .collect();
            let mut all = Vec::new();
            for (y, row) in (0..).zip(rows) {
                all.extend(row.map_err(|overflowed| self.overflow_at(y..y + 1, overflowed))?);
            }
            return Ok(all);
        }
        Ok(self
            .hit_map()?
            .into_iter()
            .map(|hit| hit.map(|(object, _)| object))
            .collect())
    }

    /// What each pixel's primary ray hits first, row by row, as (object, part): the part is
    /// the triangle of a mesh, 0 for other objects.
    ///
    /// # Errors
    /// As [`Self::render`].
    pub fn hit_map(&self) -> Result<Vec<Option<(usize, u32)>>> {
        self.per_pixel(|_, _, ray| self.scene.first_hit(&ray))
    }
}

impl<S: Scalar> Prepared<S> {
    /// Each pixel's primary ray in row `y`, as the renderer's first sample makes it where it
    /// traces the pixel's centre: by the camera's ray method, or through a lens from the
    /// pixel's first lens point.
    fn primary_rays(&self, y: u32) -> Vec<Ray<S>> {
        let Some(row) = self.camera.row(y) else {
            return Vec::new();
        };
        if row.has_lens() {
            (0..self.camera.width())
                .filter_map(|x| row.ray_through_lens(x, [S::ZERO; 2], Pattern::lens(x, y).disc(0)))
                .collect()
        } else {
            row.rays().collect()
        }
    }

    /// The first pixel whose rays meet an object that culling leaves out of its row
    /// ([`obscura::skips::first_skipped_hit`]), or whose ray tree changes when its shadow rays
    /// skip what the shadow cones rule out or rays inside a lone ball test its wall alone
    /// ([`obscura::skips::first_skipped_secondary`]), as
    /// (x, y, object), or `None`.
    ///
    /// # Errors
    /// As [`Self::render`].
    pub fn skipped_hit(&self) -> Result<Option<(u32, u32, usize)>> {
        for y in 0..self.camera.height() {
            let skipped = checked::catch(|| first_skipped_hit(&self.scene, &self.camera, y))
                .map_err(|overflowed| self.overflow_at(y..y + 1, overflowed))?;
            if let Some((x, object)) = skipped {
                return Ok(Some((x, y, object)));
            }
        }
        checked::catch(|| first_skipped_secondary(&self.scene, &self.camera))
            .map_err(|overflowed| self.overflow_at(0..self.camera.height(), overflowed))
    }

    /// The objects each pixel's ray tree meets ([`obscura::Sample::met`]), row by row.
    ///
    /// # Errors
    /// As [`Self::render`].
    pub fn met_map(&self) -> Result<Vec<u64>> {
        self.per_pixel(|x, y, ray| self.scene.trace(ray, SampleId { x, y, sample: 0 }).met)
    }

    /// `of` each pixel's primary ray (its column, its row and the ray), row by row, the rows
    /// shared out among the threads of the pool it runs in; the first row where a number
    /// wraps is the error.
    fn per_pixel<T: Send>(&self, of: impl Fn(u32, u32, Ray<S>) -> T + Sync) -> Result<Vec<T>> {
        let rows: Vec<Result<Vec<T>, Overflowed>> = (0..self.camera.height())
            .into_par_iter()
            .map(|y| {
                checked::catch(|| {
                    (0..)
                        .zip(self.primary_rays(y))
                        .map(|(x, ray)| of(x, y, ray))
                        .collect()
                })
            })
            .collect();
        let mut all = Vec::new();
        for (y, row) in (0..).zip(rows) {
            all.extend(row.map_err(|overflowed| self.overflow_at(y..y + 1, overflowed))?);
        }
        Ok(all)
    }
}

impl Prepared<f64> {
    /// What pixel (x, y) shows with each of its `samples` rays moved by `offset` (across,
    /// down) pixels: the mean of their colours, each ray through its point of the pixel and its
    /// lens point as the render takes them (all of them, where adaptive samples take some),
    /// and the object its first ray hits; `None` outside the image.
    pub fn pixel(
        &self,
        x: u32,
        y: u32,
        offset: [f64; 2],
        samples: u16,
    ) -> Option<(Rgb888, Option<usize>)> {
        let (within, lens) = (Pattern::pixel(x, y), Pattern::lens(x, y));
        let mut sum = [0.0; 3];
        let mut first = None;
        for i in 0..samples {
            let [across, down] = if samples > 1 {
                within.offset::<f64>(i)
            } else {
                [0.0; 2]
            };
            let at = [across + offset[0], down + offset[1]];
            let ray = self.camera.ray_through_lens(x, y, at, lens.disc(i))?;
            let seen = self.scene.trace(ray, SampleId { x, y, sample: i });
            first = first.or(Some(seen.object));
            for (total, channel) in sum.iter_mut().zip(seen.colour.to_f64()) {
                *total += channel.clamp(0.0, 1.0);
            }
        }
        let mean = Rgb::<f64>::from_f64(sum.map(|total| total / f64::from(samples.max(1))))?;
        Some((mean.quantize(), first.flatten()))
    }

    /// What pixel (x, y)'s first ray, moved by `offset` (across, down) pixels, hits first, as
    /// [`Self::hit_map`] gives it; `None` where it hits nothing or leaves the image.
    pub fn hit_at(&self, x: u32, y: u32, offset: [f64; 2]) -> Option<(usize, u32)> {
        let ray = self
            .camera
            .ray_through_lens(x, y, offset, Pattern::lens(x, y).disc(0))?;
        self.scene.first_hit(&ray)
    }
}

/// A prepared render whose number format was chosen at run time.
pub trait AnyFormat: Sync {
    /// See [`Prepared::render`].
    fn render(&self, threads: usize, progress: Option<&str>) -> Result<RgbImage>;
    /// See [`Prepared::object_map`].
    fn object_map(&self) -> Result<Vec<Option<usize>>>;
    /// See [`Prepared::rgb565_frame`].
    fn rgb565_frame(&self, presentation: Presentation, watch: Watch<'_>) -> Result<Vec<u16>>;
    /// See [`Prepared::skipped_hit`].
    fn skipped_hit(&self) -> Result<Option<(u32, u32, usize)>>;
}

impl<S: Scalar> AnyFormat for Prepared<S> {
    fn render(&self, threads: usize, progress: Option<&str>) -> Result<RgbImage> {
        Prepared::render(self, threads, progress)
    }
    fn object_map(&self) -> Result<Vec<Option<usize>>> {
        Prepared::object_map(self)
    }
    fn rgb565_frame(&self, presentation: Presentation, watch: Watch<'_>) -> Result<Vec<u16>> {
        Prepared::rgb565_frame(self, presentation, watch)
    }
    fn skipped_hit(&self) -> Result<Option<(u32, u32, usize)>> {
        Prepared::skipped_hit(self)
    }
}

/// Builds the request's scene in `format`.
pub fn prepare(format: Format, request: &Request<'_>) -> Result<Box<dyn AnyFormat>> {
    struct Job<'a, 'b>(&'a Request<'b>);
    impl FormatJob for Job<'_, '_> {
        type Output = Result<Box<dyn AnyFormat>>;
        fn run<S: Scalar>(self) -> Self::Output {
            Ok(Box::new(Prepared::<S>::new(self.0)?))
        }
    }
    format.run::<Checked, _>(Job(request))
}

/// A progress bar of `rows` rows labelled `label`, drawn on standard error when that is a
/// terminal (hidden otherwise, and when there is no label).
fn progress_bar(label: Option<&str>, rows: u32) -> ProgressBar {
    match label {
        Some(label) if std::io::stderr().is_terminal() => {
            let bar = ProgressBar::new(u64::from(rows));
            let style = ProgressStyle::with_template("{msg}: {bar:40} {percent:>3}% {eta}")
                .unwrap_or_else(|_| ProgressStyle::default_bar());
            bar.set_style(style);
            bar.set_message(label.to_owned());
            bar
        }
        _ => ProgressBar::hidden(),
    }
}

/// A thread's buffers: a line of pixels and the corner rows of adaptive anti-aliasing.
struct Buffers {
    line: Vec<Rgb888>,
    corners: Vec<Corner>,
}

/// Rows of an RGB888 image `width` pixels wide from row `top` down, as a draw target.
struct BandTarget<'a> {
    top: u32,
    width: u32,
    pixels: &'a mut [u8],
}

impl OriginDimensions for BandTarget<'_> {
    fn size(&self) -> Size {
        let rows = u32::try_from(self.pixels.len() / (3 * self.width.max(1) as usize));
        Size::new(self.width, self.top + rows.unwrap_or(0))
    }
}

impl DrawTarget for BandTarget<'_> {
    type Color = Rgb888;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb888>>,
    {
        for Pixel(point, colour) in pixels {
            let place = u32::try_from(point.x)
                .ok()
                .filter(|&x| x < self.width)
                .zip(
                    u32::try_from(point.y)
                        .ok()
                        .and_then(|y| y.checked_sub(self.top)),
                )
                .map(|(x, row)| 3 * (row * self.width + x) as usize);
            if let Some(pixel) = place.and_then(|i| self.pixels.get_mut(i..i + 3)) {
                pixel.copy_from_slice(&[colour.r(), colour.g(), colour.b()]);
            }
        }
        Ok(())
    }
}

/// A frame of raw RGB565 values, row after row.
/// An RGB565 frame (`width` pixels a row) as an RGB888 image, each channel scaled to 8 bits
/// with rounding, as a display shows it.
pub fn rgb565_image(frame: &[u16], width: u32) -> RgbImage {
    let height = u32::try_from(frame.len()).unwrap_or(0) / width.max(1);
    RgbImage::from_fn(width, height, |x, y| {
        let raw = frame.get((y * width + x) as usize).copied().unwrap_or(0);
        let colour = Rgb888::from(Rgb565::from(RawU16::new(raw)));
        image::Rgb([colour.r(), colour.g(), colour.b()])
    })
}

/// What watches an RGB565 frame build up: called with the frame so far and the rows just drawn.
pub type Watch<'a> = &'a mut dyn FnMut(&[u16], Range<u32>);

struct Rgb565Frame<'a> {
    width: u32,
    pixels: Vec<u16>,
    watch: Watch<'a>,
}

impl OriginDimensions for Rgb565Frame<'_> {
    fn size(&self) -> Size {
        Size::new(
            self.width,
            u32::try_from(self.pixels.len()).unwrap_or(0) / self.width.max(1),
        )
    }
}

impl DrawTarget for Rgb565Frame<'_> {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb565>>,
    {
        for Pixel(point, colour) in pixels {
            if let (Ok(x), Ok(y)) = (u32::try_from(point.x), u32::try_from(point.y))
                && x < self.width
                && let Some(pixel) = self.pixels.get_mut((y * self.width + x) as usize)
            {
                *pixel = colour.into_storage();
            }
        }
        Ok(())
    }

    /// As the default, then shows `watch` the rows drawn.
    fn fill_contiguous<I>(&mut self, area: &Rectangle, colours: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Rgb565>,
    {
        self.draw_iter(
            area.points()
                .zip(colours)
                .map(|(point, colour)| Pixel(point, colour)),
        )?;
        let top = u32::try_from(area.top_left.y).unwrap_or(0);
        (self.watch)(&self.pixels, top..top + area.size.height);
        Ok(())
    }
}
