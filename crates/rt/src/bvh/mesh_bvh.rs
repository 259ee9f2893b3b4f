//! One bottom-level BVH per mesh, with its triangles reordered for the GPU.

use super::node::BvhStats;
use super::wide_node::{convert_cwbvh, wide_stats};
use crate::asset::MeshData;
use crate::layout::{
    GpuTriangle, GpuTriangleAttribute, GpuTriangleShading, GpuTriangleTangents, GpuTriangleUvs, GpuWideNode,
};
use crate::scene::UvSet;
use glam::{Vec3, Vec3A};
use obvhs::{BvhBuildParams, cwbvh::CwBvh, triangle::Triangle};
use std::time::{Duration, Instant};

/// obvhs's build presets, from fastest build to fastest traversal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, clap::ValueEnum)]
pub enum BuildQuality {
    Fastest,
    #[default]
    Medium,
    Slow,
    VerySlow,
}

impl BuildQuality {
    fn params(self) -> BvhBuildParams {
        match self {
            BuildQuality::Fastest => BvhBuildParams::fastest_build(),
            BuildQuality::Medium => BvhBuildParams::medium_build(),
            BuildQuality::Slow => BvhBuildParams::slow_build(),
            BuildQuality::VerySlow => BvhBuildParams::very_slow_build(),
        }
    }
}

/// A mesh ready for upload: wide nodes (root first), and triangles in leaf order.
#[derive(Clone, Debug)]
pub struct MeshBvh {
    pub nodes: Vec<GpuWideNode>,
    pub triangles: Vec<GpuTriangle>,
    pub shading: Vec<GpuTriangleShading>,
    /// Per triangle (in `triangles`' order), for normal maps: the frame of the uv set its
    /// material's normal map reads (zero where that set has none); empty unless the mesh
    /// has tangents and some material of it has a normal map.
    pub tangents: Vec<GpuTriangleTangents>,
    /// Per triangle (in `triangles`' order): the second uv set, empty unless some
    /// material of the mesh reads it (see `asset::load_mesh`).
    pub second_uvs: Vec<GpuTriangleUvs>,
    /// Per triangle (in `triangles`' order), the mesh's attributes one after another
    /// (`attribute_count` of them each).
    pub attributes: Vec<GpuTriangleAttribute>,
    pub bounds_min: Vec3,
    pub bounds_max: Vec3,
    pub stats: BvhStats,
    pub build_time: Duration,
}

impl MeshBvh {
    /// How many attributes each triangle has.
    pub fn attribute_count(&self) -> usize {
        self.attributes.len().checked_div(self.triangles.len()).unwrap_or(0)
    }

    /// Whether some triangle has a vertex normal other than its face's: a face without
    /// normals stores its own at each vertex, so a flat-shaded mesh has none.
    pub fn has_interpolated_normals(&self) -> bool {
        self.triangles.iter().zip(&self.shading).any(|(t, s)| {
            let [v0, v1, v2] = [t.v0, t.v1, t.v2].map(Vec3::from);
            let face = (v1 - v0).cross(v2 - v0).normalize_or_zero();
            face != Vec3::ZERO
                && [s.n0, s.n1, s.n2].iter().any(|&n| Vec3::from(n).normalize_or_zero().dot(face) < 1.0 - 1e-6)
        })
    }

