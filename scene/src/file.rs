//! The scenes obscura takes: a built-in one by name, or a TOML scene file (see
//! `host/scenes/` and the book's "Scene files", `docs/scene-files.md`). A file is read (up to [`MAX_FILE_BYTES`]),
//! parsed and checked for vectors of three here; the core's scene build then checks what it
//! says, and [`NamedScene::locate`] points its refusals at the file's line and column.

use crate::animation::AnimationError;
use crate::mesh_file;
use crate::meshes::OwnedMeshes;
use crate::object::{FileObject, FileShape};
use crate::owned::OwnedScene;
use anyhow::{Context, Result, bail};
use obscura::mesh::HierarchyError;
use obscura::{Item, SceneError, scenes};
use obscura::{ObjectDesc, ShapeDesc};
use std::fmt;
use std::io::Read;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// The largest scene file read: far beyond a scene the core holds (a full one takes a few
/// KiB), small enough that a wrong file is refused before it is parsed.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// What joins a camera path's name and a frame's number in the frame's name.
const FRAME: &str = "-frame-";

/// Where `name` is a camera path's frame's (`NAME-frame-K`, [`NamedScene::at_frame`]): the
/// path's name and the frame.
#[must_use]
pub fn path_frame(name: &str) -> Option<(&str, u16)> {
    let (path, frame) = name.rsplit_once(FRAME)?;
    Some((path, frame.parse().ok()?))
}

/// A scene and what to call it.
#[derive(Clone, Debug)]
pub struct NamedScene {
    /// The built-in scene's name, or the file's stem.
    pub name: String,
    /// The description.
    pub scene: OwnedScene,
    /// The file it was read from, if it was.
    source: Option<Source>,
}

/// A scene file's path and text.
#[derive(Clone, Debug)]
struct Source {
    path: PathBuf,
    text: String,
}

/// A place in a scene file: what an error there is about. Its `Display` is `file:line:column`;
/// [`Located::excerpt`] shows the line.
#[derive(Debug)]
pub struct Located {
    path: PathBuf,
    /// 1-based.
    line: usize,
    /// 1-based, in characters.
    column: usize,
    /// The line's text.
    text: String,
    /// How many characters of the line the place spans (at least 1).
    width: usize,
}

impl Located {
    /// The place in `text` at byte `span`.
    fn new(path: &Path, text: &str, span: Range<usize>) -> Self {
        let start = span.start.min(text.len());
        let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
        let end = span.end.clamp(start, line_end);
        Self {
            path: path.to_owned(),
            line: text[..start].matches('\n').count() + 1,
            column: text[line_start..start].chars().count() + 1,
            text: text[line_start..line_end].trim_end().to_owned(),
            width: text[start..end].chars().count().max(1),
        }
    }

    /// The line, with the place marked under it.
    pub fn excerpt(&self) -> String {
        let number = self.line.to_string();
        let gutter = " ".repeat(number.len());
        format!(
            "{gutter} |\n{number} | {}\n{gutter} | {}{}",
            self.text,
            " ".repeat(self.column - 1),
            "^".repeat(self.width)
        )
    }
}

impl fmt::Display for Located {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.path.display(), self.line, self.column)
    }
}

impl std::error::Error for Located {}

/// The built-in scene called `name`, or else the scene file at that path.
///
/// # Errors
/// When it is neither, or the file cannot be read or is not a scene: where in the file, and
/// why.
pub fn load(name: &str) -> Result<NamedScene> {
    if let Some(built_in) = scenes::find(name) {
        return Ok(NamedScene {
            name: built_in.name.to_owned(),
            scene: OwnedScene::from_desc(&built_in.desc),
            source: None,
        });
    }
    let path = Path::new(name);
    if path.is_dir() {
        bail!("{name} is a directory: give a scene file in it (a .toml; see host/scenes/)");
    }
    if !path.is_file() {
        let names: Vec<_> = scenes::BUILT_IN.iter().map(|s| s.name).collect();
        bail!(
            "there is no scene `{name}`: give a built-in scene ({}) or a scene file (see \
             host/scenes/)",
            names.join(", ")
        );
    }
    let text = read(path)?;
    let scene = parse(path, &text)?;
    Ok(NamedScene {
        name: path.file_stem().map_or_else(
            || name.to_owned(),
            |stem| stem.to_string_lossy().into_owned(),
        ),
        scene,
        source: Some(Source {
            path: path.to_owned(),
            text,
        }),
    })
}

