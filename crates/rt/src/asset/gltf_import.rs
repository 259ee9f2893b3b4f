//! glTF 2.0 (`.gltf` with external or embedded buffers, `.glb`) import.
//!
//! Materials map onto rt's lobe weights as below; every absent field takes its glTF
//! default, because glTF writers (Blender's among them) leave default values out.
//!
//! | glTF (default when absent)                                | rt material                    |
//! |-----------------------------------------------------------|--------------------------------|
//! | `baseColorFactor` rgb (1, 1, 1)                           | `base_color`                   |
//! | `metallicFactor` `m` (1)                                  | `reflection = m`               |
//! | `KHR_materials_transmission` factor `t` (0)               | `transmission = (1 - m) t`     |
//! | (the rest)                                                | `diffuse = (1 - m)(1 - t)`     |
//! | `roughnessFactor` (1)                                     | `roughness`                    |
//! | `KHR_materials_ior` (1.5)                                 | `ior`                          |
//! | `emissiveFactor` (0) × `KHR_materials_emissive_strength` (1) | `emission`                  |
//! | `KHR_materials_specular` factor `s` (1)                   | `specular_ior_level = s / 2` (with a diffuse part) |
//! | `extras.rt_specular_ior_level` (absent)                   | `specular_ior_level`, instead of `s / 2` (Blender's level may exceed 0.5) |
//! | `KHR_materials_specular` colour factor (1, 1, 1)          | `specular_tint`                |
//! | `KHR_materials_clearcoat` factor, roughness factor (0, 0)  | `coat`, `coat_roughness` (index 1.5, untinted) |
//! | `extras.rt_coat`, `_roughness`, `_ior`, `_tint` (absent, absent, 1.5, (1, 1, 1)) | `coat`, `coat_roughness` (instead of clearcoat's), `coat_ior`, `coat_tint` |
//! | `extras.rt_glossy_color` `[r, g, b]` (absent)             | Cycles' Glossy BSDF: `specular = 1` tinted by the colour (`specular_tint`), no other lobe |
//! | `KHR_materials_sheen` colour, roughness factors ((0, 0, 0), 0) | `sheen = 1`, `sheen_tint`, `sheen_roughness` (as Blender imports it; none without the extension) |
//! | `extras.rt_sheen`, `_roughness`, `_tint` (absent)          | `sheen`, `sheen_roughness`, `sheen_tint`, instead of the extension's |
//! | `KHR_materials_anisotropy` strength, rotation (0, 0 rad)  | `anisotropy`, `anisotropy_rotation = rotation / 2π` (as Blender imports it); with its texture, the uv map's tangent |
//! | `extras.rt_anisotropy`, `rt_anisotropy_rotation` (absent) | `anisotropy`, `anisotropy_rotation`, instead of the extension's |
//! | `KHR_materials_iridescence` factor (0), index (1.3), thickness maximum (400) | `thin_film_weight` (the factor; 0: no film), `thin_film_ior`, `thin_film_thickness` (the maximum) |
//! | `extras.rt_tangent` (`"radial_z"`)                        | `tangent` |
//! | `KHR_materials_clearcoat` textures, `KHR_materials_specular` colour texture, `KHR_materials_sheen` textures (the roughness's re-encoded) and `_anisotropy`'s (its directions), `extras.rt_*_texture` | `textures.layers` (`gltf_layer_textures`) |
//! | `KHR_materials_transmission` texture, `KHR_materials_specular` texture | `textures.layers` (R × the transmission factor, A × the level); with a transmission texture the weights are those of the part that does not transmit and `textures.transmission` is the factor |
//! | `KHR_materials_clearcoat.clearcoatNormalTexture` (`scale` 1) | `textures.coat_normal`, `coat_normal_scale` (none: the coat is not normal-mapped) |
//! | `extras.rt_ior_texture`, `rt_ior_minimum`, `rt_coat_ior_minimum`, `rt_thin_film_ior_minimum` (absent; the material's own indices) | `textures.layers.ior` (R the IOR, G the coat's, B the film's from the minimum at 0 to the factor at 1), `textures.ior_minimum` |
//! | `extras.rt_diffuse_roughness` (0)                         | `diffuse_roughness` (Principled's Diffuse Roughness; glTF has none) |
//! | `KHR_materials_iridescence` thickness texture, minimum (100), `extras.rt_diffuse_roughness_texture` | `textures.layers` (`gltf_layer_textures`), `textures.thin_film_minimum` |
//! | `extras.rt_bump_map_correction` (true)                    | `bump_map_correction` (Blender's material setting; glTF has none) |
//! | `KHR_materials_volume` colour `c` (1), distance `d` (∞)   | `absorption = -ln(c) / d`; 0 if `d = ∞` |
//! | `extras.rt_volume_emission` `[r, g, b]` (0)               | `volume_emission`              |
//! | `extras.rt_closure_weight` (1)                         | `closure_weight` (an Add Shader's halves: 2) |
//! | `extras.rt_lobe` `{"module": NAME, PARAM: value, …}` (absent) | `lobe`: a lobe module's BSDF, weighted by the base colour (`scene::lobe`) |
//!
//! The specular layer is a dielectric coating of the diffuse part (Cycles' Principled
//! specular layer; glTF's default F0 of 0.04 is level 0.5 at index 1.5).
//! Metal is a layer over the dielectric in glTF, so transmission and specular apply
//! only to the `1 - m` that is not metal.
//! `c` is clamped to (0, 1] so that a black attenuation colour stays finite.
//!
//! A primitive without a material gets [`Material::default`] (white diffuse), not glTF's
//! default material (a rough white metal): rt treats a material-less mesh as plain
//! geometry, the same as an OBJ without a `.mtl` and a scene material left at defaults.

