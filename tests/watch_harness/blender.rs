//! A Blender session that edits a scene step by step while `rt watch --headless` watches
//! what it exports: the live tests' start-up and their edit-and-reload steps.

use super::Watcher;
use crate::common::{bpy_python, empty_temp_dir, repo};
use std::path::{Path, PathBuf};
use std::process::Child;
use std::time::{Duration, Instant};

/// A bpy script run on a folder: it exports its scene there and writes `done-0`, then
/// for each step N waits for `go-N`, makes its edit and writes `done-N`.
pub struct BlenderSession {
    child: Child,
    out: PathBuf,
}

impl BlenderSession {
    /// Starts `tests/blender/SCRIPT` on `out` and waits for its first export.
    pub fn start(script: &str, out: &Path) -> Self {
        let child = std::process::Command::new(bpy_python())
            .arg(repo().join("tests/blender").join(script))
            .arg(out)
            .spawn()
            .expect("start the Blender session");
        let mut session = Self { child, out: out.to_path_buf() };
        session.wait_for("done-0");
        session
    }

    /// Lets the session make edit `step` and waits until it has.
    pub fn step(&mut self, step: u32) {
        std::fs::write(self.out.join(format!("go-{step}")), "").expect("signal the Blender session");
        self.wait_for(&format!("done-{step}"));
    }

    /// Waits for the session to write `name`.
    fn wait_for(&mut self, name: &str) {
        let deadline = Instant::now() + Duration::from_secs(300);
        while !self.out.join(name).exists() {
            if let Ok(Some(status)) = self.child.try_wait() {
                panic!("the Blender session exited ({status}) before writing {name}");
            }
            assert!(Instant::now() < deadline, "the Blender session wrote no {name} in 300 s");
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Waits for the session to end; it must succeed.
    pub fn finish(mut self) {
        let status = self.child.wait().expect("the Blender session");
        assert!(status.success(), "the Blender session: {status}");
    }
}

/// `tests/blender/SCRIPT` on a fresh folder `name`, and `rt watch --headless` (2 spp,
/// 32×32) on its export once the first frame is out: the session, the watcher, the folder.
pub fn watch_blender_session(script: &str, name: &str) -> (BlenderSession, Watcher, PathBuf) {
    let out = empty_temp_dir(name);
    let blender = BlenderSession::start(script, &out);
    let mut watch = Watcher::start(&out.join("scene.toml"), &out.join("frames"), 2, 32, &[]);
    watch.wait_for("frame #0 ");
    (blender, watch, out)
}

/// Makes edit `step` in Blender; rt must reload once for it, the reload line containing
/// `expected`, and draw a new image.
pub fn edit_and_expect_reload(blender: &mut BlenderSession, watch: &mut Watcher, step: u32, expected: &str) {
    blender.step(step);
    let reload = watch.wait_for(&format!("reload #{step} "));
    assert!(reload.contains(expected), "step {step}: {reload}\n{}", watch.log().join("\n"));
    watch.wait_for(&format!("frame #{step} "));
    assert!(watch.frame(step - 1) != watch.frame(step), "step {step} left the image as it was");
}
