//! Everything a scene puts on the GPU: the meshes' bottom-level BVHs, a top
//! level over instances and spheres, and the material table.

use super::emitter_table::EmissiveTriangles;
use super::light_tree::LightTree;
use super::mesh_bvh::{BuildQuality, MeshBvh};
use super::node::BvhStats;
use super::node_table::NodeTable;
use super::pack::{LoadedMesh, build_all_in_memory, load_or_pack_all};
use super::placement::{MeshSlot, Placement, with_bases};
use super::scene_lights::SceneLights;
use super::top_level::TopLevel;
use crate::asset::node_program;
use crate::layout::*;
use crate::scene::{GeometrySummary, Material, Scene};
use anyhow::{Result, bail};
use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;
use std::collections::HashMap;
use std::path::PathBuf;
use std::time::Duration;

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
    /// Per triangle, the most attributes a mesh has, one after another: empty when no mesh
    /// has any, else zero past a mesh's own.
    pub attributes: Vec<GpuTriangleAttribute>,
    pub instances: Vec<GpuInstance>,
    /// Each instance's Shadow Terminator settings, holdout and Random, in the instances'
    /// order; then, when some object is not white, each instance's Object Color (RGBA in
    /// the record's four words: the colours share the settings' binding, since lavapipe
    /// binds at most 29 storage buffers per stage and the atmosphere's pipeline had 29).
    pub object_settings: Vec<GpuObjectSettings>,
    /// Some instance's Object Color is not white (its colours follow the settings).
    pub object_colors: bool,
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
            object_colors: self.object_colors,
            moving: !self.motion_matrices.is_empty(),
            moving_lights: self.moving_lights,
            node_code: self.node_code,
            graph_normals: self.materials_in_use.iter().any(|m| node_program::drives(&m.node_program, "normal")),
            attributes_read: !self.attributes.is_empty()
                && self.materials_in_use.iter().any(|m| node_program::reads_attributes(&m.node_program)),
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
            + self.attributes.len() * size_of::<GpuTriangleAttribute>()
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
        let MeshArrays { wide_nodes, triangles, shading, tangents, second_uvs, attributes, slots, mut materials } =
            MeshArrays::of(scene, &meshes);
        let placed = Placed::of(scene, &meshes, &slots, &mut materials, &mesh_of_path)?;
        let Placed { placement, mut in_use, entries, boxes, spheres } = placed;
        // The world's graph, if any, is the last material (`shaders/sky_graph.wgsl`).
        if let Some(world) = super::world_graph::material(scene)? {
            materials.push(world);
            in_use.push(true);
        }
        let Placement {
            mut instances,
            object_settings,
            object_colors,
            shading_offsets,
            held_out,
            motion_matrices,
            instance_motion,
            instance_mesh,
            ..
        } = placement;
        let smooth_normals = !instances.is_empty() && meshes.iter().any(|m| m.bvh.has_interpolated_normals());
        let node_table = NodeTable::of(&materials);
        let materials_in_use = shown_materials(&materials, &mut in_use);
        let mesh_triangles: Vec<_> = slots
            .iter()
            .zip(&meshes)
            .map(|(s, m)| s.triangle_offset..s.triangle_offset + m.bvh.triangles.len() as u32)
            .collect();
        let emissive =
            EmissiveTriangles { mesh_triangles: &mesh_triangles, triangles: &triangles, materials: &materials };
        let (emitters, emitter_bounds, emitter_total_power) = emissive.table(&instances, &instance_mesh, &spheres);
        let moving_lights = mark_moving(scene, &mut instances, &instance_motion, motion_matrices.len(), &emitters)?;
        let top = TopLevel::build(&boxes, &entries);
        let lights =
            SceneLights::of(scene, &emitters, &emitter_bounds, moving_lights, (top.bounds_min, top.bounds_max))?;
        Ok(Self {
            nodes: top.nodes,
            wide_nodes,
            triangles,
            shading,
            tangents,
            second_uvs,
            attributes,
            instances,
            object_colors: coloured(&object_colors),
            object_settings: with_colors(object_settings, &object_colors),
            shading_offsets,
            held_out,
            moving_lights,
            motion_matrices,
            tlas_primitives: top.primitives,
            spheres,
            materials: gpu_materials(&materials, &node_table),
            node_programs: node_table.words,
            node_shapes: node_table.shapes,
            node_code: node_table.key,
            emitters,
            emitter_total_power,
            lamps: lights.lamps,
            lamp_info: lights.lamp_info,
            light_tree: lights.tree,
            light_tree_build_time: lights.tree_build_time,
            tlas_root: 0,
            tlas_stats: top.stats,
            tlas_build_time: top.build_time,
            meshes,
            materials_in_use,
            smooth_normals,
            bounds_min: top.bounds_min,
            bounds_max: top.bounds_max,
        })
    }
}

