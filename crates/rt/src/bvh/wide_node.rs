//! The bottom levels' node layout: obvhs's compressed 8-wide BVH (`CwBvh`, Ylitie,
//! Karras & Laine 2017) with its child boxes quantised again, conservatively.
//!
//! obvhs quantises a child's box as `floor((min − origin) / step)` in f32, whose
//! rounding can put the dequantised plane a little inside the exact box. Here every
//! node's box is recomputed bottom-up from its triangles, and each plane `origin + q ·
//! step` is checked in f64 (where it is exact) to lie outside the child's exact box, so
//! that a ray can only miss a dequantised box when it misses the geometry inside it.
//! The shader's slab test adds its own rounding bound on top (`shaders/wide_bvh.wgsl`).

use super::node::BvhStats;
use crate::layout::{GpuTriangle, GpuWideNode};
use obvhs::cwbvh::CwBvh;

/// The layout's name, recorded in caches so that a new layout invalidates old files.
pub const NODE_LAYOUT: &str = "cwbvh8-conservative-80";

/// Children per node.
pub const WIDTH: usize = 8;
/// Triangles one node's leaves may reference (bits 0..24 of the shader's hit mask).
pub const MAX_NODE_TRIANGLES: u32 = 24;

/// What one child slot of a node holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    Empty,
    /// Index of the child node (relative to the mesh's first node).
    Inner(u32),
    /// (first triangle, triangle count), relative to the mesh's first triangle.
    Leaf(u32, u32),
}

pub fn imask(node: &GpuWideNode) -> u8 {
    node.exponents_imask[3]
}

/// Decodes slot `i` the way the shader does: inner children are numbered in slot order
/// from `child_base`, leaves count their triangles in unary in the meta byte's top bits.
pub fn slot(node: &GpuWideNode, i: usize) -> Slot {
    let meta = node.child_meta[i];
    if meta == 0 {
        return Slot::Empty;
    }
    let imask = imask(node) as u32;
    if imask & (1 << i) != 0 {
        return Slot::Inner(node.child_base.wrapping_add((imask & ((1 << i) - 1)).count_ones()));
    }
    Slot::Leaf(node.primitive_base.wrapping_add((meta & 0b1_1111) as u32), (meta >> 5).count_ones())
}

/// Whether slot `i`'s meta byte is one the shader decodes as `slot` does: an inner child's
/// meta is 0b001_11000 + i and its `imask` bit is set; a leaf's count is unary (1, 3 or 7 in
/// the top bits) and its triangles fit in the node's 24 hit-mask bits.
pub fn slot_is_well_formed(node: &GpuWideNode, i: usize) -> bool {
    let meta = node.child_meta[i];
    let inner = imask(node) & (1 << i) != 0;
    if meta == 0 {
        return !inner;
    }
    if inner {
        return meta == 0b0011_1000 + i as u8;
    }
    let count = meta >> 5;
    matches!(count, 0b001 | 0b011 | 0b111) && (meta & 0b1_1111) as u32 + count.count_ones() <= MAX_NODE_TRIANGLES
}

#[derive(Clone, Copy)]
struct Bounds {
    min: [f32; 3],
    max: [f32; 3],
}

impl Bounds {
    const EMPTY: Bounds = Bounds { min: [f32::MAX; 3], max: [f32::MIN; 3] };

    fn grow(&mut self, other: &Bounds) {
        for a in 0..3 {
            self.min[a] = self.min[a].min(other.min[a]);
            self.max[a] = self.max[a].max(other.max[a]);
        }
    }

    fn of_triangles(triangles: &[GpuTriangle]) -> Bounds {
        let mut b = Bounds::EMPTY;
        for v in triangles.iter().flat_map(|t| [t.v0, t.v1, t.v2]) {
            b.grow(&Bounds { min: v, max: v });
        }
        b
    }
}

/// Converts `bvh`, whose `primitive_indices` order `triangles` follows: leaf slots
/// index `triangles` directly. The root is node 0. A BVH with no nodes becomes one
/// node with eight empty slots.
pub fn convert_cwbvh(bvh: &CwBvh, triangles: &[GpuTriangle]) -> Vec<GpuWideNode> {
    if bvh.nodes.is_empty() || triangles.is_empty() {
        return vec![GpuWideNode { exponents_imask: [127, 127, 127, 0], ..Default::default() }];
    }
    let mut nodes: Vec<GpuWideNode> = bytemuck::cast_slice(&bvh.nodes).to_vec();
    requantise(&mut nodes, triangles);
    nodes
}

/// Children are stored after their parents, so one backward pass sees every child's
/// exact box before its parent's.
fn requantise(nodes: &mut [GpuWideNode], triangles: &[GpuTriangle]) {
    let mut boxes = vec![Bounds::EMPTY; nodes.len()];
    for i in (0..nodes.len()).rev() {
        let children: [Option<Bounds>; WIDTH] = std::array::from_fn(|s| match slot(&nodes[i], s) {
            Slot::Empty => None,
            Slot::Inner(c) => Some(boxes[c as usize]),
            Slot::Leaf(first, count) => Some(Bounds::of_triangles(&triangles[first as usize..][..count as usize])),
        });
        let mut node_box = Bounds::EMPTY;
        children.iter().flatten().for_each(|c| node_box.grow(c));
        boxes[i] = node_box;
        quantise(&mut nodes[i], &node_box, &children);
    }
}

