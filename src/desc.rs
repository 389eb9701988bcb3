//! Scene descriptions: plain `f32` data in world units, const-constructible so that a firmware
//! keeps its scene in flash. [`crate::Scene::build`] validates one and converts it into a
//! number format.

crate::phase::declare_phase!(Some(crate::phase::Phase::Build));

/// A scene as its author writes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneDesc<'a> {
    /// Where the camera stands and looks, and its lens.
    pub camera: CameraDesc,
    /// Spheres, planes, triangles and meshes, each with its material.
    pub objects: &'a [ObjectDesc],
    /// The triangles and hierarchies of the scene's meshes ([`ShapeDesc::Mesh`]);
    /// [`MeshesDesc::NONE`] for a scene without them.
    pub meshes: MeshesDesc<'a>,
    /// Lights: points, or discs casting soft shadows.
    pub lights: &'a [LightDesc],
    /// Light that reaches every surface, shadowed or not (a fraction of the surface colour).
    pub ambient: [f32; 3],
    /// What a ray that hits nothing sees.
    pub background: BackgroundDesc,
    /// The radius of the world around the eye: nothing farther is seen, and every object and
    /// light must lie within it. A fixed-point format only has to hold numbers this big, so
    /// model no more than the scene needs.
    pub far: f32,
    /// The deepest ray tree: 0 traces primary rays only, each level adds one reflection or
    /// refraction.
    pub max_depth: u8,
    /// Rays per pixel, 1 to [`MAX_SAMPLES`](crate::pattern::MAX_SAMPLES): 1 traces the
    /// pixel's centre (the lecture's camera; through a lens, from one point of it); more spread
    /// over the pixel (and the lens) in a fixed pattern and average (anti-aliasing).
    pub samples: u16,
    /// Adaptive anti-aliasing after Whitted (1980): rays at the pixels'
    /// corners, shared with their neighbours, and cells split into quarters where their
    /// corners differ, down to 1/`samples` of the pixel (`samples` then 4, 16, 64 or 256).
    /// Flat regions cost about a ray a pixel, a pixel split all through more than `samples`.
    /// Not with a lens.
    pub adaptive_samples: bool,
    /// Shadow rays from a point to each light with a [`LightDesc::radius`], 1 to
    /// [`MAX_SAMPLES`](crate::pattern::MAX_SAMPLES): 1 aims at the light's centre (a hard
    /// shadow); more spread over the light in a fixed pattern, and the share that gets
    /// through is the light that arrives (soft shadows).
    pub shadow_samples: u16,
    /// Adaptive shadow rays: a point takes an area light's first
    /// [`SHADOW_PROBES`](crate::pattern::SHADOW_PROBES) shadow rays, and the rest only where those
    /// disagree (in the penumbra). Faster where most points are in full light or full shadow;
    /// a sliver of penumbra that all the first rays miss is taken for full light or shadow.
    pub adaptive_shadows: bool,
    /// How the frame's pixels are found: each by its own ray ([`Pixels::Exact`]), or in blocks
    /// filled from their corners where the corners agree ([`Pixels::Adaptive`]: one sample a
    /// pixel, not with a lens or adaptive samples).
    pub pixels: Pixels,
}

impl SceneDesc<'static> {
    /// An empty scene, to fill in with `..SceneDesc::DEFAULT`: a pinhole camera at the origin
    /// looking along +z with +y up and 60° of view, a world of radius 100, no objects or
    /// lights, a dim grey ambient light (0.1), a black background, ray trees 5 levels deep,
    /// one ray a pixel and one shadow ray a light. A scene file's keys left out take these
    /// values too.
    ///
    /// ```
    /// use obscura::{CameraDesc, LightDesc, MaterialDesc, ObjectDesc, Scene, SceneDesc, ShapeDesc};
    ///
    /// const BALL: &[ObjectDesc] = &[ObjectDesc {
    ///     shape: ShapeDesc::Sphere { center: [0.0, 1.0, 0.0], radius: 1.0 },
    ///     material: MaterialDesc::matte([0.9, 0.2, 0.1]),
    /// }];
    /// const SCENE: SceneDesc<'static> = SceneDesc {
    ///     camera: CameraDesc::pinhole([0.0, 1.5, -5.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0], 45.0),
    ///     objects: BALL,
    ///     lights: &[LightDesc::point([-3.0, 5.0, -4.0], [1.0; 3])],
    ///     far: 20.0,
    ///     ..SceneDesc::DEFAULT
    /// };
    /// assert!(Scene::<f32, 1, 1, 6>::build(&SCENE).is_ok());
    /// ```
    pub const DEFAULT: Self = Self {
        camera: CameraDesc::pinhole([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 60.0),
        objects: &[],
        meshes: MeshesDesc::NONE,
        lights: &[],
        ambient: [0.1; 3],
        background: BackgroundDesc::Solid([0.0; 3]),
        far: 100.0,
        max_depth: 5,
        samples: 1,
        adaptive_samples: false,
        shadow_samples: 1,
        adaptive_shadows: false,
        pixels: Pixels::Exact,
    };
}

