//! Blender live, without saves: "Live export on every edit" in a bpy session with
//! `rt watch --headless` on what it exports (each scripted edit is one reload of the
//! right kind; a drag is throttled and its last state lands), and the viewport's
//! Rendered mode driven as Blender drives it (its camera from Blender's matrices gives
//! the exported camera's image; each edit reaches the streaming rt as a reload of the
//! right files). Needs RT_BPY_PYTHON, a Python with `bpy` (scripts/test sets one up).

use crate::common;
use crate::watch_harness;

use common::{bpy_python, empty_temp_dir, repo};
use serde_json::Value;
use std::path::Path;
use std::process::Command;
use std::time::Duration;
use watch_harness::{edit_and_expect_reload, watch_blender_session};

fn json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Whether step `step`'s classified updates name `object` under `kind`.
fn classified(report: &Value, step: usize, kind: &str, name: &str) -> bool {
    report["classified"][step - 1]
        .as_array()
        .expect("the step's updates")
        .iter()
        .any(|u| u[kind].as_array().is_some_and(|names| names.iter().any(|n| n == name)))
}

#[test]
fn each_edit_in_blender_is_one_reload_in_rt_watch_without_saving() {
    let (mut blender, mut watch, out) = watch_blender_session("live_edits.py", "blender-live-edits");
    let steps = [
        (1, "kind=placement cause=scene.toml"),
        (2, "kind=asset cause=cube.gltf"),
        (3, "kind=asset cause=cube.rtmesh"),
        (4, "kind=camera cause=scene.toml"),
        (5, "kind=placement cause=scene.toml"),
    ];
    for (step, expected) in steps {
        edit_and_expect_reload(&mut blender, &mut watch, step, expected);
        if step < 5 {
            // One reload for one edit: nothing more comes before the next edit.
            std::thread::sleep(Duration::from_millis(500));
            let log = watch.log();
            assert!(
                !log.iter().any(|l| l.starts_with(&format!("reload #{} ", step + 1))),
                "step {step} made more than one reload:\n{}",
                log.join("\n")
            );
        }
    }
    blender.finish();
    // The drag's held-back last state lands as a reload of its own (or merged into the
    // first one by the watcher's debouncing): placements only, at most two.
    std::thread::sleep(Duration::from_millis(1000));
    let log = watch.log();
    let drag: Vec<&String> = log.iter().filter(|l| l.starts_with("reload #")).skip(4).collect();
    assert!((1..=2).contains(&drag.len()), "{}", log.join("\n"));
    assert!(drag.iter().all(|l| l.contains("kind=placement")), "{}", log.join("\n"));
    assert!(!log.iter().any(|l| l.starts_with("error ")), "{}", log.join("\n"));

    let report = json(&out.join("live_edits.json"));
    for key in ["first_move_exported", "timer_scheduled", "last_state_held_back", "last_state_landed"] {
        assert_eq!(report[key], true, "the drag: {key} is not true: {report}");
    }
    assert!(classified(&report, 1, "transform", "cube") && !classified(&report, 1, "geometry", "cube"), "{report}");
    assert!(classified(&report, 2, "materials", "paint"), "{report}");
    assert!(classified(&report, 3, "meshes", "cube") && classified(&report, 3, "geometry", "cube"), "{report}");
    assert!(classified(&report, 4, "transform", "Camera") && !classified(&report, 4, "transform", "cube"), "{report}");
    watch.stop();
}

#[test]
fn the_viewport_streams_blenders_camera_and_each_edit() {
    let out = empty_temp_dir("blender-viewport");
    let result = Command::new(bpy_python())
        .arg(repo().join("tests/blender/viewport.py"))
        .arg(&out)
        .env("RT_BINARY", env!("CARGO_BIN_EXE_rt"))
        .output()
        .expect("run the Blender session");
    let text = String::from_utf8_lossy(&result.stdout).into_owned() + &String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "the Blender session failed:\n{text}");
    let report = json(&out.join("viewport.json"));
    println!("viewport: {report}");

    // The same rays give the same samples: the two images agree to float rounding,
    // depth of field included (the camera's 50 mm at f/0.025: an aperture 1 m in radius),
    // while a pinhole or a 10% longer lens moves every edge.
    let same = report["same_camera_difference"].as_f64().expect("a number");
    let pinhole = report["pinhole_difference"].as_f64().expect("a number");
    let longer = report["longer_lens_difference"].as_f64().expect("a number");
    assert!(same < 1e-3, "Blender's camera matrices give another image than the exported camera: {same}");
    assert!(pinhole > 1e-2, "the comparison cannot tell the depth of field from a pinhole: {pinhole}");
    assert!(longer > 1e-2, "the comparison cannot tell a 10% longer lens: {longer}");
    let radius = report["aperture"]["aperture"].as_f64().expect("the aperture sent");
    assert!((radius - 1.0).abs() < 1e-6 && report["aperture"]["focus"] == 20.0, "{}", report["aperture"]);
    // The exported camera's frame, from before the viewport's first view, is not drawn.
    assert_eq!(report["drawn"], serde_json::json!({"exported": false, "same": true}));

    for (step, file, kind) in [
        ("move", "scene.toml", "kind=placement cause=scene.toml"),
        ("material", "assets/cube/cube.gltf", "kind=asset cause=cube.gltf"),
        ("mesh", "assets/cube/cube.rtmesh", "kind=asset cause=cube.rtmesh"),
        ("camera", "scene.toml", "kind=camera cause=scene.toml"),
    ] {
        let updates = report["updates"][step].as_array().expect("the step's updates");
        assert_eq!(updates.len(), 1, "{step}: {updates:?}");
        assert_eq!(updates[0]["written"], serde_json::json!([file]), "{step}");
        let reload = updates[0]["reload"].as_str().expect("rt's reload line");
        assert!(reload.starts_with("reload #") && reload.contains(kind), "{step}: {reload}");
    }
    // The scene file's new camera must not take the place of the viewport's own view.
    let moved = report["camera_object_moved_difference"].as_f64().expect("a number");
    assert!(moved < 1e-3, "moving the scene camera changed the viewport's image: {moved}");
    assert_eq!(report["errors"], serde_json::json!([]));
    assert_eq!(report["rt_exit"], 0, "rt quits when the viewport closes");
}
