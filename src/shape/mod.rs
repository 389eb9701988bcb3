//! The geometric primitives, one file each, and [`Shape`], which dispatches between them by
//! the chosen [`Methods`].

crate::phase::declare_phase!(Some(crate::phase::Phase::Tests));

pub mod mesh;
pub(crate) mod plane;
pub(crate) mod sphere;
pub(crate) mod triangle;

pub use plane::{CHECKER_PERIOD, Checker, Plane};
pub use sphere::Sphere;
pub use triangle::{PerRay, Triangle};

use crate::color::Rgb;
use crate::methods::{Methods, RootMethod};
use crate::ray::{Ray, Span};
use crate::scalar::Scalar;
use crate::uses::Uses;
use crate::vec3::Vec3;
use mesh::{Meshes, Search};

/// Where a ray meets a shape: the distance along it, on a triangle the barycentric
/// coordinates of the point, a + u·e1 + v·e2 = (1 − u − v)·a + u·b + v·c (zero on the others),
/// and on a mesh which of its triangles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Intersection<S> {
    /// The distance along the ray.
    pub t: S,
    /// The weight of a triangle's second vertex.
    pub u: S,
    /// The weight of a triangle's third vertex.
    pub v: S,
    /// The index of a mesh's triangle met (0 on other shapes).
    pub part: u32,
}

impl<S: Scalar> Intersection<S> {
    /// A hit at distance `t` on a sphere or a plane.
    #[inline]
    #[must_use]
    pub const fn at(t: S) -> Self {
        Self {
            t,
            u: S::ZERO,
            v: S::ZERO,
            part: 0,
        }
    }
}

/// Any primitive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape<S: Scalar> {
    /// A sphere.
    Sphere(Sphere<S>),
    /// A plane.
    Plane(Plane<S>),
    /// A triangle.
    Triangle(Triangle<S>),
    /// A mesh: the index of its hierarchy's root among the scene's nodes ([`crate::shape::mesh`]).
    Mesh(u32),
}

crate::words::words_of_enum!(Shape<S> {
    Sphere(sphere) if Uses::SPHERES,
    Plane(plane) if Uses::PLANES,
    Triangle(triangle) if Uses::TRIANGLES,
    Mesh(root) if Uses::MESHES
});

impl<S: Scalar> Shape<S> {
    /// The nearest point in `span` at which `ray` meets the shape; `per_ray` carries what the
    /// tests of this ray against several shapes share, `meshes` where a mesh's triangles are
    /// and what its search may skip. A kind of shape `uses` leaves out is met nowhere: no
    /// scene of a tracer without it has one ([`crate::Uses`]).
    #[inline(always)]
    #[must_use]
    pub fn intersect<M: Meshes<S>>(
        &self,
        ray: &Ray<S>,
        span: Span<S>,
        methods: &Methods,
        uses: Uses,
        per_ray: &mut PerRay<S>,
        meshes: &Search<'_, S, M>,
    ) -> Option<Intersection<S>> {
        match self {
            Self::Sphere(sphere) if uses.contains(Uses::SPHERES) => sphere
                .intersect(ray, span, methods.sphere, methods.roots)
                .map(Intersection::at),
            Self::Plane(plane) if uses.contains(Uses::PLANES) => plane
                .intersect(ray, span, methods.roots)
                .map(Intersection::at),
            Self::Triangle(triangle) if uses.contains(Uses::TRIANGLES) => {
                triangle.intersect_sharing(ray, span, methods.triangle, methods.roots, per_ray)
            }
            Self::Mesh(root) if uses.contains(Uses::MESHES) => {
                meshes.run(*root, ray, span, |triangle, span| {
                    triangle.intersect_sharing(ray, span, methods.triangle, methods.roots, per_ray)
                })
            }
            Self::Sphere(_) | Self::Plane(_) | Self::Triangle(_) | Self::Mesh(_) => None,
        }
    }

    /// Where a ray that starts on this shape's surface meets it again: only where it leaves a
    /// solid it is entering (`into`); never for a ray leaving a sheet or the outside of a
    /// sphere, which cannot return to it.
    #[inline(always)]
    #[must_use]
    pub fn intersect_again(
        &self,
        ray: &Ray<S>,
        span: Span<S>,
        methods: &Methods,
        uses: Uses,
        into: bool,
    ) -> Option<Intersection<S>> {
        match self {
            Self::Sphere(sphere) if into && uses.contains(Uses::SPHERES) => sphere
                .exit(ray, span, methods.sphere, methods.roots)
                .map(Intersection::at),
            Self::Sphere(_) | Self::Plane(_) | Self::Triangle(_) | Self::Mesh(_) => None,
        }
    }

    /// The surface point of a hit of `ray`, and the unit normal there (outward for a sphere).
    /// Secondary rays start from the surface itself, not from wherever the rounding of o + t·d
    /// put the hit: on a sphere the point nearest it, on a plane its projection, on a triangle
    /// the point of its barycentric coordinates (on a mesh, of its triangle in `meshes`, which a
    /// tracer without meshes does not give).
    #[inline]
    #[must_use]
    pub fn surface(
        &self,
        ray: &Ray<S>,
        hit: &Intersection<S>,
        roots: RootMethod,
        meshes: Option<&impl Meshes<S>>,
    ) -> (Vec3<S>, Vec3<S>) {
        let on = |triangle: &Triangle<S>| (triangle.at(hit.u, hit.v), triangle.normal());
        match self {
            Self::Sphere(sphere) => sphere.surface(ray.at(hit.t), roots),
            Self::Plane(plane) => (plane.project(ray.at(hit.t)), plane.normal()),
            Self::Triangle(triangle) => on(triangle),
            // The search found the triangle there, so it is there (in a tracer with meshes).
            Self::Mesh(_) => meshes
                .and_then(|meshes| meshes.triangle(hit.part))
                .map_or_else(|| (ray.at(hit.t), -ray.dir), |triangle| on(&triangle)),
        }
    }

    /// The normal that shades a hit on a smooth mesh: its triangle's corners' normals
    /// interpolated ([`mesh::smooth_normal`]), on either side. `None` elsewhere, where the
    /// surface's own normal shades it.
    #[inline]
    #[must_use]
    pub fn smooth_normal(
        &self,
        hit: &Intersection<S>,
        roots: RootMethod,
        meshes: Option<&impl Meshes<S>>,
    ) -> Option<Vec3<S>> {
        match self {
            Self::Mesh(_) => meshes?
                .normals(hit.part)
                .and_then(|normals| mesh::smooth_normal(normals, hit.u, hit.v, roots)),
            Self::Sphere(_) | Self::Plane(_) | Self::Triangle(_) => None,
        }
    }

    /// The colour of the surface at a point: the material's, or a pattern's.
    #[inline]
    #[must_use]
    pub fn surface_colour(
        &self,
        point: Vec3<S>,
        material_colour: Rgb<S::Narrow>,
    ) -> Rgb<S::Narrow> {
        match self {
            Self::Plane(plane) => plane.pattern_colour(point).unwrap_or(material_colour),
            Self::Sphere(_) | Self::Triangle(_) | Self::Mesh(_) => material_colour,
        }
    }

    /// Whether the shape encloses a volume, so that a ray can be inside it and refraction
    /// bends rays in and out. Planes, triangles and meshes are thin sheets.
    #[inline]
    #[must_use]
    pub const fn is_solid(&self) -> bool {
        matches!(self, Self::Sphere(_))
    }
}
