//! [`SceneError`]: why a scene description cannot be built, and how to fix it.

crate::phase::declare_phase!(Some(crate::phase::Phase::Build));

use crate::scalar::FormatSet;
use crate::vec3::SHORTEST_DIRECTION;
use core::fmt;

/// The part of a scene description an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Item {
    /// The camera.
    Camera,
    /// The object at this index of [`crate::SceneDesc::objects`].
    Object(usize),
    /// The light at this index of [`crate::SceneDesc::lights`].
    Light(usize),
    /// A value of the scene as a whole (ambient light, background, `far`, depth).
    Scene,
}

impl fmt::Display for Item {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Camera => f.write_str("the camera"),
            Self::Object(i) => write!(f, "object {i}"),
            Self::Light(i) => write!(f, "light {i}"),
            Self::Scene => f.write_str("the scene"),
        }
    }
}

/// What to change in a scene so that a value fits a format, or a feature shows in it: the
/// advice of a refusal, which follows from what the value grows with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Remedy {
    /// The value grows with the world: a smaller `far`, objects nearer the eye.
    ShrinkWorld,
    /// The light a pixel adds up: dimmer lights, ambient light or background, a lower
    /// `max_depth`.
    LessLight,
    /// A refractive index.
    LowerIor,
    /// The image plane: a narrower field of view, a less elongated image.
    NarrowerView,
    /// Neighbouring pixels closer than the format can aim: a wider field of view, fewer
    /// pixels.
    WiderView,
    /// An image with more pixels on a side than the format can count.
    SmallerImage,
    /// A checkerboard's squares, against the world they cover.
    LargerSquares,
    /// A sphere too small or too far away for its test.
    LargerSphere,
    /// A triangle too thin to have an area at the format's resolution.
    FatterTriangle,
    /// A triangle too large for Möller–Trumbore's reciprocal of its determinant.
    SmallerTriangle,
    /// A triangle too small, or seen from too near, for its distance to resolve.
    LargerTriangle,
    /// The eye too near a surface.
    MoveEye,
    /// A lens whose tilt the format cannot resolve: so small an aperture, or so far a focus,
    /// that its rays meet off the focal plane.
    WiderAperture,
    /// A light too near a surface.
    MoveLight,
    /// A light too bright for a format's steps.
    DimLight,
    /// A plane so near the world's edge that the world cuts only a small disc from it.
    AwayFromTheEdge,
}

impl fmt::Display for Remedy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::ShrinkWorld => "shrink the scene (a smaller far, objects nearer the eye)",
            Self::LessLight => {
                "dim the lights, the ambient light or the background, or lower max_depth"
            }
            Self::LowerIor => "lower the ior",
            Self::NarrowerView => "narrow the field of view or make the image less elongated",
            Self::WiderView => "widen the field of view or render fewer pixels",
            Self::SmallerImage => "render fewer pixels on the longer side",
            Self::LargerSquares => "make the checker's squares larger",
            Self::LargerSphere => "make the sphere larger or bring it nearer the eye",
            Self::FatterTriangle => "move a corner away from the line through the other two",
            Self::SmallerTriangle => "split the triangle into smaller ones",
            Self::LargerTriangle => "make the triangle larger or look at it from farther away",
            Self::MoveEye => "move the eye away from the surface",
            Self::WiderAperture => {
                "open the aperture or focus nearer (or make the camera a pinhole: aperture = 0)"
            }
            Self::MoveLight => "move the light away from the surface",
            Self::DimLight => "dim the light",
            Self::AwayFromTheEdge => {
                "raise far well beyond the plane's distance from the eye, or bring the plane nearer"
            }
        })
    }
}

