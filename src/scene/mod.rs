//! [`Scene`]: a validated scene in one number format, in fixed-capacity storage, and the build
//! that proves a description fits that format before converting it.

crate::phase::declare_phase!(Some(crate::phase::Phase::Build));

pub(crate) mod error;
// The range proof's analysis (its bounds and features): the harness's `analyze`, predictions and
// stress cases read it; a user of the core needs only `Scene::build`, which runs it.
#[doc(hidden)]
pub mod range;
pub(crate) mod validate;

use validate::direction;

pub use error::{Item, Remedy, SceneError};

use crate::camera::{Camera, Frame, MAX_IMAGE_SIDE};
use crate::color::Rgb;
use crate::cull::{self, Bound};
use crate::desc::{
    BackgroundDesc, CheckerDesc, LightDesc, MaterialDesc, ObjectDesc, SceneDesc, ShapeDesc,
    triangle_has_area,
};
use crate::light::{Background, Light};
use crate::material::Material;
use crate::methods::{Methods, RootMethod};
use crate::occlusion::{self, Cone, Side};
use crate::scalar::REACH_ERRORS;
use crate::scalar::{Bits, FormatInfo, FormatSet, Precision, Scalar};
use crate::shape::mesh::{MeshStorage, MeshWords, Meshes, NoMeshes, Node};
use crate::shape::{CHECKER_PERIOD, Checker, Plane, Shape, Sphere, Triangle};
use crate::uses::{Everything, Parts, Uses};
use crate::vec3::Vec3;
use crate::words::{self, ProvenScene, Reader, Words, WordsError, Writer};
use core::marker::PhantomData;
use heapless::Vec;

/// How far a secondary ray starts off its surface by the epsilon method, and how near a hit may
/// be, in rounding errors: the format's resolution near zero (an LSB for fixed point, nothing
/// for a float), plus its resolution at 1 times the surface point's largest coordinate, plus the
/// object's own part ([`Object::tolerance`]).
pub const SURFACE_TOLERANCE_STEPS: f64 = 8.0;

/// A ray whose weight falls below 1/`CUTOFF` on every channel is not traced: it could not move
/// a pixel by half a level of an 8-bit channel.
pub const WEIGHT_CUTOFF: i32 = 512;

/// An object: a shape and its material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Object<S: Scalar> {
    /// The geometry.
    pub shape: Shape<S>,
    /// The surface.
    pub material: Material<S>,
    /// The object's own part of the surface tolerance (see [`SURFACE_TOLERANCE_STEPS`]). For a
    /// sphere of radius r (the range proof's `own_tolerance_terms`), a ray from its surface computes
    /// c = |o − c|² − r² ≈ 0 with the rounding error of r² and finds a root near c/2r: the
    /// error grows as the sphere shrinks (for a fixed format, an LSB over r), besides the
    /// rounding of a point r from the centre. For a triangle
    /// (`triangle_tolerance_terms`), the distance it finds rounds with its corners'
    /// coordinates and its edges against its area. A plane adds nothing.
    pub tolerance: S,
    /// Where primary rays can meet it ([`crate::cull`]).
    pub bound: Bound,
}

crate::words::words_of_struct!(Object<S> {
    shape,
    material,
    tolerance,
    bound
});

/// A scene ready to trace in format `S`, holding up to `OBJECTS` objects and `LIGHTS` lights
/// and tracing ray trees with a stack of `RAYS` rays (at least `max_depth + 1`), by a tracer
/// of the parts `P` ([`Parts`]; [`Everything`] unless given).
///
/// Positions are stored relative to the eye, which keeps the numbers small. Only the storage
/// depends on the capacities: the tracer itself sees slices, so a firmware
/// with several scenes carries one copy of it per number format (and set of parts). A scene
/// whose `P` leaves parts out comes only from words ([`Self::from_words`]) whose scene needs
/// none of them: its tracer, built without them, lacks nothing the scene needs.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene<
    S: Scalar,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts = Everything,
    M = NoMeshes,
> {
    pub(crate) objects: Vec<Object<S>, OBJECTS>,
    /// The meshes' nodes and triangles ([`crate::shape::mesh`]).
    pub(crate) meshes: M,
    pub(crate) lights: Vec<Light<S>, LIGHTS>,
    /// For each light, each object's cone ([`crate::occlusion`]).
    pub(crate) cones: Vec<[Cone<S>; OBJECTS], LIGHTS>,
    pub(crate) settings: Settings<S>,
    frame: Frame,
    parts: PhantomData<fn() -> P>,
}

/// What the tracer needs of a scene besides its objects and lights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Settings<S: Scalar> {
    pub(crate) ambient: Rgb<S>,
    pub(crate) background: Background<S>,
    /// The longest a ray can be: the diameter of the ball rays start in (the world and its
    /// slack), longer than any way from a ray's origin to a surface in the world, so that no
    /// hit at the world's far side is lost to the rounding of its distance.
    pub(crate) ray_length: S,
    /// The surface tolerance at the origin; see [`SURFACE_TOLERANCE_STEPS`].
    pub(crate) tolerance_base: S,
    /// How much it grows per unit of a surface point's largest coordinate (or radius).
    pub(crate) tolerance_per_unit: S,
    /// The widening of a mesh's box test ([`crate::shape::mesh::slack`]).
    pub(crate) box_slack: S,
    /// See [`WEIGHT_CUTOFF`].
    pub(crate) min_weight: S::Narrow,
    pub(crate) max_depth: u8,
    /// Rays per pixel ([`SceneDesc::samples`]).
    pub(crate) samples: u16,
    /// See [`SceneDesc::adaptive_samples`].
    pub(crate) adaptive_samples: bool,
    /// See [`SceneDesc::adaptive_shadows`].
    pub(crate) adaptive_shadows: bool,
    /// The side of adaptive pixels' blocks ([`SceneDesc::pixels`]): 1 for exact pixels.
    pub(crate) pixel_block: u8,
    pub(crate) methods: Methods,
    /// The balls a ray may be inside of (they let light through) with nothing else inside, a
    /// bit each (bit i for object i, below [`crate::cull::SHARED_BIT`]): every other object is
    /// clear of the ball by more than the errors with which a ray finds either, so a ray inside
    /// can meet only its wall, and tests that alone ([`Converter::lone_balls`]).
    pub(crate) lone_balls: u32,
}

