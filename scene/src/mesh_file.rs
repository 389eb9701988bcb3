//! Triangle meshes read from files and placed in the world: a scene file's
//! `shape.mesh = { file = "teapot.obj", scale = 1.0, rotate_degrees = [-90.0, 0.0, 0.0] }`
//! ([`MeshFile`]) read by [`load`] into a [`LoadedMesh`] in world coordinates.
//!
//! This module owns the mesh formats: Wavefront OBJ (through `tobj`, after a pre-scan of its
//! own that places a wrong line at `file:line:column`, which `tobj` cannot) and STL, binary and
//! ASCII (parsed here). It owns the placing too: scale, then rotate about x, then y, then z,
//! then translate, in f64, rounded to f32 once. What the mesh's triangles then make of the
//! scene (a hierarchy, the refusal of what the core cannot hold) is the scene build's.
//!
//! Triangles are kept exactly as the file gives them, degenerate ones too (a zero-area
//! triangle, or one whose corners are not three distinct vertices): the renderer's scene
//! build decides what to do with them.

use anyhow::{Result, anyhow, bail};
use std::ffi::OsStr;
use std::fmt::Display;
use std::fs::File;
use std::io::Read;
use std::path::Path;

/// The largest mesh file read, 256 MiB: millions of triangles, far more than a scene that
/// renders in reasonable time needs; checked before the file is read.
pub(crate) const MAX_MESH_FILE_BYTES: u64 = 256 << 20;

/// How a scene file places a mesh: `shape.mesh = { file = "teapot.obj", scale = 1.0,
/// rotate_degrees = [-90.0, 0.0, 0.0], translate = [0.0, 0.0, 0.0] }`.
#[derive(Clone, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MeshFile {
    /// The mesh file: `.obj` (Wavefront OBJ) or `.stl` (binary or ASCII STL), a path relative
    /// to the scene file's directory (an absolute path also works).
    pub(crate) file: String,
    /// How much the mesh is scaled about the file's origin (first, before it is rotated);
    /// negative mirrors it through the origin. 1 if not given.
    #[serde(default = "one")]
    pub(crate) scale: f32,
    /// The rotation in degrees about x, then y, then z (right-handed: +90° about y takes +x
    /// to -z). None if not given.
    #[serde(default)]
    pub(crate) rotate_degrees: [f32; 3],
    /// Where the file's origin goes (last, after scaling and rotating). The origin if not
    /// given.
    #[serde(default)]
    pub(crate) translate: [f32; 3],
}

impl MeshFile {
    /// The file `file`, placed as it is.
    pub(crate) fn at(file: String) -> Self {
        Self {
            file,
            scale: 1.0,
            rotate_degrees: [0.0; 3],
            translate: [0.0; 3],
        }
    }
}

/// [`MeshFile::scale`]'s default: the file's own size.
const fn one() -> f32 {
    1.0
}

/// A mesh in world coordinates: shared vertices, triangles as indices into them (anticlockwise
/// as the file gives them), and, when the file gives a normal at every corner, one unit normal
/// per vertex (same length as `vertices`), else empty.
///
/// Every triangle the file gives is here, degenerate ones too. A negative scale mirrors the
/// mesh: its normals are flipped with it (they point out of the mirrored surface), its
/// triangles keep the file's order of corners.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LoadedMesh {
    /// The vertices, placed.
    pub(crate) vertices: Vec<[f32; 3]>,
    /// Each triangle's corners, indices into `vertices`.
    pub(crate) triangles: Vec<[u32; 3]>,
    /// One unit normal per vertex (placed), or none.
    pub(crate) normals: Vec<[f32; 3]>,
}

/// Reads `spec.file` (relative to `scene_dir`) and places it: each point p ↦
/// R(z)·R(y)·R(x)·(scale·p) + translate (scale first, then rotate about x, then y, then z,
/// then translate, computed in f64 and rounded to f32 once); normals rotated the same way
/// (and flipped if scale < 0) and renormalised.
///
/// The format is the extension's, in any case: `.obj` or `.stl` (binary when the file's size
/// is the 84 + 50·n bytes its triangle count n makes, else ASCII when it starts with `solid`).
///
/// # Errors
/// When the extension is neither, the placing is not finite (or scales by 0), the file cannot
/// be read or is larger than [`MAX_MESH_FILE_BYTES`], the file is not a valid mesh of its
/// format (at `file:line:column` for a text file, at a byte offset for a binary STL), it has
/// no triangles, or a placed point is beyond f32's range. Each error says how to fix it.
pub(crate) fn load(scene_dir: &Path, spec: &MeshFile) -> Result<LoadedMesh> {
    let path = scene_dir.join(&spec.file);
    let format = MeshFormat::of(&path)?;
    let placement = Placement::of(spec)?;
    let bytes = read_mesh_file(&path)?;
    let mesh = match format {
        MeshFormat::Obj => obj::parse(&path, &bytes)?,
        MeshFormat::Stl => stl::parse(&path, &bytes)?,
    };
    placement.place(&path, mesh)
}

/// The mesh formats read, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum MeshFormat {
    /// Wavefront OBJ, `.obj`.
    Obj,
    /// STL, binary or ASCII, `.stl`.
    Stl,
}

impl MeshFormat {
    /// The format `path`'s extension names, in any case.
    fn of(path: &Path) -> Result<Self> {
        let extension = path.extension().and_then(OsStr::to_str).unwrap_or_default();
        if extension.eq_ignore_ascii_case("obj") {
            Ok(Self::Obj)
        } else if extension.eq_ignore_ascii_case("stl") {
            Ok(Self::Stl)
        } else {
            let named = if extension.is_empty() {
                "has no extension".to_owned()
            } else {
                format!("has the extension `.{extension}`")
            };
            bail!(
                "{}: {named}, which is no mesh format read here; a mesh file is a Wavefront OBJ \
                 (`.obj`) or an STL, binary or ASCII (`.stl`): export the mesh as one of those",
                path.display()
            )
        }
    }
}

/// A mesh as its file gives it, before it is placed (in f64, which holds every file's f32
/// exactly).
#[derive(Debug, Default)]
struct FileMesh {
    /// The vertices.
    vertices: Vec<[f64; 3]>,
    /// Each triangle's corners, indices into `vertices`.
    triangles: Vec<[u32; 3]>,
    /// One normal per vertex, or none.
    normals: Vec<[f64; 3]>,
}

/// The bytes of the mesh file at `path`, refused unread if it is larger than
/// [`MAX_MESH_FILE_BYTES`].
fn read_mesh_file(path: &Path) -> Result<Vec<u8>> {
    let cannot = |doing: &str, error: std::io::Error| {
        anyhow!(
            "{}: cannot {doing} it ({error}); check the mesh's `file` (a path relative to the \
             scene file's directory, or an absolute one)",
            path.display()
        )
    };
    let file = File::open(path).map_err(|error| cannot("open", error))?;
    let size = file
        .metadata()
        .map_err(|error| cannot("read", error))?
        .len();
    refuse_if_too_large(path, size)?;
    let mut bytes = Vec::with_capacity(usize::try_from(size).unwrap_or_default());
    file.take(MAX_MESH_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|error| cannot("read", error))?;
    // The file may have grown since its size was asked.
    refuse_if_too_large(path, u64::try_from(bytes.len()).unwrap_or(u64::MAX))?;
    Ok(bytes)
}

/// Refuses a mesh file of `size` bytes if it is larger than [`MAX_MESH_FILE_BYTES`].
fn refuse_if_too_large(path: &Path, size: u64) -> Result<()> {
    if size > MAX_MESH_FILE_BYTES {
        bail!(
            "{}: is {size} bytes, more than the {} MiB a mesh file may be; simplify (decimate) \
             the mesh or split it into several files",
            path.display(),
            MAX_MESH_FILE_BYTES >> 20
        );
    }
    Ok(())
}

/// A line of a text mesh file: where its errors are, as `file:line:column`.
#[derive(Clone, Copy, Debug)]
struct Line<'a> {
    /// The file.
    path: &'a Path,
    /// 1-based.
    number: usize,
    /// The line's text, without its line ending.
    text: &'a str,
}

impl Line<'_> {
    /// An error at byte `byte` of the line: `{path}:{line}:{column}: {message}`, the column
    /// 1-based in characters.
    fn error(&self, byte: usize, message: impl Display) -> anyhow::Error {
        let column = self
            .text
            .get(..byte)
            .map_or(1, |before| before.chars().count() + 1);
        anyhow!(
            "{}:{}:{column}: {message}",
            self.path.display(),
            self.number
        )
    }

    /// The number `word` spells (as f32 parses it, which is how `tobj` reads OBJ too).
    fn number(&self, word: Word<'_>) -> Result<f32> {
        word.text.parse().map_err(|_| {
            self.error(
                word.start,
                format_args!(
                    "`{}` is not a number; write it as a decimal number such as `1.5` or `-2e3`",
                    word.text
                ),
            )
        })
    }

    /// The finite number `word` spells.
    fn finite_number(&self, word: Word<'_>) -> Result<f32> {
        let number = self.number(word)?;
        if number.is_finite() {
            Ok(number)
        } else {
            Err(self.error(
                word.start,
                format_args!(
                    "`{}` is not a finite number (an f32 is at most 3.4e38 in size); give a \
                     finite one",
                    word.text
                ),
            ))
        }
    }

    /// Refuses a word after the last one a line of `what` has.
    fn refuse_more<'a>(&self, mut words: impl Iterator<Item = Word<'a>>, what: &str) -> Result<()> {
        match words.next() {
            Some(extra) => Err(self.error(
                extra.start,
                format_args!("`{}` after {what}; remove it", extra.text),
            )),
            None => Ok(()),
        }
    }
}

