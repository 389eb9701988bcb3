//! [`MeshVecs`]: a scene's meshes in its format, in `Vec`s, where a scene built at run time on
//! a machine with a heap keeps them (the harness's scenes, and the proof of a firmware's, which
//! writes them to words). Behind the feature `alloc`.

crate::phase::declare_phase!(Some(crate::phase::Phase::Tests));

use super::{MeshStorage, Meshes, Node};
use crate::shape::Triangle;
use crate::vec3::Vec3;
use alloc::vec::Vec;

/// A scene's meshes in `Vec`s: nodes, triangles and, for a smooth mesh, its corners' normals.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshVecs<S> {
    nodes: Vec<Node<S>>,
    triangles: Vec<Triangle<S>>,
    normals: Vec<[Vec3<S>; 3]>,
}

impl<S> Default for MeshVecs<S> {
    fn default() -> Self {
        Self {
            nodes: Vec::new(),
            triangles: Vec::new(),
            normals: Vec::new(),
        }
    }
}

impl<S: Copy> Meshes<S> for MeshVecs<S> {
    fn node(&self, index: u32) -> Option<Node<S>> {
        self.nodes.get(index as usize).copied()
    }
    fn triangle(&self, index: u32) -> Option<Triangle<S>> {
        self.triangles.get(index as usize).copied()
    }
    fn normals(&self, index: u32) -> Option<[Vec3<S>; 3]> {
        self.normals.get(index as usize).copied()
    }
}

impl<S: Copy> MeshStorage<S> for MeshVecs<S> {
    fn capacity(&self) -> usize {
        usize::MAX
    }
    fn push_node(&mut self, node: Node<S>) -> bool {
        self.nodes.push(node);
        true
    }
    fn push_triangle(&mut self, triangle: Triangle<S>) -> bool {
        self.triangles.push(triangle);
        true
    }
    fn push_normals(&mut self, normals: [Vec3<S>; 3]) -> bool {
        self.normals.push(normals);
        true
    }
}