/// The text of the file at `path`, refused beyond [`MAX_FILE_BYTES`] before more is read.
fn read(path: &Path) -> Result<String> {
    let file =
        std::fs::File::open(path).with_context(|| format!("cannot read {}", path.display()))?;
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .with_context(|| format!("cannot read {}", path.display()))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        bail!(
            "{} is larger than a scene file may be ({} KiB): is it the scene you meant?",
            path.display(),
            MAX_FILE_BYTES / 1024
        );
    }
    String::from_utf8(bytes).map_err(|error| {
        let valid = error.utf8_error().valid_up_to();
        let bytes = error.as_bytes();
        let before = String::from_utf8_lossy(&bytes[..valid]);
        let line = before.matches('\n').count() + 1;
        let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        anyhow::anyhow!(
            "{}:{line}:{column}: byte 0x{:02x} is not UTF-8 text; a scene file is TOML, which is \
             UTF-8: save it as UTF-8",
            path.display(),
            bytes[valid]
        )
    })
}

/// Parses the TOML text of the scene file at `path`.
///
/// # Errors
/// TOML's own, a vector without three numbers, or a value of the wrong kind: each located in
/// the file ([`Located`]) and saying what was expected.
pub fn parse(path: &Path, text: &str) -> Result<OwnedScene> {
    let at = |span: Option<Range<usize>>, message: String| {
        let error = anyhow::Error::msg(message);
        match span {
            Some(span) => error.context(Located::new(path, text, span)),
            None => error.context(format!("{} is not a scene file", path.display())),
        }
    };
    let table = DeTable::parse(text).map_err(|e| at(e.span(), e.message().to_owned()))?;
    if let Some((span, message)) = wrong_vector(table.get_ref(), "") {
        return Err(at(Some(span), message));
    }
    let scene: OwnedScene<FileObject> =
        toml::from_str(text).map_err(|e| at(e.span(), e.message().to_owned()))?;
    if let Some(animation) = &scene.animation {
        animation
            .check(&scene.camera)
            .map_err(|e| at(animation_span(table.get_ref(), &e), e.message))?;
    }
    read_meshes(path, scene, |i| {
        let object = element(table.get_ref(), "objects", i)?;
        let DeValue::Table(object) = object.get_ref() else {
            return Some(object.span());
        };
        let shape = entry(object, "shape")?;
        let DeValue::Table(shape) = shape.get_ref() else {
            return Some(shape.span());
        };
        Some(entry(shape, "mesh")?.span())
    })
    .map_err(|(span, error)| match span {
        Some(span) => error.context(Located::new(path, text, span)),
        None => error.context(path.display().to_string()),
    })
}

/// The scene with the mesh files its objects name read (relative to the scene file at `path`)
/// into its meshes, each of their objects a [`ShapeDesc::Mesh`]. An error is placed at the span
/// `place` gives for the object's index.
fn read_meshes(
    path: &Path,
    scene: OwnedScene<FileObject>,
    place: impl Fn(usize) -> Option<Range<usize>>,
) -> Result<OwnedScene, (Option<Range<usize>>, anyhow::Error)> {
    let directory = path.parent().unwrap_or(Path::new("."));
    let mut meshes = OwnedMeshes::default();
    let mut index = 0;
    let mut scene = scene.map_objects(|object| {
        let i = index;
        index += 1;
        let mesh = match object.shape {
            FileShape::Shape(shape) => {
                return Ok(ObjectDesc {
                    shape,
                    material: object.material,
                });
            }
            FileShape::Mesh { mesh } => mesh,
        };
        let fail = |error: anyhow::Error| (place(i), error);
        let loaded = mesh_file::load(directory, &mesh).map_err(fail)?;
        let added = meshes
            .add(&loaded.vertices, &loaded.normals, &loaded.triangles)
            .map_err(|error| fail(anyhow::anyhow!(hierarchy_error(&mesh.file, error))))?;
        Ok(ObjectDesc {
            shape: ShapeDesc::Mesh { root: added.root },
            material: object.material,
        })
    })?;
    scene.meshes = meshes;
    Ok(scene)
}