crate::words::words_of_struct!(Settings<S> {
    ambient,
    background,
    ray_length,
    tolerance_base,
    tolerance_per_unit,
    box_slack,
    min_weight,
    max_depth,
    samples,
    adaptive_samples,
    adaptive_shadows,
    pixel_block,
    methods,
    lone_balls
});

impl<S: Scalar, const OBJECTS: usize, const LIGHTS: usize, const RAYS: usize, M: MeshStorage<S>>
    Scene<S, OBJECTS, LIGHTS, RAYS, Everything, M>
{
    /// Validates `desc`, proves that format `S` holds it (the range proof) and converts it, to be
    /// traced by the lecture's methods ([`Methods::LECTURE`]).
    ///
    /// # Errors
    /// A [`SceneError`] that names the offending value and says how to fix it.
    ///
    /// ```
    /// use obscura::{I16F16, Scene, SceneError, scenes};
    ///
    /// // 8 objects, 4 lights, a ray stack of 6: room for `whitted`.
    /// assert!(Scene::<I16F16, 8, 4, 6>::build(&scenes::WHITTED).is_ok());
    /// // Too few objects for it: refused, saying so.
    /// let refused = Scene::<I16F16, 2, 4, 6>::build(&scenes::WHITTED);
    /// assert!(matches!(refused, Err(SceneError::TooMany { what: "objects", .. })));
    /// ```
    pub fn build(desc: &SceneDesc<'_>) -> Result<Self, SceneError> {
        Self::build_with(desc, Methods::LECTURE)
    }

    /// [`Self::build`] for other methods.
    ///
    /// # Errors
    /// As [`Self::build`], and [`SceneError::MethodUnavailable`] for a method the format does
    /// not have.
    pub fn build_with(desc: &SceneDesc<'_>, methods: Methods) -> Result<Self, SceneError> {
        Self::build_with_tolerances_of(desc, methods, &FormatInfo::of::<S>())
    }

    /// [`Self::build_with`], with the surface tolerances that
    /// format `tolerances` computes rather than `S`'s: the scene a finer format traces to tell
    /// the offsets of the epsilon method in `tolerances` from its rounding.
    ///
    /// # Errors
    /// As [`Self::build_with`].
    pub fn build_with_tolerances_of(
        desc: &SceneDesc<'_>,
        methods: Methods,
        tolerances: &FormatInfo,
    ) -> Result<Self, SceneError> {
        if methods.roots == RootMethod::Approx && !S::FAST_ROOTS {
            return Err(SceneError::MethodUnavailable {
                method: "sqrt=approx",
                format: S::NAME,
            });
        }
        let frame = validate::validate(desc)?;
        capacity("objects", desc.objects.len(), OBJECTS)?;
        capacity("lights", desc.lights.len(), LIGHTS)?;
        if usize::from(desc.max_depth) + 1 > RAYS {
            return Err(SceneError::DepthExceedsStack {
                max_depth: desc.max_depth,
                capacity: RAYS,
            });
        }
        Converter::<S>::proven(desc, methods, tolerances, frame)?.scene(desc)
    }
}

impl<
    S: Scalar,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S>,
> Scene<S, OBJECTS, LIGHTS, RAYS, P, M>
{
    /// The camera for an image of `width × height` pixels.
    ///
    /// # Errors
    /// [`SceneError::ImageSize`] when a side is 0 or larger than [`MAX_IMAGE_SIDE`]; when the
    /// image plane leaves the format, its pixels are closer than the format can aim rays, or
    /// its lens tilts rays too little to focus in the format, why.
    ///
    /// ```
    /// use obscura::{Scene, SceneError, scenes};
    ///
    /// let scene = Scene::<f32, 8, 4, 6>::build(&scenes::SHAPES)?;
    /// let camera = scene.camera(240, 240)?;
    /// assert_eq!((camera.width(), camera.height()), (240, 240));
    /// assert!(matches!(scene.camera(0, 240), Err(SceneError::ImageSize { .. })));
    /// # Ok::<(), SceneError>(())
    /// ```
    pub fn camera(&self, width: u32, height: u32) -> Result<Camera<S>, SceneError> {
        camera(&self.frame, &self.settings.methods, width, height)
    }

    /// How the frame's pixels are found ([`SceneDesc::pixels`]).
    #[must_use]
    pub const fn pixels(&self) -> crate::Pixels {
        match self.settings.pixel_block {
            0 | 1 => crate::Pixels::Exact,
            block => crate::Pixels::Adaptive(block),
        }
    }

    /// The objects, in the order of the description.
    #[must_use]
    pub fn objects(&self) -> &[Object<S>] {
        &self.objects
    }

    /// The lights, in the order of the description.
    #[must_use]
    pub fn lights(&self) -> &[Light<S>] {
        &self.lights
    }

    /// What of the tracer the scene uses: its kinds of shape, its methods, area lights and
    /// several rays per pixel. Its camera's parts are the camera's ([`Camera::uses`]).
    #[must_use]
    pub fn uses(&self) -> Uses {
        let shapes = self.objects.iter().fold(Uses::NOTHING, |uses, object| {
            uses.union(match object.shape {
                Shape::Sphere(_) => Uses::SPHERES,
                Shape::Plane(_) => Uses::PLANES,
                Shape::Triangle(_) => Uses::TRIANGLES,
                Shape::Mesh(_) => Uses::MESHES,
            })
        });
        let area_lights = self.lights.iter().any(|light| light.shadow_rays > 1);
        let part = |used: bool, part: Uses| if used { part } else { Uses::NOTHING };
        Uses::methods(&self.settings.methods)
            .union(shapes)
            .union(part(area_lights, Uses::AREA_LIGHTS))
            .union(part(self.settings.samples > 1, Uses::SAMPLES))
    }
}

