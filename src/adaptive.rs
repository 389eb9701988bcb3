//! Adaptive anti-aliasing after Whitted (1980): rays at the corners of each pixel, each corner
//! shared with the pixel's neighbours, and where a cell's four corners differ by more than
//! [`CONTRAST`] the cell splits into quarters, tracing its five new corners, down to cells of
//! 1/[`SceneDesc::samples`] of the pixel. A cell shows the mean of its corners, a pixel the
//! mean of its cells weighted by their areas. Flat regions cost about one ray a pixel when the
//! rows are traced top to bottom; only edges, silhouettes and textures pay for more. A point
//! on an edge two split cells share is traced by each (at depth 2 a pixel split all through
//! traces 25 points for 21 places, at depth 4 425 for 285): a cache of a pixel's points would
//! cost the stack a small MCU lacks.
//!
//! No frame buffer: the renderer keeps the corners along the top and the bottom of the row it
//! traces, two rows of `width + 1` [`Corner`]s ([`corner_rows`]), and the bottom corners of one
//! row are the top corners of the next. A corner's ray is a function of its place in the image
//! alone, whichever row traces it first, so every way of splitting a frame into rows draws the
//! same image; where a row does not follow the row above it in one call (a progressive frame,
//! two cores sharing the rows, [`crate::RowTracer`]) its top corners are traced again: about
//! two rays a flat pixel.
//!
//! The points are binary fractions of the pixel, exact in every format, and each traced colour
//! is clamped and kept in 16-bit fractions, as a pixel's samples are summed
//! ([`crate::render`]): the host in every format, the f64 reference and the firmware trace the
//! same rays and average them alike.
//!
//! [`SceneDesc::samples`]: crate::SceneDesc::samples

crate::phase::declare_phase!(Some(crate::phase::Phase::Output));

use crate::camera::{Camera, Row};
use crate::color::Rgb;
use crate::pattern::SampleId;
use crate::scalar::Scalar;
use crate::scene::Scene;
use crate::shape::mesh::Meshes;
use crate::uses::Parts;
use crate::vec3::Vec3;

/// The colour a ray traced at a corner of a cell brings back, clamped to what a display shows,
/// in 16-bit fractions: 1 and 1 − 2⁻¹⁶ are both kept as 0xFFFF, which reads back as 1, so that
/// white stays white in every format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Corner(pub(crate) [u16; 3]);

impl Corner {
    /// Black: what a corner buffer starts as, before any corner is traced into it.
    pub const ZERO: Self = Self([0; 3]);

    pub(crate) fn of<S: Scalar>(colour: Rgb<S>) -> Self {
        Self(
            colour
                .to_q16()
                .map(|c| u16::try_from(c).unwrap_or(u16::MAX)),
        )
    }

    /// The colour in 16-bit fractions, as [`Rgb::to_q16`] gives it (0xFFFF read as 1).
    pub(crate) fn q16(self) -> [u32; 3] {
        self.0.map(|c| u32::from(c) + u32::from(c == u16::MAX))
    }
}

/// Where a renderer keeps its corner rows ([`corner_rows`]): an array sized at compile time, or
/// any slice. An empty array holds none ([`Self::NONE`]): a firmware whose scenes take no
/// adaptive samples passes one, and the adaptive code is left out of its build.
pub trait CornerRows {
    /// Whether the type can hold no corner.
    const NONE: bool;
    /// The corners.
    fn rows(&mut self) -> &mut [Corner];
}

impl<const N: usize> CornerRows for [Corner; N] {
    const NONE: bool = N == 0;
    fn rows(&mut self) -> &mut [Corner] {
        self
    }
}

impl CornerRows for [Corner] {
    const NONE: bool = false;
    fn rows(&mut self) -> &mut [Corner] {
        self
    }
}

/// How far apart a cell's corners may be, in any channel, before it splits: a sixteenth of
/// full scale, some sixteen levels of an 8-bit channel.
pub const CONTRAST: u16 = 0x1000;

