//! Whole frames on the desktop: the core's scanline renderer run on several threads, row by
//! row, into an image.

use crate::canvas::Canvas;
use crate::format::{Format, FormatJob};
use anyhow::{Context, Result};
use embedded_graphics::pixelcolor::{IntoStorage, Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use image::RgbImage;
use obscura::{Camera, Methods, RootMethod, Scalar, Scene, SceneDesc, render_rows};
use std::convert::Infallible;
use std::io::Write;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU32, Ordering};
use std::time::{Duration, Instant};

/// Every core of this machine: the threads of a render that is not timed.
pub fn all_cores() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZero::get)
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
/// exact roots (f64 has no others), so that a difference is the format's numeric error alone.
///
/// # Errors
/// When the scene is invalid or too large even for f64.
pub fn prepare_reference(request: &Request<'_>) -> Result<Box<dyn AnyFormat>> {
    prepare(
        Format::F64,
        &Request {
            methods: exact_roots(request.methods),
            ..*request
        },
    )
}

/// Objects a scene on the host may have.
pub const MAX_OBJECTS: usize = 64;
/// Lights a scene on the host may have.
pub const MAX_LIGHTS: usize = 16;
/// The host's ray stack: ray trees up to 15 levels deep.
pub const RAY_STACK: usize = 16;

/// A scene in format `S` with the host's capacities.
pub type HostScene<S> = Scene<S, MAX_OBJECTS, MAX_LIGHTS, RAY_STACK>;

/// A render request: a scene, an image size and the methods.
#[derive(Clone, Copy, Debug)]
pub struct Request<'a> {
    /// The scene.
    pub desc: &'a SceneDesc<'a>,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The numerical methods.
    pub methods: Methods,
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
        let scene = HostScene::<S>::build_with(request.desc, request.methods)
            .with_context(|| format!("the scene cannot be built in {}", S::NAME))?;
        let camera = scene.camera(request.width, request.height)?;
        Ok(Self { scene, camera })
    }

    /// Renders the frame on `threads` threads, each taking the next row not yet taken.
    pub fn render(&self, threads: usize, progress: Option<&str>) -> RgbImage {
        let (width, height) = (self.camera.width(), self.camera.height());
        let image = Mutex::new(RgbImage::new(width, height));
        let next_row = AtomicU32::new(0);
        let rows_done = AtomicU32::new(0);
        std::thread::scope(|scope| {
            for _ in 0..threads.max(1) {
                scope.spawn(|| {
                    let mut line = vec![Rgb888::BLACK; width as usize];
                    let mut target = SharedImage(&image);
                    loop {
                        let y = next_row.fetch_add(1, Ordering::Relaxed);
                        if y >= height {
                            break;
                        }
                        let rendered = render_rows(
                            &self.scene,
                            &self.camera,
                            y..y + 1,
                            &mut line,
                            &mut target,
                        );
                        // The camera fits the image, the line holds a row and the target is
                        // infallible: no error is possible here.
                        debug_assert!(rendered.is_ok());
                        rows_done.fetch_add(1, Ordering::Relaxed);
                    }
                });
            }
            if let Some(label) = progress {
                report_progress(label, &rows_done, height);
            }
        });
        image
            .into_inner()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// The frame in RGB565, as a display receives it, rendered on one thread through the same
    /// scanline renderer as the firmware's.
    pub fn rgb565_frame(&self) -> Vec<u16> {
        let (width, height) = (self.camera.width(), self.camera.height());
        let mut frame = Rgb565Frame {
            width,
            pixels: vec![0; (width * height) as usize],
        };
        let mut line = vec![Rgb565::BLACK; width as usize];
        let rendered = render_rows(&self.scene, &self.camera, 0..height, &mut line, &mut frame);
        // The camera fits the frame and the line holds a row: no error is possible here.
        debug_assert!(rendered.is_ok());
        frame.pixels
    }

    /// The index of the object each pixel's primary ray hits first, row by row, the rays made
    /// as the renderer makes them.
    pub fn object_map(&self) -> Vec<Option<usize>> {
        (0..self.camera.height())
            .flat_map(|y| self.camera.row(y).rays())
            .map(|ray| self.scene.first_hit(&ray))
            .collect()
    }
}

/// A prepared render whose number format was chosen at run time.
pub trait AnyFormat {
    /// See [`Prepared::render`].
    fn render(&self, threads: usize, progress: Option<&str>) -> RgbImage;
    /// See [`Prepared::object_map`].
    fn object_map(&self) -> Vec<Option<usize>>;
    /// See [`Prepared::rgb565_frame`].
    fn rgb565_frame(&self) -> Vec<u16>;
}

impl<S: Scalar> AnyFormat for Prepared<S> {
    fn render(&self, threads: usize, progress: Option<&str>) -> RgbImage {
        Prepared::render(self, threads, progress)
    }
    fn object_map(&self) -> Vec<Option<usize>> {
        Prepared::object_map(self)
    }
    fn rgb565_frame(&self) -> Vec<u16> {
        Prepared::rgb565_frame(self)
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
    format.run(Job(request))
}

/// Prints "label: 42%" on stderr every 100 ms once a second has passed, until every row is
/// done. It looks every 10 ms, so a short render is not held up waiting for it.
fn report_progress(label: &str, rows_done: &AtomicU32, height: u32) {
    let start = Instant::now();
    let mut last_shown = None;
    loop {
        let done = rows_done.load(Ordering::Relaxed);
        if done >= height {
            break;
        }
        let due = last_shown.is_none_or(|at: Instant| at.elapsed() >= Duration::from_millis(100));
        if start.elapsed() > Duration::from_secs(1) && due {
            eprint!(
                "\r{label}: {:3}%",
                u64::from(done) * 100 / u64::from(height)
            );
            let _ = std::io::stderr().flush();
            last_shown = Some(Instant::now());
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    if last_shown.is_some() {
        eprintln!("\r{label}: 100%");
    }
}

/// A frame of raw RGB565 values, row after row.
struct Rgb565Frame {
    width: u32,
    pixels: Vec<u16>,
}

impl OriginDimensions for Rgb565Frame {
    fn size(&self) -> Size {
        Size::new(
            self.width,
            u32::try_from(self.pixels.len()).unwrap_or(0) / self.width.max(1),
        )
    }
}

impl DrawTarget for Rgb565Frame {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb565>>,
    {
        for Pixel(point, colour) in pixels {
            if let (Ok(x), Ok(y)) = (u32::try_from(point.x), u32::try_from(point.y)) {
                if x < self.width {
                    if let Some(pixel) = self.pixels.get_mut((y * self.width + x) as usize) {
                        *pixel = colour.into_storage();
                    }
                }
            }
        }
        Ok(())
    }
}

/// An image shared by the render threads; each row is written under the lock once.
struct SharedImage<'a>(&'a Mutex<RgbImage>);

impl SharedImage<'_> {
    fn canvas<T>(&self, draw: impl FnOnce(&mut Canvas<'_>) -> T) -> T {
        let mut image = self
            .0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        draw(&mut Canvas(&mut image))
    }
}

impl OriginDimensions for SharedImage<'_> {
    fn size(&self) -> Size {
        self.canvas(|canvas| canvas.size())
    }
}

impl DrawTarget for SharedImage<'_> {
    type Color = Rgb888;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb888>>,
    {
        self.canvas(|canvas| canvas.draw_iter(pixels))
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colours: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Rgb888>,
    {
        self.canvas(|canvas| canvas.fill_contiguous(area, colours))
    }
}