impl<S: Bits, const OBJECTS: usize, const LIGHTS: usize, const RAYS: usize, P: Parts>
    Scene<S, OBJECTS, LIGHTS, RAYS, P, MeshWords<S>>
{
    /// The scene and the camera a build script proved on the host (`obscura_scene::build`),
    /// read back from their words ([`ProvenScene`]): the scene, its meshes read in place, and
    /// the camera. The chip builds and proves nothing.
    ///
    /// # Errors
    /// As [`Self::from_words`], [`MeshWords::from_words`] and [`Camera::from_words`]: when the
    /// words are not a scene's, meshes' and camera's of format `S` within these capacities and
    /// parts.
    pub fn from_proven(proven: &ProvenScene<'_>) -> Result<(Self, Camera<S>), WordsError> {
        // A tracer without meshes reads none: its scene has none to meet.
        let meshes = if P::USES.contains(Uses::MESHES) {
            MeshWords::from_words(proven.meshes)
        } else {
            Ok(MeshWords::default())
        };
        let mut scene = Self::from_words(proven.scene)?;
        scene.set_meshes(meshes?);
        Ok((scene, Camera::from_words(proven.camera)?))
    }
}

impl<
    S: Bits,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S> + Default,
> Scene<S, OBJECTS, LIGHTS, RAYS, P, M>
{
    /// Writes the scene as words to `sink` (as [`ProvenScene`] holds them): what a firmware's build keeps as
    /// constants of a scene it has built, and so proven, on the host. Only the objects and
    /// lights the scene has are written, not its capacities.
    pub fn write_words(&self, sink: &mut dyn FnMut(u32)) {
        words::write::<S>("scene", self, sink);
    }

    /// The scene [`Self::write_words`] wrote in format `S`, in storage of these capacities and
    /// for a tracer of the parts `P`: what a firmware traces without building the scene or
    /// proving its range again.
    ///
    /// # Errors
    /// When `words` are not such a scene's, or it has more objects or lights than the
    /// capacities, a deeper ray tree than the ray stack holds, or uses a part `P` leaves
    /// out ([`Self::uses`]).
    pub fn from_words(words: &[u32]) -> Result<Self, WordsError> {
        words::read::<S, Self>("scene", words)
    }

    /// Writes the scene's meshes as words to `sink`, as [`MeshWords`] reads them: what a
    /// firmware's build keeps in flash beside the scene's words ([`Self::write_words`]), which
    /// do not hold them.
    pub fn write_mesh_words(&self, sink: &mut dyn FnMut(u32)) {
        crate::shape::mesh::write_words::<S>(&self.meshes, sink);
    }

    /// Gives the scene its meshes: a scene read from words ([`Self::from_words`]) with the
    /// meshes written beside it ([`Self::write_mesh_words`], read by
    /// [`MeshWords`]). In place: a firmware's scene is not copied.
    pub fn set_meshes(&mut self, meshes: M) {
        self.meshes = meshes;
    }
}

impl<
    S: Bits,
    const OBJECTS: usize,
    const LIGHTS: usize,
    const RAYS: usize,
    P: Parts,
    M: Meshes<S> + Default,
> Words for Scene<S, OBJECTS, LIGHTS, RAYS, P, M>
{
    fn put(&self, out: &mut Writer<'_>) {
        let count = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        out.word(count(self.objects.len()));
        for object in &self.objects {
            object.put(out);
        }
        out.word(count(self.lights.len()));
        for light in &self.lights {
            light.put(out);
        }
        for cones in &self.cones {
            for cone in cones.iter().take(self.objects.len()) {
                cone.put(out);
            }
        }
        self.settings.put(out);
        self.frame.put(out);
    }

    /// Refuses the parts `P` leaves out where they are read: a kind of shape at its tag
    /// ([`Reader::allow_only`]), a method, an area light or several rays per pixel once read.
    fn take<const IN_PLACE: bool>(input: &mut Reader<'_, IN_PLACE>) -> Self {
        let parts = P::USES;
        input.allow_only(parts);
        let mut objects = Vec::new();
        for _ in 0..input.count(OBJECTS) {
            // Within the capacity: count() says so.
            if objects.push(Object::take(input)).is_err() {
                input.refuse();
            }
        }
        let mut lights = Vec::new();
        for _ in 0..input.count(LIGHTS) {
            if lights.push(Light::take(input)).is_err() {
                input.refuse();
            }
        }
        let mut cones = Vec::new();
        for _ in 0..lights.len() {
            let mut of_light = [Cone::Everywhere; OBJECTS];
            for cone in of_light.iter_mut().take(objects.len()) {
                *cone = Cone::take(input);
            }
            if cones.push(of_light).is_err() {
                input.refuse();
            }
        }
        let settings = Settings::take(input);
        let area_lights = lights.iter().any(|light| light.shadow_rays > 1);
        if usize::from(settings.max_depth) >= RAYS
            || !parts.contains(Uses::methods(&settings.methods))
            || (area_lights && !parts.contains(Uses::AREA_LIGHTS))
            || (settings.samples > 1 && !parts.contains(Uses::SAMPLES))
        {
            input.refuse();
        }
        Self {
            objects,
            meshes: M::default(),
            lights,
            cones,
            settings,
            frame: Frame::take(input),
            parts: PhantomData,
        }
    }
}

/// [`Scene::camera`] of a scene whose camera has `frame`, by `methods`: out of line, one copy per
/// format however many scenes (of different capacities) a firmware draws.
#[inline(never)]
fn camera<S: Scalar>(
    frame: &Frame,
    methods: &Methods,
    width: u32,
    height: u32,
) -> Result<Camera<S>, SceneError> {
    let valid = 1..=MAX_IMAGE_SIDE;
    if !valid.contains(&width) || !valid.contains(&height) {
        return Err(SceneError::ImageSize { width, height });
    }
    let half_width = frame.half_width(width, height);
    let tilt = frame.lens_tilt();
    range::check_camera(
        &FormatInfo::of::<S>(),
        half_width,
        frame.half_height,
        (width, height),
        tilt,
    )?;
    let (corner, _, _) = range::camera(half_width, frame.half_height, width, height, tilt);
    Camera::new(frame, width, height, methods).ok_or(SceneError::OutOfRange {
        item: Item::Camera,
        quantity: corner.quantity,
        value: corner.value,
        format: S::NAME,
        range: S::RANGE,
        remedy: corner.remedy,
        holds: FormatSet::of(|f| range::fits(corner.value, f.range)),
    })
}

