//! `.rtmesh` sources and `.rtbvh` caches through the `rt` binary: packing is
//! deterministic and skips fresh caches; a broken source is an error naming it; a
//! broken cache is rebuilt with a warning and the render does not change.

use crate::common;

use common::{repo, temp_dir};
use rt::asset::{MeshData, load_mesh, rtmesh};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rt(args: &[&str], paths: &[&Path]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_rt")).args(args).args(paths).output().expect("run rt");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "rt panicked:\n{stderr}");
    out
}

fn text(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr)
}

/// A copy of the committed teapot asset folder in a fresh directory.
fn teapot_copy(test: &str) -> (PathBuf, PathBuf) {
    let dir = temp_dir(test);
    let _ = std::fs::remove_dir_all(&dir);
    let folder = dir.join("teapot");
    std::fs::create_dir_all(&folder).expect("folder");
    for ext in ["rtmesh", "gltf"] {
        let name = format!("teapot.{ext}");
        std::fs::copy(repo().join("assets/teapot").join(&name), folder.join(&name)).expect("copy teapot");
    }
    (dir, folder)
}

#[test]
fn packing_is_deterministic_and_skips_fresh_caches() {
    let (dir, folder) = teapot_copy("pack-twice");
    let cache = folder.join("teapot.rtbvh");
    let first = rt(&["pack"], &[&dir]);
    assert!(first.status.success() && text(&first).contains("packed 992 triangles"), "{}", text(&first));
    let bytes = std::fs::read(&cache).expect("cache written");
    let modified = std::fs::metadata(&cache).and_then(|m| m.modified()).expect("mtime");

    let second = rt(&["pack"], &[&dir]);
    assert!(second.status.success(), "{}", text(&second));
    assert_eq!(String::from_utf8_lossy(&second.stdout).trim(), format!("{}: up to date", folder.display()));
    assert_eq!(std::fs::metadata(&cache).and_then(|m| m.modified()).expect("mtime"), modified, "rewritten");

    let forced = rt(&["pack", "--force"], &[&dir]);
    assert!(text(&forced).contains("(forced)"), "{}", text(&forced));
    assert_eq!(std::fs::read(&cache).expect("cache"), bytes, "the same sources gave different bytes");

    // Another quality is another cache: rebuilt, and up to date at that quality.
    let slow = rt(&["pack", "--quality", "slow"], &[&dir]);
    assert!(text(&slow).contains("stale: built with other parameters"), "{}", text(&slow));
    let _ = std::fs::remove_dir_all(&dir);
}

fn write_scene(dir: &Path) -> PathBuf {
    let scene = dir.join("scene.toml");
    let text = "[camera]\nposition = [0.0, 0.6, 2.5]\nlook_at = [0.0, 0.4, 0.0]\n\
                [sky]\nkind = \"uniform\"\ncolor = [1.0, 1.0, 1.0]\n\
                [[mesh]]\nasset = \"teapot\"\n";
    std::fs::write(&scene, text).expect("scene");
    scene
}

fn render_png(scene: &Path, png: &Path) -> (Vec<u8>, String) {
    let out = rt(&["render", "--size", "24x24", "--spp", "2", "-o"], &[png, scene]);
    assert!(out.status.success(), "{}", text(&out));
    (std::fs::read(png).expect("png"), text(&out))
}

