//! Unit tests of the lobe modules' registry: scene files and glTF extras read by the
//! declarations, the shader file made from them, and the exporter's copy of the table.

use super::*;
use std::path::Path;

fn material(toml: &str) -> Result<crate::scene::Material, String> {
    let text = format!("[materials.m]\n{toml}\n[[sphere]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n");
    let scene = crate::scene::parse(&text, "scene.toml", Path::new(".")).map_err(|e| e.to_string())?;
    Ok(scene.materials.into_iter().find(|(name, _)| name == "m").map(|(_, m)| m).expect("the material"))
}

#[test]
fn a_scene_files_lobe_takes_its_declared_parameters() {
    let m = material("lobe = { module = \"toon\", size = 0.25, component = \"glossy\" }").expect("parses");
    let lobe = m.lobe.expect("a lobe");
    assert_eq!(lobe.declaration().name, "toon");
    // Smooth left out takes its default; values beyond a range are clamped, as Cycles clamps.
    assert_eq!(lobe.params, [0.25, 0.0, 1.0, 0.0]);
    let m = material("lobe = { module = \"toon\", size = 3, smooth = -1 }").expect("parses");
    assert_eq!(m.lobe.expect("a lobe").params, [1.0, 0.0, 0.0, 0.0]);
    assert_eq!(material("").expect("parses").lobe, None);
}

#[test]
fn a_wrong_lobe_is_named_with_its_place() {
    for (toml, expected) in [
        ("lobe = { module = \"cartoon\" }", "lobe: no module `cartoon` (rt has toon)"),
        ("lobe = { size = 0.5 }", "lobe: `module` is missing (toon)"),
        ("lobe = { module = \"toon\", sise = 0.5 }", "lobe toon: no parameter `sise` (it has size, smooth, component)"),
        (
            "lobe = { module = \"toon\", component = \"shiny\" }",
            "lobe toon: component: no choice `shiny` (one of diffuse, glossy)",
        ),
        ("lobe = { module = \"toon\", size = \"big\" }", "lobe toon: size: must be a finite number"),
    ] {
        let error = material(toml).expect_err(toml);
        assert!(error.starts_with("scene.toml:2:"), "{error}");
        assert!(error.contains(expected), "{toml}: {error}");
    }
}

#[test]
fn gltf_extras_read_as_scene_files_do() {
    let lobe: ModuleLobe =
        serde_json::from_str(r#"{"module": "toon", "size": 0.4, "smooth": 0.1, "component": "diffuse"}"#)
            .expect("reads");
    assert_eq!(lobe.params, [0.4, 0.1, 0.0, 0.0]);
    assert_eq!(ModuleLobe::from_number(ModuleLobe::number(Some(&lobe)), lobe.params), Some(lobe));
    assert_eq!(ModuleLobe::from_number(0, [0.0; MAX_PARAMS]), None);
    assert_eq!(ModuleLobe::from_number(LOBES.len() as u32 + 1, [0.0; MAX_PARAMS]), None);
}

#[test]
fn every_module_declares_what_the_shaders_and_the_gpu_material_hold() {
    for lobe in LOBES {
        assert!(lobe.params.len() <= MAX_PARAMS, "{}: {} parameters", lobe.name, lobe.params.len());
        for function in ["eval", "pdf", "sample"] {
            assert!(lobe.wgsl.1.contains(&format!("fn {}_{function}(", lobe.name)), "{} lacks {function}", lobe.wgsl.0);
        }
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders").join(lobe.wgsl.0);
        assert!(file.is_file(), "{}: `rt watch --dev` reads it from shaders/", file.display());
    }
    assert_eq!(crate::layout::GpuMaterial::default().lobe_params.len(), MAX_PARAMS);
    let code = wgsl();
    assert!(code.contains("fn toon_size(m: Material) -> f32 { return m.lobe_params.x; }"), "{code}");
    assert!(code.contains("const TOON_COMPONENT_GLOSSY: f32 = 1.0;"), "{code}");
}

/// The exporter reads `blender/rt_blender/rt_lobes.json`; it must be this registry's table.
/// `RT_WRITE_LOBES=1 cargo test -p rt exporters_table` rewrites it after a module changes.
#[test]
fn the_exporters_table_is_the_registry() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../blender/rt_blender/rt_lobes.json");
    let table = serde_json::to_string_pretty(&exporter_table()).expect("serialises") + "\n";
    if std::env::var_os("RT_WRITE_LOBES").is_some() {
        std::fs::write(&path, &table).expect("writes the table");
    }
    let written = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(written == table, "{} is stale: run RT_WRITE_LOBES=1 cargo test -p rt exporters_table", path.display());
}
