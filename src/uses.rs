//! [`Uses`]: what of the tracer a scene uses — its kinds of shape, its methods, and the
//! features beyond a pinhole's one ray per pixel and point lights — as a set of bits.
//!
//! A scene's type carries the set its tracer may use ([`crate::Scene`]'s [`Parts`],
//! [`Everything`] unless said), and the tracer tests it before each part: a build whose scenes
//! use less (a firmware, from [`crate::Scene::from_words`]) leaves the rest out of its image. A scene of a
//! type comes only from a build (which may use everything) or from words whose scene uses no
//! more than the type's set, so nothing the scene needs is ever left out.

crate::phase::declare_phase!(Some(crate::phase::Phase::Build));

use crate::methods::{
    BiasMethod, MethodName, Methods, RayMethod, RootMethod, SphereMethod, TriangleMethod,
};
use core::fmt;

/// The parts of the tracer a scene's type carries: a type whose constant [`Self::USES`] is the
/// set, so that a tracer of fewer parts is a type of its own and its build leaves the rest out.
/// A build script's proven scene (`obscura_scene::build`) defines one of exactly its scene's
/// parts; a scene built at run time takes [`Everything`].
pub trait Parts: Copy + fmt::Debug + PartialEq + Eq + 'static {
    /// The parts.
    const USES: Uses;
}

/// Every part of the tracer: what a scene built at run time may use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Everything;

impl Parts for Everything {
    const USES: Uses = Uses::EVERYTHING;
}

/// A set of the tracer's parts: its kinds of shape, its methods, and the features beyond a
/// pinhole's one ray per pixel and point lights. A scene's type carries one ([`Parts`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Uses(u32);

/// A family of methods and the first of its bits: its variants' bits follow in the order of
/// [`MethodName::ALL`].
pub(crate) trait Family: MethodName + PartialEq {
    const FIRST: u32;
}

impl Family for SphereMethod {
    const FIRST: u32 = 8;
}
impl Family for TriangleMethod {
    const FIRST: u32 = 10;
}
impl Family for RootMethod {
    const FIRST: u32 = 13;
}
impl Family for RayMethod {
    const FIRST: u32 = 15;
}
impl Family for BiasMethod {
    const FIRST: u32 = 17;
}

/// The parts with a name of their own, in the order [`Uses`]'s `Display` lists them.
const PARTS: [(Uses, &str); 7] = [
    (Uses::SPHERES, "spheres"),
    (Uses::PLANES, "planes"),
    (Uses::TRIANGLES, "triangles"),
    (Uses::MESHES, "meshes"),
    (Uses::AREA_LIGHTS, "area lights"),
    (Uses::SAMPLES, "several rays per pixel"),
    (Uses::LENS, "a lens"),
];

impl Uses {
    /// Nothing.
    pub const NOTHING: Self = Self(0);
    /// Every part: what a scene built at run time may use.
    pub const EVERYTHING: Self = Self(u32::MAX);
    /// Spheres.
    pub const SPHERES: Self = Self(1);
    /// Planes.
    pub const PLANES: Self = Self(1 << 1);
    /// Triangles.
    pub const TRIANGLES: Self = Self(1 << 2);
    /// Lights with a radius, tested by several shadow rays.
    pub const AREA_LIGHTS: Self = Self(1 << 3);
    /// Several rays per pixel.
    pub const SAMPLES: Self = Self(1 << 4);
    /// A camera's lens.
    pub const LENS: Self = Self(1 << 5);
    /// Meshes of triangles, through their hierarchies.
    pub const MESHES: Self = Self(1 << 6);

    /// The set whose bits are `bits` ([`Self::bits`]).
    #[must_use]
    pub const fn from_bits(bits: u32) -> Self {
        Self(bits)
    }

    /// The set's bits: what a scene's type carries.
    #[must_use]
    pub const fn bits(self) -> u32 {
        self.0
    }

    /// Both sets' parts.
    #[must_use]
    pub const fn union(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }

    /// The parts of `other` that are not in the set.
    #[must_use]
    pub const fn missing(self, other: Self) -> Self {
        Self(other.0 & !self.0)
    }

