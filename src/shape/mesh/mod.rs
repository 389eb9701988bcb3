//! Meshes: triangles that share corners, found through a bounding-volume hierarchy
//! ([`build_hierarchy`], on the host) rather than tested one by one. A scene keeps its meshes'
//! triangles and nodes, converted into its format, in a [`MeshStorage`] of the caller's
//! choosing (a `Vec` on a desktop; words in flash on a board, read as they are needed), and the
//! tracer walks a mesh's hierarchy with a stack of at most [`MAX_DEPTH`] + 1 nodes, never by
//! recursion.
//!
//! A mesh whose vertices have normals is shaded smooth: each triangle keeps its corners'
//! normals, and the normal at a hit is theirs interpolated by its barycentric coordinates
//! ([`smooth_normal`]; Phong, "Illumination for computer generated pictures", 1975).
//!
//! A node is tested by the separating axes of its box and the ray's segment up to the nearest
//! hit so far (Ericson, *Real-Time Collision Detection*, 5.3.3): products of differences of
//! positions with unit directions, no reciprocal of a direction, so that every value stays
//! within the range proof's bounds, and each comparison is widened by a slack of a few steps
//! of the format ([`slack`]) so that a box is never missed by rounding where one of its
//! triangles is met.

crate::phase::declare_phase!(Some(crate::phase::Phase::Tests));

pub(crate) mod flash;
pub(crate) mod hierarchy;
#[cfg(feature = "alloc")]
pub(crate) mod vecs;

pub use flash::MeshWords;
pub(crate) use flash::write as write_words;
pub use hierarchy::{HierarchyError, MAX_DEPTH, MAX_LEAF, build_hierarchy};
#[cfg(feature = "alloc")]
pub use vecs::MeshVecs;

use crate::methods::RootMethod;
use crate::ray::{Ray, Span};
use crate::scalar::{Scalar, Work};
use crate::shape::{Intersection, Triangle};
use crate::vec3::Vec3;
use heapless::Vec;

/// A node of a hierarchy in a scene's format: its box, about a centre relative to the eye, with
/// half its extent rounded outwards, and the triangles or children under it ([`crate::desc::NodeDesc`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node<S> {
    pub(crate) centre: Vec3<S>,
    pub(crate) half: Vec3<S>,
    pub(crate) first: u32,
    pub(crate) end: u32,
    pub(crate) right: u32,
    pub(crate) axis: u32,
}

crate::words::words_of_struct!(Node<S> {
    centre,
    half,
    first,
    end,
    right,
    axis
});

/// The widening of every comparison of the box test, in steps of the format at the largest
/// magnitude it forms, `magnitude`: the test's operands each carry a step or two of rounding
/// (the segment's midpoint, its difference with the box's centre, the products with the
/// direction, the box itself), which this exceeds.
pub const SLACK_STEPS: f64 = 16.0;

/// [`SLACK_STEPS`] of `resolution` (a format's step at a magnitude) at `magnitude`.
#[must_use]
pub fn slack(resolution: impl Fn(f64) -> f64, magnitude: f64) -> f64 {
    SLACK_STEPS * resolution(magnitude)
}

impl<S: Scalar> Node<S> {
    /// Whether the segment from `mid` − `reach`·`dir` to `mid` + `reach`·`dir` may meet the
    /// box: false only where an axis separates them by more than `slack`.
    #[inline(always)]
    fn meets(&self, dir: Vec3<S>, mid: Vec3<S>, reach: S, slack: S) -> bool {
        let m = mid - self.centre;
        let (dx, dy, dz) = (dir.x.abs(), dir.y.abs(), dir.z.abs());
        let h = self.half;
        if m.x.abs() > h.x + reach * dx + slack
            || m.y.abs() > h.y + reach * dy + slack
            || m.z.abs() > h.z + reach * dz + slack
        {
            return false;
        }
        // The axes across the segment: each edge direction of the box times the segment's.
        let across = m.cross(dir);
        across.x.abs() <= h.y * dz + h.z * dy + slack
            && across.y.abs() <= h.x * dz + h.z * dx + slack
            && across.z.abs() <= h.x * dy + h.y * dx + slack
    }
}

/// Where a scene finds its meshes' nodes and triangles, by index.
pub trait Meshes<S> {
    /// Node `index`, if there is one.
    fn node(&self, index: u32) -> Option<Node<S>>;
    /// Triangle `index`, if there is one.
    fn triangle(&self, index: u32) -> Option<Triangle<S>>;
    /// The normals at triangle `index`'s corners, where the meshes have normals (zero where
    /// the triangle is shaded flat).
    fn normals(&self, index: u32) -> Option<[Vec3<S>; 3]>;
}

/// Storage a scene build fills with its meshes' nodes and triangles, in the order of
/// [`crate::desc::MeshesDesc`].
pub trait MeshStorage<S>: Meshes<S> + Default {
    /// How many triangles it can hold.
    fn capacity(&self) -> usize;
    /// Adds a node; false where it is full.
    fn push_node(&mut self, node: Node<S>) -> bool;
    /// Adds a triangle; false where it is full.
    fn push_triangle(&mut self, triangle: Triangle<S>) -> bool;
    /// Adds the normals at the corners of the triangle of the same index; false where it is
    /// full. Given for every triangle, or for none.
    fn push_normals(&mut self, normals: [Vec3<S>; 3]) -> bool;
}