/// Sets the node's grid (origin and power-of-two steps) and its children's 8-bit planes
/// so that each dequantised box contains the child's exact box.
fn quantise(node: &mut GpuWideNode, node_box: &Bounds, children: &[Option<Bounds>; WIDTH]) {
    node.origin = node_box.min;
    let mut planes = [[[0u8; WIDTH]; 2]; 3];
    for (axis, [axis_lo, axis_hi]) in planes.iter_mut().enumerate() {
        let origin = node_box.min[axis] as f64;
        let top = node_box.max[axis] as f64;
        // A step far below the coordinates' rounding would gain nothing; keeping it above
        // 2⁻³² of their magnitude keeps origin + q · step exact in f64.
        let finest = (origin.abs().max(top.abs()) * 2f64.powi(-32)).max(2f64.powi(-100));
        let mut k = ((top - origin) / 255.0).max(finest).log2().ceil() as i32;
        while origin + 255.0 * 2f64.powi(k) < top {
            k += 1;
        }
        let k = k.clamp(-126, 127);
        node.exponents_imask[axis] = (k + 127) as u8;
        let step = 2f64.powi(k);
        for (s, child) in children.iter().enumerate() {
            let Some(b) = child else { continue };
            let (lo, hi) = (b.min[axis] as f64, b.max[axis] as f64);
            let mut q_lo = ((lo - origin) / step).floor().clamp(0.0, 255.0);
            while q_lo > 0.0 && origin + q_lo * step > lo {
                q_lo -= 1.0;
            }
            let mut q_hi = ((hi - origin) / step).ceil().clamp(0.0, 255.0);
            while q_hi < 255.0 && origin + q_hi * step < hi {
                q_hi += 1.0;
            }
            axis_lo[s] = q_lo as u8;
            axis_hi[s] = q_hi as u8;
        }
    }
    [node.child_min_x, node.child_max_x] = planes[0];
    [node.child_min_y, node.child_max_y] = planes[1];
    [node.child_min_z, node.child_max_z] = planes[2];
}

/// The dequantised box of slot `s` (exact in f64).
fn child_box(node: &GpuWideNode, s: usize) -> ([f64; 3], [f64; 3]) {
    let q = [
        (node.child_min_x[s], node.child_max_x[s]),
        (node.child_min_y[s], node.child_max_y[s]),
        (node.child_min_z[s], node.child_max_z[s]),
    ];
    let mut lo = [0.0; 3];
    let mut hi = [0.0; 3];
    for a in 0..3 {
        let step = 2f64.powi(node.exponents_imask[a] as i32 - 127);
        lo[a] = node.origin[a] as f64 + q[a].0 as f64 * step;
        hi[a] = node.origin[a] as f64 + q[a].1 as f64 * step;
    }
    (lo, hi)
}

fn half_area((lo, hi): ([f64; 3], [f64; 3])) -> f64 {
    let d = [0, 1, 2].map(|i| (hi[i] - lo[i]).max(0.0));
    d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}

