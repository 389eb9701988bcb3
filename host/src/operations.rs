//! The operation-count model of a frame (`obscura render --count`): per pixel and phase, the
//! products, quotients, roots, sums and object tests the tracer does for a scene, counted by
//! rendering it with [`Counted`] numbers on the host (the firmware's arithmetic, operation for
//! operation), and beside them the floor: what a pixel of that scene needs at least.
//!
//! The floor keeps the scene's shading and the picture, and assumes the best a tracer can do
//! with the rest: each primary ray's direction stepped along its row by three additions and
//! made a unit vector (three squares, two sums, a root, three products), but the row pass's,
//! which need none ([`obscura::row_pass`]); each ray tests only
//! the object it meets, at what that test cost here (a ray that meets nothing and a shadow ray
//! that reaches its light test nothing); shading as measured; and each pixel's colour a product
//! and a sum per channel on its way to the display.

use crate::checked::Checked;
use crate::counted::{Counted, Operations, Tally, kind_index, reset, take};
use crate::render::{Prepared, Request};
use anyhow::Result;
use image::RgbImage;
use obscura::Scalar;
use obscura::scalar::RayKind;
use obscura_scene::{Format, FormatJob};
use std::fmt::Write;

/// The floor of a primary ray's direction: stepped by three sums, then a unit vector (see the
/// module documentation).
const DIRECTION_FLOOR: Operations = Operations {
    products: 6,
    quotients: 0,
    roots: 1,
    sums: 5,
};

/// The floor of a pixel's output: a product and a sum per channel.
const OUTPUT_FLOOR: Operations = Operations {
    products: 3,
    quotients: 0,
    roots: 0,
    sums: 3,
};

/// A frame's operations, counted.
#[derive(Clone, Debug)]
pub struct FrameCount {
    /// Pixels in the frame.
    pub pixels: u64,
    /// What the counter saw.
    pub tally: Tally,
}

/// One line of the model: a phase's operations and object tests, measured and at the floor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    /// The phase.
    pub phase: &'static str,
    /// Measured: operations and tests in the frame.
    pub measured: (Operations, u64),
    /// The floor: likewise.
    pub floor: (Operations, u64),
}

/// The kinds of ray, with the names the table gives their tests.
const KINDS: [(RayKind, &str); 3] = [
    (RayKind::Primary, "object tests: primary rays"),
    (
        RayKind::Secondary,
        "object tests: reflected and refracted rays",
    ),
    (RayKind::Shadow, "object tests: shadow rays"),
];

impl FrameCount {
    /// Textbook operations per pixel, of every phase of a pixel's work (products, quotients,
    /// roots and sums alike).
    pub fn operations_per_pixel(&self) -> f64 {
        let (whole, _) = self
            .lines()
            .last()
            .map(|line| line.measured)
            .unwrap_or_default();
        whole.total() as f64 / self.pixels.max(1) as f64
    }

    /// The model's lines, the whole pixel last.
    pub fn lines(&self) -> Vec<Line> {
        let tally = &self.tally;
        // The row pass's rays take no unit vector.
        let directed = tally.rays[kind_index(RayKind::Primary)].rays - tally.row_passed;
        let mut lines = vec![Line {
            phase: "primary rays (camera)",
            measured: (tally.camera, 0),
            floor: (DIRECTION_FLOOR * directed, 0),
        }];
        lines.extend(KINDS.iter().map(|&(kind, phase)| {
            let rays = &tally.rays[kind_index(kind)];
            Line {
                phase,
                measured: (rays.operations, rays.tests),
                floor: rays.floor,
            }
        }));
        lines.push(Line {
            phase: "shadow cones: which objects to test",
            measured: (tally.cones, 0),
            floor: (Operations::default(), 0),
        });
        lines.push(Line {
            phase: "shading (the floor: the same)",
            measured: (tally.shading, 0),
            floor: (tally.shading, 0),
        });
        lines.push(Line {
            phase: "colour and output",
            measured: (tally.output, 0),
            floor: (OUTPUT_FLOOR * self.pixels, 0),
        });
        let sum = |pick: fn(&Line) -> (Operations, u64)| {
            lines
                .iter()
                .map(pick)
                .fold((Operations::default(), 0), |(operations, tests), (o, t)| {
                    (operations + o, tests + t)
                })
        };
        let whole = Line {
            phase: "the whole pixel",
            measured: sum(|line| line.measured),
            floor: sum(|line| line.floor),
        };
        lines.push(whole);
        lines
    }