    /// Whether every part of `other` is in the set.
    #[must_use]
    pub const fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }

    /// `methods`' five choices.
    #[must_use]
    pub fn methods(methods: &Methods) -> Self {
        let Methods {
            sphere,
            triangle,
            roots,
            rays,
            bias,
        } = *methods;
        Self::method(sphere)
            .union(Self::method(triangle))
            .union(Self::method(roots))
            .union(Self::method(rays))
            .union(Self::method(bias))
    }

    /// The bit of one method.
    pub(crate) fn method<M: Family>(method: M) -> Self {
        let place = M::ALL.iter().position(|(m, _)| *m == method);
        // Every variant is in its ALL, and no family has more than 3.
        place.map_or(Self::NOTHING, |p| Self(1 << (M::FIRST + p as u32)))
    }

    /// The one method of family `M` the set holds, if it holds just one.
    #[inline(always)]
    pub(crate) fn only<M: Family>(self) -> Option<M> {
        let held = (self.0 >> M::FIRST) & ((1 << M::ALL.len()) - 1);
        if held.count_ones() == 1 {
            M::ALL.get(held.trailing_zeros() as usize).map(|(m, _)| *m)
        } else {
            None
        }
    }

    /// `methods` as a tracer of this set computes them: each choice of which the set holds one
    /// method is that method, a constant, so that the others drop out of the build; the rest
    /// as given.
    #[inline(always)]
    #[must_use]
    pub(crate) fn narrow(self, methods: &Methods) -> Methods {
        Methods {
            sphere: self.only().unwrap_or(methods.sphere),
            triangle: self.only().unwrap_or(methods.triangle),
            roots: self.only().unwrap_or(methods.roots),
            rays: self.only().unwrap_or(methods.rays),
            bias: self.only().unwrap_or(methods.bias),
        }
    }
}

/// The parts with a name, and the methods by their names: `spheres, planes; quadratic, exact,
/// per-pixel, epsilon` (of each family of methods only those the set holds).
impl fmt::Display for Uses {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if *self == Self::EVERYTHING {
            return f.write_str("everything");
        }
        let mut separator = "";
        for (part, name) in PARTS {
            if self.contains(part) {
                write!(f, "{separator}{name}")?;
                separator = ", ";
            }
        }
        separator = "; ";
        let mut methods = |names: &mut dyn Iterator<Item = (bool, &str)>| {
            for (held, name) in names {
                if held {
                    write!(f, "{separator}{name}")?;
                    separator = ", ";
                }
            }
            Ok(())
        };
        methods(&mut held::<SphereMethod>(*self))?;
        methods(&mut held::<TriangleMethod>(*self))?;
        methods(&mut held::<RootMethod>(*self))?;
        methods(&mut held::<RayMethod>(*self))?;
        methods(&mut held::<BiasMethod>(*self))
    }
}

/// Whether `uses` holds each method of family `M`, with its name.
fn held<M: Family>(uses: Uses) -> impl Iterator<Item = (bool, &'static str)> {
    M::ALL
        .iter()
        .map(move |&(m, name)| (uses.contains(Uses::method(m)), name))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_family_the_set_holds_one_method_of_is_that_method() {
        let lecture = Uses::methods(&Methods::LECTURE);
        let stable = Methods {
            sphere: SphereMethod::Stable,
            ..Methods::LECTURE
        };
        // Every choice held alone: the lecture's methods whatever the scene's say.
        assert_eq!(lecture.narrow(&stable), Methods::LECTURE);
        // Both sphere methods held: the scene's.
        let both = lecture.union(Uses::methods(&stable));
        assert_eq!(both.narrow(&stable), stable);
        assert_eq!(both.narrow(&Methods::LECTURE), Methods::LECTURE);
        assert_eq!(Uses::EVERYTHING.narrow(&stable), stable);
    }

    #[test]
    fn the_bits_of_the_families_do_not_overlap() {
        let mut seen = Uses::NOTHING;
        for (part, _) in PARTS {
            assert!(!seen.contains(part) && part != Uses::NOTHING);
            seen = seen.union(part);
        }
        for methods in Methods::LECTURE.variants() {
            let bits = Uses::methods(&methods);
            assert_eq!(bits.bits().count_ones(), 5, "{methods:?}");
            assert_eq!(seen.bits() & bits.bits(), 0);
        }
        let all_methods = Methods::LECTURE
            .variants()
            .iter()
            .fold(Uses::NOTHING, |all, m| all.union(Uses::methods(m)));
        assert_eq!(all_methods.bits().count_ones(), 11);
    }

    #[test]
    fn a_set_names_its_parts_and_methods() {
        let uses = Uses::SPHERES
            .union(Uses::PLANES)
            .union(Uses::methods(&Methods::LECTURE));
        assert_eq!(
            uses.to_string(),
            "spheres, planes; quadratic, cramer, exact, per-pixel, epsilon"
        );
        assert_eq!(Uses::EVERYTHING.to_string(), "everything");
    }
}
