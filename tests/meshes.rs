//! Meshes: a mesh traces as its triangles do (its hierarchy skips no triangle a ray meets), in
//! every format; a smooth mesh (normals at its vertices) shades as the surface it approximates;
//! and a hierarchy that is not what `build_hierarchy` makes, or normals that are not unit, are
//! refused.

use obscura::mesh::{MeshVecs, build_hierarchy};
use obscura::pattern::SampleId;
use obscura::{
    BackgroundDesc, CameraDesc, Everything, I16F16, LightDesc, MaterialDesc, MeshesDesc, NodeDesc,
    ObjectDesc, Scalar, Scene, SceneDesc, SceneError, ShapeDesc,
};

type MeshScene<S> = Scene<S, 48, 2, 4, Everything, MeshVecs<S>>;

/// A ball of radius 1 about (0, 1, 4) by latitude and longitude: 4 bands of 6 quads, the
/// poles' bands fans of 6, 36 triangles sharing their edges.
fn ball() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    const BANDS: u32 = 4;
    const AROUND: u32 = 6;
    let at = |band: u32, turn: u32| -> [f32; 3] {
        let (lat, lon) = (
            std::f64::consts::PI * f64::from(band) / f64::from(BANDS),
            std::f64::consts::TAU * f64::from(turn % AROUND) / f64::from(AROUND),
        );
        [
            lat.sin() * lon.cos(),
            1.0 + lat.cos(),
            4.0 + lat.sin() * lon.sin(),
        ]
        .map(|c| c as f32)
    };
    // The poles, then each ring between them.
    let mut vertices = vec![at(0, 0), at(BANDS, 0)];
    let ring = |band: u32, turn: u32| 2 + (band - 1) * AROUND + turn % AROUND;
    for band in 1..BANDS {
        vertices.extend((0..AROUND).map(|turn| at(band, turn)));
    }
    let mut triangles = Vec::new();
    for turn in 0..AROUND {
        triangles.push([0, ring(1, turn + 1), ring(1, turn)]);
        triangles.push([1, ring(BANDS - 1, turn), ring(BANDS - 1, turn + 1)]);
        for band in 1..BANDS - 1 {
            let (a, b) = (ring(band, turn), ring(band, turn + 1));
            let (c, d) = (ring(band + 1, turn), ring(band + 1, turn + 1));
            triangles.extend([[a, b, d], [a, d, c]]);
        }
    }
    (vertices, triangles)
}

const MATERIAL: MaterialDesc = MaterialDesc {
    colour: [0.8, 0.4, 0.2],
    diffuse: 0.8,
    specular: 0.5,
    shininess: 20,
    reflection: 0.2,
    transmission: 0.0,
    ior: 1.0,
};

/// A floor, and a light above: the ball shadows the floor and the floor shows in the ball.
fn scene<'a>(objects: &'a [ObjectDesc], meshes: MeshesDesc<'a>) -> SceneDesc<'a> {
    const LIGHTS: &[LightDesc] = &[LightDesc::point([-3.0, 6.0, 0.0], [1.0; 3])];
    SceneDesc {
        camera: CameraDesc::pinhole([0.3, 1.6, 0.0], [0.0, 1.0, 4.0], [0.0, 1.0, 0.0], 40.0),
        objects,
        meshes,
        lights: LIGHTS,
        ambient: [0.1; 3],
        background: BackgroundDesc::Solid([0.2, 0.3, 0.5]),
        far: 20.0,
        max_depth: 2,
        ..SceneDesc::DEFAULT
    }
}

const FLOOR: ObjectDesc = ObjectDesc {
    shape: ShapeDesc::Plane {
        point: [0.0, 0.0, 0.0],
        normal: [0.0, 1.0, 0.0],
        checker: None,
    },
    material: MaterialDesc::matte([0.7; 3]),
};

/// The ball as a mesh, with its hierarchy (its nodes and reordered triangles).
fn mesh() -> (Vec<[f32; 3]>, Vec<[u32; 3]>, Vec<NodeDesc>) {
    let (vertices, mut triangles) = ball();
    let mut nodes = vec![NodeDesc::default(); 2 * triangles.len() - 1];
    let made = build_hierarchy(&vertices, &mut triangles, &mut nodes).expect("a hierarchy");
    nodes.truncate(made);
    (vertices, triangles, nodes)
}

/// A pixel's colour, and what its primary ray meets: the object, and on a mesh its triangle.
type Pixel = ([f64; 3], Option<(usize, u32)>);

