//! What rt reads of a glTF material beyond the `gltf` crate's model, as raw JSON (the crate
//! does not model them): `KHR_materials_clearcoat` and `KHR_materials_iridescence`; and rt's
//! own Glossy lobe (`extras.rt_glossy_color`). Textures of these extensions are not read:
//! their factors stand for them, with a warning naming the material.

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
/// no coat), which gltf leaves as raw JSON. Its textures are not read.
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

/// `KHR_materials_iridescence` as rt's thin film: thickness (nm) and index, or `None` for no
/// film (absent, or `iridescenceFactor` 0, glTF's default). rt's film is all or nothing: a
/// factor between 0 and 1 is rendered as 1, with a warning. Without a thickness texture the
/// film is `iridescenceThicknessMaximum` thick (glTF's defaults: 400 nm, index 1.3); a
/// texture is not read and the maximum stands for it.
pub(super) fn iridescence(m: &gltf::Material) -> Result<Option<(f32, f32)>, String> {
    const NAME: &str = "KHR_materials_iridescence";
    let Some(ext) = m.extension_value(NAME) else {
        return Ok(None);
    };
    let factor = number(ext, NAME, "iridescenceFactor", 0.0)?;
    if factor <= 0.0 {
        return Ok(None);
    }
    if factor < 1.0 {
        log::warn!(
            "{}: {NAME}.iridescenceFactor {factor} is rendered as 1 (rt's film has no weight)",
            material_name(m)
        );
    }
    warn_textures(m, ext, NAME, &["iridescenceTexture"], "iridescenceFactor");
    warn_textures(m, ext, NAME, &["iridescenceThicknessTexture"], "iridescenceThicknessMaximum");
    let thickness = number(ext, NAME, "iridescenceThicknessMaximum", 400.0)?.clamp(0.0, 100_000.0);
    let ior = number(ext, NAME, "iridescenceIor", 1.3)?.max(1.0);
    Ok(Some((thickness, ior)))
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

    fn import(name: &str, materials: &str) -> Vec<Material> {
        let dir = crate::asset::fixture::TempDir::new(name);
        let json = format!(r#"{{ "asset": {{ "version": "2.0" }}, "materials": [{materials}] }}"#);
        let mesh = crate::asset::gltf_import::load(&dir.write("m.gltf", &json)).expect("loads");
        mesh.materials.into_iter().map(|(_, m)| m).collect()
    }

    /// Iridescence is rt's thin film at the maximum thickness; factor 0 (glTF's default) is none,
    /// and absent fields take glTF's defaults (index 1.3, 400 nm).
    #[test]
    fn iridescence_is_imported_as_the_thin_film() {
        let m = import(
            "gltf_iridescence",
            r#"{ "extensions": { "KHR_materials_iridescence": { "iridescenceFactor": 1, "iridescenceIor": 1.45,
                  "iridescenceThicknessMinimum": 200, "iridescenceThicknessMaximum": 650 } } },
               { "extensions": { "KHR_materials_iridescence": { "iridescenceFactor": 0.5 } } },
               { "extensions": { "KHR_materials_iridescence": { "iridescenceIor": 1.8 } } },
               { "extensions": { "KHR_materials_iridescence": { "iridescenceFactor": 1,
                  "iridescenceThicknessTexture": { "index": 0 } } } },
               {}"#,
        );
        let film = |m: &Material| (m.thin_film_thickness, m.thin_film_ior);
        assert_eq!(film(&m[0]), (650.0, 1.45));
        assert_eq!(film(&m[1]), (400.0, 1.3));
        assert!(!m[2].has_thin_film());
        assert_eq!(film(&m[3]), (400.0, 1.3), "a thickness texture: its maximum");
        assert!(!m[4].has_thin_film());
    }

    #[test]
    fn iridescence_of_the_wrong_type_is_an_error() {
        let doc = r#"{ "asset": { "version": "2.0" }, "materials": [
            { "extensions": { "KHR_materials_iridescence": { "iridescenceFactor": 1, "iridescenceIor": "high" } } }] }"#;
        let gltf = gltf::Gltf::from_slice(doc.as_bytes()).expect("parses");
        let e = iridescence(&gltf.materials().next().expect("a material")).expect_err("refused");
        assert!(e.contains("KHR_materials_iridescence.iridescenceIor must be a number"), "{e}");
    }

    #[test]
    fn glossy_is_the_tinted_specular_lobe_alone() {
        let base = Material { diffuse: 0.5, reflection: 0.5, roughness: 0.3, ..Material::default() };
        let m = glossy(base, [0.9, 0.5, 2.0]);
        assert_eq!((m.diffuse, m.specular, m.reflection, m.transmission), (0.0, 1.0, 0.0, 0.0));
        assert_eq!((m.specular_tint, m.specular_ior_level, m.roughness), ([0.9, 0.5, 1.0], 0.0, 0.3));
    }
}
