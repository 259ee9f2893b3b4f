//! The top level's node layout: obvhs's `Bvh2` (one box per node) converted into
//! nodes that hold both children's boxes, as the seed renderer's 64-byte node did.
//! Leaves live in their parent's child slot, so traversal never fetches a leaf node.
//! (Meshes use the wide layout of `wide_node`.)

use crate::layout::{EMPTY_LINK, GpuBvhNode};
use obvhs::{aabb::Aabb, bvh2::Bvh2};

struct Child {
    min: [f32; 3],
    max: [f32; 3],
    link: u32,
    count: u32,
}

impl Child {
    /// A slot no ray can enter: an inverted box.
    const EMPTY: Child = Child { min: [f32::MAX; 3], max: [f32::MIN; 3], link: EMPTY_LINK, count: 0 };

    fn new(aabb: &Aabb, link: u32, count: u32) -> Self {
        Self { min: aabb.min.to_array(), max: aabb.max.to_array(), link, count }
    }
}

fn node(a: Child, b: Child) -> GpuBvhNode {
    GpuBvhNode {
        a_min: a.min,
        a_link: a.link,
        a_max: a.max,
        a_count: a.count,
        b_min: b.min,
        b_link: b.link,
        b_max: b.max,
        b_count: b.count,
    }
}

/// Converts `bvh`; leaf links index the primitives in `bvh.primitive_indices` order.
/// The root is node 0. A BVH with no primitives becomes one node with two empty slots.
pub fn convert_bvh2(bvh: &Bvh2) -> Vec<GpuBvhNode> {
    let Some(root) = bvh.nodes.first() else {
        return vec![node(Child::EMPTY, Child::EMPTY)];
    };
    if bvh.primitive_indices.is_empty() {
        return vec![node(Child::EMPTY, Child::EMPTY)];
    }
    if root.is_leaf() {
        return vec![node(Child::new(&root.aabb, root.first_index, root.prim_count), Child::EMPTY)];
    }
    let mut out = vec![GpuBvhNode::default()];
    // (obvhs inner node, its slot in `out`)
    let mut work = vec![(0usize, 0usize)];
    while let Some((src, dst)) = work.pop() {
        let first = bvh.nodes[src].first_index as usize;
        let [a, b] = [first, first + 1].map(|c| {
            let n = &bvh.nodes[c];
            if n.is_leaf() {
                Child::new(&n.aabb, n.first_index, n.prim_count)
            } else {
                let slot = out.len();
                out.push(GpuBvhNode::default());
                work.push((c, slot));
                Child::new(&n.aabb, slot as u32, 0)
            }
        });
        out[dst] = node(a, b);
    }
    out
}

/// Shape of a converted BVH, for `rt info`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BvhStats {
    pub nodes: usize,
    pub leaves: usize,
    /// Nodes on the longest root-to-leaf path, leaves included.
    pub depth: usize,
    /// Surface area heuristic cost with unit traversal and intersection costs,
    /// relative to the root's area.
    pub sah_cost: f64,
}

fn half_area(min: [f32; 3], max: [f32; 3]) -> f64 {
    let d = [0, 1, 2].map(|i| (max[i] as f64 - min[i] as f64).max(0.0));
    d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}

pub fn stats(nodes: &[GpuBvhNode]) -> BvhStats {
    let mut s = BvhStats { nodes: nodes.len(), ..Default::default() };
    let Some(root) = nodes.first() else { return s };
    let root_min = [0, 1, 2].map(|i| root.a_min[i].min(root.b_min[i]));
    let root_max = [0, 1, 2].map(|i| root.a_max[i].max(root.b_max[i]));
    let root_area = half_area(root_min, root_max);
    if root_area <= 0.0 {
        return s;
    }
    // The root's traversal step, then each child slot's: inner slots cost a step, leaves their primitives.
    let mut cost = root_area;
    let mut work = vec![(0usize, 1usize)];
    while let Some((i, depth)) = work.pop() {
        let n = &nodes[i];
        for (min, max, link, count) in
            [(n.a_min, n.a_max, n.a_link, n.a_count), (n.b_min, n.b_max, n.b_link, n.b_count)]
        {
            if link == EMPTY_LINK {
                continue;
            }
            let area = half_area(min, max);
            if count > 0 {
                s.leaves += 1;
                s.depth = s.depth.max(depth + 1);
                cost += area * count as f64;
            } else {
                cost += area;
                work.push((link as usize, depth + 1));
            }
        }
    }
    s.sah_cost = cost / root_area;
    s
}
