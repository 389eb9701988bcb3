//! Several rays per pixel (`SceneDesc::samples`): one sample draws the images obscura drew
//! before it had samples, bit for bit; more cover an edge as its geometry says.

mod common;

use common::{Frame, render};
use embedded_graphics::pixelcolor::RgbColor;
use obscura::formats::I8f24;
use obscura::{
    BackgroundDesc, CameraDesc, I16F16, MaterialDesc, Methods, ObjectDesc, Scalar, SceneDesc,
    ShapeDesc, scenes,
};

/// FNV-1a over a frame's RGB888 bytes, row by row.
fn fingerprint(frame: &Frame) -> u64 {
    frame
        .pixels
        .iter()
        .flat_map(|c| [c.r(), c.g(), c.b()])
        .fold(0xcbf2_9ce4_8422_2325, |hash, byte| {
            (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3)
        })
}

/// The built-in scenes at 64×64, as obscura drew them before a pixel could take several rays
/// (fingerprints of frames rendered by the code of commit 398a67f; the fixed format's since its
/// surfaces' colours, weights and shading cosines are narrow numbers, and since the row pass
/// finds a floor's hits by a quotient a row, each change of pictures held to `f64` by `obscura
/// compare`): one sample is that camera.
#[test]
fn one_sample_draws_the_images_of_before_bit_for_bit() {
    let drawn = [
        fingerprint(&render::<I16F16>(&scenes::WHITTED, 64, 64, Methods::LECTURE).0),
        fingerprint(&render::<f32>(&scenes::WHITTED, 64, 64, Methods::LECTURE).0),
        fingerprint(&render::<I16F16>(&scenes::SHAPES, 64, 64, Methods::LECTURE).0),
        fingerprint(&render::<f32>(&scenes::SHAPES, 64, 64, Methods::LECTURE).0),
    ];
    assert_eq!(drawn, BEFORE_SAMPLES, "{drawn:#x?}");
}

const BEFORE_SAMPLES: [u64; 4] = [
    0x26b2_46f9_cf19_aca2,
    0x781f_0775_2b70_7489,
    0xeeaf_3175_c2ee_553c,
    0xd337_49d6_5e24_0499,
];

/// The image's side in the edge tests.
const SIDE: u32 = 16;

/// Where an edge crosses its pixel, as the fraction of the pixel before it.
const CROSSING: f64 = 0.3;

/// A white surface lit by ambient light alone (so it draws at full intensity) against black.
const WHITE: MaterialDesc = MaterialDesc {
    colour: [1.0; 3],
    diffuse: 0.0,
    specular: 0.0,
    shininess: 1,
    reflection: 0.0,
    transmission: 0.0,
    ior: 1.0,
};

/// A white triangle in the plane z = 1, which a 90° camera at the origin sees as its whole
/// image plane, with one edge straight across the image: down column `SIDE/2` at `CROSSING` of
/// its width (`vertical`), or along row `SIDE/2` at `CROSSING` of its height.
fn edge(vertical: bool) -> ObjectDesc {
    // Pixel column c's centre lies at x = 1 − (c + ½)·2/SIDE (+x points left), so the edge at
    // column SIDE/2 + CROSSING lies at x = −CROSSING·2/SIDE; rows likewise, +y up.
    let at = (-CROSSING * 2.0 / f64::from(SIDE)) as f32;
    let corners = [[at, -1.5, 1.0], [at, 1.5, 1.0], [at - 3.0, 0.0, 1.0]];
    ObjectDesc {
        shape: ShapeDesc::Triangle {
            vertices: corners.map(|[x, y, z]| if vertical { [x, y, z] } else { [y, x, z] }),
        },
        material: WHITE,
    }
}

/// `objects` in ambient light alone, seen by a 90° camera at the origin looking along +z, by
/// `samples` rays per pixel.
fn scene(objects: &[ObjectDesc], samples: u16) -> SceneDesc<'_> {
    sampled(objects, samples, false)
}

/// [`scene`], its samples adaptive or not.
fn sampled(objects: &[ObjectDesc], samples: u16, adaptive_samples: bool) -> SceneDesc<'_> {
    SceneDesc {
        camera: CameraDesc::pinhole([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 90.0),
        objects,
        lights: &[],
        ambient: [1.0; 3],
        background: BackgroundDesc::Solid([0.0; 3]),
        far: 4.0,
        max_depth: 0,
        samples,
        adaptive_samples,
        ..SceneDesc::DEFAULT
    }
}