use super::gltf_extensions::{Film, Sheen, anisotropy, clearcoat, glossy, iridescence, sheen};
use super::gltf_texture_transform::{of_info, of_normal};
use super::gltf_textures::{ColorSpace, TextureLoader};
use super::material_extras as extras;
use super::{AssetError, MeshData};
use crate::scene::lobe::ModuleLobe;
use crate::scene::{Material, MaterialTextures, Tangent, slots};
use gltf::json::Value;
use gltf::material::AlphaMode;
use std::path::Path;

/// Loads the default scene (else the first, else every root node) of a glTF file,
/// with node transforms applied. A file with no meshes yields its materials only.
pub fn load(path: &Path) -> Result<MeshData, AssetError> {
    let err = |message: String| AssetError::new(path, message);
    let bytes = crate::files::read(path).map_err(|e| err(e.message()))?;
    let unchecked =
        gltf::Gltf::from_slice_without_validation(&bytes).map_err(|e| err(format!("cannot read glTF: {e}")))?;
    let json = unchecked.document.into_json();
    check_primitive_accessors(&json).map_err(err)?;
    let document = gltf::Document::from_json(json).map_err(|e| err(format!("invalid glTF: {e}")))?;
    let blob = unchecked.blob;
    let buffers = super::gltf_buffers::load(&document, path.parent().unwrap_or(Path::new("")), blob).map_err(err)?;

    let mut mesh = MeshData::default();
    // Images are decoded by rt (not by gltf's importer), and only those that a material
    // uses, so that an error names the material and the image.
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut loader = TextureLoader::new(&buffers, dir);
    for (i, m) in document.materials().enumerate() {
        let name = m.name().map_or_else(|| format!("material_{i}"), str::to_owned);
        let material = gltf_material(&m, &document, &mut loader).map_err(|e| err(format!("material `{name}`: {e}")))?;
        warn_of_unknown_extras(path, &name, &m);
        mesh.materials.push((name, material));
    }
    let count = mesh.materials.len();
    if let Some((name, mix)) =
        mesh.materials.iter().find_map(|(n, m)| m.mix_material.filter(|&i| i as usize >= count).map(|i| (n, i)))
    {
        return Err(err(format!(
            "material `{name}`: rt_mix_material {mix} is not one of the file's {count} materials"
        )));
    }
    mesh.textures = loader.textures;

    super::gltf_nodes::place_meshes(&document, &buffers, mesh, path).map_err(err)
}

