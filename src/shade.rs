//! Whitted's illumination (1980): the colour a primary ray brings back, from local shading
//! (ambient, Lambert diffuse, Phong specular, each light tested by a shadow ray), mirror
//! reflection and refraction by Snell's law; and Cook, Porter and Carpenter's soft shadows
//! (1984): an area light tested by several shadow rays spread over it. The ray tree is walked
//! with an explicit stack of fixed capacity, never by recursion.

crate::phase::declare_phase!(Some(crate::phase::Phase::Shading));

use crate::camera::Row;
use crate::color::Rgb;
use crate::light::Light;
use crate::material::Material;
use crate::methods::{BiasMethod, Methods, RootMethod};
use crate::occlusion::Cone;
use crate::pattern::{Pattern, SHADOW_PROBES, SampleId};
use crate::ray::{Ray, Span};
use crate::row_pass::PlaneRow;
use crate::scalar::{RayKind, Scalar, Work, shl_u64};
use crate::scene::{Object, Scene, Settings};
use crate::shape::mesh::{Meshes, Search};
use crate::shape::{Intersection, PerRay, Shape};
use crate::uses::{Parts, Uses};
use crate::vec3::Vec3;
use core::marker::PhantomData;
use heapless::{Vec, VecView};

/// What a primary ray brings back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<S> {
    /// The linear colour.
    pub colour: Rgb<S>,
    /// The index of the object the primary ray hit first, if any: comparing it between formats
    /// separates geometric error from shading error.
    pub object: Option<usize>,
    /// The objects any ray of the tree met, a bit each (objects 64 and beyond share bit 63):
    /// those hit by the primary and secondary rays, and those that cast a shadow on them.
    /// What an object's error can change in this pixel is limited to these.
    pub met: u64,
}

/// A ray waiting on the stack, with the share of the pixel it contributes (at most 1 on each
/// channel: a narrow colour).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Task<S: Scalar> {
    ray: Ray<S>,
    weight: Rgb<S::Narrow>,
    depth: u8,
    /// The surface the ray leaves (none for a primary ray).
    from: Option<Leaving<S>>,
}

/// The surface a secondary ray leaves: the object, whether the ray goes into it (a solid
/// entered, or crossed from inside), and how far off the surface the epsilon method starts it.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Leaving<S> {
    object: usize,
    /// Which of a mesh's triangles (0 on other shapes).
    part: u32,
    into: bool,
    tolerance: S,
}

/// The nearest hit of a ray.
#[derive(Clone, Copy, Debug)]
struct Hit<'a, S: Scalar> {
    object: &'a Object<S>,
    index: usize,
    at: Intersection<S>,
}

/// A point being shaded: where its shadow rays start, the side they leave and its normals.
#[derive(Clone, Copy, Debug)]
struct Shaded<S: Scalar> {
    /// The point, moved off the surface to the side the ray arrived on by the bias method.
    above: Vec3<S>,
    /// The surface's normal on that side.
    facing: Vec3<S>,
    /// The normal that shades it, in the narrow format (a smooth mesh's own).
    shading: Vec3<S::Narrow>,
    /// The mirror direction about `shading`, read only where the material has a highlight.
    shading_mirror: Vec3<S::Narrow>,
    /// The surface the shadow rays leave.
    from: Leaving<S>,
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
    /// Bytes of RAM the scene and the ray stack of one trace take: what the capacities cost.
    #[must_use]
    pub const fn storage_bytes() -> usize {
        size_of::<Self>() + size_of::<Vec<Task<S>, RAYS>>()
    }

    /// Traces a primary ray through the whole ray tree; `id` says which ray of the image it
    /// is, which chooses where its shadow rays meet area lights.
    ///
    /// ```
    /// use obscura::pattern::SampleId;
    /// use obscura::{Scene, scenes};
    ///
    /// let scene = Scene::<f64, 8, 4, 6>::build(&scenes::WHITTED)?;
    /// let camera = scene.camera(64, 64)?;
    /// // The middle of the top row: sky, no object met.
    /// let ray = camera.row(0).and_then(|row| row.rays().nth(32)).expect("a ray");
    /// let sample = scene.trace(ray, SampleId { x: 32, y: 0, sample: 0 });
    /// assert_eq!(sample.met, 0);
    /// assert!(sample.colour.to_f64()[2] > 0.5, "blue");
    /// # Ok::<(), obscura::SceneError>(())
    /// ```
    #[must_use]
    pub fn trace(&self, primary: Ray<S>, id: SampleId) -> Sample<S> {
        let mut stack: Vec<Task<S>, RAYS> = Vec::new();
        self.tracer(id)
            .trace(primary, u32::MAX, stack.as_mut_view())
    }

    /// The index of the first object `ray` hits, if any, and on a mesh the index of its
    /// triangle (0 on other shapes): what a primary ray sees, without shading it.
    ///
    /// ```
    /// use obscura::{Scene, scenes};
    ///
    /// let scene = Scene::<f32, 8, 4, 6>::build(&scenes::WHITTED)?;
    /// let camera = scene.camera(64, 64)?;
    /// // The bottom row sees the checkerboard, object 0.
    /// let ray = camera.row(63).and_then(|row| row.rays().nth(32)).expect("a ray");
    /// assert_eq!(scene.first_hit(&ray), Some((0, 0)));
    /// # Ok::<(), obscura::SceneError>(())
    /// ```
    #[must_use]
    pub fn first_hit(&self, ray: &Ray<S>) -> Option<(usize, u32)> {
        self.tracer(SampleId::default())
            .nearest(ray, None, || true)
            .map(|hit| (hit.index, hit.at.part))
    }