/// Why [`crate::Scene::build`] refused a description. Each variant's documentation says how
/// to fix the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum SceneError {
    /// A value is NaN or infinite. Give a finite number.
    NotFinite {
        /// Whose value.
        item: Item,
        /// Which value: its key in a scene file, under the item's table
        /// (`shape.sphere.radius`, `material.ior`).
        field: &'static str,
    },
    /// A value lies outside the interval it must lie in. Give one inside it.
    OutOfBounds {
        /// Whose value.
        item: Item,
        /// Which value: its key in a scene file, under the item's table
        /// (`shape.sphere.radius`, `material.ior`).
        field: &'static str,
        /// What it is.
        value: f32,
        /// What it must be, in words ("> 0", "in (0, 180)", ...).
        expected: &'static str,
    },
    /// A vector that must give a direction (a plane's normal, the camera's view direction or
    /// up, the sky's up) is too short to: no longer than f32's epsilon. Give it a direction.
    TooShort {
        /// Whose vector.
        item: Item,
        /// Which vector: its key in a scene file, under the item's table, or the difference
        /// of two (`look_at − eye`).
        field: &'static str,
        /// Its length.
        length: f64,
    },
    /// The three corners of a triangle lie on one line, so it has no area and no normal.
    /// Move a corner off the line through the other two, or leave the triangle out.
    DegenerateTriangle {
        /// Which object.
        item: Item,
    },
    /// A mesh's triangles or hierarchy are not what [`crate::shape::mesh::build_hierarchy`] makes
    /// ([`crate::MeshesDesc`]). Build the hierarchy again from the triangles.
    MalformedMesh {
        /// Which object (the scene, for the meshes' triangles as a whole).
        item: Item,
        /// What is wrong.
        what: &'static str,
    },
    /// The scene has meshes, and this build keeps none: its [`crate::Scene`]'s mesh storage is
    /// [`crate::mesh::NoMeshes`]. Build it with a storage that holds them
    /// ([`crate::mesh::MeshStorage`]).
    MeshesNotHeld,
    /// The camera's up vector is parallel to its view direction, so "up" on the image is
    /// undefined. Choose an up vector that is not along the line from eye to target.
    UpParallelToView,
    /// More objects or lights than this build holds (the capacities of [`crate::Scene`]).
    /// Model fewer, or, building the library yourself, raise the capacity.
    TooMany {
        /// "objects" or "lights".
        what: &'static str,
        /// How many the description has.
        count: usize,
        /// How many fit.
        capacity: usize,
    },
    /// `max_depth` needs a deeper ray stack than this build has. Lower `max_depth` (or,
    /// building the library yourself, raise the stack capacity to `max_depth + 1`).
    DepthExceedsStack {
        /// The requested depth.
        max_depth: u8,
        /// The ray stack's capacity.
        capacity: usize,
    },
    /// Part of an object or a light lies farther from the eye than `far`, the world's radius.
    /// Raise `far` or move the item closer.
    OutsideWorld {
        /// Which item.
        item: Item,
        /// Its farthest point's distance from the eye.
        distance: f64,
        /// The world's radius.
        far: f32,
    },
    /// The lens reaches a surface: some point within `aperture` of the eye is on it or behind
    /// it. Make the aperture smaller than the surface's distance from the eye, or move the eye
    /// away from it.
    LensTouches {
        /// Which object.
        object: usize,
        /// Its surface's distance from the eye.
        clearance: f64,
        /// The lens's radius.
        aperture: f32,
    },
    /// A value the tracer computes for this scene would leave the format's range. Use a
    /// format with a wider range (the message lists those that hold it), or change the scene
    /// as the [`Remedy`] says.
    OutOfRange {
        /// Whose computation.
        item: Item,
        /// Which value: a value of the description by its key in a scene file
        /// (`shape.sphere.center`), or one the tracer computes from it, in words.
        quantity: &'static str,
        /// The largest magnitude it reaches.
        value: f64,
        /// The format.
        format: &'static str,
        /// The format's largest magnitude.
        range: f64,
        /// What to change in the scene.
        remedy: Remedy,
        /// The formats whose range holds it.
        holds: FormatSet,
    },
    /// A feature of the scene is too small for the format to resolve: its shape would be lost
    /// to rounding. Use a finer format or a steadier method (the message names those that
    /// resolve it), or change the scene as the [`Remedy`] says.
    BelowResolution {
        /// Whose feature.
        item: Item,
        /// Which feature: a value of the description by its key in a scene file
        /// (`shape.plane.checker.size`), or one the tracer computes from it, in words.
        quantity: &'static str,
        /// Its size.
        value: f64,
        /// The format.
        format: &'static str,
        /// The smallest size the format resolves here.
        minimum: f64,
        /// What to change in the scene.
        remedy: Remedy,
        /// The formats that resolve it by the same methods.
        holds: FormatSet,
        /// A method that resolves it in this format, if one does, as (question, name): e.g.
        /// `("sphere", "stable")`.
        method: Option<(&'static str, &'static str)>,
    },
    /// The format has no such method (the fast roots are the 32-bit fixed formats'). Choose
    /// another method, or another format (for floats with approximate roots, `f32-approx`).
    MethodUnavailable {
        /// The method.
        method: &'static str,
        /// The format.
        format: &'static str,
    },
    /// An image size outside 1..=[`crate::MAX_IMAGE_SIDE`] on a side.
    ImageSize {
        /// The requested width.
        width: u32,
        /// The requested height.
        height: u32,
    },
}