/// The rt material of glTF material `m`, with its textures (decoded by `loader`).
fn gltf_material(
    m: &gltf::Material,
    document: &gltf::Document,
    loader: &mut TextureLoader,
) -> Result<Material, String> {
    let mut material = map_material(m)?;
    material.textures = material_textures(m, loader)?;
    let layers = super::gltf_layer_textures::layer_textures(document, m, loader)?;
    material.textures.layers = layers.textures;
    material.textures.second_uv_set |= layers.second_uv_set;
    material.textures.anisotropy_directions = layers.anisotropy_directions;
    let (coat_normal, coat_normal_scale, coat_normal_uv_set) =
        super::gltf_layer_textures::coat_normal_texture(m, document, loader)?;
    (material.textures.coat_normal, material.textures.coat_normal_scale) = (coat_normal, coat_normal_scale);
    material.textures.second_uv_set |= coat_normal_uv_set;
    material.textures.thin_film_minimum = iridescence(m).ok().flatten().map_or(0.0, |f| f.minimum);
    let textured_metal = material.textures.metallic_roughness.is_some();
    let textured_transmission = material.textures.layers.transmission.is_some();
    if textured_metal || textured_transmission {
        // The lobe weights become those of the part that is not metal, or does not
        // transmit: the texture sets the rest.
        material.textures.transmission = transmission_factor(m);
        material = Material {
            textures: material.textures,
            ..map_material_with(
                m,
                if textured_metal { 0.0 } else { metallic_factor(m) },
                if textured_transmission { 0.0 } else { transmission_factor(m) },
            )?
        };
    }
    // A channel of the indices' texture that an export leaves undriven has the material's own index.
    if material.textures.layers.ior.is_some() {
        let mut minimum = [material.ior, material.coat_ior, material.thin_film_ior];
        for (i, key) in
            [extras::IOR_MINIMUM, extras::COAT_IOR_MINIMUM, extras::THIN_FILM_IOR_MINIMUM].into_iter().enumerate()
        {
            if let Some(v) = extra::<f32>(m.extras(), key)? {
                minimum[i] = v;
            }
        }
        material.textures.ior_minimum = minimum;
    }
    Ok(material)
}

/// The textures of a material; unsupported ones (occlusion: a path tracer finds
/// occlusion itself) are left out, normal maps with a warning.
fn material_textures(m: &gltf::Material, loader: &mut TextureLoader) -> Result<MaterialTextures, String> {
    let pbr = m.pbr_metallic_roughness();
    let mut second_uv_set = 0;
    let mut load = |info: Option<gltf::texture::Info>, space, slot: usize, what: &str| {
        info.map(|i| {
            let used = of_info(&i);
            second_uv_set |= uv_set_bit(used.tex_coord, slot, what);
            loader.load(&i.texture(), space, used.transform).map_err(|e| format!("{what} texture: {e}"))
        })
        .transpose()
    };
    let base_color = load(pbr.base_color_texture(), ColorSpace::Srgb, slots::BASE_COLOR, "base colour")?;
    let metallic_roughness =
        load(pbr.metallic_roughness_texture(), ColorSpace::Linear, slots::METALLIC_ROUGHNESS, "metallic-roughness")?;
    let emission = load(m.emissive_texture(), ColorSpace::Srgb, slots::EMISSION, "emissive")?;
    let normal_info = m.normal_texture();
    // Its tangent frame is of the set it reads: glTF's TANGENT or MikkTSpace's of
    // TEXCOORD_0, MikkTSpace's of TEXCOORD_1.
    // The frame is the uv set's, whatever the texture's transform (as Cycles' Normal Map
    // node takes its tangents from the uv map, not from a Mapping node in front of the image).
    let normal = match &normal_info {
        Some(n) => {
            let used = of_normal(n)?;
            second_uv_set |= uv_set_bit(used.tex_coord, slots::NORMAL, "normal");
            Some(
                loader
                    .load(&n.texture(), ColorSpace::Linear, used.transform)
                    .map_err(|e| format!("normal texture: {e}"))?,
            )
        }
        None => None,
    };
    let alpha_cutoff = match m.alpha_mode() {
        AlphaMode::Opaque | AlphaMode::Blend => 0.0,
        AlphaMode::Mask => m.alpha_cutoff().unwrap_or(0.5),
    };
    Ok(MaterialTextures {
        base_color,
        metallic_roughness,
        emission,
        metallic: pbr.metallic_factor().clamp(0.0, 1.0),
        base_alpha: pbr.base_color_factor()[3],
        alpha_cutoff,
        alpha_blend: m.alpha_mode() == AlphaMode::Blend,
        normal,
        normal_scale: normal_info.map_or(1.0, |n| n.scale()),
        coat_normal: None,
        coat_normal_scale: 1.0,
        second_uv_set,
        layers: Default::default(),
        thin_film_minimum: 0.0,
        transmission: 0.0,
        anisotropy_directions: false,
        ior_minimum: [1.5, 1.5, 1.33],
    })
}