/// What is wrong with the triangles of mesh file `file`, and how to mend it.
fn hierarchy_error(file: &str, error: HierarchyError) -> String {
    match error {
        HierarchyError::Count => format!(
            "{file} has no triangle with an area (or more than 2³¹): give a mesh of triangles \
             whose corners are not on one line"
        ),
        HierarchyError::NoSuchVertex { triangle } => format!(
            "{file}: triangle {triangle} names a corner the file does not have: export the \
             mesh again"
        ),
        HierarchyError::TooFewNodes { needed } => {
            format!("{file}: its hierarchy needs {needed} nodes, which could not be made")
        }
    }
}

/// The first array of numbers in `table` whose length is not 3 (every vector and colour of a
/// scene has three), with its span and what is wrong; `path` is the table's key path.
fn wrong_vector(table: &DeTable<'_>, path: &str) -> Option<(Range<usize>, String)> {
    table.iter().find_map(|(key, value)| {
        let path = if path.is_empty() {
            key.get_ref().to_string()
        } else {
            format!("{path}.{}", key.get_ref())
        };
        wrong_in(value.get_ref(), value.span(), &path)
    })
}

fn wrong_in(value: &DeValue<'_>, span: Range<usize>, path: &str) -> Option<(Range<usize>, String)> {
    match value {
        DeValue::Table(table) => wrong_vector(table, path),
        DeValue::Array(items) => {
            let numbers = items
                .iter()
                .all(|v| matches!(v.get_ref(), DeValue::Integer(_) | DeValue::Float(_)));
            // An empty list is no vector: a scene may have no objects or no lights.
            if numbers && !items.is_empty() && items.len() != 3 {
                return Some((
                    span,
                    format!(
                        "{path} has {} numbers; a vector or a colour has exactly 3",
                        items.len()
                    ),
                ));
            }
            items
                .iter()
                .enumerate()
                .find_map(|(i, v)| wrong_in(v.get_ref(), v.span(), &format!("{path}[{i}]")))
        }
        _ => None,
    }
}

impl NamedScene {
    /// The still scenes it is drawn as: each frame of its camera path in order
    /// ([`Self::at_frame`]), or itself, a still scene.
    #[must_use]
    pub fn frames(&self) -> Vec<Self> {
        match &self.scene.animation {
            Some(animation) => (0..animation.frames).map(|k| self.at_frame(k)).collect(),
            None => vec![self.clone()],
        }
    }

    /// Where this is a frame of a camera path ([`Self::at_frame`]): the path's name and the
    /// frame ([`path_frame`]).
    #[must_use]
    pub fn path_frame(&self) -> Option<(&str, u16)> {
        path_frame(&self.name)
    }

    /// The still scene of `frame` of its camera path ([`OwnedScene::at_frame`]), named
    /// `NAME-frame-K`, its refusals placed in the same file.
    #[must_use]
    pub fn at_frame(&self, frame: u16) -> Self {
        Self {
            name: format!("{}{FRAME}{frame}", self.name),
            scene: self.scene.at_frame(frame),
            source: self.source.clone(),
        }
    }

    /// The file the scene was read from, if it was.
    #[must_use]
    pub fn path(&self) -> Option<&Path> {
        self.source.as_ref().map(|source| source.path.as_path())
    }

    /// `error`, where it is a refusal of this scene's build ([`SceneError`]) and the scene came
    /// from a file, placed at the line and column of the value at fault (or of its object,
    /// light or camera when the value is one the tracer computes, or of `far` for one of the
    /// whole scene's).
    pub fn locate(&self, error: anyhow::Error) -> anyhow::Error {
        let Some(source) = &self.source else {
            return error;
        };
        let Some(refusal) = error.chain().find_map(|e| e.downcast_ref::<SceneError>()) else {
            return error;
        };
        let Ok(table) = DeTable::parse(&source.text) else {
            return error;
        };
        // A refusal of the whole scene at no key the file spells out (a value the tracer
        // computes) is about the world's size, which `far` sets.
        let span = span_of(table.get_ref(), refusal).or_else(|| {
            (refusal.item() == Some(Item::Scene))
                .then(|| entry(table.get_ref(), "far").map(Spanned::span))
                .flatten()
        });
        match span {
            Some(span) => error.context(Located::new(&source.path, &source.text, span)),
            None => error.context(source.path.display().to_string()),
        }
    }
}