impl SceneError {
    /// The part of the description the error is about, if it is about one.
    pub fn item(&self) -> Option<Item> {
        match *self {
            Self::NotFinite { item, .. }
            | Self::OutOfBounds { item, .. }
            | Self::TooShort { item, .. }
            | Self::DegenerateTriangle { item }
            | Self::MalformedMesh { item, .. }
            | Self::OutsideWorld { item, .. }
            | Self::OutOfRange { item, .. }
            | Self::BelowResolution { item, .. } => Some(item),
            Self::UpParallelToView | Self::LensTouches { .. } => Some(Item::Camera),
            Self::DepthExceedsStack { .. } => Some(Item::Scene),
            Self::TooMany { .. }
            | Self::MeshesNotHeld
            | Self::MethodUnavailable { .. }
            | Self::ImageSize { .. } => None,
        }
    }

    /// The value of the item the error is about, where it is one: its key in a scene file under
    /// the item's table, at the start of the text (`material.reflection + material.transmission`
    /// begins with `material.reflection`). A value the tracer computes is named in words, and
    /// starts with no key of the item.
    pub fn field(&self) -> Option<&'static str> {
        match *self {
            Self::NotFinite { field, .. }
            | Self::OutOfBounds { field, .. }
            | Self::TooShort { field, .. } => Some(field),
            Self::OutOfRange { quantity, .. } | Self::BelowResolution { quantity, .. } => {
                Some(quantity)
            }
            Self::DegenerateTriangle { .. } => Some("shape.triangle.vertices"),
            Self::UpParallelToView => Some("up"),
            Self::LensTouches { .. } => Some("aperture"),
            Self::DepthExceedsStack { .. } => Some("max_depth"),
            Self::TooMany { .. }
            | Self::MeshesNotHeld
            | Self::MalformedMesh { .. }
            | Self::OutsideWorld { .. }
            | Self::MethodUnavailable { .. }
            | Self::ImageSize { .. } => None,
        }
    }
}

