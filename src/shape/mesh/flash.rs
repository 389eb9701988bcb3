//! [`MeshWords`]: a scene's meshes as words ([`crate::words`]) left where they are — in a
//! firmware's flash — each node and triangle read when the tracer asks for it, so that a mesh
//! takes no RAM however many triangles it has. [`crate::Scene::write_mesh_words`] writes them
//! from a scene built and proven on the host.

use super::{Meshes, Node};
use crate::scalar::Bits;
use crate::shape::Triangle;
use crate::words::{self, Reader, Words, WordsError, Writer};
use core::marker::PhantomData;

/// What the words hold: `"meshes"`, in the tag that names them and their format.
pub(crate) const WHAT: &str = "meshes";

/// A scene's meshes as words: after a tag, the number of nodes and of triangles and the words
/// each takes, the nodes, then the triangles, then a checksum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshWords<S> {
    nodes: &'static [u32],
    triangles: &'static [u32],
    node_words: usize,
    triangle_words: usize,
    format: PhantomData<S>,
}

/// No meshes.
impl<S> Default for MeshWords<S> {
    fn default() -> Self {
        Self {
            nodes: &[],
            triangles: &[],
            node_words: 1,
            triangle_words: 1,
            format: PhantomData,
        }
    }
}

impl<S: Bits> MeshWords<S> {
    /// The meshes [`crate::Scene::write_mesh_words`] wrote in format `S`, read in place.
    ///
    /// # Errors
    /// When `words` are not meshes written in format `S` (their tag, their checksum or their
    /// length is not theirs).
    pub fn from_words(words: &'static [u32]) -> Result<Self, WordsError> {
        let refused = WordsError {
            what: WHAT,
            format: S::NAME,
        };
        let body = words::body::<S>(WHAT, words)?;
        let (&[nodes, triangles, node_words, triangle_words], items) =
            body.split_first_chunk::<4>().ok_or(refused)?;
        let size = |n: u32| usize::try_from(n).map_err(|_| refused);
        let (node_words, triangle_words) = (size(node_words)?, size(triangle_words)?);
        let node_part = size(nodes)?.checked_mul(node_words).ok_or(refused)?;
        let triangle_part = size(triangles)?
            .checked_mul(triangle_words)
            .ok_or(refused)?;
        if node_words == 0 || triangle_words == 0 || node_part + triangle_part != items.len() {
            return Err(refused);
        }
        let (nodes, triangles) = items.split_at(node_part);
        Ok(Self {
            nodes,
            triangles,
            node_words,
            triangle_words,
            format: PhantomData,
        })
    }
}

/// Item `index` of `words`, `stride` words each.
#[inline(always)]
fn item<T: Words>(words: &[u32], stride: usize, index: u32) -> Option<T> {
    let start = (index as usize).checked_mul(stride)?;
    let mut input = Reader::<true>::over(words.get(start..start.checked_add(stride)?)?);
    Some(T::take(&mut input))
}

impl<S: Bits> Meshes<S> for MeshWords<S> {
    fn node(&self, index: u32) -> Option<Node<S>> {
        item(self.nodes, self.node_words, index)
    }
    fn triangle(&self, index: u32) -> Option<Triangle<S>> {
        item(self.triangles, self.triangle_words, index)
    }
}

/// The words `value` takes.
fn words_of(value: &impl Words) -> u32 {
    let mut count = 0;
    value.put(&mut Writer::counting(&mut |_| count += 1));
    count
}

/// Writes the nodes and triangles of `meshes` in format `S` to `sink`, as [`MeshWords`] reads
/// them.
pub(crate) fn write<S: Bits>(meshes: &impl Meshes<S>, sink: &mut dyn FnMut(u32)) {
    let nodes = || (0..).map_while(|i| meshes.node(i));
    let triangles = || (0..).map_while(|i| meshes.triangle(i));
    let count = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    words::write_with::<S>(WHAT, sink, |out| {
        out.word(count(nodes().count()));
        out.word(count(triangles().count()));
        out.word(nodes().next().map_or(1, |node| words_of(&node)));
        out.word(triangles().next().map_or(1, |triangle| words_of(&triangle)));
        nodes().for_each(|node| node.put(out));
        triangles().for_each(|triangle| triangle.put(out));
    });
}