    /// The scene as the tracer sees it, over slices: what the renderer's pixel loop takes, so
    /// that a firmware holds one copy of it per format however many scenes it draws.
    pub(crate) fn tracer(&self, id: SampleId) -> Tracer<'_, S, M, P> {
        Tracer {
            objects: &self.objects,
            meshes: &self.meshes,
            lights: &self.lights,
            cones: self.cones.as_flattened(),
            objects_capacity: OBJECTS,
            lone_balls: self.settings.lone_balls,
            settings: &self.settings,
            id,
            parts: PhantomData,
        }
    }
}

/// The tracer proper, over slices: one copy per number format and set of parts ([`Uses`]),
/// whatever the capacities.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tracer<'a, S: Scalar, M, P: Parts> {
    objects: &'a [Object<S>],
    /// The meshes' nodes and triangles.
    meshes: &'a M,
    lights: &'a [Light<S>],
    /// Each light's cones ([`crate::occlusion`]), one per object: a run of
    /// `objects_capacity` for each light.
    cones: &'a [Cone<S>],
    objects_capacity: usize,
    /// [`Settings::lone_balls`] (none: rays inside a ball test every object).
    lone_balls: u32,
    settings: &'a Settings<S>,
    /// Which ray of the image is traced.
    id: SampleId,
    parts: PhantomData<fn() -> P>,
}

impl<'a, S: Scalar, M: Meshes<S>, P: Parts> Tracer<'a, S, M, P> {
    /// The parts the tracer has.
    pub(crate) const USES: Uses = P::USES;

    /// Whether the tracer has `part`: a constant, which leaves what it guards out of a build
    /// whose scenes do not use it.
    #[inline(always)]
    const fn has(part: Uses) -> bool {
        Self::USES.contains(part)
    }

    /// The scene's methods, as a constant wherever the tracer has only one of a kind.
    #[inline(always)]
    pub(crate) fn methods(&self) -> Methods {
        Self::USES.narrow(&self.settings.methods)
    }

    /// The objects.
    pub(crate) const fn objects(&self) -> &[Object<S>] {
        self.objects
    }

    /// This tracer with shadow rays that test every object, whatever their cones, and rays
    /// inside a lone ball too: what the cones and the lone balls are checked against
    /// ([`crate::skips::first_skipped_secondary`]).
    pub(crate) fn testing_everything(self) -> Self {
        Self {
            cones: &[],
            lone_balls: 0,
            ..self
        }
    }

    /// The cones of the objects from `light` (none: every object is tested).
    fn cones_of(&self, light: &Light<S>) -> &[Cone<S>] {
        let start = usize::from(light.index) * self.objects_capacity;
        self.cones.get(start..).unwrap_or(&[])
    }

    /// Rays per pixel: 1 for a tracer without several ([`Uses::SAMPLES`]).
    #[inline(always)]
    pub(crate) const fn samples(&self) -> u16 {
        if Self::has(Uses::SAMPLES) {
            self.settings.samples
        } else {
            1
        }
    }

    /// [`Scene::trace`] of ray `id` of the image, its primary ray testing only the objects in
    /// `candidates` (those it can meet, [`crate::cull::Candidates`]: bit i for object i, objects
    /// 31 and beyond sharing bit 31), on `stack` (empty, and at least `max_depth + 1` deep).
    ///
    /// Sets the tracer's ray in place: a pixel loop's one tracer, where a copy a pixel cost
    /// the M4F more than a quantised colour.
    pub(crate) fn trace_ray(
        &mut self,
        primary: Ray<S>,
        id: SampleId,
        candidates: u32,
        stack: &mut VecView<Task<S>>,
    ) -> Sample<S> {
        self.id = id;
        self.trace(primary, candidates, stack)
    }

    /// Traces a primary ray, which tests the objects in `candidates`, through the whole ray
    /// tree, on `stack` (empty, and at least `max_depth + 1` deep).
    ///
    /// Out of line, so that a firmware holds one copy per format however many scenes (of
    /// different capacities) it draws.
    #[inline(never)]
    fn trace(&self, primary: Ray<S>, candidates: u32, stack: &mut VecView<Task<S>>) -> Sample<S> {
        let mut task = Task {
            ray: primary,
            weight: Rgb::WHITE,
            depth: 0,
            from: None,
        };
        let mut candidates = candidates;
        let mut sample = Sample {
            colour: Rgb::BLACK,
            object: None,
            met: 0,
        };
        loop {
            // Object i's bit is bit i of what is left of the mask shifted right i times: an
            // arithmetic shift, which keeps bit 31 for the objects beyond 30 that share it.
            let mut rest = candidates;
            let hit = self.nearest(&task.ray, task.from, || {
                let wanted = rest & 1 != 0;
                let shifted = i32::from_ne_bytes(rest.to_ne_bytes()) >> 1;
                rest = u32::from_ne_bytes(shifted.to_ne_bytes());
                wanted
            });
            if task.from.is_some() && hit.is_none() && candidates != u32::MAX {
                // A ray inside a lone ball that misses its wall (it started, within the
                // rounding, already out) searches everything.
                candidates = u32::MAX;
                continue;
            }
            if task.from.is_none() {
                sample.object = hit.as_ref().map(|hit| hit.index);
            }
            self.add(&task, hit, stack, &mut sample);
            let Some(next) = stack.pop() else {
                return sample;
            };
            task = next;
            candidates = self.secondary_candidates(task.from);
        }
    }

