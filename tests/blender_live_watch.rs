//! Blender's live link end to end: the add-on's "Live export on save" in a bpy session,
//! `rt watch --headless` on what it exports; each save is one reload of the right kind.
//! Needs RT_BPY_PYTHON, a Python with `bpy` (scripts/test sets one up).

use crate::common;
use crate::watch_harness;

use common::{repo, temp_dir};
use std::path::{Path, PathBuf};
use std::process::{Child, Command};
use std::time::{Duration, Instant};
use watch_harness::Watcher;

fn bpy_python() -> PathBuf {
    let python = std::env::var_os("RT_BPY_PYTHON").map(PathBuf::from).unwrap_or_else(|| {
        panic!("RT_BPY_PYTHON is not set: it must name a Python 3.11 with bpy==5.0.1 (scripts/test sets it)")
    });
    if python.is_relative() { repo().join(python) } else { python }
}

/// Waits for the Blender session to write `name` into `out`.
fn wait_for_blender(blender: &mut Child, out: &Path, name: &str) {
    let deadline = Instant::now() + Duration::from_secs(300);
    while !out.join(name).exists() {
        if let Ok(Some(status)) = blender.try_wait() {
            panic!("the Blender session exited ({status}) before writing {name}");
        }
        assert!(Instant::now() < deadline, "the Blender session wrote no {name} in 300 s");
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
fn each_save_in_blender_is_one_reload_in_rt_watch() {
    let out = temp_dir("blender-live-watch");
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).expect("output folder");
    let script = repo().join("tests/blender/live_watch.py");
    let mut blender = Command::new(bpy_python()).arg(&script).arg(&out).spawn().expect("start the Blender session");
    wait_for_blender(&mut blender, &out, "done-0");

    let mut watch = Watcher::start(&out.join("scene.toml"), &out.join("frames"), 2, 32, &[]);
    watch.wait_for("frame #0 ");
    let steps =
        [(1, "kind=asset cause=cube.gltf"), (2, "kind=camera cause=scene.toml"), (3, "kind=asset cause=cube.rtmesh")];
    for (step, expected) in steps {
        std::fs::write(out.join(format!("go-{step}")), "").expect("signal the Blender session");
        wait_for_blender(&mut blender, &out, &format!("done-{step}"));
        let reload = watch.wait_for(&format!("reload #{step} "));
        assert!(reload.contains(expected), "step {step}: {reload}\n{}", watch.log().join("\n"));
        watch.wait_for(&format!("frame #{step} "));
        assert!(watch.frame(step - 1) != watch.frame(step), "step {step} left the image as it was");
    }
    let status = blender.wait().expect("the Blender session");
    assert!(status.success(), "the Blender session: {status}");
    assert!(!watch.log().iter().any(|l| l.starts_with("error ")), "{}", watch.log().join("\n"));
    watch.stop();
}
