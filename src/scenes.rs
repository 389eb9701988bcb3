//! The built-in scenes, as const data that a firmware keeps in flash.

crate::phase::declare_phase!(Some(crate::phase::Phase::Build));

use crate::desc::{
    BackgroundDesc, CameraDesc, CheckerDesc, LightDesc, MaterialDesc, ObjectDesc, SceneDesc,
    ShapeDesc,
};

/// A built-in scene with its name and a line about it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuiltIn {
    /// The name the command line uses.
    pub name: &'static str,
    /// What it shows.
    pub summary: &'static str,
    /// The scene.
    pub desc: SceneDesc<'static>,
}

/// Every built-in scene.
pub const BUILT_IN: [BuiltIn; 4] = [
    BuiltIn {
        name: "whitted",
        summary: "Whitted's 1979 spheres and checkerboard: a glass sphere above a mirrored one",
        desc: WHITTED,
    },
    BuiltIn {
        name: "shapes",
        summary: "the three primitives: spheres, a checkered plane and triangles, two coloured lights",
        desc: SHAPES,
    },
    BuiltIn {
        name: "soft",
        summary: "the lecture's soft shadows: a sphere, a ball and a tetrahedron on a floor under a disc light",
        desc: SOFT,
    },
    BuiltIn {
        name: "focus",
        summary: "depth of field: five spheres in a row, the lens focused on the middle one",
        desc: FOCUS,
    },
];

/// The built-in scenes that trace one ray per pixel and one shadow ray per light, whose cost
/// and accuracy the methods chart measures (and the cost model reads): the sampling of the
/// others multiplies both, and is measured on its own axis.
pub fn one_ray() -> impl Iterator<Item = &'static BuiltIn> {
    BUILT_IN.iter().filter(|scene| scene.desc.traces_one_ray())
}

/// The built-in scene called `name`.
#[must_use]
pub fn find(name: &str) -> Option<&'static BuiltIn> {
    BUILT_IN.iter().find(|scene| scene.name == name)
}

const GLASS: MaterialDesc = MaterialDesc {
    colour: [1.0, 1.0, 1.0],
    diffuse: 0.04,
    specular: 0.7,
    shininess: 120,
    reflection: 0.1,
    transmission: 0.88,
    ior: 1.5,
};

const MIRRORED: MaterialDesc = MaterialDesc {
    colour: [0.75, 0.75, 0.72],
    diffuse: 0.35,
    specular: 0.6,
    shininess: 40,
    reflection: 0.55,
    transmission: 0.0,
    ior: 1.0,
};

const RED: [f32; 3] = [0.95, 0.08, 0.05];
const YELLOW: [f32; 3] = [0.98, 0.86, 0.08];

const WHITTED_OBJECTS: [ObjectDesc; 3] = [
    ObjectDesc {
        shape: ShapeDesc::Plane {
            point: [0.0, 0.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            checker: Some(CheckerDesc {
                colour: YELLOW,
                size: 1.0,
            }),
        },
        material: MaterialDesc::matte(RED),
    },
    ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [-1.2, 1.0, 3.2],
            radius: 1.0,
        },
        material: MIRRORED,
    },
    ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [0.55, 1.9, 0.6],
            radius: 1.0,
        },
        material: GLASS,
    },
];

const WHITTED_LIGHTS: [LightDesc; 1] = [LightDesc::point([-5.0, 12.0, -8.0], [1.0, 1.0, 1.0])];

/// Whitted's "spheres and checkerboard" (1979): a mostly transmissive, slightly reflective glass
/// sphere in front of and above an opaque reflective sphere, over a red-and-yellow checkerboard,
/// under a blue sky, lit by one point light with hard shadows.
pub const WHITTED: SceneDesc<'static> = SceneDesc {
    camera: CameraDesc::pinhole([0.0, 3.0, -6.0], [-0.2, 1.0, 2.0], [0.0, 1.0, 0.0], 45.0),
    objects: &WHITTED_OBJECTS,
    lights: &WHITTED_LIGHTS,
    ambient: [0.12, 0.12, 0.14],
    background: BackgroundDesc::Gradient {
        up: crate::desc::Y_UP,
        horizon: [0.55, 0.72, 0.98],
        zenith: [0.12, 0.3, 0.8],
    },
    far: 30.0,
    max_depth: 5,
    ..SceneDesc::DEFAULT
};

