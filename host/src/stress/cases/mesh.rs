//! A closed mesh of triangles sharing edges (an octahedron, as eight triangles and as one mesh
//! through its hierarchy), and rays aimed from outside at its edges and vertices, each bound
//! to enter it there: the rays that slip through (and meet
//! only the far side, or nothing) are cracks. They must
//! be none for the watertight test; for the others the count is reported, their known weakness.

use super::{MATTE, Tally, bare, log_sweep, refused};
use crate::checked::Checked;
use crate::render::HostScene;
use crate::stress::{Case, Outcome, Row};
use anyhow::Result;
use obscura::methods::MethodName;
use obscura::{Methods, ObjectDesc, Ray, Scalar, SceneDesc, ShapeDesc, TriangleMethod, Vec3};
use obscura_scene::{FormatJob, OwnedMeshes};

pub const CASE: Case = Case {
    name: "mesh",
    about: "a closed mesh, rays at its shared edges and vertices: the ones that slip through",
    x_label: "the mesh's distance from the eye",
    log_x: true,
    y_label: "rays slipping through (%)",
    run: |format| format.run::<Checked, _>(Job),
};

/// The rows' names of the triangle methods, in the order of [`TriangleMethod::ALL`]: the
/// octahedron's faces as eight triangles, and as one mesh through its hierarchy.
const TRIANGLES: &[&str] = &["cramer", "moller-trumbore", "watertight"];
/// See [`TRIANGLES`].
const IN_A_MESH: &[&str] = &["cramer, mesh", "moller-trumbore, mesh", "watertight, mesh"];

/// Points along each edge a ray is aimed at, as fractions of it (0 is a vertex).
const ALONG: usize = 64;
/// Rays per point, from origins spread around the outward direction.
const FROM: usize = 20;

/// The octahedron's six corners around `c`, turned off the axes so that no coordinate is
/// round, and its eight faces, anticlockwise from outside.
fn octahedron(c: [f64; 3]) -> ([[f64; 3]; 6], [[usize; 3]; 8]) {
    let corner = |axis: usize, sign: f64| {
        let mut p = [0.0; 3];
        p[axis] = sign;
        let turned = turn(p);
        std::array::from_fn(|k| c[k] + turned[k])
    };
    let corners = [
        corner(0, 1.0),
        corner(0, -1.0),
        corner(1, 1.0),
        corner(1, -1.0),
        corner(2, 1.0),
        corner(2, -1.0),
    ];
    let mut faces = [[0; 3]; 8];
    for (k, face) in faces.iter_mut().enumerate() {
        let (x, y, z) = (k & 1, (k >> 1) & 1, (k >> 2) & 1);
        // Corners +x/−x, +y/−y, +z/−z; flip the order where the signs' product is negative.
        let (a, b, cz) = (x, 2 + y, 4 + z);
        *face = if (x + y + z) % 2 == 0 {
            [a, b, cz]
        } else {
            [a, cz, b]
        };
    }
    (corners, faces)
}

/// A rotation by 0.7 about the axis (1, 2, 3)/√14, by Rodrigues' formula.
fn turn(p: [f64; 3]) -> [f64; 3] {
    let norm = 14.0_f64.sqrt();
    let k = [1.0 / norm, 2.0 / norm, 3.0 / norm];
    let (sin, cos) = 0.7_f64.sin_cos();
    let dot: f64 = (0..3).map(|i| k[i] * p[i]).sum();
    let cross = [
        k[1] * p[2] - k[2] * p[1],
        k[2] * p[0] - k[0] * p[2],
        k[0] * p[1] - k[1] * p[0],
    ];
    std::array::from_fn(|i| p[i] * cos + cross[i] * sin + k[i] * dot * (1.0 - cos))
}

struct Job;