/// How a frame's pixels are found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Pixels {
    /// Every pixel by its own ray (or its samples).
    #[default]
    Exact,
    /// Blocks of N×N pixels (N = 2, 4 or 8) filled from their corners where the corners
    /// agree (the same objects met, the same checker square, close colours), split where they
    /// do not: about 1/N² of the rays where the image is flat.
    Adaptive(u8),
}

impl crate::methods::MethodName for Pixels {
    const ALL: &'static [(Self, &'static str)] = &[
        (Self::Exact, "exact"),
        (Self::Adaptive(2), "adaptive:2"),
        (Self::Adaptive(4), "adaptive:4"),
        (Self::Adaptive(8), "adaptive:8"),
    ];
}

impl Pixels {
    /// The side of a block: 1 for exact pixels.
    #[must_use]
    pub const fn block(self) -> u8 {
        match self {
            Self::Exact => 1,
            Self::Adaptive(n) => n,
        }
    }

    /// The sides a block can take.
    pub const BLOCKS: [u8; 3] = [2, 4, 8];
}

/// [`SceneDesc::DEFAULT`].
impl Default for SceneDesc<'_> {
    fn default() -> Self {
        SceneDesc::DEFAULT
    }
}

impl SceneDesc<'_> {
    /// Whether a pixel takes one ray and a light one shadow ray: no samples spread over the
    /// pixel, and no area light sampled.
    #[must_use]
    pub const fn traces_one_ray(&self) -> bool {
        let mut rest = self.lights;
        let mut point_lights = true;
        while let [first, others @ ..] = rest {
            point_lights &= first.radius == 0.0;
            rest = others;
        }
        self.samples == 1 && !self.adaptive_samples && (point_lights || self.shadow_samples == 1)
    }

    /// Whether any object is a triangle or a mesh (the triangle methods matter only then).
    #[must_use]
    pub const fn has_triangles(&self) -> bool {
        let mut rest = self.objects;
        while let [first, others @ ..] = rest {
            if let ShapeDesc::Triangle { .. } | ShapeDesc::Mesh { .. } = first.shape {
                return true;
            }
            rest = others;
        }
        false
    }

    /// Every object as the primitives it is made of, with its index: a mesh as each of its
    /// triangles (with the mesh's material), every other object as itself. What the range
    /// proof and the analyses bound: a mesh's triangle is traced as a triangle is.
    pub fn primitives(&self) -> impl Iterator<Item = (usize, ObjectDesc)> + '_ {
        self.objects
            .iter()
            .enumerate()
            .flat_map(move |(i, object)| {
                let mesh = match object.shape {
                    ShapeDesc::Mesh { root } => self.meshes.triangles_of(root),
                    _ => &[],
                };
                let whole = (!matches!(object.shape, ShapeDesc::Mesh { .. })).then_some(*object);
                whole
                    .into_iter()
                    .chain(mesh.iter().map(move |&corners| ObjectDesc {
                        shape: ShapeDesc::Triangle {
                            vertices: self.meshes.corners(corners),
                        },
                        material: object.material,
                    }))
                    .map(move |primitive| (i, primitive))
            })
    }
}

/// The triangles of a scene's meshes, shared corners and a bounding-volume hierarchy over
/// them: what [`ShapeDesc::Mesh`] objects refer to. Const-constructible, so that a firmware's
/// scene keeps it in flash; `obscura::mesh::build_hierarchy` makes the hierarchy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshesDesc<'a> {
    /// The corners, in world units.
    pub vertices: &'a [[f32; 3]],
    /// Each triangle's corners, as indices into `vertices`, in the order of the hierarchy's
    /// leaves.
    pub triangles: &'a [[u32; 3]],
    /// The hierarchy's nodes, each subtree's root before its left subtree and that before its
    /// right: a mesh's root is the node its object names.
    pub nodes: &'a [NodeDesc],
    /// A unit normal at each vertex, for a surface shaded as smooth (the normal interpolated
    /// across each triangle from its corners'), or none at all: then, and on a triangle with
    /// a corner whose normal is zero, the triangle's own normal shades it.
    pub normals: &'a [[f32; 3]],
}

