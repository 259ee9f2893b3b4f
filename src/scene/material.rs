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
    /// Principled's Diffuse Roughness (the Diffuse BSDF's Roughness): the `diffuse` lobe is
    /// Cycles' energy-preserving Oren-Nayar of this roughness (Fujii's model with OpenPBR's
    /// multiple-scattering term); 0: Lambertian.
    pub diffuse_roughness: f32,
    /// Principled's Specular Tint: the F82 tint of the `reflection` metal and a tint of the
    /// dielectric coating's F0.
    pub specular_tint: [f32; 3],
    /// Principled's Specular IOR Level: above 0, the `diffuse` lobe lies under a dielectric
    /// coating of index `ior` whose F0 is scaled by 2 × this (0.5: the physical F0), and
    /// the diffuse keeps what the coating does not reflect. 0: no coating.
    pub specular_ior_level: f32,
    /// Principled's Coat: the weight of a dielectric GGX layer over every other lobe, its
    /// roughness (perceptual), index, and the tint of the light that crosses it (at
    /// normal incidence; Beer's law along the refracted view).
    pub coat: f32,
    pub coat_roughness: f32,
    pub coat_ior: f32,
    pub coat_tint: [f32; 3],
    /// Principled's Sheen: the weight of Cycles' microfiber sheen layer over every other lobe
    /// (the coat included), its roughness and its colour.
    pub sheen: f32,
    pub sheen_roughness: f32,
    pub sheen_tint: [f32; 3],
    /// Principled's Anisotropic and Anisotropic Rotation: the rough lobes' GGX is stretched
    /// along the surface's tangent (α / aspect along it, α × aspect across it, aspect =
    /// √(1 − 0.9 × anisotropy)), the tangent turned about the normal by rotation × 360°.
    pub anisotropy: f32,
    pub anisotropy_rotation: f32,
    /// The tangent that `anisotropy` stretches along: Cycles' Tangent node linked into the
    /// Principled BSDF's Tangent input, radial about an axis or a uv map's.
    pub tangent: Tangent,
    /// Principled's Thin Film Thickness (nm; 0: no film) and Thin Film IOR: a film on the
    /// specular, metal and glass lobes whose interference colours their Fresnel reflectance
    /// (Belcour & Barla 2017, as Cycles 5.0 renders it).
    pub thin_film_thickness: f32,
    pub thin_film_ior: f32,
    /// How much of the film there is (glTF's `iridescenceFactor`; Blender's film is all
    /// there, 1): the lobes' Fresnel is the film's and the bare one mixed by it.
    pub thin_film_weight: f32,
    /// Cycles' Bump Map Correction (Blender's material setting, on by default): on a
    /// smooth-shaded surface, the glossy, metal, glass and coat lobes take their normal
    /// tilted just enough that the mirror direction of the view stays above the surface,
    /// and light below the interpolated normal does not reach them.
    pub bump_map_correction: bool,
    /// The seed renderer's Phong-like exponent; mapped to `roughness` when given.
    pub hardness: Option<f32>,
    pub emission: [f32; 3],
    pub absorption: [f32; 3],
    pub volume_emission: [f32; 3],
    /// Image textures, from the asset importers (scene files give none).
    #[serde(skip)]
    pub textures: MaterialTextures,
}

/// Which tangent the anisotropic lobes follow, in Blender's axes (rt's Y is Blender's Z).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Tangent {
    /// Circles about the object's Z axis (rt's Y), through its origin: what Cycles uses
    /// when the Tangent input is unlinked.
    #[default]
    RadialZ,
    RadialX,
    RadialY,
    /// The MikkTSpace tangent of the mesh's first uv set (along increasing u).
    Uv,
}

