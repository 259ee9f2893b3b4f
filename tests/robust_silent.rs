//! Inputs that used to give a wrong answer without a word: a sphere too large for f32
//! (it vanished), a mesh of degenerate triangles (it rendered as nothing), a misspelt
//! asset path ("unsupported asset type"), and `--frames-dir` naming a file.

use crate::common;

use common::bounded::{fresh_dir, names, rt};
use std::path::Path;
use std::time::Duration;

const DEADLINE: Duration = Duration::from_secs(120);

fn write(dir: &Path, name: &str, text: &str) {
    if let Some(parent) = dir.join(name).parent() {
        std::fs::create_dir_all(parent).expect("folder");
    }
    std::fs::write(dir.join(name), text).expect("write test file");
}

/// The camera inside an emitter of `radius` that reflects nothing, under a black sky:
/// every pixel sees exactly its radiance, 1.
fn inside_a_sphere(radius: &str) -> String {
    format!(
        "[camera]\nposition = [0.0, 1.0, 5.0]\n[materials.glow]\nemission = [1.0, 1.0, 1.0]\ndiffuse = 0.0\n\
         [[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = {radius}\nmaterial = \"glow\"\n"
    )
}

#[test]
fn a_sphere_too_large_for_f32_is_refused_and_the_largest_allowed_renders_right() {
    let dir = fresh_dir("huge-sphere");
    write(&dir, "huge.toml", &inside_a_sphere("1e20"));
    let outcome = rt(&dir, &["render", "huge.toml", "--size", "16x16", "--spp", "1", "-o", "huge.exr"], DEADLINE);
    outcome.expect("radius 1e20", 1).says(
        "radius 1e20",
        &["huge.toml:8:10: sphere 1: radius must be positive and at most 1e15 m (rt intersects spheres in f32), got 1e20"],
    );
    write(&dir, "far.toml", &inside_a_sphere("1.0").replace("center = [0.0, 0.0, 0.0]", "center = [0.0, 0.0, -2e15]"));
    rt(&dir, &["render", "far.toml", "-o", "far.exr"], DEADLINE)
        .expect("centre at -2e15", 1)
        .says("centre at -2e15", &["far.toml:7:10: sphere 1: center must be within ±1e15 m"]);

    write(&dir, "limit.toml", &inside_a_sphere("1e15"));
    rt(&dir, &["render", "limit.toml", "--size", "16x16", "--spp", "1", "-o", "limit.exr"], DEADLINE)
        .expect("radius 1e15", 0);
    let image = image::open(dir.join("limit.exr")).expect("EXR").to_rgb32f();
    let worst = image.pixels().flat_map(|p| p.0).map(|c| (c - 1.0).abs()).fold(0.0f32, f32::max);
    // Emission seen directly carries no noise: only float rounding.
    assert!(worst < 1e-5, "inside a sphere of radius 1e15 a pixel is off by {worst}");
    assert_eq!(names(&dir), ["far.toml", "huge.toml", "limit.exr", "limit.toml"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn a_mesh_of_degenerate_triangles_is_named_in_a_warning() {
    let dir = fresh_dir("degenerate");
    // Collinear vertices, and a triangle that repeats one.
    write(&dir, "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n");
    write(&dir, "scene.toml", "[[mesh]]\nasset = \"flat.obj\"\n[[sphere]]\ncenter = [0.0, 1.0, 0.0]\nradius = 0.5\n");
    let warning = "flat.obj: all 2 triangles are degenerate (zero area): the mesh is invisible";
    for run in ["packed", "from its cache"] {
        rt(&dir, &["render", "scene.toml", "--size", "8x8", "--spp", "1", "-o", "out.png"], DEADLINE)
            .expect(run, 0)
            .says(run, &[warning]);
    }
    let outcome = rt(&dir, &["pack", "flat.obj", "--force"], DEADLINE);
    outcome.expect("rt pack", 0).says("rt pack", &[warning]);
    std::fs::write(dir.join("one.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 3\n").expect("write");
    rt(&dir, &["pack", "one.obj"], DEADLINE)
        .expect("one triangle", 0)
        .says("one triangle", &["one.obj: its only triangle is degenerate (zero area): the mesh is invisible"]);
    for name in ["one.obj", "one.rtbvh"] {
        std::fs::remove_file(dir.join(name)).expect("remove");
    }
    assert_eq!(names(&dir), ["flat.obj", "flat.rtbvh", "out.png", "scene.toml"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn a_misspelt_asset_path_is_missing_with_a_did_you_mean() {
    let dir = fresh_dir("misspelt");
    write(&dir, "assets/dragon/dragon.rtmesh", "");
    write(&dir, "assets/bunny.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    for (asset, message) in [
        ("assets/dragn", "assets/dragn: no such file or folder; did you mean `dragon`?"),
        ("assets/bunyn.obj", "assets/bunyn.obj: no such file or folder; did you mean `bunny.obj`?"),
        ("assets/zzzzzzzz", "assets/zzzzzzzz: no such file or folder"),
    ] {
        write(&dir, "scene.toml", &format!("[[mesh]]\nasset = \"{asset}\"\n"));
        let outcome = rt(&dir, &["render", "scene.toml", "--size", "8x8", "--spp", "1", "-o", "out.png"], DEADLINE);
        outcome.expect(asset, 1).says(asset, &[message]);
        assert!(!outcome.stderr.contains("unsupported asset type"), "{}", outcome.stderr);
    }
    rt(&dir, &["pack", "assets/dragn"], DEADLINE)
        .expect("rt pack", 1)
        .says("rt pack", &["assets/dragn: no such file or folder; did you mean `dragon`?"]);
    assert_eq!(names(&dir), ["assets", "scene.toml"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn frames_dir_naming_a_file_says_so() {
    let dir = fresh_dir("frames-file");
    write(&dir, "afile", "not a folder");
    write(&dir, "scene.toml", "[[sphere]]\ncenter = [0.0, 1.0, 0.0]\nradius = 0.5\n");
    rt(&dir, &["watch", "--headless", "--frames-dir", "afile", "--max-reloads", "0", "scene.toml"], DEADLINE)
        .expect("--frames-dir afile", 1)
        .says("--frames-dir afile", &["error: --frames-dir: afile: is a file, not a folder"]);
    assert_eq!(std::fs::read_to_string(dir.join("afile")).expect("read"), "not a folder");
    assert_eq!(names(&dir), ["afile", "scene.toml"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}
