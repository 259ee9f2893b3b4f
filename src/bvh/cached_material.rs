//! Materials as a cache file stores them: every field of [`Material`], as
//! written, so that loading a cache gives exactly what importing the source gives.

use crate::scene::Material;
use bytemuck::{Pod, Zeroable};

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct CachedMaterial {
    pub base_color: [f32; 3],
    pub diffuse: f32,
    pub specular: f32,
    pub reflection: f32,
    pub transmission: f32,
    pub ior: f32,
    pub roughness: f32,
    /// 0 when the material gives none (a hardness must be positive).
    pub hardness: f32,
    pub emission: [f32; 3],
    pub absorption: [f32; 3],
    pub volume_emission: [f32; 3],
    pub _pad: f32,
}

impl From<&Material> for CachedMaterial {
    fn from(m: &Material) -> Self {
        Self {
            base_color: m.base_color,
            diffuse: m.diffuse,
            specular: m.specular,
            reflection: m.reflection,
            transmission: m.transmission,
            ior: m.ior,
            roughness: m.roughness,
            hardness: m.hardness.unwrap_or(0.0),
            emission: m.emission,
            absorption: m.absorption,
            volume_emission: m.volume_emission,
            _pad: 0.0,
        }
    }
}

impl From<&CachedMaterial> for Material {
    fn from(m: &CachedMaterial) -> Self {
        Self {
            base_color: m.base_color,
            diffuse: m.diffuse,
            specular: m.specular,
            reflection: m.reflection,
            transmission: m.transmission,
            ior: m.ior,
            roughness: m.roughness,
            hardness: (m.hardness > 0.0).then_some(m.hardness),
            emission: m.emission,
            absorption: m.absorption,
            volume_emission: m.volume_emission,
        }
    }
}

impl CachedMaterial {
    pub fn all_finite(&self) -> bool {
        let vectors = [self.base_color, self.emission, self.absorption, self.volume_emission];
        let scalars =
            [self.diffuse, self.specular, self.reflection, self.transmission, self.ior, self.roughness, self.hardness];
        vectors.into_iter().flatten().chain(scalars).all(f32::is_finite)
    }
}
