//! The layered lobes' textures of a glTF material ([`LayerTextures`]): `KHR_materials_clearcoat`'s
//! `clearcoatTexture` (R) and `clearcoatRoughnessTexture` (G), `KHR_materials_specular`'s
//! `specularColorTexture` and `specularTexture` (A), `KHR_materials_transmission`'s
//! `transmissionTexture` (R), `KHR_materials_iridescence`'s `iridescenceThicknessTexture` (G:
//! the thickness from the extension's minimum to its maximum), and rt's own extras for
//! what glTF has no texture of: `rt_coat_tint_texture` (RGB), `rt_sheen_texture` (R weight,
//! G roughness), `rt_sheen_tint_texture` (RGB), `rt_anisotropy_texture` (R amount, G
//! rotation), `rt_diffuse_roughness_texture` (R) and `rt_ior_texture` (R the IOR, G the
//! coat's, B the film's), each a texture info as glTF writes one
//! (`{"index": i, "texCoord": n}`, with its own `KHR_texture_transform`). Beside them, the
//! coat's own normal map: `clearcoatNormalTexture` (with its `scale`).

use super::gltf_import::{extra, uv_set_bit};
use super::gltf_texture_transform::{TextureUse, of_info, of_json};
use super::gltf_textures::{ColorSpace, Reading, TextureLoader};
use super::material_extras as extras;
use crate::scene::LayerTextures;
use crate::scene::slots::{
    ANISOTROPY, COAT, COAT_NORMAL, COAT_ROUGHNESS, COAT_TINT, DIFFUSE_ROUGHNESS, IOR, SHEEN, SHEEN_TINT,
    SPECULAR_LEVEL, SPECULAR_TINT, THIN_FILM_THICKNESS, TRANSMISSION,
};
use gltf::json::Value;

/// A texture info in raw JSON: its texture's index and how it is read.
fn info(v: &Value, what: &str) -> Result<(usize, TextureUse), String> {
    let index = v
        .get("index")
        .and_then(Value::as_u64)
        .ok_or_else(|| format!("{what}.index must be a texture index, got {v}"))?;
    let tex_coord = match v.get("texCoord") {
        None => 0,
        Some(t) => t.as_u64().ok_or_else(|| format!("{what}.texCoord must be a whole number, got {t}"))?,
    };
    let transform = v.get("extensions").and_then(|e| e.get("KHR_texture_transform"));
    Ok((index as usize, of_json(tex_coord as u32, transform, what)?))
}

/// The texture `index` of `document`, loaded for `what`.
fn texture<'a>(document: &'a gltf::Document, index: usize, what: &str) -> Result<gltf::Texture<'a>, String> {
    document
        .textures()
        .nth(index)
        .ok_or_else(|| format!("{what}: no texture {index} (the file has {})", document.textures().len()))
}

/// The coat's normal map (`KHR_materials_clearcoat.clearcoatNormalTexture`): its texture,
/// its `scale` (glTF's default 1) and the bit of `second_uv_set` it adds.
pub(super) fn coat_normal_texture(
    m: &gltf::Material,
    document: &gltf::Document,
    loader: &mut TextureLoader,
) -> Result<(Option<u32>, f32, u32), String> {
    const WHAT: &str = "KHR_materials_clearcoat.clearcoatNormalTexture";
    let Some(v) = m.extension_value("KHR_materials_clearcoat").and_then(|c| c.get("clearcoatNormalTexture")) else {
        return Ok((None, 1.0, 0));
    };
    let (index, used) = info(v, WHAT)?;
    let scale = match v.get("scale") {
        None => 1.0,
        Some(s) => {
            s.as_f64().filter(|s| s.is_finite()).ok_or_else(|| format!("{WHAT}.scale must be a number, got {s}"))?
                as f32
        }
    };
    let texture = texture(document, index, WHAT)?;
    let bit = uv_set_bit(used.tex_coord, COAT_NORMAL, "clearcoat normal");
    // As the base's normal map: the tangent frame is the uv set's, whatever the transform.
    let loaded = loader
        .load(&texture, ColorSpace::Linear, used.transform)
        .map_err(|e| format!("clearcoat normal texture: {e}"))?;
    Ok((Some(loaded), scale, bit))
}

/// The layer textures of a material, and what goes with them.
pub(super) struct Layers {
    pub textures: LayerTextures,
    /// The bits of `MaterialTextures::second_uv_set` they add.
    pub second_uv_set: u32,
    /// `MaterialTextures::anisotropy_directions`.
    pub anisotropy_directions: bool,
}