const GREEN: MaterialDesc = MaterialDesc {
    colour: [0.2, 0.75, 0.3],
    diffuse: 0.85,
    specular: 0.3,
    shininess: 20,
    reflection: 0.0,
    transmission: 0.0,
    ior: 1.0,
};

/// A tetrahedron's apex and base corners, an edge towards the camera so that two faces show,
/// each lit by a different light (three faces are modelled; the base stays hidden).
const APEX: [f32; 3] = [0.3, 1.6, 3.2];
const BASE: [[f32; 3]; 3] = [[0.3, 0.0, 2.25], [1.12, 0.0, 3.675], [-0.52, 0.0, 3.675]];

const SHAPES_OBJECTS: [ObjectDesc; 6] = [
    ObjectDesc {
        shape: ShapeDesc::Plane {
            point: [0.0, 0.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            checker: Some(CheckerDesc {
                colour: [0.35, 0.35, 0.38],
                size: 0.75,
            }),
        },
        material: MaterialDesc::matte([0.85, 0.85, 0.85]),
    },
    ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [-1.7, 0.8, 2.2],
            radius: 0.8,
        },
        material: MaterialDesc {
            specular: 0.4,
            shininess: 30,
            ..MaterialDesc::matte([0.85, 0.15, 0.12])
        },
    },
    ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [1.9, 0.6, 1.6],
            radius: 0.6,
        },
        material: MaterialDesc {
            colour: [0.2, 0.35, 0.9],
            diffuse: 0.5,
            specular: 0.8,
            shininess: 80,
            reflection: 0.35,
            transmission: 0.0,
            ior: 1.0,
        },
    },
    ObjectDesc {
        shape: ShapeDesc::Triangle {
            vertices: [BASE[0], BASE[1], APEX],
        },
        material: GREEN,
    },
    ObjectDesc {
        shape: ShapeDesc::Triangle {
            vertices: [BASE[1], BASE[2], APEX],
        },
        material: GREEN,
    },
    ObjectDesc {
        shape: ShapeDesc::Triangle {
            vertices: [BASE[2], BASE[0], APEX],
        },
        material: GREEN,
    },
];

const SHAPES_LIGHTS: [LightDesc; 2] = [
    LightDesc::point([-4.0, 7.0, -3.0], [0.75, 0.6, 0.45]),
    LightDesc::point([5.0, 6.0, -1.0], [0.35, 0.45, 0.75]),
];

/// The lecture's three primitives together: two spheres, a checkered plane and a tetrahedron
/// of triangles, lit by a warm and a cool light that cast coloured shadows.
pub const SHAPES: SceneDesc<'static> = SceneDesc {
    camera: CameraDesc::pinhole([0.0, 2.4, -4.5], [0.0, 0.8, 2.4], [0.0, 1.0, 0.0], 50.0),
    objects: &SHAPES_OBJECTS,
    lights: &SHAPES_LIGHTS,
    ambient: [0.1, 0.1, 0.1],
    background: BackgroundDesc::Solid([0.08, 0.1, 0.14]),
    far: 25.0,
    max_depth: 3,
    ..SceneDesc::DEFAULT
};

/// The soft scene's tetrahedron: apex and base corners.
const SOFT_APEX: [f32; 3] = [1.35, 1.9, 1.7];
const SOFT_BASE: [[f32; 3]; 3] = [[1.35, 0.0, 0.75], [2.2, 0.0, 2.2], [0.5, 0.0, 2.2]];
const SOFT_TETRAHEDRON: MaterialDesc = MaterialDesc {
    specular: 0.25,
    shininess: 20,
    ..MaterialDesc::matte([0.95, 0.7, 0.2])
};

const SOFT_OBJECTS: [ObjectDesc; 6] = [
    ObjectDesc {
        shape: ShapeDesc::Plane {
            point: [0.0, 0.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            checker: None,
        },
        material: MaterialDesc::matte([0.85, 0.85, 0.82]),
    },
    ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [-1.15, 0.9, 1.2],
            radius: 0.9,
        },
        material: MaterialDesc {
            specular: 0.4,
            shininess: 40,
            ..MaterialDesc::matte([0.8, 0.15, 0.12])
        },
    },
    ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [0.35, 0.35, -0.6],
            radius: 0.35,
        },
        material: MaterialDesc {
            specular: 0.5,
            shininess: 60,
            ..MaterialDesc::matte([0.15, 0.3, 0.85])
        },
    },
    ObjectDesc {
        shape: ShapeDesc::Triangle {
            vertices: [SOFT_BASE[0], SOFT_BASE[1], SOFT_APEX],
        },
        material: SOFT_TETRAHEDRON,
    },
    ObjectDesc {
        shape: ShapeDesc::Triangle {
            vertices: [SOFT_BASE[1], SOFT_BASE[2], SOFT_APEX],
        },
        material: SOFT_TETRAHEDRON,
    },
    ObjectDesc {
        shape: ShapeDesc::Triangle {
            vertices: [SOFT_BASE[2], SOFT_BASE[0], SOFT_APEX],
        },
        material: SOFT_TETRAHEDRON,
    },
];