/// A material's image textures, as indices into its asset's texture list, and the
/// factors that go with them (glTF's metallic-roughness model).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialTextures {
    /// RGB multiplies `base_color`; A multiplies `base_alpha` for cut-outs.
    pub base_color: Option<u32>,
    /// G × `roughness` is the roughness, B × `metallic` the metal fraction. With it, the
    /// lobe weights are those of the non-metal part (as if `metallic` were 0).
    pub metallic_roughness: Option<u32>,
    /// RGB multiplies `emission`.
    pub emission: Option<u32>,
    /// glTF's `metallicFactor`, used with `metallic_roughness` only.
    pub metallic: f32,
    /// glTF's `baseColorFactor` alpha.
    pub base_alpha: f32,
    /// glTF `alphaMode` MASK's `alphaCutoff`: texels whose alpha is below it are not
    /// there at all, for every ray. 0: opaque.
    pub alpha_cutoff: f32,
    /// glTF `alphaMode` BLEND: the opacity is the probability that a ray meets the
    /// surface (stochastic transparency), for every ray; `alpha_cutoff` is then unused.
    pub alpha_blend: bool,
    /// A tangent-space normal map (glTF `normalTexture`, linear RGB: xyz = 2·RGB − 1).
    pub normal: Option<u32>,
    /// glTF's `normalTexture.scale`: multiplies the map's x and y.
    pub normal_scale: f32,
    /// Which texture slots read the mesh's second uv set (glTF `texCoord` 1): bit i for
    /// slot i of [`Self::indices_mut`] (base colour, metallic-roughness, emission, normal,
    /// then the layers' nine); the others read the first. A normal map's tangents are of
    /// the set it reads.
    pub second_uv_set: u32,
    /// The layered lobes' textures: [`LayerTextures`].
    pub layers: LayerTextures,
    /// The film's thickness (nm) where its thickness texture reads 0 (glTF's
    /// `iridescenceThicknessMinimum`), used with `layers.thin_film_thickness` only.
    pub thin_film_minimum: f32,
}

/// Textures of the coat, sheen, anisotropy, specular tint, diffuse roughness and thin film
/// thickness (Principled's sockets of those names), each an index into the asset's textures.
/// Factors multiply the texels, as glTF's do (the film's thickness is a range instead).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LayerTextures {
    /// R × `coat` (glTF's `clearcoatTexture`).
    pub coat: Option<u32>,
    /// G × `coat_roughness` (glTF's `clearcoatRoughnessTexture`).
    pub coat_roughness: Option<u32>,
    /// RGB (colour) × `coat_tint`.
    pub coat_tint: Option<u32>,
    /// R × `sheen`, G × `sheen_roughness`.
    pub sheen: Option<u32>,
    /// RGB (colour) × `sheen_tint`.
    pub sheen_tint: Option<u32>,
    /// R × `anisotropy`; G + `anisotropy_rotation` is the rotation (a turn is 1).
    pub anisotropy: Option<u32>,
    /// RGB (colour) × `specular_tint` (glTF's `specularColorTexture`).
    pub specular_tint: Option<u32>,
    /// R × `diffuse_roughness` (rt's `extras.rt_diffuse_roughness_texture`).
    pub diffuse_roughness: Option<u32>,
    /// G: the film's thickness, from `MaterialTextures::thin_film_minimum` at 0 to
    /// `thin_film_thickness` at 1 (glTF's `iridescenceThicknessTexture`).
    pub thin_film_thickness: Option<u32>,
}

impl LayerTextures {
    pub fn any(&self) -> bool {
        self.slots().iter().any(Option::is_some)
    }

    /// The slots, in the order of [`MaterialTextures::indices_mut`] after its first four.
    pub fn slots(&self) -> [Option<u32>; 9] {
        [
            self.coat,
            self.coat_roughness,
            self.coat_tint,
            self.sheen,
            self.sheen_tint,
            self.anisotropy,
            self.specular_tint,
            self.diffuse_roughness,
            self.thin_film_thickness,
        ]
    }

    /// The textures of `slots`, in the order [`Self::slots`] gives them.
    pub fn from_slots(slots: [Option<u32>; 9]) -> Self {
        let [
            coat,
            coat_roughness,
            coat_tint,
            sheen,
            sheen_tint,
            anisotropy,
            specular_tint,
            diffuse_roughness,
            thin_film_thickness,
        ] = slots;
        Self {
            coat,
            coat_roughness,
            coat_tint,
            sheen,
            sheen_tint,
            anisotropy,
            specular_tint,
            diffuse_roughness,
            thin_film_thickness,
        }
    }
}

