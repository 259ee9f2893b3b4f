//! Everything a scene puts on the GPU: the meshes' bottom-level BVHs, a top
//! level over instances and spheres, and the material table.

use super::light_bounds::{lamp_bounds, sphere_bounds, triangle_bounds};
use super::light_tree::{LightBounds, LightTree, TreeLight};
use super::lights::{LampTable, lamp_table, scene_radius};
use super::mesh_bvh::BuildQuality;
use super::node::{BvhStats, convert_bvh2, stats};
use super::node_table::NodeTable;
use super::pack::{LoadedMesh, build_all_in_memory, load_or_pack_all};
use super::placement::{MeshSlot, Placement, with_bases};
use crate::layout::*;
use crate::scene::{GeometrySummary, LightSampler, Material, Sampling, Scene};
use anyhow::{Result, bail};
use glam::{Vec3, Vec3A};
use obvhs::{BvhBuildParams, aabb::Aabb};
use std::collections::HashMap;
use std::path::PathBuf;
use std::time::{Duration, Instant};

pub struct SceneGeometry {
    /// The top level (binary, from `tlas_root`).
    pub nodes: Vec<GpuBvhNode>,
    /// The bottom levels of every mesh (8-wide), each mesh's root first.
    pub wide_nodes: Vec<GpuWideNode>,
    pub triangles: Vec<GpuTriangle>,
    pub shading: Vec<GpuTriangleShading>,
    /// Per triangle, for normal maps: empty when no mesh has tangents, else zero for
    /// the triangles of meshes that have none.
    pub tangents: Vec<GpuTriangleTangents>,
    /// Per triangle, the second uv set: empty when no mesh keeps one, else zero for the
    /// triangles of meshes that have none.
    pub second_uvs: Vec<GpuTriangleUvs>,
    pub instances: Vec<GpuInstance>,
    /// Each instance's Shadow Terminator settings and holdout, in the instances' order.
    pub object_settings: Vec<GpuObjectSettings>,
    /// Some instance has a Shadow Terminator Shading Offset.
    pub shading_offsets: bool,
    /// Some instance is a holdout.
    pub held_out: bool,
    /// Some emissive instance moves over the shutter (lights are then sampled by power).
    pub moving_lights: bool,
    /// The moving instances' matrices over the shutter (see `MOVING_INSTANCE`).
    pub motion_matrices: Vec<GpuMotionMatrix>,
    pub tlas_primitives: Vec<u32>,
    pub spheres: Vec<GpuSphere>,
    /// The default material first, then the scene's, then each mesh's own.
    pub materials: Vec<GpuMaterial>,
    /// The materials' node programs, one after another, each after its shape's number
    /// (`GpuMaterial::node_program` is where its first word is).
    pub node_programs: Vec<u32>,
    /// One program of each shape, for the pipeline's specialised code (none: interpreted).
    pub node_shapes: Vec<Vec<u32>>,
    /// Names `node_shapes` (0 when there are none).
    pub node_code: u64,
    /// Emissive triangles and spheres with their cumulative selection probabilities.
    pub emitters: Vec<GpuEmitter>,
    /// Sum of the emitters' powers (area × luminance of emission).
    pub emitter_total_power: f32,
    /// `[[light]]` lamps, and how light sampling shares its samples when there are some.
    pub lamps: Vec<GpuLamp>,
    pub lamp_info: GpuLampInfo,
    /// The light tree over the emitters and the lamps other than suns.
    pub light_tree: LightTree,
    /// Building it (at every load: it is over the placed lights, not per asset).
    pub light_tree_build_time: Duration,
    pub tlas_root: u32,
    pub tlas_stats: BvhStats,
    /// Building the top level over the instances' and spheres' boxes (obvhs, then the GPU layout).
    pub tlas_build_time: Duration,
    pub meshes: Vec<LoadedMesh>,
    /// Every material some triangle or sphere uses.
    pub materials_in_use: Vec<Material>,
    /// Some placed triangle has a vertex normal other than its face's
    /// ([`MeshBvh::has_interpolated_normals`](super::mesh_bvh::MeshBvh::has_interpolated_normals)).
    pub smooth_normals: bool,
    pub bounds_min: Vec3,
    pub bounds_max: Vec3,
}