/// The most corners any scene keeps for an image `width` pixels wide: what a renderer that
/// does not know its scene passes. What a given scene needs is
/// [`SceneDesc::corner_rows`](crate::SceneDesc::corner_rows).
#[must_use]
pub const fn corner_rows(width: u32) -> usize {
    let samples = sample_rows(width);
    let blocks = node_rows(width, 8);
    if samples > blocks { samples } else { blocks }
}

/// The corner rows ([`crate::Corner`]s) that adaptive pixels of blocks of `block` keep for an
/// image `width` pixels wide: `block/2 + 1` rows of `width/2 + 1` corners of two
/// [`crate::Corner`]s each (a colour, and what the corner's ray tree met).
#[must_use]
pub const fn node_rows(width: u32, block: u8) -> usize {
    2 * (block as usize / 2 + 1) * (width as usize / 2 + 1)
}

/// The corners a renderer keeps for adaptive anti-aliasing of an image `width` pixels wide:
/// a row of `width + 1` above the row of pixels it traces and one below.
pub(crate) const fn sample_rows(width: u32) -> usize {
    2 * (width as usize + 1)
}

/// How deep a pixel of a scene with `samples` rays splits: into 4ᵈ cells, d = log₄ samples.
pub(crate) const fn depth(samples: u16) -> u32 {
    samples.trailing_zeros() / 2
}

/// Traces corner row `cy` (0 to the image's height) of the image `camera` sees of `scene` into
/// `corners`, one corner per pixel column and one for the right edge.
pub(crate) fn trace_corner_row<
    S,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
>(
    scene: &Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
    camera: &Camera<S>,
    cy: u32,
    corners: &mut [Corner],
) where
    S: Scalar,
{
    let (width, height) = (camera.width(), camera.height());
    // The corners along the image's bottom and right edges are the last pixels' far ones.
    let (y, down) = edge(cy, height);
    let Some(row) = camera.row(y) else { return };
    for (cx, corner) in (0..=width).zip(corners.iter_mut()) {
        let (x, across) = edge(cx, width);
        let Some(centre) = row.centre(x) else { return };
        let ray = row.sample(centre, [across, down], [S::ZERO; 2]);
        // Only a hash of it seeds the area lights' patterns: the corner's own place.
        let id = SampleId {
            x: cx,
            y: cy,
            sample: 0,
        };
        *corner = Corner::of(scene.trace(ray, id).colour);
    }
}

/// The pixel along an image side of `pixels` whose top (left) edge is grid line `line`, and
/// the offset from its centre to the line: −½, or +½ for the far edge of the last pixel.
fn edge<S: Scalar>(line: u32, pixels: u32) -> (u32, S) {
    let half = S::from_q16(0x8000);
    if line < pixels {
        (line, -half)
    } else {
        (pixels.saturating_sub(1), half)
    }
}

/// One pixel of a row, split where its corners differ: its cells' corners on a grid of
/// `2^depth` steps across the pixel.
pub(crate) struct Pixel<
    'a,
    S: Scalar,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
> {
    pub(crate) scene: &'a Scene<S, OBJECTS, LIGHTS, RAYS, P, M>,
    pub(crate) row: &'a Row<S>,
    pub(crate) centre: Vec3<S>,
    pub(crate) x: u32,
    pub(crate) y: u32,
    pub(crate) depth: u32,
}

impl<
    S: Scalar,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