/// The index of the scene's material `name` in the material table (the default, 0, for none).
fn scene_material(scene: &Scene, name: &Option<String>) -> Result<u32> {
    match name {
        None => Ok(0),
        Some(n) => match scene.material_index(n) {
            Some(i) => Ok(1 + i as u32),
            None => bail!("{}: no material named {n:?}", scene.origin),
        },
    }
}

/// Every mesh's arrays one after another, and the material table: the default material,
/// the scene's, then each mesh's own (set materials are added when placed).
struct MeshArrays {
    wide_nodes: Vec<GpuWideNode>,
    triangles: Vec<GpuTriangle>,
    shading: Vec<GpuTriangleShading>,
    tangents: Vec<GpuTriangleTangents>,
    second_uvs: Vec<GpuTriangleUvs>,
    attributes: Vec<GpuTriangleAttribute>,
    slots: Vec<MeshSlot>,
    materials: Vec<Material>,
}

impl MeshArrays {
    fn of(scene: &Scene, meshes: &[LoadedMesh]) -> Self {
        let mut materials: Vec<Material> = vec![Material::default()];
        materials.extend(scene.materials.iter().map(|(_, m)| m.clone()));
        let mut arrays = Self {
            wide_nodes: Vec::new(),
            triangles: Vec::new(),
            shading: Vec::new(),
            tangents: Vec::new(),
            second_uvs: Vec::new(),
            attributes: Vec::new(),
            slots: Vec::new(),
            materials,
        };
        let attribute_stride = meshes.iter().map(|m| m.bvh.attribute_count()).max().unwrap_or(0);
        let any_tangents = meshes.iter().any(|m| !m.bvh.tangents.is_empty());
        let any_second_uvs = meshes.iter().any(|m| !m.bvh.second_uvs.is_empty());
        // Each mesh's textures follow the previous meshes' in the scene's texture table.
        let mut texture_base = 0u32;
        for mesh in meshes {
            arrays.slots.push(MeshSlot {
                node_offset: arrays.wide_nodes.len() as u32,
                triangle_offset: arrays.triangles.len() as u32,
                material_base: arrays.materials.len() as u32,
                texture_base,
            });
            arrays.wide_nodes.extend_from_slice(&mesh.bvh.nodes);
            arrays.triangles.extend_from_slice(&mesh.bvh.triangles);
            arrays.shading.extend_from_slice(&mesh.bvh.shading);
            let count = arrays.triangles.len();
            if any_tangents {
                extend_or_zero(&mut arrays.tangents, &mesh.bvh.tangents, count);
            }
            if any_second_uvs {
                extend_or_zero(&mut arrays.second_uvs, &mesh.bvh.second_uvs, count);
            }
            extend_attributes(&mut arrays.attributes, &mesh.bvh, attribute_stride);
            let material_base = arrays.materials.len() as u32;
            arrays.materials.extend(mesh.materials.iter().map(|(_, m)| with_bases(m, texture_base, material_base)));
            texture_base += mesh.textures.len() as u32;
        }
        arrays
    }
}

/// A mesh's per-triangle records after the previous meshes', or zeros to `count` for a
/// mesh that has none.
fn extend_or_zero<T: Copy + Default>(all: &mut Vec<T>, mesh: &[T], count: usize) {
    match mesh.is_empty() {
        true => all.resize(count, T::default()),
        false => all.extend_from_slice(mesh),
    }
}

/// A mesh's triangles' attributes after the previous meshes', each triangle's padded with
/// zeros to `stride`.
fn extend_attributes(all: &mut Vec<GpuTriangleAttribute>, mesh: &MeshBvh, stride: usize) {
    let own = mesh.attribute_count();
    if stride == 0 {
        return;
    }
    if own == 0 {
        all.resize(all.len() + mesh.triangles.len() * stride, GpuTriangleAttribute::default());
        return;
    }
    for triangle in mesh.attributes.chunks_exact(own) {
        all.extend_from_slice(triangle);
        all.resize(all.len() + stride - own, GpuTriangleAttribute::default());
    }
}