/// Marks the GPU records of the moving instances (see `MOVING_INSTANCE`), once the emitter
/// table and the lights' bounds are made from each instance where the frame has it;
/// returns whether some emitter moves.
fn mark_moving(
    scene: &Scene,
    instances: &mut [GpuInstance],
    instance_motion: &[(usize, u32)],
    matrices: usize,
    emitters: &[GpuEmitter],
) -> Result<bool> {
    if matrices > MAX_INSTANCE_MOTION_MATRICES {
        bail!("{}: {matrices} motion matrices; rt keeps at most {MAX_INSTANCE_MOTION_MATRICES}", scene.origin);
    }
    let mut moving = vec![false; instances.len()];
    for &(i, word) in instance_motion {
        instances[i].mark_moving(word);
        moving[i] = true;
    }
    Ok(emitters.iter().any(|e| e.primitive & SPHERE_BIT == 0 && moving[e.instance as usize]))
}

/// The materials as the GPU reads them, each with where its node program starts.
fn gpu_materials(materials: &[Material], nodes: &NodeTable) -> Vec<GpuMaterial> {
    let programs = nodes.starts.iter().copied();
    materials
        .iter()
        .zip(programs)
        .map(|(m, start)| GpuMaterial { node_program: start.unwrap_or(NO_PROGRAM), ..GpuMaterial::from(m) })
        .collect()
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
            smooth_normals: self.smooth_normals,
            shading_offsets: self.shading_offsets,
            held_out: self.held_out,
            moving: !self.motion_matrices.is_empty(),
            moving_lights: self.moving_lights,
            node_code: self.node_code,
            materials_in_use: self.materials_in_use.clone(),
        }
    }

    /// GPU bytes of the meshes (bottom levels, triangles, shading), counted once
    /// however many instances place them.
    pub fn mesh_bytes(&self) -> usize {
        let bottom_nodes = self.tlas_root as usize;
        bottom_nodes * size_of::<GpuBvhNode>()
            + self.triangles.len() * size_of::<GpuTriangle>()
            + self.shading.len() * size_of::<GpuTriangleShading>()
            + self.tangents.len() * size_of::<GpuTriangleTangents>()
            + self.second_uvs.len() * size_of::<GpuTriangleUvs>()
    }

    /// GPU bytes that grow with the instances and spheres: their records, the top
    /// level's nodes and its leaf entries.
    pub fn top_level_bytes(&self) -> usize {
        let top_nodes = self.nodes.len() - self.tlas_root as usize;
        self.instances.len() * size_of::<GpuInstance>()
            + self.object_settings.len() * size_of::<GpuObjectSettings>()
            + self.motion_matrices.len() * size_of::<GpuMotionMatrix>()
            + self.spheres.len() * size_of::<GpuSphere>()
            + top_nodes * size_of::<GpuBvhNode>()
            + self.tlas_primitives.len() * size_of::<u32>()
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
        if let Some(a) = asset_paths(scene).iter().find(|a| !mesh_of_path.contains_key(*a)) {
            bail!("{}: the asset {} was not loaded", scene.origin, a.display());
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

        let mut wide_nodes = Vec::new();
        let mut triangles = Vec::new();
        let mut shading = Vec::new();
        let mut tangents = Vec::new();
        let any_tangents = meshes.iter().any(|m| !m.bvh.tangents.is_empty());
        let mut second_uvs = Vec::new();
        let any_second_uvs = meshes.iter().any(|m| !m.bvh.second_uvs.is_empty());
        let mut slots = Vec::new();
        // Each mesh's textures follow the previous meshes' in the scene's texture table.
        let mut texture_base = 0u32;
        for mesh in &meshes {
            slots.push(MeshSlot {
                node_offset: wide_nodes.len() as u32,
                triangle_offset: triangles.len() as u32,
                material_base: materials.len() as u32,
                texture_base,
            });
            wide_nodes.extend_from_slice(&mesh.bvh.nodes);
            triangles.extend_from_slice(&mesh.bvh.triangles);
            shading.extend_from_slice(&mesh.bvh.shading);
            if any_tangents {
                match mesh.bvh.tangents.is_empty() {
                    true => tangents.resize(triangles.len(), GpuTriangleTangents::default()),
                    false => tangents.extend_from_slice(&mesh.bvh.tangents),
                }
            }
            if any_second_uvs {
                match mesh.bvh.second_uvs.is_empty() {
                    true => second_uvs.resize(triangles.len(), GpuTriangleUvs::default()),
                    false => second_uvs.extend_from_slice(&mesh.bvh.second_uvs),
                }
            }
            let material_base = materials.len() as u32;
            materials.extend(mesh.materials.iter().map(|(_, m)| with_bases(m, texture_base, material_base)));
            texture_base += mesh.textures.len() as u32;
        }

        let mut placement = Placement::new(&meshes, &slots, materials.len());
        for m in &scene.meshes {
            let material_override = match &m.material {
                Some(_) => scene_material(&m.material)?,
                None => NO_MATERIAL,
            };
            let settings = GpuObjectSettings::new(m.shadow_terminator, m.holdout);
            placement.place(mesh_of_path[&m.asset], &m.object_to_world, material_override, settings, m.motion.as_ref());
        }
        for set in &scene.instance_sets {
            let named = |n: &str| scene_material(&Some(n.to_owned()));
            placement.place_file(scene, set, mesh_of_path[&set.asset], named)?;
        }
        let mut in_use = placement.override_used.clone();
        for (mesh_index, slot) in slots.iter().enumerate() {
            if placement.own_materials_shown[mesh_index] {
                let base = slot.material_base as usize;
                in_use[base..base + meshes[mesh_index].materials.len()].fill(true);
            }
        }
        // Material sets' blocks follow the meshes' own materials; only used sets have one.
        in_use.resize(in_use.len() + placement.set_materials.len(), true);
        let Placement {
            instances,
            object_settings,
            shading_offsets,
            held_out,
            motion_matrices,
            instance_motion,
            instance_mesh,
            mut boxes,
            set_materials,
            ..
        } = placement;
        materials.extend(set_materials);
        // Top-level primitive of each box: instance index, or sphere index | SPHERE_BIT.
        let mut entries: Vec<u32> = (0..instances.len() as u32).collect();
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

        let smooth_normals = !instances.is_empty() && meshes.iter().any(|m| m.bvh.has_interpolated_normals());
        // A Mix Shader's second material is shown wherever its first is.
        for (i, m) in materials.iter().enumerate() {
            if let Some(mix) = m.mix_material.filter(|_| in_use[i]) {
                in_use[mix as usize] = true;
            }
        }
        let node_table = NodeTable::of(&materials);
        let materials_in_use = materials.iter().zip(&in_use).filter(|(_, u)| **u).map(|(m, _)| m.clone()).collect();
        let mesh_triangles: Vec<_> = slots
            .iter()
            .zip(&meshes)
            .map(|(s, m)| s.triangle_offset..s.triangle_offset + m.bvh.triangles.len() as u32)
            .collect();
        let emissive =
            EmissiveTriangles { mesh_triangles: &mesh_triangles, triangles: &triangles, materials: &materials };
        let (emitters, emitter_bounds, emitter_total_power) = emissive.table(&instances, &instance_mesh, &spheres);
        let mut instances = instances;
        let moving_lights = mark_moving(scene, &mut instances, &instance_motion, motion_matrices.len(), &emitters)?;
        // The tree bounds each light where the frame has it; a light that moves over the
        // shutter could leave its bounds, so such scenes sample lights by power.
        let mut light_sampler = scene.render.light_sampler;
        if moving_lights && light_sampler == LightSampler::Tree {
            log::warn!("{}: an emissive mesh moves over the shutter: lights are sampled by power", scene.origin);
            light_sampler = LightSampler::Power;
        }

        let build_start = Instant::now();
        let (nodes, tlas_primitives) = if boxes.is_empty() {
            (convert_bvh2(&obvhs::bvh2::Bvh2::default()), Vec::new())
        } else {
            let bvh = super::binned_build::build_optimised(&boxes, &BvhBuildParams::medium_build());
            let prims = bvh.primitive_indices.iter().map(|&i| entries[i as usize]).collect();
            (convert_bvh2(&bvh), prims)
        };
        let tlas_build_time = build_start.elapsed();
        let tlas_root = 0;
        let tlas_stats = stats(&nodes);
        let (bounds_min, bounds_max) =
            boxes.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), b| {
                (lo.min(b.min.into()), hi.max(b.max.into()))
            });

        if scene.render.sampling == Sampling::Resampled {
            for (i, _) in scene.lights.iter().enumerate().filter(|(_, l)| l.is_delta()) {
                log::warn!(
                    "{}: light {} has no size (a point, or a sun of angle 0): with sampling = \"seed\" no ray finds it and it lights nothing",
                    scene.origin,
                    i + 1
                );
            }
        }
        let LampTable { lamps, info: lamp_info } = lamp_table(
            &scene.lights,
            scene.sun.is_some(),
            !emitters.is_empty(),
            scene_radius(bounds_min, bounds_max),
            light_sampler,
        );
        let tree_start = Instant::now();
        // Scenes that sample by power pay nothing for the tree: theirs is empty, and a
        // pipeline with the tree's code (all features) then finds emitters by BSDF rays only.
        let light_tree = if light_sampler == LightSampler::Tree {
            tree_of(&emitter_bounds, &scene.lights, &lamps)?
        } else {
            LightTree::build(&[], emitter_bounds.len() + lamps.len())?
        };
        let light_tree_build_time = tree_start.elapsed();
        log::info!(
            "light tree: {} nodes over {} lights in {:.2} ms",
            light_tree.nodes.len(),
            light_tree.trails.len(),
            light_tree_build_time.as_secs_f64() * 1e3
        );

        Ok(Self {
            nodes,
            wide_nodes,
            triangles,
            shading,
            tangents,
            second_uvs,
            instances,
            object_settings,
            shading_offsets,
            held_out,
            moving_lights,
            motion_matrices,
            tlas_primitives,
            spheres,
            materials: gpu_materials(&materials, &node_table),
            node_programs: node_table.words,
            node_shapes: node_table.shapes,
            node_code: node_table.key,
            emitters,
            emitter_total_power,
            lamps,
            lamp_info,
            light_tree,
            light_tree_build_time,
            tlas_root,
            tlas_stats,
            tlas_build_time,
            meshes,
            materials_in_use,
            smooth_normals,
            bounds_min,
            bounds_max,
        })
    }
}