/// How many triangles storage `M` holds.
fn meshes_capacity<S, M: MeshStorage<S>>() -> usize {
    M::default().capacity()
}

fn capacity(what: &'static str, count: usize, capacity: usize) -> Result<(), SceneError> {
    if count > capacity {
        Err(SceneError::TooMany {
            what,
            count,
            capacity,
        })
    } else {
        Ok(())
    }
}

/// The shadow rays of one light, as a cone is found for them: the light's centre relative to
/// the eye, its disc's radius, and the longest a shadow ray is.
#[derive(Clone, Copy, Debug)]
struct ShadowRays {
    light: Vec3<f64>,
    disc: f64,
    longest: f64,
}

/// Converts validated `f64` values into format `S`, relative to the eye.
struct Converter<S> {
    eye: Vec3<f64>,
    world: f64,
    /// How far beyond the world a ray can start ([`range::origin_slack`]).
    slack: f64,
    /// The format whose rounding the surface tolerances are sized for: `S`, but for a
    /// reference scene ([`Scene::build_with_tolerances_of`]).
    tolerances: FormatInfo,
    /// The camera's frame and the methods, for the objects' bounds ([`crate::cull`]).
    frame: Frame,
    methods: Methods,
    _format: PhantomData<S>,
}

impl<S: Scalar> Converter<S> {
    /// Proves that format `S` holds `desc` by `methods` (whose camera has `frame`) and readies
    /// its conversion, with the surface tolerances of `tolerances`. Out of line, as
    /// [`Self::object`] is.
    #[inline(never)]
    fn proven(
        desc: &SceneDesc<'_>,
        methods: Methods,
        tolerances: &FormatInfo,
        frame: Frame,
    ) -> Result<Self, SceneError> {
        range::check(&FormatInfo::of::<S>(), desc, &methods)?;
        Ok(Self {
            eye: Vec3::from_f32(desc.camera.eye),
            world: f64::from(desc.far),
            slack: range::origin_slack(desc, &methods, &FormatInfo::of::<S>()),
            tolerances: *tolerances,
            frame,
            methods,
            _format: PhantomData,
        })
    }

    fn scene<const O: usize, const L: usize, const R: usize, M: MeshStorage<S>>(
        &self,
        desc: &SceneDesc<'_>,
    ) -> Result<Scene<S, O, L, R, Everything, M>, SceneError> {
        // `build` checked both lengths against the capacities.
        let too_many = |what, count, capacity| SceneError::TooMany {
            what,
            count,
            capacity,
        };
        let meshes = self.meshes(desc)?;
        let mut objects = Vec::new();
        for (i, object) in desc.objects.iter().enumerate() {
            let object = self.object(Item::Object(i), &object.shape, &object.material, desc)?;
            objects
                .push(object)
                .map_err(|_| too_many("objects", desc.objects.len(), O))?;
        }
        let mut lights = Vec::new();
        let mut cones = Vec::new();
        let tolerance = self.largest_tolerance(&objects);
        for (i, light) in desc.lights.iter().enumerate() {
            lights
                .push(self.light(i, light, desc.shadow_samples)?)
                .map_err(|_| too_many("lights", desc.lights.len(), L))?;
            let mut of_light = [Cone::Everywhere; O];
            for (j, cone) in of_light.iter_mut().take(desc.objects.len()).enumerate() {
                *cone = self.cone(Item::Light(i), light, j, desc, tolerance)?;
            }
            cones
                .push(of_light)
                .map_err(|_| too_many("lights", desc.lights.len(), L))?;
        }
        Ok(Scene {
            objects,
            meshes,
            lights,
            cones,
            settings: self.settings(desc, tolerance)?,
            frame: self.frame,
            parts: PhantomData,
        })
    }

    /// Light `i` of a description whose area lights take `shadow_samples` shadow rays. Out of
    /// line, as [`Self::object`] is.
    #[inline(never)]
    fn light(
        &self,
        i: usize,
        light: &LightDesc,
        shadow_samples: u16,
    ) -> Result<Light<S>, SceneError> {
        let item = Item::Light(i);
        let radius = self.scalar(item, "radius", f64::from(light.radius))?;
        Ok(Light {
            position: self.point(item, "position", light.position)?,
            colour: self.colour(item, "colour", light.colour)?,
            radius,
            // A radius below the format's resolution is a point light's.
            shadow_rays: if radius > S::ZERO { shadow_samples } else { 1 },
            // Fewer lights than the capacity, far fewer than 2¹⁶.
            index: i as u16,
        })
    }

    /// The cone of object `index` of `desc` from `light` ([`crate::occlusion`]): of its ball,
    /// or of a plane's side ([`Self::plane_cone`]), where shadow rays start off surfaces by at
    /// most `tolerance`. Out of line, as [`Self::object`] is.
    #[inline(never)]
    fn cone(
        &self,
        item: Item,
        light: &LightDesc,
        index: usize,
        desc: &SceneDesc<'_>,
        tolerance: f64,
    ) -> Result<Cone<S>, SceneError> {
        let position = Vec3::from_f32(light.position) - self.eye;
        // A shadow ray starts within the world (or its slack beyond it) and ends at the light.
        let longest = self.world + self.slack + position.length();
        let Some(shape) = desc.objects.get(index).map(|object| &object.shape) else {
            return Ok(Cone::Everywhere);
        };
        if let ShapeDesc::Plane { point, normal, .. } = *shape {
            let shadow = ShadowRays {
                light: position,
                disc: f64::from(light.radius),
                longest,
            };
            return Ok(self
                .plane_cone(index, (point, normal), shadow, desc, tolerance)
                .unwrap_or(Cone::Everywhere));
        }
        let ball = self
            .finding_error(shape, desc, longest)
            .zip(cull::ball(shape, &desc.meshes, self.eye))
            .map(|(error, (centre, radius))| (centre, radius + REACH_ERRORS * error));
        Cone::of(ball, position, f64::from(light.radius), longest)
            .ok_or_else(|| self.out_of_range(item, "a shadow cone's axis", position))
    }

