//! Everything a scene puts on the GPU: the meshes' bottom-level BVHs, a top
//! level over instances and spheres, and the material table.

use super::mesh_bvh::BuildQuality;
use super::node::{BvhStats, convert_bvh2, stats};
use super::pack::{LoadedMesh, build_all_in_memory, load_or_pack_all};
use crate::layout::*;
use crate::scene::{GeometrySummary, Material, Scene};
use anyhow::{Result, bail};
use glam::{Mat4, Vec3, Vec3A};
use obvhs::{BvhBuildParams, aabb::Aabb, bvh2::builder::build_bvh2};
use std::collections::HashMap;
use std::path::PathBuf;
use std::time::Duration;

pub struct SceneGeometry {
    /// Bottom levels of every mesh, then the top level (from `tlas_root`).
    pub nodes: Vec<GpuBvhNode>,
    pub triangles: Vec<GpuTriangle>,
    pub shading: Vec<GpuTriangleShading>,
    pub instances: Vec<GpuInstance>,
    pub tlas_primitives: Vec<u32>,
    pub spheres: Vec<GpuSphere>,
    /// The default material first, then the scene's, then each mesh's own.
    pub materials: Vec<GpuMaterial>,
    /// Emissive triangles and spheres with their cumulative selection probabilities.
    pub emitters: Vec<GpuEmitter>,
    /// Sum of the emitters' powers (area × luminance of emission).
    pub emitter_total_power: f32,
    pub tlas_root: u32,
    pub tlas_stats: BvhStats,
    pub meshes: Vec<LoadedMesh>,
    /// Every material some triangle or sphere uses.
    pub materials_in_use: Vec<Material>,
    pub bounds_min: Vec3,
    pub bounds_max: Vec3,
}

impl SceneGeometry {
    /// The scene's textures in the order the materials index them: each mesh's in turn.
    pub fn textures(&self) -> impl Iterator<Item = &crate::asset::TextureImage> {
        self.meshes.iter().flat_map(|m| &m.textures)
    }

    /// What the feature analysis needs to know of the geometry.
    pub fn summary(&self) -> GeometrySummary {
        GeometrySummary {
            triangles: !self.instances.is_empty(),
            spheres: !self.spheres.is_empty(),
            materials_in_use: self.materials_in_use.clone(),
        }
    }

    /// Loads every asset's BVH once (from its cache, or packing it when the cache is
    /// missing or stale), and places instances and spheres.
    pub fn build(scene: &Scene, quality: BuildQuality) -> Result<Self> {
        Self::load_and_assemble(scene, load_or_pack_all(&asset_paths(scene), quality)?)
    }

    /// Every mesh's BVH built afresh at `quality` in memory, caches neither read nor
    /// written: to time builds without disturbing caches of another quality.
    pub fn build_in_memory(scene: &Scene, quality: BuildQuality) -> Result<Self> {
        Self::load_and_assemble(scene, build_all_in_memory(&asset_paths(scene), quality)?)
    }

    fn load_and_assemble(scene: &Scene, meshes: Vec<LoadedMesh>) -> Result<Self> {
        for mesh in &meshes {
            log::info!("{}: {} triangles, {:?}", mesh.path.display(), mesh.triangle_count, mesh.provenance);
        }
        Self::assemble(scene, meshes)
    }

