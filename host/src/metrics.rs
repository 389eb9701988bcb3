//! How far an image is from its reference: PSNR, channel errors, differing pixels, and the
//! share of pixels whose primary ray hit a different object (geometric error, kept apart from
//! shading error).

use image::RgbImage;

/// The error of one image against a reference of the same size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Accuracy {
    /// Peak signal-to-noise ratio over all RGB888 channels, in dB; infinite for identical images.
    pub psnr_db: f64,
    /// The mean absolute channel error, in 8-bit levels.
    pub mean_abs_error: f64,
    /// The largest channel error, in 8-bit levels.
    pub max_abs_error: u8,
    /// Pixels with any channel different, in percent.
    pub differing_pixels_pct: f64,
    /// Pixels whose primary ray hit another object (or none), in percent.
    pub object_mismatch_pct: f64,
}

/// Compares `image` with `reference`, and the object maps of both (one entry per pixel).
///
/// # Panics
/// If the sizes differ: both come from the same request.
pub fn accuracy(
    image: &RgbImage,
    reference: &RgbImage,
    objects: &[Option<usize>],
    reference_objects: &[Option<usize>],
) -> Accuracy {
    assert_eq!(
        image.dimensions(),
        reference.dimensions(),
        "images of different sizes"
    );
    assert_eq!(
        objects.len(),
        reference_objects.len(),
        "object maps of different sizes"
    );
    let pixels = f64::from(image.width()) * f64::from(image.height());
    let mut squared = 0.0;
    let mut absolute = 0.0;
    let mut max_abs_error = 0;
    let mut differing = 0_u64;
    for (a, b) in image.pixels().zip(reference.pixels()) {
        let mut differs = false;
        for (x, y) in a.0.iter().zip(b.0.iter()) {
            let e = x.abs_diff(*y);
            squared += f64::from(e) * f64::from(e);
            absolute += f64::from(e);
            max_abs_error = max_abs_error.max(e);
            differs |= e != 0;
        }
        differing += u64::from(differs);
    }
    let channels = 3.0 * pixels;
    let mse = squared / channels;
    let mismatched = objects
        .iter()
        .zip(reference_objects)
        .filter(|(a, b)| a != b)
        .count();
    Accuracy {
        psnr_db: 10.0 * (255.0 * 255.0 / mse).log10(),
        mean_abs_error: absolute / channels,
        max_abs_error,
        differing_pixels_pct: 100.0 * differing as f64 / pixels,
        object_mismatch_pct: 100.0 * mismatched as f64 / pixels,
    }
}

/// The PSNR of `image` against `reference` over all RGB888 channels, in dB; infinite for
/// identical images.
///
/// # Panics
/// If the sizes differ.
pub fn psnr_db(image: &RgbImage, reference: &RgbImage) -> f64 {
    accuracy(image, reference, &[], &[]).psnr_db
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_images_have_infinite_psnr_and_no_error() {
        let a = RgbImage::from_pixel(4, 4, image::Rgb([10, 20, 30]));
        let objects = vec![Some(1); 16];
        let acc = accuracy(&a, &a, &objects, &objects);
        assert!(acc.psnr_db.is_infinite());
        assert_eq!((acc.mean_abs_error, acc.max_abs_error), (0.0, 0));
        assert_eq!(
            (acc.differing_pixels_pct, acc.object_mismatch_pct),
            (0.0, 0.0)
        );
    }

    #[test]
    fn figures_match_hand_computation() {
        // 2×2 image; one pixel off by (3, 0, 0), one by (0, 0, 255).
        let reference = RgbImage::from_pixel(2, 2, image::Rgb([100, 100, 0]));
        let mut image = reference.clone();
        image.put_pixel(0, 0, image::Rgb([103, 100, 0]));
        image.put_pixel(1, 1, image::Rgb([100, 100, 255]));
        let objects = [Some(0), None, Some(2), Some(2)];
        let reference_objects = [Some(0), Some(1), Some(2), Some(2)];
        let acc = accuracy(&image, &reference, &objects, &reference_objects);
        let mse: f64 = (9.0 + 255.0 * 255.0) / 12.0;
        assert!((acc.psnr_db - 10.0 * (255.0 * 255.0 / mse).log10()).abs() < 1e-9);
        assert!((acc.mean_abs_error - 258.0 / 12.0).abs() < 1e-9);
        assert_eq!(acc.max_abs_error, 255);
        assert_eq!(acc.differing_pixels_pct, 50.0);
        assert_eq!(acc.object_mismatch_pct, 25.0);
    }
}
