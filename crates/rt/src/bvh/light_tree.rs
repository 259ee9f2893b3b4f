//! The light tree: a BVH over the scene's lamps and emissive triangles and spheres whose
//! nodes bound the lights' positions, emission directions and power (Conty Estevez &
//! Kulla 2018, as pbrt-v4's `BVHLightSampler`). The GPU walks it from the root to one
//! light, choosing each child with probability in proportion to its importance seen
//! from the shaded point (`shaders/light_tree.wgsl`); a BSDF ray that hits a light
//! evaluates the same probability by following the light's bit trail from the root.
//! Suns are not in the tree: light sampling gives them a fixed share.

use crate::layout::*;
use anyhow::{Result, bail};
use glam::Vec3;
use std::f32::consts::PI;

/// Depth of the deepest leaf: a trail holds one bit per level.
pub const MAX_DEPTH: u32 = 31;
/// Centroid buckets per axis when choosing a split.
const BUCKETS: usize = 12;

/// A cone of directions: `w` with half-angle acos(`cos_theta`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionCone {
    pub w: Vec3,
    pub cos_theta: f32,
}

impl DirectionCone {
    pub const ENTIRE_SPHERE: Self = Self { w: Vec3::Z, cos_theta: -1.0 };

    /// The smallest cone about both (pbrt-v4 `Union(DirectionCone, DirectionCone)`).
    pub fn union(a: Self, b: Self) -> Self {
        // The common cases of flat emitters and of points, without trigonometry.
        if a.w == b.w {
            return Self { w: a.w, cos_theta: a.cos_theta.min(b.cos_theta) };
        }
        if a.cos_theta <= -1.0 || b.cos_theta <= -1.0 {
            return Self::ENTIRE_SPHERE;
        }
        let (theta_a, theta_b) = (a.cos_theta.clamp(-1.0, 1.0).acos(), b.cos_theta.clamp(-1.0, 1.0).acos());
        let theta_d = a.w.angle_between(b.w);
        if (theta_d + theta_b).min(PI) <= theta_a {
            return a;
        }
        if (theta_d + theta_a).min(PI) <= theta_b {
            return b;
        }
        let theta_o = 0.5 * (theta_a + theta_d + theta_b);
        if theta_o >= PI {
            return Self::ENTIRE_SPHERE;
        }
        // Rotate a's axis towards b's by theta_o − theta_a.
        let theta_r = theta_o - theta_a;
        let k = a.w.cross(b.w);
        if k.length_squared() == 0.0 {
            return Self::ENTIRE_SPHERE;
        }
        let k = k.normalize();
        let w = a.w * theta_r.cos() + k.cross(a.w) * theta_r.sin();
        Self { w: w.normalize(), cos_theta: theta_o.cos() }
    }
}

/// What the tree knows of a light or a group of lights (pbrt-v4 `LightBounds`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    pub min: Vec3,
    pub max: Vec3,
    /// Luminous power (lamps: Blender's watts × luminance of the colour).
    pub phi: f32,
    /// Surface normals (or a spot's axis) lie within this cone…
    pub normals: DirectionCone,
    /// …and light leaves at most this far beyond it (cos of the angle).
    pub cos_theta_e: f32,
    pub two_sided: bool,
}

impl LightBounds {
    pub fn union(a: &Self, b: &Self) -> Self {
        // A light of no power has no say in where the group points.
        if a.phi == 0.0 {
            return Self { min: a.min.min(b.min), max: a.max.max(b.max), ..*b };
        }
        if b.phi == 0.0 {
            return Self { min: a.min.min(b.min), max: a.max.max(b.max), ..*a };
        }
        Self {
            min: a.min.min(b.min),
            max: a.max.max(b.max),
            phi: a.phi + b.phi,
            normals: DirectionCone::union(a.normals, b.normals),
            cos_theta_e: a.cos_theta_e.min(b.cos_theta_e),
            two_sided: a.two_sided || b.two_sided,
        }
    }

