//! A top-down binned SAH build (Wald, "On fast construction of SAH-based bounding
//! volume hierarchies", 2007) whose time and depth stay bounded whatever the boxes are:
//! a range whose centroids cannot be told apart (coincident or concentric boxes) is
//! split in half by index, so the tree is at most ~log₂ n deep there and the build is
//! O(n log n).
//!
//! obvhs' PLOC merges each cluster with its nearest neighbour; over coincident or nested
//! boxes every merge leaves the best partner unchanged, and it builds a chain as deep as
//! there are boxes in quadratic time (10,000 coincident spheres: depth 9,993 in 2 s).
//! Both levels are built here: a scene's entries and a mesh's triangles.

use glam::Vec3A;
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::{Bvh2, leaf_collapser::collapse, node::Bvh2Node, reinsertion::ReinsertionOptimizer};
use obvhs::cwbvh::{CwBvh, bvh2_to_cwbvh::bvh2_to_cwbvh};
use obvhs::splits::split_aabbs_preset;
use obvhs::triangle::Triangle;

/// The builder's name in the caches' parameter hash: trees of an earlier builder are
/// built again.
pub const BUILDER: &str = "binned-sah-1";

/// Bins per axis where a range is too large for a full sweep.
const BINS: usize = 32;

/// The deepest a tree may be: the GPU's top-level traversal keeps 32 nodes on its stack.
pub const MAX_DEPTH: usize = 30;

/// Ranges of at most this many boxes are split at the best of every cut along each axis
/// (a full sweep); larger ones at the best of [`BINS`] bins per axis.
const SWEEP_LIMIT: usize = 32;

/// See [`binned_cut`].
const ONE_AXIS_LIMIT: usize = 16384;

/// A BVH2 over `boxes`, one box per leaf, root at node 0 (obvhs' layout: an inner node's
/// children are `first_index` and `first_index + 1`; a leaf's `first_index` is its
/// position in `primitive_indices`). At most [`MAX_DEPTH`] deep for up to 2³⁰ boxes: a
/// range that the SAH would split too unevenly to fit is split at its median.
pub fn build(boxes: &[Aabb]) -> Bvh2 {
    if boxes.is_empty() {
        return Bvh2::default();
    }
    // Moved as the ranges are partitioned, so that each pass reads memory in order.
    let mut items: Vec<Item> =
        boxes.iter().enumerate().map(|(i, b)| Item { bounds: *b, centre: b.center(), index: i as u32 }).collect();
    let mut nodes = Vec::with_capacity(2 * boxes.len() - 1);
    nodes.push(Bvh2Node::default());
    let mut tasks = vec![(0usize, 0usize, boxes.len(), 1usize)];
    while let Some((node, start, end, depth)) = tasks.pop() {
        let range = &mut items[start..end];
        let (mut bounds, mut lo, mut hi) = (Aabb::INVALID, Vec3A::MAX, Vec3A::MIN);
        for item in range.iter() {
            bounds = bounds.union(&item.bounds);
            (lo, hi) = (lo.min(item.centre), hi.max(item.centre));
        }
        if range.len() == 1 {
            nodes[node] = Bvh2Node::new(bounds, 1, start as u32);
            continue;
        }
        // Levels a balanced tree over this range still needs.
        let needed = usize::BITS as usize - (range.len() - 1).leading_zeros() as usize;
        let middle = start + split(range, lo, hi - lo, depth + needed >= MAX_DEPTH);
        let first_child = nodes.len();
        nodes.push(Bvh2Node::default());
        nodes.push(Bvh2Node::default());
        nodes[node] = Bvh2Node::new(bounds, 0, first_child as u32);
        tasks.push((first_child, start, middle, depth + 1));
        tasks.push((first_child + 1, middle, end, depth + 1));
    }
    let primitive_indices = items.iter().map(|item| item.index).collect();
    Bvh2 { nodes, primitive_indices, ..Default::default() }
}

/// A box as the build moves it: its bounds, centroid and index in the input.
#[derive(Clone, Copy)]
struct Item {
    bounds: Aabb,
    centre: Vec3A,
    index: u32,
}

/// How many levels `bvh` has (a lone leaf is 1).
pub fn depth(bvh: &Bvh2) -> usize {
    let mut deepest = 0;
    let mut stack = vec![(0usize, 1usize)];
    while let Some((node, d)) = stack.pop() {
        let Some(n) = bvh.nodes.get(node) else { continue };
        deepest = deepest.max(d);
        if !n.is_leaf() {
            stack.extend([(n.first_index as usize, d + 1), (n.first_index as usize + 1, d + 1)]);
        }
    }
    deepest
}

