//! The emitter table: every emissive triangle of every placed instance and every
//! emissive sphere, with selection probabilities in proportion to power, for
//! next-event estimation and the light tree.

use super::light_bounds::{sphere_bounds, triangle_bounds};
use super::light_tree::LightBounds;
use crate::layout::*;
use crate::scene::Material;
use std::collections::HashMap;

/// The triangles that can emit, per mesh, to find emitters without visiting every
/// triangle of every instance.
pub(super) struct EmissiveTriangles<'a> {
    /// The range of each mesh's triangles in `triangles`.
    pub mesh_triangles: &'a [std::ops::Range<u32>],
    pub triangles: &'a [GpuTriangle],
    pub materials: &'a [Material],
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
    pub fn table(
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