/// "; formats that hold it: a b c", when there are any.
fn formats(f: &mut fmt::Formatter<'_>, holds: FormatSet, verb: &str) -> fmt::Result {
    if !holds.is_empty() {
        write!(f, "; formats that {verb} it:")?;
        for format in holds.iter() {
            write!(f, " {}", format.name)?;
        }
    }
    Ok(())
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            SceneError::NotFinite { item, field } => {
                write!(
                    f,
                    "{item}: {field} is not a finite number; give a finite value"
                )
            }
            SceneError::TooShort {
                item,
                field,
                length: 0.0,
            } => write!(f, "{item}: {field} has zero length; give it a direction"),
            SceneError::TooShort {
                item,
                field,
                length,
            } => write!(
                f,
                "{item}: {field} is {length:.3e} long, too short to give a direction (it must be \
                 longer than f32's epsilon, {SHORTEST_DIRECTION:.3e}); give it a direction of \
                 length 1"
            ),
            SceneError::DegenerateTriangle { item } => write!(
                f,
                "{item}: the triangle's corners lie on one line, so it has no area; move a \
                 corner off that line or leave the triangle out"
            ),
            SceneError::MalformedMesh { item, what } => write!(
                f,
                "{item}: the mesh is malformed: {what}; build its hierarchy again from its \
                 triangles (obscura::mesh::build_hierarchy)"
            ),
            SceneError::MeshesNotHeld => f.write_str(
                "the scene has meshes, and this build keeps none: give its Scene a mesh storage \
                 (obscura::mesh::MeshStorage)",
            ),
            SceneError::UpParallelToView => f.write_str(
                "the camera: the up vector is parallel to the view direction; choose an up \
                 vector that does not point along the line from eye to look_at",
            ),
            SceneError::TooMany {
                what,
                count,
                capacity,
            } => write!(
                f,
                "the scene has {count} {what}, more than the {capacity} this build holds; \
                 model fewer {what}"
            ),
            SceneError::DepthExceedsStack {
                max_depth,
                capacity,
            } => write!(
                f,
                "max_depth {max_depth} needs a ray stack of {}, but this build holds {capacity}; \
                 lower max_depth to {}",
                usize::from(max_depth) + 1,
                capacity.saturating_sub(1)
            ),
            SceneError::MethodUnavailable { method, format } => write!(
                f,
                "{method} is not a method of {format}: the fast roots belong to the 32-bit fixed \
                 formats (i16f16, i20f12); use sqrt=exact, or the f32-approx format for floats \
                 with approximate roots"
            ),
            SceneError::ImageSize { width, height } => write!(
                f,
                "an image of {width}x{height} pixels: each side must be 1 to {}",
                crate::MAX_IMAGE_SIDE
            ),
            SceneError::OutOfBounds {
                item,
                field,
                value,
                expected,
            } => {
                write!(
                    f,
                    "{item}: {field} is {}, but it must be {expected}",
                    Number(value)
                )
            }
            SceneError::LensTouches {
                object,
                clearance,
                aperture,
            } => {
                write!(
                    f,
                    "the camera: the lens of aperture {} reaches the surface of object \
                     {object}, {:.4} from the eye; make the aperture smaller than the \
                     surface's distance from the eye, or move the eye away from it",
                    Number(aperture),
                    Number(clearance)
                )
            }
            SceneError::OutsideWorld {
                item,
                distance,
                far,
            } => {
                write!(
                    f,
                    "{item} reaches {:.4} from the eye, beyond the world radius far = {}; raise \
                     far or move it closer",
                    Number(distance),
                    Number(far)
                )
            }
            SceneError::OutOfRange {
                item,
                quantity,
                value,
                format,
                range,
                remedy,
                holds,
            } => {
                write!(
                    f,
                    "{item}: {quantity} reaches {value:.6e}, beyond {format}'s range of \
                     ±{range:.6e}"
                )?;
                formats(f, holds, "hold")?;
                write!(f, "; or {remedy}")
            }
            SceneError::BelowResolution {
                item,
                quantity,
                value,
                format,
                minimum,
                remedy,
                holds,
                method,
            } => {
                write!(
                    f,
                    "{item}: {quantity} is {value:.3e}, below the {minimum:.3e} that {format} \
                     resolves"
                )?;
                formats(f, holds, "resolve")?;
                if let Some((question, name)) = method {
                    write!(f, "; {question}={name} resolves it in {format}")?;
                }
                write!(f, "; or {remedy}")
            }
        }
    }
}

impl core::error::Error for SceneError {}

/// A number as a message prints it: as written (to the precision asked, if any) where it is of
/// everyday size, in scientific notation where it is huge or tiny, so that an aperture of 10³⁰
/// is not 31 digits.
struct Number<T>(T);

/// The magnitudes a message writes out in full; others in scientific notation.
const EVERYDAY: core::ops::Range<f64> = 1e-4..1e6;

impl<T: Copy + Into<f64> + fmt::Display + fmt::LowerExp> fmt::Display for Number<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (x, magnitude) = (self.0, self.0.into().abs());
        let everyday = magnitude == 0.0 || !magnitude.is_finite() || EVERYDAY.contains(&magnitude);
        match (everyday, f.precision()) {
            (true, Some(digits)) => write!(f, "{x:.digits$}"),
            (true, None) => write!(f, "{x}"),
            (false, _) => write!(f, "{x:.3e}"),
        }
    }
}
