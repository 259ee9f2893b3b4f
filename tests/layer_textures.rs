//! The layered lobes' textures and the tangent as rt reads them from glTF: the clearcoat
//! textures of `KHR_materials_clearcoat`, `KHR_materials_specular`'s colour texture and rt's
//! own extras (what `blender/rt_export.py` writes for Principled's coat tint, sheen,
//! anisotropy and diffuse roughness sockets), `KHR_materials_iridescence`'s thickness
//! texture, `KHR_materials_transmission`'s and `KHR_materials_specular`'s textures, each in
//! its colour space, and the coat's own normal map (`clearcoatNormalTexture`); bad ones
//! refused naming the file and the material.

use crate::common;

use common::{temp_dir, write};
use rt::asset::load_mesh;
use rt::scene::Tangent;

/// A unit quad with uvs whose one material is `material` (JSON), with two textures (repeating,
/// clamped) of one 2 × 2 PNG beside it.
fn quad_gltf(material: &str) -> String {
    let mut bytes = Vec::new();
    [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .flatten()
        .for_each(|f| bytes.extend(f.to_le_bytes()));
    [[0.0f32, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]].iter().flatten().for_each(|f| bytes.extend(f.to_le_bytes()));
    [0u32, 1, 2, 0, 2, 3].iter().for_each(|i| bytes.extend(i.to_le_bytes()));
    format!(
        r#"{{
  "asset": {{ "version": "2.0" }}, "scene": 0, "scenes": [{{ "nodes": [0] }}], "nodes": [{{ "mesh": 0 }}],
  "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_specular", "KHR_materials_transmission",
    "KHR_materials_sheen", "KHR_materials_anisotropy"],
  "meshes": [{{ "primitives": [{{ "attributes": {{ "POSITION": 0, "TEXCOORD_0": 1 }}, "indices": 2, "material": 0 }}] }}],
  "materials": [{material}],
  "textures": [{{ "source": 0 }}, {{ "source": 0, "sampler": 0 }}],
  "samplers": [{{ "wrapS": 33071, "wrapT": 33071 }}],
  "images": [{{ "uri": "grey.png" }}],
  "buffers": [{{ "byteLength": {len}, "uri": "data:application/octet-stream;base64,{data}" }}],
  "bufferViews": [{{ "buffer": 0, "byteLength": 48 }}, {{ "buffer": 0, "byteOffset": 48, "byteLength": 32 }},
    {{ "buffer": 0, "byteOffset": 80, "byteLength": 24 }}],
  "accessors": [
    {{ "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0] }},
    {{ "bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2" }},
    {{ "bufferView": 2, "componentType": 5125, "count": 6, "type": "SCALAR" }}]
}}"#,
        len = bytes.len(),
        data = base64::encode(&bytes)
    )
}

fn load(name: &str, material: &str) -> Result<rt::asset::MeshData, String> {
    let dir = temp_dir(name);
    image::RgbaImage::from_pixel(2, 2, image::Rgba([128, 64, 32, 255]))
        .save(dir.join("grey.png"))
        .expect("writes the PNG");
    write(&dir.join("quad.gltf"), &quad_gltf(material));
    load_mesh(&dir.join("quad.gltf")).map_err(|e| e.to_string())
}

#[test]
fn layer_textures_and_the_tangent_are_read_in_their_colour_spaces() {
    let material = r#"{ "name": "layers",
      "extensions": {
        "KHR_materials_clearcoat": { "clearcoatFactor": 1, "clearcoatTexture": { "index": 0 },
                                     "clearcoatRoughnessTexture": { "index": 0 } },
        "KHR_materials_specular": { "specularColorTexture": { "index": 1 } } },
      "extras": { "rt_coat": 1, "rt_sheen": 1, "rt_anisotropy": 1, "rt_tangent": "radial_x",
                  "rt_coat_tint_texture": { "index": 1 }, "rt_sheen_texture": { "index": 0 },
                  "rt_sheen_tint_texture": { "index": 1 }, "rt_anisotropy_texture": { "index": 1, "texCoord": 0 } } }"#;
    let mesh = load("layer_textures_read", material).unwrap_or_else(|e| panic!("{e}"));
    let m = &mesh.materials[0].1;
    assert_eq!(m.tangent, Tangent::RadialX);
    let l = m.textures.layers;
    let srgb = |slot: Option<u32>| mesh.textures[slot.expect("a texture") as usize].srgb;
    // Data: coat weight and roughness, sheen, anisotropy; colour: the tints.
    assert!(!srgb(l.coat) && !srgb(l.coat_roughness) && !srgb(l.sheen) && !srgb(l.anisotropy), "{l:?}");
    assert!(srgb(l.coat_tint) && srgb(l.sheen_tint) && srgb(l.specular_tint), "{l:?}");
    // One image through two samplers, as data and as colour: one texture per use that differs.
    assert_eq!(l.coat, l.coat_roughness);
    assert_eq!(l.coat_tint, l.specular_tint);
    assert_ne!(l.anisotropy, l.coat_tint);
    assert_eq!(mesh.textures.len(), 3, "data of each sampler, colour of the second");
    assert_eq!(m.textures.second_uv_set, 0);
    assert!(m.textures.any() && !m.reads_tangents());
}