/// The storage of a scene without meshes: it holds none.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NoMeshes;

impl<S> Meshes<S> for NoMeshes {
    fn node(&self, _: u32) -> Option<Node<S>> {
        None
    }
    fn triangle(&self, _: u32) -> Option<Triangle<S>> {
        None
    }
    fn normals(&self, _: u32) -> Option<[Vec3<S>; 3]> {
        None
    }
}

impl<S> MeshStorage<S> for NoMeshes {
    fn capacity(&self) -> usize {
        0
    }
    fn push_node(&mut self, _: Node<S>) -> bool {
        false
    }
    fn push_triangle(&mut self, _: Triangle<S>) -> bool {
        false
    }
    fn push_normals(&mut self, _: [Vec3<S>; 3]) -> bool {
        false
    }
}

/// The unit normal at the point with barycentric coordinates (`u`, `v`) of a triangle with
/// `normals` at its corners: n₀ + u·(n₁ − n₀) + v·(n₂ − n₀), normalised. `None` where a corner
/// has no normal (zero), or where they nearly cancel (the sum shorter than ½, which no surface
/// smooth enough to shade so has), and the triangle's own normal shades it.
///
/// Every value stays within 5: the corners' are unit, and a hit's weights are within [0, 1].
///
/// ```
/// use obscura::Vec3;
/// use obscura::mesh::smooth_normal;
/// use obscura::methods::RootMethod;
///
/// let (up, side) = (Vec3::new(0.0_f64, 0.0, 1.0), Vec3::new(1.0, 0.0, 0.0));
/// // Halfway between a corner facing up and one facing sideways: 45° between them.
/// let n = smooth_normal([up, side, up], 0.5, 0.0, RootMethod::Exact).expect("a normal");
/// assert!((n.x - n.z).abs() < 1e-12 && (n.length_squared() - 1.0).abs() < 1e-12);
/// // A corner without a normal: the triangle shades flat.
/// assert_eq!(smooth_normal([up, Vec3::ZERO, up], 0.5, 0.0, RootMethod::Exact), None);
/// ```
#[inline]
#[must_use]
pub fn smooth_normal<S: Scalar>(
    normals: [Vec3<S>; 3],
    u: S,
    v: S,
    roots: RootMethod,
) -> Option<Vec3<S>> {
    let [a, b, c] = normals;
    if normals.contains(&Vec3::ZERO) {
        return None;
    }
    let n = a.add_scaled(b - a, u).add_scaled(c - a, v);
    (n.length_squared() >= S::ratio(1, 4)).then(|| n.normalized(roots))
}

/// A search of a mesh for a ray: where the meshes are, and what the search may skip.
#[derive(Clone, Copy, Debug)]
pub struct Search<'a, S, M> {
    /// The scene's meshes.
    pub meshes: &'a M,
    /// The widening of the box test ([`slack`]).
    pub slack: S,
    /// A triangle the ray leaves and cannot meet again (the bias method of exclusion).
    pub skip: Option<u32>,
    /// Whether any hit will do (a shadow ray's occluder), not only the nearest.
    pub any: bool,
}

impl<S: Scalar, M: Meshes<S>> Search<'_, S, M> {
    /// The nearest hit of `ray` in `span` on a triangle of the mesh under node `root`, by
    /// `test` (or with [`Self::any`], the first found), its [`Intersection::part`] the
    /// triangle's index.
    #[inline(always)]
    pub(crate) fn run(
        &self,
        root: u32,
        ray: &Ray<S>,
        mut span: Span<S>,
        mut test: impl FnMut(&Triangle<S>, Span<S>) -> Option<Intersection<S>>,
    ) -> Option<Intersection<S>> {
        let half = S::ratio(1, 2);
        let mut reach = span.max * half;
        let mut mid = ray.at(reach);
        let mut found = None;
        // Each node taken puts at most its two children on: one more than the depth waits.
        let mut waiting: Vec<u32, { MAX_DEPTH + 1 }> = Vec::new();
        let _ = waiting.push(root);
        while let Some(index) = waiting.pop() {
            let Some(node) = self.meshes.node(index) else {
                continue;
            };
            S::note(Work::Node);
            if !node.meets(ray.dir, mid, reach, self.slack) {
                continue;
            }
            if node.right == 0 {
                for part in node.first..node.end {
                    let Some(triangle) = self
                        .meshes
                        .triangle(part)
                        .filter(|_| self.skip != Some(part))
                    else {
                        continue;
                    };
                    S::note(Work::Test);
                    if let Some(at) = test(&triangle, span) {
                        S::note(Work::Hit);
                        span.max = at.t;
                        found = Some(Intersection { part, ..at });
                        if self.any {
                            return found;
                        }
                        reach = span.max * half;
                        mid = ray.at(reach);
                    }
                }
            } else {
                // The child on the side the ray comes from first: its hits cut the other's.
                let along = match node.axis {
                    0 => ray.dir.x,
                    1 => ray.dir.y,
                    _ => ray.dir.z,
                };
                let (near, far) = if along < S::ZERO {
                    (node.right, index.saturating_add(1))
                } else {
                    (index.saturating_add(1), node.right)
                };
                let _ = waiting.push(far);
                let _ = waiting.push(near);
            }
        }
        found
    }
}