#[test]
fn broken_cache_is_rebuilt_with_a_warning_and_renders_the_same() {
    let (dir, folder) = teapot_copy("broken-cache");
    let scene = write_scene(&dir);
    let cache = folder.join("teapot.rtbvh");
    let png = dir.join("out.png");
    let (reference, log) = render_png(&scene, &png);
    assert!(!log.contains("WARN"), "packing a missing cache is not a warning:\n{log}");
    let good = std::fs::read(&cache).expect("render packed the cache");

    /// (what, how, what the warning says)
    type Corruption = (&'static str, fn(&mut Vec<u8>), &'static str);
    let corruptions: [Corruption; 3] = [
        ("truncated", |b| b.truncate(b.len() - 100), "invalid: truncated"),
        (
            "bit flip",
            |b| {
                let middle = b.len() / 2;
                b[middle] ^= 0x10;
            },
            "checksum mismatch",
        ),
        ("version", |b| b[8] = 99, "format version 99"),
    ];
    for (what, corrupt, reason) in corruptions {
        let mut bytes = good.clone();
        corrupt(&mut bytes);
        std::fs::write(&cache, &bytes).expect("corrupt the cache");
        let (image, log) = render_png(&scene, &png);
        assert!(log.contains("WARN") && log.contains(reason) && log.contains("rebuilding"), "{what}:\n{log}");
        assert!(log.contains(&cache.display().to_string()), "{what}: the warning names the cache:\n{log}");
        assert_eq!(image, reference, "{what}: the render changed");
        assert_eq!(std::fs::read(&cache).expect("cache"), good, "{what}: the cache was not rewritten");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

fn expect_source_error(folder: &Path, bytes: &[u8], needle: &str) {
    let main = folder.join("teapot.rtmesh");
    std::fs::write(&main, bytes).expect("write rtmesh");
    let message = load_mesh(folder).expect_err("a broken .rtmesh must not load").to_string();
    assert!(message.starts_with(&main.display().to_string()), "names the file: {message}");
    assert!(message.contains(needle), "{needle:?} missing from: {message}");
    let out = rt(&["pack"], &[folder]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    assert!(text(&out).contains(&main.display().to_string()) && text(&out).contains(needle), "{}", text(&out));
}

#[test]
fn broken_rtmesh_is_an_error_naming_the_file() {
    let (dir, folder) = teapot_copy("broken-rtmesh");
    let good = std::fs::read(folder.join("teapot.rtmesh")).expect("teapot");

    expect_source_error(&folder, &good[..good.len() - 7], "truncated or corrupt");
    let mut other_version = good.clone();
    other_version[8] = 5;
    expect_source_error(&folder, &other_version, "unsupported .rtmesh version 5");
    // The top bit of the last triangle's last index: far past the vertex count.
    let mut flipped = good.clone();
    let last_index = good.len() - 4 * 992 - 1;
    flipped[last_index] ^= 0x80;
    expect_source_error(&folder, &flipped, "triangle 991 refers to vertex");

    let mut huge = vec![0u8; 100];
    huge[..8].copy_from_slice(&rtmesh::MAGIC);
    huge[8..12].copy_from_slice(&1u32.to_le_bytes());
    huge[16..20].copy_from_slice(&4_000_000_000u32.to_le_bytes());
    expect_source_error(&folder, &huge, "4000000000 vertices");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn rtmesh_written_from_an_obj_loads_back_the_same() {
    let dir = temp_dir("rtmesh-from-obj");
    let bunny: MeshData = load_mesh(&repo().join("assets/bunny/bunny.obj")).expect("bunny");
    let folder = dir.join("bunny");
    std::fs::create_dir_all(&folder).expect("folder");
    rtmesh::write(&folder.join("bunny.rtmesh"), &bunny).expect("write");
    let materials = r#"{ "asset": { "version": "2.0" }, "materials": [{ "name": "default",
        "pbrMetallicRoughness": { "metallicFactor": 0.0 } }] }"#;
    std::fs::write(folder.join("bunny.gltf"), materials).expect("gltf");
    let back = load_mesh(&folder).expect("loads");
    assert_eq!(
        (&back.positions, &back.normals, &back.uvs, &back.indices, &back.material_ids),
        (&bunny.positions, &bunny.normals, &bunny.uvs, &bunny.indices, &bunny.material_ids)
    );
    assert_eq!(back.materials[0].0, "default");
    let _ = std::fs::remove_dir_all(&dir);
}