/// The top level's tree: [`build`], then obvhs' reinsertion and leaf collapse with
/// `params`, as its own `build_bvh2` does after PLOC. Reinsertion may deepen the tree:
/// where it goes past [`MAX_DEPTH`], the tree without it is kept.
pub fn build_optimised(boxes: &[Aabb], params: &BvhBuildParams) -> Bvh2 {
    let built = build(boxes);
    let mut bvh = built.clone();
    let mut reinsertion = ReinsertionOptimizer::default();
    reinsertion.run(&mut bvh, params.reinsertion_batch_ratio, None);
    collapse(&mut bvh, params.max_prims_per_leaf.clamp(1, 255), params.collapse_traversal_cost);
    let ratio = params.reinsertion_batch_ratio * params.post_collapse_reinsertion_batch_ratio_multiplier;
    reinsertion.run(&mut bvh, ratio, None);
    if depth(&bvh) <= MAX_DEPTH {
        return bvh;
    }
    let mut bvh = built;
    collapse(&mut bvh, params.max_prims_per_leaf.clamp(1, 255), params.collapse_traversal_cost);
    bvh
}

/// A mesh's wide BVH: [`build`] over its triangles' boxes (split first where `params`
/// asks for spatial splits, as obvhs splits them), obvhs' reinsertion where it keeps the
/// depth bounded, then turned into a CWBVH as obvhs turns its own. Over the meshes rt
/// ships this gives a lower SAH cost than obvhs' PLOC (the 46k dragon 15.99 against
/// 17.28), and it stays shallow and fast on repeated and nested triangles, where PLOC
/// builds a chain in quadratic time.
pub fn mesh_cwbvh(tris: &[Triangle], params: BvhBuildParams) -> CwBvh {
    let mut boxes: Vec<Aabb> = tris.iter().map(Triangle::aabb).collect();
    let mut indices: Vec<u32> = (0..tris.len() as u32).collect();
    if params.pre_split && !boxes.is_empty() {
        let areas: Vec<f32> = boxes.iter().map(Aabb::half_area).collect();
        let largest = areas.iter().copied().fold(0.0, f32::max);
        let mean = areas.iter().sum::<f32>() / areas.len() as f32;
        split_aabbs_preset(&mut boxes, &mut indices, tris, mean, largest);
    }
    let mut built = build(&boxes);
    for p in &mut built.primitive_indices {
        *p = indices[*p as usize];
    }
    built.uses_spatial_splits = params.pre_split;
    let mut bvh = built.clone();
    ReinsertionOptimizer::default().run(&mut bvh, params.reinsertion_batch_ratio, None);
    let bvh = if depth(&bvh) <= MAX_DEPTH { bvh } else { built };
    bvh2_to_cwbvh(&bvh, params.max_prims_per_leaf.clamp(1, 3), true, false)
}

/// Reorders `range` and returns how many of its boxes go to the first child (1..len),
/// given the bounds of their centroids. With `balanced`, or where the centroids cannot be
/// told apart, the cut is the median.
fn split(range: &mut [Item], lo: Vec3A, extent: Vec3A, balanced: bool) -> usize {
    let e = extent;
    let widest = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let half = range.len() / 2;
    // Centroids that cannot be told apart (or are not finite): halves by index.
    if !(e[widest] > 0.0 && e[widest].is_finite()) {
        return half;
    }
    let by_axis = |axis: usize| move |a: &Item, b: &Item| a.centre[axis].total_cmp(&b.centre[axis]);
    if balanced {
        range.select_nth_unstable_by(half, by_axis(widest));
        return half;
    }
    let cut = if range.len() <= SWEEP_LIMIT { sweep_cut(range) } else { binned_cut(range, lo, extent) };
    match cut {
        Some((axis, Cut::Sorted(count))) => {
            range.sort_unstable_by(by_axis(axis));
            count
        }
        Some((axis, Cut::Below(position))) => {
            let mut left = 0;
            for k in 0..range.len() {
                if range[k].centre[axis] < position {
                    range.swap(k, left);
                    left += 1;
                }
            }
            if left == 0 || left == range.len() {
                range.select_nth_unstable_by(half, by_axis(widest));
                half
            } else {
                left
            }
        }
        None => {
            range.select_nth_unstable_by(half, by_axis(widest));
            half
        }
    }
}

/// Where a range is cut on an axis: after its first `count` boxes in centroid order, or
/// between the centroids below `position` and the others.
enum Cut {
    Sorted(usize),
    Below(f32),
}

/// The cheapest cut by the SAH, `half_area(left) × n_left + half_area(right) × n_right`,
/// over every position along every axis; ties go to the more even cut.
fn sweep_cut(range: &[Item]) -> Option<(usize, Cut)> {
    let n = range.len();
    let evenness = |count: usize| count.min(n - count);
    let mut order = range.to_vec();
    let mut right = vec![0.0f32; n];
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in 0..3 {
        order.sort_unstable_by(|a, b| a.centre[axis].total_cmp(&b.centre[axis]));
        let mut b = Aabb::INVALID;
        for k in (1..n).rev() {
            b = b.union(&order[k].bounds);
            right[k] = b.half_area();
        }
        let mut b = Aabb::INVALID;
        for k in 1..n {
            b = b.union(&order[k - 1].bounds);
            let cost = b.half_area() * k as f32 + right[k] * (n - k) as f32;
            let better = best.is_none_or(|(c, _, count)| cost < c || (cost == c && evenness(k) > evenness(count)));
            if cost.is_finite() && better {
                best = Some((cost, axis, k));
            }
        }
    }
    best.map(|(_, axis, count)| (axis, Cut::Sorted(count)))
}