/// The bit of [`MaterialTextures::second_uv_set`] for a texture of `slot` read with
/// `TEXCOORD_{tex_coord}`: rt carries two sets, so a third or later one is read as the first.
pub(super) fn uv_set_bit(tex_coord: u32, slot: usize, what: &str) -> u32 {
    match tex_coord {
        0 => 0,
        1 => 1 << slot,
        n => {
            log::warn!("{what} texture uses TEXCOORD_{n}; rt carries TEXCOORD_0 and TEXCOORD_1 and reads TEXCOORD_0");
            0
        }
    }
}

fn metallic_factor(m: &gltf::Material) -> f32 {
    m.pbr_metallic_roughness().metallic_factor().clamp(0.0, 1.0)
}

fn transmission_factor(m: &gltf::Material) -> f32 {
    m.transmission().map_or(0.0, |t| t.transmission_factor()).clamp(0.0, 1.0)
}

fn map_material(m: &gltf::Material) -> Result<Material, String> {
    map_material_with(m, metallic_factor(m), transmission_factor(m))
}

/// The material with `metallic` and `transmission` for its factors: 0 gives the part that
/// is not metal, or does not transmit, of a material whose texture sets the rest.
fn map_material_with(m: &gltf::Material, metallic: f32, transmission: f32) -> Result<Material, String> {
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, _] = pbr.base_color_factor();
    let dielectric = 1.0 - metallic;
    let strength = m.emissive_strength().unwrap_or(1.0);
    let diffuse = dielectric * (1.0 - transmission);
    let level = match extra::<f32>(m.extras(), extras::SPECULAR_IOR_LEVEL)? {
        Some(level) => level,
        None => m.specular().map_or(1.0, |s| s.specular_factor()) / 2.0,
    };
    let clearcoat = clearcoat(m)?;
    let sheen = sheen(m)?.unwrap_or(Sheen { weight: 0.0, tint: [1.0; 3], roughness: 0.5 });
    let (anisotropy, anisotropy_rotation) = anisotropy(m)?;
    let film = iridescence(m)?.unwrap_or(Film { thickness: 0.0, minimum: 0.0, ior: 1.33, weight: 1.0 });
    let material = Material {
        base_color: [r, g, b],
        diffuse,
        specular: 0.0,
        specular_ior_level: if diffuse > 0.0 { level.clamp(0.0, 1.0) } else { 0.0 },
        specular_tint: m.specular().map_or([1.0; 3], |s| s.specular_color_factor().map(|c| c.clamp(0.0, 1.0))),
        coat: extra::<f32>(m.extras(), extras::COAT)?.unwrap_or(clearcoat.factor).clamp(0.0, 1.0),
        coat_roughness: extra::<f32>(m.extras(), extras::COAT_ROUGHNESS)?
            .unwrap_or(clearcoat.roughness)
            .clamp(0.0, 1.0),
        coat_ior: extra::<f32>(m.extras(), extras::COAT_IOR)?.unwrap_or(1.5).max(1.0),
        coat_tint: extra::<[f32; 3]>(m.extras(), extras::COAT_TINT)?.unwrap_or([1.0; 3]).map(|c| c.clamp(0.0, 1.0)),
        sheen: extra::<f32>(m.extras(), extras::SHEEN)?.unwrap_or(sheen.weight).clamp(0.0, 1.0),
        sheen_roughness: extra::<f32>(m.extras(), extras::SHEEN_ROUGHNESS)?.unwrap_or(sheen.roughness).clamp(0.0, 1.0),
        sheen_tint: extra::<[f32; 3]>(m.extras(), extras::SHEEN_TINT)?.unwrap_or(sheen.tint).map(|c| c.clamp(0.0, 1.0)),
        anisotropy: extra::<f32>(m.extras(), extras::ANISOTROPY)?.unwrap_or(anisotropy).clamp(0.0, 1.0),
        anisotropy_rotation: extra::<f32>(m.extras(), extras::ANISOTROPY_ROTATION)?
            .unwrap_or(anisotropy_rotation)
            .rem_euclid(1.0),
        thin_film_thickness: film.thickness,
        thin_film_ior: film.ior,
        thin_film_weight: film.weight,
        tangent: tangent(m)?,
        diffuse_roughness: extra::<f32>(m.extras(), extras::DIFFUSE_ROUGHNESS)?.unwrap_or(0.0).clamp(0.0, 1.0),
        bump_map_correction: extra::<bool>(m.extras(), extras::BUMP_MAP_CORRECTION)?.unwrap_or(true),
        reflection: metallic,
        transmission: dielectric * transmission,
        ior: m.ior().unwrap_or(1.5),
        roughness: pbr.roughness_factor(),
        emission: m.emissive_factor().map(|e| e * strength),
        absorption: m.volume().map_or([0.0; 3], |v| absorption(v.attenuation_color(), v.attenuation_distance())),
        volume_emission: volume_emission(m.extras())?,
        node_program: match extra::<serde_json::Value>(m.extras(), extras::NODE_GRAPH)? {
            Some(graph) => node_program_or_constants(m, &graph),
            None => Vec::new(),
        },
        mix_material: extra::<u32>(m.extras(), extras::MIX_MATERIAL)?,
        holdout: extra::<f32>(m.extras(), extras::HOLDOUT)?.unwrap_or(0.0).clamp(0.0, 1.0),
        lobe: extra::<ModuleLobe>(m.extras(), extras::LOBE)?,
        closure_weight: extra::<f32>(m.extras(), extras::CLOSURE_WEIGHT)?.unwrap_or(1.0).clamp(0.0, 16.0),
        ..Material::default()
    };
    Ok(match extra::<[f32; 3]>(m.extras(), extras::GLOSSY_COLOR)? {
        Some(color) => glossy(material, color),
        None => material,
    })
}