/// A whitespace-separated word of a line, and where it starts.
#[derive(Clone, Copy, Debug)]
struct Word<'a> {
    /// The word.
    text: &'a str,
    /// Its first byte's offset in the line.
    start: usize,
}

/// The whitespace-separated words of `line` (as `str::split_whitespace`, which `tobj` uses,
/// splits them), with where each starts.
fn words(line: &str) -> impl Iterator<Item = Word<'_>> {
    let mut searched = 0;
    std::iter::from_fn(move || {
        let rest = line.get(searched..)?;
        let start = searched + rest.find(|c: char| !c.is_whitespace())?;
        let word = line.get(start..)?;
        let length = word.find(char::is_whitespace).unwrap_or(word.len());
        searched = start + length;
        Some(Word {
            text: word.get(..length)?,
            start,
        })
    })
}

/// `bytes` as UTF-8 text (without a byte-order mark), or an error at the first byte that is
/// not, as `file:line:column`.
fn utf8_text<'a>(path: &Path, bytes: &'a [u8], what: &str) -> Result<&'a str> {
    match std::str::from_utf8(bytes) {
        Ok(text) => Ok(text.strip_prefix('\u{feff}').unwrap_or(text)),
        Err(error) => {
            let offset = error.valid_up_to();
            let before = bytes
                .get(..offset)
                .and_then(|valid| std::str::from_utf8(valid).ok())
                .unwrap_or_default();
            let line_start = before.rfind('\n').map_or(0, |newline| newline + 1);
            let line = Line {
                path,
                number: before.matches('\n').count() + 1,
                text: before.get(line_start..).unwrap_or_default(),
            };
            Err(line.error(
                offset - line_start,
                format_args!(
                    "byte {offset} is not UTF-8 text; {what} is text: save it as UTF-8 (or \
                     export the mesh again)"
                ),
            ))
        }
    }
}

/// Wavefront OBJ: a pre-scan of the lines that places what is wrong at `file:line:column`,
/// then `tobj` (triangulating, one index per vertex), its objects and groups merged.
mod obj {
    use super::{FileMesh, Line, Word, utf8_text, words};
    use anyhow::{Result, anyhow, bail};
    use std::borrow::Cow;
    use std::path::Path;

    /// Lines whose keyword this loader does without, blanked before `tobj` reads the text:
    /// polylines (`l`, no surface; `tobj` would make triangles of them) and materials
    /// (`mtllib`, `usemtl`; the scene file gives the mesh its material).
    const IGNORED_KEYWORDS: [&str; 3] = ["l", "mtllib", "usemtl"];

    /// The mesh the OBJ file at `path` holds in `bytes`.
    pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<FileMesh> {
        let text = utf8_text(path, bytes, "an OBJ file")?;
        let scan = Scan::of(path, text)?;
        if scan.faces == 0 {
            bail!(
                "{}: has no faces (f lines): is it a mesh? Export the model's surfaces as \
                 polygons (f lines), not only its points or lines",
                path.display()
            );
        }
        let text = if scan.ignored_lines == 0 {
            Cow::Borrowed(text)
        } else {
            Cow::Owned(without_ignored_lines(text))
        };
        let options = tobj::LoadOptions {
            single_index: true,
            triangulate: true,
            ..tobj::LoadOptions::default()
        };
        // Materials are never read: a missing .mtl file is no error.
        let (models, _materials) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .map_err(|error| {
            anyhow!(
                "{}: is not a valid OBJ file ({error}); check it in a modelling program \
                     and export it again",
                path.display()
            )
        })?;
        merge(path, &models)
    }

    /// `text` with the lines of [`IGNORED_KEYWORDS`] blanked (their line endings kept).
    fn without_ignored_lines(text: &str) -> String {
        text.split_inclusive('\n')
            .map(|line| {
                let ignored = words(line)
                    .next()
                    .is_some_and(|keyword| IGNORED_KEYWORDS.contains(&keyword.text));
                match (ignored, line.ends_with('\n')) {
                    (false, _) => line,
                    (true, true) => "\n",
                    (true, false) => "",
                }
            })
            .collect()
    }

    /// `tobj`'s models as one mesh: each model's indices offset by the vertices before it;
    /// normals only if every vertex of every model has one.
    fn merge(path: &Path, models: &[tobj::Model]) -> Result<FileMesh> {
        let every_vertex_has_a_normal = models
            .iter()
            .all(|model| model.mesh.normals.len() == model.mesh.positions.len());
        let mut mesh = FileMesh::default();
        for model in models {
            let offset = index(path, mesh.vertices.len())?;
            mesh.vertices.extend(triples(&model.mesh.positions));
            if every_vertex_has_a_normal {
                mesh.normals.extend(triples(&model.mesh.normals));
            }
            // Every index is below `count`, so adding `offset` stays below `total`.
            let total = index(path, mesh.vertices.len())?;
            let count = total - offset;
            for corners in model.mesh.indices.chunks_exact(3) {
                if let &[a, b, c] = corners {
                    if a.max(b).max(c) >= count {
                        bail!(
                            "{}: tobj gave a triangle with a corner past the model's {count} \
                             vertices; report this bug with the file",
                            path.display()
                        );
                    }
                    mesh.triangles.push([a + offset, b + offset, c + offset]);
                }
            }
        }
        Ok(mesh)
    }

    /// A count or index of vertices as a u32, which a mesh's indices are.
    fn index(path: &Path, count: usize) -> Result<u32> {
        u32::try_from(count).map_err(|_| {
            anyhow!(
                "{}: has more than 2³² vertices; simplify the mesh",
                path.display()
            )
        })
    }