    /// [`Cone::NOWHERE`] for plane `index` of `desc`, through `point` with `normal`, where no
    /// shadow ray towards the light can meet it (see [`crate::occlusion`]): the light's disc and
    /// the far end of every shadow ray aimed at it clear the plane by more than the error with
    /// which a ray finds the plane, and so does every point a shadow ray may start from on
    /// every other object, less the error with which a ray finds that object (or, on an opaque
    /// sphere met from outside, a shaded point's own) and the largest surface tolerance
    /// (`tolerance`), by which a shadow ray starts off its surface; and the
    /// light is steep enough over the plane that Lambert's cosine on its far side is negative
    /// whatever its rounding. `None` where that is not so, or cannot be bounded.
    fn plane_cone(
        &self,
        index: usize,
        (point, normal): ([f32; 3], [f32; 3]),
        ShadowRays {
            light: position,
            disc,
            longest,
        }: ShadowRays,
        desc: &SceneDesc<'_>,
        tolerance: f64,
    ) -> Option<Cone<S>> {
        let from_eye = |p| Vec3::from_f32(p) - self.eye;
        let side = Side::towards(from_eye(point), Vec3::from_f32(normal), position)?;
        let plane = &desc.objects.get(index)?.shape;
        let needed = REACH_ERRORS * self.finding_error(plane, desc, longest)?;
        let cosine_error = occlusion::cosine_error::<S>();
        let light_height = side.height(position) - disc;
        if light_height - occlusion::end_error::<S>(disc, longest) <= needed
            || light_height <= cosine_error * longest
        {
            return None;
        }
        // Where a secondary ray can start: within the world, or its slack beyond it.
        let anywhere = self.world + self.slack;
        for (i, object) in desc.objects.iter().enumerate() {
            if i == index {
                continue;
            }
            let found = |shape| Some(REACH_ERRORS * self.finding_error(shape, desc, anywhere)?);
            let lowest = match object.shape {
                ShapeDesc::Plane { point, normal, .. } => {
                    side.height_of_plane(from_eye(point), Vec3::from_f32(normal))?
                        - found(&object.shape)?
                }
                ShapeDesc::Sphere { center, radius }
                    if disc == 0.0 && self.met_from_outside(i, desc, tolerance) =>
                {
                    let (centre, radius) = (from_eye(center), f64::from(radius));
                    // A shaded point of a sphere is c + r·n for its computed unit normal n
                    // (`Sphere::surface`): off the surface by n's error times r and the
                    // rounding of the product and sum, whatever the error of the ray's t.
                    let off = REACH_ERRORS
                        * 3.0_f64.sqrt()
                        * (radius * occlusion::unit_error::<S>() + 2.0 * S::resolution(centre.length() + radius));
                    side.lowest_of_lit_cap((centre, radius), off, position, cosine_error)
                }
                _ => {
                    let (centre, radius) = cull::ball(&object.shape, &desc.meshes, self.eye)?;
                    side.lowest_of_ball(centre, radius) - found(&object.shape)?
                }
            };
            if lowest - tolerance <= needed {
                return None;
            }
        }
        Some(Cone::NOWHERE)
    }

    /// Whether every ray that meets sphere `index` of `desc` meets it from outside, so that
    /// its inside starts no shadow ray: it is opaque, the eye (and the lens about it) is
    /// outside it, and no object that sends rays on (by reflection or transmission) comes
    /// within `margin` of it, where a ray it sends could start inside.
    fn met_from_outside(&self, index: usize, desc: &SceneDesc<'_>, margin: f64) -> bool {
        let Some(&ObjectDesc {
            shape: ShapeDesc::Sphere { center, radius },
            material,
        }) = desc.objects.get(index)
        else {
            return false;
        };
        let (centre, radius) = (Vec3::from_f32(center) - self.eye, f64::from(radius));
        let apart = |distance: f64| distance > radius + margin;
        material.transmission == 0.0
            && apart(centre.length() - f64::from(desc.camera.aperture))
            && desc.objects.iter().enumerate().all(|(i, other)| {
                let sends = other.material.reflection > 0.0 || other.material.transmission > 0.0;
                if i == index || !sends {
                    return true;
                }
                // A NaN gap (a plane without a normal) is not apart.
                self.gap((centre, radius), &other.shape, desc)
                    .is_some_and(|gap| gap > margin)
            })
    }

    /// How far `shape` of `desc` lies outside the ball about `centre` (from the eye) of
    /// `radius`: a plane's distance from the centre, or the distance between the centres less
    /// the radius of the shape's ball ([`cull::ball`]), less `radius`. Negative where they
    /// meet; NaN for a plane without a normal; `None` for a shape without a ball.
    fn gap(
        &self,
        (centre, radius): (Vec3<f64>, f64),
        shape: &ShapeDesc,
        desc: &SceneDesc<'_>,
    ) -> Option<f64> {
        match *shape {
            ShapeDesc::Plane { point, normal, .. } => {
                let normal = Vec3::from_f32(normal);
                let offset = centre - (Vec3::from_f32(point) - self.eye);
                Some(normal.dot(offset).abs() / normal.length() - radius)
            }
            _ => cull::ball(shape, &desc.meshes, self.eye)
                .map(|(c, r)| (c - centre).length() - r - radius),
        }
    }

    /// The largest surface tolerance anywhere a shadow ray may start: the tolerance at the
    /// farthest a surface point can be from the eye, and the largest of `objects`' own parts.
    fn largest_tolerance(&self, objects: &[Object<S>]) -> f64 {
        let (base, per_unit) = self.tolerances();
        let own = objects
            .iter()
            .map(|object| object.tolerance.to_f64())
            .fold(0.0, f64::max);
        base + per_unit * (self.world + self.slack) + own
    }

