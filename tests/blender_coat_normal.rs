//! The exporter's Coat Normal: `tests/blender/coat_normal_export.py` builds coated materials
//! in bpy and exports them with blender/rt_export.py. One Normal Map node into Normal and
//! Coat Normal is one texture in both glTF slots (the coat shares the base's normal); a
//! Normal Map node into Coat Normal alone is `clearcoatNormalTexture` with its strength as
//! the scale; a Bump node there is warned about, naming the material and the node. A coat's
//! normal map on another uv set than the base's is oriented by the base's set's tangents (a
//! triangle carries one frame): rt warns about it when it loads the mesh, and not about a
//! coat weight texture on the second set, which needs no tangents. Needs RT_BPY_PYTHON, a
//! Python with `bpy`.

use crate::common;

use serde_json::Value;
use std::path::Path;
use std::process::Command;

/// What `rt pack` of the asset folder `folder` prints, after checking that it succeeds.
fn pack_log(folder: &Path) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_rt")).arg("pack").arg(folder).output().expect("run rt");
    let log = String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{log}");
    log
}

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

    // The base's map on the default uv map, the coat's on the second: each texture names its
    // set, and rt says whose tangents orient the coat's.
    let two = gltf("two_sets");
    let coat = &two["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"];
    assert_eq!((coat["texCoord"].as_u64(), two["normalTexture"].get("texCoord")), (Some(1), None), "{two}");
    let log = pack_log(&out.join("assets/two_sets"));
    let needle = "material \"two_sets\" has normal maps on two uv sets (the base's and the coat's); \
                  the coat's map is oriented by the base's set's tangents";
    assert!(log.contains("WARN") && log.contains(needle), "{needle:?} missing from:\n{log}");
    // A coat weight texture on the second set beside the base's map: read there, no warning.
    let weight = gltf("weight_on_second");
    assert_eq!(weight["extensions"]["KHR_materials_clearcoat"]["clearcoatTexture"]["texCoord"].as_u64(), Some(1));
    let log = pack_log(&out.join("assets/weight_on_second"));
    assert!(!log.contains("WARN"), "{log}");
    assert!(!stderr.contains("two_sets") && !stderr.contains("weight_on_second"), "{stderr}");
    let _ = std::fs::remove_dir_all(&out);
}