/// The layer textures of `m`.
pub(super) fn layer_textures(
    document: &gltf::Document,
    m: &gltf::Material,
    loader: &mut TextureLoader,
) -> Result<Layers, String> {
    let mut second_uv_set = 0;
    let mut load = |raw: Option<(usize, TextureUse)>, reading: Reading, slot: usize, what: &str| {
        let Some((index, used)) = raw else { return Ok(None) };
        let texture = texture(document, index, what)?;
        second_uv_set |= uv_set_bit(used.tex_coord, slot, what);
        loader.load_as(&texture, reading, used.transform).map(Some).map_err(|e| format!("{what} texture: {e}"))
    };
    let (srgb, linear) = (Reading::As(ColorSpace::Srgb), Reading::As(ColorSpace::Linear));
    let clearcoat = m.extension_value("KHR_materials_clearcoat");
    let from_clearcoat = |key: &str| -> Result<Option<(usize, TextureUse)>, String> {
        clearcoat.and_then(|c| c.get(key)).map(|v| info(v, &format!("KHR_materials_clearcoat.{key}"))).transpose()
    };
    let from_extras = |key: &str| -> Result<Option<(usize, TextureUse)>, String> {
        extra::<Value>(m.extras(), key)?.map(|v| info(&v, &format!("extras.{key}"))).transpose()
    };
    let of = |i: gltf::texture::Info| (i.texture().index(), of_info(&i));
    let specular_color = m.specular().and_then(|s| s.specular_color_texture()).map(of);
    let specular_level = m.specular().and_then(|s| s.specular_texture()).map(of);
    let transmission = m.transmission().and_then(|t| t.transmission_texture()).map(of);
    // glTF's sheen and anisotropy textures, where rt's own extras give none.
    let from_extension = |name: &str, key: &str| -> Result<Option<(usize, TextureUse)>, String> {
        m.extension_value(name).and_then(|e| e.get(key)).map(|v| info(v, &format!("{name}.{key}"))).transpose()
    };
    // The texture, and whether it is the extension's.
    let own_or_extension = |own: &str, name: &str, key: &str| -> Result<(Option<(usize, TextureUse)>, bool), String> {
        Ok(match from_extras(own)? {
            Some(own) => (Some(own), false),
            None => (from_extension(name, key)?, true),
        })
    };
    let (sheen, sheen_of_gltf) =
        own_or_extension(extras::SHEEN_TEXTURE, "KHR_materials_sheen", "sheenRoughnessTexture")?;
    let (sheen_tint, _) = own_or_extension(extras::SHEEN_TINT_TEXTURE, "KHR_materials_sheen", "sheenColorTexture")?;
    // glTF's anisotropy texture holds directions, which the shader turns into rotations
    // after filtering, as Blender's import of it does (a filtered rotation would turn the
    // wrong way between texels: 3.6% off Cycles on a block at a stripe's edge).
    let (anisotropy, anisotropy_of_gltf) =
        own_or_extension(extras::ANISOTROPY_TEXTURE, "KHR_materials_anisotropy", "anisotropyTexture")?;
    let anisotropy_directions = anisotropy_of_gltf && anisotropy.is_some();
    let sheen_reading = if sheen_of_gltf { Reading::SheenRoughness } else { linear };
    let film_thickness = m
        .extension_value("KHR_materials_iridescence")
        .and_then(|f| f.get("iridescenceThicknessTexture"))
        .map(|v| info(v, "KHR_materials_iridescence.iridescenceThicknessTexture"))
        .transpose()?;
    let layers = LayerTextures {
        coat: load(from_clearcoat("clearcoatTexture")?, linear, COAT, "clearcoat")?,
        coat_roughness: load(
            from_clearcoat("clearcoatRoughnessTexture")?,
            linear,
            COAT_ROUGHNESS,
            "clearcoat roughness",
        )?,
        coat_tint: load(from_extras(extras::COAT_TINT_TEXTURE)?, srgb, COAT_TINT, "coat tint")?,
        sheen: load(sheen, sheen_reading, SHEEN, "sheen")?,
        sheen_tint: load(sheen_tint, srgb, SHEEN_TINT, "sheen tint")?,
        anisotropy: load(anisotropy, linear, ANISOTROPY, "anisotropy")?,
        specular_tint: load(specular_color, srgb, SPECULAR_TINT, "specular colour")?,
        diffuse_roughness: load(
            from_extras(extras::DIFFUSE_ROUGHNESS_TEXTURE)?,
            linear,
            DIFFUSE_ROUGHNESS,
            "diffuse roughness",
        )?,
        thin_film_thickness: load(film_thickness, linear, THIN_FILM_THICKNESS, "iridescence thickness")?,
        transmission: load(transmission, linear, TRANSMISSION, "transmission")?,
        specular_level: load(specular_level, linear, SPECULAR_LEVEL, "specular")?,
        ior: load(from_extras(extras::IOR_TEXTURE)?, linear, IOR, "ior")?,
    };
    Ok(Layers { textures: layers, second_uv_set, anisotropy_directions })
}
