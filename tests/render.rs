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
    BackgroundDesc, CameraDesc, Corner, Dither, I16F16, LightDesc, MaterialDesc, ObjectDesc,
    Pixels, Presentation, RenderError, RowOrder, RowTracer, Scene, SceneDesc, ShapeDesc,
    render_frame, scenes, send_row,
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
const ADAPTIVE_WHITTED: SceneDesc<'static> = SceneDesc {
    samples: 16,
    adaptive_samples: true,
    ..scenes::WHITTED
};

fn adaptive_whitted() -> SmallScene {
    SmallScene::build(&ADAPTIVE_WHITTED).unwrap()
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
    assert_eq!(ADAPTIVE_WHITTED.corner_rows(32), corners.len());
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

/// Adaptive pixels ([`Pixels::Adaptive`]): a pixel's colour depends on its place alone, so a
/// frame is the same top down, row by row from the bottom up, in bands and progressive; and
/// the frame is not the exact one, but close to it.
#[test]
fn adaptive_pixels_draw_the_same_frame_however_the_rows_are_split() {
    let (width, height) = (48, 40);
    let mut line = [Rgb565::BLACK; 48];
    let exact_scene = SmallScene::build(&scenes::WHITTED).unwrap();
    let camera = exact_scene.camera(width, height).unwrap();
    let mut exact = Recorder::new(width, height);
    draw_band(
        &exact_scene,
        &camera,
        0..height,
        &mut line,
        &mut [],
        &mut exact,
    );
    for block in Pixels::BLOCKS {
        let desc = SceneDesc {
            pixels: Pixels::Adaptive(block),
            ..scenes::WHITTED
        };
        let scene = SmallScene::build(&desc).unwrap();
        let mut corners = vec![Corner::ZERO; desc.corner_rows(width)];
        let mut whole = Recorder::new(width, height);
        draw_band(
            &scene,
            &camera,
            0..height,
            &mut line,
            corners.as_mut_slice(),
            &mut whole,
        );
        let mut banded = Recorder::new(width, height);
        for rows in [0..13, 13..29, 29..height] {
            draw_band(
                &scene,
                &camera,
                rows,
                &mut line,
                corners.as_mut_slice(),
                &mut banded,
            );
        }
        assert_eq!(whole.pixels, banded.pixels, "blocks of {block}");
        let mut upwards = Recorder::new(width, height);
        let mut tracer = RowTracer::new(
            &scene,
            &camera,
            Dither::None,
            &mut line,
            corners.as_mut_slice(),
        )
        .unwrap();
        for y in (0..height).rev() {
            send_row(&mut upwards, tracer.trace(y).unwrap(), y, 1).unwrap();
        }
        assert_eq!(whole.pixels, upwards.pixels, "blocks of {block}");
        let progressive = Presentation {
            order: RowOrder::Progressive,
            dither: Dither::None,
        };
        let mut frame = Recorder::new(width, height);
        let corners = corners.as_mut_slice();
        render_frame(&scene, &camera, progressive, &mut line, corners, &mut frame).unwrap();
        assert_eq!(whole.pixels, frame.pixels, "blocks of {block}");
        let differing = whole
            .pixels
            .iter()
            .zip(&exact.pixels)
            .filter(|(a, b)| a != b)
            .count();
        eprintln!("blocks of {block}: {differing} pixels differ from the exact frame");
        assert!(
            differing < whole.pixels.len() / 8,
            "blocks of {block}: {differing} pixels differ from the exact frame"
        );
    }
}

/// A ball smaller than a block, between the corners of blocks over a floor, is not filled
/// over: culling says a primary ray of those blocks may meet it, so they are traced, and every
/// pixel that shows the ball in the exact frame shows it with adaptive pixels.
#[test]
fn a_ball_between_the_corners_of_a_block_is_traced_not_filled_over() {
    const OBJECTS: &[ObjectDesc] = &[
        ObjectDesc {
            shape: ShapeDesc::Plane {
                point: [0.0, 0.0, 0.0],
                normal: [0.0, 1.0, 0.0],
                checker: None,
            },
            material: MaterialDesc::matte([0.2, 0.6, 0.2]),
        },
        ObjectDesc {
            // About 5 pixels across at 64x64, centred near pixel (36, 36): between the
            // corners of a block of 8.
            shape: ShapeDesc::Sphere {
                center: [0.25, 0.75, 0.0],
                radius: 0.13,
            },
            material: MaterialDesc::matte([1.0, 0.1, 0.1]),
        },
    ];
    let exact = SceneDesc {
        camera: CameraDesc::pinhole([0.0, 1.0, -5.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0], 40.0),
        objects: OBJECTS,
        lights: &[LightDesc::point([2.0, 6.0, -3.0], [1.0; 3])],
        far: 8.0,
        background: BackgroundDesc::Solid([0.2, 0.3, 0.6]),
        ..SceneDesc::DEFAULT
    };
    let adaptive = SceneDesc {
        pixels: Pixels::Adaptive(8),
        ..exact
    };
    let (width, height) = (64, 64);
    let mut line = [Rgb565::BLACK; 64];
    let mut corners = vec![Corner::ZERO; adaptive.corner_rows(width)];
    let frames = [exact, adaptive].map(|desc| {
        let scene = SmallScene::build(&desc).unwrap();
        let camera = scene.camera(width, height).unwrap();
        let mut frame = Recorder::new(width, height);
        draw_band(
            &scene,
            &camera,
            0..height,
            &mut line,
            corners.as_mut_slice(),
            &mut frame,
        );
        frame.pixels
    });
    let red = |c: &Rgb565| c.r() > 2 * c.g();
    let ball: Vec<_> = frames[0].iter().map(red).collect();
    assert!(ball.iter().filter(|&&b| b).count() >= 4, "the ball shows");
    assert_eq!(ball, frames[1].iter().map(red).collect::<Vec<_>>());
}

/// Adaptive pixels take blocks of 2, 4 or 8, one ray a pixel and no lens; anything else is
/// refused, saying what to set.
#[test]
fn adaptive_pixels_other_than_blocks_of_two_to_eight_or_with_samples_are_refused() {
    let refused = |desc: SceneDesc<'_>| SmallScene::build(&desc).unwrap_err().to_string();
    let odd = refused(SceneDesc {
        pixels: Pixels::Adaptive(3),
        ..scenes::WHITTED
    });
    assert!(
        odd.contains("adaptive:2, adaptive:4 or adaptive:8"),
        "{odd}"
    );
    let sampled = refused(SceneDesc {
        pixels: Pixels::Adaptive(4),
        samples: 4,
        ..scenes::WHITTED
    });
    assert!(sampled.contains("samples = 1"), "{sampled}");
    let lens = refused(SceneDesc {
        pixels: Pixels::Adaptive(4),
        camera: CameraDesc {
            aperture: 0.05,
            ..scenes::WHITTED.camera
        },
        ..scenes::WHITTED
    });
    assert!(lens.contains("aperture"), "{lens}");
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
