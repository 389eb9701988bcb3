//! Adaptive image-space sampling ([`crate::Pixels::Adaptive`]): fewer rays than pixels. The
//! image is cut into blocks of N×N pixels whose corners are pixel centres N apart, each traced
//! as that pixel's own ray; where a block's four corners agree its pixels are filled between them,
//! else it splits into four of half the size and traces their new corners, down to blocks of 2,
//! whose pixels are traced one by one (image-space subdivision, as old as Whitted's 1980 paper;
//! the real-time tracers of small chips trace one pixel in several the same way).
//!
//! Corners **agree** when their primary rays met the same object (on a checkered plane, the same
//! square), their ray trees the same objects (every object a ray of the tree met or was shadowed
//! by, [`Sample::met`], those from 15 on sharing a bit: the same reflections, refractions and
//! shadows), and their colours are within [`CONTRAST`] in every channel. A filled pixel is the
//! bilinear mean of its block's corners, in integers of 16-bit fractions, rounded once: the
//! same bits on every machine.
//!
//! **No object vanishes** between corners that agree: a block is filled only if every object
//! that culling says a primary ray of the block's rows and columns may meet ([`crate::cull`],
//! whose bounds hold whatever the rounding) is the corners' object or a plane, and the corners'
//! object is not a mesh. The region of the image where a sphere, a triangle or the world's
//! piece of a plane is seen before any plane is the image of a convex solid (the shape cut by
//! each plane's half-space on the eye's side), so convex: a block whose four corners see it sees
//! it all through. Anything else that may appear in the block has its block traced pixel by
//! pixel. What the rule cannot see is what no primary ray's object says: a thin shadow, a
//! small reflection, or a checker square between corners of the same colour (the stress cases
//! of `obscura stress`).
//!
//! No frame buffer: the corners of a band of N rows lie on its even rows, kept in the corner
//! rows a renderer passes ([`crate::CornerRows`]), N/2 + 1 rows of `width/2 + 1` corners
//! ([`crate::adaptive::node_rows`]), each traced only when a block asks for it; a band's
//! bottom row is the next band's top. A pixel's colour is a function of its place alone, so
//! every order of rows (two cores, a progressive frame) draws the same frame. A block the
//! image's right or bottom edge cuts is traced pixel by pixel.

crate::phase::declare_phase!(Some(crate::phase::Phase::Output));

use crate::adaptive::{Corner, contrast};
use crate::camera::{Camera, Row as CameraRow};
use crate::row_pass::PlaneRow;
use crate::color::{DisplayColor, Dither, Rgb};
use crate::cull::{RowRanges, SHARED_BIT};
use crate::pattern::SampleId;
use crate::ray::{Ray, Span};
use crate::scalar::Scalar;
use crate::scene::Scene;
use crate::shade::{Sample, Task, Tracer, bit};
use crate::shape::Shape;
use crate::shape::mesh::Meshes;
use crate::uses::Parts;
use heapless::Vec;

/// How far apart a block's corners may be, in any channel, for its pixels to be filled: a
/// thirty-second of full scale, some eight levels of an 8-bit channel.
pub const CONTRAST: u16 = 0x0800;

/// The largest block.
const MAX_BLOCK: u32 = 8;

/// The rows of corners a band keeps: its even rows.
const MAX_SLOTS: usize = MAX_BLOCK as usize / 2 + 1;

/// A traced corner of a block: its colour, and what its ray tree met.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Node {
    colour: Corner,
    /// The primary ray's object ([`NOTHING`]: none).
    object: u16,
    /// The objects the tree met, a bit each ([`Sample::met`]'s first 15, and bit 15 for the
    /// rest).
    met: u16,
    /// On a checkered plane, the square the primary ray met, its two coordinates folded into
    /// 16 bits (squares a block apart never fold alike); else 0.
    square: u16,
}

/// The objects from this one on share the last bit of [`Node::met`].
const MET_SHARED: u32 = 15;

/// A node's object where it is not yet traced.
const UNTRACED: u16 = u16::MAX;

/// A node's object where its primary ray met nothing.
const NOTHING: u16 = u16::MAX - 1;

