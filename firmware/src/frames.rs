//! What the firmware renders: each configured scene in each configured format, by the
//! configured methods (or by each variant of them), with the scene's storage (objects, lights,
//! ray stack) sized by const generics to exactly what it needs. The build script writes the
//! list ([`render_all`]) from the configuration, having proven each scene in each format on the
//! host: each frame's scene and camera as words ([`obscura::words`]), or the reason a chart's
//! variant is refused.

use crate::clock::Clock;
use crate::stack;
use core::fmt;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use obscura::mesh::MeshWords;
use obscura::{
    Bits, Camera, Corner, Parts, Presentation, ProvenScene, RenderError, Scene, render_frame,
};

/// What goes wrong drawing a frame on `B`'s display.
pub type FrameError<B> = RenderError<<<B as Backend>::Display as DrawTarget>::Error>;

/// What a display back-end provides: a display to draw each frame on, and a place to say how
/// it went.
pub trait Backend {
    /// The display.
    type Display: DrawTarget<Color = Rgb565, Error: fmt::Debug>;
    /// Readies the display for the frame of `job`.
    fn begin(&mut self, job: &Job<'_>);
    /// The display.
    fn display(&mut self) -> &mut Self::Display;
    /// Ends the frame begun.
    fn end(&mut self) {}
    /// Traces the frame `camera` sees of `scene` and sends it to the display in the order and
    /// dither of `presentation`: by default on this core, through one line buffer and the
    /// corner rows of adaptive anti-aliasing ([`render_frame`], [`CORNER_ROWS`]). A board with
    /// a second core shares the rows between them.
    ///
    /// # Errors
    /// When the display fails.
    fn draw_frame<
        S: Bits,
        const OBJECTS: usize,
        const LIGHTS: usize,
        const RAYS: usize,
        P: Parts,
    >(
        &mut self,
        scene: &Scene<S, OBJECTS, LIGHTS, RAYS, P, MeshWords<S>>,
        camera: &Camera<S>,
        presentation: Presentation,
    ) -> Result<(), FrameError<Self>> {
        let mut line = [Rgb565::BLACK; SIDE as usize];
        let mut corners = [Corner::ZERO; CORNER_ROWS];
        render_frame(
            scene,
            camera,
            presentation,
            &mut line,
            &mut corners,
            self.display(),
        )
    }
    /// Reports a finished frame.
    fn report(&mut self, report: &Report<'_>);
    /// Reports a frame that could not be drawn, and why.
    fn failed(&mut self, job: &Job<'_>, why: &dyn fmt::Display);
    /// Reports a chart variant whose scene the format cannot hold by its methods, and why:
    /// an outcome of the comparison, not a failure.
    fn refused(&mut self, job: &Job<'_>, why: &dyn fmt::Display);
}

/// One frame to draw.
#[derive(Clone, Copy, Debug)]
pub struct Job<'a> {
    /// The scene's name.
    pub scene: &'a str,
    /// The frame of the scene's camera path, if it has one.
    pub frame: Option<u16>,
    /// The format's name.
    pub format: &'a str,
    /// The methods, as they are spelled everywhere ([`obscura::Methods`]'s `Display`: the
    /// build's, so that the chip links no formatting of them).
    pub methods: &'a str,
    /// The order of its rows and its dither.
    pub presentation: Presentation,
}

impl Job<'_> {
    /// What the frame is called: the scene's name, and a camera path's frame as `NAME-frame-K`
    /// (the harness's name for it, `obscura_scene::NamedScene::at_frame`).
    pub fn name(&self) -> JobName<'_> {
        JobName(self)
    }
}

/// A frame's name ([`Job::name`]).
#[derive(Debug)]
pub struct JobName<'a>(&'a Job<'a>);

impl fmt::Display for JobName<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0.scene)?;
        match self.0.frame {
            // As a u64, whose formatting every report links already.
            Some(frame) => write!(f, "-frame-{}", u64::from(frame)),
            None => Ok(()),
        }
    }
}

/// The measurements of one frame.
#[derive(Debug)]
pub struct Report<'a> {
    /// What was drawn.
    pub job: &'a Job<'a>,
    /// SysTick ticks the frame took, from the first row to the last.
    pub ticks: u64,
    /// The stack's high-water mark during the frame, in bytes.
    pub stack_bytes: u32,
    /// Bytes of the scene and its ray stack with capacities sized to the scene.
    pub storage_bytes: usize,
    /// The same with the host's fixed capacities (64 objects, 16 lights, 16 rays).
    pub fixed_storage_bytes: usize,
}