/// The compiled node graph of `m`; a graph rt cannot compile (a node it does not evaluate,
/// more registers than it has, a newer format) leaves the material its constant inputs, with
/// a warning that names the material and what stopped the graph: a render never fails on it.
fn node_program_or_constants(m: &gltf::Material, graph: &serde_json::Value) -> Vec<u32> {
    super::node_graph::compile_json(graph).unwrap_or_else(|e| {
        log::warn!("material `{}`: {e}; it renders with its inputs' own values", m.name().unwrap_or("unnamed"));
        Vec::new()
    })
}

/// `extras.rt_tangent`: the Principled BSDF's linked Tangent input; when absent, the uv
/// map's tangent for a `KHR_materials_anisotropy` texture (whose directions are in its
/// frame, as Blender's importer links it), else "radial_z".
fn tangent(m: &gltf::Material) -> Result<Tangent, String> {
    let textured = m.extension_value("KHR_materials_anisotropy").is_some_and(|a| a.get("anisotropyTexture").is_some());
    match extra::<String>(m.extras(), extras::TANGENT)?.as_deref() {
        None if textured => Ok(Tangent::Uv),
        None | Some("radial_z") => Ok(Tangent::RadialZ),
        Some("radial_x") => Ok(Tangent::RadialX),
        Some("radial_y") => Ok(Tangent::RadialY),
        Some("uv") => Ok(Tangent::Uv),
        Some(other) => Err(format!(
            "extras.rt_tangent is {other:?}{}",
            crate::scene::did_you_mean(other, ["radial_x", "radial_y", "radial_z", "uv"].into_iter())
        )),
    }
}

