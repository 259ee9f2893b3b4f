//! Placing meshes as instances: each one's GPU record, its world box for the top level,
//! and which materials it makes the scene use. Work per instance is constant (a matrix
//! inverse and eight corners), so a million instances of one mesh cost what a million
//! of a triangle do.

use super::pack::LoadedMesh;
use crate::asset::{AssetError, rtinst};
use crate::layout::{GpuInstance, NO_MATERIAL};
use crate::scene::{InstanceSet, Scene};
use anyhow::{Result, bail};
use glam::{DMat4, Mat4, Vec3, Vec3A};
use obvhs::aabb::Aabb;

/// Where a mesh's data sits in the scene's concatenated buffers.
#[derive(Clone, Copy)]
pub(super) struct MeshSlot {
    pub node_offset: u32,
    pub triangle_offset: u32,
    pub material_base: u32,
}

pub(super) struct Placement<'m> {
    meshes: &'m [LoadedMesh],
    slots: &'m [MeshSlot],
    pub instances: Vec<GpuInstance>,
    /// Which mesh each instance places.
    pub instance_mesh: Vec<u32>,
    /// World box of each instance, for the top level.
    pub boxes: Vec<Aabb>,
    /// Whether some instance shows a mesh with its own materials.
    pub own_materials_shown: Vec<bool>,
    /// Whether some instance uses this material as its override.
    pub override_used: Vec<bool>,
}

impl<'m> Placement<'m> {
    pub fn new(meshes: &'m [LoadedMesh], slots: &'m [MeshSlot], material_count: usize) -> Self {
        Self {
            meshes,
            slots,
            instances: Vec::new(),
            instance_mesh: Vec::new(),
            boxes: Vec::new(),
            own_materials_shown: vec![false; meshes.len()],
            override_used: vec![false; material_count],
        }
    }

    /// Places mesh `mesh_index` at `object_to_world` (invertible), with the material
    /// table index `material_override` or `NO_MATERIAL`. Empty meshes place nothing.
    pub fn place(&mut self, mesh_index: usize, object_to_world: &Mat4, material_override: u32) {
        let mesh = &self.meshes[mesh_index];
        if mesh.triangle_count == 0 {
            return;
        }
        if material_override == NO_MATERIAL {
            self.own_materials_shown[mesh_index] = true;
        } else {
            self.override_used[material_override as usize] = true;
        }
        let slot = self.slots[mesh_index];
        self.boxes.push(transformed_box(object_to_world, mesh.bvh.bounds_min, mesh.bvh.bounds_max));
        self.instance_mesh.push(mesh_index as u32);
        self.instances.push(GpuInstance {
            world_to_object: affine_rows(&object_to_world.inverse()),
            node_offset: slot.node_offset,
            triangle_offset: slot.triangle_offset,
            material_base: slot.material_base,
            material_override,
        });
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
        let records = rtinst::read(&set.file)?;
        let overrides: Vec<u32> = set.materials.iter().map(|n| scene_material(n)).collect::<Result<_>>()?;
        self.instances.reserve(records.len());
        self.boxes.reserve(records.len());
        self.instance_mesh.reserve(records.len());
        for (index, r) in records.iter().enumerate() {
            let material = match r.material {
                rtinst::OWN_MATERIALS => NO_MATERIAL,
                i => match overrides.get(i as usize) {
                    Some(&m) => m,
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
            self.place(mesh_index, &r.object_to_world(), material);
        }
        Ok(())
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