pub use configured::{CORNER_ROWS, LOOPS, SIDE, render_all};
use configured::{MAX_LIGHTS, MAX_OBJECTS, RAY_STACK};

/// What a board shows: every configured frame, and where a scene has a camera path
/// ([`LOOPS`]), every frame again and again, for good.
pub fn show(backend: &mut impl Backend, clock: &Clock) {
    loop {
        render_all(backend, clock);
        if !LOOPS {
            return;
        }
    }
}

/// The frames the build configured, as its script wrote them.
mod configured {
    include!(concat!(env!("OUT_DIR"), "/frames.rs"));
}

/// Words a camera path's frames share but at some places: frame 0's words, the places where
/// any frame's differ, and each frame's words there, one frame's after the other. Positions are
/// kept relative to the eye, so that a scene's change with it; what the camera keeps of the
/// image's size and lens does not.
#[derive(Debug)]
pub struct Shared<const WORDS: usize> {
    /// Frame 0's words.
    pub base: [u32; WORDS],
    /// The places where any frame's words differ from frame 0's.
    pub changed: &'static [u16],
    /// Each frame's words at those places, frame after frame.
    pub values: &'static [u32],
}

impl<const WORDS: usize> Shared<WORDS> {
    /// Frame `n`'s words.
    fn frame(&self, n: usize) -> [u32; WORDS] {
        let mut words = self.base;
        let c = self.changed.len();
        let values = self.values.get(n * c..(n + 1) * c).unwrap_or_default();
        for (&at, &value) in self.changed.iter().zip(values) {
            if let Some(word) = words.get_mut(usize::from(at)) {
                *word = value;
            }
        }
        words
    }
}

/// Draws each of a camera path's `frames`, in order: `job` with the frame's number, its scene
/// and its camera from the words the frames share ([`Shared`]).
#[inline(never)]
pub fn draw_path<
    S: Bits,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    const SCENE_WORDS: usize,
    const CAMERA_WORDS: usize,
>(
    backend: &mut impl Backend,
    clock: &Clock,
    job: &Job<'_>,
    (scene, camera): (&Shared<SCENE_WORDS>, &Shared<CAMERA_WORDS>),
    frames: u16,
    meshes: &'static [u32],
) {
    for (n, frame) in (0..usize::from(frames)).zip(0..frames) {
        let job = Job {
            frame: Some(frame),
            ..*job
        };
        let (scene, camera) = (scene.frame(n), camera.frame(n));
        draw::<S, OBJECTS, LIGHTS, RAYS, P>(backend, clock, &job, &scene, meshes, &camera);
    }
}

/// Draws the frame of `job`: the scene whose words are `scene` (written by the build from the
/// scene it proved in format `S`), its meshes read in place from the words `meshes`, as the
/// camera whose words are `camera` sees it; then reports the frame. The chip builds and proves
/// nothing: it reads the scene back from its words. Out of line, so that each frame's scene
/// lives on the stack only while it is drawn.
#[inline(never)]
pub(crate) fn draw<
    S: Bits,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
>(
    backend: &mut impl Backend,
    clock: &Clock,
    job: &Job<'_>,
    scene: &[u32],
    meshes: &'static [u32],
    camera: &[u32],
) {
    // Hidden from the optimiser, so that no build folds a constant scene into the tracer: every
    // frame measures the same general code, whichever scenes and formats share the firmware.
    let proven = core::hint::black_box(ProvenScene {
        scene,
        meshes,
        camera,
    });
    stack::paint();
    let (scene, camera) =
        match Scene::<S, OBJECTS, LIGHTS, RAYS, P, MeshWords<S>>::from_proven(&proven) {
            Ok(read) => read,
            Err(error) => return backend.failed(job, &error),
        };
    backend.begin(job);
    let (drawn, ticks) = clock.measure(|| backend.draw_frame(&scene, &camera, job.presentation));
    backend.end();
    let stack_bytes = stack::high_water();
    match drawn {
        Ok(()) => backend.report(&Report {
            job,
            ticks,
            stack_bytes,
            storage_bytes: Scene::<S, OBJECTS, LIGHTS, RAYS, P, MeshWords<S>>::storage_bytes(),
            fixed_storage_bytes: Scene::<S, MAX_OBJECTS, MAX_LIGHTS, RAY_STACK>::storage_bytes(),
        }),
        Err(error) => backend.failed(job, &error),
    }
}