impl MeshesDesc<'_> {
    /// No meshes.
    pub const NONE: MeshesDesc<'static> = MeshesDesc {
        vertices: &[],
        triangles: &[],
        nodes: &[],
        normals: &[],
    };

    /// The triangles under node `root` (none where the node or its range is not there:
    /// validation refuses such a mesh).
    #[must_use]
    pub fn triangles_of(&self, root: u32) -> &[[u32; 3]] {
        self.nodes
            .get(root as usize)
            .and_then(|node| self.triangles.get(node.first as usize..node.end as usize))
            .unwrap_or(&[])
    }

    /// The corners a triangle's indices name (the origin where an index is not there:
    /// validation refuses such a mesh).
    #[must_use]
    pub fn corners(&self, indices: [u32; 3]) -> [[f32; 3]; 3] {
        indices.map(|i| self.vertices.get(i as usize).copied().unwrap_or([0.0; 3]))
    }

    /// The normals at the corners a triangle's indices name, where the meshes have normals and
    /// each of the three is nonzero; else the triangle is shaded flat.
    #[must_use]
    pub fn corner_normals(&self, indices: [u32; 3]) -> Option<[[f32; 3]; 3]> {
        let normals = indices.map(|i| self.normals.get(i as usize).copied());
        match normals {
            [Some(a), Some(b), Some(c)] if [a, b, c].iter().all(|n| *n != [0.0; 3]) => {
                Some([a, b, c])
            }
            _ => None,
        }
    }
}

/// A node of a mesh's bounding-volume hierarchy: a box holding the triangles `first..end`,
/// which are the node's own where it is a leaf (`right` 0), else its children's: the left one
/// is the next node, the right one node `right`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NodeDesc {
    /// The box's lowest corner.
    pub min: [f32; 3],
    /// The box's highest corner.
    pub max: [f32; 3],
    /// The first triangle under the node.
    pub first: u32,
    /// One past the last triangle under the node.
    pub end: u32,
    /// The right child's index, after the node's own; 0 for a leaf.
    pub right: u32,
    /// The axis (0, 1, 2 for x, y, z) the children were split along: a ray visits first the
    /// child on the side it comes from.
    pub axis: u8,
}

/// A camera: a pinhole, or a thin lens that blurs what is off its focal plane (depth of field).
/// Coordinates are right-handed: with +y up and the camera looking along +z, +x points to the
/// left of the image.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct CameraDesc {
    /// The eye: where every primary ray starts.
    pub eye: [f32; 3],
    /// The point in the centre of the image.
    pub look_at: [f32; 3],
    /// Which way is up (need not be perpendicular to the view direction, must not be parallel).
    pub up: [f32; 3],
    /// The vertical field of view in degrees, in (0, 180).
    pub vfov_degrees: f32,
    /// The lens's radius, ≥ 0: 0 is the lecture's pinhole, every point sharp. A lens of this
    /// radius about the eye, facing `look_at`, brings to a point only what lies on the plane
    /// `focus_distance` ahead; nearer and farther points blur into discs that grow with the
    /// aperture (Cook, Porter and Carpenter's thin lens). Each of a pixel's
    /// [`SceneDesc::samples`] rays starts from another point of the lens.
    #[cfg_attr(feature = "serde", serde(default))]
    pub aperture: f32,
    /// How far ahead, along the view direction, the lens focuses: the distance from the eye to
    /// `look_at` where it is not given. Matters only with an `aperture`.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub focus_distance: Option<f32>,
}

impl CameraDesc {
    /// A pinhole camera at `eye` looking at `look_at`, `up` being up, seeing `vfov_degrees`
    /// from the top of the image to the bottom.
    ///
    /// ```
    /// use obscura::CameraDesc;
    ///
    /// let camera = CameraDesc::pinhole([0.0, 1.0, -4.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0], 45.0);
    /// assert_eq!(camera.aperture, 0.0); // a pinhole: no depth of field
    /// ```
    #[must_use]
    pub const fn pinhole(
        eye: [f32; 3],
        look_at: [f32; 3],
        up: [f32; 3],
        vfov_degrees: f32,
    ) -> Self {
        Self {
            eye,
            look_at,
            up,
            vfov_degrees,
            aperture: 0.0,
            focus_distance: None,
        }
    }
}

/// One object: a shape and what it is made of.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct ObjectDesc {
    /// The geometry.
    pub shape: ShapeDesc,
    /// The surface.
    #[cfg_attr(feature = "serde", serde(default))]
    pub material: MaterialDesc,
}

/// The geometric primitives.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum ShapeDesc {
    /// A sphere.
    Sphere {
        /// Its centre.
        center: [f32; 3],
        /// Its radius, > 0.
        radius: f32,
    },
    /// A plane through `point` facing `normal`, cut off where it leaves the world (see
    /// [`SceneDesc::far`]), optionally patterned as a checkerboard.
    Plane {
        /// A point on the plane; the checkerboard's squares are aligned to it.
        point: [f32; 3],
        /// The plane's normal (any length but zero).
        normal: [f32; 3],
        /// A checkerboard of the material's colour and this one.
        checker: Option<CheckerDesc>,
    },
    /// A triangle, visible from both sides.
    Triangle {
        /// The corners, in any order.
        vertices: [[f32; 3]; 3],
    },
    /// A mesh of triangles ([`SceneDesc::meshes`]), each visible from both sides, found through
    /// its bounding-volume hierarchy. A scene file names a mesh file instead, which its reader
    /// loads into the scene's meshes.
    #[cfg_attr(feature = "serde", serde(skip))]
    Mesh {
        /// The index of the hierarchy's root in [`MeshesDesc::nodes`].
        root: u32,
    },
}