    /// Places `meshes` (one per path of [`asset_paths`], in any order) as the scene's
    /// instances, with its spheres and materials: everything but loading assets, so that a
    /// live reload of one asset or of the materials reuses the BVHs of the others.
    pub fn assemble(scene: &Scene, meshes: Vec<LoadedMesh>) -> Result<Self> {
        let mesh_of_path: HashMap<PathBuf, usize> =
            meshes.iter().enumerate().map(|(i, m)| (m.path.clone(), i)).collect();
        if let Some(m) = scene.meshes.iter().find(|m| !mesh_of_path.contains_key(&m.asset)) {
            bail!("{}: the asset {} was not loaded", scene.origin, m.asset.display());
        }

        let mut materials: Vec<Material> = vec![Material::default()];
        materials.extend(scene.materials.iter().map(|(_, m)| m.clone()));
        let scene_material = |name: &Option<String>| -> Result<u32> {
            match name {
                None => Ok(0),
                Some(n) => match scene.material_index(n) {
                    Some(i) => Ok(1 + i as u32),
                    None => bail!("{}: no material named {n:?}", scene.origin),
                },
            }
        };

        let mut nodes = Vec::new();
        let mut triangles = Vec::new();
        let mut shading = Vec::new();
        // (node offset, triangle offset, material base) of each mesh.
        let mut placed = Vec::new();
        // Each mesh's textures follow the previous meshes' in the scene's texture table.
        let mut texture_base = 0u32;
        for mesh in &meshes {
            placed.push((nodes.len() as u32, triangles.len() as u32, materials.len() as u32));
            nodes.extend_from_slice(&mesh.bvh.nodes);
            triangles.extend_from_slice(&mesh.bvh.triangles);
            shading.extend_from_slice(&mesh.bvh.shading);
            materials.extend(mesh.materials.iter().map(|(_, m)| {
                let mut m = m.clone();
                for index in m.textures.indices_mut().into_iter().flatten() {
                    *index += texture_base;
                }
                m
            }));
            texture_base += mesh.textures.len() as u32;
        }

        let mut in_use = vec![false; materials.len()];
        let mut instances = Vec::new();
        // (first triangle, triangle count) of each instance's mesh.
        let mut instance_triangles = Vec::new();
        let mut boxes = Vec::new();
        // Top-level primitive of each box: instance index, or sphere index | SPHERE_BIT.
        let mut entries = Vec::new();
        for m in &scene.meshes {
            let mesh_index = mesh_of_path[&m.asset];
            let mesh = &meshes[mesh_index];
            if mesh.triangle_count == 0 {
                continue;
            }
            let (node_offset, triangle_offset, material_base) = placed[mesh_index];
            let material_override = match &m.material {
                Some(_) => scene_material(&m.material)?,
                None => NO_MATERIAL,
            };
            if material_override == NO_MATERIAL {
                for i in 0..mesh.materials.len() {
                    in_use[material_base as usize + i] = true;
                }
            } else {
                in_use[material_override as usize] = true;
            }
            entries.push(instances.len() as u32);
            instance_triangles.push(triangle_offset..triangle_offset + mesh.bvh.triangles.len() as u32);
            boxes.push(transformed_box(&m.object_to_world, mesh.bvh.bounds_min, mesh.bvh.bounds_max));
            instances.push(GpuInstance {
                world_to_object: affine_rows(&m.object_to_world.inverse()),
                object_to_world: affine_rows(&m.object_to_world),
                node_offset,
                triangle_offset,
                material_base,
                material_override,
            });
        }
        let mut spheres = Vec::new();
        for s in &scene.spheres {
            let material = scene_material(&s.material)?;
            in_use[material as usize] = true;
            entries.push(spheres.len() as u32 | SPHERE_BIT);
            let r = Vec3A::splat(s.radius);
            let c = Vec3A::from(s.center);
            boxes.push(Aabb::new(c - r, c + r));
            let k = s.center.as_dvec3().length_squared() - (s.radius as f64).powi(2);
            spheres.push(GpuSphere {
                center: s.center.to_array(),
                radius: s.radius,
                material,
                k: k as f32,
                _pad: [0; 2],
            });
        }

        let materials_in_use = materials.iter().zip(&in_use).filter(|(_, u)| **u).map(|(m, _)| m.clone()).collect();
        let (emitters, emitter_total_power) =
            emitter_table(&instances, &instance_triangles, &triangles, &spheres, &materials);

        let (tlas_nodes, tlas_primitives) = if boxes.is_empty() {
            (convert_bvh2(&obvhs::bvh2::Bvh2::default()), Vec::new())
        } else {
            let bvh = build_bvh2(&boxes, BvhBuildParams::medium_build(), &mut Duration::default());
            let prims = bvh.primitive_indices.iter().map(|&i| entries[i as usize]).collect();
            (convert_bvh2(&bvh), prims)
        };
        let tlas_root = nodes.len() as u32;
        let tlas_stats = stats(&tlas_nodes);
        nodes.extend_from_slice(&tlas_nodes);
        let (bounds_min, bounds_max) =
            boxes.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), b| {
                (lo.min(b.min.into()), hi.max(b.max.into()))
            });

        Ok(Self {
            nodes,
            triangles,
            shading,
            instances,
            tlas_primitives,
            spheres,
            materials: materials.iter().map(GpuMaterial::from).collect(),
            emitters,
            emitter_total_power,
            tlas_root,
            tlas_stats,
            meshes,
            materials_in_use,
            bounds_min,
            bounds_max,
        })
    }
}