    fn centroid(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// pbrt-v4's `EvaluateCost`: power × the solid angle of emission × surface area,
    /// with boxes long along `axis` of `whole` favoured for splitting there.
    fn cost(&self, whole_extent: Vec3, axis: usize) -> f32 {
        let theta_o = self.normals.cos_theta.clamp(-1.0, 1.0).acos();
        let theta_e = self.cos_theta_e.clamp(-1.0, 1.0).acos();
        let theta_w = (theta_o + theta_e).min(PI);
        let sin_o = (1.0 - self.normals.cos_theta.powi(2)).max(0.0).sqrt();
        let m_omega = 2.0 * PI * (1.0 - self.normals.cos_theta)
            + PI / 2.0
                * (2.0 * theta_w * sin_o - (theta_o - 2.0 * theta_w).cos() - 2.0 * theta_o * sin_o
                    + self.normals.cos_theta);
        let kr = whole_extent.max_element() / whole_extent[axis];
        let d = self.max - self.min;
        let area = 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
        self.phi * m_omega * kr * area
    }

    fn gpu(&self, link: u32, leaf: bool) -> GpuLightTreeNode {
        let flags = if leaf { LIGHT_TREE_LEAF } else { 0 } | if self.two_sided { LIGHT_TREE_TWO_SIDED } else { 0 };
        GpuLightTreeNode {
            bounds_min: self.min.to_array(),
            power: self.phi,
            bounds_max: self.max.to_array(),
            cos_theta_o: self.normals.cos_theta,
            axis: self.normals.w.to_array(),
            cos_theta_e: self.cos_theta_e,
            link,
            flags,
            _pad: [0; 2],
        }
    }
}

/// One light to put in the tree: its bounds, the leaf `link` that names it
/// (see [`GpuLightTreeNode::link`]) and the index of its entry in the trails.
#[derive(Clone, Copy, Debug)]
pub struct TreeLight {
    pub bounds: LightBounds,
    pub link: u32,
    pub trail_index: u32,
}

/// The tree as the GPU reads it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LightTree {
    /// The root first, each inner node followed by its first child's subtree. Never
    /// empty: without lights, one leaf of no power that the GPU never picks.
    pub nodes: Vec<GpuLightTreeNode>,
    /// Per light (emitters, then lamps): the children taken from the root to its leaf,
    /// bit d for depth d (1: the second child); `LIGHT_TREE_ABSENT` if it is not in the tree.
    pub trails: Vec<u32>,
}

impl LightTree {
    /// The tree over `lights` (those of no power are left out); `trail_count` entries of
    /// trails, one per light that could be in it.
    pub fn build(lights: &[TreeLight], trail_count: usize) -> Result<Self> {
        let mut lit: Vec<TreeLight> = lights.iter().copied().filter(|l| l.bounds.phi > 0.0).collect();
        if lit.len() > 1usize << MAX_DEPTH {
            bail!("{} lights are more than the light tree holds ({})", lit.len(), 1usize << MAX_DEPTH);
        }
        let mut tree = Self { nodes: Vec::new(), trails: vec![LIGHT_TREE_ABSENT; trail_count] };
        if lit.is_empty() {
            tree.nodes.push(GpuLightTreeNode { flags: LIGHT_TREE_LEAF, ..Default::default() });
            return Ok(tree);
        }
        let mut fragment = Fragment { nodes: Vec::with_capacity(2 * lit.len() - 1), trails: Vec::new() };
        subtree(&mut lit, 0, 0, &mut fragment);
        tree.nodes = fragment.nodes;
        for (index, trail) in fragment.trails {
            tree.trails[index as usize] = trail;
        }
        Ok(tree)
    }
}

/// Subtrees of this many lights or more, this near the root, are built on threads of their own.
const PARALLEL_LIGHTS: usize = 8192;
const PARALLEL_DEPTH: u32 = 3;

/// Part of the tree: nodes whose links count from its first, and (trail index, trail) pairs.
#[derive(Default)]
struct Fragment {
    nodes: Vec<GpuLightTreeNode>,
    trails: Vec<(u32, u32)>,
}

