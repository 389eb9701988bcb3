//! The difference image: each pixel coloured by its largest channel error against the
//! reference, on a logarithmic scale, with a legend strip underneath.
//!
//! Scale: an error of e 8-bit levels sits at p = log₂(1 + e) / 8 along a dark-to-bright ramp
//! (black, purple, red, orange, pale yellow), so 0 is black, 1 is a dim purple and 255 is pale
//! yellow; the legend marks e = 0, 1, 3, 7, 15, 31, 63, 127, 255.

use crate::canvas::Canvas;
use embedded_graphics::mono_font::{MonoTextStyle, ascii::FONT_5X8};
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
use embedded_graphics::text::{Alignment, Baseline, Text, TextStyleBuilder};
use image::RgbImage;

/// The height of the legend strip below the image, in pixels.
pub const LEGEND_HEIGHT: u32 = 34;

/// The ramp's stops: (position, colour).
const RAMP: [(f64, [u8; 3]); 5] = [
    (0.0, [0, 0, 0]),
    (0.25, [66, 10, 104]),
    (0.5, [188, 55, 84]),
    (0.75, [249, 142, 9]),
    (1.0, [252, 255, 164]),
];

/// The error levels the legend labels.
const TICKS: [u8; 9] = [0, 1, 3, 7, 15, 31, 63, 127, 255];

/// The heat-map colour of an error of `e` levels.
pub fn error_colour(e: u8) -> [u8; 3] {
    position_colour((1.0 + f64::from(e)).log2() / 8.0)
}

fn position_colour(p: f64) -> [u8; 3] {
    let p = p.clamp(0.0, 1.0);
    let upper = RAMP
        .iter()
        .position(|(q, _)| *q >= p)
        .unwrap_or(RAMP.len() - 1)
        .max(1);
    let ((p0, c0), (p1, c1)) = (RAMP[upper - 1], RAMP[upper]);
    let f = (p - p0) / (p1 - p0);
    std::array::from_fn(|i| {
        (f64::from(c0[i]) + f * (f64::from(c1[i]) - f64::from(c0[i]))).round() as u8
    })
}

/// The heat map of `image` against `reference` (same size), with the legend below it.
pub fn heatmap(image: &RgbImage, reference: &RgbImage) -> RgbImage {
    let (width, height) = image.dimensions();
    let mut out = RgbImage::new(width, height + LEGEND_HEIGHT);
    for (x, y, pixel) in image.enumerate_pixels() {
        let other = reference.get_pixel(x, y);
        let e = pixel
            .0
            .iter()
            .zip(other.0.iter())
            .map(|(a, b)| a.abs_diff(*b))
            .max()
            .unwrap_or(0);
        out.put_pixel(x, y, image::Rgb(error_colour(e)));
    }
    draw_legend(&mut Canvas(&mut out), width, height);
    out
}

fn draw_legend(canvas: &mut Canvas<'_>, width: u32, top: u32) {
    let top = top as i32;
    let background = Rgb888::new(24, 24, 28);
    let _ = Rectangle::new(Point::new(0, top), Size::new(width, LEGEND_HEIGHT))
        .into_styled(PrimitiveStyle::with_fill(background))
        .draw(canvas);
    let margin = 8;
    let bar = (width as i32 - 2 * margin).max(1);
    for i in 0..bar {
        let [r, g, b] = position_colour(f64::from(i) / f64::from((bar - 1).max(1)));
        let column = Rectangle::new(Point::new(margin + i, top + 4), Size::new(1, 10));
        let _ = column
            .into_styled(PrimitiveStyle::with_fill(Rgb888::new(r, g, b)))
            .draw(canvas);
    }
    let text = MonoTextStyle::new(&FONT_5X8, Rgb888::new(230, 230, 230));
    let centred = TextStyleBuilder::new()
        .alignment(Alignment::Center)
        .baseline(Baseline::Top)
        .build();
    let mut last_right = i32::MIN;
    for tick in TICKS {
        let x = margin + ((1.0 + f64::from(tick)).log2() / 8.0 * f64::from(bar - 1)).round() as i32;
        let label = tick.to_string();
        let half = (label.len() as i32 * 5) / 2 + 2;
        if x - half <= last_right {
            continue;
        }
        last_right = x + half;
        let _ = Text::with_text_style(&label, Point::new(x, top + 16), text, centred).draw(canvas);
    }
    let caption = "max channel error, 8-bit levels (log scale)";
    if caption.len() as i32 * 5 <= width as i32 {
        let _ = Text::with_text_style(
            caption,
            Point::new(width as i32 / 2, top + 25),
            text,
            centred,
        )
        .draw(canvas);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_runs_from_black_to_pale_yellow_and_grows() {
        assert_eq!(error_colour(0), [0, 0, 0]);
        assert_eq!(error_colour(255), [252, 255, 164]);
        let brightness = |e| error_colour(e).iter().map(|&c| u32::from(c)).sum::<u32>();
        for e in 0..255 {
            assert!(brightness(e + 1) >= brightness(e), "{e}");
        }
        assert!(brightness(1) > 0, "an error of one level is visible");
    }

    #[test]
    fn heatmap_marks_exactly_the_differing_pixels() {
        let reference = RgbImage::from_pixel(64, 8, image::Rgb([50, 60, 70]));
        let mut image = reference.clone();
        image.put_pixel(3, 2, image::Rgb([50, 61, 70]));
        let map = heatmap(&image, &reference);
        assert_eq!(map.dimensions(), (64, 8 + LEGEND_HEIGHT));
        for (x, y, p) in map.enumerate_pixels().filter(|(_, y, _)| *y < 8) {
            let expected = if (x, y) == (3, 2) {
                error_colour(1)
            } else {
                [0, 0, 0]
            };
            assert_eq!(p.0, expected, "({x}, {y})");
        }
    }
}