    /// `tobj`'s flat list of coordinates (f32, or f64 with its `use_f64` feature) as
    /// points.
    fn triples<F: Copy + Into<f64>>(flat: &[F]) -> impl Iterator<Item = [f64; 3]> + '_ {
        flat.chunks_exact(3).filter_map(|point| match *point {
            [x, y, z] => Some([x.into(), y.into(), z.into()]),
            _ => None,
        })
    }

    /// Which of the three things a face's corner names.
    #[derive(Clone, Copy, Debug)]
    enum Element {
        /// A vertex (`v`), the corner's first index.
        Vertex,
        /// A texture coordinate (`vt`), the second.
        TextureCoordinate,
        /// A normal (`vn`), the third.
        Normal,
    }

    impl Element {
        /// The elements of a corner `v/vt/vn`, in order.
        const IN_A_CORNER: [Self; 3] = [Self::Vertex, Self::TextureCoordinate, Self::Normal];

        /// What it is called.
        const fn name(self) -> &'static str {
            match self {
                Self::Vertex => "vertex",
                Self::TextureCoordinate => "texture coordinate",
                Self::Normal => "normal",
            }
        }

        /// The line that defines one.
        const fn keyword(self) -> &'static str {
            match self {
                Self::Vertex => "v",
                Self::TextureCoordinate => "vt",
                Self::Normal => "vn",
            }
        }
    }

    /// Whether a file's vertices have colours (`v x y z r g b`), and the line of the first
    /// vertex, which says so: `tobj` takes colours of every vertex or of none.
    #[derive(Clone, Copy, Debug)]
    struct Colours {
        /// Whether the first vertex has colours.
        given: bool,
        /// The first vertex's line.
        line: usize,
    }

    /// The pre-scan of an OBJ file: every `v`, `vt`, `vn` and `f` line checked as `tobj` will
    /// read it, and what it counted (a face's indices refer to the elements above it).
    #[derive(Debug, Default)]
    struct Scan {
        /// The `v` lines so far.
        vertices: usize,
        /// The `vt` lines so far.
        texture_coordinates: usize,
        /// The `vn` lines so far.
        normals: usize,
        /// The `f` lines so far.
        faces: usize,
        /// The lines of [`IGNORED_KEYWORDS`] so far.
        ignored_lines: usize,
        /// Whether the vertices have colours, once there is a vertex.
        colours: Option<Colours>,
    }

    impl Scan {
        /// The scan of `text`, the file at `path`, or its first wrong line's error.
        fn of(path: &Path, text: &str) -> Result<Self> {
            let mut scan = Self::default();
            for (index, text) in text.lines().enumerate() {
                scan.line(Line {
                    path,
                    number: index + 1,
                    text,
                })?;
            }
            Ok(scan)
        }

        /// Checks and counts one line.
        fn line(&mut self, line: Line<'_>) -> Result<()> {
            let mut words = words(line.text);
            let Some(keyword) = words.next() else {
                return Ok(());
            };
            match keyword.text {
                "v" => self.vertex(line, keyword, &words.collect::<Vec<_>>()),
                "vt" => self.texture_coordinate(line, keyword, &words.collect::<Vec<_>>()),
                "vn" => self.normal(line, keyword, &words.collect::<Vec<_>>()),
                "f" => self.face(line, keyword, words),
                ignored if IGNORED_KEYWORDS.contains(&ignored) => {
                    self.ignored_lines += 1;
                    Ok(())
                }
                _ => Ok(()),
            }
        }

        /// A `v x y z`, `v x y z w` or `v x y z r g b` line.
        fn vertex(&mut self, line: Line<'_>, keyword: Word<'_>, values: &[Word<'_>]) -> Result<()> {
            const FORMS: &str = "a vertex is `v x y z`, `v x y z w` or `v x y z r g b`";
            let (coordinates, rest) = values.split_at(values.len().min(3));
            let &[x, y, z] = coordinates else {
                return Err(line.error(
                    keyword.start,
                    format_args!(
                        "a vertex with {} numbers: {FORMS}; give it x, y and z",
                        values.len()
                    ),
                ));
            };
            let point = [x, y, z].map(|word| line.finite_number(word));
            let [x, y, z] = point;
            let point = [x?, y?, z?];
            match *rest {
                [] => {}
                [w] => Self::weight(line, w, point)?,
                [red, green, blue] => {
                    for colour in [red, green, blue] {
                        line.number(colour)?;
                    }
                }
                [.., extra] => {
                    return Err(line.error(
                        extra.start,
                        format_args!(
                            "a vertex with {} numbers: {FORMS}; remove the extra ones",
                            values.len()
                        ),
                    ));
                }
            }
            self.same_colours(line, keyword, rest.len() == 3)?;
            self.vertices += 1;
            Ok(())
        }

        /// A vertex's weight `w`, which `tobj` divides its coordinates by.
        fn weight(line: Line<'_>, w: Word<'_>, point: [f32; 3]) -> Result<()> {
            let weight = line.finite_number(w)?;
            if weight == 0.0
                || point
                    .iter()
                    .any(|coordinate| !(coordinate / weight).is_finite())
            {
                return Err(line.error(
                    w.start,
                    format_args!(
                        "the weight w = {} makes the vertex's x/w, y/w, z/w beyond f32's range; \
                         give a weight near 1 (or none)",
                        w.text
                    ),
                ));
            }
            Ok(())
        }

        /// Refuses a vertex with colours in a file whose first vertex has none, or the other
        /// way around.
        fn same_colours(&mut self, line: Line<'_>, keyword: Word<'_>, given: bool) -> Result<()> {
            let first = *self.colours.get_or_insert(Colours {
                given,
                line: line.number,
            });
            if first.given == given {
                return Ok(());
            }
            let (this, that) = if given {
                ("has colours", "has none")
            } else {
                ("has no colours", "has")
            };
            Err(line.error(
                keyword.start,
                format_args!(
                    "this vertex {this} (`v x y z r g b`) but the first one, at line {}, {that}; \
                     give every vertex colours or none",
                    first.line
                ),
            ))
        }

        /// A `vt u v` or `vt u v w` line.
        fn texture_coordinate(
            &mut self,
            line: Line<'_>,
            keyword: Word<'_>,
            values: &[Word<'_>],
        ) -> Result<()> {
            if let Some(extra) = values.get(3) {
                return Err(line.error(
                    extra.start,
                    "a texture coordinate is `vt u v` or `vt u v w`; remove the extra numbers",
                ));
            }
            if values.len() < 2 {
                return Err(line.error(
                    keyword.start,
                    format_args!(
                        "a texture coordinate with {} numbers: it is `vt u v` or `vt u v w`; \
                         give it u and v (or remove the line and the faces' references to it)",
                        values.len()
                    ),
                ));
            }
            for &value in values {
                line.number(value)?;
            }
            self.texture_coordinates += 1;
            Ok(())
        }

        /// A `vn x y z` line: a direction, so finite and not zero.
        fn normal(&mut self, line: Line<'_>, keyword: Word<'_>, values: &[Word<'_>]) -> Result<()> {
            let &[x, y, z] = values else {
                let at = values.get(3).map_or(keyword.start, |extra| extra.start);
                return Err(line.error(
                    at,
                    format_args!(
                        "a normal with {} numbers: it is `vn x y z`; give it exactly x, y and z",
                        values.len()
                    ),
                ));
            };
            let [x, y, z] = [x, y, z].map(|word| line.finite_number(word));
            let squared_length: f64 = [x?, y?, z?]
                .iter()
                .map(|&coordinate| f64::from(coordinate).powi(2))
                .sum();
            if squared_length == 0.0 {
                return Err(line.error(
                    keyword.start,
                    "a normal of length 0 has no direction; give a nonzero normal (or drop the \
                     file's normals, `vn` lines and the faces' `//n`)",
                ));
            }
            self.normals += 1;
            Ok(())
        }

        /// An `f` line: at least 3 corners, each `v`, `v/vt`, `v//vn` or `v/vt/vn`, with
        /// indices of elements defined above it.
        fn face<'a>(
            &mut self,
            line: Line<'_>,
            keyword: Word<'_>,
            corners: impl Iterator<Item = Word<'a>>,
        ) -> Result<()> {
            let mut count = 0;
            for corner in corners {
                self.corner(line, corner)?;
                count += 1;
            }
            if count < 3 {
                return Err(line.error(
                    keyword.start,
                    format_args!(
                        "a face with {count} corners: a face needs at least 3 (`f 1 2 3`); give \
                         it 3 or more, or remove it"
                    ),
                ));
            }
            self.faces += 1;
            Ok(())
        }

        /// A face's corner: `v`, `v/vt`, `v//vn` or `v/vt/vn`.
        fn corner(&self, line: Line<'_>, corner: Word<'_>) -> Result<()> {
            if corner.text.split('/').count() > Element::IN_A_CORNER.len() {
                return Err(line.error(
                    corner.start,
                    format_args!(
                        "the corner `{}` has more than 3 indices: a corner is `v`, `v/vt`, \
                         `v//vn` or `v/vt/vn`; remove the extra ones",
                        corner.text
                    ),
                ));
            }
            let mut start = corner.start;
            for (part, element) in corner.text.split('/').zip(Element::IN_A_CORNER) {
                let index = Word { text: part, start };
                start += part.len() + 1;
                if !part.is_empty() {
                    self.index(line, index, element)?;
                } else if matches!(element, Element::Vertex) {
                    return Err(line.error(
                        index.start,
                        format_args!(
                            "the corner `{}` has no vertex index: a corner is `v`, `v/vt`, \
                             `v//vn` or `v/vt/vn`; give its vertex",
                            corner.text
                        ),
                    ));
                }
            }
            Ok(())
        }

        /// One index of a corner: 1 is the first element defined, -1 the last so far.
        fn index(&self, line: Line<'_>, index: Word<'_>, element: Element) -> Result<()> {
            let name = element.name();
            // As `tobj` reads it.
            let Ok(value) = index.text.parse::<isize>() else {
                return Err(line.error(
                    index.start,
                    format_args!(
                        "the {name} index `{}` is not a whole number; give 1 for the first \
                         {name} defined (or -1 for the last one so far)",
                        index.text
                    ),
                ));
            };
            let defined = match element {
                Element::Vertex => self.vertices,
                Element::TextureCoordinate => self.texture_coordinates,
                Element::Normal => self.normals,
            };
            if value == 0 {
                return Err(line.error(
                    index.start,
                    format_args!(
                        "{name} index 0: OBJ counts from 1 (and back from the last with -1); \
                         give 1 for the first {name}"
                    ),
                ));
            }
            let keyword = element.keyword();
            if defined == 0 {
                return Err(line.error(
                    index.start,
                    format_args!(
                        "{name} index {value} refers to no {name}: no `{keyword}` line comes \
                         before this face; define it with a `{keyword}` line above the face, or \
                         drop the index"
                    ),
                ));
            }
            if value.unsigned_abs() > defined {
                return Err(line.error(
                    index.start,
                    format_args!(
                        "{name} index {value} is out of range: {defined} `{keyword}` lines come \
                         before this face; refer to one of those (1 to {defined}, or -1 to \
                         -{defined} from the last)"
                    ),
                ));
            }
            Ok(())
        }
    }
}

/// STL, binary (an 80-byte header, a u32 triangle count, 50 bytes a triangle) or ASCII
/// (`solid` … `endsolid`), with the corners that are bitwise equal merged into one vertex.
mod stl {
    use super::{FileMesh, Line, Word, utf8_text, words};
    use anyhow::{Result, anyhow, bail};
    use std::collections::HashMap;
    use std::collections::hash_map::Entry;
    use std::path::Path;

    /// A binary STL's header: free bytes.
    const HEADER_BYTES: usize = 80;
    /// The header and the u32 triangle count after it.
    const PREAMBLE_BYTES: usize = HEADER_BYTES + 4;
    /// One triangle: its normal (12 bytes, ignored), 3 corners (36) and an attribute (2).
    const TRIANGLE_BYTES: usize = 50;
    /// Where a triangle's corners start in it.
    const CORNERS_OFFSET: usize = 12;
    /// Where they end.
    const CORNERS_END: usize = CORNERS_OFFSET + 36;

    /// The mesh the STL file at `path` holds in `bytes`.
    pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<FileMesh> {
        let mesh = if is_binary(bytes) {
            parse_binary(path, bytes)?
        } else {
            parse_ascii(path, utf8_text(path, bytes, "an ASCII STL file")?)?
        };
        if mesh.triangles.is_empty() {
            bail!(
                "{}: has no triangles: is it a mesh? Export the model's surfaces (not only \
                 its points or lines) as STL",
                path.display()
            );
        }
        Ok(mesh)
    }

    /// Whether `bytes` are a binary STL: its size is the 84 + 50·n bytes its count n makes,
    /// or it is not text starting with `solid` (then the binary parse says what is wrong).
    fn is_binary(bytes: &[u8]) -> bool {
        let size = u64::try_from(bytes.len()).unwrap_or(u64::MAX);
        if triangle_count(bytes).is_some_and(|count| expected_size(count) == size) {
            return true;
        }
        let start = bytes.trim_ascii_start();
        let says_solid = start
            .get(..5)
            .is_some_and(|word| word.eq_ignore_ascii_case(b"solid"));
        !(says_solid && std::str::from_utf8(bytes).is_ok())
    }

    /// The triangle count a binary STL's header gives, at byte 80.
    fn triangle_count(bytes: &[u8]) -> Option<u32> {
        let count = bytes.get(HEADER_BYTES..PREAMBLE_BYTES)?;
        Some(u32::from_le_bytes(count.try_into().ok()?))
    }

    /// The size of a binary STL of `count` triangles.
    fn expected_size(count: u32) -> u64 {
        PREAMBLE_BYTES as u64 + TRIANGLE_BYTES as u64 * u64::from(count)
    }

    /// A binary STL's mesh.
    fn parse_binary(path: &Path, bytes: &[u8]) -> Result<FileMesh> {
        let Some(count) = triangle_count(bytes) else {
            bail!(
                "{}: byte {}: the file ends inside a binary STL's first 84 bytes (an 80-byte \
                 header, then the triangle count); an ASCII STL starts with `solid`: export \
                 the mesh as STL again",
                path.display(),
                bytes.len()
            );
        };
        check_binary_size(path, bytes.len(), count)?;
        let mut merged = MergedVertices::default();
        let triangles = bytes.get(PREAMBLE_BYTES..).unwrap_or_default();
        for (index, triangle) in triangles.chunks_exact(TRIANGLE_BYTES).enumerate() {
            let offset = PREAMBLE_BYTES + TRIANGLE_BYTES * index;
            let corners = binary_corners(path, offset, triangle)?;
            merged.push_triangle(path, corners)?;
        }
        Ok(merged.into_mesh())
    }

    /// Refuses a binary STL whose size is not what its triangle count makes.
    fn check_binary_size(path: &Path, size: usize, count: u32) -> Result<()> {
        let expected = expected_size(count);
        let size_u64 = u64::try_from(size).unwrap_or(u64::MAX);
        if size_u64 < expected {
            let held = (size - PREAMBLE_BYTES) / TRIANGLE_BYTES;
            bail!(
                "{}: byte {size}: the file ends there, where {expected} bytes were expected: it \
                 holds {held} of the {count} triangles its header counts (the u32 at byte 80); \
                 the file is truncated: copy or export it again",
                path.display()
            );
        }
        if size_u64 > expected {
            bail!(
                "{}: byte {expected}: the file goes on for {} bytes after the {count} triangles \
                 its header counts (the u32 at byte 80); it is no binary STL as written (an \
                 ASCII STL starts with `solid`): export the mesh as STL again",
                path.display(),
                size_u64 - expected
            );
        }
        Ok(())
    }

    /// The 3 corners of the binary triangle at byte `offset`, each coordinate finite.
    fn binary_corners(path: &Path, offset: usize, triangle: &[u8]) -> Result<[[f32; 3]; 3]> {
        let mut values = [0.0; 9];
        let bytes = triangle
            .get(CORNERS_OFFSET..CORNERS_END)
            .unwrap_or_default();
        for ((slot, value), four) in values.iter_mut().enumerate().zip(bytes.chunks_exact(4)) {
            *value = f32::from_le_bytes(four.try_into()?);
            if !value.is_finite() {
                bail!(
                    "{}: byte {}: triangle {}'s corner {} has the coordinate {value}, which is \
                     not a finite number; repair the mesh or export it again",
                    path.display(),
                    offset + CORNERS_OFFSET + 4 * slot,
                    (offset - PREAMBLE_BYTES) / TRIANGLE_BYTES + 1,
                    slot / 3 + 1
                );
            }
        }
        let [ax, ay, az, bx, by, bz, cx, cy, cz] = values;
        Ok([[ax, ay, az], [bx, by, bz], [cx, cy, cz]])
    }

    /// Where an ASCII STL's parse is: what the next line must be.
    #[derive(Clone, Copy, Debug)]
    enum Expected {
        /// `solid name`, the file's first line.
        Solid,
        /// `facet normal nx ny nz`, or `endsolid` to close the solid.
        FacetOrEndsolid,
        /// `outer loop`.
        OuterLoop,
        /// The first `vertex x y z`.
        FirstVertex,
        /// The second, after the first.
        SecondVertex([f32; 3]),
        /// The third, after the first two.
        ThirdVertex([f32; 3], [f32; 3]),
        /// `endloop` after the loop's 3 corners.
        Endloop([[f32; 3]; 3]),
        /// `endfacet` after the loop.
        Endfacet([[f32; 3]; 3]),
        /// Another `solid`, or the end of the file.
        SolidOrEnd,
    }

    impl Expected {
        /// What the line expected is, in an error.
        const fn described(self) -> &'static str {
            match self {
                Self::Solid => "`solid name`",
                Self::FacetOrEndsolid => "`facet normal nx ny nz` or `endsolid`",
                Self::OuterLoop => "`outer loop`",
                Self::FirstVertex => "`vertex x y z` (the first of the facet's 3)",
                Self::SecondVertex(_) => "`vertex x y z` (the second of the facet's 3)",
                Self::ThirdVertex(..) => "`vertex x y z` (the third of the facet's 3)",
                Self::Endloop(_) => "`endloop` (a facet's loop has exactly 3 vertices)",
                Self::Endfacet(_) => "`endfacet`",
                Self::SolidOrEnd => "the end of the file or another `solid`",
            }
        }
    }

    /// An ASCII STL's mesh.
    fn parse_ascii(path: &Path, text: &str) -> Result<FileMesh> {
        let mut expected = Expected::Solid;
        let mut merged = MergedVertices::default();
        let mut last_line = None;
        for (index, text) in text.lines().enumerate() {
            let line = Line {
                path,
                number: index + 1,
                text,
            };
            let mut words = words(text);
            let Some(keyword) = words.next() else {
                continue;
            };
            last_line = Some(line);
            expected = ascii_line(line, expected, keyword, words, &mut merged)?;
        }
        if matches!(expected, Expected::SolidOrEnd) {
            return Ok(merged.into_mesh());
        }
        let message = format!(
            "the file ends where {} was expected: it may be truncated; export it again (or end \
             it with `endsolid`)",
            expected.described()
        );
        Err(match last_line {
            Some(line) => line.error(line.text.len(), message),
            None => anyhow!("{}:1:1: {message}", path.display()),
        })
    }

    /// Reads the line that starts with `keyword` where `expected`, and says what is expected
    /// next.
    fn ascii_line<'a>(
        line: Line<'_>,
        expected: Expected,
        keyword: Word<'_>,
        mut words: impl Iterator<Item = Word<'a>>,
        merged: &mut MergedVertices,
    ) -> Result<Expected> {
        let is = |name: &str| keyword.text.eq_ignore_ascii_case(name);
        let next = match expected {
            Expected::Solid | Expected::SolidOrEnd if is("solid") => {
                return Ok(Expected::FacetOrEndsolid);
            }
            Expected::FacetOrEndsolid if is("endsolid") => return Ok(Expected::SolidOrEnd),
            Expected::FacetOrEndsolid if is("facet") => {
                facet_normal(line, keyword, &mut words)?;
                Expected::OuterLoop
            }
            Expected::OuterLoop if is("outer") => {
                match words.next() {
                    Some(word) if word.text.eq_ignore_ascii_case("loop") => {}
                    _ => return Err(line.error(keyword.start, "expected `outer loop`; write it")),
                }
                Expected::FirstVertex
            }
            Expected::FirstVertex if is("vertex") => {
                Expected::SecondVertex(vertex(line, keyword, &mut words)?)
            }
            Expected::SecondVertex(a) if is("vertex") => {
                Expected::ThirdVertex(a, vertex(line, keyword, &mut words)?)
            }
            Expected::ThirdVertex(a, b) if is("vertex") => {
                Expected::Endloop([a, b, vertex(line, keyword, &mut words)?])
            }
            Expected::Endloop(corners) if is("endloop") => Expected::Endfacet(corners),
            Expected::Endfacet(corners) if is("endfacet") => {
                merged.push_triangle(line.path, corners)?;
                Expected::FacetOrEndsolid
            }
            _ => {
                return Err(line.error(
                    keyword.start,
                    format_args!(
                        "expected {}, found `{}`; an ASCII STL is `solid name`, then for each \
                         triangle `facet normal nx ny nz`, `outer loop`, 3 × `vertex x y z`, \
                         `endloop`, `endfacet`, and last `endsolid`",
                        expected.described(),
                        keyword.text
                    ),
                ));
            }
        };
        line.refuse_more(words, expected.described())?;
        Ok(next)
    }

    /// The rest of a `facet normal nx ny nz` line (the normal, which is not kept, must be 3
    /// numbers).
    fn facet_normal<'a>(
        line: Line<'_>,
        keyword: Word<'_>,
        words: &mut impl Iterator<Item = Word<'a>>,
    ) -> Result<()> {
        let normal = words.next();
        if !normal.is_some_and(|word| word.text.eq_ignore_ascii_case("normal")) {
            return Err(line.error(
                normal.map_or(keyword.start, |word| word.start),
                "expected `facet normal nx ny nz`; write `normal` after `facet`",
            ));
        }
        for _ in 0..3 {
            match words.next() {
                Some(word) => line.number(word).map(drop)?,
                None => {
                    return Err(line.error(
                        line.text.len(),
                        "a facet's normal is 3 numbers, `facet normal nx ny nz`; give all 3 \
                         (0 0 0 if unknown)",
                    ));
                }
            }
        }
        Ok(())
    }

    /// The point of a `vertex x y z` line.
    fn vertex<'a>(
        line: Line<'_>,
        keyword: Word<'_>,
        words: &mut impl Iterator<Item = Word<'a>>,
    ) -> Result<[f32; 3]> {
        let mut point = [0.0; 3];
        for coordinate in &mut point {
            let Some(word) = words.next() else {
                return Err(line.error(
                    keyword.start,
                    "a vertex is 3 numbers, `vertex x y z`; give x, y and z",
                ));
            };
            *coordinate = line.finite_number(word)?;
        }
        Ok(point)
    }

    /// The vertices of a mesh being read, those bitwise equal merged, and its triangles.
    #[derive(Debug, Default)]
    struct MergedVertices {
        /// Each vertex's index, by its coordinates' bits.
        index_of_bits: HashMap<[u32; 3], u32>,
        /// The vertices, in the order first met.
        vertices: Vec<[f32; 3]>,
        /// The triangles so far.
        triangles: Vec<[u32; 3]>,
    }

    impl MergedVertices {
        /// Adds the triangle of `corners`.
        fn push_triangle(&mut self, path: &Path, corners: [[f32; 3]; 3]) -> Result<()> {
            let [a, b, c] = corners;
            let triangle = [
                self.index(path, a)?,
                self.index(path, b)?,
                self.index(path, c)?,
            ];
            self.triangles.push(triangle);
            Ok(())
        }

        /// The index of the vertex at `point`, added if it is new.
        fn index(&mut self, path: &Path, point: [f32; 3]) -> Result<u32> {
            match self.index_of_bits.entry(point.map(f32::to_bits)) {
                Entry::Occupied(known) => Ok(*known.get()),
                Entry::Vacant(new) => {
                    let index = u32::try_from(self.vertices.len()).map_err(|_| {
                        anyhow!(
                            "{}: has more than 2³² vertices; simplify the mesh",
                            path.display()
                        )
                    })?;
                    self.vertices.push(point);
                    Ok(*new.insert(index))
                }
            }
        }

        /// The mesh read (STL gives no normals a vertex).
        fn into_mesh(self) -> FileMesh {
            FileMesh {
                vertices: self
                    .vertices
                    .into_iter()
                    .map(|point| point.map(f64::from))
                    .collect(),
                triangles: self.triangles,
                normals: Vec::new(),
            }
        }
    }
}