/// The distinct assets that a scene's meshes place, in file order.
pub fn asset_paths(scene: &Scene) -> Vec<PathBuf> {
    let mut seen = std::collections::HashSet::new();
    scene.meshes.iter().filter(|m| seen.insert(&m.asset)).map(|m| m.asset.clone()).collect()
}

/// Every emissive triangle of every instance, and every emissive sphere, with
/// selection probabilities in proportion to power: world area × luminance of
/// emission (the GPU's light pdfs assume exactly this).
fn emitter_table(
    instances: &[GpuInstance],
    instance_triangles: &[std::ops::Range<u32>],
    triangles: &[GpuTriangle],
    spheres: &[GpuSphere],
    materials: &[Material],
) -> (Vec<GpuEmitter>, f32) {
    let mut entries: Vec<(GpuEmitter, f64)> = Vec::new();
    for (index, (inst, range)) in instances.iter().zip(instance_triangles).enumerate() {
        let to_world = |v: [f32; 3]| {
            let p = glam::DVec3::from(v.map(f64::from));
            let r = inst.object_to_world.map(|row| glam::DVec4::from(row.map(f64::from)));
            glam::DVec3::new(
                r[0].truncate().dot(p) + r[0].w,
                r[1].truncate().dot(p) + r[1].w,
                r[2].truncate().dot(p) + r[2].w,
            )
        };
        for t in range.clone() {
            let tri = &triangles[t as usize];
            let material = if inst.material_override == NO_MATERIAL {
                inst.material_base + tri.material
            } else {
                inst.material_override
            };
            let lum = crate::scene::luminance(materials[material as usize].emission) as f64;
            if lum <= 0.0 {
                continue;
            }
            let (a, b, c) = (to_world(tri.v0), to_world(tri.v1), to_world(tri.v2));
            let area = 0.5 * (b - a).cross(c - a).length();
            if area > 0.0 {
                entries.push((GpuEmitter { primitive: t, instance: index as u32, cdf: 0.0, _pad0: 0 }, area * lum));
            }
        }
    }
    for (index, s) in spheres.iter().enumerate() {
        let lum = crate::scene::luminance(materials[s.material as usize].emission) as f64;
        if lum > 0.0 {
            let area = 4.0 * std::f64::consts::PI * (s.radius as f64).powi(2);
            entries.push((
                GpuEmitter { primitive: index as u32 | SPHERE_BIT, instance: 0, cdf: 0.0, _pad0: 0 },
                area * lum,
            ));
        }
    }
    let total: f64 = entries.iter().map(|(_, p)| p).sum();
    let mut running = 0.0;
    let mut emitters: Vec<GpuEmitter> = entries
        .into_iter()
        .map(|(mut e, p)| {
            running += p;
            e.cdf = (running / total) as f32;
            e
        })
        .collect();
    // Rounding must not leave u ∈ [cdf_last, 1) without an emitter.
    if let Some(last) = emitters.last_mut() {
        last.cdf = 1.0;
    }
    (emitters, total as f32)
}

fn affine_rows(m: &Mat4) -> [[f32; 4]; 3] {
    [m.row(0).to_array(), m.row(1).to_array(), m.row(2).to_array()]
}

fn transformed_box(m: &Mat4, lo: Vec3, hi: Vec3) -> Aabb {
    let mut b = Aabb::empty();
    for i in 0..8 {
        let corner = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        b.extend(m.transform_point3(corner).into());
    }
    // The GPU transforms rays with its own rounding; a margin of a few ULPs of
    // the box's magnitude keeps the box conservative for them.
    let margin = (b.min.abs().max(b.max.abs())).max_element() * 4.0 * f32::EPSILON;
    Aabb::new(b.min - Vec3A::splat(margin), b.max + Vec3A::splat(margin))
}