/// Every pixel of a 48 × 48 image of `desc` in format `S`.
fn image<S: Scalar>(desc: &SceneDesc<'_>) -> Vec<Pixel> {
    let scene = MeshScene::<S>::build(desc).expect("the scene builds");
    let camera = scene.camera(48, 48).expect("a camera");
    (0..48)
        .flat_map(|y| {
            let row = camera.row(y).expect("a row");
            let scene = &scene;
            (0..).zip(row.rays()).map(move |(x, ray)| {
                let id = SampleId { x, y, sample: 0 };
                (scene.trace(ray, id).colour.to_f64(), scene.first_hit(&ray))
            })
        })
        .collect()
}

#[test]
fn a_mesh_traces_as_its_triangles_do() {
    let (vertices, triangles, nodes) = mesh();
    let meshes = MeshesDesc {
        vertices: &vertices,
        triangles: &triangles,
        nodes: &nodes,
        normals: &[],
    };
    let as_mesh = [
        FLOOR,
        ObjectDesc {
            shape: ShapeDesc::Mesh { root: 0 },
            material: MATERIAL,
        },
    ];
    let as_triangles: Vec<ObjectDesc> = std::iter::once(FLOOR)
        .chain(triangles.iter().map(|&t| ObjectDesc {
            shape: ShapeDesc::Triangle {
                vertices: meshes.corners(t),
            },
            material: MATERIAL,
        }))
        .collect();
    let (mesh_scene, triangle_scene) = (
        scene(&as_mesh, meshes),
        scene(&as_triangles, MeshesDesc::NONE),
    );
    // The same hits: every primary ray meets the triangle it meets among the triangles (the
    // mesh's triangle k is object k + 1 there), so the hierarchy skips none a ray meets. The
    // colours differ only by the surface tolerance (a mesh's is its triangles' largest), which
    // moves where secondary rays start by a few steps of the format: less than a level.
    for (name, mesh, triangles) in [
        (
            "f64",
            image::<f64>(&mesh_scene),
            image::<f64>(&triangle_scene),
        ),
        (
            "f32",
            image::<f32>(&mesh_scene),
            image::<f32>(&triangle_scene),
        ),
        (
            "i16f16",
            image::<I16F16>(&mesh_scene),
            image::<I16F16>(&triangle_scene),
        ),
    ] {
        let on_ball = mesh
            .iter()
            .filter(|(_, hit)| matches!(hit, Some((1, _))))
            .count();
        assert!(on_ball > mesh.len() / 4, "{name}: the ball fills the image");
        for (i, ((colour, hit), (colour_there, hit_there))) in
            mesh.iter().zip(&triangles).enumerate()
        {
            let same = match (*hit, *hit_there) {
                (Some((1, part)), Some((object, 0))) => object == part as usize + 1,
                (hit, hit_there) => hit == hit_there,
            };
            assert!(same, "{name}, pixel {i}: {hit:?} against {hit_there:?}");
            let off = colour
                .iter()
                .zip(colour_there)
                .map(|(a, b)| (a - b).abs() * 255.0)
                .fold(0.0, f64::max);
            assert!(off < 1.0, "{name}, pixel {i}: {off} levels apart");
        }
    }
}

/// The ball's own normals at its vertices: from its centre, (0, 1, 4), out.
fn ball_normals(vertices: &[[f32; 3]]) -> Vec<[f32; 3]> {
    vertices
        .iter()
        .map(|&[x, y, z]| {
            let n = [f64::from(x), f64::from(y) - 1.0, f64::from(z) - 4.0];
            let length = n.iter().map(|c| c * c).sum::<f64>().sqrt();
            n.map(|c| (c / length) as f32)
        })
        .collect()
}

