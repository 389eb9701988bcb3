//! [`OwnedMeshes`]: a scene's meshes, owned: triangles added mesh by mesh, each with its
//! bounding-volume hierarchy built ([`obscura::mesh::build_hierarchy`]), lent to the core as a
//! [`MeshesDesc`]; and [`MeshVecs`], where a scene built at run time keeps them in its format.

use obscura::mesh::{HierarchyError, MeshStorage, Meshes, Node, build_hierarchy};
use obscura::shape::Triangle;
use obscura::{MeshesDesc, NodeDesc, desc::triangle_has_area};

/// The triangles and hierarchies of a scene's meshes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OwnedMeshes {
    /// See [`MeshesDesc::vertices`].
    pub vertices: Vec<[f32; 3]>,
    /// See [`MeshesDesc::triangles`].
    pub triangles: Vec<[u32; 3]>,
    /// See [`MeshesDesc::nodes`].
    pub nodes: Vec<NodeDesc>,
}

/// A mesh [`OwnedMeshes::add`] added.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Added {
    /// Its hierarchy's root: what its object names ([`obscura::ShapeDesc::Mesh`]).
    pub root: u32,
    /// The triangles it has.
    pub triangles: usize,
    /// The triangles left out because they have no area ([`triangle_has_area`]).
    pub without_area: usize,
}

impl OwnedMeshes {
    /// A copy of `desc`.
    #[must_use]
    pub fn from_desc(desc: &MeshesDesc<'_>) -> Self {
        Self {
            vertices: desc.vertices.to_vec(),
            triangles: desc.triangles.to_vec(),
            nodes: desc.nodes.to_vec(),
        }
    }

    /// The meshes, borrowed.
    #[must_use]
    pub fn desc(&self) -> MeshesDesc<'_> {
        MeshesDesc {
            vertices: &self.vertices,
            triangles: &self.triangles,
            nodes: &self.nodes,
        }
    }

    /// Adds the mesh of `triangles` over `vertices` (their corners' indices), leaving out the
    /// triangles without area, and builds its hierarchy.
    ///
    /// # Errors
    /// When no triangle with area is left, or a triangle names a corner `vertices` lacks.
    pub fn add(
        &mut self,
        vertices: &[[f32; 3]],
        triangles: &[[u32; 3]],
    ) -> Result<Added, HierarchyError> {
        let corner = |i: u32| vertices.get(i as usize).copied();
        let mut kept = Vec::with_capacity(triangles.len());
        for (index, triangle) in triangles.iter().enumerate() {
            let [Some(a), Some(b), Some(c)] = triangle.map(corner) else {
                return Err(HierarchyError::NoSuchVertex { triangle: index });
            };
            if triangle_has_area([a, b, c]) {
                kept.push(*triangle);
            }
        }
        let mut nodes = vec![NodeDesc::default(); (2 * kept.len()).saturating_sub(1)];
        let made = build_hierarchy(vertices, &mut kept, &mut nodes)?;
        nodes.truncate(made);
        let base = |n: usize| u32::try_from(n).map_err(|_| HierarchyError::Count);
        let (vertex_base, triangle_base, node_base) = (
            base(self.vertices.len())?,
            base(self.triangles.len())?,
            base(self.nodes.len())?,
        );
        let added = Added {
            root: node_base,
            triangles: kept.len(),
            without_area: triangles.len() - kept.len(),
        };
        self.vertices.extend_from_slice(vertices);
        self.triangles
            .extend(kept.iter().map(|t| t.map(|i| i + vertex_base)));
        self.nodes.extend(nodes.into_iter().map(|node| NodeDesc {
            first: node.first + triangle_base,
            end: node.end + triangle_base,
            right: if node.right == 0 {
                0
            } else {
                node.right + node_base
            },
            ..node
        }));
        Ok(added)
    }

    /// Moves every vertex through `position` and fits each node's box to its triangles again
    /// (the hierarchy's shape stays; its boxes hold what they hold).
    pub fn moved(&self, position: impl Fn([f32; 3]) -> [f32; 3]) -> Self {
        let vertices: Vec<[f32; 3]> = self.vertices.iter().map(|&p| position(p)).collect();
        let nodes = self
            .nodes
            .iter()
            .map(|node| {
                let (mut min, mut max) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
                let range = node.first as usize..node.end as usize;
                for triangle in self.triangles.get(range).unwrap_or_default() {
                    for &i in triangle {
                        let p = vertices.get(i as usize).copied().unwrap_or_default();
                        for k in 0..3 {
                            min[k] = min[k].min(p[k]);
                            max[k] = max[k].max(p[k]);
                        }
                    }
                }
                NodeDesc { min, max, ..*node }
            })
            .collect();
        Self {
            vertices,
            triangles: self.triangles.clone(),
            nodes,
        }
    }
}

/// A scene's meshes in its format, in `Vec`s: where a scene built at run time keeps them (the
/// harness's scenes, and the proof of a firmware's, which writes them to words).
#[derive(Clone, Debug, PartialEq)]
pub struct MeshVecs<S> {
    nodes: Vec<Node<S>>,
    triangles: Vec<Triangle<S>>,
}

impl<S> Default for MeshVecs<S> {
    fn default() -> Self {
        Self {
            nodes: Vec::new(),
            triangles: Vec::new(),
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
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square of two triangles, and a triangle with no area.
    const SQUARE: [[f32; 3]; 4] = [[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];

    #[test]
    fn meshes_are_added_after_each_other_without_their_flat_triangles() {
        let mut meshes = OwnedMeshes::default();
        let first = meshes
            .add(&SQUARE, &[[0, 1, 2], [0, 2, 3], [0, 1, 1]])
            .unwrap();
        assert_eq!((first.root, first.triangles, first.without_area), (0, 2, 1));
        let second = meshes
            .add(&SQUARE, &[[0, 1, 2], [0, 2, 3], [1, 2, 3]])
            .unwrap();
        // The first mesh's two triangles make one leaf: the second's root is the next node.
        assert_eq!(second.root, 1);
        // The second mesh's corners follow the first's, its triangles and nodes too.
        assert_eq!(meshes.triangles[2], [4, 5, 6]);
        let root = meshes.nodes[second.root as usize];
        assert_eq!((root.first, root.end), (2, 5));
        assert!(root.right == 0 || root.right > second.root);
        assert!(matches!(
            meshes.add(&SQUARE, &[[0, 1, 9]]),
            Err(HierarchyError::NoSuchVertex { triangle: 0 })
        ));
        assert!(
            meshes.add(&SQUARE, &[[0, 0, 1]]).is_err(),
            "nothing with area"
        );
    }

    #[test]
    fn moving_the_vertices_fits_the_boxes_to_them() {
        let mut meshes = OwnedMeshes::default();
        meshes.add(&SQUARE, &[[0, 1, 2], [0, 2, 3]]).unwrap();
        let moved = meshes.moved(|[x, y, z]| [2.0 * x + 1.0, y, z]);
        assert_eq!(
            (moved.nodes[0].min, moved.nodes[0].max),
            ([1.0, 0.0, 0.0], [3.0, 1.0, 0.0])
        );
    }
}
