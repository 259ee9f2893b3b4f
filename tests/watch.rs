//! `rt watch`: scripted edits through the real file system, each answered by exactly one
//! reload of the right kind; a burst of saves coalesced; the window under Xvfb showing
//! what a headless render writes.

use crate::common;
use crate::watch_harness;

use common::{icosphere_obj, render, temp_dir};
use rt::render::tonemap::display_pixel;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};
use watch_harness::Watcher;

const SIZE: u32 = 32;
const SPP: u32 = 2;

fn scene_text(camera_x: f32, color: [f32; 3]) -> String {
    format!(
        r#"[render]
max_bounces = 3

[camera]
position = [{camera_x}, 0.5, 4.0]
look_at = [0.0, 0.0, 0.0]
fov_y_deg = 40.0

[sky]
kind = "uniform"
color = [0.6, 0.7, 0.9]

[materials.paint]
base_color = [{}, {}, {}]

[[mesh]]
asset = "assets/ball.obj"
material = "paint"
"#,
        color[0], color[1], color[2]
    )
}

/// Writes `text` under a temporary name and renames it into place, as exporters do.
fn save_by_rename(path: &Path, text: &str) {
    let tmp = path.with_file_name(format!(".{}.tmp", path.file_name().and_then(|n| n.to_str()).unwrap_or("f")));
    std::fs::write(&tmp, text).expect("write temp");
    std::fs::rename(&tmp, path).expect("rename into place");
}

/// An icosphere of `radius` as OBJ text.
fn ball(radius: f64) -> String {
    let (_, vertices, faces) = icosphere_obj(2);
    let mut text = String::new();
    for v in vertices {
        text.push_str(&format!("v {} {} {}\n", v[0] * radius, v[1] * radius, v[2] * radius));
    }
    for f in faces {
        text.push_str(&format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1));
    }
    text
}

fn mean(pixels: &[[f32; 3]]) -> [f32; 3] {
    let n = pixels.len() as f32;
    pixels.iter().fold([0.0; 3], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n, a[2] + p[2] / n])
}

fn reload_lines(log: &[String]) -> Vec<String> {
    log.iter().filter(|l| l.starts_with("reload #")).cloned().collect()
}

/// A folder with the scene and its ball asset.
fn project(name: &str) -> (PathBuf, PathBuf, PathBuf) {
    let dir = temp_dir(name);
    let _ = std::fs::remove_dir_all(dir.join("frames"));
    std::fs::create_dir_all(dir.join("assets")).expect("assets folder");
    let scene = dir.join("scene.toml");
    std::fs::write(dir.join("assets/ball.obj"), ball(1.0)).expect("ball");
    std::fs::write(&scene, scene_text(0.0, [0.8, 0.8, 0.8])).expect("scene");
    (dir.clone(), scene, dir.join("frames"))
}

#[test]
fn each_edit_is_one_reload_of_the_right_kind() {
    let (dir, scene, frames) = project("watch-edits");
    let asset = dir.join("assets/ball.obj");
    let mut watch = Watcher::start(&scene, &frames, SPP, SIZE, &[]);
    watch.wait_for("frame #0 ");

    save_by_rename(&scene, &scene_text(1.0, [0.8, 0.8, 0.8]));
    assert!(watch.wait_for("reload #1 ").contains("kind=camera cause=scene.toml"));
    watch.wait_for("frame #1 ");
    assert!(watch.frame(0) != watch.frame(1), "the camera moved, the image did not");

    // Truncated and rewritten in place, as many editors save.
    std::fs::write(&scene, scene_text(1.0, [0.9, 0.1, 0.1])).expect("rewrite scene");
    assert!(watch.wait_for("reload #2 ").contains("kind=materials"));
    watch.wait_for("frame #2 ");
    let (before, after) = (mean(&watch.frame(1)), mean(&watch.frame(2)));
    assert!(after[1] < before[1] * 0.9 && after[0] > after[1], "the ball turned red: {before:?} → {after:?}");

    save_by_rename(&asset, &ball(0.5));
    assert!(watch.wait_for("reload #3 ").contains("kind=asset cause=ball.obj"));
    watch.wait_for("frame #3 ");
    assert!(watch.frame(2) != watch.frame(3), "the ball shrank, the image did not change");

    let good = std::fs::read_to_string(&scene).expect("scene");
    std::fs::write(&scene, "[camera\nposition = [").expect("broken scene");
    let error = watch.wait_for("error ");
    assert!(error.contains("scene.toml:1:"), "the error names the file and line: {error}");
    save_by_rename(&scene, &good);
    assert!(watch.wait_for("reload #4 ").contains("kind=none"), "the fix restores the last good scene");
    watch.wait_for("frame #4 ");
    assert!(watch.frame(3) == watch.frame(4), "the last good image did not stay");

    std::fs::remove_file(&asset).expect("delete the asset");
    let errors = || watch.log().iter().filter(|l| l.starts_with("error ")).count();
    let deadline = Instant::now() + Duration::from_secs(60);
    while errors() < 2 {
        assert!(Instant::now() < deadline, "no error for the deleted asset:\n{}", watch.log().join("\n"));
        std::thread::sleep(Duration::from_millis(20));
    }
    let error = watch.log().into_iter().filter(|l| l.starts_with("error ")).nth(1).expect("second error");
    assert!(error.contains("ball.obj"), "the error names the asset: {error}");
    std::fs::write(&asset, ball(1.0)).expect("recreate the asset");
    assert!(watch.wait_for("reload #5 ").contains("kind=asset"));
    watch.wait_for("frame #5 ");
    assert!(watch.frame(5) == watch.frame(2), "the first ball is back, red: the image should be frame 2's");

    let log = watch.log();
    let kinds: Vec<&str> =
        log.iter().filter_map(|l| l.strip_prefix("reload #")).filter_map(|l| l.split(' ').nth(1)).collect();
    assert_eq!(kinds, ["kind=camera", "kind=materials", "kind=asset", "kind=none", "kind=asset"], "{log:#?}");
    watch.stop();
}