    /// The objects a secondary ray leaving `from` tests: a ray inside a lone ball
    /// ([`Settings::lone_balls`]) its wall alone, every other ray every object.
    #[inline(always)]
    fn secondary_candidates(&self, from: Option<Leaving<S>>) -> u32 {
        let ball = from
            .filter(|leaving| leaving.into)
            .and_then(|leaving| u32::try_from(leaving.object).ok())
            .and_then(|object| 1_u32.checked_shl(object))
            .unwrap_or(0);
        if self.lone_balls & ball != 0 {
            ball
        } else {
            u32::MAX
        }
    }

    /// Adds what `task`'s ray brings back, having met `hit`, to `sample`, pushing the rays its
    /// hit spawns.
    #[inline(always)]
    fn add(
        &self,
        task: &Task<S>,
        hit: Option<Hit<'_, S>>,
        stack: &mut VecView<Task<S>>,
        sample: &mut Sample<S>,
    ) {
        let colour = match hit {
            None => self.background(task.ray.dir),
            Some(hit) => {
                sample.met |= bit(hit.index);
                self.shade(task, &hit, stack, &mut sample.met)
            }
        };
        sample.colour = sample.colour + colour.filter(task.weight);
    }

    /// What a ray along the unit direction `dir` that meets nothing sees.
    #[inline(always)]
    pub(crate) fn background(&self, dir: Vec3<S>) -> Rgb<S> {
        self.settings.background.colour(dir)
    }

    /// The span a ray leaving `from` searches: beyond the surface's tolerance for the epsilon
    /// method, beyond zero when the surface left is handled by exclusion.
    fn span(&self, from: Option<Leaving<S>>, max: S) -> Span<S> {
        let min = match (self.methods().bias, from) {
            (BiasMethod::Exclude, Some(_)) => S::ZERO,
            (BiasMethod::Epsilon, Some(leaving)) => leaving.tolerance,
            (_, None) => self.settings.tolerance_base,
        };
        Span { min, max }
    }