/// Diffuse roughness (rt's extras) and the film's thickness (`iridescenceThicknessTexture`,
/// its G between the extension's minimum and maximum) are data textures, the factor the
/// film's weight.
#[test]
fn diffuse_roughness_and_film_thickness_textures_are_read() {
    let material = r#"{ "name": "film",
      "extensions": { "KHR_materials_iridescence": { "iridescenceFactor": 0.5, "iridescenceThicknessMinimum": 150,
                      "iridescenceThicknessMaximum": 900, "iridescenceThicknessTexture": { "index": 0 } } },
      "extras": { "rt_diffuse_roughness": 1, "rt_diffuse_roughness_texture": { "index": 0 } } }"#;
    let mesh = load("layer_textures_film", material).unwrap_or_else(|e| panic!("{e}"));
    let m = &mesh.materials[0].1;
    let l = m.textures.layers;
    let srgb = |slot: Option<u32>| mesh.textures[slot.expect("a texture") as usize].srgb;
    assert!(!srgb(l.diffuse_roughness) && !srgb(l.thin_film_thickness), "{l:?}");
    assert_eq!((m.thin_film_thickness, m.textures.thin_film_minimum, m.thin_film_weight), (900.0, 150.0, 0.5));
    assert_eq!(m.diffuse_roughness, 1.0);
}

/// A transmission texture (R × the factor) leaves the weights of the part that does not
/// transmit, beside the metal's, and keeps the factor for the shader; the specular texture
/// (A × the level) is data.
#[test]
fn transmission_and_specular_level_textures_are_read() {
    let material = r#"{ "name": "glass",
      "pbrMetallicRoughness": { "metallicFactor": 0.25 },
      "extensions": { "KHR_materials_transmission": { "transmissionFactor": 0.8, "transmissionTexture": { "index": 0 } },
                      "KHR_materials_specular": { "specularTexture": { "index": 1 } } },
      "extras": { "rt_specular_ior_level": 1.0 } }"#;
    let mesh = load("layer_textures_transmission", material).unwrap_or_else(|e| panic!("{e}"));
    let m = &mesh.materials[0].1;
    let l = m.textures.layers;
    let srgb = |slot: Option<u32>| mesh.textures[slot.expect("a texture") as usize].srgb;
    assert!(!srgb(l.transmission) && !srgb(l.specular_level), "{l:?}");
    assert_eq!((m.reflection, m.diffuse, m.transmission), (0.25, 0.75, 0.0));
    assert_eq!((m.textures.transmission, m.specular_ior_level), (0.8, 1.0));
    assert!(m.may_transmit() && m.textures.layers.any());
    // Without the texture the factor is the weight, as before.
    let material = r#"{ "name": "plain", "pbrMetallicRoughness": { "metallicFactor": 0.25 },
      "extensions": { "KHR_materials_transmission": { "transmissionFactor": 0.8 } } }"#;
    let mesh = load("layer_textures_transmission_factor", material).unwrap_or_else(|e| panic!("{e}"));
    let m = &mesh.materials[0].1;
    assert!((m.transmission - 0.6).abs() < 1e-6 && (m.diffuse - 0.15).abs() < 1e-6, "{m:?}");
}

/// glTF's sheen and anisotropy textures fill rt's slots: the grey texel (128, 64, 32, 255)
/// is a sheen roughness of A = 1, re-encoded into the G that rt's sheen slot reads (R, the
/// weight, 1); the anisotropy texture keeps its directions, marked as such for the shader.
/// The tangent becomes the uv map's, as Blender's importer links it.
#[test]
fn sheen_and_anisotropy_textures_of_the_extensions_are_read() {
    let material = r#"{ "name": "brushed",
      "extensions": { "KHR_materials_sheen": { "sheenColorFactor": [1, 1, 1], "sheenColorTexture": { "index": 0 },
                                                "sheenRoughnessFactor": 0.5, "sheenRoughnessTexture": { "index": 0 } },
                      "KHR_materials_anisotropy": { "anisotropyStrength": 1, "anisotropyTexture": { "index": 0 } } } }"#;
    let mesh = load("layer_textures_extensions", material).unwrap_or_else(|e| panic!("{e}"));
    let m = &mesh.materials[0].1;
    let l = m.textures.layers;
    let first = |slot: Option<u32>| {
        let t = &mesh.textures[slot.expect("a texture") as usize];
        (t.srgb, t.texels[0].to_le_bytes())
    };
    assert_eq!(first(l.sheen_tint), (true, [128, 64, 32, 255]));
    assert_eq!(first(l.sheen), (false, [255, 255, 0, 255]));
    assert_eq!(first(l.anisotropy), (false, [128, 64, 32, 255]));
    assert!(m.textures.anisotropy_directions);
    assert_eq!((m.sheen, m.sheen_roughness, m.anisotropy, m.tangent), (1.0, 0.5, 1.0, Tangent::Uv));
    assert!(m.reads_uv_tangents());
}