    /// The surface tolerance at the eye, and its growth per unit of a coordinate.
    fn tolerances(&self) -> (f64, f64) {
        let at = |reach| range::error_with(&range::tolerance_terms(reach, None), &self.tolerances);
        (at(0.0), at(1.0) - at(0.0))
    }

    /// What the tracer needs of `desc` besides its objects and lights, where secondary rays
    /// start off surfaces by at most `tolerance`. Out of line, as [`Self::object`] is.
    #[inline(never)]
    fn settings(&self, desc: &SceneDesc<'_>, tolerance: f64) -> Result<Settings<S>, SceneError> {
        let background = match desc.background {
            BackgroundDesc::Solid(c) => {
                Background::Solid(self.colour(Item::Scene, "background.solid", c)?)
            }
            BackgroundDesc::Gradient {
                horizon,
                zenith,
                up,
            } => Background::Gradient {
                horizon: self.colour(Item::Scene, "background.gradient.horizon", horizon)?,
                rise: self.colour_f64(
                    Item::Scene,
                    "background.gradient.zenith − horizon",
                    Vec3::from_f32(zenith) - Vec3::from_f32(horizon),
                )?,
                up: self.vector(
                    Item::Scene,
                    "background.gradient.up",
                    direction(Item::Scene, "background.gradient.up", Vec3::from_f32(up))?,
                )?,
            },
        };
        let (tolerance_base, tolerance_per_unit) = self.tolerances();
        Ok(Settings {
            ambient: self.colour(Item::Scene, "ambient", desc.ambient)?,
            background,
            ray_length: self.scalar(
                Item::Scene,
                "a ray's length",
                range::ray_length(self.world, self.slack),
            )?,
            tolerance_base: self.scalar(Item::Scene, "the surface tolerance", tolerance_base)?,
            tolerance_per_unit: self.scalar(
                Item::Scene,
                "the surface tolerance",
                tolerance_per_unit,
            )?,
            box_slack: self.scalar(
                Item::Scene,
                "the widening of a mesh's box test",
                crate::shape::mesh::slack(
                    |magnitude| S::resolution(magnitude),
                    range::box_magnitude(self.world, self.slack),
                ),
            )?,
            // 2⁻⁹ in 16-bit fractions: exact in every narrow format.
            min_weight: S::Narrow::from_q16((1 << 16) / WEIGHT_CUTOFF),
            max_depth: desc.max_depth,
            samples: desc.samples,
            adaptive_samples: desc.adaptive_samples,
            adaptive_shadows: desc.adaptive_shadows,
            pixel_block: desc.pixels.block(),
            methods: self.methods,
            lone_balls: self.lone_balls(desc, tolerance),
        })
    }

    /// [`Settings::lone_balls`] of `desc`: its spheres that let light through, of the first
    /// [`crate::cull::SHARED_BIT`] objects, that every other object clears by more than
    /// [`REACH_ERRORS`] times the errors with which a ray from anywhere in the world finds
    /// either, and `tolerance`, the farthest a secondary ray starts off its surface. A ray
    /// inside such a ball meets its wall before anything else; if it misses the wall (it
    /// started, within the rounding, already out), the tracer searches everything.
    fn lone_balls(&self, desc: &SceneDesc<'_>, tolerance: f64) -> u32 {
        let anywhere = self.world + self.slack;
        let found = |shape: &ShapeDesc| Some(REACH_ERRORS * self.finding_error(shape, desc, anywhere)?);
        let lone = |i: usize, object: &ObjectDesc| {
            let ShapeDesc::Sphere { center, radius } = object.shape else {
                return Some(false);
            };
            if object.material.transmission == 0.0 {
                return Some(false);
            }
            let (centre, radius) = (Vec3::from_f32(center) - self.eye, f64::from(radius));
            let own = found(&object.shape)?;
            for (j, other) in desc.objects.iter().enumerate() {
                if j == i {
                    continue;
                }
                let gap = self.gap((centre, radius), &other.shape, desc)?;
                // A NaN gap (a plane without a normal) is not clear.
                let clear = gap > own + found(&other.shape)? + tolerance;
                if !clear {
                    return Some(false);
                }
            }
            Some(true)
        };
        (0..)
            .zip(desc.objects.iter().take(cull::SHARED_BIT))
            .filter(|&(i, object)| lone(i, object) == Some(true))
            .fold(0, |balls, (i, _)| balls | 1 << i)
    }