    /// The row pass of `row` ([`PlaneRow`]), or `None` where it has none (in a tracer without
    /// planes, none at all).
    #[inline(always)]
    pub(crate) fn plane_row(&self, row: &Row<S>) -> Option<PlaneRow<'a, S>> {
        if !Self::has(Uses::PLANES) {
            return None;
        }
        let span = self.span(None, self.settings.ray_length);
        PlaneRow::new(self.objects, row, span, self.methods().roots)
    }

    /// How far off the surface of `object` at `point` a secondary ray starts by the epsilon
    /// method: a multiple of the rounding error of a surface point, which grows with its
    /// coordinates, plus the object's own part ([`crate::scene::SURFACE_TOLERANCE_STEPS`]).
    #[inline(always)]
    fn tolerance(&self, point: Vec3<S>, object: &Object<S>) -> S {
        let reach = point.max_abs();
        self.settings.tolerance_base + self.settings.tolerance_per_unit * reach + object.tolerance
    }

    /// How far off a surface whose tolerance is `tolerance` its secondary rays start: the
    /// tolerance by the epsilon method, none by exclusion.
    #[inline(always)]
    fn bias_offset(&self, tolerance: S) -> S {
        match self.methods().bias {
            BiasMethod::Epsilon => tolerance,
            BiasMethod::Exclude => S::ZERO,
        }
    }

    /// Where `ray` meets `object` (number `index`), given the surface it leaves; on a mesh
    /// the nearest of its triangles, or with `any` the first found (a shadow ray's).
    #[inline(always)]
    fn meet(
        &self,
        ray: &Ray<S>,
        span: Span<S>,
        (index, object): (usize, &Object<S>),
        from: Option<Leaving<S>>,
        per_ray: &mut PerRay<S>,
        any: bool,
    ) -> Option<Intersection<S>> {
        let excluded = |leaving: &Leaving<S>| {
            leaving.object == index && self.methods().bias == BiasMethod::Exclude
        };
        // A ray leaving a mesh's triangle by exclusion meets the mesh's others.
        let mesh = Self::has(Uses::MESHES) && matches!(object.shape, Shape::Mesh(_));
        match from {
            Some(leaving) if excluded(&leaving) && !mesh => {
                object
                    .shape
                    .intersect_again(ray, span, &self.methods(), Self::USES, leaving.into)
            }
            _ => {
                let search = Search {
                    meshes: self.meshes,
                    slack: self.settings.box_slack,
                    skip: from
                        .filter(|leaving| mesh && excluded(leaving))
                        .map(|l| l.part),
                    any,
                };
                let methods = self.methods();
                object
                    .shape
                    .intersect(ray, span, &methods, Self::USES, per_ray, &search)
            }
        }
    }

    /// The nearest object along `ray` within the world, of those `wanted`: asked once for
    /// each object, in order.
    #[inline(always)]
    fn nearest(
        &self,
        ray: &Ray<S>,
        from: Option<Leaving<S>>,
        mut wanted: impl FnMut() -> bool,
    ) -> Option<Hit<'_, S>> {
        S::note(Work::Search(if from.is_some() {
            RayKind::Secondary
        } else {
            RayKind::Primary
        }));
        let mut span = self.span(from, self.settings.ray_length);
        let mut nearest = None;
        let mut per_ray = PerRay::new();
        for (index, object) in self.objects.iter().enumerate() {
            if !wanted() {
                continue;
            }
            S::note(Work::Test);
            if let Some(at) = self.meet(ray, span, (index, object), from, &mut per_ray, false) {
                S::note(Work::Met);
                span.max = at.t;
                nearest = Some(Hit { object, index, at });
            }
        }
        nearest
    }

    /// The local colour at a hit, pushing its reflected and transmitted rays, and adding the
    /// objects that shadow it to `met`.
    fn shade(
        &self,
        task: &Task<S>,
        hit: &Hit<'_, S>,
        stack: &mut VecView<Task<S>>,
        met: &mut u64,
    ) -> Rgb<S> {
        let material = &hit.object.material;
        let shape = &hit.object.shape;
        let roots = self.methods().roots;
        let d = task.ray.dir;
        let meshes = Self::has(Uses::MESHES).then_some(self.meshes);
        let (point, normal) = shape.surface(&task.ray, &hit.at, roots, meshes);
        // Shade the side the ray arrived on: for a sphere hit from inside, that is the inside.
        let cos_in = -d.dot(normal);
        let entering = cos_in >= S::ZERO;
        let (facing, cos_in) = if entering {
            (normal, cos_in)
        } else {
            (-normal, -cos_in)
        };
        let two = S::from_int(2);
        // The mirror direction serves the reflected ray and the Phong highlight, the latter
        // about the shading normal where a smooth mesh's differs from the surface's: the
        // rays leave about the surface's own, never into it.
        let mirror = d.add_scaled(facing, two * cos_in);
        let smooth = if Self::has(Uses::MESHES) {
            shape.smooth_normal(&hit.at, roots, meshes)
        } else {
            None
        };
        let (shading, shading_mirror) = smooth.map_or((facing, mirror), |n| {
            let n = if n.dot(facing) < S::ZERO { -n } else { n };
            (n, d.add_scaled(n, -two * d.dot(n)))
        });
        // Rays leave on the side the ray arrived on (shadow, reflection), or the other
        // (transmission); the epsilon method starts them a tolerance off the surface.
        let solid = shape.is_solid();
        let tolerance = self.tolerance(point, hit.object);
        let leaving = |into| Leaving {
            object: hit.index,
            part: hit.at.part,
            into,
            tolerance,
        };
        let (this_side, other_side) = (leaving(solid && !entering), leaving(solid && entering));
        let offset = self.bias_offset(tolerance);
        let above = point.add_scaled(facing, offset);
        let below = point.add_scaled(facing, -offset);

        let surface = shape.surface_colour(point, material.colour);
        // Lambert's and Phong's cosines are of unit vectors: taken in the narrow format, a
        // 16×16 product a coordinate in the formats whose narrow format is 2.14.
        let local = self.local(
            material,
            surface,
            Shaded {
                above,
                facing,
                shading: shading.narrow(),
                shading_mirror: shading_mirror.narrow(),
                from: this_side,
            },
            met,
        );

        if task.depth < self.settings.max_depth {
            let depth = task.depth + 1;
            let mut reflection = material.reflection;
            if material.transmission > S::Narrow::ZERO {
                if solid {
                    // Snell, with η = n₁/n₂: the incident direction's part along the surface,
                    // t = d + cos θᵢ·n (|t| = sin θᵢ), is scaled by η, and the refracted ray is
                    // η·t − cos θₜ·n with cos² θₜ = k = 1 − |η·t|², negative beyond the critical
                    // angle, where all the light is reflected instead. Its length is 1 whatever
                    // the rounding of d, where the textbook's 1 − η²(1 − cos² θᵢ) would
                    // multiply the rounding of cos θᵢ by η².
                    let eta = if entering {
                        material.inv_ior
                    } else {
                        material.ior
                    };
                    let bent = d.add_scaled(facing, cos_in) * eta;
                    let k = S::ONE - bent.length_squared();
                    if k < S::ZERO {
                        reflection = reflection + material.transmission;
                    } else {
                        let dir = bent.add_scaled(facing, -roots.sqrt(k));
                        let ray = Ray::new(below, dir);
                        self.spawn(stack, ray, other_side, task, material.transmission, depth);
                    }
                } else {
                    // A sheet has no inside: the light passes straight through.
                    let ray = Ray::new(below, d);
                    self.spawn(stack, ray, other_side, task, material.transmission, depth);
                }
            }
            if reflection > S::Narrow::ZERO {
                self.spawn(
                    stack,
                    Ray::new(above, mirror),
                    this_side,
                    task,
                    reflection,
                    depth,
                );
            }
        }
        local
    }

    /// The light a surface of `material` and colour `surface` sends back at a shaded point
    /// ([`Shaded`]): the ambient light, and each light's Lambert and Phong terms where a shadow
    /// ray finds it, adding the objects that shadow it to `met`. The light's colour (in the
    /// format) is filtered by the surface's colour, weights and cosines (narrow numbers, at
    /// most 1 each).
    ///
    /// Inlined into [`Self::shade`] and the row pass's [`Self::shade_plane_row`], whose copy
    /// knows the surface matte and its normal the row's.
    #[inline(always)]
    fn local(
        &self,
        material: &Material<S>,
        surface: Rgb<S::Narrow>,
        at: Shaded<S>,
        met: &mut u64,
    ) -> Rgb<S> {
        let roots = self.methods().roots;
        let mut local = self.settings.ambient.filter(surface);
        for light in self.lights {
            let (l, distance) = (light.position - at.above).normalized_with_length(roots);
            let towards = l.narrow();
            let lambert = at.shading.dot(towards);
            if lambert <= S::Narrow::ZERO {
                continue;
            }
            let shadow = if Self::has(Uses::AREA_LIGHTS) && light.shadow_rays > 1 {
                self.visible_share(light, at.above, at.facing, at.from, met)
            } else {
                let cones = self.cones_of(light);
                self.transmittance(&Ray::new(at.above, l), distance, at.from, met, |i| {
                    cones.get(i).is_none_or(|cone| cone.admits(l))
                })
            };
            if shadow == S::Narrow::ZERO {
                continue;
            }
            let arriving = light.colour.scale_narrow(shadow);
            let diffuse = surface.scale(material.diffuse * lambert);
            local = local + arriving.filter(diffuse);
            let highlight = at.shading_mirror.dot(towards);
            if material.specular > S::Narrow::ZERO && highlight > S::Narrow::ZERO {
                // The cosine of two unit vectors, which rounding can lift a few steps above 1,
                // where the power would multiply the excess by the exponent: clamped, it loses
                // nothing and stays within 1 whatever the exponent.
                let cosine = highlight.min(S::Narrow::ONE);
                let phong = material.specular * cosine.powi(material.shininess);
                local = local + arriving.scale_narrow(phong);
            }
        }
        local
    }

    /// What primary ray `id` of a row pass brings back from `point` on the matte plane `row`
    /// is of, which the ray met from the side `row` faces ([`PlaneRow`]): its local light
    /// alone, as [`Self::shade`] finds it (the surface's terms read no direction but the side
    /// the ray arrives on), a matte surface spawning no ray.
    ///
    /// Out of line on the M0, where a copy of the lights' code inlined into the pixel loop
    /// would take a one-scene image past its 32 KiB of flash, for about 1 % of its cycles.
    #[cfg_attr(armv6m, inline(never))]
    pub(crate) fn shade_plane_row(
        &self,
        row: &PlaneRow<'_, S>,
        point: Vec3<S>,
        id: SampleId,
    ) -> Rgb<S> {
        self.light_plane_row(row, point, id, &mut 0)
    }

    /// [`Self::shade_plane_row`], adding to `met` the objects that shadow the point
    /// ([`Sample::met`]).
    #[inline(always)]
    pub(crate) fn light_plane_row(
        &self,
        row: &PlaneRow<'_, S>,
        point: Vec3<S>,
        id: SampleId,
        met: &mut u64,
    ) -> Rgb<S> {
        // A copy with the ray's place, as the M0 (where this is out of line) reads its fields
        // fastest.
        let this = Tracer { id, ..*self };
        let (index, object) = row.object();
        let (facing, shading) = row.facing();
        let tolerance = this.tolerance(point, object);
        let at = Shaded {
            above: point.add_scaled(facing, this.bias_offset(tolerance)),
            facing,
            shading,
            // A matte surface has no highlight.
            shading_mirror: shading,
            from: Leaving {
                object: index,
                part: 0,
                into: false,
                tolerance,
            },
        };
        let surface = row.surface_colour(point);
        this.local(&object.material, surface, at, met)
    }

    /// Pushes a secondary ray unless its weight is too small to show.
    fn spawn(
        &self,
        stack: &mut VecView<Task<S>>,
        ray: Ray<S>,
        from: Leaving<S>,
        parent: &Task<S>,
        share: S::Narrow,
        depth: u8,
    ) {
        let weight = parent.weight.scale(share);
        if weight.max_channel() >= self.settings.min_weight {
            push(
                stack,
                Task {
                    ray,
                    weight,
                    depth,
                    from: Some(from),
                },
            );
        }
    }

    /// How much light passes from `ray.origin` to a light `distance` away: 1 in the open, the
    /// product of the occluders' transmissions, 0 behind an opaque object. The occluders are
    /// added to `met`.
    ///
    /// Inlined into both its callers: called out of line, it cost the M4F's one-ray `whitted`
    /// about 60 instructions per pixel.
    #[inline(always)]
    fn transmittance(
        &self,
        ray: &Ray<S>,
        distance: S,
        from: Leaving<S>,
        met: &mut u64,
        admits: impl Fn(usize) -> bool,
    ) -> S::Narrow {
        S::note(Work::Search(RayKind::Shadow));
        let span = self.span(Some(from), distance);
        let mut passed = S::Narrow::ONE;
        let mut per_ray = PerRay::new();
        for (index, object) in self.objects.iter().enumerate() {
            if !admits(index) {
                continue;
            }
            S::note(Work::Test);
            if self
                .meet(ray, span, (index, object), Some(from), &mut per_ray, true)
                .is_some()
            {
                S::note(Work::Met);
                *met |= bit(index);
                passed = passed * object.material.transmission;
                if passed == S::Narrow::ZERO {
                    break;
                }
            }
        }
        passed
    }

    /// The share of area light `light` that reaches `origin`, on a surface facing `facing`: the
    /// mean transmittance of the light's shadow rays, each aimed at a point of the disc that
    /// faces `origin`, in 16-bit fractions summed as a pixel's samples are (they fit however
    /// many). A point of the disc behind the surface's own horizon is hidden by the surface,
    /// whichever the bias method. With adaptive shadows, when the first [`SHADOW_PROBES`]
    /// agree, the point is taken to be in full light, full shadow or behind the same glass for
    /// all of them, and the rest are not traced: the answer is what all of them would give if
    /// they agreed too.
    ///
    /// Out of line: it runs for area lights alone, and inlined into the light loop it slowed
    /// the images of point lights too. It finds the light's direction again rather than take
    /// it from the loop, which costs the point lights' loop less.
    #[inline(never)]
    fn visible_share(
        &self,
        light: &Light<S>,
        origin: Vec3<S>,
        facing: Vec3<S>,
        from: Leaving<S>,
        met: &mut u64,
    ) -> S::Narrow {
        let roots = self.methods().roots;
        let pattern = Pattern::light(self.id, light.index);
        let l = (light.position - origin).normalized(roots);
        // Every ray to the disc is in the cone of an object it can meet ([`crate::occlusion`]).
        let cones = self.cones_of(light);
        let admitted = (0..self.objects.len()).fold(0, |admitted, i| {
            if cones.get(i).is_none_or(|cone| cone.admits(l)) {
                admitted | bit(i)
            } else {
                admitted
            }
        });
        let [across, up] = perpendiculars(l, roots);
        let n = light.shadow_rays;
        let (mut first, mut agree, mut sum) = (0, true, 0_u32);
        for i in 0..n {
            let [a, b] = pattern.disc::<S>(i);
            let target = light
                .position
                .add_scaled(across, light.radius * a)
                .add_scaled(up, light.radius * b);
            let (dir, distance) = (target - origin).normalized_with_length(roots);
            let passed = if facing.dot(dir) > S::ZERO {
                self.transmittance(&Ray::new(origin, dir), distance, from, met, |i| {
                    admitted & bit(i) != 0
                })
            } else {
                S::Narrow::ZERO
            };
            // At most 2¹⁶.
            let passed = passed
                .clamp(S::Narrow::ZERO, S::Narrow::ONE)
                .to_q16()
                .unsigned_abs();
            if i == 0 {
                first = passed;
            }
            agree &= passed == first;
            if agree && i + 1 == SHADOW_PROBES && self.settings.adaptive_shadows {
                return S::Narrow::from_q16(first as i32);
            }
            sum += passed;
        }
        let n = u32::from(n);
        S::Narrow::from_q16(((sum + n / 2) / n) as i32)
    }
}