    /// The model as a table, per pixel.
    pub fn table(&self) -> String {
        let per_pixel = |n: u64| n as f64 / self.pixels.max(1) as f64;
        let cells = |(operations, tests): (Operations, u64)| {
            let Operations {
                products,
                quotients,
                roots,
                sums,
            } = operations;
            [products, quotients, roots, sums, tests]
                .map(|n| format!("{:>8.1}", per_pixel(n)))
                .join(" ")
        };
        let mut table = String::new();
        let heading = "products quotients  roots     sums    tests";
        let _ = writeln!(table, "{:<44} {heading} | floor: {heading}", "per pixel");
        for line in self.lines() {
            let _ = writeln!(
                table,
                "{:<44} {} | {:>6} {}",
                line.phase,
                cells(line.measured),
                "",
                cells(line.floor)
            );
        }
        for (kind, name) in ["primary", "reflected and refracted", "shadow"]
            .iter()
            .enumerate()
        {
            let rays = &self.tally.rays[kind];
            let per_ray = |n: u64| n as f64 / rays.rays.max(1) as f64;
            // A mesh's hierarchy tests boxes besides its triangles.
            let boxes = if rays.boxes > 0 {
                format!(" and {:.2} box tests", per_ray(rays.boxes))
            } else {
                String::new()
            };
            // The primary rays the row pass found, where it found any.
            let passed = if kind == kind_index(RayKind::Primary) && self.tally.row_passed > 0 {
                format!(
                    "; {:.0} % by the row pass",
                    100.0 * per_ray(self.tally.row_passed)
                )
            } else {
                String::new()
            };
            let _ = writeln!(
                table,
                "{name} rays per pixel {:.2}: {:.2} object tests{boxes} each, {:.0} % of them meet \
                 their object{passed}",
                per_pixel(rays.rays),
                per_ray(rays.tests),
                100.0 * rays.met as f64 / rays.tests.max(1) as f64,
            );
        }
        table
    }
}

/// Renders the frame of `request` in `format` on this thread with counted numbers: its count,
/// and the image (the same as without counting).
///
/// # Errors
/// As [`Prepared::new`] and [`Prepared::render`].
pub fn count(format: Format, request: &Request<'_>) -> Result<(FrameCount, RgbImage)> {
    struct Count<'a>(&'a Request<'a>);
    impl FormatJob for Count<'_> {
        type Output = Result<(FrameCount, RgbImage)>;
        fn run<S: Scalar>(self) -> Self::Output {
            let prepared = Prepared::<Counted<S>>::new(self.0)?;
            reset();
            let image = prepared.render(1, None)?;
            let tally = take();
            let pixels = u64::from(self.0.width) * u64::from(self.0.height);
            Ok((FrameCount { pixels, tally }, image))
        }
    }
    format.run::<Checked, _>(Count(request))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::prepare;
    use obscura::{Methods, scenes};

    /// Counting changes no bit of any built-in scene's picture; a primary ray meets what the
    /// object map says it meets (the floor's primary tests are the pixels that show an object);
    /// and the floor is below what is measured in every phase.
    #[test]
    fn counting_changes_nothing_and_the_floor_is_below_the_count() {
        for built_in in &scenes::BUILT_IN {
            for format in [Format::I16f16, Format::F32] {
                let request = Request::new(built_in.desc, (40, 30), Methods::LECTURE);
                let plain = prepare(format, &request).expect("builds");
                let (count, image) = count(format, &request).expect("counts");
                let context = format!("{} in {format}", built_in.name);
                assert!(
                    image == plain.render(1, None).expect("renders"),
                    "{context}"
                );
                let shown = plain.object_map().expect("maps").iter().flatten().count();
                let primary = &count.tally.rays[kind_index(RayKind::Primary)];
                let samples = u64::from(built_in.desc.samples.max(1));
                assert_eq!(primary.rays, count.pixels * samples, "{context}");
                if samples == 1 && built_in.desc.camera.aperture == 0.0 {
                    assert_eq!(primary.floor.1, shown as u64, "{context}");
                }
                for line in count.lines() {
                    let ((m, mt), (f, ft)) = (line.measured, line.floor);
                    assert!(
                        f.products <= m.products
                            && f.quotients <= m.quotients
                            && f.roots <= m.roots
                            && f.sums <= m.sums
                            && ft <= mt,
                        "{context}, {}: floor {f:?} {ft} above {m:?} {mt}",
                        line.phase
                    );
                }
            }
        }
    }

    /// Repeated squaring: x¹ one product, x² two (a square, then the result), x⁴⁰ seven.
    #[test]
    fn powers_count_the_products_repeated_squaring_takes() {
        let x = Counted(1.5_f64);
        let mut products = Vec::new();
        for exponent in [0, 1, 2, 3, 40] {
            reset();
            assert_eq!(x.powi(exponent).0, 1.5_f64.powi(i32::from(exponent)));
            products.push(take().setup.products);
        }
        assert_eq!(products, [0, 1, 2, 3, 7]);
    }
}
