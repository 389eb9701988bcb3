//! Helpers shared by the unit tests.

use crate::camera::Camera;
use crate::methods::Methods;
use crate::ray::Span;
use crate::scalar::Scalar;
use crate::scene::Scene;
use crate::scenes::BUILT_IN;
use crate::vec3::Vec3;

/// Runs a block once per number format, with `$s` naming the format.
macro_rules! for_each_format {
    ($s:ident, $body:block) => {{
        {
            type $s = crate::scalar::I16F16;
            $body
        }
        {
            type $s = crate::scalar::I32F32;
            $body
        }
        {
            type $s = f32;
            $body
        }
        {
            type $s = f64;
            $body
        }
    }};
}
pub(crate) use for_each_format;

/// A vector from `f64` coordinates that fit every format.
pub(crate) fn v<S: Scalar>(x: f64, y: f64, z: f64) -> Vec3<S> {
    Vec3::from_f64([x, y, z]).expect("test values fit every format")
}

/// The span (1/1000, max): a small positive epsilon that every format resolves.
pub(crate) fn span<S: Scalar>(max: f64) -> Span<S> {
    Span {
        min: S::ratio(1, 1000),
        max: S::from_f64(max).expect("test values fit"),
    }
}

/// Asserts |got − want| ≤ tol, naming the format.
#[track_caller]
pub(crate) fn assert_close<S: Scalar>(got: S, want: f64, tol: f64) {
    let got = got.to_f64();
    assert!(
        (got - want).abs() <= tol,
        "{}: got {got}, want {want} ± {tol}",
        S::NAME
    );
}

/// Runs `check` on every built-in scene that format `S` holds, by the lecture's methods and
/// each variant that changes one of them, with room for 8 objects, 4 lights and 8 rays, and its
/// camera at `side` × `side` pixels; `check` gets the scene's name and the methods too.
pub(crate) fn each_built_in_scene<S: Scalar>(
    side: u32,
    mut check: impl FnMut(&str, Methods, &Scene<S, 8, 4, 8>, &Camera<S>),
) {
    for built_in in &BUILT_IN {
        for methods in Methods::LECTURE.variants() {
            let Ok(scene) = Scene::<S, 8, 4, 8>::build_with(&built_in.desc, methods) else {
                continue;
            };
            let Ok(camera) = scene.camera(side, side) else {
                continue;
            };
            check(built_in.name, methods, &scene, &camera);
        }
    }
}

/// A check generic over the number format, for [`for_every_format`].
pub(crate) trait FormatCheck {
    /// Runs the check in format `S`.
    fn check<S: Scalar>(&self);
}

/// Runs `check` in every format of [`crate::scalar::FORMATS`] (where [`for_each_format`] takes
/// four that stand for them).
pub(crate) fn for_every_format(check: &impl FormatCheck) {
    macro_rules! each {
        (fixed { $($f:ident => $raw:ident,)* } float { $($v:ident => $t:ty,)* }) => {
            $(check.check::<crate::scalar::Fx<fixed::types::$raw>>();)*
            $(check.check::<$t>();)*
        };
    }
    crate::for_each_format!(each);
}
