//! Special files as inputs: a FIFO (which blocks an open or read forever) or a device
//! (`/dev/zero` never ends) given as a scene, an asset, an `.mtl`, a glTF buffer, a BVH
//! cache, or lying in a folder given to `rt pack`, is refused by name (or skipped in a
//! folder) at once, within a small memory bound, with no panic and nothing left behind.

mod common;

use common::bounded::{fresh_dir, mkfifo, names, rt};
use std::os::unix::fs::symlink;
use std::path::Path;
use std::time::Duration;

/// Long enough for a lavapipe start; a blocked read never finishes at all.
const DEADLINE: Duration = Duration::from_secs(60);
/// A refused input costs what rt costs to start: far below a read of /dev/zero.
const MEMORY_MIB: f64 = 150.0;

const TRIANGLE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).expect("write test file");
}

#[test]
fn a_fifo_or_device_as_the_scene_is_refused() {
    let dir = fresh_dir("scene");
    mkfifo(&dir.join("fifo.toml"));
    symlink("/dev/zero", dir.join("zero.toml")).expect("link");
    rt(&dir, &["render", "fifo.toml", "-o", "out.png"], DEADLINE)
        .expect("FIFO scene", 1)
        .says("FIFO scene", &["error: fifo.toml: is a FIFO, not a file"])
        .peak_below("FIFO scene", MEMORY_MIB);
    rt(&dir, &["render", "zero.toml", "-o", "out.png"], DEADLINE)
        .expect("/dev/zero scene", 1)
        .says("/dev/zero scene", &["error: zero.toml: is a character device, not a file"])
        .peak_below("/dev/zero scene", MEMORY_MIB);
    rt(&dir, &["watch", "--headless", "--frames-dir", "frames", "fifo.toml"], DEADLINE)
        .expect("FIFO watched scene", 1)
        .says("FIFO watched scene", &["fifo.toml: is a FIFO, not a file"]);
    assert_eq!(names(&dir), ["fifo.toml", "frames", "zero.toml"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn a_fifo_or_device_as_an_asset_is_refused() {
    let dir = fresh_dir("asset");
    mkfifo(&dir.join("fifo.obj"));
    symlink("/dev/zero", dir.join("zero.glb")).expect("link");
    rt(&dir, &["pack", "fifo.obj"], DEADLINE)
        .expect("FIFO .obj", 1)
        .says("FIFO .obj", &["error: fifo.obj: is a FIFO, not a file"])
        .peak_below("FIFO .obj", MEMORY_MIB);
    rt(&dir, &["pack", "zero.glb"], DEADLINE)
        .expect("/dev/zero .glb", 1)
        .says("/dev/zero .glb", &["error: zero.glb: is a character device, not a file"])
        .peak_below("/dev/zero .glb", MEMORY_MIB);
    // Through a scene, as a render meets it.
    write(&dir, "scene.toml", "[[mesh]]\nasset = \"fifo.obj\"\n");
    rt(&dir, &["render", "scene.toml", "--size", "8x8", "--spp", "1", "-o", "out.png"], DEADLINE)
        .expect("FIFO asset of a scene", 1)
        .says("FIFO asset of a scene", &["fifo.obj: is a FIFO, not a file"]);
    assert_eq!(names(&dir), ["fifo.obj", "scene.toml", "zero.glb"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn a_fifo_or_device_as_a_material_library_or_buffer_is_refused() {
    let dir = fresh_dir("sidecars");
    write(&dir, "m.obj", &format!("mtllib m.mtl\n{TRIANGLE_OBJ}"));
    mkfifo(&dir.join("m.mtl"));
    rt(&dir, &["pack", "m.obj"], DEADLINE)
        .expect("FIFO .mtl", 1)
        .says("FIFO .mtl", &["m.mtl: is a FIFO, not a file"])
        .peak_below("FIFO .mtl", MEMORY_MIB);

    let gltf =
        |uri: &str| format!(r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": 36, "uri": "{uri}"}}]}}"#);
    write(&dir, "fifo.gltf", &gltf("fifo.bin"));
    mkfifo(&dir.join("fifo.bin"));
    rt(&dir, &["pack", "fifo.gltf"], DEADLINE)
        .expect("FIFO .bin", 1)
        .says("FIFO .bin", &["fifo.bin: is a FIFO, not a file"])
        .peak_below("FIFO .bin", MEMORY_MIB);
    write(&dir, "zero.gltf", &gltf("file:///dev/zero"));
    rt(&dir, &["pack", "zero.gltf"], DEADLINE)
        .expect("/dev/zero buffer", 1)
        .says("/dev/zero buffer", &["zero.gltf: /dev/zero: is a character device, not a file"])
        .peak_below("/dev/zero buffer", MEMORY_MIB);
    assert_eq!(names(&dir), ["fifo.bin", "fifo.gltf", "m.mtl", "m.obj", "zero.gltf"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn a_fifo_as_a_bvh_cache_is_neither_read_nor_replaced() {
    let dir = fresh_dir("cache");
    write(&dir, "m.obj", TRIANGLE_OBJ);
    mkfifo(&dir.join("m.rtbvh"));
    rt(&dir, &["pack", "m.obj"], DEADLINE)
        .expect("FIFO cache", 1)
        .says("FIFO cache", &["m.rtbvh: is a FIFO, not a file: rt replaces only files"])
        .peak_below("FIFO cache", MEMORY_MIB);
    // A render does without the cache: the BVH stays in memory.
    write(&dir, "scene.toml", "[camera]\nposition = [0.3, 0.3, 2.0]\n[[mesh]]\nasset = \"m.obj\"\n");
    rt(&dir, &["render", "scene.toml", "--size", "8x8", "--spp", "1", "-o", "out.png"], DEADLINE)
        .expect("FIFO cache in a render", 0)
        .says("FIFO cache in a render", &["m.rtbvh: invalid: is a FIFO, not a file; rebuilding it"])
        .says("FIFO cache in a render", &["the BVH stays in memory only"]);
    assert!(!std::fs::metadata(dir.join("m.rtbvh")).expect("cache").is_file(), "the FIFO is still there");
    assert_eq!(names(&dir), ["m.obj", "m.rtbvh", "out.png", "scene.toml"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn special_files_in_a_packed_folder_are_skipped() {
    let dir = fresh_dir("folder");
    std::fs::create_dir_all(dir.join("assets")).expect("folder");
    write(&dir, "assets/good.obj", TRIANGLE_OBJ);
    mkfifo(&dir.join("assets/pipe.obj"));
    symlink("/dev/zero", dir.join("assets/zero.glb")).expect("link");
    let outcome = rt(&dir, &["pack", "assets"], DEADLINE);
    outcome
        .expect("folder with special files", 0)
        .says("folder with special files", &["assets/pipe.obj: skipped: a FIFO, not a file"])
        .says("folder with special files", &["assets/zero.glb: skipped: a character device, not a file"])
        .peak_below("folder with special files", MEMORY_MIB);
    assert!(outcome.stdout.contains("assets/good.obj: packed 1 triangles"), "{}", outcome.stdout);
    assert_eq!(names(&dir.join("assets")), ["good.obj", "good.rtbvh", "pipe.obj", "zero.glb"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

/// Images go through the same opener: a FIFO or a device as the world's environment
/// image or as a texture is refused by name (it once hung rt for ever).
#[test]
fn a_fifo_or_device_as_an_environment_or_texture_image_is_refused() {
    let dir = fresh_dir("images");
    mkfifo(&dir.join("sky.hdr"));
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.exr")).expect("link");
    let scene = |image: &str| {
        format!(
            "[camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\n\n[sky]\nkind = \"environment\"\n\
             image = \"{image}\"\n\n[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\n"
        )
    };
    write(&dir, "fifo.toml", &scene("sky.hdr"));
    write(&dir, "zero.toml", &scene("zero.exr"));
    for (file, says) in
        [("fifo.toml", "sky.hdr: is a FIFO, not a file"), ("zero.toml", "zero.exr: is a character device")]
    {
        rt(&dir, &["render", file, "-o", "out.png", "--size", "8x8", "--spp", "1"], DEADLINE)
            .expect(file, 1)
            .says(file, &[says])
            .peak_below(file, MEMORY_MIB);
    }
    let material = r#"{ "name": "leaf", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }"#;
    let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    write(&dir, "leaf.gltf", &common::quad_gltf::textured_quad(corners, material, "leaf.png", None));
    mkfifo(&dir.join("leaf.png"));
    rt(&dir, &["pack", "leaf.gltf"], DEADLINE)
        .expect("FIFO texture", 1)
        .says("FIFO texture", &["leaf.png: is a FIFO, not a file"])
        .peak_below("FIFO texture", MEMORY_MIB);
    assert_eq!(names(&dir), ["fifo.toml", "leaf.gltf", "leaf.png", "sky.hdr", "zero.exr", "zero.toml"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}
