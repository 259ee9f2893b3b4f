//! What rt reads of a glTF material beyond the `gltf` crate's model, as raw JSON (the crate
//! does not model them): `KHR_materials_clearcoat`, `KHR_materials_iridescence`,
//! `KHR_materials_sheen` and `KHR_materials_anisotropy`, the last two mapped onto the
//! Principled BSDF as Blender's own glTF importer maps them; and rt's own Glossy lobe
//! (`extras.rt_glossy_color`). Textures of the last three are not read: their factors stand
//! for them, with a warning naming the material (rt's extras carry the sheen's and the
//! anisotropy's textures; clearcoat's textures: `gltf_layer_textures`).

use crate::scene::Material;
use gltf::json::Value;

/// Cycles' Glossy BSDF (`extras.rt_glossy_color`, which rt_export.py writes beside factors of
/// a metal of that colour for other readers): rt's `specular` lobe, GGX without Fresnel
/// tinted by the colour, and nothing else.
pub(super) fn glossy(m: Material, color: [f32; 3]) -> Material {
    Material {
        diffuse: 0.0,
        specular: 1.0,
        reflection: 0.0,
        transmission: 0.0,
        specular_ior_level: 0.0,
        specular_tint: color.map(|c| c.clamp(0.0, 1.0)),
        ..m
    }
}

/// `KHR_materials_clearcoat`'s factors (glTF's defaults 0 and 0 for absent keys; no extension:
/// no coat), which gltf leaves as raw JSON (its textures: `gltf_layer_textures`).
pub(super) struct Clearcoat {
    pub factor: f32,
    pub roughness: f32,
}

pub(super) fn clearcoat(m: &gltf::Material) -> Result<Clearcoat, String> {
    let Some(ext) = m.extension_value("KHR_materials_clearcoat") else {
        return Ok(Clearcoat { factor: 0.0, roughness: Material::default().coat_roughness });
    };
    let factor = |key: &str| number(ext, "KHR_materials_clearcoat", key, 0.0);
    Ok(Clearcoat { factor: factor("clearcoatFactor")?, roughness: factor("clearcoatRoughnessFactor")? })
}

/// Field `key` of extension `ext` (raw JSON), `default` when absent.
fn number(ext: &Value, name: &str, key: &str, default: f32) -> Result<f32, String> {
    match ext.get(key) {
        None => Ok(default),
        Some(v) => v
            .as_f64()
            .filter(|f| f.is_finite())
            .map(|f| f as f32)
            .ok_or_else(|| format!("{name}.{key} must be a number, got {v}")),
    }
}

fn colour(ext: &Value, name: &str, key: &str, default: [f32; 3]) -> Result<[f32; 3], String> {
    let Some(v) = ext.get(key) else {
        return Ok(default);
    };
    let bad = || format!("{name}.{key} must be three numbers, got {v}");
    let items = v.as_array().filter(|a| a.len() == 3).ok_or_else(bad)?;
    let mut c = [0.0; 3];
    for (out, item) in c.iter_mut().zip(items) {
        *out = item.as_f64().filter(|f| f.is_finite()).ok_or_else(bad)? as f32;
    }
    Ok(c)
}

fn material_name(m: &gltf::Material) -> String {
    match (m.name(), m.index()) {
        (Some(name), _) => format!("material \"{name}\""),
        (None, Some(i)) => format!("material {i}"),
        (None, None) => "the default material".to_string(),
    }
}

/// Warns that the textures `keys` of extension `name` that `ext` names are not read.
fn warn_textures(m: &gltf::Material, ext: &Value, name: &str, keys: &[&str], instead: &str) {
    for key in keys.iter().filter(|k| ext.get(**k).is_some()) {
        log::warn!("{}: {name}.{key} is not supported; rt uses {instead}", material_name(m));
    }
}