/// Beer–Lambert: white light keeps fraction `c` after distance `d`.
fn absorption(color: [f32; 3], distance: f32) -> [f32; 3] {
    if !(distance.is_finite() && distance > 0.0) {
        return [0.0; 3];
    }
    color.map(|c| -c.clamp(f32::MIN_POSITIVE, 1.0).ln() / distance)
}

/// `extras.rt_volume_emission`: glTF has no field for light emitted inside a medium.
/// Other tools' extras may hold anything, so only our own key is checked.
fn volume_emission(extras: &gltf::json::Extras) -> Result<[f32; 3], String> {
    Ok(extra(extras, extras::VOLUME_EMISSION)?.unwrap_or([0.0; 3]))
}

/// Warns of keys in `m`'s extras that look like rt's and are none it reads (an exporter's
/// typo would otherwise leave a value silently unused).
fn warn_of_unknown_extras(path: &Path, name: &str, m: &gltf::Material) {
    let Some(raw) = m.extras() else { return };
    let Ok(value) = serde_json::from_str::<serde_json::Value>(raw.get()) else { return };
    for key in extras::unknown_keys(&value) {
        log::warn!("{}: material `{name}`: {key} is not a key rt reads; it is left unused", path.display());
    }
}

/// The rt value `key` of a material's `extras`, if there.
pub(super) fn extra<T: serde::de::DeserializeOwned>(
    extras: &gltf::json::Extras,
    key: &str,
) -> Result<Option<T>, String> {
    let Some(raw) = extras else {
        return Ok(None);
    };
    let value: Value = gltf::json::deserialize::from_str(raw.get()).map_err(|e| format!("extras are not JSON: {e}"))?;
    match value.get(key) {
        None => Ok(None),
        Some(v) => gltf::json::deserialize::from_value(v.clone())
            .map(Some)
            .map_err(|e| format!("extras.{key} has the wrong type: {e}")),
    }
}