/// What the triangle covers of pixel (x, y): all of the pixels beyond the edge's, none of those
/// before it, and 1 − `CROSSING` of the edge's own.
fn coverage(vertical: bool, x: u32, y: u32) -> f64 {
    // Vertically the triangle lies at x ≤ at: columns from the edge rightwards in the image.
    // Across, at y ≤ at: rows from the edge downwards.
    let along = if vertical { x } else { y };
    match along.cmp(&(SIDE / 2)) {
        std::cmp::Ordering::Less => 0.0,
        std::cmp::Ordering::Equal => 1.0 - CROSSING,
        std::cmp::Ordering::Greater => 1.0,
    }
}

/// n samples per pixel cover an edge along either axis to within 1/n of what geometry says (a
/// power of two of them is a (0, m, 2)-net: one sample in each 1/n of the pixel across and
/// down), and a pixel off the edge exactly; in a float, the 32-bit fixed format with the most
/// fraction bits and i16f16.
#[test]
fn supersampling_covers_an_edge_as_geometry_says() {
    covers_the_edge(false, |samples| 1.0 / f64::from(samples));
}

/// Adaptive samples (Whitted's corners, split where they differ) draw a pixel off the edge
/// exactly, and the edge's own to within half a cell of the deepest split: the cells the edge
/// crosses show the mean of their corners, one side black, the other white.
#[test]
fn adaptive_samples_cover_an_edge_as_geometry_says() {
    covers_the_edge(true, |samples| 0.5 / f64::from(samples).sqrt());
}

/// Checks that 4, 16 and 64 samples (adaptive or not) draw pixels off the edge exactly and the
/// edge's own to within `error(samples)` of its coverage (and half an 8-bit level), in `f64`,
/// `f32`, `i8f24` and `i16f16`.
fn covers_the_edge(adaptive: bool, error: fn(u16) -> f64) {
    fn check<S: Scalar>(adaptive: bool, error: fn(u16) -> f64) {
        for vertical in [true, false] {
            for samples in [4_u16, 16, 64] {
                let objects = [edge(vertical)];
                let desc = sampled(&objects, samples, adaptive);
                let (frame, _) = render::<S>(&desc, SIDE, SIDE, Methods::LECTURE);
                for (i, pixel) in frame.pixels.iter().enumerate() {
                    let (x, y) = (i as u32 % SIDE, i as u32 / SIDE);
                    let want = coverage(vertical, x, y);
                    let got = f64::from(pixel.r()) / 255.0;
                    let bound = if want == 0.0 || want == 1.0 {
                        0.0
                    } else {
                        error(samples) + 0.5 / 255.0
                    };
                    assert!(
                        (got - want).abs() <= bound,
                        "{} {samples} samples{}, {}: ({x}, {y}) is {got}, geometry says {want}",
                        S::NAME,
                        if adaptive { ", adaptive" } else { "" },
                        if vertical { "vertical" } else { "across" },
                    );
                }
            }
        }
    }
    check::<f64>(adaptive, error);
    check::<f32>(adaptive, error);
    check::<I8f24>(adaptive, error);
    check::<I16F16>(adaptive, error);
}

/// Adaptive samples split a pixel into quarters, so they are refused unless a power of 4, and
/// with a lens (they spread over the pixel alone); each error names the field and the fix.
#[test]
fn adaptive_samples_other_than_powers_of_four_or_with_a_lens_are_refused() {
    let objects = [edge(true)];
    for samples in [1, 2, 8, 32] {
        let desc = sampled(&objects, samples, true);
        let message = obscura::Scene::<f32, 1, 1, 1>::build(&desc)
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("samples") && message.contains("4, 16, 64 or 256"),
            "{message}"
        );
    }
    let mut desc = sampled(&objects, 16, true);
    desc.camera.aperture = 0.01;
    let message = obscura::Scene::<f32, 1, 1, 1>::build(&desc)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("aperture") && message.contains("adaptive_samples"),
        "{message}"
    );
}

/// More samples than a pixel may take, or none, are refused, naming the limit.
#[test]
fn a_sample_count_beyond_the_limit_is_refused() {
    for samples in [0, obscura::pattern::MAX_SAMPLES + 1] {
        let objects = [edge(true)];
        let desc = scene(&objects, samples);
        let error = obscura::Scene::<f32, 1, 1, 1>::build(&desc).unwrap_err();
        let message = error.to_string();
        assert!(
            message.contains("samples")
                && message.contains(&format!("1 to {}", obscura::pattern::MAX_SAMPLES)),
            "{message}"
        );
    }
}