    /// Object `item` of `desc`. Out of line, so that a firmware holds one copy per format
    /// however many scenes (of different capacities) it builds.
    #[inline(never)]
    fn object(
        &self,
        item: Item,
        shape_desc: &ShapeDesc,
        m: &MaterialDesc,
        desc: &SceneDesc<'_>,
    ) -> Result<Object<S>, SceneError> {
        let mut tolerance = 0.0;
        let shape = match *shape_desc {
            ShapeDesc::Sphere { center, radius } => {
                let r = f64::from(radius);
                tolerance = range::error_with(&range::own_tolerance_terms(r), &self.tolerances);
                Shape::Sphere(Sphere::new(
                    self.point(item, "shape.sphere.center", center)?,
                    self.scalar(item, "shape.sphere.radius", r)?,
                ))
            }
            ShapeDesc::Plane {
                point,
                normal,
                checker,
            } => {
                let n = direction(item, "shape.plane.normal", Vec3::from_f32(normal))?;
                // The eye's foot on the plane, and the radius of the disc the world cuts from
                // it (validation keeps the plane within the world).
                let to_eye = self.eye - Vec3::from_f32(point);
                let height = n.dot(to_eye);
                let foot = self.eye - n * height;
                let rim = range::visible_rim(self.world, height);
                let checker = match checker {
                    Some(checker) => {
                        Some(self.checker(item, Vec3::from_f32(point), n, &checker)?)
                    }
                    None => None,
                };
                Shape::Plane(Plane::new(
                    self.point(item, "shape.plane.point", point)?,
                    self.vector(item, "shape.plane.normal", n)?,
                    self.vector(item, "the eye's foot on the plane", foot - self.eye)?,
                    self.scalar(item, "the plane's visible disc", rim)?,
                    checker,
                ))
            }
            ShapeDesc::Triangle { vertices } => {
                let (triangle, own) = self.triangle(item, vertices)?;
                tolerance = own;
                Shape::Triangle(triangle)
            }
            ShapeDesc::Mesh { root } => {
                // Every triangle's own tolerance at its largest.
                tolerance = desc
                    .meshes
                    .triangles_of(root)
                    .iter()
                    .map(|&corners| {
                        range::error_with(
                            &range::triangle_tolerance_terms(
                                desc.meshes.corners(corners),
                                self.eye,
                            ),
                            &self.tolerances,
                        )
                    })
                    .fold(0.0, f64::max);
                Shape::Mesh(root)
            }
        };
        // Only a transmissive surface refracts: another's index of refraction is never read.
        let ior = if m.transmission > 0.0 {
            f64::from(m.ior)
        } else {
            1.0
        };
        let material = Material {
            colour: self.narrow_colour(item, "material.colour", m.colour)?,
            diffuse: self.narrow(item, "material.diffuse", m.diffuse)?,
            specular: self.narrow(item, "material.specular", m.specular)?,
            shininess: m.shininess,
            reflection: self.narrow(item, "material.reflection", m.reflection)?,
            transmission: self.narrow(item, "material.transmission", m.transmission)?,
            ior: self
                .scalar(item, "material.ior", ior)
                .map_err(|error| with_remedy(error, Remedy::LowerIor))?,
            inv_ior: self.scalar(item, "1 / ior", 1.0 / ior)?,
        };
        Ok(Object {
            shape,
            material,
            tolerance: self.scalar(item, "the surface tolerance", tolerance)?,
            // A primary ray may be judged to meet the object this far beyond it (if bounded).
            bound: self
                .finding_error(shape_desc, desc, 0.0)
                .map_or(Bound::Everywhere, |error| {
                    Bound::of(shape_desc, &desc.meshes, self.eye, error, &self.frame)
                }),
        })
    }

    /// [`range::finding_error`] of a shape of `desc`; of a mesh, its triangles' largest.
    fn finding_error(&self, shape: &ShapeDesc, desc: &SceneDesc<'_>, beyond: f64) -> Option<f64> {
        let eye = desc.camera.eye;
        match *shape {
            ShapeDesc::Mesh { root } => {
                desc.meshes
                    .triangles_of(root)
                    .iter()
                    .try_fold(0.0, |largest: f64, &corners| {
                        let vertices = desc.meshes.corners(corners);
                        let triangle = ShapeDesc::Triangle { vertices };
                        range::finding_error::<S>(&triangle, &self.methods, eye, beyond)
                            .map(|error| largest.max(error))
                    })
            }
            _ => range::finding_error::<S>(shape, &self.methods, eye, beyond),
        }
    }

    /// A triangle with these corners, and its own part of the surface tolerance
    /// ([`Object::tolerance`]).
    fn triangle(
        &self,
        item: Item,
        [a, b, c]: [[f32; 3]; 3],
    ) -> Result<(Triangle<S>, f64), SceneError> {
        let (a64, b64, c64) = (Vec3::from_f32(a), Vec3::from_f32(b), Vec3::from_f32(c));
        // Degenerate relative to its own size, as validation tests it, never to the unit.
        if !triangle_has_area([a, b, c]) {
            return Err(SceneError::DegenerateTriangle { item });
        }
        let cross = (b64 - a64).cross(c64 - a64);
        let n = cross * cross.length().recip();
        let corners = [
            self.point(item, "shape.triangle.vertices", a)?,
            self.point(item, "shape.triangle.vertices", b)?,
            self.point(item, "shape.triangle.vertices", c)?,
        ];
        // Möller–Trumbore's smallest determinant: below it 1/det, or a numerator over
        // it, would leave the format.
        let origin = self.world + self.slack;
        let multiples = range::reciprocal_multiples(origin, self.eye, [a64, b64, c64]);
        let min_det = multiples * range::RANGE_HEADROOM / S::RANGE;
        let tolerance = range::error_with(
            &range::triangle_tolerance_terms([a, b, c], self.eye),
            &self.tolerances,
        );
        let triangle = Triangle::new(
            corners,
            self.vector(item, "triangle normal", n)?,
            self.scalar(item, "the smallest determinant", min_det)?,
        );
        Ok((triangle, tolerance))
    }

    /// The meshes of `desc` in storage `M`: every triangle and node, in their order. An error
    /// names the first mesh object whose triangles hold the one at fault. Out of line, as
    /// [`Self::object`] is.
    #[inline(never)]
    fn meshes<M: MeshStorage<S>>(&self, desc: &SceneDesc<'_>) -> Result<M, SceneError> {
        let mut meshes = M::default();
        let pool = &desc.meshes;
        if !pool.triangles.is_empty() && meshes.capacity() == 0 {
            return Err(SceneError::MeshesNotHeld);
        }
        let full = || SceneError::TooMany {
            what: "mesh triangles",
            count: pool.triangles.len(),
            capacity: meshes_capacity::<S, M>(),
        };
        let item = |triangle: usize| {
            let object = desc.objects.iter().position(|object| match object.shape {
                ShapeDesc::Mesh { root } => pool.nodes.get(root as usize).is_some_and(|node| {
                    (node.first as usize..node.end as usize).contains(&triangle)
                }),
                _ => false,
            });
            object.map_or(Item::Scene, Item::Object)
        };
        for (i, &corners) in pool.triangles.iter().enumerate() {
            let (triangle, _) = self.triangle(item(i), pool.corners(corners))?;
            if !meshes.push_triangle(triangle) {
                return Err(full());
            }
        }
        if !pool.normals.is_empty() {
            for (i, &corners) in pool.triangles.iter().enumerate() {
                let normals = match pool.corner_normals(corners) {
                    Some(normals) => {
                        let normal = |n| self.vector(item(i), "a vertex normal", Vec3::from_f32(n));
                        let [a, b, c] = normals;
                        [normal(a)?, normal(b)?, normal(c)?]
                    }
                    None => [Vec3::ZERO; 3],
                };
                if !meshes.push_normals(normals) {
                    return Err(full());
                }
            }
        }
        for node in pool.nodes {
            let (low, high) = (Vec3::from_f32(node.min), Vec3::from_f32(node.max));
            let item = item(node.first as usize);
            let node = Node {
                centre: self.vector(item, "a mesh's box", (low + high) * 0.5 - self.eye)?,
                half: self.vector(item, "a mesh's box", (high - low) * 0.5)?,
                first: node.first,
                end: node.end,
                right: node.right,
                axis: u32::from(node.axis),
            };
            if !meshes.push_node(node) {
                return Err(full());
            }
        }
        Ok(meshes)
    }