/// The span of what `error` is about in a scene file's `root` table: the value named by its
/// field, as deep as the file spells it out, or else its item.
fn span_of(root: &DeTable<'_>, error: &SceneError) -> Option<Range<usize>> {
    if let SceneError::TooMany { what, capacity, .. } = *error {
        return element(root, what, capacity).map(Spanned::span);
    }
    let (mut span, mut table) = match error.item()? {
        Item::Scene => (None, root),
        item => {
            let found = match item {
                Item::Object(i) => element(root, "objects", i),
                Item::Light(i) => element(root, "lights", i),
                _ => entry(root, "camera"),
            }?;
            match found.get_ref() {
                DeValue::Table(table) => (Some(found.span()), table),
                _ => return Some(found.span()),
            }
        }
    };
    let field = error.field().unwrap_or("");
    let key_end = field
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '.'))
        .unwrap_or(field.len());
    for part in field[..key_end].split('.') {
        let Some(value) = entry(table, part) else {
            break;
        };
        span = Some(value.span());
        match value.get_ref() {
            DeValue::Table(inner) => table = inner,
            _ => break,
        }
    }
    span
}

/// Where an animation's fault is in the file's `root` table: the field of its key, or of the
/// `[animation]` table itself.
fn animation_span(root: &DeTable<'_>, error: &AnimationError) -> Option<Range<usize>> {
    let animation = entry(root, "animation")?;
    let DeValue::Table(table) = animation.get_ref() else {
        return Some(animation.span());
    };
    let (holder, span) = match error.key {
        Some(i) => {
            let key = element(table, "keys", i)?;
            match key.get_ref() {
                DeValue::Table(key_table) => (key_table, key.span()),
                _ => return Some(key.span()),
            }
        }
        None => (table, animation.span()),
    };
    Some(entry(holder, error.field).map_or(span, Spanned::span))
}

/// The value of `key` in `table`.
fn entry<'t, 'i>(table: &'t DeTable<'i>, key: &str) -> Option<&'t Spanned<DeValue<'i>>> {
    table
        .iter()
        .find(|(k, _)| k.get_ref() == key)
        .map(|(_, v)| v)
}