/// A 3×3 matrix, by rows.
type Matrix = [[f64; 3]; 3];

/// How a mesh is placed: p ↦ `rotation`·(`scale`·p) + `translate`.
#[derive(Clone, Copy, Debug)]
struct Placement {
    /// The scale, applied first.
    scale: f64,
    /// R(z)·R(y)·R(x).
    rotation: Matrix,
    /// The translation, applied last.
    translate: [f64; 3],
}

impl Placement {
    /// The placement `spec` gives, refused if it is not finite or scales by 0.
    fn of(spec: &MeshFile) -> Result<Self> {
        let refuse = |what: String| {
            anyhow!(
                "the mesh `{}`: {what}; give finite numbers (a nonzero scale)",
                spec.file
            )
        };
        if !spec.scale.is_finite() || spec.scale == 0.0 {
            return Err(refuse(format!("scale = {}", spec.scale)));
        }
        if spec.rotate_degrees.iter().any(|angle| !angle.is_finite()) {
            return Err(refuse(format!(
                "rotate_degrees = {:?}",
                spec.rotate_degrees
            )));
        }
        if spec.translate.iter().any(|offset| !offset.is_finite()) {
            return Err(refuse(format!("translate = {:?}", spec.translate)));
        }
        let [x, y, z] = spec.rotate_degrees.map(f64::from);
        Ok(Self {
            scale: f64::from(spec.scale),
            rotation: product(&rotation_z(z), &product(&rotation_y(y), &rotation_x(x))),
            translate: spec.translate.map(f64::from),
        })
    }

