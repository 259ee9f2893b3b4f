//! What rt reads of a glTF material beyond the `gltf` crate's model: `KHR_materials_clearcoat`
//! (raw JSON: the crate does not model it) and rt's own Glossy lobe (`extras.rt_glossy_color`).

use crate::scene::Material;

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
    let factor = |key: &str| -> Result<f32, String> {
        match ext.get(key) {
            None => Ok(0.0),
            Some(v) => v
                .as_f64()
                .filter(|f| f.is_finite())
                .map(|f| f as f32)
                .ok_or_else(|| format!("KHR_materials_clearcoat.{key} must be a number, got {v}")),
        }
    };
    Ok(Clearcoat { factor: factor("clearcoatFactor")?, roughness: factor("clearcoatRoughnessFactor")? })
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

    #[test]
    fn glossy_is_the_tinted_specular_lobe_alone() {
        let base = Material { diffuse: 0.5, reflection: 0.5, roughness: 0.3, ..Material::default() };
        let m = glossy(base, [0.9, 0.5, 2.0]);
        assert_eq!((m.diffuse, m.specular, m.reflection, m.transmission), (0.0, 1.0, 0.0, 0.0));
        assert_eq!((m.specular_tint, m.specular_ior_level, m.roughness), ([0.9, 0.5, 1.0], 0.0, 0.3));
    }
}
