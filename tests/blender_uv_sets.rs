//! Blender → rt for textures on a second uv map and for `--bake`: `tests/blender/uv_sets_bake.py`
//! exports scenes of `tests/cycles/make_texture_refs.py` with blender/rt_export.py. Needs
//! RT_BPY_PYTHON, a Python with `bpy`.

use crate::common;

use common::temp_dir;
use rt::asset::load_mesh;
use serde_json::Value;
use std::path::Path;

#[test]
fn the_exporter_writes_second_uv_maps_and_bakes_procedural_sockets() {
    let out = temp_dir("blender-uv-sets-bake");
    let log = common::run_bpy_script("uv_sets_bake.py", &out);
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).expect("report")).expect("JSON");
    second_uv_maps_and_mappings(&out, &log);
    graphs_are_not_baked(&out, &log);
    procedural_sockets_are_baked(&out, &log, &report);
    bumps_are_baked_into_normal_maps(&out, &log, &report);
}

fn load(out: &Path, scene: &str) -> rt::asset::MeshData {
    load_mesh(&out.join(scene).join("assets/Plane")).unwrap_or_else(|e| panic!("{e}"))
}

/// The red channel of a baked 32 × 32 texture.
fn reds(texels: &[u32]) -> Vec<u8> {
    texels[..32 * 32].iter().map(|t| t.to_le_bytes()[0]).collect()
}

fn second_uv_maps_and_mappings(out: &Path, log: &str) {
    // The base colour reads the UV Map node's map (the mesh's second set), the roughness the default one.
    let mesh = load(out, "uv_sets");
    let textures = &mesh.materials[0].1.textures;
    assert!(textures.reads_second_uv_set(0) && !textures.reads_second_uv_set(1), "{textures:?}");
    let (first, second) = (mesh.uvs.expect("uvs"), mesh.second_uvs.expect("the second uv map"));
    assert!(first.iter().zip(&second).any(|(a, b)| a != b), "the two maps differ");

    // Two Mapping nodes on one uv map: each texture its own transform, Blender's Mapping
    // (rotation · scale + location) as rt reads it; the uvs as Blender has them (the plane's 0 and 1).
    let mapped = load(out, "mappings");
    let textures = &mapped.materials[0].1.textures;
    let transform = |slot: Option<u32>| mapped.textures[slot.expect("a texture") as usize].uv_transform;
    let (s, c) = 20f32.to_radians().sin_cos();
    let cases = [
        (transform(textures.base_color), [[1.5 * c, -1.5 * s, 0.1], [1.5 * s, 1.5 * c, 0.2]]),
        (transform(textures.metallic_roughness), [[4.0, 0.0, 0.0], [0.0, 4.0, 0.0]]),
    ];
    for (got, want) in cases {
        let close = got.iter().flatten().zip(want.iter().flatten()).all(|(a, b)| (a - b).abs() < 1e-5);
        assert!(close, "{got:?}, expected {want:?}");
    }
    let uvs = mapped.uvs.expect("uvs");
    assert!(uvs.iter().flatten().all(|&x| x == 0.0 || x == 1.0), "{uvs:?}");
    assert!(!log.contains("different Mapping nodes"), "{log}");
}

fn graphs_are_not_baked(out: &Path, log: &str) {
    // A Noise Texture into Base Color is a node graph rt evaluates: nothing baked, nothing warned.
    let graph = load(out, "graph");
    assert!(graph.materials[0].1.textures.base_color.is_none());
    assert!(!graph.materials[0].1.node_program.is_empty(), "the noise is a node program");
    // The log's bakes are the turned noise's below (a plane and its instances): none is the graph's.
    assert_eq!(log.matches("noise: baked Base Color (TEX_NOISE)").count(), 2, "{log}");
    assert_eq!(log.matches("linked to TEX_NOISE").count(), 1, "only the unbaked export warns: {log}");

    // A Bump node fed by the noise into Normal is a node graph rt evaluates: nothing baked.
    let bump_graph = load(out, "bump_graph");
    let material = &bump_graph.materials[0].1;
    assert!(material.textures.normal.is_none() && bump_graph.textures.is_empty(), "the Bump's graph is not baked");
    assert!(rt::asset::node_program::drives(&material.node_program, "normal"), "the graph sets the normal");
}

fn procedural_sockets_are_baked(out: &Path, log: &str, report: &Value) {
    // Baked: the turned noise is a base colour texture that varies; the node tree is as it was.
    let baked = load(out, "baked");
    let index = baked.materials[0].1.textures.base_color.expect("a baked base colour texture") as usize;
    let image = &baked.textures[index];
    assert_eq!((image.width, image.height), (32, 32));
    let red = reds(&image.texels);
    assert!(red.iter().max() > red.iter().min(), "the bake is not a constant");
    assert_eq!(report["before"], report["after"], "the bake leaves the node tree as it was");
    assert!(log.contains("noise: baked Base Color (TEX_NOISE) into 32x32 texels"), "{log}");
    // Without --bake the socket keeps its own value, with the warning.
    let unbaked = load(out, "unbaked");
    assert!(unbaked.materials[0].1.textures.base_color.is_none());
    assert!(log.contains("Base Color is linked to TEX_NOISE, which rt cannot follow"), "{log}");

    // Seen only through collection instances (its own collection excluded), the plane is
    // baked on a stand-in object, which is gone afterwards.
    let instanced = load(out, "instanced");
    let index = instanced.materials[0].1.textures.base_color.expect("the instanced plane's baked base colour");
    let red = reds(&instanced.textures[index as usize].texels);
    assert!(red.iter().max() > red.iter().min(), "the instances' bake is not a constant");
    let objects = report["objects_after_instanced_bake"].as_array().expect("object names");
    assert!(objects.iter().all(|o| !o.as_str().unwrap_or("").starts_with("rt_bake")), "{objects:?}");
}

fn bumps_are_baked_into_normal_maps(out: &Path, log: &str, report: &Value) {
    // A Bump node fed by a Gabor Texture into Normal: Cycles' NORMAL pass in tangent space becomes
    // a normal map of strength 1 that tilts the normal (x and y away from 0.5 somewhere),
    // facing out (z above 0.5 everywhere); the node tree is as it was.
    let bumped = load(out, "bump");
    let textures = &bumped.materials[0].1.textures;
    let index = textures.normal.expect("a baked normal map") as usize;
    assert_eq!(textures.normal_scale, 1.0);
    let texels: Vec<[u8; 4]> = bumped.textures[index].texels[..32 * 32].iter().map(|t| t.to_le_bytes()).collect();
    let tilted = texels.iter().filter(|t| t[0].abs_diff(128) > 8 || t[1].abs_diff(128) > 8).count();
    assert!(tilted > 32, "only {tilted} of 1024 texels are tilted");
    assert!(texels.iter().all(|t| t[2] > 128), "a baked normal points into the surface");
    assert_eq!(report["bump_before"], report["bump_after"], "the normal bake leaves the node tree as it was");
    assert!(log.contains("noise: baked Normal (BUMP) into 32x32 texels"), "{log}");
}
