//! The binary top level of a scene: a BVH over its instances' and spheres' world boxes.

use super::node::{BvhStats, convert_bvh2, stats};
use crate::layout::GpuBvhNode;
use glam::Vec3;
use obvhs::{BvhBuildParams, aabb::Aabb};
use std::time::{Duration, Instant};

/// The binary top level over the instances' and spheres' boxes.
pub(super) struct TopLevel {
    pub nodes: Vec<GpuBvhNode>,
    pub primitives: Vec<u32>,
    pub build_time: Duration,
    pub stats: BvhStats,
    pub bounds_min: Vec3,
    pub bounds_max: Vec3,
}

impl TopLevel {
    pub fn build(boxes: &[Aabb], entries: &[u32]) -> Self {
        let start = Instant::now();
        let (nodes, primitives) = if boxes.is_empty() {
            (convert_bvh2(&obvhs::bvh2::Bvh2::default()), Vec::new())
        } else {
            let bvh = super::binned_build::build_optimised(boxes, &BvhBuildParams::medium_build());
            let prims = bvh.primitive_indices.iter().map(|&i| entries[i as usize]).collect();
            (convert_bvh2(&bvh), prims)
        };
        let build_time = start.elapsed();
        let stats = stats(&nodes);
        let (bounds_min, bounds_max) =
            boxes.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), b| {
                (lo.min(b.min.into()), hi.max(b.max.into()))
            });
        Self { nodes, primitives, build_time, stats, bounds_min, bounds_max }
    }
}