/// `KHR_materials_iridescence` as rt's thin film: thickness (nm), index and weight, or `None`
/// for no film (absent, or `iridescenceFactor` 0, glTF's default). Without a thickness
/// texture the film is `iridescenceThicknessMaximum` thick (glTF's defaults: 400 nm, index
/// 1.3); with one (read by `gltf_layer_textures`) its G runs from the minimum (100 nm) to
/// the maximum. A texture of the factor is not read: the factor stands for it.
pub(super) fn iridescence(m: &gltf::Material) -> Result<Option<Film>, String> {
    const NAME: &str = "KHR_materials_iridescence";
    let Some(ext) = m.extension_value(NAME) else {
        return Ok(None);
    };
    let factor = number(ext, NAME, "iridescenceFactor", 0.0)?;
    if factor <= 0.0 {
        return Ok(None);
    }
    warn_textures(m, ext, NAME, &["iridescenceTexture"], "iridescenceFactor");
    let thickness = number(ext, NAME, "iridescenceThicknessMaximum", 400.0)?.clamp(0.0, 100_000.0);
    let minimum = number(ext, NAME, "iridescenceThicknessMinimum", 100.0)?.clamp(0.0, 100_000.0);
    let ior = number(ext, NAME, "iridescenceIor", 1.3)?.max(1.0);
    Ok(Some(Film { thickness, minimum, ior, weight: factor.min(1.0) }))
}

/// `KHR_materials_iridescence`: the film's thickness (nm), index, and weight (its factor:
/// the lobes' Fresnel is the bare one and the film's mixed by it, as the extension defines).
#[derive(Debug)]
pub(super) struct Film {
    pub thickness: f32,
    /// The thickness where a thickness texture reads 0.
    pub minimum: f32,
    pub ior: f32,
    pub weight: f32,
}

/// `KHR_materials_sheen` as Blender's importer reads it into the Principled BSDF: Sheen
/// Weight 1, Sheen Tint `sheenColorFactor` (glTF's default black: no sheen to see), Sheen
/// Roughness `sheenRoughnessFactor` (default 0); `None` without the extension.
pub(super) struct Sheen {
    pub weight: f32,
    pub tint: [f32; 3],
    pub roughness: f32,
}

pub(super) fn sheen(m: &gltf::Material) -> Result<Option<Sheen>, String> {
    const NAME: &str = "KHR_materials_sheen";
    let Some(ext) = m.extension_value(NAME) else {
        return Ok(None);
    };
    Ok(Some(Sheen {
        weight: 1.0,
        tint: colour(ext, NAME, "sheenColorFactor", [0.0; 3])?.map(|c| c.clamp(0.0, 1.0)),
        roughness: number(ext, NAME, "sheenRoughnessFactor", 0.0)?.clamp(0.0, 1.0),
    }))
}