    /// `mesh` placed, or an error naming a point placed beyond f32's range.
    fn place(&self, path: &Path, mesh: FileMesh) -> Result<LoadedMesh> {
        let vertices = mesh
            .vertices
            .iter()
            .map(|&point| self.point(path, point))
            .collect::<Result<_>>()?;
        let normals = mesh
            .normals
            .iter()
            .map(|&normal| self.normal(path, normal))
            .collect::<Result<_>>()?;
        Ok(LoadedMesh {
            vertices,
            triangles: mesh.triangles,
            normals,
        })
    }

    /// `point` placed and rounded to f32, refused if beyond its range.
    fn point(&self, path: &Path, point: [f64; 3]) -> Result<[f32; 3]> {
        let scaled = point.map(|coordinate| coordinate * self.scale);
        let turned = transform(&self.rotation, scaled);
        let placed = add(turned, self.translate).map(to_f32);
        if let Some((axis, value)) = ["x", "y", "z"]
            .into_iter()
            .zip(placed)
            .find(|(_, value)| !value.is_finite())
        {
            let [px, py, pz] = point;
            bail!(
                "{}: the vertex ({px}, {py}, {pz}) placed (scale {}, then rotated, then \
                 translated by {:?}) has {axis} = {value}, beyond f32's range (about ±3.4e38); \
                 give the mesh a smaller scale (or a smaller translate)",
                path.display(),
                self.scale,
                self.translate
            );
        }
        Ok(placed)
    }

    /// `normal` turned with the mesh (flipped if it is mirrored), of unit length.
    fn normal(&self, path: &Path, normal: [f64; 3]) -> Result<[f32; 3]> {
        let turned = transform(&self.rotation, normal);
        let length = dot(turned, turned).sqrt();
        if !(length.is_finite() && length > 0.0) {
            let [nx, ny, nz] = normal;
            bail!(
                "{}: the normal ({nx}, {ny}, {nz}) has no direction; give the file nonzero \
                 normals (or none)",
                path.display()
            );
        }
        let sign = if self.scale < 0.0 { -1.0 } else { 1.0 };
        Ok(turned.map(|coordinate| to_f32(sign * coordinate / length)))
    }
}

/// `value` rounded to the nearest f32 (infinite beyond its range): the one rounding of a
/// placed coordinate.
#[allow(clippy::cast_possible_truncation)]
const fn to_f32(value: f64) -> f32 {
    value as f32
}

/// The sine and cosine of `degrees`, exact at multiples of 90° (so that a quarter turn
/// moves a point exactly).
fn sin_cos_degrees(degrees: f64) -> (f64, f64) {
    match degrees.rem_euclid(360.0) {
        0.0 => (0.0, 1.0),
        90.0 => (1.0, 0.0),
        180.0 => (0.0, -1.0),
        270.0 => (-1.0, 0.0),
        _ => degrees.to_radians().sin_cos(),
    }
}

/// The rotation by `degrees` about x (right-handed: +90° takes +y to +z).
fn rotation_x(degrees: f64) -> Matrix {
    let (sin, cos) = sin_cos_degrees(degrees);
    [[1.0, 0.0, 0.0], [0.0, cos, -sin], [0.0, sin, cos]]
}

/// The rotation by `degrees` about y (right-handed: +90° takes +z to +x, +x to -z).
fn rotation_y(degrees: f64) -> Matrix {
    let (sin, cos) = sin_cos_degrees(degrees);
    [[cos, 0.0, sin], [0.0, 1.0, 0.0], [-sin, 0.0, cos]]
}

/// The rotation by `degrees` about z (right-handed: +90° takes +x to +y).
fn rotation_z(degrees: f64) -> Matrix {
    let (sin, cos) = sin_cos_degrees(degrees);
    [[cos, -sin, 0.0], [sin, cos, 0.0], [0.0, 0.0, 1.0]]
}

/// The dot product of `a` and `b`.
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `a` + `b`.
fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let [ax, ay, az] = a;
    let [bx, by, bz] = b;
    [ax + bx, ay + by, az + bz]
}

/// `matrix`·`vector`.
fn transform(matrix: &Matrix, vector: [f64; 3]) -> [f64; 3] {
    matrix.map(|row| dot(row, vector))
}

/// `a`·`b`: `b` applied first.
fn product(a: &Matrix, b: &Matrix) -> Matrix {
    let [[b00, b01, b02], [b10, b11, b12], [b20, b21, b22]] = *b;
    let columns = [[b00, b10, b20], [b01, b11, b21], [b02, b12, b22]];
    a.map(|row| columns.map(|column| dot(row, column)))
}

/// Normals at the corners of a mesh's triangles, for smooth shading: `corners[k]` names the
/// normals at triangle k's corners among `normals`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerNormals<'a> {
    /// The unit normals.
    pub normals: &'a [[f32; 3]],
    /// Each triangle's corners' normals, as indices into `normals`.
    pub corners: &'a [[u32; 3]],
}

