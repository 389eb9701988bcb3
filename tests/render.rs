//! The scanline renderer through a recording display: every pixel exactly once, row by row,
//! each row as one rectangle; and its errors.

use core::convert::Infallible;
use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use obscura::{I16F16, RenderError, Scene, render_rows, scenes};

/// A display that records what it is sent.
struct Recorder {
    size: Size,
    rectangles: Vec<Rectangle>,
    writes: Vec<u32>,
}

impl Recorder {
    fn new(width: u32, height: u32) -> Self {
        Self {
            size: Size::new(width, height),
            rectangles: Vec::new(),
            writes: vec![0; (width * height) as usize],
        }
    }
}

impl OriginDimensions for Recorder {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Recorder {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, _: I) -> Result<(), Infallible> {
        panic!("the renderer must send whole rows through fill_contiguous, not single pixels");
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colours: I,
    ) -> Result<(), Infallible> {
        self.rectangles.push(*area);
        let mut count = 0;
        for (point, _) in area.points().zip(colours) {
            self.writes[(point.y as u32 * self.size.width + point.x as u32) as usize] += 1;
            count += 1;
        }
        assert_eq!(
            count,
            area.size.width * area.size.height,
            "one colour per pixel of the area"
        );
        Ok(())
    }
}

type SmallScene = Scene<I16F16, 8, 4, 6>;

#[test]
fn every_pixel_exactly_once_row_by_row() {
    let (width, height) = (40, 24);
    let scene = SmallScene::build(&scenes::SHAPES).unwrap();
    let camera = scene.camera(width, height).unwrap();
    let mut display = Recorder::new(width, height);
    let mut line = [Rgb565::BLACK; 40];
    render_rows(&scene, &camera, 0..height, &mut line, &mut display).unwrap();
    assert!(
        display.writes.iter().all(|&n| n == 1),
        "a pixel written other than once"
    );
    let expected: Vec<_> = (0..height)
        .map(|y| Rectangle::new(Point::new(0, y as i32), Size::new(width, 1)))
        .collect();
    assert_eq!(display.rectangles, expected);
}

#[test]
fn a_band_of_rows_and_a_longer_line_buffer() {
    let scene = SmallScene::build(&scenes::WHITTED).unwrap();
    let camera = scene.camera(16, 16).unwrap();
    let mut display = Recorder::new(16, 16);
    let mut line = [Rgb565::BLACK; 64];
    render_rows(&scene, &camera, 5..9, &mut line, &mut display).unwrap();
    let written: Vec<_> = display.rectangles.iter().map(|r| r.top_left.y).collect();
    assert_eq!(written, [5, 6, 7, 8]);
    for (i, &n) in display.writes.iter().enumerate() {
        assert_eq!(n, u32::from((5..9).contains(&(i / 16))), "pixel {i}");
    }
}

#[test]
fn the_same_rows_in_two_bands_equal_one_pass() {
    // MockDisplay fails on a pixel drawn twice or outside it: two bands must tile the frame.
    let scene = SmallScene::build(&scenes::WHITTED).unwrap();
    let camera = scene.camera(32, 32).unwrap();
    let mut line = [Rgb565::BLACK; 32];
    let mut whole = MockDisplay::new();
    render_rows(&scene, &camera, 0..32, &mut line, &mut whole).unwrap();
    let mut banded = MockDisplay::new();
    render_rows(&scene, &camera, 0..13, &mut line, &mut banded).unwrap();
    render_rows(&scene, &camera, 13..32, &mut line, &mut banded).unwrap();
    whole.assert_eq(&banded);
}

#[test]
fn short_line_buffer_and_rows_beyond_the_image_are_refused() {
    let scene = SmallScene::build(&scenes::WHITTED).unwrap();
    let camera = scene.camera(16, 8).unwrap();
    let mut display = Recorder::new(16, 8);
    let mut short = [Rgb565::BLACK; 15];
    assert_eq!(
        render_rows(&scene, &camera, 0..8, &mut short, &mut display),
        Err(RenderError::LineBufferTooSmall {
            needed: 16,
            got: 15
        })
    );
    let mut line = [Rgb565::BLACK; 16];
    assert_eq!(
        render_rows(&scene, &camera, 4..9, &mut line, &mut display),
        Err(RenderError::RowsOutOfRange { end: 9, height: 8 })
    );
    assert!(
        display.rectangles.is_empty(),
        "nothing drawn before the error"
    );
}