impl Node {
    /// The node of a corner whose ray brought back `sample` and met a checker's `square`.
    fn of<S: Scalar>(sample: &Sample<S>, square: Option<[i32; 2]>) -> Self {
        let object = sample
            .object
            .map_or(NOTHING, |i| u16::try_from(i).unwrap_or(NOTHING - 1).min(NOTHING - 1));
        let low = sample.met & ((1 << MET_SHARED) - 1);
        let rest = u64::from(sample.met >> MET_SHARED != 0) << MET_SHARED;
        let square = square.map_or(0, |[u, v]| (u ^ v.rotate_left(8)) as u16);
        Self {
            colour: Corner::of(sample.colour),
            object,
            met: u16::try_from(low | rest).unwrap_or(u16::MAX),
            square,
        }
    }

    /// The node kept in `pair`, if it is traced.
    fn load(pair: &[Corner]) -> Option<Self> {
        let [colour, Corner([object, met, square])] = *pair else {
            return None;
        };
        (object != UNTRACED).then_some(Self {
            colour,
            object,
            met,
            square,
        })
    }

    fn store(self, pair: &mut [Corner]) {
        if let [colour, path] = pair {
            *colour = self.colour;
            *path = Corner([self.object, self.met, self.square]);
        }
    }

    /// The primary ray's object.
    fn object(&self) -> Option<usize> {
        (self.object < NOTHING).then_some(usize::from(self.object))
    }

    /// Whether the ray trees of both met the same objects.
    fn same_path(&self, other: &Self) -> bool {
        [self.object, self.met, self.square] == [other.object, other.met, other.square]
    }
}

/// What adaptive pixels keep between rows: the corners of the band's even rows, and the band's
/// culling ranges.
pub(crate) struct Blocks<'a> {
    nodes: &'a mut [Corner],
    block: u32,
    /// The image row each row of `nodes` holds (`u32::MAX`: none).
    held: [u32; MAX_SLOTS],
    /// The band's top row, and for each object the pixels that any of the band's rows may meet
    /// it at.
    band: Option<(u32, RowRanges)>,
    /// The scene's planes and meshes, a bit each (of the objects below [`SHARED_BIT`]).
    planes: u32,
    meshes: u32,
}

impl<'a> Blocks<'a> {
    /// Adaptive pixels of blocks of `block` (2, 4 or 8) in `nodes`
    /// ([`crate::adaptive::node_rows`] of them).
    pub(crate) fn new(nodes: &'a mut [Corner], block: u8) -> Self {
        Self {
            nodes,
            block: u32::from(block).clamp(2, MAX_BLOCK),
            held: [u32::MAX; MAX_SLOTS],
            band: None,
            planes: 0,
            meshes: 0,
        }
    }
}

/// Traces `row` (row `y` of the image) into `line` by adaptive pixels, each pixel quantised by
/// `dither`.
#[inline(never)]
pub(crate) fn trace_row<
    S,
    C,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
>(
    scene: &Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
    row: &CameraRow<S>,
    y: u32,
    dither: Dither,
    line: &mut [C],
    blocks: &mut Blocks<'_>,
) where
    S: Scalar,
    C: DisplayColor,
{
    let mut line = Line { line, dither, y };
    let row = &row.narrowed(Tracer::<S, M, P>::USES);
    Row {
        scene,
        blocks,
        y,
        own: OwnRays::new(scene, row, y),
        shown: &mut line,
    }
    .run();
}

/// What the pixels of a row traced by their own rays share, as exact pixels do
/// ([`crate::render`]): the row, its row pass ([`crate::row_pass`]) and its culling.
struct OwnRays<'r, S: Scalar> {
    row: &'r CameraRow<S>,
    plane: Option<PlaneRow<'r, S>>,
    ranges: RowRanges,
}

impl<'r, S: Scalar> OwnRays<'r, S> {
    fn new<const OBJECTS: usize, const LIGHTS: usize, const RAYS: usize, P: Parts, M: Meshes<S>>(
        scene: &'r Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
        row: &'r CameraRow<S>,
        y: u32,
    ) -> Self {
        let bounds = scene.objects.iter().map(|object| &object.bound);
        Self {
            row,
            plane: scene.tracer(SampleId::default()).plane_row(row),
            ranges: RowRanges::new(bounds, row.camera().image_plane(), y),
        }
    }
}

