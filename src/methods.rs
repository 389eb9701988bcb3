//! The numerical methods the tracer can use where the literature says precision breaks, each
//! chosen per render: [`Methods`] holds one choice per question.

crate::phase::declare_phase!(Some(crate::phase::Phase::Arithmetic));

use crate::scalar::Scalar;
use core::fmt;

/// How a ray meets a sphere.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SphereMethod {
    /// The lecture's quadratic: t = −b ± √(b² − c) with b = d·(o − c), c = |o − c|² − r².
    /// b² − c cancels catastrophically for a small or distant sphere.
    #[default]
    Quadratic,
    /// Haines et al. (Ray Tracing Gems, ch. 7): the discriminant as r² − |f − (f·d)d|², the
    /// squared distance of the ray from the centre, and the near root through
    /// q = −b − sign(b)·√Δ and c/q, neither of which cancels.
    Stable,
}

/// How a ray meets a triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TriangleMethod {
    /// The lecture's: Cramer's rule on (−d, e1, e2), three determinants over a fourth.
    #[default]
    Cramer,
    /// Möller and Trumbore (1997): the same system with shared cross products and one
    /// reciprocal of the determinant.
    MollerTrumbore,
    /// Woop, Benthin and Wald (2013): edge functions in a ray-aligned frame whose signs are
    /// exact (in double-width integers for fixed point), so no ray slips between two triangles
    /// that share an edge.
    Watertight,
}

/// How square roots, reciprocal square roots and quotients are taken.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RootMethod {
    /// Exactly (fixed point: the exact root and the truncated quotient).
    #[default]
    Exact,
    /// The 32-bit fixed formats' fast approximations: one Newton step instead of two, and
    /// quotients as products with a reciprocal, about 14 bits each. (For floats with
    /// approximations choose the `f32-approx` format.)
    Approx,
}

/// How primary rays are generated along a scanline.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RayMethod {
    /// Each pixel's point on the image plane from one exact ratio.
    #[default]
    PerPixel,
    /// The point stepped by a constant increment along the row: one addition per pixel, and
    /// the increment's rounding accumulates across the row.
    Stepped,
}

/// How a secondary ray avoids hitting the surface it leaves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum BiasMethod {
    /// It starts a small offset (derived from the format) off the surface, and hits nearer
    /// than that offset are ignored.
    #[default]
    Epsilon,
    /// It starts on the surface and ignores the primitive it leaves, which is exact here: a
    /// ray leaving a plane, a triangle or the outside of a sphere cannot meet it again, and one
    /// entering a sphere meets it only where it leaves.
    Exclude,
}

/// One choice of every method.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Methods {
    /// Ray–sphere.
    pub sphere: SphereMethod,
    /// Ray–triangle.
    pub triangle: TriangleMethod,
    /// Roots and quotients.
    pub roots: RootMethod,
    /// Primary rays.
    pub rays: RayMethod,
    /// Self-intersection.
    pub bias: BiasMethod,
}

impl Methods {
    /// The lecture's methods: the quadratic, Cramer's rule, exact roots, a ray per pixel, an
    /// epsilon offset. What [`crate::Scene::build`] uses.
    pub const LECTURE: Self = Self {
        sphere: SphereMethod::Quadratic,
        triangle: TriangleMethod::Cramer,
        roots: RootMethod::Exact,
        rays: RayMethod::PerPixel,
        bias: BiasMethod::Epsilon,
    };
}

impl Methods {
    /// `self` and each variant of it that changes one method: what the speed–accuracy chart
    /// compares. Some variants can equal `self` (when `self` already uses that method).
    #[must_use]
    pub const fn variants(self) -> [Self; 7] {
        [
            self,
            Self {
                sphere: SphereMethod::Stable,
                ..self
            },
            Self {
                triangle: TriangleMethod::MollerTrumbore,
                ..self
            },
            Self {
                triangle: TriangleMethod::Watertight,
                ..self
            },
            Self {
                roots: RootMethod::Approx,
                ..self
            },
            Self {
                rays: RayMethod::Stepped,
                ..self
            },
            Self {
                bias: BiasMethod::Exclude,
                ..self
            },
        ]
    }

    /// Whether these methods tell a scene apart from `base`'s in format `S`: a triangle method
    /// matters only with triangles, and fast roots exist only in the 32-bit fixed formats.
    #[must_use]
    pub fn matter<S: Scalar>(&self, base: &Self, has_triangles: bool) -> bool {
        let triangle_moot = self.triangle != base.triangle && !has_triangles;
        let roots_moot = self.roots == RootMethod::Approx && !S::FAST_ROOTS;
        !triangle_moot && !roots_moot
    }
}

impl RootMethod {
    /// √x.
    #[inline(always)]
    #[track_caller]
    pub fn sqrt<S: Scalar>(self, x: S) -> S {
        match self {
            Self::Exact => x.sqrt(),
            Self::Approx => x.sqrt_approx(),
        }
    }