/// One of the two sets of texture coordinates a mesh may carry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UvSet {
    First = 0,
    Second = 1,
}

/// The texture slots of a material: indices into [`MaterialTextures::indices_mut`] and
/// bits of its `second_uv_set` (the importers and `shaders/texture.wgsl` number them so).
pub mod slots {
    pub const BASE_COLOR: usize = 0;
    pub const METALLIC_ROUGHNESS: usize = 1;
    pub const EMISSION: usize = 2;
    pub const NORMAL: usize = 3;
    pub const COAT: usize = 4;
    pub const COAT_ROUGHNESS: usize = 5;
    pub const COAT_TINT: usize = 6;
    pub const SHEEN: usize = 7;
    pub const SHEEN_TINT: usize = 8;
    pub const ANISOTROPY: usize = 9;
    pub const SPECULAR_TINT: usize = 10;
    pub const DIFFUSE_ROUGHNESS: usize = 11;
    pub const THIN_FILM_THICKNESS: usize = 12;
    pub const COUNT: usize = 13;
}

impl Default for MaterialTextures {
    fn default() -> Self {
        Self {
            base_color: None,
            metallic_roughness: None,
            emission: None,
            metallic: 0.0,
            base_alpha: 1.0,
            alpha_cutoff: 0.0,
            alpha_blend: false,
            normal: None,
            normal_scale: 1.0,
            second_uv_set: 0,
            layers: LayerTextures::default(),
            thin_film_minimum: 0.0,
        }
    }
}

impl MaterialTextures {
    pub fn any(&self) -> bool {
        self.base_color.is_some()
            || self.metallic_roughness.is_some()
            || self.emission.is_some()
            || self.normal.is_some()
            || self.layers.any()
    }

    /// The indices, for offsetting into a scene-wide texture list, in the order of
    /// [`slots`]; slot i's uv set is bit i of `second_uv_set` (`UV1_*` in
    /// `shaders/texture.wgsl`).
    pub fn indices_mut(&mut self) -> [&mut Option<u32>; slots::COUNT] {
        let l = &mut self.layers;
        [
            &mut self.base_color,
            &mut self.metallic_roughness,
            &mut self.emission,
            &mut self.normal,
            &mut l.coat,
            &mut l.coat_roughness,
            &mut l.coat_tint,
            &mut l.sheen,
            &mut l.sheen_tint,
            &mut l.anisotropy,
            &mut l.specular_tint,
            &mut l.diffuse_roughness,
            &mut l.thin_film_thickness,
        ]
    }

    /// Whether texture slot `slot` (an index into [`Self::indices_mut`]) reads the second uv set.
    pub fn reads_second_uv_set(&self, slot: usize) -> bool {
        self.second_uv_set & (1 << slot) != 0
    }

    /// The uv set the normal map reads, and so the tangents it is in.
    pub fn normal_uv_set(&self) -> UvSet {
        if self.reads_second_uv_set(slots::NORMAL) { UvSet::Second } else { UvSet::First }
    }

    /// Some texture reads the second uv set.
    pub fn uses_second_uv_set(&self) -> bool {
        self.second_uv_set != 0
    }

    /// Some of the surface may be missing: a cut-out or a blend.
    pub fn has_alpha(&self) -> bool {
        self.alpha_cutoff > 0.0 || self.alpha_blend
    }
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
            diffuse_roughness: 0.0,
            specular_tint: [1.0; 3],
            specular_ior_level: 0.0,
            coat: 0.0,
            coat_roughness: 0.03,
            coat_ior: 1.5,
            coat_tint: [1.0; 3],
            sheen: 0.0,
            sheen_roughness: 0.5,
            sheen_tint: [1.0; 3],
            anisotropy: 0.0,
            anisotropy_rotation: 0.0,
            tangent: Tangent::RadialZ,
            thin_film_thickness: 0.0,
            thin_film_ior: 1.33,
            thin_film_weight: 1.0,
            bump_map_correction: true,
            hardness: None,
            emission: [0.0; 3],
            absorption: [0.0; 3],
            volume_emission: [0.0; 3],
            textures: MaterialTextures::default(),
        }
    }
}

