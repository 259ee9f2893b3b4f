//! The exporter's Coat Normal: `tests/blender/coat_normal_export.py` builds coated materials
//! in bpy and exports them with blender/rt_export.py. One Normal Map node into Normal and
//! Coat Normal is one texture in both glTF slots (the coat shares the base's normal); a
//! Normal Map node into Coat Normal alone is `clearcoatNormalTexture` with its strength as
//! the scale; a Bump node there is warned about, naming the material and the node. Needs
//! RT_BPY_PYTHON, a Python with `bpy`.

use crate::common;

use serde_json::Value;

#[test]
fn coat_normal_exports_as_the_clearcoat_normal_texture() {
    let out = common::empty_temp_dir("blender-coat-normal");
    let stderr = common::run_bpy_script("coat_normal_export.py", &out);
    let gltf = |name: &str| -> Value {
        let file = out.join(format!("assets/{name}/{name}.gltf"));
        let text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        serde_json::from_str::<Value>(&text).expect("JSON")["materials"][0].clone()
    };
    let load = |name: &str| {
        let mesh = rt::asset::load_mesh(&out.join(format!("assets/{name}"))).unwrap_or_else(|e| panic!("{e}"));
        mesh.materials[0].1.clone()
    };

    let shared = gltf("shared");
    let coat = &shared["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"];
    assert_eq!(coat, &shared["normalTexture"], "{shared}");
    let m = load("shared");
    assert_eq!((m.textures.coat_normal, m.textures.coat_normal_scale), (m.textures.normal, 0.8));
    assert!(m.textures.normal.is_some() && !m.has_own_coat_normal(), "{m:?}");

    let own = gltf("own");
    assert!(own.get("normalTexture").is_none(), "{own}");
    let coat = &own["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"];
    assert!((coat["scale"].as_f64().expect("a scale") - 0.6).abs() < 1e-6, "{own}");
    let m = load("own");
    assert!(m.textures.normal.is_none() && m.textures.coat_normal.is_some() && m.has_own_coat_normal(), "{m:?}");

    let bumped = gltf("bumped");
    assert!(bumped["extensions"]["KHR_materials_clearcoat"].get("clearcoatNormalTexture").is_none(), "{bumped}");
    let needle =
        "bumped: Coat Normal is linked to BUMP, which rt cannot follow; the coat takes the interpolated normal";
    assert!(stderr.contains(needle), "{needle:?} missing from:\n{stderr}");
    let _ = std::fs::remove_dir_all(&out);
}
