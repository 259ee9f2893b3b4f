//! Placing meshes as instances: each one's GPU record, its world box for the top level,
//! and which materials it makes the scene use. Work per instance is constant (a matrix
//! inverse and eight corners), so a million instances of one mesh cost what a million
//! of a triangle do.

use super::pack::LoadedMesh;
use crate::asset::AssetError;
use crate::asset::rtinst::{self, MaterialSets};
use crate::layout::{GpuInstance, GpuMotionMatrix, GpuObjectSettings, NO_MATERIAL};
use crate::scene::{InstanceSet, Material, Motion, Scene};
use anyhow::{Result, bail};
use glam::{DMat4, Mat4, Vec3, Vec3A};
use obvhs::aabb::Aabb;
use std::path::Path;

/// Where a mesh's data sits in the scene's concatenated buffers.
#[derive(Clone, Copy)]
pub(super) struct MeshSlot {
    pub node_offset: u32,
    pub triangle_offset: u32,
    pub material_base: u32,
    /// The mesh's first texture in the scene's texture table.
    pub texture_base: u32,
}

/// `material` with its texture indices moved past the textures of the meshes before its own.
/// `material` of a mesh whose textures start at `texture_base` in the scene's texture table
/// and whose own materials at `material_base` in its material table: its indices made the
/// scene's (a Mix Shader's second material is among the mesh's own).
pub(super) fn with_bases(material: &Material, texture_base: u32, material_base: u32) -> Material {
    let mut m = material.clone();
    for index in m.textures.indices_mut().into_iter().flatten() {
        *index += texture_base;
    }
    if let Some(mix) = &mut m.mix_material {
        *mix += material_base;
    }
    m
}

pub(super) struct Placement<'m> {
    meshes: &'m [LoadedMesh],
    slots: &'m [MeshSlot],
    pub instances: Vec<GpuInstance>,
    /// Each instance's Shadow Terminator settings, holdout and Random.
    pub object_settings: Vec<GpuObjectSettings>,
    /// Each instance's Object Color.
    pub object_colors: Vec<[f32; 4]>,
    /// Some instance has a Shading Offset (the terminator shift's code is needed).
    pub shading_offsets: bool,
    /// Some instance is a holdout.
    pub held_out: bool,
    /// The moving instances' matrices over the shutter, one block per instance.
    pub motion_matrices: Vec<GpuMotionMatrix>,
    /// Each moving instance and its motion: its first matrix << 8 | how many.
    pub instance_motion: Vec<(usize, u32)>,
    /// Which mesh each instance places.
    pub instance_mesh: Vec<u32>,
    /// World box of each instance, for the top level.
    pub boxes: Vec<Aabb>,
    /// Whether some instance shows a mesh with its own materials.
    pub own_materials_shown: Vec<bool>,
    /// Whether some instance uses this material as its override.
    pub override_used: Vec<bool>,
    /// The materials of the material sets that instance files use, each set a block as
    /// long as its mesh's materials, to follow the scene's material table.
    pub set_materials: Vec<Material>,
    material_count: usize,
}

impl<'m> Placement<'m> {
    pub fn new(meshes: &'m [LoadedMesh], slots: &'m [MeshSlot], material_count: usize) -> Self {
        Self {
            meshes,
            slots,
            instances: Vec::new(),
            object_settings: Vec::new(),
            object_colors: Vec::new(),
            shading_offsets: false,
            held_out: false,
            motion_matrices: Vec::new(),
            instance_motion: Vec::new(),
            instance_mesh: Vec::new(),
            boxes: Vec::new(),
            own_materials_shown: vec![false; meshes.len()],
            override_used: vec![false; material_count],
            set_materials: Vec::new(),
            material_count,
        }
    }

    /// Places mesh `mesh_index` at `object_to_world` (invertible), with the material
    /// table index `material_override` or `NO_MATERIAL`, with its object's settings and
    /// Object Color, and
    /// moving through `motion` over the shutter if it moves. Empty meshes place nothing.
    pub fn place(
        &mut self,
        mesh_index: usize,
        object_to_world: &Mat4,
        material_override: u32,
        settings: (GpuObjectSettings, [f32; 4]),
        motion: Option<&Motion>,
    ) {
        let base = self.slots[mesh_index].material_base;
        if self.place_with_base(mesh_index, object_to_world, material_override, base, settings)
            && let Some(motion) = motion
        {
            self.set_moving(mesh_index, motion);
        }
    }

    /// Makes the instance placed last, of mesh `mesh_index`, move through `motion`: its
    /// matrices over the shutter, and a top-level box that holds its whole sweep.
    fn set_moving(&mut self, mesh_index: usize, motion: &Motion) {
        let samples = motion.world_to_object_samples();
        let word = (self.motion_matrices.len() as u32) << 8 | samples.len() as u32;
        self.motion_matrices.extend(samples.iter().map(GpuMotionMatrix::from));
        self.instance_motion.push((self.instances.len() - 1, word));
        let bvh = &self.meshes[mesh_index].bvh;
        let (lo, hi) = motion.swept_box(bvh.bounds_min, bvh.bounds_max);
        if let Some(b) = self.boxes.last_mut() {
            *b = transformed_box(&Mat4::IDENTITY, lo, hi);
        }
    }