#[test]
fn a_smooth_mesh_shades_as_the_surface_it_approximates() {
    let (vertices, triangles, nodes) = mesh();
    let normals = ball_normals(&vertices);
    let flat = MeshesDesc {
        vertices: &vertices,
        triangles: &triangles,
        nodes: &nodes,
        normals: &[],
    };
    let smooth = MeshesDesc {
        normals: &normals,
        ..flat
    };
    // Matte and specular, no mirror: what the normal shades is all there is to see.
    let material = MaterialDesc {
        reflection: 0.0,
        ..MATERIAL
    };
    let mesh = [
        FLOOR,
        ObjectDesc {
            shape: ShapeDesc::Mesh { root: 0 },
            material,
        },
    ];
    let ball = [
        FLOOR,
        ObjectDesc {
            shape: ShapeDesc::Sphere {
                center: [0.0, 1.0, 4.0],
                radius: 1.0,
            },
            material,
        },
    ];
    let sphere = image::<f64>(&scene(&ball, MeshesDesc::NONE));
    // The mean difference from the sphere, in levels, where the primary ray meets the ball in
    // both pictures.
    let apart = |image: &[Pixel]| {
        let both: Vec<f64> = image
            .iter()
            .zip(&sphere)
            .filter(|((_, hit), (_, there))| {
                matches!(hit, Some((1, _))) && matches!(there, Some((1, _)))
            })
            .map(|((colour, _), (colour_there, _))| {
                colour
                    .iter()
                    .zip(colour_there)
                    .map(|(a, b)| (a - b).abs() * 255.0)
                    .fold(0.0, f64::max)
            })
            .collect();
        assert!(both.len() > image.len() / 5, "the ball fills the image");
        both.iter().sum::<f64>() / both.len() as f64
    };
    let flat_apart = apart(&image::<f64>(&scene(&mesh, flat)));
    let smooth_image = image::<f64>(&scene(&mesh, smooth));
    let smooth_apart = apart(&smooth_image);
    // Of 36 triangles, the ball's hits are up to a sixth of its radius inside the sphere's and
    // its interpolated normals a few degrees off the sphere's there: the smooth picture is not
    // the sphere's, but less than half as far from it as the facets'.
    assert!(
        smooth_apart < flat_apart / 2.0,
        "smooth {smooth_apart:.1} levels from the sphere, flat {flat_apart:.1}"
    );
    // A 32-bit split shades it as f64 does, within a level or two where the hit is the same.
    for (i, ((colour, hit), (colour_there, hit_there))) in image::<I16F16>(&scene(&mesh, smooth))
        .iter()
        .zip(&smooth_image)
        .enumerate()
    {
        if hit == hit_there {
            let off = colour
                .iter()
                .zip(colour_there)
                .map(|(a, b)| (a - b).abs() * 255.0)
                .fold(0.0, f64::max);
            assert!(off < 2.0, "i16f16, pixel {i}: {off} levels from f64");
        }
    }
}

#[test]
fn normals_that_are_not_one_unit_normal_per_vertex_are_refused() {
    let (vertices, triangles, nodes) = mesh();
    let objects = [ObjectDesc {
        shape: ShapeDesc::Mesh { root: 0 },
        material: MATERIAL,
    }];
    let refused = |normals: &[[f32; 3]]| {
        let meshes = MeshesDesc {
            vertices: &vertices,
            triangles: &triangles,
            nodes: &nodes,
            normals,
        };
        match MeshScene::<f32>::build(&scene(&objects, meshes)) {
            Err(SceneError::MalformedMesh { what, .. }) => Some(what),
            Ok(_) => None,
            Err(other) => panic!("{other:?}"),
        }
    };
    let mut normals = ball_normals(&vertices);
    assert_eq!(refused(&normals), None);
    normals[3] = [0.0; 3];
    assert_eq!(refused(&normals), None, "a vertex without a normal");
    assert!(refused(&normals[1..]).is_some_and(|what| what.contains("one per vertex")));
    normals[3] = [0.0, 2.0, 0.0];
    assert!(refused(&normals).is_some_and(|what| what.contains("length")));
}

#[test]
fn a_hierarchy_that_does_not_hold_its_triangles_is_refused() {
    let (vertices, triangles, nodes) = mesh();
    let objects = [ObjectDesc {
        shape: ShapeDesc::Mesh { root: 0 },
        material: MATERIAL,
    }];
    let refused = |nodes: &[NodeDesc]| {
        let meshes = MeshesDesc {
            vertices: &vertices,
            triangles: &triangles,
            nodes,
            normals: &[],
        };
        match MeshScene::<f32>::build(&scene(&objects, meshes)) {
            Err(SceneError::MalformedMesh { what, .. }) => what,
            other => panic!("{other:?}"),
        }
    };
    // A leaf's box shrunk off one of its triangles.
    let mut shrunk = nodes.clone();
    let leaf = shrunk.iter_mut().find(|n| n.right == 0).expect("a leaf");
    leaf.max[0] = leaf.min[0];
    assert!(refused(&shrunk).contains("leaf's box"));
    // Children that do not split their parent's triangles.
    let mut split = nodes.clone();
    split[1].end -= 1;
    assert!(refused(&split).contains("children"));
    // A root that is not a node.
    let mut rootless = nodes.clone();
    rootless.truncate(0);
    assert!(refused(&rootless).contains("not among the nodes"));
    // A corner that is not a vertex.
    let mut corners = triangles.clone();
    corners[0][0] = 999;
    let meshes = MeshesDesc {
        vertices: &vertices,
        triangles: &corners,
        nodes: &nodes,
        normals: &[],
    };
    assert!(matches!(
        MeshScene::<f32>::build(&scene(&objects, meshes)),
        Err(SceneError::MalformedMesh { .. })
    ));
}