> Pixel<'_, S, OBJECTS, LIGHTS, RAYS, P, M>
{
    /// The pixel's colour from its four corners (top left, top right, bottom left, bottom
    /// right): the mean of its cells weighted by area, in 16-bit fractions.
    pub(crate) fn colour(&self, corners: [Corner; 4]) -> Rgb<S> {
        let steps = 1_u32 << self.depth;
        let sum = self.cell(corners, [0, 0], steps);
        // Each cell adds its four corners times its area in grid cells: 4 · steps² in all.
        let total = 4 * steps * steps;
        Rgb::from_q16(sum.map(|s| (s + total / 2) / total))
    }

    /// The sum over the cell at grid point `at` of `size` steps of its cells' corners, each
    /// times its area in grid cells. At most 4 · 256 · 2¹⁶ = 2²⁶ for the deepest split.
    #[inline(never)]
    fn cell(&self, corners: [Corner; 4], at: [u32; 2], size: u32) -> [u32; 3] {
        if size == 1 || contrast(&corners) <= CONTRAST {
            let area = size * size;
            return corners
                .iter()
                .fold([0; 3], |sum, corner| {
                    let [r, g, b] = corner.q16();
                    [sum[0] + r, sum[1] + g, sum[2] + b]
                })
                .map(|channel| channel * area);
        }
        let half = size / 2;
        let [x, y] = at;
        let [top_left, top_right, bottom_left, bottom_right] = corners;
        let top = self.point([x + half, y]);
        let left = self.point([x, y + half]);
        let middle = self.point([x + half, y + half]);
        let right = self.point([x + size, y + half]);
        let bottom = self.point([x + half, y + size]);
        let quarters = [
            self.cell([top_left, top, left, middle], [x, y], half),
            self.cell([top, top_right, middle, right], [x + half, y], half),
            self.cell([left, middle, bottom_left, bottom], [x, y + half], half),
            self.cell(
                [middle, right, bottom, bottom_right],
                [x + half, y + half],
                half,
            ),
        ];
        quarters.iter().fold([0; 3], |sum, q| {
            [sum[0] + q[0], sum[1] + q[1], sum[2] + q[2]]
        })
    }

    /// Traces grid point `at` of the pixel: `at / 2^depth` of a pixel from its top left corner.
    fn point(&self, [gx, gy]: [u32; 2]) -> Corner {
        let offset =
            |g: u32| S::from_q16(i32::try_from((g << 16) >> self.depth).unwrap_or(0) - 0x8000);
        let ray = self
            .row
            .sample(self.centre, [offset(gx), offset(gy)], [S::ZERO; 2]);
        // Sample 0 is the corner's, traced by its corner row; the grid has at most 17 × 17
        // points.
        let points = (1 << self.depth) + 1;
        let sample = u16::try_from(1 + gy * points + gx).unwrap_or(u16::MAX);
        let id = SampleId {
            x: self.x,
            y: self.y,
            sample,
        };
        Corner::of(self.scene.trace(ray, id).colour)
    }
}

/// The largest difference between two of the corners in one channel.
pub(crate) fn contrast(corners: &[Corner; 4]) -> u16 {
    let (low, high) =
        corners
            .iter()
            .fold(([u16::MAX; 3], [0; 3]), |(low, high), Corner([r, g, b])| {
                (
                    [low[0].min(*r), low[1].min(*g), low[2].min(*b)],
                    [high[0].max(*r), high[1].max(*g), high[2].max(*b)],
                )
            });
    high.iter()
        .zip(low)
        .map(|(high, low)| high.saturating_sub(low))
        .max()
        .unwrap_or(0)
}

impl crate::desc::SceneDesc<'_> {
    /// The corner rows ([`crate::Corner`]s) a renderer of this scene passes for an image
    /// `width` pixels wide: adaptive samples' (two rows of `width + 1`), adaptive
    /// pixels' (N/2 + 1 rows of `width/2 + 1` corners of two `Corner`s each, for blocks of
    /// N), or none.
    #[must_use]
    pub const fn corner_rows(&self, width: u32) -> usize {
        corners_kept(self.adaptive_samples, self.pixels.block(), width)
    }
}

/// The corner rows a scene keeps at `width` with adaptive samples or not and adaptive pixels'
/// blocks of `block` (1: exact pixels).
pub(crate) const fn corners_kept(adaptive_samples: bool, block: u8, width: u32) -> usize {
    if adaptive_samples {
        sample_rows(width)
    } else if block > 1 {
        node_rows(width, block)
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::I24f8;

    /// A corner keeps a colour in 16 bits, and white must read back as exactly white: with eight
    /// fraction bits, 1 − 2⁻¹⁶ would round to 255/256 and show as 254.
    #[test]
    fn white_and_black_read_back_exactly() {
        fn check<S: Scalar>() {
            for colour in [Rgb::<S>::new(S::ONE, S::ONE, S::ONE), Rgb::BLACK] {
                assert_eq!(Corner::of(colour).q16(), colour.to_q16(), "{}", S::NAME);
            }
        }
        check::<f32>();
        check::<crate::I16F16>();
        check::<I24f8>();
    }
}
