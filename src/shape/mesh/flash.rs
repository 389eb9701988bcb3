//! [`MeshWords`]: a scene's meshes as words ([`crate::words`]) left where they are — in a
//! firmware's flash — each node and triangle read when the tracer asks for it, so that a mesh
//! takes no RAM however many triangles it has. [`crate::Scene::write_mesh_words`] writes them
//! from a scene built and proven on the host.

crate::phase::declare_phase!(Some(crate::phase::Phase::Tests));

use super::{Meshes, Node};
use crate::scalar::Bits;
use crate::shape::Triangle;
use crate::vec3::Vec3;
use crate::words::{self, Reader, Words, WordsError};
use core::marker::PhantomData;

/// What the words hold: `"meshes"`, in the tag that names them and their format.
pub(crate) const WHAT: &str = "meshes";

/// A scene's meshes as words: after a tag, the number of nodes, of triangles and of triangles'
/// corner normals (all or none); the nodes, the triangles, the normals, each in the words its
/// format gives it, no more and no less; then a checksum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshWords<S> {
    nodes: &'static [u32],
    triangles: &'static [u32],
    normals: &'static [u32],
    format: PhantomData<S>,
}

/// No meshes.
impl<S> Default for MeshWords<S> {
    fn default() -> Self {
        Self {
            nodes: &[],
            triangles: &[],
            normals: &[],
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
        let (&[nodes, triangles, normals], items) = body.split_first_chunk::<3>().ok_or(refused)?;
        let part = |count: u32, words: usize| {
            usize::try_from(count)
                .ok()
                .and_then(|count| count.checked_mul(words))
                .ok_or(refused)
        };
        let node_part = part(nodes, Node::<S>::WORDS)?;
        let triangle_part = part(triangles, Triangle::<S>::WORDS)?;
        let normal_part = part(normals, <[Vec3<S>; 3]>::WORDS)?;
        let total = node_part
            .checked_add(triangle_part)
            .and_then(|n| n.checked_add(normal_part));
        if !(normals == 0 || normals == triangles) || total != Some(items.len()) {
            return Err(refused);
        }
        let (nodes, rest) = items.split_at(node_part);
        let (triangles, normals) = rest.split_at(triangle_part);
        Ok(Self {
            nodes,
            triangles,
            normals,
            format: PhantomData,
        })
    }
}

/// What a mesh keeps in words, item by item: each item the same number of words, known as
/// the firmware is compiled, so that reading one checks its bounds once, not word by word.
trait Item: Words {
    /// The words an item takes.
    const WORDS: usize;
}

impl<S: Bits> Item for Node<S> {
    /// The box's centre and half extent, 3 numbers each; `first`, `end`, `right`, `axis`.
    const WORDS: usize = 6 * S::WORDS + 4;
}

impl<S: Bits> Item for Triangle<S> {
    /// 7 vectors (3 corners, 2 edges, their cross product, the normal) and 2 numbers.
    const WORDS: usize = 23 * S::WORDS;
}

impl<S: Bits> Item for [Vec3<S>; 3] {
    const WORDS: usize = 9 * S::WORDS;
}

/// Item `index` of `words`.
#[inline(always)]
fn item<T: Item>(words: &[u32], index: u32) -> Option<T> {
    let start = (index as usize).checked_mul(T::WORDS)?;
    let mut input = Reader::<true>::over(words.get(start..start.checked_add(T::WORDS)?)?);
    Some(T::take(&mut input))
}

impl<S: Bits> Meshes<S> for MeshWords<S> {
    fn node(&self, index: u32) -> Option<Node<S>> {
        item(self.nodes, index)
    }
    fn triangle(&self, index: u32) -> Option<Triangle<S>> {
        item(self.triangles, index)
    }
    fn normals(&self, index: u32) -> Option<[Vec3<S>; 3]> {
        item(self.normals, index)
    }
}

/// Writes the nodes and triangles of `meshes` in format `S` to `sink`, as [`MeshWords`] reads
/// them.
pub(crate) fn write<S: Bits>(meshes: &impl Meshes<S>, sink: &mut dyn FnMut(u32)) {
    let nodes = || (0..).map_while(|i| meshes.node(i));
    let triangles = || (0..).map_while(|i| meshes.triangle(i));
    let normals = || (0..).map_while(|i| meshes.normals(i));
    let count = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    words::write_with::<S>(WHAT, sink, |out| {
        out.word(count(nodes().count()));
        out.word(count(triangles().count()));
        out.word(count(normals().count()));
        nodes().for_each(|node| node.put(out));
        triangles().for_each(|triangle| triangle.put(out));
        normals().for_each(|corners| corners.put(out));
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::I16F16;
    use crate::mesh::{MeshStorage, MeshVecs};
    use crate::words::Writer;

    /// Meshes of two triangles under one leaf, the second shaded smooth, in format `S`.
    fn meshes<S: Bits>() -> MeshVecs<S> {
        let v = |x: f64, y: f64, z: f64| Vec3::<f64>::new(x, y, z).convert().expect("held");
        let up = v(0.0, 0.0, 1.0);
        let triangle = |corners| Triangle::new(corners, up, S::ZERO);
        let mut meshes = MeshVecs::default();
        assert!(meshes.push_node(Node {
            centre: v(0.5, 0.5, 0.0),
            half: v(0.5, 0.5, 0.0),
            first: 0,
            end: 2,
            right: 0,
            axis: 2,
        }));
        assert!(meshes.push_triangle(triangle([v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), up])));
        assert!(meshes.push_triangle(triangle([v(0.0, 1.0, 0.0), v(1.0, 1.0, 0.0), up])));
        assert!(meshes.push_normals([Vec3::ZERO; 3]));
        assert!(meshes.push_normals([up, v(0.6, 0.0, 0.8), v(0.0, 0.6, 0.8)]));
        meshes
    }

    fn read_back<S: Bits>() {
        let written = meshes::<S>();
        let mut words = Vec::new();
        write(&written, &mut |word| words.push(word));
        let read = MeshWords::<S>::from_words(words.leak()).expect("its own words");
        for i in 0..3 {
            assert_eq!(read.node(i), written.node(i), "node {i}");
            assert_eq!(read.triangle(i), written.triangle(i), "triangle {i}");
            assert_eq!(read.normals(i), written.normals(i), "normals {i}");
        }
        assert!(read.normals(1).is_some() && read.node(1).is_none());
    }

    #[test]
    fn meshes_read_from_their_words_are_the_meshes_written() {
        read_back::<f32>();
        read_back::<I16F16>();
    }

    /// The words `value` takes.
    fn words_of(value: &impl Words) -> usize {
        let mut count = 0;
        value.put(&mut Writer::counting(&mut |_| count += 1));
        count
    }

    fn item_words<S: Bits>() {
        let meshes = meshes::<S>();
        let (node, triangle, normals) = (
            meshes.node(0).unwrap(),
            meshes.triangle(0).unwrap(),
            meshes.normals(0).unwrap(),
        );
        assert_eq!(words_of(&node), Node::<S>::WORDS, "{}", S::NAME);
        assert_eq!(words_of(&triangle), Triangle::<S>::WORDS, "{}", S::NAME);
        assert_eq!(words_of(&normals), <[Vec3<S>; 3]>::WORDS, "{}", S::NAME);
    }

    #[test]
    fn an_item_takes_the_words_its_format_gives_it() {
        item_words::<f32>();
        item_words::<I16F16>();
        item_words::<crate::I32F32>();
        item_words::<f64>();
    }

    #[test]
    fn words_of_another_format_or_cut_short_are_refused() {
        let mut words = Vec::new();
        write(&meshes::<f32>(), &mut |word| words.push(word));
        let words: &'static [u32] = words.leak();
        assert!(MeshWords::<I16F16>::from_words(words).is_err());
        let cut = words.len() - 2;
        assert!(MeshWords::<f32>::from_words(&words[..cut]).is_err());
    }
}