/// The light tree over emitters (trail and link `j` for emitter j) and lamps (link
/// `i | LIGHT_TREE_LAMP`, trail `emitter count + i` for lamp i).
fn tree_of(emitter_bounds: &[LightBounds], lights: &[crate::scene::Light], lamps: &[GpuLamp]) -> Result<LightTree> {
    let count = emitter_bounds.len();
    let emitters =
        emitter_bounds.iter().enumerate().map(|(j, b)| TreeLight { bounds: *b, link: j as u32, trail_index: j as u32 });
    let lamps = lights.iter().zip(lamps).enumerate().filter_map(|(i, (l, lamp))| {
        let bounds = lamp_bounds(l, lamp)?;
        Some(TreeLight { bounds, link: i as u32 | LIGHT_TREE_LAMP, trail_index: (count + i) as u32 })
    });
    let tree_lights: Vec<TreeLight> = emitters.chain(lamps).collect();
    LightTree::build(&tree_lights, count + lights.len())
}

/// The distinct assets that a scene's meshes and instance files place, in file order.
pub fn asset_paths(scene: &Scene) -> Vec<PathBuf> {
    let mut seen = std::collections::HashSet::new();
    let placed = scene.meshes.iter().map(|m| &m.asset).chain(scene.instance_sets.iter().map(|s| &s.asset));
    placed.filter(|a| seen.insert(*a)).cloned().collect()
}