    /// 1/√x.
    #[inline(always)]
    #[track_caller]
    pub fn rsqrt<S: Scalar>(self, x: S) -> S {
        match self {
            Self::Exact => x.rsqrt(),
            Self::Approx => x.rsqrt_approx(),
        }
    }

    /// a/b.
    #[inline(always)]
    #[track_caller]
    pub fn div<S: Scalar>(self, a: S, b: S) -> S {
        match self {
            Self::Exact => a / b,
            Self::Approx => a.div_approx(b),
        }
    }
}

/// Names for the command line and for reports, one per variant.
pub trait MethodName: Sized + Copy + 'static {
    /// Every variant with its name.
    const ALL: &'static [(Self, &'static str)];

    /// The variant's name.
    fn name(self) -> &'static str
    where
        Self: PartialEq,
    {
        Self::ALL
            .iter()
            .find(|(m, _)| *m == self)
            .map_or("?", |(_, name)| name)
    }

    /// The variant called `name`.
    fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().find(|(_, n)| *n == name).map(|(m, _)| *m)
    }
}

impl MethodName for SphereMethod {
    const ALL: &'static [(Self, &'static str)] =
        &[(Self::Quadratic, "quadratic"), (Self::Stable, "stable")];
}

impl MethodName for TriangleMethod {
    const ALL: &'static [(Self, &'static str)] = &[
        (Self::Cramer, "cramer"),
        (Self::MollerTrumbore, "moller-trumbore"),
        (Self::Watertight, "watertight"),
    ];
}

impl MethodName for RootMethod {
    const ALL: &'static [(Self, &'static str)] =
        &[(Self::Exact, "exact"), (Self::Approx, "approx")];
}

impl MethodName for RayMethod {
    const ALL: &'static [(Self, &'static str)] =
        &[(Self::PerPixel, "per-pixel"), (Self::Stepped, "stepped")];
}

impl MethodName for BiasMethod {
    const ALL: &'static [(Self, &'static str)] =
        &[(Self::Epsilon, "epsilon"), (Self::Exclude, "exclude")];
}

impl Methods {
    /// Each method that differs from the lecture's, as (question, name): `("sphere", "stable")`.
    pub fn changes(&self) -> impl Iterator<Item = (&'static str, &'static str)> {
        let base = Self::LECTURE;
        [
            (self.sphere != base.sphere, "sphere", self.sphere.name()),
            (
                self.triangle != base.triangle,
                "triangle",
                self.triangle.name(),
            ),
            (self.roots != base.roots, "sqrt", self.roots.name()),
            (self.rays != base.rays, "rays", self.rays.name()),
            (self.bias != base.bias, "bias", self.bias.name()),
        ]
        .into_iter()
        .filter(|&(differs, _, _)| differs)
        .map(|(_, question, name)| (question, name))
    }
}

/// The one spelling of a choice of methods, everywhere (the command line's reports, the
/// firmware's configuration, its reports over QEMU, frame files, the chart's CSV): `lecture`
/// for the lecture's own, otherwise each method that differs from it, in the order sphere,
/// triangle, sqrt, rays, bias: `sphere=stable,bias=exclude`. [`core::str::FromStr`] reads it
/// back.
impl fmt::Display for Methods {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut changes = self.changes().peekable();
        if changes.peek().is_none() {
            return f.write_str("lecture");
        }
        for (i, (question, name)) in changes.enumerate() {
            let separator = if i == 0 { "" } else { "," };
            write!(f, "{separator}{question}={name}")?;
        }
        Ok(())
    }
}

/// Methods spelled as their [`fmt::Display`] spells them (`lecture`, `sphere=stable,bias=exclude`),
/// or with the lecture's own spelled out too, commas or spaces between them; nothing is the
/// lecture's. Each question at most once.
impl core::str::FromStr for Methods {
    type Err = ParseMethodsError;

    fn from_str(text: &str) -> Result<Self, ParseMethodsError> {
        let mut methods = Self::LECTURE;
        let mut seen = [false; 5];
        for choice in text
            .split([',', ' '])
            .filter(|s| !s.is_empty() && *s != "lecture")
        {
            let (question, name) = choice
                .split_once('=')
                .ok_or(ParseMethodsError::NotAChoice)?;
            let (index, known) = match question {
                "sphere" => (0, set(&mut methods.sphere, name)),
                "triangle" => (1, set(&mut methods.triangle, name)),
                "sqrt" => (2, set(&mut methods.roots, name)),
                "rays" => (3, set(&mut methods.rays, name)),
                "bias" => (4, set(&mut methods.bias, name)),
                _ => return Err(ParseMethodsError::UnknownQuestion),
            };
            let (Some(&asked), Some(seen)) = (QUESTIONS.get(index), seen.get_mut(index)) else {
                return Err(ParseMethodsError::UnknownQuestion);
            };
            if !known {
                return Err(ParseMethodsError::UnknownMethod(asked));
            }
            if core::mem::replace(seen, true) {
                return Err(ParseMethodsError::Twice(asked.0));
            }
        }
        Ok(methods)
    }
}

