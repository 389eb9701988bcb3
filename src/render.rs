//! The scanline renderer: traces a range of rows into a line buffer and sends each finished row
//! to an embedded-graphics [`DrawTarget`] as one rectangle. It needs no frame buffer.

use crate::camera::Camera;
use crate::color::DisplayColor;
use crate::scalar::Scalar;
use crate::scene::Scene;
use core::fmt;
use core::ops::Range;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

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
    /// The rows asked for end below the image. Ask for rows within `0..height`.
    RowsOutOfRange {
        /// The end of the requested rows.
        end: u32,
        /// The image height.
        height: u32,
    },
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
            Self::RowsOutOfRange { end, height } => {
                write!(
                    f,
                    "rows up to {end} were asked for, but the image has {height}"
                )
            }
            Self::Target(e) => write!(f, "the display failed: {e:?}"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for RenderError<E> {}

/// Renders `rows` of the image that `camera` sees of `scene`, top to bottom. Row y of the image
/// goes to row y of `target` (pixels (0, y) to (width − 1, y)), through `line`, which must hold
/// a row.
///
/// # Errors
/// [`RenderError`] for a short line buffer, rows beyond the image, or a failing target.
pub fn render_rows<S, C, D, const OBJECTS: usize, const LIGHTS: usize, const RAYS: usize>(
    scene: &Scene<S, OBJECTS, LIGHTS, RAYS>,
    camera: &Camera<S>,
    rows: Range<u32>,
    line: &mut [C],
    target: &mut D,
) -> Result<(), RenderError<D::Error>>
where
    S: Scalar,
    C: DisplayColor,
    D: DrawTarget<Color = C>,
{
    let width = camera.width();
    let too_small = RenderError::LineBufferTooSmall {
        needed: width,
        got: line.len(),
    };
    let line = usize::try_from(width)
        .ok()
        .and_then(|w| line.get_mut(..w))
        .ok_or(too_small)?;
    if rows.end > camera.height() {
        return Err(RenderError::RowsOutOfRange {
            end: rows.end,
            height: camera.height(),
        });
    }
    let (end, height) = (rows.end, camera.height());
    for y in rows {
        let row = camera
            .row(y)
            .ok_or(RenderError::RowsOutOfRange { end, height })?;
        for (pixel, ray) in line.iter_mut().zip(row.rays()) {
            *pixel = scene.trace(ray).colour.quantize();
        }
        // Both fit i32: they are at most MAX_IMAGE_SIDE.
        let top = i32::try_from(y).unwrap_or(i32::MAX);
        let row = Rectangle::new(Point::new(0, top), Size::new(width, 1));
        target
            .fill_contiguous(&row, line.iter().copied())
            .map_err(RenderError::Target)?;
    }
    Ok(())
}