impl Material {
    pub fn is_emissive(&self) -> bool {
        self.emission.iter().any(|&e| e > 0.0)
    }

    /// Its shading reads the mesh's tangents: a normal map, or anisotropy along the uv map.
    pub fn reads_tangents(&self) -> bool {
        self.textures.normal.is_some() || self.reads_uv_tangents()
    }

    /// Its anisotropic lobes follow the uv map's tangents.
    pub fn reads_uv_tangents(&self) -> bool {
        self.anisotropy > 0.0 && self.tangent == Tangent::Uv
    }

    /// Absorbs or emits inside (only meaningful with `transmission`).
    pub fn has_medium(&self) -> bool {
        self.absorption.iter().chain(&self.volume_emission).any(|&v| v > 0.0)
    }

    /// The GGX α of the rough lobes. `roughness` is perceptual (α = roughness², as in
    /// Blender and glTF). The seed's Phong-like `hardness` n, when given, wins and maps
    /// through the Beckmann–Phong correspondence α = √(2 / (n + 2)) (Walter et al. 2007).
    pub fn alpha(&self) -> f32 {
        match self.hardness {
            Some(n) => (2.0 / (n + 2.0)).sqrt(),
            None => self.roughness * self.roughness,
        }
    }

    /// Lobe weights (diffuse, specular, reflection, transmission), scaled down
    /// if they sum above 1 so that the material never reflects more than it receives.
    pub fn lobe_weights(&self) -> [f32; 4] {
        let w = [self.diffuse, self.specular, self.reflection, self.transmission];
        let sum: f32 = w.iter().sum();
        if sum > 1.0 { w.map(|v| v / sum) } else { w }
    }
}

impl Material {
    /// The dielectric coating of the diffuse lobe, as Cycles' Principled BSDF sets up its
    /// specular layer: the index whose real Fresnel curve it follows and its F0 (before
    /// `specular_tint`), or `None` for no coating.
    /// A thin film reflects even over a coating of index 1 (Specular IOR Level 0), as in Cycles.
    pub fn dielectric_coating(&self) -> Option<(f32, f32)> {
        let film = self.has_thin_film();
        if (self.specular_ior_level <= 0.0 && !film) || self.diffuse <= 0.0 {
            return None;
        }
        let f0 = f0_from_ior(self.ior) * 2.0 * self.specular_ior_level.max(0.0);
        // An F0 of 1 or more would be an infinite index: clamp just below.
        let f0 = f0.min(0.9999);
        let eta = ior_from_f0(f0);
        (eta > 1.0 || film).then_some((eta, f0))
    }

    /// Whether the diffuse lobe is Oren-Nayar rather than Lambertian.
    pub fn has_rough_diffuse(&self) -> bool {
        self.diffuse > 0.0 && self.diffuse_roughness > 0.0
    }

    /// Whether the thin film is there: Cycles ignores films of 0.1 nm and less
    /// (`THINFILM_THICKNESS_CUTOFF`).
    pub fn has_thin_film(&self) -> bool {
        self.thin_film_thickness > THIN_FILM_CUTOFF && self.thin_film_weight > 0.0
    }
}

/// Thickness (nm) at and below which a film is not there (`THIN_FILM_CUTOFF` in `shaders/thin_film.wgsl`).
pub const THIN_FILM_CUTOFF: f32 = 0.1;

/// Reflectance at normal incidence of an interface of relative index `ior`.
pub fn f0_from_ior(ior: f32) -> f32 {
    ((ior - 1.0) / (ior + 1.0)).powi(2)
}

/// The relative index (above 1) whose reflectance at normal incidence is `f0`.
pub fn ior_from_f0(f0: f32) -> f32 {
    let r = f0.clamp(0.0, 0.9999).sqrt();
    (1.0 + r) / (1.0 - r)
}

/// Luminance of linear Rec. 709 RGB.
pub fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

#[cfg(test)]
#[path = "material_tests.rs"]
mod tests;
