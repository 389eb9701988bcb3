//! Building a mesh's bounding-volume hierarchy: binned surface-area heuristic (Wald 2007) over
//! the triangles' centroids, in place, without recursion or heap: what the host runs once per
//! mesh and a firmware keeps in flash.

crate::phase::declare_phase!(Some(crate::phase::Phase::Build));

use crate::desc::NodeDesc;
use heapless::Vec;

/// The deepest a hierarchy goes below its root: [`build_hierarchy`] makes a leaf of a node this
/// deep, and the scene build refuses a deeper one, so that a ray's traversal holds at most this
/// many nodes waiting ([`super::Node`]).
pub const MAX_DEPTH: usize = 32;

/// Bins of the surface-area heuristic along a node's widest axis of centroids.
const BINS: usize = 12;

/// A leaf holds at most this many triangles where it can be split at all.
pub const MAX_LEAF: usize = 4;

/// Why no hierarchy was built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HierarchyError {
    /// `nodes` holds fewer than the 2n − 1 nodes n triangles may need.
    TooFewNodes {
        /// What it must hold.
        needed: usize,
    },
    /// A triangle names a corner `vertices` does not have.
    NoSuchVertex {
        /// The triangle, in the order given.
        triangle: usize,
    },
    /// There are no triangles, or more than 2³¹.
    Count,
}

/// An axis-aligned box.
#[derive(Clone, Copy, Debug)]
struct Aabb {
    min: [f32; 3],
    max: [f32; 3],
}

impl Aabb {
    const EMPTY: Self = Self {
        min: [f32::INFINITY; 3],
        max: [f32::NEG_INFINITY; 3],
    };

    fn grow(&mut self, p: [f32; 3]) {
        for ((low, high), x) in self.min.iter_mut().zip(&mut self.max).zip(p) {
            *low = low.min(x);
            *high = high.max(x);
        }
    }

    fn join(&mut self, other: &Self) {
        self.grow(other.min);
        self.grow(other.max);
    }

    /// Half the surface area (what the heuristic compares); 0 for an empty box.
    fn half_area(&self) -> f64 {
        let mut sides = [0.0; 3];
        for ((side, low), high) in sides.iter_mut().zip(self.min).zip(self.max) {
            *side = (f64::from(high) - f64::from(low)).max(0.0);
        }
        let [x, y, z] = sides;
        x * y + y * z + z * x
    }
}

/// A range of triangles waiting to become a node: the node whose right child it is, if it
/// is one, the range, and its depth.
#[derive(Clone, Copy, Debug)]
struct Pending {
    parent: Option<usize>,
    first: usize,
    end: usize,
    depth: usize,
}

/// Builds the hierarchy of the triangles `triangles` (corner indices into `vertices`),
/// reordering them into its leaves, into `nodes` (at least 2n − 1 for n triangles), its root
/// first and each node's left subtree right after it ([`NodeDesc`]). Returns how many nodes it
/// made. A node of at most [`MAX_LEAF`] triangles the heuristic finds no cheaper to split, of
/// two, or [`MAX_DEPTH`] deep is a leaf.
///
/// # Errors
/// Too few nodes, a corner index out of range, or no triangles.
///
/// ```
/// use obscura::NodeDesc;
/// use obscura::mesh::build_hierarchy;
///
/// // A unit square of two triangles: they fit one leaf, the root.
/// let vertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// let mut triangles = [[0, 1, 2], [0, 2, 3]];
/// let mut nodes = [NodeDesc::default(); 3];
/// let made = build_hierarchy(&vertices, &mut triangles, &mut nodes)?;
/// assert_eq!(made, 1);
/// assert_eq!((nodes[0].min, nodes[0].max), ([0.0; 3], [1.0, 1.0, 0.0]));
/// # Ok::<(), obscura::mesh::HierarchyError>(())
/// ```
pub fn build_hierarchy(
    vertices: &[[f32; 3]],
    triangles: &mut [[u32; 3]],
    nodes: &mut [NodeDesc],
) -> Result<usize, HierarchyError> {
    let n = triangles.len();
    if n == 0 || u32::try_from(n).is_err() {
        return Err(HierarchyError::Count);
    }
    if nodes.len() < 2 * n - 1 {
        return Err(HierarchyError::TooFewNodes { needed: 2 * n - 1 });
    }
    if let Some(triangle) = triangles
        .iter()
        .position(|t| t.iter().any(|&i| vertices.get(i as usize).is_none()))
    {
        return Err(HierarchyError::NoSuchVertex { triangle });
    }
    let corner = |i: u32| vertices.get(i as usize).copied().unwrap_or([0.0; 3]);
    let bounds = |t: &[u32; 3]| {
        let mut b = Aabb::EMPTY;
        t.iter().for_each(|&i| b.grow(corner(i)));
        b
    };
    let centroid = |t: &[u32; 3]| -> [f64; 3] {
        let mut sum = [0.0; 3];
        for &i in t {
            for (s, x) in sum.iter_mut().zip(corner(i)) {
                *s += f64::from(x) / 3.0;
            }
        }
        sum
    };

    // Each split takes one range off and puts two on: at most one more than the depth waits.
    let mut pending: Vec<Pending, { MAX_DEPTH + 2 }> = Vec::new();
    let root = Pending {
        parent: None,
        first: 0,
        end: n,
        depth: 0,
    };
    let _ = pending.push(root);
    let mut made = 0;
    while let Some(Pending {
        parent,
        first,
        end,
        depth,
    }) = pending.pop()
    {
        let index = made;
        made += 1;
        if let Some(parent) = parent.and_then(|p| nodes.get_mut(p)) {
            parent.right = index as u32;
        }
        let range = triangles.get_mut(first..end).unwrap_or_default();
        let mut node_bounds = Aabb::EMPTY;
        range.iter().for_each(|t| node_bounds.join(&bounds(t)));
        let split = if depth >= MAX_DEPTH || range.len() <= 2 {
            None
        } else {
            split(range, &bounds, &centroid, &node_bounds)
        };
        let mut axis = 0;
        if let Some((split_axis, left)) = split {
            axis = split_axis;
            let child = |first, end| Pending {
                parent: None,
                first,
                end,
                depth: depth + 1,
            };
            // Right first: the left one is taken next, and so numbered next.
            let right = Pending {
                parent: Some(index),
                ..child(first + left, end)
            };
            let _ = pending.push(right);
            let _ = pending.push(child(first, first + left));
        }
        if let Some(node) = nodes.get_mut(index) {
            *node = NodeDesc {
                min: node_bounds.min,
                max: node_bounds.max,
                first: first as u32,
                end: end as u32,
                right: 0,
                axis: axis as u8,
            };
        }
    }
    Ok(made)
}