/// Where a row's pixels go: each pixel's colour, and the object its block's corners (or its own
/// ray) met first.
trait Shown<S: Scalar> {
    fn show(&mut self, x: u32, colour: Rgb<S>, object: Option<usize>);
}

/// A line of the display's colours.
struct Line<'l, C> {
    line: &'l mut [C],
    dither: Dither,
    y: u32,
}

impl<S: Scalar, C: DisplayColor> Shown<S> for Line<'_, C> {
    #[inline(always)]
    fn show(&mut self, x: u32, colour: Rgb<S>, _: Option<usize>) {
        if let Some(pixel) = self.line.get_mut(x as usize) {
            *pixel = colour.quantize_at(self.dither, x, self.y);
        }
    }
}

/// The objects each pixel of row `y` shows by adaptive pixels of blocks of `block`, through
/// `nodes` ([`crate::adaptive::node_rows`] of them): the object its block's corners met
/// first, or its own ray's. What the harness holds against an exact frame's objects: an
/// object that vanished between corners shows as a mismatch.
pub fn shown_objects<
    S: Scalar,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
>(
    scene: &Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
    camera: &Camera<S>,
    nodes: &mut [Corner],
    block: u8,
    y: u32,
) -> impl Iterator<Item = Option<usize>> + use<S, OBJECTS, LIGHTS, RAYS, P, M> {
    struct Objects(Vec<Option<usize>, { crate::camera::MAX_IMAGE_SIDE as usize }>);
    impl<S: Scalar> Shown<S> for Objects {
        fn show(&mut self, x: u32, _: Rgb<S>, object: Option<usize>) {
            if let Some(slot) = self.0.get_mut(x as usize) {
                *slot = object;
            }
        }
    }
    let width = camera.width() as usize;
    let mut objects = Objects(core::iter::repeat_n(None, width).collect());
    let mut blocks = Blocks::new(nodes, block);
    if let Some(row) = camera.narrowed(P::USES).row(y) {
        Row {
            scene,
            blocks: &mut blocks,
            y,
            own: OwnRays::new(scene, &row, y),
            shown: &mut objects,
        }
        .run();
    }
    objects.0.into_iter()
}

/// One row being traced.
struct Row<
    'r,
    'a,
    S: Scalar,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M,
    W,
> {
    scene: &'r Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
    blocks: &'r mut Blocks<'a>,
    y: u32,
    own: OwnRays<'r, S>,
    shown: &'r mut W,
}

impl<S, const OBJECTS: usize, const LIGHTS: usize, const RAYS: usize, P, M, W>
    Row<'_, '_, S, OBJECTS, LIGHTS, RAYS, P, M, W>