/// gltf's own validation indexes a primitive's accessors before it checks
/// that they exist, and panics on a dangling one: those are refused first.
fn check_primitive_accessors(json: &gltf::json::Root) -> Result<(), String> {
    let count = json.accessors.len();
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let used = prim.attributes.values().chain(prim.indices.as_ref());
            if let Some(bad) = used.map(|a| a.value()).find(|&a| a >= count) {
                return Err(format!("mesh {m} primitive {p}: accessor {bad} does not exist ({count} accessors)"));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::asset::fixture::{TempDir, base64};
    use crate::asset::load_mesh;
    use crate::scene::Material;
    use glam::{Mat3, Vec3};

    const POSITIONS: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    const NORMAL: [f32; 3] = [0.48, 0.6, 0.64];

    /// One indexed triangle with normals under a parent node translated by [1, 2, 3]
    /// and a child scaled by [-1, 2, 1]; `material` is the JSON of its only material.
    fn triangle_gltf(material: Option<&str>) -> String {
        let mut bytes = Vec::new();
        let floats = POSITIONS.iter().flatten().chain([NORMAL; 3].iter().flatten());
        floats.for_each(|f| bytes.extend(f.to_le_bytes()));
        [0u32, 1, 2].iter().for_each(|i| bytes.extend(i.to_le_bytes()));
        let (materials, use_material) = match material {
            Some(json) => (format!(r#""materials": [{json}],"#), r#", "material": 0"#),
            None => (String::new(), ""),
        };
        format!(
            r#"{{
  "asset": {{ "version": "2.0" }}, "scene": 0, "scenes": [{{ "nodes": [0] }}],
  "nodes": [{{ "translation": [1, 2, 3], "children": [1] }}, {{ "scale": [-1, 2, 1], "mesh": 0 }}],
  "meshes": [{{ "primitives": [{{
    "attributes": {{ "POSITION": 0, "NORMAL": 1 }}, "indices": 2{use_material} }}] }}],
  {materials}
  "buffers": [{{ "byteLength": {len}, "uri": "data:application/octet-stream;base64,{data}" }}],
  "bufferViews": [{{ "buffer": 0, "byteLength": 36 }},
    {{ "buffer": 0, "byteOffset": 36, "byteLength": 36 }},
    {{ "buffer": 0, "byteOffset": 72, "byteLength": 12 }}],
  "accessors": [
    {{ "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
       "min": [0, 0, 0], "max": [1, 1, 0] }},
    {{ "bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3" }},
    {{ "bufferView": 2, "componentType": 5125, "count": 3, "type": "SCALAR" }}]
}}"#,
            len = bytes.len(),
            data = base64(&bytes),
        )
    }

    #[test]
    fn gltf_node_transforms_and_material_mapping() {
        let material = r#"{
          "name": "glass",
          "pbrMetallicRoughness": { "baseColorFactor": [0.8, 0.9, 1.0, 1.0],
                                    "metallicFactor": 0.0, "roughnessFactor": 0.1 },
          "emissiveFactor": [1.0, 0.5, 0.0],
          "extensions": {
            "KHR_materials_transmission": { "transmissionFactor": 1.0 },
            "KHR_materials_ior": { "ior": 1.33 },
            "KHR_materials_emissive_strength": { "emissiveStrength": 4.0 },
            "KHR_materials_volume": { "thicknessFactor": 0.1, "attenuationDistance": 2.0,
                                      "attenuationColor": [0.5, 0.25, 1.0] }
          },
          "extras": { "rt_volume_emission": [0.1, 0.2, 0.3], "other_tool": "x" }
        }"#;
        let dir = TempDir::new("gltf_transforms_material");
        let mesh = load_mesh(&dir.write("tri.gltf", &triangle_gltf(Some(material)))).expect("loads");

        // Parent × child: x' = 1 - x, y' = 2 + 2y, z' = 3 + z.
        assert_eq!(mesh.positions, [[1.0, 2.0, 3.0], [0.0, 2.0, 3.0], [1.0, 4.0, 3.0]]);
        // The mirror flips the winding, so the face still points the same side as its normals.
        assert_eq!(mesh.indices, [[0, 2, 1]]);
        let expected = (Mat3::from_diagonal(Vec3::new(-1.0, 0.5, 1.0)) * Vec3::from(NORMAL)).normalize();
        for n in mesh.normals.as_ref().expect("normals") {
            assert!(Vec3::from(*n).abs_diff_eq(expected, 1e-6), "{n:?}");
        }
        assert!(mesh.uvs.is_none());

        assert_eq!(mesh.material_ids, [0]);
        let (name, m) = &mesh.materials[0];
        assert_eq!(name, "glass");
        let ln2 = std::f32::consts::LN_2;
        assert_eq!(
            m,
            &Material {
                base_color: [0.8, 0.9, 1.0],
                diffuse: 0.0,
                specular: 0.0,
                reflection: 0.0,
                transmission: 1.0,
                ior: 1.33,
                roughness: 0.1,
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
                tangent: crate::scene::Tangent::RadialZ,
                thin_film_thickness: 0.0,
                thin_film_ior: 1.33,
                thin_film_weight: 1.0,
                bump_map_correction: true,
                diffuse_roughness: 0.0,
                hardness: None,
                emission: [4.0, 2.0, 0.0],
                absorption: [ln2 / 2.0, 2.0 * ln2 / 2.0, 0.0],
                volume_emission: [0.1, 0.2, 0.3],
                holdout: 0.0,
                textures: Default::default(),
                node_program: Vec::new(),
                mix_material: None,
                closure_weight: 1.0,
                lobe: None,
            }
        );
    }

    #[test]
    fn gltf_absent_fields_take_gltf_defaults() {
        let dir = TempDir::new("gltf_defaults");
        let path = dir.write("tri.gltf", &triangle_gltf(Some(r#"{ "name": "plain" }"#)));
        let m = &load_mesh(&path).expect("loads").materials[0].1;
        // glTF's defaults: metallic 1, roughness 1, white.
        assert_eq!((m.reflection, m.diffuse, m.transmission), (1.0, 0.0, 0.0));
        assert_eq!((m.roughness, m.ior, m.base_color), (1.0, 1.5, [1.0; 3]));
        assert_eq!((m.emission, m.absorption), ([0.0; 3], [0.0; 3]));
    }

    #[test]
    fn gltf_specular_becomes_the_diffuse_coating() {
        let dir = TempDir::new("gltf_specular");
        let dielectric = r#""pbrMetallicRoughness": { "metallicFactor": 0.0 }"#;
        let cases = [
            (format!("{{ {dielectric} }}"), 0.5, [1.0; 3]),
            (
                format!(
                    r#"{{ {dielectric}, "extensions": {{ "KHR_materials_specular":
                      {{ "specularFactor": 0.6, "specularColorFactor": [1.0, 0.5, 0.25] }} }} }}"#
                ),
                0.3,
                [1.0, 0.5, 0.25],
            ),
            (
                format!(
                    r#"{{ {dielectric}, "extensions": {{ "KHR_materials_specular": {{ "specularFactor": 1.0 }} }},
                      "extras": {{ "rt_specular_ior_level": 0.8 }} }}"#
                ),
                0.8,
                [1.0; 3],
            ),
        ];
        for (json, level, tint) in cases {
            let m = &load_mesh(&dir.write("tri.gltf", &triangle_gltf(Some(&json)))).expect("loads").materials[0].1;
            assert_eq!((m.specular, m.specular_ior_level, m.specular_tint), (0.0, level, tint), "{json}");
        }
    }

    #[test]
    fn gltf_without_material_gets_white_diffuse() {
        let dir = TempDir::new("gltf_no_material");
        let mesh = load_mesh(&dir.write("tri.gltf", &triangle_gltf(None))).expect("loads");
        assert_eq!(mesh.materials, [("default".to_string(), Material::default())]);
        assert_eq!(mesh.material_ids, [0]);
    }

    #[test]
    fn gltf_materials_only_has_no_triangles() {
        let dir = TempDir::new("gltf_materials_only");
        let json = r#"{ "asset": { "version": "2.0" }, "materials": [{ "name": "a" }, { "name": "b" }] }"#;
        let path = dir.write("mats.gltf", json);
        let mesh = super::load(&path).expect("materials-only glTF is valid");
        assert!(mesh.positions.is_empty() && mesh.normals.is_none());
        assert_eq!(mesh.materials.len(), 2);
        let message = load_mesh(&path).expect_err("no geometry").to_string();
        assert!(message.contains("contains no triangles"), "{message}");
    }

    #[test]
    fn gltf_malformed_is_an_error() {
        let dir = TempDir::new("gltf_malformed");
        let message = load_mesh(&dir.write("bad.glb", "not a glb")).expect_err("bad").to_string();
        assert!(message.contains("bad.glb: cannot read glTF"), "{message}");
    }
}
