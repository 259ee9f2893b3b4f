//! Materials as a cache file stores them: every field of [`Material`], as
//! written, so that loading a cache gives exactly what importing the source gives.

use crate::scene::lobe::{MAX_PARAMS, ModuleLobe};
use crate::scene::{LAYER_COUNT, LayerTextures, Material, MaterialTextures, Tangent};

/// A texture slot left empty.
pub const NO_TEXTURE: u32 = u32::MAX;

fn slot(index: Option<u32>) -> u32 {
    index.unwrap_or(NO_TEXTURE)
}

fn unslot(index: u32) -> Option<u32> {
    (index != NO_TEXTURE).then_some(index)
}
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
    pub specular_ior_level: f32,
    /// Texture indices into the asset's textures, or [`NO_TEXTURE`].
    pub base_color_texture: u32,
    pub metallic_roughness_texture: u32,
    pub emission_texture: u32,
    pub metallic: f32,
    pub base_alpha: f32,
    pub alpha_cutoff: f32,
    /// 1: glTF `alphaMode` BLEND.
    pub alpha_blend: u32,
    pub normal_texture: u32,
    pub normal_scale: f32,
    pub specular_tint: [f32; 3],
    pub coat: f32,
    pub coat_roughness: f32,
    pub coat_ior: f32,
    pub coat_tint: [f32; 3],
    pub sheen: f32,
    pub sheen_roughness: f32,
    pub sheen_tint: [f32; 3],
    pub anisotropy: f32,
    pub anisotropy_rotation: f32,
    /// `MaterialTextures::second_uv_set`.
    pub second_uv_set: u32,
    pub thin_film_thickness: f32,
    pub thin_film_ior: f32,
    /// `LayerTextures`, in the order of its `slots`.
    pub layer_textures: [u32; LAYER_COUNT],
    /// `Tangent`: 0 radial Z, 1 radial X, 2 radial Y, 3 the uv map's.
    pub tangent: u32,
    pub diffuse_roughness: f32,
    pub thin_film_weight: f32,
    /// 1: Bump Map Correction.
    pub bump_map_correction: u32,
    /// `MaterialTextures::thin_film_minimum`.
    pub thin_film_minimum: f32,
    /// `MaterialTextures::transmission`.
    pub transmission_factor: f32,
    /// 1: `MaterialTextures::anisotropy_directions`.
    pub anisotropy_directions: u32,
    /// `MaterialTextures::coat_normal` and its scale (from version 11 on).
    pub coat_normal_texture: u32,
    pub coat_normal_scale: f32,
    /// `MaterialTextures::ior_minimum`.
    pub ior_minimum: [f32; 3],
    /// `Material::mix_material`, or [`NO_TEXTURE`] (version 12 on).
    pub mix_material: u32,
    /// `Material::holdout` (version 13 on).
    pub holdout: f32,
    /// `Material::lobe`: its module's number (`ModuleLobe::number`, 0: none) and its
    /// parameters (version 16 on).
    pub lobe_module: u32,
    pub lobe_params: [f32; MAX_PARAMS],
    /// `Material::closure_weight` (version 16 on).
    pub closure_weight: f32,
}