    /// The checkerboard's axes: the world axis least aligned with the normal, made
    /// perpendicular to it (so a floor's squares follow x and z), and normal × that.
    fn checker(
        &self,
        item: Item,
        point: Vec3<f64>,
        n: Vec3<f64>,
        desc: &CheckerDesc,
    ) -> Result<Checker<S>, SceneError> {
        let (x, y, z) = (n.x.abs(), n.y.abs(), n.z.abs());
        let least = if x <= y && x <= z {
            Vec3::new(1.0, 0.0, 0.0)
        } else if y <= z {
            Vec3::new(0.0, 1.0, 0.0)
        } else {
            Vec3::new(0.0, 0.0, 1.0)
        };
        let u = direction(item, "shape.plane.normal", least - n * n.dot(least))?;
        let v = n.cross(u);
        let size = f64::from(desc.size);
        // The place of the eye's foot on the plane (where the pattern is measured from, so
        // that the coordinates it multiplies are of points within the world, however large the
        // squares) on the grid of squares aligned to the plane's point, counted in squares.
        // The place is kept modulo two squares, not one: a square's colour is the parity of
        // its two coordinates, and the parity of the foot's own square must stay, or an eye
        // moved across a square's edge would swap every colour of the board.
        let to_eye = self.eye - point;
        let place = |axis: Vec3<f64>| {
            let squares = to_eye.dot(axis) / size;
            squares - CHECKER_PERIOD * libm::floor(squares / CHECKER_PERIOD)
        };
        Ok(Checker {
            colour: self.narrow_colour(item, "shape.plane.checker.colour", desc.colour)?,
            u: self.vector(item, "checker axis", u * size.recip())?,
            v: self.vector(item, "checker axis", v * size.recip())?,
            start: [
                self.scalar(item, "the eye's place on the checker", place(u))?,
                self.scalar(item, "the eye's place on the checker", place(v))?,
            ],
        })
    }

    fn point(
        &self,
        item: Item,
        quantity: &'static str,
        p: [f32; 3],
    ) -> Result<Vec3<S>, SceneError> {
        self.vector(item, quantity, Vec3::from_f32(p) - self.eye)
    }

    fn vector(
        &self,
        item: Item,
        quantity: &'static str,
        v: Vec3<f64>,
    ) -> Result<Vec3<S>, SceneError> {
        v.convert()
            .ok_or_else(|| self.out_of_range(item, quantity, v))
    }

    fn colour(
        &self,
        item: Item,
        quantity: &'static str,
        c: [f32; 3],
    ) -> Result<Rgb<S>, SceneError> {
        self.colour_f64(item, quantity, Vec3::from_f32(c))
    }

    fn colour_f64(
        &self,
        item: Item,
        quantity: &'static str,
        c: Vec3<f64>,
    ) -> Result<Rgb<S>, SceneError> {
        Rgb::from_f64(c.to_f64())
            .ok_or_else(|| with_remedy(self.out_of_range(item, quantity, c), Remedy::LessLight))
    }

    /// A surface's colour in the narrow format ([`Scalar::Narrow`]).
    fn narrow_colour(
        &self,
        item: Item,
        quantity: &'static str,
        c: [f32; 3],
    ) -> Result<Rgb<S::Narrow>, SceneError> {
        let [r, g, b] = c.map(|channel| self.narrow(item, quantity, channel));
        Ok(Rgb::new(r?, g?, b?))
    }

    /// A surface's colour channel or weight in the narrow format, which holds it: validation
    /// keeps each within [0, 1].
    fn narrow(&self, item: Item, quantity: &'static str, x: f32) -> Result<S::Narrow, SceneError> {
        let x = f64::from(x);
        S::Narrow::from_f64(x).ok_or(SceneError::OutOfRange {
            item,
            quantity,
            value: x.abs(),
            format: S::Narrow::NAME,
            range: S::Narrow::RANGE,
            remedy: Remedy::LessLight,
            holds: FormatSet::of(|format| range::fits(x.abs(), format.range)),
        })
    }

    fn scalar(&self, item: Item, quantity: &'static str, x: f64) -> Result<S, SceneError> {
        S::from_f64(x).ok_or_else(|| self.out_of_range(item, quantity, Vec3::new(x, x, x)))
    }

    /// A value that does not fit: the range proof has ruled out all but positions too far
    /// for the format, which a smaller world brings in.
    fn out_of_range(&self, item: Item, quantity: &'static str, v: Vec3<f64>) -> SceneError {
        let value = v.max_abs();
        SceneError::OutOfRange {
            item,
            quantity,
            value,
            format: S::NAME,
            range: S::RANGE,
            remedy: Remedy::ShrinkWorld,
            holds: FormatSet::of(|format| range::fits(value, format.range)),
        }
    }
}

/// `error` with another remedy, where it is an [`SceneError::OutOfRange`].
fn with_remedy(error: SceneError, remedy: Remedy) -> SceneError {
    match error {
        SceneError::OutOfRange {
            item,
            quantity,
            value,
            format,
            range,
            holds,
            ..
        } => SceneError::OutOfRange {
            item,
            quantity,
            value,
            format,
            range,
            remedy,
            holds,
        },
        other => other,
    }
}
