//! The rt material: weights of the lobes plus the optical constants they need.

use super::lobe::ModuleLobe;
use super::material_textures::MaterialTextures;
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
    /// The share of the surface that is Blender's Holdout shader (a Mix Shader's weight of
    /// it; 1: all of it): the camera sees nothing there, and the pixel's alpha loses that
    /// share; any other ray loses it as absorbed. The rest of the material is scaled by
    /// what remains.
    pub holdout: f32,
    /// Image textures, from the asset importers (scene files give none).
    #[serde(skip)]
    pub textures: MaterialTextures,
    /// The compiled shader node graph that drives some of the inputs above at each
    /// shading point (`asset::node_graph`); empty: none.
    #[serde(skip)]
    pub node_program: Vec<u32>,
    /// A Mix Shader whose factor a node graph drives (`node_program`'s `mix_factor`): the
    /// index of the material its factor selects, among the asset's own (the scene's table
    /// once placed). Each shading point is this material or that one, by the factor.
    #[serde(skip)]
    pub mix_material: Option<u32>,
    /// What the material's BSDF is scaled by (its emission is not): an Add Shader's two BSDFs
    /// are each one of a Mix of factor ½ and weight 2. Cycles' closures add up past 1 there.
    pub closure_weight: f32,
    /// A lobe module's BSDF in place of the lobes above (`scene::lobe`: Blender's Toon BSDF,
    /// …), weighted by `base_color`; emission, alpha and holdout stay the material's.
    pub lobe: Option<ModuleLobe>,
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
            holdout: 0.0,
            textures: MaterialTextures::default(),
            node_program: Vec::new(),
            mix_material: None,
            closure_weight: 1.0,
            lobe: None,
        }
    }
}

impl Material {
    pub fn is_emissive(&self) -> bool {
        self.emission.iter().any(|&e| e > 0.0)
    }

    /// Its shading reads the mesh's tangents: a normal map, or anisotropy along the uv map.
    pub fn reads_tangents(&self) -> bool {
        self.textures.has_normal_map() || self.reads_uv_tangents()
    }

    /// Its coat is shaded with a normal of its own (Principled's Coat Normal): it has a coat
    /// and a normal map that the coat does not share (see `MaterialTextures::coat_normal_differs`).
    pub fn has_own_coat_normal(&self) -> bool {
        self.coat > 0.0 && self.textures.coat_normal_differs()
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

    /// Whether some of the surface refracts: by its weight, or by its transmission texture.
    pub fn may_transmit(&self) -> bool {
        self.transmission > 0.0 || (self.textures.layers.transmission.is_some() && self.textures.transmission > 0.0)
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

/// The sRGB code `c` decoded to linear, as Cycles' `color_srgb_to_linear` decodes it
/// (codes above 1 follow the same power; below 0, nothing).
pub fn srgb_decode(c: f32) -> f32 {
    if c <= 0.04045 { c.max(0.0) / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// Linear `c` (clamped to [0, 1]) encoded as an sRGB code: what a display and an 8-bit
/// image hold.
pub fn srgb_encode(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 }
}

/// Luminance of linear Rec. 709 RGB.
pub fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}
