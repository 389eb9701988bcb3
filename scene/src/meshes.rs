//! [`OwnedMeshes`]: a scene's meshes, owned: triangles added mesh by mesh, each with its
//! bounding-volume hierarchy built ([`obscura::mesh::build_hierarchy`]), lent to the core as a
//! [`MeshesDesc`].

use obscura::mesh::{HierarchyError, build_hierarchy};
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
    /// See [`MeshesDesc::normals`].
    pub normals: Vec<[f32; 3]>,
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
            normals: desc.normals.to_vec(),
        }
    }

    /// The meshes, borrowed.
    #[must_use]
    pub fn desc(&self) -> MeshesDesc<'_> {
        MeshesDesc {
            vertices: &self.vertices,
            triangles: &self.triangles,
            nodes: &self.nodes,
            normals: &self.normals,
        }
    }

    /// Adds the mesh of `triangles` over `vertices` (their corners' indices), leaving out the
    /// triangles without area, and builds its hierarchy. `normals` are the vertices' unit
    /// normals in their order, for a smooth mesh: a vertex with a zero normal or beyond them
    /// has none, and a triangle with such a corner is shaded flat (none at all: a flat mesh).
    ///
    /// # Errors
    /// When no triangle with area is left, or a triangle names a corner `vertices` lacks.
    pub fn add(
        &mut self,
        vertices: &[[f32; 3]],
        normals: &[[f32; 3]],
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
        // Normals are one per vertex of every mesh, or none: a flat mesh's are zero where
        // another's are given.
        if !normals.is_empty() || !self.normals.is_empty() {
            self.normals.resize(self.vertices.len(), [0.0; 3]);
            self.normals
                .extend(normals.iter().take(vertices.len()).copied());
            self.normals
                .resize(self.vertices.len() + vertices.len(), [0.0; 3]);
        }
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

    /// Moves every vertex through `position` and its normal through `direction`, and fits each
    /// node's box to its triangles again (the hierarchy's shape stays; its boxes hold what
    /// they hold).
    pub fn moved(
        &self,
        position: impl Fn([f32; 3]) -> [f32; 3],
        direction: impl Fn([f32; 3]) -> [f32; 3],
    ) -> Self {
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
            normals: self
                .normals
                .iter()
                .map(|&n| if n == [0.0; 3] { n } else { direction(n) })
                .collect(),
        }
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
            .add(&SQUARE, &[], &[[0, 1, 2], [0, 2, 3], [0, 1, 1]])
            .unwrap();
        assert_eq!((first.root, first.triangles, first.without_area), (0, 2, 1));
        let second = meshes
            .add(&SQUARE, &[], &[[0, 1, 2], [0, 2, 3], [1, 2, 3]])
            .unwrap();
        // The first mesh's two triangles make one leaf: the second's root is the next node.
        assert_eq!(second.root, 1);
        // The second mesh's corners follow the first's, its triangles and nodes too.
        assert_eq!(meshes.triangles[2], [4, 5, 6]);
        let root = meshes.nodes[second.root as usize];
        assert_eq!((root.first, root.end), (2, 5));
        assert!(root.right == 0 || root.right > second.root);
        assert!(matches!(
            meshes.add(&SQUARE, &[], &[[0, 1, 9]]),
            Err(HierarchyError::NoSuchVertex { triangle: 0 })
        ));
        assert!(
            meshes.add(&SQUARE, &[], &[[0, 0, 1]]).is_err(),
            "nothing with area"
        );
    }

    #[test]
    fn moving_the_vertices_fits_the_boxes_to_them() {
        let mut meshes = OwnedMeshes::default();
        meshes.add(&SQUARE, &[], &[[0, 1, 2], [0, 2, 3]]).unwrap();
        let moved = meshes.moved(|[x, y, z]| [2.0 * x + 1.0, y, z], |d| d);
        assert_eq!(
            (moved.nodes[0].min, moved.nodes[0].max),
            ([1.0, 0.0, 0.0], [3.0, 1.0, 0.0])
        );
    }

    #[test]
    fn normals_are_one_per_vertex_of_every_mesh_once_one_has_them() {
        let up = [0.0, 0.0, 1.0];
        let mut meshes = OwnedMeshes::default();
        meshes.add(&SQUARE, &[], &[[0, 1, 2]]).unwrap();
        assert!(meshes.normals.is_empty(), "a flat mesh has none");
        // Three normals for four vertices: the fourth has none.
        meshes.add(&SQUARE, &[up; 3], &[[0, 1, 2]]).unwrap();
        meshes.add(&SQUARE, &[], &[[0, 1, 2]]).unwrap();
        let zero = [0.0; 3];
        let expected = [[zero; 4], [up, up, up, zero], [zero; 4]].concat();
        assert_eq!(meshes.normals, expected);
        assert_eq!(meshes.desc().corner_normals([4, 5, 6]), Some([up; 3]));
        assert_eq!(meshes.desc().corner_normals([4, 5, 7]), None);
        // Mirrored, the normals turn with the surface; a vertex without one keeps none.
        let mirrored = meshes.moved(|p| p, |[x, y, z]| [x, y, -z]);
        assert_eq!(mirrored.normals[4], [0.0, 0.0, -1.0]);
        assert_eq!(mirrored.normals[0], zero);
    }
}