const TANGENTS: [Tangent; 4] = [Tangent::RadialZ, Tangent::RadialX, Tangent::RadialY, Tangent::Uv];

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
            specular_ior_level: m.specular_ior_level,
            base_color_texture: slot(m.textures.base_color),
            metallic_roughness_texture: slot(m.textures.metallic_roughness),
            emission_texture: slot(m.textures.emission),
            metallic: m.textures.metallic,
            base_alpha: m.textures.base_alpha,
            alpha_cutoff: m.textures.alpha_cutoff,
            alpha_blend: u32::from(m.textures.alpha_blend),
            normal_texture: slot(m.textures.normal),
            normal_scale: m.textures.normal_scale,
            specular_tint: m.specular_tint,
            coat: m.coat,
            coat_roughness: m.coat_roughness,
            coat_ior: m.coat_ior,
            coat_tint: m.coat_tint,
            sheen: m.sheen,
            sheen_roughness: m.sheen_roughness,
            sheen_tint: m.sheen_tint,
            anisotropy: m.anisotropy,
            anisotropy_rotation: m.anisotropy_rotation,
            second_uv_set: m.textures.second_uv_set,
            thin_film_thickness: m.thin_film_thickness,
            thin_film_ior: m.thin_film_ior,
            layer_textures: m.textures.layers.slots().map(slot),
            tangent: TANGENTS.iter().position(|&t| t == m.tangent).unwrap_or(0) as u32,
            diffuse_roughness: m.diffuse_roughness,
            thin_film_weight: m.thin_film_weight,
            bump_map_correction: u32::from(m.bump_map_correction),
            thin_film_minimum: m.textures.thin_film_minimum,
            transmission_factor: m.textures.transmission,
            anisotropy_directions: u32::from(m.textures.anisotropy_directions),
            coat_normal_texture: slot(m.textures.coat_normal),
            coat_normal_scale: m.textures.coat_normal_scale,
            ior_minimum: m.textures.ior_minimum,
            mix_material: slot(m.mix_material),
            holdout: m.holdout,
            lobe_module: ModuleLobe::number(m.lobe.as_ref()),
            lobe_params: m.lobe.map_or([0.0; MAX_PARAMS], |l| l.params),
            closure_weight: m.closure_weight,
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
            diffuse_roughness: m.diffuse_roughness,
            specular_tint: m.specular_tint,
            specular_ior_level: m.specular_ior_level,
            coat: m.coat,
            coat_roughness: m.coat_roughness,
            coat_ior: m.coat_ior,
            coat_tint: m.coat_tint,
            sheen: m.sheen,
            sheen_roughness: m.sheen_roughness,
            sheen_tint: m.sheen_tint,
            anisotropy: m.anisotropy,
            anisotropy_rotation: m.anisotropy_rotation,
            tangent: TANGENTS.get(m.tangent as usize).copied().unwrap_or_default(),
            thin_film_thickness: m.thin_film_thickness,
            thin_film_ior: m.thin_film_ior,
            thin_film_weight: m.thin_film_weight,
            bump_map_correction: m.bump_map_correction != 0,
            hardness: (m.hardness > 0.0).then_some(m.hardness),
            emission: m.emission,
            absorption: m.absorption,
            volume_emission: m.volume_emission,
            textures: MaterialTextures {
                base_color: unslot(m.base_color_texture),
                metallic_roughness: unslot(m.metallic_roughness_texture),
                emission: unslot(m.emission_texture),
                metallic: m.metallic,
                base_alpha: m.base_alpha,
                alpha_cutoff: m.alpha_cutoff,
                alpha_blend: m.alpha_blend != 0,
                normal: unslot(m.normal_texture),
                normal_scale: m.normal_scale,
                coat_normal: unslot(m.coat_normal_texture),
                coat_normal_scale: m.coat_normal_scale,
                ior_minimum: m.ior_minimum,
                second_uv_set: m.second_uv_set,
                layers: LayerTextures::from_slots(m.layer_textures.map(unslot)),
                thin_film_minimum: m.thin_film_minimum,
                transmission: m.transmission_factor,
                anisotropy_directions: m.anisotropy_directions != 0,
            },
            node_program: Vec::new(),
            mix_material: unslot(m.mix_material),
            holdout: m.holdout,
            lobe: ModuleLobe::from_number(m.lobe_module, m.lobe_params),
            closure_weight: m.closure_weight,
        }
    }
}

impl CachedMaterial {
    pub fn all_finite(&self) -> bool {
        let vectors = [
            self.base_color,
            self.emission,
            self.absorption,
            self.volume_emission,
            self.specular_tint,
            self.coat_tint,
            self.sheen_tint,
            self.ior_minimum,
        ];
        let lobe = self.lobe_params;
        let scalars = [
            self.diffuse,
            self.specular,
            self.reflection,
            self.transmission,
            self.ior,
            self.roughness,
            self.specular_ior_level,
            self.coat,
            self.coat_roughness,
            self.coat_ior,
            self.sheen,
            self.sheen_roughness,
            self.anisotropy,
            self.anisotropy_rotation,
            self.thin_film_thickness,
            self.thin_film_ior,
            self.thin_film_weight,
            self.thin_film_minimum,
            self.transmission_factor,
            self.diffuse_roughness,
            self.hardness,
            self.metallic,
            self.base_alpha,
            self.alpha_cutoff,
            self.normal_scale,
            self.coat_normal_scale,
            self.closure_weight,
        ];
        vectors.into_iter().flatten().chain(scalars).chain(lobe).all(f32::is_finite)
    }

    /// Whether `tangent` names a [`Tangent`].
    pub fn tangent_known(&self) -> bool {
        (self.tangent as usize) < TANGENTS.len()
    }

    /// Whether `lobe_module` names one of this build's lobe modules, or none.
    pub fn lobe_known(&self) -> bool {
        self.lobe_module == 0 || ModuleLobe::from_number(self.lobe_module, self.lobe_params).is_some()
    }

    /// The texture slots that are filled.
    pub fn textures(&self) -> impl Iterator<Item = u32> {
        [self.base_color_texture, self.metallic_roughness_texture, self.emission_texture, self.normal_texture]
            .into_iter()
            .chain(self.layer_textures)
            .chain([self.coat_normal_texture])
            .filter(|&t| t != NO_TEXTURE)
    }
}
