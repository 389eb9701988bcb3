//! [`Ray`]: a half-line r(t) = origin + t·dir with a unit direction, so that t is a distance.

crate::phase::declare_phase!(None);

use crate::scalar::Scalar;
use crate::vec3::Vec3;

/// A ray. `dir` has unit length, so the parameter `t` of a hit is its distance from `origin`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray<S> {
    /// Where the ray starts.
    pub origin: Vec3<S>,
    /// Where it goes: a unit vector.
    pub dir: Vec3<S>,
}

impl<S: Scalar> Ray<S> {
    /// A ray from `origin` along `dir`, which must already have unit length.
    #[inline]
    #[must_use]
    pub const fn new(origin: Vec3<S>, dir: Vec3<S>) -> Self {
        Self { origin, dir }
    }

    /// The point r(t).
    #[inline]
    #[must_use]
    pub fn at(&self, t: S) -> Vec3<S> {
        self.origin.add_scaled(self.dir, t)
    }
}

/// The interval of ray parameters a hit must fall in: `min < t < max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span<S> {
    /// Hits at or before this distance are ignored: the format's epsilon.
    pub min: S,
    /// Hits at or beyond this distance are ignored: the nearest hit so far, or the world's end.
    pub max: S,
}

impl<S: Scalar> Span<S> {
    /// Whether `t` lies strictly inside the span.
    #[inline(always)]
    #[must_use]
    pub fn contains(&self, t: S) -> bool {
        t > self.min && t < self.max
    }
}
