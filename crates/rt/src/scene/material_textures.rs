//! A material's image textures: which texture feeds each of its slots, and the glTF
//! factors that go with them.

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
    /// The coat's own tangent-space normal map (Principled's Coat Normal, glTF's
    /// `clearcoatNormalTexture`). Without one the coat takes the interpolated normal, not
    /// `normal`'s: a normal map on the base does not bend the coat.
    pub coat_normal: Option<u32>,
    /// `clearcoatNormalTexture.scale`: multiplies the coat map's x and y.
    pub coat_normal_scale: f32,
    /// Which texture slots read the mesh's second uv set (glTF `texCoord` 1): bit i for
    /// slot i of [`Self::indices_mut`] (base colour, metallic-roughness, emission, normal,
    /// then the layers' twelve, then the coat's normal); the others read the first. A normal
    /// map's tangents are of the set it reads (a triangle carries one set: the base map's,
    /// or without one the coat map's).
    pub second_uv_set: u32,
    /// The layered lobes' textures: [`LayerTextures`].
    pub layers: LayerTextures,
    /// The film's thickness (nm) where its thickness texture reads 0 (glTF's
    /// `iridescenceThicknessMinimum`), used with `layers.thin_film_thickness` only.
    pub thin_film_minimum: f32,
    /// glTF's `transmissionFactor`, used with `layers.transmission` only. With that texture,
    /// the lobe weights are those of the part that does not transmit (as if the factor were
    /// 0), and the shader moves `factor × R` of the diffuse and its coating to the glass.
    pub transmission: f32,
    /// `layers.anisotropy` is glTF's `anisotropyTexture`: RG a direction (2·RG − 1) in the
    /// tangent frame that turns the rotation, B × `anisotropy` (else rt's: R × `anisotropy`,
    /// G + the rotation).
    pub anisotropy_directions: bool,
    /// The IOR, the coat's and the film's where `layers.ior` reads 0 (rt's
    /// `extras.rt_ior_minimum`, `rt_coat_ior_minimum`, `rt_thin_film_ior_minimum`; a
    /// channel the texture does not drive has the material's own).
    pub ior_minimum: [f32; 3],
}

/// Textures of the coat, sheen, anisotropy, specular tint, diffuse roughness, thin film
/// thickness, transmission, specular IOR level and the indices (Principled's sockets of those names),
/// each an index into the asset's textures. Factors multiply the texels, as glTF's do (the
/// film's thickness is a range instead).
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
    /// R × `MaterialTextures::transmission` is the transmission weight (glTF's
    /// `transmissionTexture`).
    pub transmission: Option<u32>,
    /// A × `specular_ior_level` (glTF's `specularTexture`, whose alpha is its factor's).
    pub specular_level: Option<u32>,
    /// The indices: R the IOR, G the coat's, B the film's, each from its
    /// `MaterialTextures::ior_minimum` at 0 to the material's own at 1 (rt's
    /// `extras.rt_ior_texture`).
    pub ior: Option<u32>,
}

impl LayerTextures {
    pub fn any(&self) -> bool {
        self.slots().iter().any(Option::is_some)
    }

    /// The slots, in the order of [`MaterialTextures::indices_mut`] after its first four.
    pub fn slots(&self) -> [Option<u32>; LAYER_COUNT] {
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
            self.transmission,
            self.specular_level,
            self.ior,
        ]
    }

    /// The textures of `slots`, in the order [`Self::slots`] gives them.
    pub fn from_slots(slots: [Option<u32>; LAYER_COUNT]) -> Self {
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
            transmission,
            specular_level,
            ior,
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
            transmission,
            specular_level,
            ior,
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
    pub const TRANSMISSION: usize = 13;
    pub const SPECULAR_LEVEL: usize = 14;
    pub const IOR: usize = 15;
    pub const COAT_NORMAL: usize = 16;
    pub const COUNT: usize = 17;
}

/// How many of the slots are [`LayerTextures`]'s: those from the coat's to the specular level's.
pub const LAYER_COUNT: usize = slots::COAT_NORMAL - slots::COAT;

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
            coat_normal: None,
            coat_normal_scale: 1.0,
            second_uv_set: 0,
            layers: LayerTextures::default(),
            thin_film_minimum: 0.0,
            transmission: 0.0,
            anisotropy_directions: false,
            ior_minimum: [1.5, 1.5, 1.33],
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
            || self.coat_normal.is_some()
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
            &mut l.transmission,
            &mut l.specular_level,
            &mut l.ior,
            &mut self.coat_normal,
        ]
    }

    /// Whether texture slot `slot` (an index into [`Self::indices_mut`]) reads the second uv set.
    pub fn reads_second_uv_set(&self, slot: usize) -> bool {
        self.second_uv_set & (1 << slot) != 0
    }

    /// The uv set whose tangents the triangles carry: the normal map's, or without one the
    /// coat's normal map's.
    pub fn normal_uv_set(&self) -> UvSet {
        let slot = if self.normal.is_none() && self.coat_normal.is_some() { slots::COAT_NORMAL } else { slots::NORMAL };
        if self.reads_second_uv_set(slot) { UvSet::Second } else { UvSet::First }
    }

    /// Some normal map, the base's or the coat's.
    pub fn has_normal_map(&self) -> bool {
        self.normal.is_some() || self.coat_normal.is_some()
    }

    /// The coat's normal is not the base's: the base has a normal map that the coat does not
    /// share, or the coat has its own (the same map, scale and uv set as the base's is shared).
    pub fn coat_normal_differs(&self) -> bool {
        let same_set = self.reads_second_uv_set(slots::NORMAL) == self.reads_second_uv_set(slots::COAT_NORMAL);
        self.has_normal_map()
            && !(self.coat_normal == self.normal && self.coat_normal_scale == self.normal_scale && same_set)
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

#[cfg(test)]
#[path = "material_textures_tests.rs"]
mod tests;