    /// As [`Self::place`] without motion, the mesh's triangles indexing materials from
    /// `material_base` (the mesh's own, or a block of `set_materials`); whether it placed
    /// anything (an empty mesh places nothing).
    fn place_with_base(
        &mut self,
        mesh_index: usize,
        object_to_world: &Mat4,
        material_override: u32,
        material_base: u32,
        (settings, color): (GpuObjectSettings, [f32; 4]),
    ) -> bool {
        let mesh = &self.meshes[mesh_index];
        if mesh.triangle_count == 0 {
            return false;
        }
        if material_override == NO_MATERIAL && material_base == self.slots[mesh_index].material_base {
            self.own_materials_shown[mesh_index] = true;
        } else if material_override != NO_MATERIAL {
            self.override_used[material_override as usize] = true;
        }
        let slot = self.slots[mesh_index];
        self.boxes.push(transformed_box(object_to_world, mesh.bvh.bounds_min, mesh.bvh.bounds_max));
        self.instance_mesh.push(mesh_index as u32);
        self.instances.push(GpuInstance {
            world_to_object: affine_rows(&object_to_world.inverse()),
            node_offset: slot.node_offset,
            triangle_offset: slot.triangle_offset,
            material_base,
            material_override,
        });
        self.object_settings.push(settings);
        self.object_colors.push(color);
        self.shading_offsets |= settings.frequency_multiplier > 1.0;
        self.held_out |= settings.holdout_and_index & 1 != 0;
        true
    }

    /// Places every record of `set`'s instance file; `scene_material` maps a scene
    /// material's name to its index in the material table.
    pub fn place_file(
        &mut self,
        scene: &Scene,
        set: &InstanceSet,
        mesh_index: usize,
        scene_material: impl Fn(&str) -> Result<u32>,
    ) -> Result<()> {
        let file = rtinst::read(&set.file)?;
        let overrides: Vec<u32> = set.materials.iter().map(|n| scene_material(n)).collect::<Result<_>>()?;
        let set_bases = self.material_set_blocks(&set.file, &file.material_sets, mesh_index)?;
        let own_base = self.slots[mesh_index].material_base;
        let records = &file.records;
        self.instances.reserve(records.len());
        self.object_settings.reserve(records.len());
        self.boxes.reserve(records.len());
        self.instance_mesh.reserve(records.len());
        for (index, r) in records.iter().enumerate() {
            let (material, base) = match r.material {
                rtinst::OWN_MATERIALS => (NO_MATERIAL, own_base),
                i if i & rtinst::MATERIAL_SET != 0 => match set_bases.get((i & !rtinst::MATERIAL_SET) as usize) {
                    Some(&base) => (NO_MATERIAL, base),
                    None => {
                        let k = i & !rtinst::MATERIAL_SET;
                        let message = format!(
                            "instance {index}: material set {k} is out of range: the file has {}",
                            set_bases.len()
                        );
                        bail!(AssetError::new(&set.file, message));
                    }
                },
                i => match overrides.get(i as usize) {
                    Some(&m) => (m, own_base),
                    None => {
                        let message = format!(
                            "instance {index}: material {i} is out of range: the [[instances]] entry of {} lists {} \
                             materials",
                            scene.origin,
                            overrides.len()
                        );
                        bail!(AssetError::new(&set.file, message));
                    }
                },
            };
            let info = file.info.get(index).copied().unwrap_or(set.info);
            let settings = GpuObjectSettings::new(set.shadow_terminator, set.holdout, info);
            if self.place_with_base(mesh_index, &r.object_to_world(), material, base, (settings, info.color))
                && let Some(motion) = file.motion_of(index)
            {
                self.set_moving(mesh_index, &motion);
            }
        }
        Ok(())
    }

    /// Appends a block of materials per material set of `file` (each slot showing the
    /// asset material its set names, the slots past the set's its own), and returns
    /// each block's first index in the scene's material table.
    fn material_set_blocks(&mut self, file: &Path, sets: &MaterialSets, mesh_index: usize) -> Result<Vec<u32>> {
        let mesh = &self.meshes[mesh_index];
        let own = &mesh.materials;
        if sets.slot_count() as usize > own.len() {
            let message = format!(
                "its material sets have {} slots but the asset {} has {} materials",
                sets.slot_count(),
                mesh.path.display(),
                own.len()
            );
            bail!(AssetError::new(file, message));
        }
        let (texture_base, material_base) = (self.slots[mesh_index].texture_base, self.slots[mesh_index].material_base);
        let mut bases = Vec::with_capacity(sets.len());
        for k in 0..sets.len() as u32 {
            let indices = sets.get(k).unwrap_or_default();
            if let Some((slot, &m)) = indices.iter().enumerate().find(|(_, m)| **m as usize >= own.len()) {
                let message = format!(
                    "material set {k}, slot {slot}: material {m} is out of range: the asset {} has {} materials",
                    mesh.path.display(),
                    own.len()
                );
                bail!(AssetError::new(file, message));
            }
            bases.push((self.material_count + self.set_materials.len()) as u32);
            let shown = (0..own.len()).map(|j| indices.get(j).map_or(j, |&m| m as usize));
            self.set_materials.extend(shown.map(|m| with_bases(&own[m].1, texture_base, material_base)));
        }
        Ok(bases)
    }
}

/// An instance's object-to-world matrix, derived in f64 from the world-to-object one
/// that the GPU record keeps.
pub fn object_to_world(instance: &GpuInstance) -> DMat4 {
    let [r0, r1, r2] = instance.world_to_object.map(|r| r.map(f64::from));
    DMat4::from_cols_array_2d(&[r0, r1, r2, [0.0, 0.0, 0.0, 1.0]]).transpose().inverse()
}

fn affine_rows(m: &Mat4) -> [[f32; 4]; 3] {
    [m.row(0).to_array(), m.row(1).to_array(), m.row(2).to_array()]
}

pub(super) fn transformed_box(m: &Mat4, lo: Vec3, hi: Vec3) -> Aabb {
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