const SOFT_LIGHTS: [LightDesc; 1] = [LightDesc {
    radius: 1.2,
    ..LightDesc::point([-2.6, 5.5, -2.2], [0.95, 0.92, 0.85])
}];

/// The lecture's "how do we get these nice, soft shadows?": a large sphere, a small ball and a
/// tetrahedron on a plain floor under one disc light, 16 shadow rays each point, taken
/// adaptively. The penumbra widens with the distance from the occluder: narrow where the ball
/// touches the floor, wide behind the apex.
pub const SOFT: SceneDesc<'static> = SceneDesc {
    camera: CameraDesc::pinhole([0.0, 3.2, -5.5], [0.0, 0.6, 1.0], [0.0, 1.0, 0.0], 45.0),
    objects: &SOFT_OBJECTS,
    lights: &SOFT_LIGHTS,
    ambient: [0.12, 0.12, 0.12],
    background: BackgroundDesc::Gradient {
        up: crate::desc::Y_UP,
        horizon: [0.6, 0.62, 0.66],
        zenith: [0.25, 0.3, 0.4],
    },
    far: 12.0,
    max_depth: 2,
    shadow_samples: 16,
    adaptive_shadows: true,
    ..SceneDesc::DEFAULT
};

/// A sphere of the focus scene: `k` steps along the row, of `colour`.
const fn focus_sphere(k: f32, material: MaterialDesc) -> ObjectDesc {
    ObjectDesc {
        shape: ShapeDesc::Sphere {
            center: [-0.9 + 0.45 * k, 0.5, -1.5 + 2.0 * k],
            radius: 0.5,
        },
        material,
    }
}

/// A shiny sphere of the focus scene.
const fn focus_ball(colour: [f32; 3]) -> MaterialDesc {
    MaterialDesc {
        specular: 0.5,
        shininess: 50,
        ..MaterialDesc::matte(colour)
    }
}

const FOCUS_OBJECTS: [ObjectDesc; 6] = [
    ObjectDesc {
        shape: ShapeDesc::Plane {
            point: [0.0, 0.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            checker: Some(CheckerDesc {
                colour: [0.2, 0.2, 0.22],
                size: 1.0,
            }),
        },
        material: MaterialDesc::matte([0.85, 0.85, 0.82]),
    },
    focus_sphere(0.0, focus_ball([0.85, 0.2, 0.12])),
    focus_sphere(1.0, focus_ball([0.95, 0.7, 0.1])),
    focus_sphere(2.0, MIRRORED),
    focus_sphere(3.0, focus_ball([0.2, 0.7, 0.3])),
    focus_sphere(4.0, focus_ball([0.2, 0.35, 0.9])),
];

const FOCUS_LIGHTS: [LightDesc; 1] = [LightDesc::point([-4.0, 7.0, -3.0], [1.0, 0.97, 0.92])];

/// The lecture's "depth of field: can we ray trace it?": five spheres in a row receding over a
/// checkerboard, seen through a lens of radius 0.25 focused on the middle, mirrored one (its
/// centre is where the camera looks). The nearest sphere and the farthest blur, and so does the
/// checkerboard away from the middle; 16 rays per pixel spread over pixel and lens.
pub const FOCUS: SceneDesc<'static> = SceneDesc {
    camera: CameraDesc {
        aperture: 0.25,
        ..CameraDesc::pinhole([0.9, 1.3, -6.0], [0.0, 0.5, 2.5], [0.0, 1.0, 0.0], 45.0)
    },
    objects: &FOCUS_OBJECTS,
    lights: &FOCUS_LIGHTS,
    ambient: [0.12, 0.12, 0.12],
    background: BackgroundDesc::Gradient {
        up: crate::desc::Y_UP,
        horizon: [0.7, 0.74, 0.8],
        zenith: [0.3, 0.42, 0.65],
    },
    far: 16.0,
    max_depth: 2,
    samples: 16,
    ..SceneDesc::DEFAULT
};