impl FormatJob for Job {
    type Output = Result<Vec<Row>>;
    fn run<S: Scalar>(self) -> Result<Vec<Row>> {
        let mut rows = Vec::new();
        for distance in log_sweep(3.0, 30.0, 3) {
            let centre = [0.3, -0.2, distance];
            let (corners, faces) = octahedron(centre);
            let objects: Vec<ObjectDesc> = faces
                .iter()
                .map(|face| ObjectDesc {
                    shape: ShapeDesc::Triangle {
                        vertices: face.map(|i| corners[i].map(|c| c as f32)),
                    },
                    material: MATTE,
                })
                .collect();
            // The same faces as one mesh, through its hierarchy.
            let mut meshes = OwnedMeshes::default();
            let corners_f32: Vec<[f32; 3]> = corners.iter().map(|c| c.map(|x| x as f32)).collect();
            let faces_u32: Vec<[u32; 3]> = faces.iter().map(|f| f.map(|i| i as u32)).collect();
            let root = meshes
                .add(&corners_f32, &[], &faces_u32)
                .map_err(|error| anyhow::anyhow!("the octahedron as a mesh: {error:?}"))?
                .root;
            let mesh = [ObjectDesc {
                shape: ShapeDesc::Mesh { root },
                material: MATTE,
            }];
            let far = (distance + 4.0) as f32;
            let forms = [
                (bare(&objects, far), TRIANGLES),
                (
                    SceneDesc {
                        meshes: meshes.desc(),
                        ..bare(&mesh, far)
                    },
                    IN_A_MESH,
                ),
            ];
            let edges: Vec<(usize, usize)> = (0..6)
                .flat_map(|i| (i + 1..6).map(move |j| (i, j)))
                .filter(|&(i, j)| i / 2 != j / 2)
                .collect();
            for ((desc, &name), &(method, _)) in forms
                .iter()
                .flat_map(|(desc, names)| names.iter().map(move |name| (desc, name)))
                .zip(TriangleMethod::ALL.iter().cycle())
            {
                let methods = Methods {
                    triangle: method,
                    ..Methods::LECTURE
                };
                let scene = match HostScene::<S>::build_with(desc, methods) {
                    Ok(scene) => scene,
                    Err(error) => {
                        rows.push(refused(S::NAME, name, distance, &error));
                        continue;
                    }
                };
                let mut tally = Tally::default();
                for &(i, j) in &edges {
                    for u in (0..ALONG).map(|k| k as f64 / ALONG as f64) {
                        // The faces around the point: those with both ends of the edge, or
                        // with its first corner where the point is that corner.
                        let at_target = |face: [u32; 3]| {
                            let has = |corner: usize| face.iter().any(|&c| c as usize == corner);
                            has(i) && (u == 0.0 || has(j))
                        };
                        let target: [f64; 3] = std::array::from_fn(|k| {
                            corners[i][k] + u * (corners[j][k] - corners[i][k])
                        });
                        let outward: [f64; 3] = std::array::from_fn(|k| target[k] - centre[k]);
                        for n in 0..FROM {
                            // An origin 2.5 out along the outward direction, spread around it, so
                            // that the ray through the target runs on into the solid.
                            let angle = std::f64::consts::TAU * n as f64 / FROM as f64;
                            let spread = [
                                0.31 * angle.cos(),
                                0.27 * angle.sin(),
                                0.19 * (2.0 * angle).sin(),
                            ];
                            let origin: [f64; 3] =
                                std::array::from_fn(|k| target[k] + 2.5 * outward[k] + spread[k]);
                            let way: [f64; 3] = std::array::from_fn(|k| target[k] - origin[k]);
                            let length = way.iter().map(|c| c * c).sum::<f64>().sqrt();
                            let (Some(o), Some(d)) = (
                                Vec3::<S>::from_f64(origin),
                                Vec3::from_f64(way.map(|c| c / length)),
                            ) else {
                                continue;
                            };
                            // It must enter through a face at the point aimed at; one that
                            // meets only the far side has slipped through a crack.
                            let entered =
                                scene
                                    .first_hit(&Ray::new(o, d))
                                    .is_some_and(|(object, part)| {
                                        match desc.objects[object].shape {
                                            ShapeDesc::Mesh { .. } => {
                                                at_target(desc.meshes.triangles[part as usize])
                                            }
                                            _ => at_target(faces_u32[object]),
                                        }
                                    });
                            tally.record(entered, true, || false);
                        }
                    }
                }
                let mut row = tally.row(S::NAME, name, distance);
                // Only the watertight test is bound to let none through.
                if method != TriangleMethod::Watertight {
                    row.outcome = Outcome::Reported {
                        value: f64::from(tally.misjudged),
                    };
                }
                rows.push(row);
            }
        }
        Ok(rows)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_octahedron_is_closed_and_faces_outwards() {
        let c = [0.0, 0.0, 5.0];
        let (corners, faces) = octahedron(c);
        // Every edge between adjacent corners belongs to exactly two faces.
        for i in 0..6 {
            for j in i + 1..6 {
                let shared = faces
                    .iter()
                    .filter(|f| f.contains(&i) && f.contains(&j))
                    .count();
                assert_eq!(shared, if i / 2 == j / 2 { 0 } else { 2 }, "{i} {j}");
            }
        }
        // Each face's normal (b − a) × (c − a) points away from the centre.
        for face in faces {
            let [a, b, d] = face.map(|k| corners[k]);
            let e1: [f64; 3] = std::array::from_fn(|k| b[k] - a[k]);
            let e2: [f64; 3] = std::array::from_fn(|k| d[k] - a[k]);
            let n = [
                e1[1] * e2[2] - e1[2] * e2[1],
                e1[2] * e2[0] - e1[0] * e2[2],
                e1[0] * e2[1] - e1[1] * e2[0],
            ];
            let out: f64 = (0..3).map(|k| n[k] * (a[k] - c[k])).sum();
            assert!(out > 0.0, "{face:?}");
        }
    }
}