/// Shape of a converted wide BVH, for `rt info`: leaves are leaf slots; the SAH cost
/// counts one per node visited and one per triangle tested, weighted by the dequantised
/// boxes' areas relative to the root's.
pub fn wide_stats(nodes: &[GpuWideNode]) -> BvhStats {
    let mut s = BvhStats { nodes: nodes.len(), ..Default::default() };
    let Some(root) = nodes.first() else { return s };
    let mut root_lo = [f64::MAX; 3];
    let mut root_hi = [f64::MIN; 3];
    for c in (0..WIDTH).filter(|&c| slot(root, c) != Slot::Empty) {
        let (lo, hi) = child_box(root, c);
        for a in 0..3 {
            root_lo[a] = root_lo[a].min(lo[a]);
            root_hi[a] = root_hi[a].max(hi[a]);
        }
    }
    let root_area = half_area((root_lo, root_hi));
    if root_area <= 0.0 {
        return s;
    }
    let mut cost = root_area;
    let mut work = vec![(0usize, 1usize)];
    while let Some((i, depth)) = work.pop() {
        let n = &nodes[i];
        for c in 0..WIDTH {
            let area = half_area(child_box(n, c));
            match slot(n, c) {
                Slot::Empty => {}
                Slot::Inner(child) => {
                    cost += area;
                    work.push((child as usize, depth + 1));
                }
                Slot::Leaf(_, count) => {
                    s.leaves += 1;
                    s.depth = s.depth.max(depth + 1);
                    cost += area * count as f64;
                }
            }
        }
    }
    s.sah_cost = cost / root_area;
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use obvhs::{BvhBuildParams, cwbvh::builder::build_cwbvh_from_tris, triangle::Triangle};
    use std::time::Duration;

    /// Triangles far from the origin and of very different sizes, where f32 quantisation
    /// rounds planes inwards.
    fn awkward_triangles() -> Vec<GpuTriangle> {
        let mut state = 12345u64;
        let mut next = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        (0..3000)
            .map(|i| {
                let scale = [1e-4f32, 1.0, 300.0][i % 3];
                let c = [1000.0 + next() * 10.0, -7.0 + next(), 0.1 * next()];
                let v =
                    |c: [f32; 3], s: f32, k: &mut dyn FnMut() -> f32| [c[0] + s * k(), c[1] + s * k(), c[2] + s * k()];
                GpuTriangle {
                    v0: v(c, scale, &mut next),
                    v1: v(c, scale, &mut next),
                    v2: v(c, scale, &mut next),
                    ..Default::default()
                }
            })
            .collect()
    }

    fn build(triangles: &[GpuTriangle]) -> (Vec<GpuWideNode>, Vec<GpuTriangle>) {
        let tris: Vec<Triangle> =
            triangles.iter().map(|t| Triangle { v0: t.v0.into(), v1: t.v1.into(), v2: t.v2.into() }).collect();
        let bvh = build_cwbvh_from_tris(&tris, BvhBuildParams::medium_build(), &mut Duration::default());
        let ordered: Vec<GpuTriangle> = bvh.primitive_indices.iter().map(|&i| triangles[i as usize]).collect();
        (convert_cwbvh(&bvh, &ordered), ordered)
    }

    /// Vertex coordinates that lie outside a slot box on the way from the root to their
    /// leaf, after checking that every slot is well formed and every triangle in one leaf.
    fn uncontained(nodes: &[GpuWideNode], triangles: &[GpuTriangle]) -> usize {
        let mut outside = 0;
        let mut seen = vec![0u32; triangles.len()];
        // (node, the intersection of the boxes its ancestors' slots promise)
        let mut work = vec![(0u32, ([f64::MIN; 3], [f64::MAX; 3]))];
        while let Some((i, (lo, hi))) = work.pop() {
            let n = &nodes[i as usize];
            for c in 0..WIDTH {
                assert!(slot_is_well_formed(n, c), "node {i} slot {c}");
                let (clo, chi) = child_box(n, c);
                let inner_lo = [0, 1, 2].map(|a| lo[a].max(clo[a]));
                let inner_hi = [0, 1, 2].map(|a| hi[a].min(chi[a]));
                match slot(n, c) {
                    Slot::Empty => {}
                    Slot::Inner(child) => work.push((child, (inner_lo, inner_hi))),
                    Slot::Leaf(first, count) => {
                        for t in &triangles[first as usize..][..count as usize] {
                            for v in [t.v0, t.v1, t.v2] {
                                outside +=
                                    (0..3).filter(|&a| !(inner_lo[a]..=inner_hi[a]).contains(&(v[a] as f64))).count();
                            }
                        }
                        (first..first + count).for_each(|k| seen[k as usize] += 1);
                    }
                }
            }
        }
        assert!(seen.iter().all(|&k| k == 1), "every triangle is in exactly one leaf");
        outside
    }

    #[test]
    fn every_dequantised_box_contains_its_subtree() {
        let (nodes, triangles) = build(&awkward_triangles());
        assert_eq!(uncontained(&nodes, &triangles), 0);
        let stats = wide_stats(&nodes);
        assert!(stats.depth > 2 && stats.sah_cost > 1.0, "{stats:?}");
    }

    /// A child whose box starts just below a grid line of a node whose origin is tiny and
    /// negative: obvhs's f32 `floor((min − origin) / step)` rounds onto the grid line, and
    /// its plane cuts 2·10⁻⁸ into the child.
    #[test]
    fn a_plane_that_f32_rounding_moves_into_its_child_is_moved_out() {
        let p = -(2f32.powi(-25) + 2f32.powi(-27));
        let m = 1.0 - 2f32.powi(-24);
        let tri = |v0, v1, v2| GpuTriangle { v0, v1, v2, ..Default::default() };
        let triangles = [
            tri([p, 0.0, 0.0], [p + 0.01, 0.0, 0.01], [p, 0.01, 0.0]),
            tri([m, 5.0, 0.0], [1.5, 5.0, 0.0], [1.2, 5.5, 0.5]),
        ];
        let (nodes, ordered) = build(&triangles);
        assert_eq!(uncontained(&nodes, &ordered), 0);
        let tris: Vec<Triangle> =
            triangles.iter().map(|t| Triangle { v0: t.v0.into(), v1: t.v1.into(), v2: t.v2.into() }).collect();
        let raw = build_cwbvh_from_tris(&tris, BvhBuildParams::medium_build(), &mut Duration::default());
        assert!(
            uncontained(bytemuck::cast_slice(&raw.nodes), &ordered) > 0,
            "obvhs's own planes held: the case is gone"
        );
    }

    #[test]
    fn an_empty_mesh_is_one_node_of_empty_slots() {
        let nodes = convert_cwbvh(&CwBvh::default(), &[]);
        assert_eq!(nodes.len(), 1);
        assert!((0..WIDTH).all(|c| slot(&nodes[0], c) == Slot::Empty && slot_is_well_formed(&nodes[0], c)));
    }
}