/// The indices' texture (rt's extras): each index from its minimum at 0 to the material's
/// own at 1; a minimum left out is the material's own (that channel is not driven).
#[test]
fn the_indices_texture_and_its_minimums_are_read() {
    let material = r#"{ "name": "lens",
      "extensions": { "KHR_materials_ior": { "ior": 2.5 } },
      "extras": { "rt_coat": 1, "rt_coat_ior": 2.2, "rt_ior_texture": { "index": 0 }, "rt_ior_minimum": 1.1 } }"#;
    let mesh = load("layer_textures_ior", material).unwrap_or_else(|e| panic!("{e}"));
    let m = &mesh.materials[0].1;
    assert!(!mesh.textures[m.textures.layers.ior.expect("a texture") as usize].srgb);
    assert_eq!((m.ior, m.coat_ior), (2.5, 2.2));
    assert_eq!(m.textures.ior_minimum, [1.1, 2.2, m.thin_film_ior]);
    let material = r#"{ "name": "bad", "extras": { "rt_ior_texture": { "index": 0 }, "rt_ior_minimum": "low" } }"#;
    let e = load("layer_textures_ior_bad", material).expect_err("refused");
    assert!(e.contains("material `bad`") && e.contains("rt_ior_minimum"), "{e}");
}

#[test]
fn a_layer_texture_that_is_not_there_is_refused() {
    let material = r#"{ "name": "missing", "extras": { "rt_sheen": 1, "rt_sheen_texture": { "index": 7 } } }"#;
    let e = load("layer_textures_missing", material).expect_err("refused");
    assert!(e.contains("material `missing`") && e.contains("sheen: no texture 7 (the file has 2)"), "{e}");
    let material = r#"{ "name": "bent", "extras": { "rt_tangent": "radial_q" } }"#;
    let e = load("layer_textures_bad_tangent", material).expect_err("refused");
    assert!(e.contains("material `bent`") && e.contains("extras.rt_tangent is \"radial_q\"; did you mean"), "{e}");
}

/// The coat's normal map: linear data with its scale and its own uv transform, beside a base
/// normal map of another scale; the quad gets MikkTSpace tangents for it.
#[test]
fn the_clearcoat_normal_texture_is_the_coats_own_normal_map() {
    let material = r#"{ "name": "paint", "normalTexture": { "index": 1, "scale": 2 },
      "extensions": { "KHR_materials_clearcoat": { "clearcoatFactor": 1,
        "clearcoatNormalTexture": { "index": 0, "scale": 0.5,
          "extensions": { "KHR_texture_transform": { "scale": [4, 4] } } } } } }"#;
    let mesh = load("layer_textures_coat_normal", material).unwrap_or_else(|e| panic!("{e}"));
    let m = &mesh.materials[0].1;
    let t = &m.textures;
    let coat_normal = t.coat_normal.expect("a coat normal map") as usize;
    assert_eq!((t.coat_normal_scale, t.normal_scale), (0.5, 2.0));
    assert!(!mesh.textures[coat_normal].srgb);
    let [u_row, v_row] = mesh.textures[coat_normal].uv_transform;
    assert_eq!((u_row[0], v_row[1]), (4.0, 4.0), "its own KHR_texture_transform");
    assert_ne!(t.coat_normal, t.normal, "another texture, another transform");
    assert!(m.has_own_coat_normal() && m.reads_tangents());
    assert!(mesh.tangents.is_some(), "tangents for the normal maps");

    // Alone, without a base normal map: the coat's still needs tangents.
    let material = r#"{ "name": "coat_only", "extensions": { "KHR_materials_clearcoat": { "clearcoatFactor": 1,
        "clearcoatNormalTexture": { "index": 0 } } } }"#;
    let mesh = load("layer_textures_coat_normal_only", material).unwrap_or_else(|e| panic!("{e}"));
    let m = &mesh.materials[0].1;
    assert_eq!((m.textures.normal, m.textures.coat_normal_scale), (None, 1.0), "glTF's default scale");
    assert!(m.has_own_coat_normal() && mesh.tangents.is_some());
}

#[test]
fn a_bad_clearcoat_normal_texture_is_refused_naming_the_file() {
    let material = r#"{ "name": "flakes", "extensions": { "KHR_materials_clearcoat": { "clearcoatFactor": 1,
        "clearcoatNormalTexture": { "index": 9 } } } }"#;
    let e = load("layer_textures_coat_normal_missing", material).expect_err("refused");
    assert!(
        e.contains("quad.gltf")
            && e.contains("material `flakes`")
            && e.contains("KHR_materials_clearcoat.clearcoatNormalTexture: no texture 9 (the file has 2)"),
        "{e}"
    );
    let material = r#"{ "name": "flakes", "extensions": { "KHR_materials_clearcoat": { "clearcoatFactor": 1,
        "clearcoatNormalTexture": { "index": 0, "scale": "strong" } } } }"#;
    let e = load("layer_textures_coat_normal_scale", material).expect_err("refused");
    assert!(e.contains("clearcoatNormalTexture.scale must be a number, got \"strong\""), "{e}");
}
