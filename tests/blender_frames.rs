//! A frame range exported from Blender (`blender/rt_export.py --frames`) and rendered with
//! `rt render --frames`: one scene file per frame, meshes stored by content (a mesh that
//! does not change is written once and its BVH built once; a mesh whose shape changes gets
//! a folder per shape). Needs RT_BPY_PYTHON.

use crate::common;

use common::bounded::{rt, run};
use common::{bpy_python, empty_temp_dir, repo};
use std::path::Path;
use std::process::Command;
use std::time::Duration;

/// The `[[mesh]]` entries of a scene file: (asset, matrix line) in file order.
fn meshes(scene: &Path) -> Vec<(String, String)> {
    let text = std::fs::read_to_string(scene).unwrap_or_else(|e| panic!("{}: {e}", scene.display()));
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        if let Some(asset) = line.strip_prefix("asset = ") {
            out.push((asset.trim_matches('"').to_owned(), lines[i + 1].to_owned()));
        }
    }
    out
}

#[test]
fn a_frame_range_exports_each_mesh_once_per_shape_and_renders() {
    let dir = empty_temp_dir("blender-frames");
    let deadline = Duration::from_secs(600);
    let mut build = Command::new(bpy_python());
    build.arg(repo().join("tests/blender/frames.py")).arg("build").arg(&dir);
    run(build, deadline).expect("build the .blend", 0);
    let mut export = Command::new(bpy_python());
    export.arg(repo().join("blender/rt_export.py")).arg(dir.join("frames.blend"));
    export.args(["--out", "assets", "--scene", "shot_####.toml", "--frames", "1..4"]).current_dir(&dir);
    // Frame 1 writes three meshes (two files each) and its scene; frame 2 the bent sheet and
    // its scene; frames 3 and 4 their scenes only (4 shows the first shape again).
    run(export, deadline).expect("export frames 1..4", 0).says(
        "the files written per frame",
        &[
            "frame 1: 7 files written",
            "frame 2: 3 files written",
            "frame 3: 1 files written",
            "frame 4: 1 files written",
        ],
    );
    let frames: Vec<_> = (1..=4).map(|f| meshes(&dir.join(format!("shot_{f:04}.toml")))).collect();
    let asset = |frame: usize, k: usize| frames[frame][k].0.clone();
    // In name order: the floor's plane, the sheet, the slider cube.
    assert_eq!((0..4).map(|f| asset(f, 0)).collect::<Vec<_>>(), vec!["assets/Plane"; 4], "the floor keeps its folder");
    assert_eq!((0..4).map(|f| asset(f, 2)).collect::<Vec<_>>(), vec!["assets/Cube"; 4], "the slider keeps its folder");
    assert!((1..4).all(|f| frames[f][2].1 != frames[f - 1][2].1), "the slider moves every frame");
    let sheet: Vec<_> = (0..4).map(|f| asset(f, 1)).collect();
    assert!(sheet[0] == sheet[3] && sheet[1] == sheet[2] && sheet[0] != sheet[1], "two shapes, two folders: {sheet:?}");

    let size = ["--spp", "2", "--size", "24x16", "--progress", "none"];
    rt(&dir, &[&["render", "shot_####.toml", "--frames", "1..4", "-o", "out_####.png"], &size[..]].concat(), deadline)
        .expect("render the frames", 0);
    let images: Vec<Vec<u8>> =
        (1..=4).map(|f| std::fs::read(dir.join(format!("out_{f:04}.png"))).expect("a frame")).collect();
    assert!((1..4).all(|f| images[f] != images[f - 1]), "each frame shows its own state");
    let caches = walk(&dir.join("assets")).into_iter().filter(|p| p.extension().is_some_and(|e| e == "rtbvh")).count();
    assert_eq!(caches, 4, "one BVH per distinct mesh, built once for all frames");

    // The add-on's Export now with Frame range on writes the same scenes; a scene file
    // without #### is refused, saying why.
    let mut addon = Command::new(bpy_python());
    addon.arg(repo().join("tests/blender/frames.py")).arg("addon").arg(&dir);
    run(addon, deadline).expect("the add-on's frame range", 0).says("no ####", &["refused:", "####"]);
    for f in 1..=4 {
        let name = format!("shot_{f:04}.toml");
        let (ours, cli) = (meshes(&dir.join("addon").join(&name)), meshes(&dir.join(&name)));
        let matrices = |m: &[(String, String)]| m.iter().map(|(_, matrix)| matrix.clone()).collect::<Vec<_>>();
        assert_eq!(matrices(&ours), matrices(&cli), "{name}: the add-on places what the command line does");
    }

    // Live export on every edit with Motion Blur on: one export per edit, sharp, the frame kept.
    let mut live = Command::new(bpy_python());
    live.arg(repo().join("tests/blender/frames.py")).arg("live").arg(&dir);
    run(live, deadline).expect("a live edit", 0).says("live and sharp", &["live exports: 1; frame 2; motion keys: 0"]);
}

fn walk(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).expect("a folder").flatten() {
        let path = entry.path();
        if path.is_dir() {
            out.extend(walk(&path));
        } else {
            out.push(path);
        }
    }
    out
}