/// Two unit vectors perpendicular to the unit `n` and to each other, after Duff et al.,
/// "Building an orthonormal basis, revisited" (2017): one division by a number from 1 to 2,
/// no root, every value within 2.
fn perpendiculars<S: Scalar>(n: Vec3<S>, roots: RootMethod) -> [Vec3<S>; 2] {
    let sign = if n.z >= S::ZERO { S::ONE } else { -S::ONE };
    let a = -roots.div(S::ONE, sign + n.z);
    let b = n.x * n.y * a;
    [
        Vec3::new(S::ONE + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    ]
}

/// The bit of object `index` in [`Sample::met`].
#[inline]
pub(crate) fn bit(index: usize) -> u64 {
    // Below 64, so the conversion is exact.
    shl_u64(1, u32::try_from(index.min(63)).unwrap_or(63))
}

/// Pushes a task. It cannot fail: a task of depth k leaves at most one sibling per level on
/// the stack, so it never holds more than max_depth + 1 ≤ RAYS tasks (checked by
/// `Scene::build`).
fn push<S: Scalar>(stack: &mut VecView<Task<S>>, task: Task<S>) {
    let pushed = stack.push(task);
    debug_assert!(pushed.is_ok(), "ray stack overflow");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::desc::{
        BackgroundDesc, CameraDesc, LightDesc, MaterialDesc, ObjectDesc, SceneDesc, ShapeDesc,
    };
    use crate::methods::{BiasMethod, Methods, SphereMethod};
    use crate::test_util::{for_each_format, v};
    use crate::vec3::Vec3;

    const CAMERA: CameraDesc =
        CameraDesc::pinhole([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 60.0);

    fn desc<'a>(
        objects: &'a [ObjectDesc],
        lights: &'a [LightDesc],
        ambient: f32,
        max_depth: u8,
    ) -> SceneDesc<'a> {
        SceneDesc {
            camera: CAMERA,
            objects,
            lights,
            ambient: [ambient; 3],
            background: BackgroundDesc::Solid([0.2, 0.4, 0.6]),
            far: 10.0,
            max_depth,
            ..SceneDesc::DEFAULT
        }
    }

    /// Every combination of the methods these tests can tell apart: both sphere methods with
    /// both self-intersection methods.
    const METHOD_SETS: [Methods; 4] = [
        Methods::LECTURE,
        Methods {
            sphere: SphereMethod::Stable,
            ..Methods::LECTURE
        },
        Methods {
            bias: BiasMethod::Exclude,
            ..Methods::LECTURE
        },
        Methods {
            sphere: SphereMethod::Stable,
            bias: BiasMethod::Exclude,
            ..Methods::LECTURE
        },
    ];

    /// The colour of one ray, traced by each of [`METHOD_SETS`].
    fn trace<S: Scalar>(
        desc: &SceneDesc<'_>,
        origin: [f64; 3],
        dir: [f64; 3],
    ) -> std::vec::Vec<(Methods, [f64; 3])> {
        let length = dir.iter().map(|c| c * c).sum::<f64>().sqrt();
        let ray = Ray::new(
            v(origin[0], origin[1], origin[2]),
            v(dir[0] / length, dir[1] / length, dir[2] / length),
        );
        METHOD_SETS
            .iter()
            .map(|&methods| {
                let scene = Scene::<S, 4, 2, 8>::build_with(desc, methods).unwrap();
                (
                    methods,
                    scene.trace(ray, SampleId::default()).colour.to_f64(),
                )
            })
            .collect()
    }

    #[track_caller]
    fn assert_colour<S: Scalar>(got: std::vec::Vec<(Methods, [f64; 3])>, want: [f64; 3], tol: f64) {
        for (methods, colour) in got {
            for (g, w) in colour.into_iter().zip(want) {
                let g = S::from_f64(g).unwrap().to_f64();
                assert!(
                    (g - w).abs() <= tol,
                    "{} with {methods}: got {colour:?}, want {want:?}",
                    S::NAME
                );
            }
        }
    }

    const FLOOR_COLOUR: [f32; 3] = [1.0, 0.5, 0.25];

    fn floor(material: MaterialDesc) -> ObjectDesc {
        ObjectDesc {
            shape: ShapeDesc::Plane {
                point: [0.0, -2.0, 0.0],
                normal: [0.0, 1.0, 0.0],
                checker: None,
            },
            material,
        }
    }

    /// The view ray from the eye along (0, −1, 1) meets the floor y = −2 at (0, −2, 2); the
    /// light at (0, 2, 4) is then along (0, 4, 2)/√20, so Lambert's cosine is 4/√20.
    const LIGHT: LightDesc = LightDesc::point([0.0, 2.0, 4.0], [1.0, 1.0, 1.0]);
    const TO_FLOOR: [f64; 3] = [0.0, -1.0, 1.0];

    fn lambert() -> f64 {
        4.0 / 20.0_f64.sqrt()
    }

    fn occluder(transmission: f32) -> ObjectDesc {
        // Centred on the segment from the floor point to the light, clear of the view ray.
        ObjectDesc {
            shape: ShapeDesc::Sphere {
                center: [0.0, 0.0, 3.0],
                radius: 0.5,
            },
            material: MaterialDesc {
                transmission,
                ..MaterialDesc::matte([0.0, 1.0, 0.0])
            },
        }
    }

    #[test]
    fn lit_surface_is_ambient_plus_lambert() {
        for_each_format!(S, {
            let objects = [floor(MaterialDesc {
                diffuse: 1.0,
                ..MaterialDesc::matte(FLOOR_COLOUR)
            })];
            let got = trace::<S>(&desc(&objects, &[LIGHT], 0.1, 0), [0.0; 3], TO_FLOOR);
            assert_colour::<S>(
                got,
                FLOOR_COLOUR.map(|c| f64::from(c) * (0.1 + lambert())),
                1e-3,
            );
        });
    }

    #[test]
    fn phong_highlight_adds_white() {
        for_each_format!(S, {
            // Straight on: the mirror direction of the view ray points at the light behind the
            // eye, so the highlight is 1 whatever the exponent.
            let material = MaterialDesc {
                diffuse: 0.8,
                specular: 0.5,
                shininess: 10,
                ..MaterialDesc::matte([0.5, 0.25, 1.0])
            };
            let objects = [ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: [0.0, 0.0, 5.0],
                    radius: 1.0,
                },
                material,
            }];
            let light = LightDesc::point([0.0, 0.0, -10.0], [1.0; 3]);
            let got = trace::<S>(&desc(&objects, &[light], 0.1, 0), [0.0; 3], [0.0, 0.0, 1.0]);
            assert_colour::<S>(
                got,
                [0.5 * 0.9 + 0.5, 0.25 * 0.9 + 0.5, 1.0 * 0.9 + 0.5],
                1e-3,
            );
        });
    }

    #[test]
    fn shadowed_surface_gets_ambient_only() {
        for_each_format!(S, {
            let objects = [
                floor(MaterialDesc {
                    diffuse: 1.0,
                    ..MaterialDesc::matte(FLOOR_COLOUR)
                }),
                occluder(0.0),
            ];
            let got = trace::<S>(&desc(&objects, &[LIGHT], 0.1, 0), [0.0; 3], TO_FLOOR);
            assert_colour::<S>(got, FLOOR_COLOUR.map(|c| f64::from(c) * 0.1), 1e-3);
        });
    }

    #[test]
    fn a_glass_occluder_lets_its_transmission_through() {
        for_each_format!(S, {
            let objects = [
                floor(MaterialDesc {
                    diffuse: 1.0,
                    ..MaterialDesc::matte(FLOOR_COLOUR)
                }),
                occluder(0.5),
            ];
            let got = trace::<S>(&desc(&objects, &[LIGHT], 0.1, 0), [0.0; 3], TO_FLOOR);
            assert_colour::<S>(
                got,
                FLOOR_COLOUR.map(|c| f64::from(c) * (0.1 + 0.5 * lambert())),
                1e-3,
            );
        });
    }

    #[test]
    fn a_mirror_shows_the_background_and_depth_zero_does_not() {
        for_each_format!(S, {
            let mirror = MaterialDesc {
                diffuse: 0.0,
                reflection: 1.0,
                ..MaterialDesc::matte(FLOOR_COLOUR)
            };
            let objects = [floor(mirror)];
            let got = trace::<S>(&desc(&objects, &[], 0.0, 1), [0.0; 3], TO_FLOOR);
            assert_colour::<S>(got, [0.2, 0.4, 0.6], 1e-3);
            let got = trace::<S>(&desc(&objects, &[], 0.0, 0), [0.0; 3], TO_FLOOR);
            assert_colour::<S>(got, [0.0; 3], 1e-3);
        });
    }

    #[test]
    fn glass_splits_the_ray_tree_by_its_weights() {
        for_each_format!(S, {
            // Along the axis of a glass ball nothing bends. Depth 0 hits the front: 0.1 reflects
            // to the sky; 0.9 refracts to the back (depth 1), where 0.81 leaves for the sky and
            // 0.09 reflects to the front (depth 2, the last level, which adds nothing).
            let glass = MaterialDesc {
                diffuse: 0.0,
                reflection: 0.1,
                transmission: 0.9,
                ior: 1.5,
                ..MaterialDesc::matte([1.0; 3])
            };
            let objects = [ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: [0.0, 0.0, 5.0],
                    radius: 1.0,
                },
                material: glass,
            }];
            let got = trace::<S>(&desc(&objects, &[], 0.0, 2), [0.0; 3], [0.0, 0.0, 1.0]);
            assert_colour::<S>(got, [0.2 * 0.91, 0.4 * 0.91, 0.6 * 0.91], 1e-3);
        });
    }

    #[test]
    fn total_internal_reflection_keeps_the_light_inside() {
        for_each_format!(S, {
            // From (0, 0.9, 0) along +x inside a unit glass ball, every bounce meets the surface
            // at 64° from the normal, beyond glass's critical angle of 41.8°: the ray never
            // leaves and never sees the sky; each of the four levels adds the ambient 0.1.
            let glass = MaterialDesc {
                diffuse: 0.0,
                transmission: 1.0,
                ior: 1.5,
                ..MaterialDesc::matte([1.0; 3])
            };
            let objects = [ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: [0.0, 0.0, 0.0],
                    radius: 1.0,
                },
                material: glass,
            }];
            let got = trace::<S>(
                &desc(&objects, &[], 0.1, 3),
                [0.0, 0.9, 0.0],
                [1.0, 0.0, 0.0],
            );
            assert_colour::<S>(got, [0.4; 3], 1e-3);
        });
    }

    #[test]
    fn a_primary_ray_tests_the_objects_its_mask_names_those_beyond_30_by_bit_31() {
        // Forty balls: 3 and 35 on the ray's axis (3 nearer), the rest above it.
        let ball = |i: u16| {
            let on_axis = i == 3 || i == 35;
            let (y, z, radius) = if on_axis {
                (0.0, if i == 3 { 3.0 } else { 6.0 }, 0.5)
            } else {
                (3.0, 1.0 + 0.2 * f32::from(i), 0.05)
            };
            ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: [0.0, y, z],
                    radius,
                },
                material: MaterialDesc::matte([1.0; 3]),
            }
        };
        let objects: std::vec::Vec<ObjectDesc> = (0..40).map(ball).collect();
        let scene = Scene::<f32, 40, 1, 8>::build(&desc(&objects, &[], 0.1, 0)).unwrap();
        let mut tracer = scene.tracer(SampleId::default());
        let mut stack: Vec<Task<f32>, 8> = Vec::new();
        let ray = Ray::new(Vec3::ZERO, v(0.0, 0.0, 1.0));
        let mut met = |candidates: u32| {
            tracer
                .trace_ray(ray, SampleId::default(), candidates, stack.as_mut_view())
                .object
        };
        assert_eq!(met(u32::MAX), Some(3));
        assert_eq!(met(!(1 << 3)), Some(35));
        assert_eq!(met(1 << 31), Some(35));
        assert_eq!(met(!(1 << 3) & !(1 << 31)), None);
    }

    #[test]
    fn whitteds_glass_ball_is_lone_and_a_ball_near_another_object_or_opaque_is_not() {
        use crate::scalar::{I16F16, I20F12};
        use crate::scenes::WHITTED;
        let lone = |objects: &[ObjectDesc]| {
            let desc = SceneDesc { objects, ..WHITTED };
            Scene::<f32, 4, 1, 8>::build(&desc).unwrap().settings.lone_balls
        };
        // The glass ball (object 2) floats 0.9 over the floor and 1.3 from the mirror ball;
        // the mirror ball lets no light through.
        assert_eq!(lone(WHITTED.objects), 1 << 2);
        assert_eq!(Scene::<I16F16, 4, 1, 8>::build(&WHITTED).unwrap().settings.lone_balls, 1 << 2);
        // A format whose errors reach the clearance (i20f12 finds the ball to within 0.45,
        // four times that over the floor's 0.9) tests every object.
        assert_eq!(Scene::<I20F12, 4, 1, 8>::build(&WHITTED).unwrap().settings.lone_balls, 0);
        let moved = |center| {
            let mut objects: [ObjectDesc; 3] = WHITTED.objects.try_into().unwrap();
            objects[2].shape = ShapeDesc::Sphere {
                center,
                radius: 1.0,
            };
            lone(&objects)
        };
        // Clear of both by a hundredth: lone; resting on the floor, or touching the other
        // ball: not.
        assert_eq!(moved([0.55, 1.01, 0.6]), 1 << 2);
        assert_eq!(moved([0.55, 1.0, 0.6]), 0);
        assert_eq!(moved([0.75, 1.3, 3.2]), 0);
        let mut opaque: [ObjectDesc; 3] = WHITTED.objects.try_into().unwrap();
        opaque[2].material.transmission = 0.0;
        assert_eq!(lone(&opaque), 0);
    }

    #[test]
    fn a_ray_inside_a_lone_ball_meets_its_wall_alone() {
        // A small matte ball inside a glass one, on the axis: the ray through the glass meets
        // it. Were the glass ball lone, the rays inside would test only its wall.
        let glass = MaterialDesc {
            transmission: 0.9,
            ior: 1.0,
            ..MaterialDesc::matte([1.0; 3])
        };
        let ball = |radius, material| ObjectDesc {
            shape: ShapeDesc::Sphere {
                center: [0.0, 0.0, 5.0],
                radius,
            },
            material,
        };
        let objects = [ball(2.0, glass), ball(0.5, MaterialDesc::matte([1.0; 3]))];
        let mut scene = Scene::<f32, 2, 1, 8>::build(&desc(&objects, &[], 0.1, 4)).unwrap();
        assert_eq!(scene.settings.lone_balls, 0, "a ball with one inside is not lone");
        let ray = Ray::new(Vec3::ZERO, v(0.0, 0.0, 1.0));
        assert_eq!(scene.trace(ray, SampleId::default()).met, 0b11);
        scene.settings.lone_balls = 1;
        assert_eq!(scene.trace(ray, SampleId::default()).met, 0b01);
    }

    #[test]
    fn a_miss_sees_the_background_and_names_no_object() {
        for_each_format!(S, {
            let scene = Scene::<S, 4, 2, 8>::build(&desc(&[], &[], 0.1, 2)).unwrap();
            let sample = scene.trace(Ray::new(Vec3::ZERO, v(0.0, 0.0, 1.0)), SampleId::default());
            assert_eq!(sample.object, None);
            assert_colour::<S>(
                vec![(Methods::LECTURE, sample.colour.to_f64())],
                [0.2, 0.4, 0.6],
                1e-4,
            );
        });
    }
}