/// Whether a triangle with these corners has an area the tracer can tell from none: its edges'
/// cross product above f32's epsilon times their lengths. The scene build refuses one without
/// (a mesh's reader can leave such triangles out first).
#[must_use]
pub fn triangle_has_area(vertices: [[f32; 3]; 3]) -> bool {
    let [a, b, c] = vertices.map(crate::vec3::Vec3::from_f32);
    let (e1, e2) = (b - a, c - a);
    e1.cross(e2).length() > f64::from(f32::EPSILON) * e1.length() * e2.length()
}

/// A checkerboard on a plane: squares alternate between the material's colour and `colour`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct CheckerDesc {
    /// The second colour.
    pub colour: [f32; 3],
    /// The side of one square, in world units.
    pub size: f32,
}

/// How a surface reflects, after Whitted (1980).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct MaterialDesc {
    /// The surface colour, linear RGB in [0, 1].
    pub colour: [f32; 3],
    /// Lambertian weight.
    pub diffuse: f32,
    /// Phong highlight weight.
    pub specular: f32,
    /// Phong exponent: larger is a smaller, sharper highlight.
    pub shininess: u16,
    /// Mirror reflection weight.
    pub reflection: f32,
    /// Transmission weight (refraction, and how much light a shadow lets through).
    pub transmission: f32,
    /// Index of refraction (≥ 1) for transmitted rays.
    pub ior: f32,
}

/// A matte light grey: what a scene file's material is where it says nothing else.
impl Default for MaterialDesc {
    fn default() -> Self {
        Self::matte([0.8; 3])
    }
}

impl MaterialDesc {
    /// A matte surface of the given colour.
    ///
    /// ```
    /// use obscura::MaterialDesc;
    ///
    /// let chalk = MaterialDesc::matte([0.9, 0.9, 0.85]);
    /// assert_eq!((chalk.specular, chalk.reflection, chalk.transmission), (0.0, 0.0, 0.0));
    /// ```
    #[must_use]
    pub const fn matte(colour: [f32; 3]) -> Self {
        Self {
            colour,
            diffuse: 0.9,
            specular: 0.0,
            shininess: 1,
            reflection: 0.0,
            transmission: 0.0,
            ior: 1.0,
        }
    }
}

/// A light: a point, or a disc that faces every point it lights.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct LightDesc {
    /// Where it is: the point, or the disc's centre.
    pub position: [f32; 3],
    /// Its colour and intensity (linear RGB; 1 is a white light of unit intensity).
    pub colour: [f32; 3],
    /// The disc's radius, ≥ 0: 0 is a point light and casts hard shadows; a disc casts
    /// penumbrae as wide as it looks from the occluder, sampled by
    /// [`SceneDesc::shadow_samples`] rays. It lights a point as its centre does, times the
    /// share of it the point sees.
    #[cfg_attr(feature = "serde", serde(default))]
    pub radius: f32,
}

impl LightDesc {
    /// A point light.
    ///
    /// ```
    /// use obscura::LightDesc;
    ///
    /// let lamp = LightDesc::point([-3.0, 5.0, -4.0], [1.0, 1.0, 1.0]);
    /// assert_eq!(lamp.radius, 0.0); // a point: hard shadows
    /// ```
    #[must_use]
    pub const fn point(position: [f32; 3], colour: [f32; 3]) -> Self {
        Self {
            position,
            colour,
            radius: 0.0,
        }
    }
}

/// What rays that hit nothing see.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum BackgroundDesc {
    /// One colour everywhere.
    Solid([f32; 3]),
    /// A sky: `horizon` for rays level with the ground or below, blending to `zenith` for a
    /// ray straight up, along `up`.
    Gradient {
        /// The colour at and below the horizon.
        horizon: [f32; 3],
        /// The colour straight up.
        zenith: [f32; 3],
        /// The scene's up, where the zenith is (any length but zero): +y, or +z for a scene
        /// modelled Z-up.
        #[cfg_attr(feature = "serde", serde(default = "y_up"))]
        up: [f32; 3],
    },
}

/// The world's +y: a gradient's up unless a scene says otherwise.
pub const Y_UP: [f32; 3] = [0.0, 1.0, 0.0];

#[cfg(feature = "serde")]
fn y_up() -> [f32; 3] {
    Y_UP
}

