//! glTF's sheen and anisotropy as Blender imports them: `tests/blender/gltf_extensions.py`
//! writes a glTF file with `KHR_materials_sheen` and `KHR_materials_anisotropy`, imports it
//! with Blender's own glTF importer and exports that with blender/rt_export.py. rt's import
//! of the file must give the Principled inputs Blender's import gave, and so must rt's import
//! of the export, with rt's extras and without them (the extensions alone). Needs
//! RT_BPY_PYTHON, a Python with `bpy`.

use crate::common;

use common::temp_dir;
use rt::scene::Material;
use serde_json::Value;
use std::path::Path;

fn materials(path: &Path) -> Vec<(String, Material)> {
    rt::asset::gltf_import::load(path).unwrap_or_else(|e| panic!("{e}")).materials
}

fn assert_as_blender(what: &str, m: &Material, blender: &Value) {
    let number = |key: &str| blender[key].as_f64().unwrap_or_else(|| panic!("{key} in {blender}")) as f32;
    let tint: Vec<f32> =
        blender["sheen_tint"].as_array().expect("a tint").iter().filter_map(|c| c.as_f64()).map(|c| c as f32).collect();
    let close = |a: f32, b: f32| (a - b).abs() < 1e-5;
    assert!(close(m.sheen, number("sheen")), "{what}: sheen {} vs Blender's {blender}", m.sheen);
    assert!(m.sheen_tint.iter().zip(&tint).all(|(a, b)| close(*a, *b)), "{what}: tint {:?} vs {blender}", m.sheen_tint);
    assert!(close(m.sheen_roughness, number("sheen_roughness")), "{what}: {} vs {blender}", m.sheen_roughness);
    assert!(close(m.anisotropy, number("anisotropy")), "{what}: anisotropy {} vs {blender}", m.anisotropy);
    // Rotations are turns: Blender keeps glTF's radians / 2π as they are (here negative), rt
    // within [0, 1). Without anisotropy there is no rotation to speak of.
    if m.anisotropy > 0.0 {
        let turn = (m.anisotropy_rotation - number("anisotropy_rotation") + 0.5).rem_euclid(1.0) - 0.5;
        assert!(turn.abs() < 1e-5, "{what}: rotation {} vs {blender}", m.anisotropy_rotation);
    }
    assert_eq!(blender["tangent_linked"], false, "{what}: Blender links no tangent without a texture");
}

#[test]
fn sheen_and_anisotropy_import_as_in_blender_and_survive_the_export() {
    let out = temp_dir("blender-gltf-extensions");
    common::run_bpy_script("gltf_extensions.py", &out);
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).expect("report")).expect("JSON");
    let names = ["sheen_anisotropy", "defaults"];
    let source = materials(&out.join("source.gltf"));
    for name in names {
        let blender = &report[name];
        let (_, m) = source.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("{name} in source.gltf"));
        assert_as_blender(&format!("{name}, rt's import"), m, blender);
        let exported = out.join(format!("assets/{name}/{name}.gltf"));
        assert_as_blender(&format!("{name}, the export"), &materials(&exported)[0].1, blender);
        // Without rt's extras: the extensions the exporter wrote, as another reader sees them.
        let mut json: Value =
            serde_json::from_str(&std::fs::read_to_string(&exported).expect("the export")).expect("JSON");
        for m in json["materials"].as_array_mut().expect("materials") {
            m.as_object_mut().expect("an object").remove("extras");
        }
        let bare = out.join(format!("{name}_bare.gltf"));
        std::fs::write(&bare, json.to_string()).expect("written");
        assert_as_blender(&format!("{name}, the export without extras"), &materials(&bare)[0].1, blender);
    }
}