/// A plane whose emission is a node graph (a 1D Voronoi of the x coordinate times a Math
/// node), seen from above.
const GRAPH_SCENE: &str = r#"[render]
max_bounces = 1

[camera]
position = [0.0, 10.0, 0.0]
look_at = [0.0, 0.0, 0.0]
up = [0.0, 0.0, -1.0]
projection = "orthographic"
ortho_scale = 2.2

[sky]
kind = "uniform"
color = [0.0, 0.0, 0.0]

[[mesh]]
asset = "assets/Plane"
"#;

/// A value edited in a node graph (a Voronoi's Scale) is a write to the program table: the
/// reload builds no pipeline (no `features=`) and the frame is the edited scene's image; a
/// new shape (the Math node's operation) builds one.
#[test]
fn a_node_value_edit_builds_no_pipeline() {
    let dir = temp_dir("watch-node-value");
    let _ = std::fs::remove_dir_all(dir.join("frames"));
    let asset = dir.join("assets/Plane");
    std::fs::create_dir_all(&asset).expect("asset folder");
    let source = common::repo().join("tests/cycles/scenes/graph_voronoi_dimensions/assets/Plane");
    for file in ["Plane.gltf", "Plane.rtmesh"] {
        std::fs::copy(source.join(file), asset.join(file)).expect("copy the asset");
    }
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, GRAPH_SCENE).expect("scene");
    let gltf = asset.join("Plane.gltf");
    let original = std::fs::read_to_string(&gltf).expect("glTF");
    let mut watch = Watcher::start(&scene, &dir.join("frames"), SPP, SIZE, &[]);
    watch.wait_for("frame #0 ");

    let scaled = original.replacen("\"value\": 4.0", "\"value\": 7.0", 1);
    assert!(scaled != original, "the Voronoi's Scale is in the glTF");
    save_by_rename(&gltf, &scaled);
    let reload = watch.wait_for("reload #1 ");
    assert!(!reload.contains("features="), "a value edit built a pipeline: {reload}");
    watch.wait_for("frame #1 ");
    let expected = render(rt::scene::parse(GRAPH_SCENE, "scene.toml", &dir).expect("scene"), SIZE, SIZE, SPP, 1);
    assert!(watch.frame(1) == expected.pixels, "the frame is not the edited graph's image");
    assert!(watch.frame(1) != watch.frame(0), "the Scale changed, the image did not");

    save_by_rename(&gltf, &scaled.replacen("\"MULTIPLY\"", "\"ADD\"", 1));
    let reload = watch.wait_for("reload #2 ");
    assert!(reload.contains("features="), "a new shape needs its pipeline: {reload}");
    watch.wait_for("frame #2 ");
    assert!(watch.frame(2) != watch.frame(1), "the Math node adds now, the image did not change");
    watch.stop();
}

