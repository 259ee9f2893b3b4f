//! rt as Blender's render engine (blender/rt_engine.py): F12 through bpy gives the image
//! `rt render` gives for the exported scene, Ctrl+F12 renders each frame of a range, a
//! stop ends rt within a second leaving no files behind, rt's errors reach the report,
//! and the packaged extension installs and renders (and its files install as a legacy
//! add-on by the package's bl_info). Also `rt render --progress json`.
//! Needs RT_BPY_PYTHON, a Python with `bpy` (scripts/test sets one up).

use crate::common;

use common::{bpy_python, empty_temp_dir, repo};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh folder for one test; the engine's cache goes under it (TMPDIR).
fn out_dir(name: &str) -> PathBuf {
    empty_temp_dir(&format!("engine-{name}"))
}

/// Runs tests/blender/engine.py MODE ARGS with the engine's environment; returns its output.
fn engine_py(out: &Path, args: &[&Path]) -> String {
    let mut command = Command::new(bpy_python());
    command
        .arg(repo().join("tests/blender/engine.py"))
        .args(args)
        .env("RT_BINARY", env!("CARGO_BIN_EXE_rt"))
        .env("TMPDIR", out)
        .env("BLENDER_USER_RESOURCES", out.join("blender_user"));
    let result = command.output().unwrap_or_else(|e| panic!("cannot run {command:?}: {e}"));
    let text = String::from_utf8_lossy(&result.stdout).into_owned() + &String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{command:?} failed:\n{text}");
    text
}

fn json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// RGB of an EXR, rows from the top.
fn exr(path: &Path) -> (u32, u32, Vec<f32>) {
    let image = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgb32f();
    (image.width(), image.height(), image.into_raw())
}

/// engine.blend (a cube on a plane under a point lamp, 64x48) rendered with F12.
fn f12(out: &Path) -> Value {
    engine_py(out, &[Path::new("f12"), out]);
    json(&out.join("f12.json"))
}

#[test]
fn f12_matches_rt_render_of_the_exported_scene() {
    let out = out_dir("f12");
    let report = f12(&out);
    let cache = PathBuf::from(report["cache"].as_str().expect("cache"));
    assert!(cache.starts_with(&out), "the cache is under the system temp dir: {}", cache.display());
    let direct = out.join("direct.exr");
    let rendered = Command::new(env!("CARGO_BIN_EXE_rt"))
        .arg("render")
        .arg(cache.join("scene.toml"))
        .arg("-o")
        .arg(&direct)
        .args(["--progress", "none", "--spp", &report["spp"].to_string()])
        .args(["--max-bounces", &report["max_bounces"].to_string()])
        .args(["--sampling", report["sampling"].as_str().expect("sampling")])
        .args(["--seed", &report["seed"].to_string()])
        .status()
        .expect("rt runs");
    assert!(rendered.success());
    let (w, h, engine) = exr(&out.join("f12.exr"));
    let (dw, dh, expected) = exr(&direct);
    assert_eq!((w, h), (64, 48), "Blender's output has the scene's size");
    assert_eq!((w, h), (dw, dh));
    let mean = expected.iter().map(|&v| v as f64).sum::<f64>() / expected.len() as f64;
    assert!(mean > 0.01, "the lamp lights the scene (mean {mean})");
    // The same seed and settings give the same samples; Blender stores the float pixels
    // it was given, without a colour transform: bit-exact.
    let differing = engine.iter().zip(&expected).filter(|(a, b)| a.to_bits() != b.to_bits()).count();
    assert_eq!(differing, 0, "F12 and rt render differ in {differing} of {} values", expected.len());
    let t = &report["timings"];
    eprintln!(
        "F12 {:.2} s; engine steps: export {:.3} s, rt {:.2} s of which rendering {:.2} s",
        report["f12_s"].as_f64().unwrap_or(0.0),
        t["export_s"].as_f64().unwrap_or(0.0),
        t["rt_s"].as_f64().unwrap_or(0.0),
        t["render_s"].as_f64().unwrap_or(0.0)
    );
}

#[test]
fn ctrl_f12_renders_each_frame_of_the_range() {
    let out = out_dir("frames");
    f12(&out);
    engine_py(&out, &[Path::new("frames"), &out]);
    let frames = json(&out.join("frames.json"));
    // Blender's (x, y, z) is rt's (x, z, -y): the keyframed height is the matrix's Y translation.
    let height = |frame: &str| frames["cube_matrix"][frame][7].as_f64().unwrap_or(f64::NAN);
    assert!((height("1") - 1.0).abs() < 1e-6, "frame 1 exports the cube at z = 1: {frames}");
    assert!((height("2") - 3.0).abs() < 1e-6, "frame 2 exports the cube at z = 3: {frames}");
    let (_, _, first) = exr(&out.join("anim_0001.exr"));
    let (_, _, second) = exr(&out.join("anim_0002.exr"));
    let changed = first.iter().zip(&second).filter(|(a, b)| (*a - *b).abs() > 0.05).count();
    assert!(changed > first.len() / 50, "the moved cube shows in frame 2 ({changed} values changed)");
}

