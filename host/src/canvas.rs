//! [`Canvas`]: an `image` buffer as an embedded-graphics draw target, so that the harness
//! draws with the same API as a display (frames, legends, text).

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use image::RgbImage;
use std::convert::Infallible;

/// An RGB image to draw on; points outside it are ignored, as a display would.
#[derive(Debug)]
pub struct Canvas<'a>(pub &'a mut RgbImage);

impl Canvas<'_> {
    fn put(&mut self, point: Point, colour: Rgb888) {
        if let (Ok(x), Ok(y)) = (u32::try_from(point.x), u32::try_from(point.y))
            && x < self.0.width()
            && y < self.0.height()
        {
            self.0
                .put_pixel(x, y, image::Rgb([colour.r(), colour.g(), colour.b()]));
        }
    }
}

impl OriginDimensions for Canvas<'_> {
    fn size(&self) -> Size {
        Size::new(self.0.width(), self.0.height())
    }
}

impl DrawTarget for Canvas<'_> {
    type Color = Rgb888;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb888>>,
    {
        for Pixel(point, colour) in pixels {
            self.put(point, colour);
        }
        Ok(())
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colours: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Rgb888>,
    {
        for (point, colour) in area.points().zip(colours) {
            self.put(point, colour);
        }
        Ok(())
    }
}