/// A mesh as Wavefront OBJ text, which a scene's `shape.mesh` reads back exactly: a `v x y z`
/// line per vertex the triangles name (in their order; each coordinate the shortest text that
/// reads back as the same f32); with `normals`, a `vn x y z` line per normal the corners name;
/// then an `f a b c` line per triangle (1-based; `f a//i b//j c//k` with normals). Normals
/// that are not one set per triangle, or name a normal that is not there or zero, are left
/// out: the mesh is written flat.
#[must_use]
pub fn obj_text(
    vertices: &[[f32; 3]],
    triangles: &[[u32; 3]],
    normals: Option<CornerNormals<'_>>,
) -> String {
    let normals = normals.filter(|given| {
        given.corners.len() == triangles.len()
            && given.corners.iter().flatten().all(|&i| {
                given
                    .normals
                    .get(i as usize)
                    .is_some_and(|n| *n != [0.0; 3])
            })
    });
    let named_vertices = Named::of(triangles);
    let named_normals = normals.map(|given| Named::of(given.corners));
    let lines = |named: &Named, keyword: &str, list: &[[f32; 3]]| -> String {
        named
            .0
            .iter()
            .map(|&i| {
                let [x, y, z] = list.get(i as usize).copied().unwrap_or_default();
                format!("{keyword} {x} {y} {z}\n")
            })
            .collect()
    };
    let mut text = lines(&named_vertices, "v", vertices);
    if let (Some(given), Some(named)) = (normals, &named_normals) {
        text += &lines(named, "vn", given.normals);
    }
    for (k, triangle) in triangles.iter().enumerate() {
        let [a, b, c] = triangle.map(|i| named_vertices.place(i));
        let corners = normals
            .zip(named_normals.as_ref())
            .and_then(|(given, named)| {
                given
                    .corners
                    .get(k)
                    .map(|corners| corners.map(|i| named.place(i)))
            });
        text += &match corners {
            Some([i, j, l]) => format!("f {a}//{i} {b}//{j} {c}//{l}\n"),
            None => format!("f {a} {b} {c}\n"),
        };
    }
    text
}

/// The indices a list of triangles names, ascending, each once: what an OBJ file writes, and
/// where (1-based).
struct Named(Vec<u32>);

impl Named {
    fn of(triangles: &[[u32; 3]]) -> Self {
        let mut named: Vec<u32> = triangles.iter().flatten().copied().collect();
        named.sort_unstable();
        named.dedup();
        Self(named)
    }