where
    S: Scalar,
    P: Parts,
    M: Meshes<S>,
    W: Shown<S>,
{
    /// Traces the row, block by block.
    fn run(&mut self) {
        let block = self.blocks.block;
        self.enter_band(self.y & !(block - 1));
        let width = self.own.row.camera().width();
        for x in (0..width).step_by(block as usize) {
            self.fill(x, block);
        }
    }

    /// Finds the culling ranges of the band of rows from `top`, unless they are held.
    fn enter_band(&mut self, top: u32) {
        if matches!(self.blocks.band, Some((held, _)) if held == top) {
            return;
        }
        let camera = &self.own.row.camera();
        let plane = camera.image_plane();
        let bounds = || self.scene.objects.iter().map(|object| &object.bound);
        let last = (top + self.blocks.block).min(camera.height().saturating_sub(1));
        let mut ranges = RowRanges::new(bounds(), plane, top);
        for y in top + 1..=last {
            ranges.widen(&RowRanges::new(bounds(), plane, y));
        }
        self.blocks.band = Some((top, ranges));
        let (mut planes, mut meshes) = (0, 0);
        for (i, object) in self.scene.objects.iter().enumerate().take(SHARED_BIT) {
            match object.shape {
                Shape::Plane(_) => planes |= 1 << i,
                Shape::Mesh(_) => meshes |= 1 << i,
                _ => {}
            }
        }
        (self.blocks.planes, self.blocks.meshes) = (planes, meshes);
    }

    /// Fills the row's pixels of the block of `size` whose left column is `x0`: from its corners
    /// where they agree, else by its halves, or pixel by pixel.
    fn fill(&mut self, x0: u32, size: u32) {
        let (width, height) = (self.own.row.camera().width(), self.own.row.camera().height());
        // Sizes are powers of two: a mask, where a remainder would be a division on the M0.
        let y0 = self.y & !(size - 1);
        let (x1, y1) = (x0 + size, y0 + size);
        let inside = x1 < width && y1 < height;
        if inside {
            let corners = [
                self.node(x0, y0),
                self.node(x1, y0),
                self.node(x0, y1),
                self.node(x1, y1),
            ];
            if self.agree(&corners, x0, x1) {
                let [first, ..] = corners;
                for x in x0..x1 {
                    let colour = mean::<S>(&corners, [x - x0, self.y - y0], size);
                    self.shown.show(x, colour, first.object());
                }
                return;
            }
            if size > 2 {
                self.fill(x0, size / 2);
                self.fill(x0 + size / 2, size / 2);
                return;
            }
        }
        for x in x0..x1.min(width) {
            if x % 2 == 0 && self.y % 2 == 0 {
                let node = self.node(x, self.y);
                self.shown.show(x, Rgb::from_q16(node.colour.q16()), node.object());
            } else {
                let (colour, object) = self.own_ray(x);
                self.shown.show(x, colour, object);
            }
        }
    }

    /// Pixel x of the row by its own ray, as an exact pixel: by the row pass where its ray can
    /// meet the plane alone, else traced. Its colour, and the object it met first.
    fn own_ray(&self, x: u32) -> (Rgb<S>, Option<usize>) {
        let own = &self.own;
        let candidates = own.ranges.within(x, x);
        let id = SampleId { x, y: self.y, sample: 0 };
        let mut tracer = self.scene.tracer(id);
        let Some(s) = own.row.centre(x) else {
            return (Rgb::BLACK, None);
        };
        if let Some(plane) = own.plane.as_ref().filter(|p| candidates == p.candidates()) {
            return match plane.hit(s) {
                Some(hit) => (tracer.shade_plane_row(plane, hit, id), Some(plane.object().0)),
                None => (tracer.background(own.row.through(s).dir), None),
            };
        }
        let mut stack: Vec<Task<S>, RAYS> = Vec::new();
        let sample = tracer.trace_ray(own.row.through(s), id, candidates, stack.as_mut_view());
        (sample.colour, sample.object)
    }

    /// Whether a block whose columns run from `x0` to `x1` may be filled from `corners`: they
    /// met the same objects, their colours are close, and no other object can show between them.
    fn agree(&self, corners: &[Node; 4], x0: u32, x1: u32) -> bool {
        let [first, ..] = corners;
        let colours = corners.map(|node| node.colour);
        corners.iter().all(|node| node.same_path(first))
            && contrast(&colours) <= CONTRAST
            && self.clear(first.object, x0, x1)
    }

    /// Whether every object a primary ray of the band may meet between columns `x0` and `x1`
    /// is `object` or a plane, and `object` is no mesh.
    fn clear(&self, object: u16, x0: u32, x1: u32) -> bool {
        let Some((_, ranges)) = &self.blocks.band else {
            return false;
        };
        let own = 1_u32.checked_shl(u32::from(object)).filter(|_| usize::from(object) < SHARED_BIT);
        let own = own.unwrap_or(0);
        own & self.blocks.meshes == 0 && ranges.within(x0, x1) & !(self.blocks.planes | own) == 0
    }

    /// Corner (x, y) of a block, traced where the band's rows do not hold it yet.
    fn node(&mut self, x: u32, y: u32) -> Node {
        let slot = self.slot(y);
        let per_row = self.own.row.camera().width() as usize / 2 + 1;
        let at = 2 * (slot * per_row + x as usize / 2);
        if self.blocks.held.get(slot) != Some(&y) {
            let start = 2 * slot * per_row;
            if let Some(row) = self.blocks.nodes.get_mut(start..start + 2 * per_row) {
                for pair in row.chunks_exact_mut(2) {
                    if let [_, path] = pair {
                        path.0[0] = UNTRACED;
                    }
                }
            }
            if let Some(held) = self.blocks.held.get_mut(slot) {
                *held = y;
            }
        }
        if let Some(node) = self.blocks.nodes.get(at..at + 2).and_then(Node::load) {
            return node;
        }
        let node = self.ray(x, y);
        if let Some(pair) = self.blocks.nodes.get_mut(at..at + 2) {
            node.store(pair);
        }
        node
    }

    /// The row of nodes that holds image row `y`, or else one that holds a row outside the
    /// band (of its `block/2 + 1` even rows, which are all a band asks for, one is free).
    fn slot(&self, y: u32) -> usize {
        let slots = self.blocks.block as usize / 2 + 1;
        let held = self.blocks.held.get(..slots).unwrap_or(&[]);
        let top = self.blocks.band.as_ref().map_or(0, |(top, _)| *top);
        let outside = |row: u32| row < top || row > top + self.blocks.block;
        held.iter()
            .position(|&row| row == y)
            .or_else(|| held.iter().position(|&row| outside(row)))
            .unwrap_or(0)
    }

    /// Traces pixel (x, y)'s ray, testing the objects the band's culling says it may meet.
    fn ray(&self, x: u32, y: u32) -> Node {
        let candidates = self
            .blocks
            .band
            .as_ref()
            .map_or(u32::MAX, |(_, ranges)| ranges.within(x, x));
        let id = SampleId { x, y, sample: 0 };
        let tracer = self.scene.tracer(id);
        let row = self.own.row.camera().row(y);
        let (Some(row), Some(s)) = (row, row.and_then(|row| row.centre(x))) else {
            let nothing = Sample {
                colour: Rgb::<S>::BLACK,
                object: None,
                met: 0,
            };
            return Node::of(&nothing, None);
        };
        // By the row pass where the ray can meet the plane alone, as an exact pixel is.
        let plane = tracer.plane_row(&row);
        if let Some(plane) = plane.filter(|plane| candidates == plane.candidates()) {
            let Some(hit) = plane.hit(s) else {
                let sky = Sample {
                    colour: tracer.background(row.through(s).dir),
                    object: None,
                    met: 0,
                };
                return Node::of(&sky, None);
            };
            let index = plane.object().0;
            let mut met = bit(index);
            let colour = tracer.light_plane_row(&plane, hit, id, &mut met);
            let lit = Sample {
                colour,
                object: Some(index),
                met,
            };
            return Node::of(&lit, plane.square(hit));
        }
        let ray = row.through(s);
        let mut stack: Vec<Task<S>, RAYS> = Vec::new();
        let mut tracer = tracer;
        let sample = tracer.trace_ray(ray, id, candidates, stack.as_mut_view());
        let square = sample.object.and_then(|i| self.square(&ray, i));
        Node::of(&sample, square)
    }

    /// The checker's square where `ray` meets object `index`, if it is a checkered plane.
    fn square(&self, ray: &Ray<S>, index: usize) -> Option<[i32; 2]> {
        let Shape::Plane(plane) = self.scene.objects.get(index)?.shape else {
            return None;
        };
        let settings = &self.scene.settings;
        let span = Span {
            min: settings.tolerance_base,
            max: settings.ray_length,
        };
        let t = plane.intersect(ray, span, settings.methods.roots)?;
        plane.square(ray.at(t))
    }
}

/// The colour at (dx, dy) pixels from the top left corner of a block of `size` with `corners`
/// (top left, top right, bottom left, bottom right): their bilinear mean, in 16-bit fractions.
/// Each term is at most 2¹⁶ times size², at most 2²² in all.
fn mean<S: Scalar>(corners: &[Node; 4], [dx, dy]: [u32; 2], size: u32) -> Rgb<S> {
    let weights = [
        (size - dx) * (size - dy),
        dx * (size - dy),
        (size - dx) * dy,
        dx * dy,
    ];
    let shift = 2 * size.trailing_zeros();
    let sum = corners
        .iter()
        .zip(weights)
        .fold([0_u32; 3], |sum, (node, weight)| {
            let [r, g, b] = node.colour.q16();
            [sum[0] + r * weight, sum[1] + g * weight, sum[2] + b * weight]
        });
    Rgb::from_q16(sum.map(|channel| (channel + (1 << shift >> 1)) >> shift))
}