/// The cheapest cut by the SAH between [`BINS`] bins of centroids on each axis.
/// Ranges of more than [`ONE_AXIS_LIMIT`] boxes are binned on their widest axis only:
/// the first cuts of a large tree, where binning each axis costs most and gains least.
fn binned_cut(range: &[Item], lo: Vec3A, extent: Vec3A) -> Option<(usize, Cut)> {
    let e = extent;
    let widest = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let one_axis = range.len() > ONE_AXIS_LIMIT;
    let usable = |a: usize| (!one_axis || a == widest) && extent[a] > 0.0 && extent[a].is_finite();
    let scale = Vec3A::from_array(std::array::from_fn(|a| if usable(a) { BINS as f32 / extent[a] } else { 0.0 }));
    let mut counts = [[0usize; BINS]; 3];
    let mut bin_bounds = [[Aabb::INVALID; BINS]; 3];
    for item in range {
        let bins = ((item.centre - lo) * scale).to_array();
        for axis in (0..3).filter(|&a| usable(a)) {
            let bin = (bins[axis] as usize).min(BINS - 1);
            counts[axis][bin] += 1;
            bin_bounds[axis][bin] = bin_bounds[axis][bin].union(&item.bounds);
        }
    }
    let mut best: Option<(f32, usize, f32)> = None;
    for axis in (0..3).filter(|&a| usable(a)) {
        if let Some((cost, cut)) = cheapest_cut(&counts[axis], &bin_bounds[axis])
            && best.is_none_or(|(c, _, _)| cost < c)
        {
            best = Some((cost, axis, lo[axis] + cut as f32 / scale[axis]));
        }
    }
    best.map(|(_, axis, position)| (axis, Cut::Below(position)))
}

/// The bin boundary (1..BINS) with the least SAH cost that leaves boxes on both sides.
fn cheapest_cut(counts: &[usize; BINS], bounds: &[Aabb; BINS]) -> Option<(f32, usize)> {
    let mut right_area = [0.0f32; BINS];
    let mut right_count = [0usize; BINS];
    let (mut b, mut n) = (Aabb::INVALID, 0);
    for k in (1..BINS).rev() {
        b = b.union(&bounds[k]);
        n += counts[k];
        right_area[k] = b.half_area();
        right_count[k] = n;
    }
    let (mut b, mut n) = (Aabb::INVALID, 0);
    let mut best: Option<(f32, usize)> = None;
    for k in 1..BINS {
        b = b.union(&bounds[k - 1]);
        n += counts[k - 1];
        if n == 0 || right_count[k] == 0 {
            continue;
        }
        let cost = b.half_area() * n as f32 + right_area[k] * right_count[k] as f32;
        if cost.is_finite() && best.is_none_or(|(c, _)| cost < c) {
            best = Some((cost, k));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit(at: Vec3A, radius: f32) -> Aabb {
        Aabb::new(at - Vec3A::splat(radius), at + Vec3A::splat(radius))
    }

    fn check(boxes: &[Aabb], max_depth: usize) {
        let bvh = build(boxes);
        let mut seen: Vec<u32> = bvh.primitive_indices.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..boxes.len() as u32).collect::<Vec<_>>(), "every box once");
        assert!(depth(&bvh) <= max_depth, "depth {} over {max_depth}", depth(&bvh));
        for n in bvh.nodes.iter().filter(|n| n.is_leaf()) {
            let b = boxes[bvh.primitive_indices[n.first_index as usize] as usize];
            assert!(n.aabb().contains_point(b.min) && n.aabb().contains_point(b.max));
        }
    }

    #[test]
    fn coincident_and_nested_boxes_give_a_tree_of_logarithmic_depth() {
        let n = 40_000;
        let coincident = vec![unit(Vec3A::ONE, 1.0); n];
        let nested: Vec<Aabb> = (0..n).map(|i| unit(Vec3A::ZERO, 1.0 + i as f32 * 1e-3)).collect();
        check(&coincident, 17);
        check(&nested, 17);
    }

    #[test]
    fn separate_boxes_are_split_where_they_lie() {
        let grid: Vec<Aabb> = (0..1000)
            .map(|i| unit(Vec3A::new((i % 10) as f32, (i / 100) as f32, ((i / 10) % 10) as f32), 0.2))
            .collect();
        check(&grid, 14);
        let two = [unit(Vec3A::ZERO, 0.1), unit(Vec3A::X * 5.0, 0.1)];
        check(&two, 2);
        check(&two[..1], 1);
    }
}