    /// Index `i`'s place in the file, from 1.
    fn place(&self, i: u32) -> usize {
        self.0.binary_search(&i).map_or(0, |place| place + 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    /// A fresh directory of the test's own.
    fn scratch_dir(test: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("obscura-mesh_file-{test}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn obj_text_reads_back_as_the_mesh_it_writes() {
        // Two triangles of four vertices and a fifth vertex neither names.
        let vertices = [
            [0.1, 0.0, 0.0],
            [1.0, 1e-7, 0.0],
            [0.0, 1.0, -3.5],
            [9.0, 9.0, 9.0],
            [1.0, 1.0, 0.0],
        ];
        let up = [0.0, 0.6, 0.8];
        let triangles = [[0, 1, 2], [1, 4, 2]];
        let spec = MeshFile::at("written.obj".into());
        for (test, normals, expected) in [
            ("flat", vec![], vec![]),
            ("smooth", vec![up; 5], vec![up; 4]),
            ("partly", vec![up, up, up, up, [0.0; 3]], vec![]),
        ] {
            let given = CornerNormals {
                normals: &normals,
                corners: &triangles,
            };
            let text = obj_text(&vertices, &triangles, Some(given));
            let loaded = load_placed(test, &spec, text.as_bytes()).unwrap();
            assert_eq!(loaded.vertices, [0, 1, 2, 4].map(|i| vertices[i]), "{test}");
            assert_eq!(loaded.normals, expected, "{test}");
            assert_eq!(loaded.triangles, [[0, 1, 2], [1, 3, 2]], "{test}");
        }
    }

    /// `spec` loaded from `bytes` written as `spec.file` in the test's directory.
    fn load_placed(test: &str, spec: &MeshFile, bytes: &[u8]) -> Result<LoadedMesh> {
        let dir = scratch_dir(test);
        std::fs::write(dir.join(&spec.file), bytes).unwrap();
        let loaded = load(&dir, spec);
        std::fs::remove_dir_all(&dir).unwrap();
        loaded
    }

    /// A mesh file named `file` placed as it is.
    fn unplaced(file: &str) -> MeshFile {
        MeshFile {
            file: file.to_owned(),
            scale: 1.0,
            rotate_degrees: [0.0; 3],
            translate: [0.0; 3],
        }
    }

    /// `bytes` loaded as the file `file`, placed as it is.
    fn load_bytes(test: &str, file: &str, bytes: &[u8]) -> Result<LoadedMesh> {
        load_placed(test, &unplaced(file), bytes)
    }

    /// The error of loading `bytes` as `file`, as text.
    fn error_of(test: &str, file: &str, bytes: &[u8]) -> String {
        match load_bytes(test, file, bytes) {
            Ok(mesh) => panic!("{file} loaded as {mesh:?}, expected an error"),
            Err(error) => format!("{error:#}"),
        }
    }

    /// The unit cube's corners.
    const CUBE_VERTICES: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
                                 v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";

    /// The unit cube's faces as quads, anticlockwise from outside.
    const CUBE_QUADS: &str = "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

    #[test]
    fn a_cube_of_quads_is_12_triangles_on_8_vertices_without_normals() {
        let text = format!("# a cube\n{CUBE_VERTICES}{CUBE_QUADS}");
        let mesh = load_bytes("cube_quads", "cube.obj", text.as_bytes()).unwrap();
        assert_eq!(mesh.vertices.len(), 8);
        assert_eq!(mesh.triangles.len(), 12);
        assert!(mesh.normals.is_empty());
        let mut corners: Vec<_> = mesh.vertices.clone();
        corners.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(corners.first(), Some(&[0.0, 0.0, 0.0]));
        assert_eq!(corners.last(), Some(&[1.0, 1.0, 1.0]));
        // The first quad 1 4 3 2 is the fan 1 4 3, 1 3 2.
        let first: Vec<_> = mesh.triangles[..2]
            .iter()
            .map(|triangle| triangle.map(|index| mesh.vertices[index as usize]))
            .collect();
        assert_eq!(
            first,
            [
                [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]],
                [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0]],
            ]
        );
    }

    #[test]
    fn a_cube_with_corner_normals_has_a_unit_normal_per_vertex() {
        let normals = "vn 0 0 -2\nvn 0 0 3\nvn 0 -1 0\nvn 1 0 0\nvn 0 1 0\nvn -1 0 0\n";
        let faces = "f 1//1 4//1 3//1 2//1\nf 5//2 6//2 7//2 8//2\nf 1//3 2//3 6//3 5//3\n\
                     f 2//4 3//4 7//4 6//4\nf 3//5 4//5 8//5 7//5\nf 4//6 1//6 5//6 8//6\n";
        let text = format!("{CUBE_VERTICES}{normals}{faces}");
        let mesh = load_bytes("cube_normals", "cube.obj", text.as_bytes()).unwrap();
        assert_eq!(mesh.triangles.len(), 12);
        // A corner is a vertex and a normal: each of the 8 corners has 3 normals.
        assert_eq!(mesh.vertices.len(), 24);
        assert_eq!(mesh.normals.len(), mesh.vertices.len());
        for normal in &mesh.normals {
            let length = normal.iter().map(|c| c * c).sum::<f32>().sqrt();
            assert!((length - 1.0).abs() < 1e-6, "{normal:?}");
        }
        assert!(mesh.normals.contains(&[0.0, 0.0, -1.0]));
        assert!(mesh.normals.contains(&[0.0, 0.0, 1.0]));
    }

    #[test]
    fn an_obj_as_exporters_write_it_loads() {
        let text = "\u{feff}# exported\r\nv 0 0 0 1 0 0\r\nv\t1 0 0 0 1 0\r\n\
                    v 1 1 0 0 0 1\r\nv 0.5 2 0 1 1 1\r\nv -0.5 1 0 0 0 0\r\n\
                    vt 0 0 0\r\nvt 1 0\r\ns off\r\np 1\r\ng pentagon\r\n\
                    f 1/1 2/2 3/1 4/2 5/1\r\n";
        let mesh = load_bytes("exporters", "exported.obj", text.as_bytes()).unwrap();
        assert_eq!(mesh.triangles, [[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
        assert_eq!(mesh.vertices.get(3), Some(&[0.5, 2.0, 0.0]));
    }

    #[test]
    fn normals_at_only_some_corners_are_dropped() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3\n";
        let mesh = load_bytes("some_normals", "some.obj", text.as_bytes()).unwrap();
        assert_eq!(mesh.vertices.len(), 3);
        assert!(mesh.normals.is_empty());
    }

    #[test]
    fn placing_scales_then_rotates_then_translates() {
        let spec = MeshFile {
            scale: 2.0,
            rotate_degrees: [0.0, 90.0, 0.0],
            translate: [1.0, 0.0, 0.0],
            ..unplaced("placed.obj")
        };
        let text = "v 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n";
        let mesh = load_placed("placing", &spec, text.as_bytes()).unwrap();
        assert_eq!(
            mesh.vertices,
            [[1.0, 0.0, -2.0], [1.0, 2.0, 0.0], [3.0, 0.0, 0.0]]
        );
    }

    #[test]
    fn rotations_are_about_x_then_y_then_z() {
        let text = "v 0 1 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n";
        let turned = |test: &str, rotate_degrees: [f32; 3]| {
            let spec = MeshFile {
                rotate_degrees,
                ..unplaced("turned.obj")
            };
            load_placed(test, &spec, text.as_bytes()).unwrap().vertices
        };
        // About x first: (0,1,0) → (0,0,1), then about y → (1,0,0); y first would leave
        // (0,1,0) alone and then take it to (0,0,1).
        let x_then_y = turned("rotate_xy", [90.0, 90.0, 0.0]);
        assert_eq!(x_then_y.first(), Some(&[1.0, 0.0, 0.0]));
        // About y before z: (1,0,0) → (0,0,-1), which z leaves; z first would give (0,1,0).
        let y_then_z = turned("rotate_yz", [0.0, 90.0, 90.0]);
        assert_eq!(y_then_z.get(1), Some(&[0.0, 0.0, -1.0]));
        // An angle that is no quarter turn: (0,0,1) about x by 30° → (0, -1/2, √3/2).
        let thirty = turned("rotate_30", [30.0, 0.0, 0.0]);
        let [x, y, z] = thirty[2];
        assert!(
            x.abs() < 1e-7 && (y + 0.5).abs() < 1e-7 && (z - 0.75_f32.sqrt()).abs() < 1e-7,
            "{x} {y} {z}"
        );
    }

    #[test]
    fn normals_turn_with_the_mesh_and_flip_when_it_is_mirrored() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 5\nf 1//1 2//1 3//1\n";
        let spec = MeshFile {
            rotate_degrees: [90.0, 0.0, 0.0],
            ..unplaced("normals.obj")
        };
        let turned = load_placed("normals_turn", &spec, text.as_bytes()).unwrap();
        assert_eq!(turned.normals, [[0.0, -1.0, 0.0]; 3]);
        let mirrored_spec = MeshFile {
            scale: -3.0,
            ..spec
        };
        let mirrored = load_placed("normals_mirror", &mirrored_spec, text.as_bytes()).unwrap();
        assert_eq!(mirrored.normals, [[0.0, 1.0, 0.0]; 3]);
        assert_eq!(mirrored.vertices.get(1), Some(&[-3.0, 0.0, 0.0]));
        assert_eq!(mirrored.triangles, turned.triangles);
    }

    #[test]
    fn negative_indices_count_back_from_the_last_vertex_so_far() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf -4 -1 2\n";
        let mesh = load_bytes("negative", "negative.obj", text.as_bytes()).unwrap();
        let triangles: Vec<_> = mesh
            .triangles
            .iter()
            .map(|triangle| triangle.map(|index| mesh.vertices[index as usize]))
            .collect();
        assert_eq!(
            triangles,
            [
                [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
                [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]],
            ]
        );
    }

    #[test]
    fn material_lines_are_tolerated_when_the_mtl_file_is_missing() {
        let text = "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n\
                    usemtl\nl 1 2 3\nusemtl\tblue\nf 3 2 1\n";
        let mesh = load_bytes("materials", "materials.obj", text.as_bytes()).unwrap();
        assert_eq!(mesh.triangles.len(), 2);
    }

    #[test]
    fn objects_and_groups_merge_into_one_mesh() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\no first\nf 1 2 3\ng second\nf 1 3 4\n\
                    o third\ng\nf 4 3 2 1\n";
        let mesh = load_bytes("groups", "groups.obj", text.as_bytes()).unwrap();
        assert_eq!(mesh.triangles.len(), 4);
        let max_index = mesh.triangles.iter().flatten().max().copied().unwrap();
        assert_eq!(max_index as usize, mesh.vertices.len() - 1);
        let corners: Vec<_> = mesh
            .triangles
            .iter()
            .map(|triangle| triangle.map(|index| mesh.vertices[index as usize]))
            .collect();
        assert_eq!(
            corners.get(1),
            Some(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
        );
        assert_eq!(
            corners.get(3),
            Some(&[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
        );
    }

    #[test]
    fn a_face_index_out_of_range_is_placed_at_its_line_and_column() {
        let text = "v 0 0 0\nv 1 0 0\nf 1 2 9\n";
        let error = error_of("out_of_range", "teapot.obj", text.as_bytes());
        assert!(error.contains("teapot.obj:3:7: vertex index 9"), "{error}");
        assert!(error.contains("2 `v` lines"), "{error}");
    }

    #[test]
    fn bad_corners_are_placed_at_their_line_and_column() {
        let cases = [
            ("f 1 2 0\n", ":4:7:", "index 0"),
            ("f 1 -4 2\n", ":4:5:", "vertex index -4"),
            ("f 1 2/x 3\n", ":4:7:", "`x` is not a whole number"),
            ("f 1 2/1 3\n", ":4:7:", "texture coordinate index 1"),
            ("f 1 2 3//2\n", ":4:10:", "normal index 2"),
            ("f 1 2\n", ":4:1:", "2 corners"),
            ("f 1/1/1/1 2 3\n", ":4:3:", "more than 3 indices"),
            ("f /1 2 3\n", ":4:3:", "no vertex index"),
        ];
        for (face, place, what) in cases {
            let text = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\n{face}");
            let error = error_of("bad_corners", "corners.obj", text.as_bytes());
            assert!(
                error.contains(&format!("corners.obj{place}")) && error.contains(what),
                "{face}: {error}"
            );
        }
    }

    #[test]
    fn a_vertex_of_two_numbers_is_placed_at_its_line() {
        let text = "v 0 0 0\n  v 1 2\nv 0 1 0\nf 1 2 3\n";
        let error = error_of("two_numbers", "flat.obj", text.as_bytes());
        assert!(
            error.contains("flat.obj:2:3: a vertex with 2 numbers"),
            "{error}"
        );
    }

    #[test]
    fn wrong_vertices_and_normals_are_placed() {
        let cases = [
            ("v 0 0 zero\n", ":1:7:", "`zero` is not a number"),
            ("v 0 0 1e39\n", ":1:7:", "not a finite number"),
            ("v 0 0 nan\n", ":1:7:", "not a finite number"),
            ("v 1 2 3 0\n", ":1:9:", "weight"),
            ("v 1 2 3 4 5\n", ":1:11:", "5 numbers"),
            ("v 1 2 3 1 1 1\nv 1 2 3\n", ":2:1:", "at line 1"),
            ("vn 0 0 0\n", ":1:1:", "length 0"),
            ("vn 0 1\n", ":1:1:", "2 numbers"),
            ("vt 1\n", ":1:1:", "1 numbers"),
        ];
        for (lines, place, what) in cases {
            let error = error_of("wrong_vertices", "wrong.obj", lines.as_bytes());
            assert!(
                error.contains(&format!("wrong.obj{place}")) && error.contains(what),
                "{lines}: {error}"
            );
        }
    }

    #[test]
    fn an_unknown_extension_is_refused_naming_those_read() {
        let error = error_of("extension", "mesh.ply", b"ply\n");
        assert!(error.contains("`.ply`"), "{error}");
        assert!(
            error.contains("`.obj`") && error.contains("`.stl`"),
            "{error}"
        );
    }

    #[test]
    fn extensions_are_read_in_any_case() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let mesh = load_bytes("extension_case", "LOUD.OBJ", text.as_bytes()).unwrap();
        assert_eq!(mesh.triangles, [[0, 1, 2]]);
    }

    #[test]
    fn a_mesh_without_faces_is_refused() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n";
        let error = error_of("no_faces", "points.obj", text.as_bytes());
        assert!(
            error.contains("points.obj: has no faces (f lines): is it a mesh?"),
            "{error}"
        );
    }

    #[test]
    fn a_file_that_is_not_utf8_is_placed_at_its_byte() {
        let error = error_of("not_utf8", "latin.obj", b"v 0 0 0\nv 1 \xe9 0\n");
        assert!(
            error.contains("latin.obj:2:5: byte 12 is not UTF-8"),
            "{error}"
        );
    }

    #[test]
    fn a_file_too_large_is_refused_unread() {
        let dir = scratch_dir("too_large");
        let file = File::create(dir.join("huge.obj")).unwrap();
        // Sparse: no disk is written.
        file.set_len(MAX_MESH_FILE_BYTES + 1).unwrap();
        let loaded = load(&dir, &unplaced("huge.obj"));
        std::fs::remove_dir_all(&dir).unwrap();
        let error = format!("{:#}", loaded.unwrap_err());
        assert!(error.contains("more than the 256 MiB"), "{error}");
    }

    #[test]
    fn a_placed_point_beyond_f32_is_refused() {
        let spec = MeshFile {
            scale: 10.0,
            ..unplaced("far.obj")
        };
        let text = "v 0 0 0\nv 3e38 0 0\nv 0 1 0\nf 1 2 3\n";
        let error = format!(
            "{:#}",
            load_placed("beyond", &spec, text.as_bytes()).unwrap_err()
        );
        assert!(
            error.contains("x = inf") && error.contains("smaller scale"),
            "{error}"
        );
    }

    #[test]
    fn a_placement_that_is_not_finite_is_refused() {
        let spec = MeshFile {
            scale: 0.0,
            ..unplaced("zero.obj")
        };
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let error = format!(
            "{:#}",
            load_placed("zero_scale", &spec, text.as_bytes()).unwrap_err()
        );
        assert!(error.contains("scale = 0"), "{error}");
    }

    #[test]
    fn a_missing_file_is_refused_naming_it() {
        let dir = scratch_dir("missing");
        let error = format!("{:#}", load(&dir, &unplaced("absent.stl")).unwrap_err());
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(error.contains("absent.stl: cannot open it"), "{error}");
    }

    #[test]
    fn mesh_file_reads_from_toml_with_defaults_and_refuses_unknown_keys() {
        let spec: MeshFile = toml::from_str(r#"file = "teapot.obj""#).unwrap();
        assert_eq!(spec, unplaced("teapot.obj"));
        let full: MeshFile = toml::from_str(
            "file = \"a.stl\"\nscale = 2.0\nrotate_degrees = [-90.0, 0.0, 0.0]\n\
             translate = [1.0, 2.0, 3.0]",
        )
        .unwrap();
        let expected = MeshFile {
            scale: 2.0,
            rotate_degrees: [-90.0, 0.0, 0.0],
            translate: [1.0, 2.0, 3.0],
            ..unplaced("a.stl")
        };
        assert_eq!(full, expected);
        assert!(toml::from_str::<MeshFile>("file = \"a.obj\"\nscael = 2.0").is_err());
    }

    /// A tetrahedron's corners.
    const TETRAHEDRON: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];

    /// Its faces, anticlockwise from outside.
    const TETRAHEDRON_FACES: [[usize; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

    /// A tetrahedron as a binary STL.
    fn binary_tetrahedron() -> Vec<u8> {
        let mut bytes = b"solid but binary".to_vec();
        bytes.resize(80, 0);
        bytes.extend(4_u32.to_le_bytes());
        for face in TETRAHEDRON_FACES {
            bytes.extend([0_u8; 12]);
            for corner in face {
                for coordinate in TETRAHEDRON[corner] {
                    bytes.extend(coordinate.to_le_bytes());
                }
            }
            bytes.extend([0_u8; 2]);
        }
        bytes
    }

    /// A tetrahedron as an ASCII STL.
    fn ascii_tetrahedron() -> String {
        use std::fmt::Write as _;
        let mut text = "solid tetrahedron\n".to_owned();
        for face in TETRAHEDRON_FACES {
            text += "  facet normal 0 0 0\n    outer loop\n";
            for corner in face {
                let [x, y, z] = TETRAHEDRON[corner];
                writeln!(text, "      vertex {x:e} {y} {z}").unwrap();
            }
            text += "    endloop\n  endfacet\n";
        }
        text + "endsolid tetrahedron\n"
    }

    /// Checks that `mesh` is the tetrahedron, its shared corners merged.
    fn assert_tetrahedron(mesh: &LoadedMesh) {
        assert_eq!(mesh.vertices.len(), 4);
        assert_eq!(mesh.triangles.len(), 4);
        assert!(mesh.normals.is_empty());
        for (triangle, face) in mesh.triangles.iter().zip(TETRAHEDRON_FACES) {
            assert_eq!(
                triangle.map(|index| mesh.vertices[index as usize]),
                face.map(|corner| TETRAHEDRON[corner])
            );
        }
    }

    #[test]
    fn a_binary_stl_tetrahedron_has_4_merged_vertices() {
        let mesh = load_bytes("binary_stl", "tetra.stl", &binary_tetrahedron()).unwrap();
        assert_tetrahedron(&mesh);
    }

    #[test]
    fn an_ascii_stl_tetrahedron_has_4_merged_vertices() {
        let text = ascii_tetrahedron();
        let mesh = load_bytes("ascii_stl", "tetra.STL", text.as_bytes()).unwrap();
        assert_tetrahedron(&mesh);
    }

    #[test]
    fn a_truncated_binary_stl_is_refused() {
        let mut bytes = binary_tetrahedron();
        bytes.truncate(84 + 50 * 3 + 20);
        let error = error_of("truncated_stl", "cut.stl", &bytes);
        assert!(error.contains("cut.stl: byte 254:"), "{error}");
        assert!(
            error.contains("holds 3 of the 4 triangles its header counts"),
            "{error}"
        );
        let error = error_of("short_stl", "short.stl", &[0; 40]);
        assert!(error.contains("short.stl: byte 40:"), "{error}");
    }

    #[test]
    fn a_binary_stl_with_a_coordinate_not_finite_is_refused_at_its_byte() {
        let mut bytes = binary_tetrahedron();
        let offset = 84 + 50 + 12 + 4 * 4;
        bytes[offset..offset + 4].copy_from_slice(&f32::NAN.to_le_bytes());
        let error = error_of("nan_stl", "nan.stl", &bytes);
        assert!(
            error.contains("nan.stl: byte 162: triangle 2's corner 2"),
            "{error}"
        );
    }

    #[test]
    fn a_wrong_ascii_stl_is_placed_at_its_line_and_column() {
        let cases = [
            ("vertex 0e0 0 0", "vertex 0e0 0", ":4:7:", "3 numbers"),
            ("vertex 0e0 0 0", "vertex 0e0 0 0 0", ":4:22:", "`0` after"),
            (
                "vertex 0e0 0 0",
                "vertex 0e0 0 x",
                ":4:20:",
                "`x` is not a number",
            ),
            (
                "    endloop",
                "      vertex 1 1 1\n    endloop",
                ":7:7:",
                "expected `endloop`",
            ),
            ("endsolid tetrahedron\n", "", ":29:11:", "ends where"),
        ];
        for (from, to, place, what) in cases {
            let text = ascii_tetrahedron().replacen(from, to, 1);
            let error = error_of("wrong_ascii", "wrong.stl", text.as_bytes());
            assert!(
                error.contains(&format!("wrong.stl{place}")) && error.contains(what),
                "{to}: {error}"
            );
        }
        let error = error_of("empty_ascii", "empty.stl", b"solid empty\nendsolid empty\n");
        assert!(error.contains("has no triangles"), "{error}");
    }

    /// A tiny xorshift: reproducible pseudo-random numbers without a dependency.
    struct XorShift(u64);

    impl XorShift {
        /// The next number.
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }

        /// A number below `bound`.
        fn below(&mut self, bound: usize) -> usize {
            let bound = u64::try_from(bound).unwrap();
            usize::try_from(self.next() % bound).unwrap()
        }

        /// A byte.
        fn byte(&mut self) -> u8 {
            self.next().to_le_bytes()[0]
        }
    }

    /// `valid` with a few bytes changed, inserted or removed, often bytes that mean
    /// something in a mesh file.
    fn mutated(random: &mut XorShift, valid: &[u8]) -> Vec<u8> {
        const MEANINGFUL: &[u8] = b"0123456789-+./ \n\tfvnteElgo#e\xff\x00";
        let mut bytes = valid.to_vec();
        for _ in 0..=random.below(4) {
            let byte = if random.below(2) == 0 {
                MEANINGFUL[random.below(MEANINGFUL.len())]
            } else {
                random.byte()
            };
            let at = random.below(bytes.len() + 1);
            match random.below(3) {
                0 if at < bytes.len() => bytes[at] = byte,
                1 if at < bytes.len() => {
                    bytes.remove(at);
                }
                _ => bytes.insert(at, byte),
            }
        }
        bytes
    }

    #[test]
    fn random_and_mutated_files_never_panic() {
        let obj = format!("mtllib a.mtl\n{CUBE_VERTICES}vt 0 0\nvn 0 0 1\no a\n{CUBE_QUADS}")
            .replace("f 1 4 3 2", "f 1/1/1 4/1/1 3//1 -1/1")
            .into_bytes();
        let ascii_stl = ascii_tetrahedron().into_bytes();
        let binary_stl = binary_tetrahedron();
        let dir = scratch_dir("fuzz");
        let mut random = XorShift(0x9e37_79b9_7f4a_7c15);
        let (mut loaded, mut refused) = (0, 0);
        for round in 0..3000 {
            let (extension, bytes) = match round % 4 {
                0 => {
                    let length = random.below(120);
                    let bytes = (0..length).map(|_| random.byte()).collect();
                    (["obj", "stl"][random.below(2)], bytes)
                }
                1 => ("obj", mutated(&mut random, &obj)),
                2 => ("stl", mutated(&mut random, &ascii_stl)),
                _ => ("stl", mutated(&mut random, &binary_stl)),
            };
            // A new file each round: ext4 flushes a file rewritten in place when it is closed.
            let file = format!("{round}.{extension}");
            std::fs::write(dir.join(&file), &bytes).unwrap();
            let spec = MeshFile {
                scale: [1.0, -1e30, 1e-30][random.below(3)],
                rotate_degrees: [0.0, 45.0, 270.0],
                ..unplaced(&file)
            };
            match load(&dir, &spec) {
                Ok(_) => loaded += 1,
                Err(_) => refused += 1,
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
        // Both outcomes are reached: the mutations are neither all harmless nor all fatal.
        assert!(
            loaded > 100 && refused > 100,
            "{loaded} loaded, {refused} refused"
        );
    }
}
