//! Blender → rt for textures on a second uv map and for `--bake`: `tests/blender/uv_sets_bake.py`
//! exports scenes of `tests/cycles/make_texture_refs.py` with blender/rt_export.py. Needs
//! RT_BPY_PYTHON, a Python with `bpy`.

use crate::common;

use common::{bpy_python, repo, temp_dir};
use rt::asset::load_mesh;
use serde_json::Value;
use std::process::Command;

#[test]
fn the_exporter_writes_second_uv_maps_and_bakes_procedural_sockets() {
    let out = temp_dir("blender-uv-sets-bake");
    let result = Command::new(bpy_python())
        .arg(repo().join("tests/blender/uv_sets_bake.py"))
        .arg(&out)
        .output()
        .expect("bpy runs");
    let log = String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{log}");
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).expect("report")).expect("JSON");

    // The base colour reads the UV Map node's map (the mesh's second set), the roughness the default one.
    let mesh = load_mesh(&out.join("uv_sets/assets/Plane")).unwrap_or_else(|e| panic!("{e}"));
    let textures = &mesh.materials[0].1.textures;
    assert!(textures.reads_second_uv_set(0) && !textures.reads_second_uv_set(1), "{textures:?}");
    let (first, second) = (mesh.uvs.expect("uvs"), mesh.second_uvs.expect("the second uv map"));
    assert!(first.iter().zip(&second).any(|(a, b)| a != b), "the two maps differ");

    // Baked: the noise is a base colour texture that varies; the node tree is as it was.
    let baked = load_mesh(&out.join("baked/assets/Plane")).unwrap_or_else(|e| panic!("{e}"));
    let index = baked.materials[0].1.textures.base_color.expect("a baked base colour texture") as usize;
    let image = &baked.textures[index];
    assert_eq!((image.width, image.height), (32, 32));
    let reds: Vec<u8> = image.texels[..32 * 32].iter().map(|t| t.to_le_bytes()[0]).collect();
    assert!(reds.iter().max() > reds.iter().min(), "the bake is not a constant");
    assert_eq!(report["before"], report["after"], "the bake leaves the node tree as it was");
    assert!(log.contains("noise: baked Base Color (TEX_NOISE) into 32x32 texels"), "{log}");
    // Without --bake the socket keeps its own value, with the warning.
    let unbaked = load_mesh(&out.join("unbaked/assets/Plane")).unwrap_or_else(|e| panic!("{e}"));
    assert!(unbaked.materials[0].1.textures.base_color.is_none());
    assert!(log.contains("Base Color is linked to TEX_NOISE, which rt cannot follow"), "{log}");
}