/// Where to split `range` (more than 2 triangles, bounded by `node_bounds`): the axis and the
/// number of triangles that go left, after moving them to the front; `None` for a leaf.
fn split(
    range: &mut [[u32; 3]],
    bounds: &impl Fn(&[u32; 3]) -> Aabb,
    centroid: &impl Fn(&[u32; 3]) -> [f64; 3],
    node_bounds: &Aabb,
) -> Option<(usize, usize)> {
    let n = range.len();
    let mut low = [f64::INFINITY; 3];
    let mut high = [f64::NEG_INFINITY; 3];
    for t in range.iter() {
        for ((low, high), c) in low.iter_mut().zip(&mut high).zip(centroid(t)) {
            *low = low.min(c);
            *high = high.max(c);
        }
    }
    let (axis, (start, extent)) = low
        .iter()
        .zip(high)
        .map(|(&low, high)| (low, high - low))
        .enumerate()
        .max_by(|(_, (_, a)), (_, (_, b))| a.total_cmp(b))?;
    if extent <= 0.0 || !extent.is_finite() {
        // Every centroid at one place: halve the range as it is, if it is too long for a leaf.
        return (n > MAX_LEAF).then_some((axis, n / 2));
    }
    let bin = |t: &[u32; 3]| {
        let at = centroid(t).get(axis).map_or(0.0, |c| (c - start) / extent);
        ((at * BINS as f64) as usize).min(BINS - 1)
    };
    let mut bins = [(0_usize, Aabb::EMPTY); BINS];
    for t in range.iter() {
        if let Some((count, area)) = bins.get_mut(bin(t)) {
            *count += 1;
            area.join(&bounds(t));
        }
    }
    // What lies after each bin: its triangles and their box's area.
    let mut after = [(0_usize, 0.0_f64); BINS];
    let mut behind = (0, Aabb::EMPTY);
    for ((count, area), (bin_count, bin_box)) in after.iter_mut().zip(&bins).rev() {
        *count = behind.0;
        *area = behind.1.half_area();
        behind.0 += bin_count;
        behind.1.join(bin_box);
    }
    // The cost of splitting after each bin: the triangles of each side times their box's area.
    let mut before = (0, Aabb::EMPTY);
    let mut best = None::<(f64, usize)>;
    for (i, ((bin_count, bin_box), &(right_count, right_area))) in
        bins.iter().zip(&after).enumerate()
    {
        before.0 += bin_count;
        before.1.join(bin_box);
        if before.0 == 0 || right_count == 0 {
            continue;
        }
        let cost = before.1.half_area() * before.0 as f64 + right_area * right_count as f64;
        if best.is_none_or(|(b, _)| cost < b) {
            best = Some((cost, i));
        }
    }
    // A leaf costs one test per triangle; a split one box test more, and each side's
    // triangles as often as a ray meets its box.
    let leaf = n as f64;
    let whole = node_bounds.half_area();
    let (cost, last) = best?;
    let split_cost = 1.0 + if whole > 0.0 { cost / whole } else { leaf };
    if n <= MAX_LEAF && split_cost >= leaf {
        return None;
    }
    // The triangles of the bins up to `last` to the front.
    let mut front = 0;
    for i in 0..n {
        if range.get(i).is_some_and(|t| bin(t) <= last) {
            range.swap(front, i);
            front += 1;
        }
    }
    Some((axis, front))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    /// A grid of `side` × `side` squares in the plane z = 0, two triangles each.
    fn grid(side: u32) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let vertices = (0..=side)
            .flat_map(|y| (0..=side).map(move |x| [x as f32, y as f32, 0.0]))
            .collect();
        let at = |x: u32, y: u32| y * (side + 1) + x;
        let triangles = (0..side)
            .flat_map(|y| {
                (0..side).flat_map(move |x| {
                    [
                        [at(x, y), at(x + 1, y), at(x + 1, y + 1)],
                        [at(x, y), at(x + 1, y + 1), at(x, y + 1)],
                    ]
                })
            })
            .collect();
        (vertices, triangles)
    }

    /// Every node's box holds its triangles and its children, its children split its range,
    /// and every triangle is under the root once.
    fn check(vertices: &[[f32; 3]], triangles: &[[u32; 3]], nodes: &[NodeDesc]) -> usize {
        let mut depth_of = vec![0; nodes.len()];
        let mut deepest = 0;
        for (i, node) in nodes.iter().enumerate() {
            for t in &triangles[node.first as usize..node.end as usize] {
                for &v in t {
                    let p = vertices[v as usize];
                    assert!((0..3).all(|k| node.min[k] <= p[k] && p[k] <= node.max[k]));
                }
            }
            if node.right != 0 {
                let (left, right) = (&nodes[i + 1], &nodes[node.right as usize]);
                assert_eq!(
                    (left.first, left.end, right.end),
                    (node.first, right.first, node.end)
                );
                depth_of[i + 1] = depth_of[i] + 1;
                depth_of[node.right as usize] = depth_of[i] + 1;
            } else {
                assert!(node.end - node.first <= MAX_LEAF as u32 || depth_of[i] == MAX_DEPTH);
            }
            deepest = deepest.max(depth_of[i]);
        }
        assert_eq!(
            (nodes[0].first as usize, nodes[0].end as usize),
            (0, triangles.len())
        );
        deepest
    }

    #[test]
    fn a_grid_splits_into_small_leaves_within_the_depth() {
        let (vertices, mut triangles) = grid(40);
        let mut sorted = triangles.clone();
        let mut nodes = vec![NodeDesc::default(); 2 * triangles.len() - 1];
        let made = build_hierarchy(&vertices, &mut triangles, &mut nodes).unwrap();
        // No leaf is forced by the depth: every one holds at most MAX_LEAF triangles.
        let depth = check(&vertices, &triangles, &nodes[..made]);
        assert!(depth < MAX_DEPTH, "{depth}");
        // The same triangles, reordered.
        let mut reordered = triangles.clone();
        sorted.sort_unstable();
        reordered.sort_unstable();
        assert_eq!(sorted, reordered);
    }

    #[test]
    fn triangles_at_one_place_are_halved_and_a_long_chain_stops_at_the_depth() {
        let vertices = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let mut same = vec![[0, 1, 2]; 100];
        let mut nodes = vec![NodeDesc::default(); 199];
        let made = build_hierarchy(&vertices, &mut same, &mut nodes).unwrap();
        check(&vertices, &same, &nodes[..made]);
        // Triangles at 2⁰, 2¹, …: each split takes one off the end.
        let vertices: Vec<[f32; 3]> = (0..60)
            .flat_map(|i| {
                let x = 2.0_f32.powi(i);
                [[x, 0.0, 0.0], [x, 1.0, 0.0], [x, 0.0, 1.0]]
            })
            .collect();
        let mut chain: Vec<[u32; 3]> = (0..60).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
        let mut nodes = vec![NodeDesc::default(); 119];
        let made = build_hierarchy(&vertices, &mut chain, &mut nodes).unwrap();
        assert!(check(&vertices, &chain, &nodes[..made]) <= MAX_DEPTH);
    }

    #[test]
    fn bad_input_is_refused() {
        let (vertices, mut triangles) = grid(2);
        let mut few = vec![NodeDesc::default(); 3];
        assert_eq!(
            build_hierarchy(&vertices, &mut triangles, &mut few),
            Err(HierarchyError::TooFewNodes { needed: 15 })
        );
        let mut nodes = vec![NodeDesc::default(); 15];
        triangles[3][1] = 99;
        assert_eq!(
            build_hierarchy(&vertices, &mut triangles, &mut nodes),
            Err(HierarchyError::NoSuchVertex { triangle: 3 })
        );
        assert_eq!(
            build_hierarchy(&vertices, &mut [], &mut nodes),
            Err(HierarchyError::Count)
        );
    }
}