/// The scene's meshes, instance sets and spheres placed in the world, with the boxes
/// and entries of the top level and which materials something shows.
struct Placed<'m> {
    placement: Placement<'m>,
    in_use: Vec<bool>,
    /// Top-level primitive of each box: instance index, or sphere index | SPHERE_BIT.
    entries: Vec<u32>,
    boxes: Vec<Aabb>,
    spheres: Vec<GpuSphere>,
}

impl<'m> Placed<'m> {
    /// `materials` gains the material sets' blocks.
    fn of(
        scene: &Scene,
        meshes: &'m [LoadedMesh],
        slots: &'m [MeshSlot],
        materials: &mut Vec<Material>,
        mesh_of_path: &HashMap<PathBuf, usize>,
    ) -> Result<Self> {
        let mut placement = Placement::new(meshes, slots, materials.len());
        for m in &scene.meshes {
            let material_override = match &m.material {
                Some(_) => scene_material(scene, &m.material)?,
                None => NO_MATERIAL,
            };
            let settings = GpuObjectSettings::new(m.shadow_terminator, m.holdout, m.info);
            let settings = (settings, m.info.color);
            placement.place(mesh_of_path[&m.asset], &m.object_to_world, material_override, settings, m.motion.as_ref());
        }
        for set in &scene.instance_sets {
            let named = |n: &str| scene_material(scene, &Some(n.to_owned()));
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
        materials.append(&mut placement.set_materials);
        let entries: Vec<u32> = (0..placement.instances.len() as u32).collect();
        let boxes = std::mem::take(&mut placement.boxes);
        let mut placed = Self { placement, in_use, entries, boxes, spheres: Vec::new() };
        placed.add_spheres(scene)?;
        Ok(placed)
    }

    fn add_spheres(&mut self, scene: &Scene) -> Result<()> {
        for s in &scene.spheres {
            let material = scene_material(scene, &s.material)?;
            self.in_use[material as usize] = true;
            self.entries.push(self.spheres.len() as u32 | SPHERE_BIT);
            let r = Vec3A::splat(s.radius);
            let c = Vec3A::from(s.center);
            self.boxes.push(Aabb::new(c - r, c + r));
            let k = s.center.as_dvec3().length_squared() - (s.radius as f64).powi(2);
            self.spheres.push(GpuSphere {
                center: s.center.to_array(),
                radius: s.radius,
                material,
                k: k as f32,
                _pad: [0; 2],
            });
        }
        Ok(())
    }
}

/// The materials something shows (`in_use`, completed here: a Mix Shader's second
/// material is shown wherever its first is).
fn shown_materials(materials: &[Material], in_use: &mut [bool]) -> Vec<Material> {
    for (i, m) in materials.iter().enumerate() {
        if let Some(mix) = m.mix_material.filter(|_| in_use[i]) {
            in_use[mix as usize] = true;
        }
    }
    materials.iter().zip(in_use.iter()).filter(|(_, u)| **u).map(|(m, _)| m.clone()).collect()
}

/// The distinct assets that a scene's meshes and instance files place, in file order.
pub fn asset_paths(scene: &Scene) -> Vec<PathBuf> {
    let mut seen = std::collections::HashSet::new();
    let placed = scene.meshes.iter().map(|m| &m.asset).chain(scene.instance_sets.iter().map(|s| &s.asset));
    placed.filter(|a| seen.insert(*a)).cloned().collect()
}

/// Whether some instance's Object Color is not white.
fn coloured(colors: &[[f32; 4]]) -> bool {
    colors.iter().any(|c| *c != [1.0; 4])
}

/// The instances' settings, followed by their Object Colors when some is not white (one
/// record each: red, green, blue and alpha in its four words).
fn with_colors(mut settings: Vec<GpuObjectSettings>, colors: &[[f32; 4]]) -> Vec<GpuObjectSettings> {
    if !coloured(colors) {
        return settings;
    }
    for c in colors {
        settings.push(GpuObjectSettings {
            geometry_offset: c[0],
            frequency_multiplier: c[1],
            holdout_and_index: c[2].to_bits(),
            random: c[3],
        });
    }
    settings
}