/// Each question a method answers, with the names of its answers.
const QUESTIONS: [(&str, &str); 5] = [
    ("sphere", "quadratic or stable"),
    ("triangle", "cramer, moller-trumbore or watertight"),
    ("sqrt", "exact or approx"),
    ("rays", "per-pixel or stepped"),
    ("bias", "epsilon or exclude"),
];

/// Sets `method` to the one called `name`; whether there is one.
fn set<M: MethodName + PartialEq>(method: &mut M, name: &str) -> bool {
    M::from_name(name).map(|m| *method = m).is_some()
}

/// Why a text is not a choice of methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParseMethodsError {
    /// A choice without `=`.
    NotAChoice,
    /// A question other than sphere, triangle, sqrt, rays and bias.
    UnknownQuestion,
    /// An answer the question does not have: the question and its answers.
    UnknownMethod((&'static str, &'static str)),
    /// A question answered twice.
    Twice(&'static str),
}

impl fmt::Display for ParseMethodsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotAChoice => {
                f.write_str("methods are written question=method, e.g. sphere=stable,bias=exclude")
            }
            Self::UnknownQuestion => {
                f.write_str("the questions are sphere, triangle, sqrt, rays and bias")
            }
            Self::UnknownMethod((question, answers)) => {
                write!(f, "the {question} method is {answers}")
            }
            Self::Twice(question) => write!(f, "the {question} method is chosen twice"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn methods_read_back_as_they_are_written() {
        for methods in Methods::LECTURE.variants() {
            let written = methods.to_string();
            assert_eq!(written.parse::<Methods>(), Ok(methods), "{written}");
        }
        let stable = Methods {
            sphere: SphereMethod::Stable,
            bias: BiasMethod::Exclude,
            ..Methods::LECTURE
        };
        assert_eq!("sphere=stable,bias=exclude".parse(), Ok(stable));
        assert_eq!(stable.to_string(), "sphere=stable,bias=exclude");
        assert_eq!(Methods::LECTURE.to_string(), "lecture");
        assert_eq!(
            "sphere=stable triangle=cramer bias=exclude".parse(),
            Ok(stable)
        );
        assert_eq!("lecture".parse(), Ok(Methods::LECTURE));
        assert_eq!("".parse(), Ok(Methods::LECTURE));
        assert_eq!(
            "sphere".parse::<Methods>(),
            Err(ParseMethodsError::NotAChoice)
        );
        assert_eq!(
            "colour=red".parse::<Methods>(),
            Err(ParseMethodsError::UnknownQuestion)
        );
        assert_eq!(
            "rays=sideways".parse::<Methods>(),
            Err(ParseMethodsError::UnknownMethod(QUESTIONS[3]))
        );
        assert_eq!(
            "bias=exclude bias=epsilon".parse::<Methods>(),
            Err(ParseMethodsError::Twice("bias"))
        );
    }

    fn round_trip<M: MethodName + PartialEq + fmt::Debug>() {
        for &(method, name) in M::ALL {
            assert_eq!(method.name(), name);
            assert_eq!(M::from_name(name), Some(method));
        }
        assert_eq!(M::from_name("no such method"), None);
    }

    #[test]
    fn every_method_has_a_name_that_names_it_back() {
        round_trip::<SphereMethod>();
        round_trip::<TriangleMethod>();
        round_trip::<RootMethod>();
        round_trip::<RayMethod>();
        round_trip::<BiasMethod>();
    }

    #[test]
    fn variants_change_one_method_each() {
        let variants = Methods::LECTURE.variants();
        assert_eq!(variants[0], Methods::LECTURE);
        for variant in &variants[1..] {
            let changed = [
                variant.sphere != Methods::LECTURE.sphere,
                variant.triangle != Methods::LECTURE.triangle,
                variant.roots != Methods::LECTURE.roots,
                variant.rays != Methods::LECTURE.rays,
                variant.bias != Methods::LECTURE.bias,
            ];
            assert_eq!(changed.iter().filter(|&&c| c).count(), 1, "{variant}");
        }
        let watertight = Methods {
            triangle: TriangleMethod::Watertight,
            ..Methods::LECTURE
        };
        assert!(!watertight.matter::<f32>(&Methods::LECTURE, false));
        assert!(watertight.matter::<f32>(&Methods::LECTURE, true));
        let approx = Methods {
            roots: RootMethod::Approx,
            ..Methods::LECTURE
        };
        assert!(approx.matter::<crate::I16F16>(&Methods::LECTURE, false));
        assert!(!approx.matter::<f32>(&Methods::LECTURE, false));
    }

    #[test]
    fn the_lecture_is_the_default() {
        assert_eq!(Methods::default(), Methods::LECTURE);
        assert_eq!(Methods::LECTURE.to_string(), "lecture");
    }
}