/// Appends the subtree over `lights` at `depth`, reached by `trail`; returns its bounds.
fn subtree(lights: &mut [TreeLight], depth: u32, trail: u32, out: &mut Fragment) -> LightBounds {
    if let [light] = lights {
        out.trails.push((light.trail_index, trail));
        out.nodes.push(light.bounds.gpu(light.link, true));
        return light.bounds;
    }
    let parallel = lights.len() >= PARALLEL_LIGHTS && depth < PARALLEL_DEPTH;
    let mid = split(lights, depth);
    let at = out.nodes.len();
    out.nodes.push(GpuLightTreeNode::default());
    let (first, second) = lights.split_at_mut(mid);
    let second_trail = trail | (1 << depth);
    let (a, b, second_index) = if parallel {
        let mut other = Fragment::default();
        let (a, b) = std::thread::scope(|scope| {
            let handle = scope.spawn(|| subtree(second, depth + 1, second_trail, &mut other));
            let a = subtree(first, depth + 1, trail, out);
            (a, handle.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)))
        });
        let offset = out.nodes.len() as u32;
        out.nodes.extend(other.nodes.into_iter().map(|mut node| {
            if node.flags & LIGHT_TREE_LEAF == 0 {
                node.link += offset;
            }
            node
        }));
        out.trails.extend(other.trails);
        (a, b, offset)
    } else {
        let a = subtree(first, depth + 1, trail, out);
        let second_index = out.nodes.len() as u32;
        (a, subtree(second, depth + 1, second_trail, out), second_index)
    };
    let bounds = LightBounds::union(&a, &b);
    out.nodes[at] = bounds.gpu(second_index, false);
    bounds
}

/// Levels a balanced tree over `n` leaves needs below its root.
fn levels(n: usize) -> u32 {
    n.next_power_of_two().trailing_zeros()
}

/// Reorders `lights` (at least two) into two groups and returns the first one's size:
/// at the bucket boundary of least cost, or at the median of the longest axis when no
/// boundary separates them or when the cheapest split would leave a group too deep
/// for a trail.
fn split(lights: &mut [TreeLight], depth: u32) -> usize {
    let n = lights.len();
    let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    let (mut c_min, mut c_max) = (lo, hi);
    for l in lights.iter() {
        (lo, hi) = (lo.min(l.bounds.min), hi.max(l.bounds.max));
        (c_min, c_max) = (c_min.min(l.bounds.centroid()), c_max.max(l.bounds.centroid()));
    }
    let extent = hi - lo;
    let bucket_of = |l: &TreeLight, axis: usize| -> usize {
        let t = (l.bounds.centroid()[axis] - c_min[axis]) / (c_max[axis] - c_min[axis]);
        ((t * BUCKETS as f32) as usize).min(BUCKETS - 1)
    };
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in 0..3 {
        if c_max[axis] <= c_min[axis] {
            continue;
        }
        let mut buckets: [Option<LightBounds>; BUCKETS] = [None; BUCKETS];
        for l in lights.iter() {
            let b = &mut buckets[bucket_of(l, axis)];
            *b = Some(b.map_or(l.bounds, |acc| LightBounds::union(&acc, &l.bounds)));
        }
        let join = |range: &[Option<LightBounds>]| {
            range
                .iter()
                .flatten()
                .fold(None, |acc: Option<LightBounds>, b| Some(acc.map_or(*b, |a| LightBounds::union(&a, b))))
        };
        for boundary in 1..BUCKETS {
            let (Some(below), Some(above)) = (join(&buckets[..boundary]), join(&buckets[boundary..])) else {
                continue;
            };
            let cost = below.cost(extent, axis) + above.cost(extent, axis);
            if cost.is_finite() && best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, boundary));
            }
        }
    }
    if let Some((_, axis, boundary)) = best {
        let mut left = 0;
        for i in 0..n {
            if bucket_of(&lights[i], axis) < boundary {
                lights.swap(i, left);
                left += 1;
            }
        }
        let room = MAX_DEPTH - depth - 1;
        if left > 0 && left < n && levels(left) <= room && levels(n - left) <= room {
            return left;
        }
    }
    let axis = (c_max - c_min).max_position();
    let mid = n / 2;
    lights.select_nth_unstable_by(mid, |a, b| a.bounds.centroid()[axis].total_cmp(&b.bounds.centroid()[axis]));
    mid
}

#[cfg(test)]
mod tests;
