//! The rt material: weights of the lobes plus the optical constants they need.

use serde::Deserialize;

/// A material as the scene file (contract 3) and the asset importers describe it.
/// Every field has a default, and the defaults give a white Lambertian diffuser.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Material {
    pub base_color: [f32; 3],
    pub diffuse: f32,
    pub specular: f32,
    pub reflection: f32,
    pub transmission: f32,
    pub ior: f32,
    pub roughness: f32,
    /// The seed renderer's Phong-like exponent; mapped to `roughness` when given.
    pub hardness: Option<f32>,
    pub emission: [f32; 3],
    pub absorption: [f32; 3],
    pub volume_emission: [f32; 3],
}

impl Default for Material {
    fn default() -> Self {
        Self {
            base_color: [1.0; 3],
            diffuse: 1.0,
            specular: 0.0,
            reflection: 0.0,
            transmission: 0.0,
            ior: 1.5,
            roughness: 0.0,
            hardness: None,
            emission: [0.0; 3],
            absorption: [0.0; 3],
            volume_emission: [0.0; 3],
        }
    }
}

impl Material {
    pub fn is_emissive(&self) -> bool {
        self.emission.iter().any(|&e| e > 0.0)
    }
}