/// The triangles that can emit, per mesh, to find emitters without visiting every
/// triangle of every instance.
struct EmissiveTriangles<'a> {
    /// The range of each mesh's triangles in `triangles`.
    mesh_triangles: &'a [std::ops::Range<u32>],
    triangles: &'a [GpuTriangle],
    materials: &'a [Material],
}

impl EmissiveTriangles<'_> {
    fn luminance(&self, material: u32) -> f64 {
        crate::scene::luminance(self.materials[material as usize].emission) as f64
    }

    /// Every emissive triangle of every instance, and every emissive sphere, with
    /// selection probabilities in proportion to power: world area × luminance of
    /// emission (the GPU's light pdfs assume exactly this), and each one's bounds for the
    /// light tree. They come sorted by (sphere or not, instance, primitive), as the GPU's
    /// search for the emitter a ray hits needs.
    fn table(
        &self,
        instances: &[GpuInstance],
        instance_mesh: &[u32],
        spheres: &[GpuSphere],
    ) -> (Vec<GpuEmitter>, Vec<LightBounds>, f32) {
        // Triangles emissive by the materials an instance without an override shows (its
        // mesh's own, or a material set's), per mesh and first material: one with an
        // emissive override emits from all its triangles.
        let mut own: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
        let mut entries: Vec<(GpuEmitter, f64, LightBounds)> = Vec::new();
        for (index, (inst, &mesh)) in instances.iter().zip(instance_mesh).enumerate() {
            let all: Vec<u32>;
            let emitting: &[u32] = if inst.material_override == NO_MATERIAL {
                own.entry((mesh, inst.material_base)).or_insert_with(|| {
                    let range = self.mesh_triangles[mesh as usize].clone();
                    range
                        .filter(|&t| self.luminance(inst.material_base + self.triangles[t as usize].material) > 0.0)
                        .collect()
                })
            } else if self.luminance(inst.material_override) > 0.0 {
                all = self.mesh_triangles[mesh as usize].clone().collect();
                &all
            } else {
                &[]
            };
            if emitting.is_empty() {
                continue;
            }
            let m = super::placement::object_to_world(inst);
            let to_world = |v: [f32; 3]| m.transform_point3(glam::DVec3::from(v.map(f64::from)));
            for &t in emitting {
                let tri = &self.triangles[t as usize];
                let material = if inst.material_override == NO_MATERIAL {
                    inst.material_base + tri.material
                } else {
                    inst.material_override
                };
                let (a, b, c) = (to_world(tri.v0), to_world(tri.v1), to_world(tri.v2));
                let area = 0.5 * (b - a).cross(c - a).length();
                if area > 0.0 {
                    let emitter = GpuEmitter { primitive: t, instance: index as u32, cdf: 0.0, _pad0: 0 };
                    let luminance = self.luminance(material);
                    entries.push((emitter, area * luminance, triangle_bounds(a, b, c, luminance)));
                }
            }
        }
        for (index, s) in spheres.iter().enumerate() {
            let lum = self.luminance(s.material);
            if lum > 0.0 {
                let area = 4.0 * std::f64::consts::PI * (s.radius as f64).powi(2);
                entries.push((
                    GpuEmitter { primitive: index as u32 | SPHERE_BIT, instance: 0, cdf: 0.0, _pad0: 0 },
                    area * lum,
                    sphere_bounds(s, lum),
                ));
            }
        }
        let total: f64 = entries.iter().map(|(_, p, _)| p).sum();
        let bounds = entries.iter().map(|(_, _, b)| *b).collect();
        let mut running = 0.0;
        let mut emitters: Vec<GpuEmitter> = entries
            .into_iter()
            .map(|(mut e, p, _)| {
                running += p;
                e.cdf = (running / total) as f32;
                e
            })
            .collect();
        // Rounding must not leave u ∈ [cdf_last, 1) without an emitter.
        if let Some(last) = emitters.last_mut() {
            last.cdf = 1.0;
        }
        (emitters, bounds, total as f32)
    }
}
