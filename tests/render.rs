//! The scanline renderer through a recording display: every pixel exactly once, row by row,
//! each row as one rectangle; a progressive frame and a dithered one; and its errors.

use core::convert::Infallible;
use core::fmt::Debug;
use core::ops::Range;
use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use obscura::adaptive::CornerRows;
use obscura::{
    Corner, Dither, I16F16, Presentation, RenderError, RowOrder, RowTracer, Scene, SceneDesc,
    corner_rows, render_frame, scenes, send_row,
};

/// A display that records what it is sent.
struct Recorder {
    size: Size,
    rectangles: Vec<Rectangle>,
    writes: Vec<u32>,
    pixels: Vec<Rgb565>,
}

impl Recorder {
    fn new(width: u32, height: u32) -> Self {
        Self {
            size: Size::new(width, height),
            rectangles: Vec::new(),
            writes: vec![0; (width * height) as usize],
            pixels: vec![Rgb565::BLACK; (width * height) as usize],
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
        for (point, colour) in area.points().zip(colours) {
            let i = (point.y as u32 * self.size.width + point.x as u32) as usize;
            self.writes[i] += 1;
            self.pixels[i] = colour;
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

/// Draws `rows` of the frame top to bottom through one [`RowTracer`], as a renderer of bands
/// of rows does.
fn draw_band<D, K>(
    scene: &SmallScene,
    camera: &obscura::Camera<I16F16>,
    rows: Range<u32>,
    line: &mut [Rgb565],
    corners: &mut K,
    display: &mut D,
) where
    D: DrawTarget<Color = Rgb565, Error: Debug>,
    K: CornerRows + ?Sized,
{
    let mut tracer = RowTracer::new(scene, camera, Dither::None, line, corners).unwrap();
    for y in rows {
        send_row(display, tracer.trace(y).unwrap(), y, 1).unwrap();
    }
}

#[test]
fn every_pixel_exactly_once_row_by_row() {
    let (width, height) = (40, 24);
    let scene = SmallScene::build(&scenes::SHAPES).unwrap();
    let camera = scene.camera(width, height).unwrap();
    let mut display = Recorder::new(width, height);
    let mut line = [Rgb565::BLACK; 40];
    render_frame(
        &scene,
        &camera,
        Presentation::default(),
        &mut line,
        &mut [],
        &mut display,
    )
    .unwrap();
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
    draw_band(&scene, &camera, 5..9, &mut line, &mut [], &mut display);
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
    draw_band(&scene, &camera, 0..32, &mut line, &mut [], &mut whole);
    let mut banded = MockDisplay::new();
    draw_band(&scene, &camera, 0..13, &mut line, &mut [], &mut banded);
    draw_band(&scene, &camera, 13..32, &mut line, &mut [], &mut banded);
    whole.assert_eq(&banded);
}

/// `whitted` with adaptive samples.
fn adaptive_whitted() -> SmallScene {
    let desc = SceneDesc {
        samples: 16,
        adaptive_samples: true,
        ..scenes::WHITTED
    };
    SmallScene::build(&desc).unwrap()
}

/// A corner's ray depends on its place in the image alone: a frame with adaptive samples is the
/// same in one pass, in two bands, row by row from the bottom up (as two cores share the rows)
/// and in the progressive order, each tracing corner rows anew where it does not go down row
/// by row.
#[test]
fn adaptive_samples_draw_the_same_frame_however_the_rows_are_split() {
    let scene = adaptive_whitted();
    let camera = scene.camera(32, 32).unwrap();
    let mut line = [Rgb565::BLACK; 32];
    let mut corners = [Corner::ZERO; 66];
    assert_eq!(corner_rows(32), corners.len());
    let mut whole = MockDisplay::new();
    draw_band(&scene, &camera, 0..32, &mut line, &mut corners, &mut whole);
    let mut banded = MockDisplay::new();
    draw_band(&scene, &camera, 0..13, &mut line, &mut corners, &mut banded);
    draw_band(
        &scene,
        &camera,
        13..32,
        &mut line,
        &mut corners,
        &mut banded,
    );
    whole.assert_eq(&banded);
    let mut rows = MockDisplay::new();
    let mut tracer =
        RowTracer::new(&scene, &camera, Dither::None, &mut line, &mut corners).unwrap();
    for y in (0..32).rev() {
        send_row(&mut rows, tracer.trace(y).unwrap(), y, 1).unwrap();
    }
    whole.assert_eq(&rows);
    let progressive = Presentation {
        order: RowOrder::Progressive,
        dither: Dither::None,
    };
    let mut frame = Recorder::new(32, 32);
    render_frame(
        &scene,
        &camera,
        progressive,
        &mut line,
        &mut corners,
        &mut frame,
    )
    .unwrap();
    let mut top_down = Recorder::new(32, 32);
    draw_band(
        &scene,
        &camera,
        0..32,
        &mut line,
        &mut corners,
        &mut top_down,
    );
    assert_eq!(frame.pixels, top_down.pixels);
    // Not the one-sample frame: the edges are smoothed.
    let plain = SmallScene::build(&scenes::WHITTED).unwrap();
    let mut one = MockDisplay::new();
    draw_band(&plain, &camera, 0..32, &mut line, &mut [], &mut one);
    assert_ne!(one, whole);
}

#[test]
fn corner_rows_too_short_for_adaptive_samples_are_refused() {
    let scene = adaptive_whitted();
    let camera = scene.camera(16, 8).unwrap();
    let mut display = Recorder::new(16, 8);
    let mut line = [Rgb565::BLACK; 16];
    let mut corners = [Corner::ZERO; 33];
    assert_eq!(
        render_frame(
            &scene,
            &camera,
            Presentation::default(),
            &mut line,
            &mut corners,
            &mut display
        ),
        Err(RenderError::CornerRowsTooSmall {
            needed: 34,
            got: 33
        })
    );
    assert!(display.rectangles.is_empty());
}

#[test]
fn short_line_buffer_and_rows_beyond_the_image_are_refused() {
    let scene = SmallScene::build(&scenes::WHITTED).unwrap();
    let camera = scene.camera(16, 8).unwrap();
    let mut display = Recorder::new(16, 8);
    let mut short = [Rgb565::BLACK; 15];
    assert_eq!(
        render_frame(
            &scene,
            &camera,
            Presentation::default(),
            &mut short,
            &mut [],
            &mut display
        ),
        Err(RenderError::LineBufferTooSmall {
            needed: 16,
            got: 15
        })
    );
    assert!(
        display.rectangles.is_empty(),
        "nothing drawn before the error"
    );
    let mut line = [Rgb565::BLACK; 16];
    let mut tracer = RowTracer::new(&scene, &camera, Dither::None, &mut line, &mut []).unwrap();
    assert_eq!(
        tracer.trace(8),
        Err(RenderError::RowsOutOfRange { end: 9, height: 8 })
    );
    assert_eq!(tracer.trace(7).map(<[Rgb565]>::len), Ok(16));
}

/// `whitted` rendered whole at `width × height` by `presentation` into a recorder.
fn frame(width: u32, height: u32, presentation: Presentation) -> Recorder {
    let scene = SmallScene::build(&scenes::WHITTED).unwrap();
    let camera = scene.camera(width, height).unwrap();
    let mut display = Recorder::new(width, height);
    let mut line = vec![Rgb565::BLACK; width as usize];
    render_frame(
        &scene,
        &camera,
        presentation,
        &mut line,
        &mut [],
        &mut display,
    )
    .unwrap();
    display
}

#[test]
fn a_progressive_frame_ends_as_the_top_down_one() {
    for (width, height) in [(40, 24), (37, 29), (8, 3)] {
        let progressive = Presentation {
            order: RowOrder::Progressive,
            ..Presentation::default()
        };
        let top_down = frame(width, height, Presentation::default());
        let drawn = frame(width, height, progressive);
        assert_eq!(drawn.pixels, top_down.pixels, "{width}x{height}");
        assert!(top_down.writes.iter().all(|&n| n == 1));
        // Each row is traced once: each rectangle starts at a row of its own.
        let mut tops: Vec<_> = drawn.rectangles.iter().map(|r| r.top_left.y).collect();
        tops.sort_unstable();
        assert_eq!(
            tops,
            (0..height as i32).collect::<Vec<_>>(),
            "{width}x{height}"
        );
    }
}

#[test]
fn each_pass_draws_a_pixel_at_most_once_and_the_first_draws_them_all() {
    let height = 21_u32;
    let rows: Vec<_> = RowOrder::Progressive.rows(height).collect();
    // The passes are where the step between rows changes: the rows 0, 8, 16; 4, 12, 20; ...
    let passes: [&[u32]; 4] = [
        &[0, 8, 16],
        &[4, 12, 20],
        &[2, 6, 10, 14, 18],
        &[1, 3, 5, 7, 9, 11, 13, 15, 17, 19],
    ];
    let mut at = 0;
    for (pass, expected) in passes.iter().enumerate() {
        let mut covered = vec![0_u32; height as usize];
        for &(y, block) in &rows[at..at + expected.len()] {
            for row in y..y + block {
                covered[row as usize] += 1;
            }
        }
        let ys: Vec<_> = rows[at..at + expected.len()]
            .iter()
            .map(|&(y, _)| y)
            .collect();
        assert_eq!(&ys, expected, "pass {pass}");
        assert!(
            covered.iter().all(|&n| n <= 1),
            "pass {pass} draws a row twice"
        );
        if pass == 0 {
            assert!(
                covered.iter().all(|&n| n == 1),
                "the first pass covers the frame"
            );
        }
        at += expected.len();
    }
    assert_eq!(at, rows.len(), "every row once");
    assert_eq!(rows.iter().map(|&(y, _)| y).max(), Some(height - 1));
}

#[test]
fn a_dithered_frame_is_deterministic_and_within_a_level_of_the_plain_one() {
    let dithered = Presentation {
        dither: Dither::Ordered,
        ..Presentation::default()
    };
    let plain = frame(48, 32, Presentation::default());
    let once = frame(48, 32, dithered);
    let again = frame(48, 32, dithered);
    assert_eq!(once.pixels, again.pixels);
    assert_ne!(once.pixels, plain.pixels, "the sky's gradient is dithered");
    for (d, p) in once.pixels.iter().zip(&plain.pixels) {
        assert!(
            d.r().abs_diff(p.r()) <= 1 && d.g().abs_diff(p.g()) <= 1 && d.b().abs_diff(p.b()) <= 1
        );
    }
}