/// Element `index` of the array `key` in `table` (an object or a light).
fn element<'t, 'i>(
    table: &'t DeTable<'i>,
    key: &str,
    index: usize,
) -> Option<&'t Spanned<DeValue<'i>>> {
    match entry(table, key)?.get_ref() {
        DeValue::Array(items) => items.get(index),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use obscura::{BackgroundDesc, MaterialDesc, ShapeDesc};

    fn parse(text: &str) -> Result<OwnedScene> {
        super::parse(Path::new("scene.toml"), text)
    }

    /// `text` as if loaded from scene.toml.
    fn named(text: &str) -> NamedScene {
        NamedScene {
            name: "scene".to_owned(),
            scene: parse(text).unwrap(),
            source: Some(Source {
                path: PathBuf::from("scene.toml"),
                text: text.to_owned(),
            }),
        }
    }

    /// Where `error` is placed in `text`, as "file:line:column".
    fn placed(text: &str, error: SceneError) -> String {
        let located = named(text).locate(anyhow::Error::new(error));
        located
            .downcast_ref::<Located>()
            .map_or_else(String::new, ToString::to_string)
    }

    const MINIMAL: &str = r#"
        far = 20.0
        camera = { eye = [0.0, 1.0, -5.0], look_at = [0.0, 1.0, 0.0], up = [0.0, 1.0, 0.0], vfov_degrees = 50.0 }

        [[objects]]
        shape.sphere = { center = [0.0, 1.0, 0.0], radius = 1.0 }
        material = { colour = [0.9, 0.2, 0.1], specular = 0.4, shininess = 30 }

        [[objects]]
        shape.plane = { point = [0.0, 0.0, 0.0], normal = [0.0, 1.0, 0.0], checker = { colour = [0.1, 0.1, 0.1], size = 1.0 } }

        [[lights]]
        position = [-3.0, 6.0, -4.0]
        colour = [1.0, 1.0, 1.0]
    "#;

    #[test]
    fn a_minimal_file_fills_in_the_defaults() {
        let scene = parse(MINIMAL).expect("parses");
        assert_eq!(scene.objects.len(), 2);
        assert_eq!(scene.max_depth, 5);
        assert_eq!(scene.samples, 1);
        assert_eq!((scene.shadow_samples, scene.adaptive_shadows), (1, false));
        assert_eq!(scene.lights[0].radius, 0.0);
        assert_eq!(scene.background, BackgroundDesc::Solid([0.0; 3]));
        let material = scene.objects[0].material;
        assert_eq!(material.colour, [0.9, 0.2, 0.1]);
        assert_eq!(material.shininess, 30);
        // What it does not say is the default matte material's.
        assert_eq!(material.diffuse, MaterialDesc::default().diffuse);
        assert_eq!(scene.objects[1].material, MaterialDesc::default());
        assert!(matches!(
            scene.objects[1].shape,
            ShapeDesc::Plane {
                checker: Some(_),
                ..
            }
        ));
    }

    #[test]
    fn mistakes_are_named_with_their_place() {
        let typo = MINIMAL.replace("radius", "radios");
        let error = format!("{:#}", parse(&typo).expect_err("an unknown field"));
        assert!(
            error.contains("radios") && error.starts_with("scene.toml:6:52: "),
            "{error}"
        );
        let missing = MINIMAL.replace("far = 20.0", "");
        let error = format!("{:#}", parse(&missing).expect_err("far is required"));
        assert!(error.contains("far"), "{error}");
        let shape = MINIMAL.replace("shape.sphere", "shape.cube");
        let error = format!("{:#}", parse(&shape).expect_err("no cubes"));
        assert!(
            error.contains("cube") && error.contains("sphere"),
            "{error}"
        );
    }

    #[test]
    fn a_scene_without_objects_or_lights_is_written_with_empty_lists() {
        let objects = MINIMAL.find("[[objects]]").unwrap();
        let empty = format!("objects = []\nlights = []\n{}", &MINIMAL[..objects]);
        let scene = parse(&empty).expect("empty lists are a scene's");
        assert!(scene.objects.is_empty() && scene.lights.is_empty());
    }

    #[test]
    fn a_count_of_rays_beyond_its_type_is_refused_as_a_count() {
        for (key, value) in [("samples", "70000"), ("shadow_samples", "-1")] {
            let text = MINIMAL.replace("far = 20.0", &format!("far = 20.0\n{key} = {value}"));
            let error = format!("{:#}", parse(&text).expect_err("beyond a count"));
            assert!(
                error.starts_with(&format!("scene.toml:3:{}: ", key.len() + 4))
                    && error.contains(&format!("{value} is not a count of rays"))
                    && !error.contains("u16"),
                "{error}"
            );
        }
    }

    #[test]
    fn bytes_that_are_not_utf8_are_refused_at_their_place() {
        let path = std::env::temp_dir().join("obscura-not-utf8.toml");
        std::fs::write(&path, b"far = 20.0\n# caf\xe9\n").unwrap();
        let error = format!("{:#}", read(&path).expect_err("latin-1"));
        let _ = std::fs::remove_file(&path);
        assert!(
            error.ends_with(&format!(
                "{}:2:6: byte 0xe9 is not UTF-8 text; a scene file is TOML, which is UTF-8: \
                 save it as UTF-8",
                path.display()
            )),
            "{error}"
        );
    }

    #[test]
    fn a_vector_of_other_than_three_numbers_is_refused_where_it_is() {
        let four = MINIMAL.replace("radius = 1.0", "radius = 1.0 }\nx = { y = [1, 2, 3, 4]");
        let long = MINIMAL.replace("[0.0, 1.0, 0.0], radius", "[0.0, 1.0, 0.0, 5.0], radius");
        let error = parse(&long).expect_err("four numbers");
        let place = error
            .downcast_ref::<Located>()
            .expect("located")
            .to_string();
        assert_eq!(place, "scene.toml:6:35");
        assert!(
            format!("{error:#}").contains("objects[0].shape.sphere.center has 4 numbers"),
            "{error:#}"
        );
        let short = MINIMAL.replace("colour = [1.0, 1.0, 1.0]", "colour = [1.0]");
        let error = format!("{:#}", parse(&short).expect_err("one number"));
        assert!(error.contains("lights[0].colour has 1 numbers"), "{error}");
        assert!(parse(&four).is_err());
    }

    #[test]
    fn a_sample_count_out_of_bounds_is_refused_where_it_is() {
        let text = MINIMAL.replace("far = 20.0", "far = 20.0\n        samples = 300");
        let scene = parse(&text).expect("parses");
        assert_eq!(scene.samples, 300);
        let error = obscura::Scene::<f32, 4, 4, 8>::build(&scene.desc()).expect_err("too many");
        assert_eq!(placed(&text, error), "scene.toml:3:19");
    }

    #[test]
    fn adaptive_samples_are_read_and_refused_at_their_count_when_not_a_power_of_four() {
        let text = MINIMAL.replace(
            "far = 20.0",
            "far = 20.0\n        samples = 16\n        adaptive_samples = true",
        );
        let scene = parse(&text).expect("parses");
        assert_eq!((scene.samples, scene.adaptive_samples), (16, true));
        assert!(obscura::Scene::<f32, 4, 4, 8>::build(&scene.desc()).is_ok());
        let eight = text.replace("samples = 16", "samples = 8");
        let error = obscura::Scene::<f32, 4, 4, 8>::build(&parse(&eight).unwrap().desc())
            .expect_err("not a power of 4");
        assert!(error.to_string().contains("4, 16, 64 or 256"), "{error}");
        assert_eq!(placed(&eight, error), "scene.toml:3:19");
    }

    #[test]
    fn adaptive_pixels_are_read_by_name_and_refused_with_samples_or_an_unknown_name() {
        let text = MINIMAL.replace("far = 20.0", "far = 20.0\n        pixels = \"adaptive:4\"");
        let scene = parse(&text).expect("parses");
        assert_eq!(scene.pixels, obscura::Pixels::Adaptive(4));
        assert!(obscura::Scene::<f32, 4, 4, 8>::build(&scene.desc()).is_ok());
        let sampled = text.replace("far = 20.0", "far = 20.0\n        samples = 4");
        let error = obscura::Scene::<f32, 4, 4, 8>::build(&parse(&sampled).unwrap().desc())
            .expect_err("adaptive pixels take one ray a pixel");
        assert!(error.to_string().contains("samples = 1"), "{error}");
        assert_eq!(placed(&sampled, error), "scene.toml:3:19");
        let unknown = text.replace("adaptive:4", "adaptive:3");
        let error = format!("{:#}", parse(&unknown).expect_err("no blocks of 3"));
        assert!(
            error.contains("`adaptive:3` is not a way to find pixels")
                && error.contains("\"adaptive:8\""),
            "{error}"
        );
    }

    #[test]
    fn an_area_light_and_its_shadow_rays_are_read_and_refused_where_they_are_wrong() {
        let text = MINIMAL
            .replace(
                "far = 20.0",
                "far = 20.0\n        shadow_samples = 16\n        adaptive_shadows = true",
            )
            .replace(
                "colour = [1.0, 1.0, 1.0]",
                "colour = [1.0, 1.0, 1.0]\n        radius = 0.5",
            );
        let scene = parse(&text).expect("parses");
        assert_eq!((scene.shadow_samples, scene.adaptive_shadows), (16, true));
        assert_eq!(scene.lights[0].radius, 0.5);
        assert!(obscura::Scene::<f32, 4, 4, 8>::build(&scene.desc()).is_ok());

        let none = text.replace("shadow_samples = 16", "shadow_samples = 0");
        let error = obscura::Scene::<f32, 4, 4, 8>::build(&parse(&none).unwrap().desc())
            .expect_err("no shadow rays");
        assert_eq!(placed(&none, error), "scene.toml:3:26");
        let negative = text.replace("radius = 0.5", "radius = -0.5");
        let error = obscura::Scene::<f32, 4, 4, 8>::build(&parse(&negative).unwrap().desc())
            .expect_err("a negative radius");
        assert!(error.to_string().contains("radius"), "{error}");
        assert_eq!(placed(&negative, error), "scene.toml:17:18");
        // A disc reaching beyond the world: the light's table is the place.
        let wide = text.replace("radius = 0.5", "radius = 15.0");
        let error = obscura::Scene::<f32, 4, 4, 8>::build(&parse(&wide).unwrap().desc())
            .expect_err("beyond the world");
        assert!(matches!(error, SceneError::OutsideWorld { .. }), "{error}");
    }

    #[test]
    fn a_camera_path_is_read_and_its_faults_placed_at_their_key() {
        let path = |keys: &str| format!("{MINIMAL}\n[animation]\nframes = 8\nfps = 4\n{keys}");
        let key = |frame: u16, x: f32| {
            format!(
                "\n[[animation.keys]]\nframe = {frame}\neye = [{x}, 1.0, -5.0]\n\
                 look_at = [0.0, 1.0, 0.0]\n"
            )
        };
        let text = path(&(key(2, 3.0) + &key(5, -3.0)));
        let scene = parse(&text).expect("parses");
        assert_eq!(scene.frames(), 8);
        // Frame 0 is the [camera] table's, and a key's frame its eye.
        assert_eq!(scene.desc().camera, scene.camera);
        assert_eq!(scene.camera_at(2).eye, [3.0, 1.0, -5.0]);
        assert_eq!(named(&text).at_frame(5).scene.camera.eye, [-3.0, 1.0, -5.0]);
        assert_eq!(scene.at_frame(5).animation, None);
        let line_of = |text: &str, error: anyhow::Error| {
            let located = error
                .downcast_ref::<Located>()
                .map_or_else(String::new, ToString::to_string);
            let line: usize = located
                .split(':')
                .nth(1)
                .unwrap_or("0")
                .parse()
                .unwrap_or(0);
            text.lines()
                .nth(line.saturating_sub(1))
                .unwrap_or("")
                .trim()
                .to_owned()
        };
        let beyond = path(&(key(2, 3.0) + &key(8, -3.0)));
        let error = parse(&beyond).expect_err("a key beyond the loop");
        assert!(
            format!("{error:#}").contains("frames run from 0 to 7"),
            "{error:#}"
        );
        assert_eq!(line_of(&beyond, error), "frame = 8");
        let twice = path(&(key(2, 3.0) + &key(2, -3.0)));
        let error = parse(&twice).expect_err("two keys on a frame");
        assert!(
            format!("{error:#}").contains("key 1 is there already"),
            "{error:#}"
        );
        let blind = path(&key(4, 0.0).replace("eye = [0, 1.0, -5.0]", "eye = [0.0, 1.0, 0.0]"));
        let error = parse(&blind).expect_err("an eye on its look-at point");
        assert!(format!("{error:#}").contains("at frame 4"), "{error:#}");
        assert_eq!(line_of(&blind, error), "eye = [0.0, 1.0, 0.0]");
        let still = format!(
            "{MINIMAL}\n[animation]\nframes = 0\nfps = 4\n{}",
            key(0, 1.0)
        );
        let error = parse(&still).expect_err("no frames");
        assert_eq!(line_of(&still, error), "frames = 0");
    }

    #[test]
    fn a_lens_is_read_and_refused_where_it_is_wrong() {
        let text = MINIMAL.replace(
            "vfov_degrees = 50.0 }",
            "vfov_degrees = 50.0, aperture = 0.2, focus_distance = 4.0 }",
        );
        let scene = parse(&text).expect("parses");
        assert_eq!(
            (scene.camera.aperture, scene.camera.focus_distance),
            (0.2, Some(4.0))
        );
        assert_eq!(parse(MINIMAL).unwrap().camera.focus_distance, None);
        assert!(obscura::Scene::<f32, 4, 4, 8>::build(&scene.desc()).is_ok());
        // The eye is 1 above the floor: a lens of radius 1.5 reaches it.
        let wide = text.replace("aperture = 0.2", "aperture = 1.5");
        let error = obscura::Scene::<f32, 4, 4, 8>::build(&parse(&wide).unwrap().desc())
            .expect_err("the lens reaches the floor");
        assert!(error.to_string().contains("object 1"), "{error}");
        assert_eq!(placed(&wide, error), "scene.toml:3:125");
        let nowhere = text.replace("focus_distance = 4.0", "focus_distance = 0.0");
        let error = obscura::Scene::<f32, 4, 4, 8>::build(&parse(&nowhere).unwrap().desc())
            .expect_err("no focus");
        assert_eq!(placed(&nowhere, error), "scene.toml:3:147");
    }

    #[test]
    fn a_refusal_of_the_build_points_at_the_value_or_else_its_item() {
        let radius = SceneError::OutOfBounds {
            item: Item::Object(0),
            field: "shape.sphere.radius",
            value: -1.0,
            expected: "> 0",
        };
        assert_eq!(placed(MINIMAL, radius), "scene.toml:6:61");
        // The material does not give an ior: the material itself is the place.
        let ior = SceneError::OutOfBounds {
            item: Item::Object(0),
            field: "material.ior",
            value: 0.5,
            expected: "≥ 1",
        };
        assert_eq!(placed(MINIMAL, ior), "scene.toml:7:20");
        // As deep as the file goes: object 1's shape.
        let triangle = SceneError::DegenerateTriangle {
            item: Item::Object(1),
        };
        assert_eq!(placed(MINIMAL, triangle), "scene.toml:10:9");
        // A value the tracer computes: the object.
        let computed = SceneError::OutOfRange {
            item: Item::Object(1),
            quantity: "b² − c in the quadratic",
            value: 1e6,
            format: "i16f16",
            range: 32768.0,
            remedy: obscura::Remedy::ShrinkWorld,
            holds: obscura::scalar::FormatSet::default(),
        };
        assert_eq!(placed(MINIMAL, computed), "scene.toml:9:9");
        assert_eq!(
            placed(MINIMAL, SceneError::UpParallelToView),
            "scene.toml:3:76"
        );
        let light = SceneError::OutsideWorld {
            item: Item::Light(0),
            distance: 30.0,
            far: 20.0,
        };
        assert_eq!(placed(MINIMAL, light), "scene.toml:12:9");
        let many = SceneError::TooMany {
            what: "objects",
            count: 2,
            capacity: 1,
        };
        assert_eq!(placed(MINIMAL, many), "scene.toml:9:9");
        let far = SceneError::OutOfBounds {
            item: Item::Scene,
            field: "far",
            value: -1.0,
            expected: "> 0",
        };
        assert_eq!(placed(MINIMAL, far), "scene.toml:2:15");
        // A value of the whole scene the tracer computes: the world's size, far.
        let world = SceneError::OutOfRange {
            item: Item::Scene,
            quantity: "a point along a ray, o + t·d",
            value: 1e6,
            format: "i16f16",
            range: 32768.0,
            remedy: obscura::Remedy::ShrinkWorld,
            holds: obscura::scalar::FormatSet::default(),
        };
        assert_eq!(placed(MINIMAL, world), "scene.toml:2:15");
    }

    #[test]
    fn a_mesh_file_is_read_beside_the_scene_and_its_mistakes_placed() {
        let directory = std::env::temp_dir().join(format!("obscura-mesh-{}", std::process::id()));
        std::fs::create_dir_all(&directory).unwrap();
        // A cube of six quads.
        let cube = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
                    f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
        std::fs::write(directory.join("cube.obj"), cube).unwrap();
        let mesh =
            r#"shape.mesh = { file = "cube.obj", scale = 2.0, translate = [0.0, 0.0, 3.0] }"#;
        let text = MINIMAL.replace(
            "shape.sphere = { center = [0.0, 1.0, 0.0], radius = 1.0 }",
            mesh,
        );
        let path = directory.join("scene.toml");
        let scene = super::parse(&path, &text).expect("reads the cube");
        assert_eq!(scene.objects[0].shape, ShapeDesc::Mesh { root: 0 });
        assert_eq!(scene.objects[0].material.shininess, 30);
        assert_eq!(scene.meshes.triangles.len(), 12);
        // Scaled, then moved: the box is [0, 2] × [0, 2] × [3, 5].
        assert_eq!(scene.meshes.nodes[0].max, [2.0, 2.0, 5.0]);
        assert!(
            obscura::Scene::<
                f32,
                4,
                4,
                8,
                obscura::Everything,
                obscura::mesh::MeshVecs<f32>,
            >::build(&scene.desc())
            .is_ok()
        );
        // A file that is not there, and a key a mesh does not have: at the mesh's place.
        let missing = text.replace("cube.obj", "sphere.obj");
        let error = format!(
            "{:#}",
            super::parse(&path, &missing).expect_err("no such file")
        );
        assert!(
            error.contains("scene.toml:6:22: ") && error.contains("sphere.obj"),
            "{error}"
        );
        let typo = text.replace("scale", "scael");
        let error = format!("{:#}", super::parse(&path, &typo).expect_err("no such key"));
        assert!(
            error.contains("scene.toml:6:") && error.contains("scael"),
            "{error}"
        );
        let _ = std::fs::remove_dir_all(&directory);
    }

    #[test]
    fn an_excerpt_marks_the_place_under_its_line() {
        let place = Located::new(Path::new("s.toml"), "a = 1\nbé = [1, 2]\n", 12..18);
        assert_eq!(place.to_string(), "s.toml:2:6");
        assert_eq!(place.excerpt(), "  |\n2 | bé = [1, 2]\n  |      ^^^^^^");
    }

    #[test]
    fn a_name_is_a_built_in_scene_or_a_file() {
        assert_eq!(load("whitted").expect("built in").name, "whitted");
        let error = format!("{:#}", load("no-such-scene").expect_err("neither"));
        assert!(
            error.contains("whitted") && error.contains("scene file"),
            "{error}"
        );
        let directory = format!(
            "{:#}",
            load(env!("CARGO_MANIFEST_DIR")).expect_err("a directory")
        );
        assert!(directory.contains("is a directory"), "{directory}");
    }
}