#[test]
fn a_stop_ends_rt_within_a_second_and_leaves_no_files() {
    let out = out_dir("cancel");
    f12(&out);
    engine_py(&out, &[Path::new("cancel"), &out]);
    let report = json(&out.join("cancel.json"));
    assert_eq!(report["cancelled"], true, "{report}");
    assert!(report["progress_events"].as_u64().unwrap_or(0) >= 1, "it was stopped mid-render: {report}");
    let stopped = report["stopped_s"].as_f64().expect("time to stop");
    assert!(stopped < 1.0, "rt took {stopped:.2} s to stop");
    let status = report["status"].as_i64().expect("exit status");
    assert!(status == 143 || status == -15, "rt ended by SIGTERM (its own exit 143, or the signal), got {status}");
    assert_eq!(report["before"], report["after"], "the stopped render left or removed files");
}

#[test]
fn rt_errors_reach_the_report() {
    let out = out_dir("error");
    f12(&out);
    let log = engine_py(&out, &[Path::new("error"), &out]);
    let report = json(&out.join("error.json"));
    // The engine's ERROR report fails bpy.ops.render.render with it, as in Blender's UI.
    let reported = report["reported"].as_array().expect("reports");
    let error =
        reported.iter().find(|r| r[0][0] == "RuntimeError").unwrap_or_else(|| panic!("F12 did not fail: {report}"));
    let message = error[1].as_str().expect("message");
    assert!(message.starts_with("Error: rt: "), "an error report from the engine: {message}");
    assert!(message.contains("scene.toml:") && message.contains("power must be non-negative"), "{message}");
    assert!(log.contains(message.trim_end()), "Blender printed the report too:\n{log}");
    assert!(!out.join("error.exr").exists(), "a failed render writes no image");
    let direct = report["run_rt"].as_str().unwrap_or_else(|| panic!("run_rt did not fail: {report}"));
    assert!(direct.contains("broken.toml:2:1") && direct.contains("did you mean"), "{direct}");
}

#[test]
fn the_extension_zip_installs_and_renders() {
    let out = out_dir("package");
    f12(&out);
    let zip = out.join("rt_blender.zip");
    let packaged = Command::new(repo().join("scripts/package_blender")).arg(&zip).status().expect("script runs");
    assert!(packaged.success());
    let log = engine_py(&out, &[Path::new("package"), &zip, &out]);
    assert!(log.contains("package: installed, rendered through its preferences"), "{log}");
    let (_, _, via_extension) = exr(&out.join("package.exr"));
    let (_, _, via_script) = exr(&out.join("f12.exr"));
    assert_eq!(via_extension, via_script, "the installed extension renders the same image");
}

#[test]
fn the_package_installs_as_a_legacy_add_on_by_its_bl_info() {
    let out = out_dir("legacy");
    let zip = out.join("rt_blender.zip");
    let packaged = Command::new(repo().join("scripts/package_blender")).arg(&zip).status().expect("script runs");
    assert!(packaged.success());
    let log = engine_py(&out, &[Path::new("legacy"), &zip, &out]);
    assert!(log.contains("legacy: listed as 'rt' (0, 1, 0), enabled with the exporter and the engine"), "{log}");
}

#[test]
fn progress_json_lines_parse() {
    let out = out_dir("progress");
    let image = out.join("p.exr");
    let run = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "--size", "32x24", "--spp", "8", "--progress", "json", "-o"])
        .arg(&image)
        .output()
        .expect("rt runs");
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let events: Vec<Value> = String::from_utf8_lossy(&run.stderr)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("not JSON ({e}): {l}")))
        .collect();
    let progress: Vec<&Value> = events.iter().filter(|e| e["event"] == "progress").collect();
    assert!(!progress.is_empty(), "{events:?}");
    let last = progress.last().expect("progress");
    assert_eq!((last["spp"].as_u64(), last["of"].as_u64()), (Some(8), Some(8)), "the last progress is the end");
    assert!(progress.iter().all(|e| e["samples_per_second"].as_f64().is_some_and(|r| r > 0.0)));
    assert!(progress.iter().all(|e| e["eta_s"].as_f64().is_some_and(|t| t >= 0.0)));
    let done = events.last().expect("events");
    assert_eq!(done["event"], "done");
    assert_eq!(done["file"].as_str().map(PathBuf::from), Some(image));
    assert!(done["seconds"].as_f64().is_some_and(|s| s > 0.0));

    let failed = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "no/such/scene.toml", "--progress", "json"])
        .output()
        .expect("rt runs");
    assert_eq!(failed.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&failed.stderr);
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "{stderr}");
    let error: Value = serde_json::from_str(lines[0]).expect("an error event");
    assert_eq!(error["event"], "error");
    assert!(error["message"].as_str().is_some_and(|m| m.contains("no/such/scene.toml")), "{error}");
}