    pub fn build(mesh: &MeshData, quality: BuildQuality) -> Self {
        let start = Instant::now();
        let p = |i: u32| Vec3A::from_array(mesh.positions[i as usize]);
        // Zero-area triangles (repeated or exactly collinear vertices) reflect
        // nothing, yet rounding in the intersection test can report hits on
        // them with a meaningless distance and normal: they are left out.
        let kept: Vec<u32> = (0..mesh.indices.len() as u32).filter(|&i| has_area(mesh, i as usize)).collect();
        let tris: Vec<Triangle> = kept
            .iter()
            .map(|&i| {
                let t = mesh.indices[i as usize];
                Triangle { v0: p(t[0]), v1: p(t[1]), v2: p(t[2]) }
            })
            .collect();
        let bvh =
            if tris.is_empty() { CwBvh::default() } else { super::binned_build::mesh_cwbvh(&tris, quality.params()) };
        // With spatial splits a triangle may appear in several leaves; each gets its copy.
        let order: Vec<u32> = bvh.primitive_indices.iter().map(|&i| kept[i as usize]).collect();
        let triangles: Vec<GpuTriangle> = order
            .iter()
            .map(|&i| {
                let t = mesh.indices[i as usize];
                let v = t.map(|k| mesh.positions[k as usize]);
                GpuTriangle {
                    v0: v[0],
                    material: mesh.material_ids[i as usize],
                    v1: v[1],
                    v2: v[2],
                    ..Default::default()
                }
            })
            .collect();
        let nodes = convert_cwbvh(&bvh, &triangles);
        let shading = order.iter().map(|&i| triangle_shading(mesh, i as usize)).collect();
        let tangents_read = mesh.materials.iter().any(|(_, m)| m.reads_tangents());
        let any_tangents = mesh.tangents.is_some() || mesh.second_tangents.is_some();
        let tangents = match tangents_read && any_tangents {
            true => order.iter().map(|&i| triangle_tangents(mesh, i as usize)).collect(),
            false => Vec::new(),
        };
        let second_uvs = match &mesh.second_uvs {
            Some(uvs) => order
                .iter()
                .map(|&i| {
                    let [uv0, uv1, uv2] = mesh.indices[i as usize].map(|k| uvs[k as usize]);
                    GpuTriangleUvs { uv0, uv1, uv2 }
                })
                .collect(),
            None => Vec::new(),
        };
        let attributes = order
            .iter()
            .flat_map(|&i| {
                let corners = mesh.indices[i as usize];
                mesh.attributes.iter().map(move |values| {
                    let [a0, a1, a2] = corners.map(|k| values[k as usize]);
                    GpuTriangleAttribute { a0, a1, a2 }
                })
            })
            .collect();
        let (bounds_min, bounds_max) = bounds(&mesh.positions);
        let stats = wide_stats(&nodes);
        let build_time = start.elapsed();
        Self { nodes, triangles, shading, tangents, second_uvs, attributes, bounds_min, bounds_max, stats, build_time }
    }
}

/// Triangle `i`'s corner tangents of the uv set its material's normal map reads (the first
/// without one: that of anisotropy along the uv map).
fn triangle_tangents(mesh: &MeshData, i: usize) -> GpuTriangleTangents {
    let set =
        mesh.materials.get(mesh.material_ids[i] as usize).map_or(UvSet::First, |(_, m)| m.textures.normal_uv_set());
    match mesh.tangents_of(set) {
        Some(tangents) => {
            let [t0, t1, t2] = mesh.indices[i].map(|k| tangents[k as usize]);
            GpuTriangleTangents { t0, t1, t2 }
        }
        None => GpuTriangleTangents::default(),
    }
}

/// Whether a triangle has non-zero area, computed exactly enough in f64 that
/// only truly degenerate triangles are refused.
fn has_area(mesh: &MeshData, triangle: usize) -> bool {
    let p = mesh.indices[triangle].map(|k| glam::DVec3::from(mesh.positions[k as usize].map(f64::from)));
    (p[1] - p[0]).cross(p[2] - p[0]).length_squared() > 0.0
}

fn triangle_shading(mesh: &MeshData, triangle: usize) -> GpuTriangleShading {
    let t = mesh.indices[triangle];
    let n = match &mesh.normals {
        Some(normals) => t.map(|k| normals[k as usize]),
        None => {
            let p = t.map(|k| Vec3::from_array(mesh.positions[k as usize]));
            // Unnormalised is fine: the shader normalises after interpolating.
            let g = (p[1] - p[0]).cross(p[2] - p[0]).to_array();
            [g; 3]
        }
    };
    let uv = match &mesh.uvs {
        Some(uvs) => t.map(|k| uvs[k as usize]),
        None => [[0.0; 2]; 3],
    };
    GpuTriangleShading {
        n0: n[0],
        u0: uv[0][0],
        n1: n[1],
        u1: uv[1][0],
        n2: n[2],
        u2: uv[2][0],
        v: uv.map(|c| c[1]),
        _pad0: 0,
    }
}

fn bounds(points: &[[f32; 3]]) -> (Vec3, Vec3) {
    let mut lo = Vec3::splat(f32::MAX);
    let mut hi = Vec3::splat(f32::MIN);
    for p in points {
        lo = lo.min(Vec3::from_array(*p));
        hi = hi.max(Vec3::from_array(*p));
    }
    (lo, hi)
}