/// `KHR_materials_anisotropy` as Blender's importer reads it without a texture: Anisotropic
/// `anisotropyStrength` (default 0) and Anisotropic Rotation `anisotropyRotation` / 2π
/// (radians to turns; default 0), the Tangent input left unlinked. With a texture Blender
/// links the uv map's tangent and the texture's direction and strength, and so does rt
/// (`gltf_layer_textures`, the tangent in `gltf_import`). `(0, 0)` without the extension.
pub(super) fn anisotropy(m: &gltf::Material) -> Result<(f32, f32), String> {
    const NAME: &str = "KHR_materials_anisotropy";
    let Some(ext) = m.extension_value(NAME) else {
        return Ok((0.0, 0.0));
    };
    let strength = number(ext, NAME, "anisotropyStrength", 0.0)?.clamp(0.0, 1.0);
    let rotation = number(ext, NAME, "anisotropyRotation", 0.0)? / std::f32::consts::TAU;
    Ok((strength, rotation.rem_euclid(1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn material(json: &str) -> Result<Clearcoat, String> {
        let doc = format!(r#"{{ "asset": {{ "version": "2.0" }}, "materials": [{json}] }}"#);
        let gltf = gltf::Gltf::from_slice(doc.as_bytes()).expect("parses");
        let m = gltf.materials().next().expect("a material");
        clearcoat(&m)
    }

    #[test]
    fn clearcoat_factors_are_read_with_gltf_defaults() {
        let full = r#"{ "extensions": { "KHR_materials_clearcoat":
            { "clearcoatFactor": 0.75, "clearcoatRoughnessFactor": 0.25 } } }"#;
        let c = material(full).expect("reads");
        assert_eq!((c.factor, c.roughness), (0.75, 0.25));
        let c = material(r#"{ "extensions": { "KHR_materials_clearcoat": {} } }"#).expect("reads");
        assert_eq!((c.factor, c.roughness), (0.0, 0.0));
        let c = material("{}").expect("reads");
        assert_eq!(c.factor, 0.0);
    }

    #[test]
    fn clearcoat_of_the_wrong_type_is_an_error() {
        let bad = r#"{ "extensions": { "KHR_materials_clearcoat": { "clearcoatFactor": "much" } } }"#;
        let e = material(bad).err().expect("refused");
        assert!(e.contains("KHR_materials_clearcoat.clearcoatFactor must be a number"), "{e}");
    }

    /// Through the importer: clearcoat becomes rt's coat (index 1.5, untinted); rt's own
    /// extras, which rt_export.py writes beside it, win.
    #[test]
    fn clearcoat_is_imported_as_the_coat() {
        let dir = crate::asset::fixture::TempDir::new("gltf_clearcoat");
        let coat = r#""extensions": { "KHR_materials_clearcoat": { "clearcoatFactor": 0.6, "clearcoatRoughnessFactor": 0.3 } }"#;
        let json = format!(
            r#"{{ "asset": {{ "version": "2.0" }}, "extensionsUsed": ["KHR_materials_clearcoat"],
                 "materials": [{{ {coat} }}, {{ {coat}, "extras": {{ "rt_coat": 0.9, "rt_coat_roughness": 0.1 }} }}] }}"#
        );
        let mesh = crate::asset::gltf_import::load(&dir.write("coat.gltf", &json)).expect("loads");
        let [(_, plain), (_, ours)] = &mesh.materials[..] else { panic!("two materials") };
        assert_eq!((plain.coat, plain.coat_roughness, plain.coat_ior, plain.coat_tint), (0.6, 0.3, 1.5, [1.0; 3]));
        assert_eq!((ours.coat, ours.coat_roughness), (0.9, 0.1));
    }

    /// A material's node graph is compiled at import; one rt cannot compile (here a node
    /// type it does not evaluate) leaves the material its constants, and the asset loads.
    /// Its second material, the Mix Shader's, is kept by index.
    #[test]
    fn node_graphs_compile_at_import_and_a_bad_one_leaves_the_constants() {
        let good = r#"{ "name": "noise", "extras": { "rt_mix_material": 2, "rt_node_graph": { "version": 1,
            "nodes": [{ "name": "N", "type": "TEX_NOISE", "settings": { "noise_dimensions": "3D", "noise_type": "FBM" } }],
            "outputs": { "base_color": { "link": [0, "Color"], "from": "RGBA", "to": "RGBA" } } } } }"#;
        let bad = r#"{ "name": "sky", "extras": { "rt_node_graph": { "version": 1,
            "nodes": [{ "name": "S", "type": "TEX_SKY" }],
            "outputs": { "base_color": { "link": [0, "Color"], "from": "RGBA", "to": "RGBA" } } } } }"#;
        let materials = import("gltf_node_graphs", &format!("{good}, {bad}, {{}}"));
        assert!(!materials[0].node_program.is_empty());
        assert_eq!(materials[0].mix_material, Some(2));
        assert!(materials[1].node_program.is_empty());
    }

    fn import(name: &str, materials: &str) -> Vec<Material> {
        let dir = crate::asset::fixture::TempDir::new(name);
        let json = format!(r#"{{ "asset": {{ "version": "2.0" }}, "materials": [{materials}] }}"#);
        let mesh = crate::asset::gltf_import::load(&dir.write("m.gltf", &json)).expect("loads");
        mesh.materials.into_iter().map(|(_, m)| m).collect()
    }

    /// Iridescence is rt's thin film at the maximum thickness, weighted by its factor; factor 0
    /// (glTF's default) is none, and absent fields take glTF's defaults (index 1.3, 400 nm).
    #[test]
    fn iridescence_is_imported_as_the_thin_film() {
        let m = import(
            "gltf_iridescence",
            r#"{ "extensions": { "KHR_materials_iridescence": { "iridescenceFactor": 1, "iridescenceIor": 1.45,
                  "iridescenceThicknessMinimum": 200, "iridescenceThicknessMaximum": 650 } } },
               { "extensions": { "KHR_materials_iridescence": { "iridescenceFactor": 0.5 } } },
               { "extensions": { "KHR_materials_iridescence": { "iridescenceIor": 1.8 } } },
               { "extensions": { "KHR_materials_iridescence": { "iridescenceFactor": 1,
                  "iridescenceThicknessMinimum": 50 } } },
               {}"#,
        );
        let film = |m: &Material| (m.thin_film_thickness, m.thin_film_ior);
        assert_eq!(film(&m[0]), (650.0, 1.45));
        assert_eq!(film(&m[1]), (400.0, 1.3));
        assert_eq!((m[0].thin_film_weight, m[1].thin_film_weight), (1.0, 0.5), "the factor is the film's weight");
        assert!(!m[2].has_thin_film());
        assert_eq!(film(&m[3]), (400.0, 1.3), "without a thickness texture: its maximum");
        assert_eq!(m[3].textures.thin_film_minimum, 50.0, "kept for a thickness texture");
        assert!(!m[4].has_thin_film());
    }

    /// Blender's Bump Map Correction comes through the extras (on when absent, as in Blender).
    #[test]
    fn bump_map_correction_is_read_from_the_extras() {
        let m = import(
            "gltf_bump_map_correction",
            r#"{ "extras": { "rt_bump_map_correction": false } }, { "extras": { "rt_bump_map_correction": true } }, {}"#,
        );
        let on: Vec<bool> = m.iter().map(|m| m.bump_map_correction).collect();
        assert_eq!(on, [false, true, true]);
    }

    #[test]
    fn iridescence_of_the_wrong_type_is_an_error() {
        let doc = r#"{ "asset": { "version": "2.0" }, "materials": [
            { "extensions": { "KHR_materials_iridescence": { "iridescenceFactor": 1, "iridescenceIor": "high" } } }] }"#;
        let gltf = gltf::Gltf::from_slice(doc.as_bytes()).expect("parses");
        let e = iridescence(&gltf.materials().next().expect("a material")).expect_err("refused");
        assert!(e.contains("KHR_materials_iridescence.iridescenceIor must be a number"), "{e}");
    }

    /// Sheen and anisotropy as Blender's glTF importer sets the Principled BSDF up: sheen weight
    /// 1 with the colour as its tint (default black) and the roughness factor (default 0);
    /// anisotropy strength, and rotation from radians to turns. rt's own extras win.
    #[test]
    fn sheen_and_anisotropy_are_imported_as_blender_imports_them() {
        let m = import(
            "gltf_sheen_anisotropy",
            r#"{ "extensions": { "KHR_materials_sheen": { "sheenColorFactor": [0.9, 0.5, 0.25], "sheenRoughnessFactor": 0.7 },
                                  "KHR_materials_anisotropy": { "anisotropyStrength": 0.6, "anisotropyRotation": 1.5707964 } } },
               { "extensions": { "KHR_materials_sheen": {}, "KHR_materials_anisotropy": { "anisotropyRotation": -1.5707964 } } },
               { "extensions": { "KHR_materials_sheen": { "sheenColorFactor": [1, 1, 1] } },
                 "extras": { "rt_sheen": 0.4, "rt_sheen_roughness": 0.2, "rt_sheen_tint": [0.5, 0.5, 0.5] } },
               {}"#,
        );
        let sheen = |m: &Material| (m.sheen, m.sheen_tint, m.sheen_roughness);
        assert_eq!(sheen(&m[0]), (1.0, [0.9, 0.5, 0.25], 0.7));
        assert!((m[0].anisotropy - 0.6).abs() < 1e-6 && (m[0].anisotropy_rotation - 0.25).abs() < 1e-6, "{:?}", m[0]);
        assert_eq!(sheen(&m[1]), (1.0, [0.0; 3], 0.0));
        assert!(m[1].anisotropy == 0.0 && (m[1].anisotropy_rotation - 0.75).abs() < 1e-6, "{:?}", m[1]);
        assert_eq!(sheen(&m[2]), (0.4, [0.5; 3], 0.2));
        assert_eq!((m[3].sheen, m[3].anisotropy), (0.0, 0.0));
    }

    /// Diffuse Roughness, which glTF has no field for, comes in rt's extras (clamped to [0, 1]).
    #[test]
    fn diffuse_roughness_is_read_from_the_extras() {
        let m = import(
            "gltf_diffuse_roughness",
            r#"{ "extras": { "rt_diffuse_roughness": 0.75 } }, { "extras": { "rt_diffuse_roughness": 3.0 } }, {}"#,
        );
        let roughness: Vec<f32> = m.iter().map(|m| m.diffuse_roughness).collect();
        assert_eq!(roughness, [0.75, 1.0, 0.0]);
    }

    #[test]
    fn glossy_is_the_tinted_specular_lobe_alone() {
        let base = Material { diffuse: 0.5, reflection: 0.5, roughness: 0.3, ..Material::default() };
        let m = glossy(base, [0.9, 0.5, 2.0]);
        assert_eq!((m.diffuse, m.specular, m.reflection, m.transmission), (0.0, 1.0, 0.0, 0.0));
        assert_eq!((m.specular_tint, m.specular_ior_level, m.roughness), ([0.9, 0.5, 1.0], 0.0, 0.3));
    }
}