#[test]
fn a_burst_of_saves_is_coalesced_and_ends_on_the_last_state() {
    let (_dir, scene, frames) = project("watch-burst");
    let mut watch = Watcher::start(&scene, &frames, SPP, SIZE, &[]);
    watch.wait_for("frame #0 ");
    let saves = 200;
    let start = Instant::now();
    for i in 1..=saves {
        let text = scene_text(i as f32 * 0.01, [0.8, 0.8, 0.8]);
        if i % 2 == 0 {
            save_by_rename(&scene, &text)
        } else {
            std::fs::write(&scene, &text).expect("save")
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    // The premise: a burst (about 2 s of saves), not a trickle rt could follow save by save.
    assert!(start.elapsed() < Duration::from_secs(10), "the saves took {:?}", start.elapsed());
    // Settled: the last reload has its frame, and no reload follows for a while.
    let settled = |log: &[String]| {
        let last = reload_lines(log).last().and_then(|l| l.split(' ').nth(1).map(str::to_owned));
        last.is_some_and(|n| log.iter().any(|l| l.starts_with(&format!("frame {n} "))))
    };
    let deadline = Instant::now() + Duration::from_secs(120);
    let mut quiet_since = Instant::now();
    let mut seen = 0;
    loop {
        let log = watch.log();
        if log.len() != seen {
            (seen, quiet_since) = (log.len(), Instant::now());
        }
        if settled(&log) && quiet_since.elapsed() > Duration::from_secs(1) {
            break;
        }
        assert!(Instant::now() < deadline, "never settled:\n{}", log.join("\n"));
        std::thread::sleep(Duration::from_millis(50));
    }
    let log = watch.log();
    let reloads = reload_lines(&log);
    assert!(!reloads.is_empty() && reloads.len() < saves / 4, "{} reloads for {saves} saves", reloads.len());
    let last: u32 = reloads.last().and_then(|l| l[8..].split(' ').next()?.parse().ok()).expect("reload number");
    let expected = render(
        rt::scene::parse(&scene_text(saves as f32 * 0.01, [0.8, 0.8, 0.8]), "scene.toml", scene.parent().expect("dir"))
            .expect("final scene"),
        SIZE,
        SIZE,
        SPP,
        3,
    );
    assert!(watch.frame(last) == expected.pixels, "the last frame is not the last save's image");
    watch.stop();
}

#[test]
fn dev_mode_reloads_shaders_and_survives_a_broken_one() {
    let (dir, scene, frames) = project("watch-dev");
    let shaders = dir.join("shaders");
    std::fs::create_dir_all(&shaders).expect("shaders folder");
    for entry in std::fs::read_dir(common::repo().join("crates/rt/shaders")).expect("crates/rt/shaders/") {
        let path = entry.expect("entry").path();
        std::fs::copy(&path, shaders.join(path.file_name().expect("name"))).expect("copy shader");
    }
    let mut watch = Watcher::start(&scene, &frames, SPP, SIZE, &["--dev".as_ref(), shaders.as_os_str()]);
    watch.wait_for("frame #0 ");
    let integrator = shaders.join("integrator.wgsl");
    let good = std::fs::read_to_string(&integrator).expect("integrator.wgsl");
    save_by_rename(&integrator, &format!("{good}\nfn broken( {{\n"));
    let error = watch.wait_for("error ");
    assert!(error.contains("shaders/integrator.wgsl"), "the error names the shader: {error}");
    save_by_rename(&integrator, &format!("{good}\n// a comment changes nothing\n"));
    assert!(watch.wait_for("reload #1 ").contains("kind=shaders cause=integrator.wgsl"));
    watch.wait_for("frame #1 ");
    assert!(watch.frame(0) == watch.frame(1), "the same shader code rendered another image");
    watch.stop();
}

#[test]
fn the_window_shows_what_a_headless_render_writes() {
    let xvfb = ["/usr/bin/xvfb-run", "/usr/local/bin/xvfb-run"].into_iter().find(|p| Path::new(p).exists());
    let xvfb = xvfb.expect("xvfb-run is needed for the window test (scripts/test installs the xvfb package)");
    let (_dir, scene, frames) = project("watch-window");
    std::fs::create_dir_all(&frames).expect("frames");
    let spp = 4;
    let output = Command::new(xvfb)
        .args(["-a", "-s", "-screen 0 640x480x24", env!("CARGO_BIN_EXE_rt"), "watch", "--spp", &spp.to_string()])
        .args(["--size", &format!("{SIZE}x{SIZE}"), "--max-reloads", "0", "--frames-dir"])
        .arg(&frames)
        .arg(&scene)
        .output()
        .expect("run rt watch under xvfb-run");
    let log = std::fs::read_to_string(frames.join(rt_watch::LOG_FILE)).unwrap_or_default();
    assert!(output.status.success(), "rt watch: {}\n{log}\n{}", output.status, String::from_utf8_lossy(&output.stderr));
    let presented: u64 = log
        .lines()
        .find_map(|l| l.strip_prefix("presented ")?.split(' ').next()?.parse().ok())
        .expect("a presented-frames line");
    assert!(presented >= 1, "{log}");

    let shown = image::open(frames.join("frame-0000.png")).expect("the window's frame").into_rgb8();
    let scene = rt::scene::load(&scene).expect("scene");
    let exposure = scene.render.exposure;
    let headless = render(scene, SIZE, SIZE, spp, 3);
    let mut worst = 0;
    for (shown, linear) in shown.pixels().zip(&headless.pixels) {
        let expected = display_pixel(*linear, exposure);
        for (a, b) in shown.0.iter().zip(expected) {
            worst = worst.max((*a as i32 - b as i32).abs());
        }
    }
    assert!(worst <= 1, "the window's pixels differ from the headless render's by up to {worst}/255");
}
