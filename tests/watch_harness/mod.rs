//! A running `rt watch --headless` for the tests: its log, its frames, and stopping it;
//! and a Blender session editing what it watches.

mod blender;

pub use blender::{edit_and_expect_reload, watch_blender_session};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A running `rt watch --headless`, stopped through its stop file when dropped.
pub struct Watcher {
    child: Child,
    frames: PathBuf,
    /// Its stderr: the errors the tests provoke on purpose stay out of the test log.
    stderr: PathBuf,
}

impl Watcher {
    /// Watches `scene` at `size`×`size` pixels and `spp`, writing EXR frames into `frames`.
    pub fn start(scene: &Path, frames: &Path, spp: u32, size: u32, extra: &[&std::ffi::OsStr]) -> Self {
        let stderr = frames.with_extension("stderr");
        let stderr_file = std::fs::File::create(&stderr).expect("stderr file");
        let child = Command::new(env!("CARGO_BIN_EXE_rt"))
            .args(["watch", "--headless", "--format", "exr", "--spp", &spp.to_string()])
            .args(extra)
            .args(["--size", &format!("{size}x{size}"), "--frames-dir"])
            .arg(frames)
            .arg(scene)
            .stdout(Stdio::null())
            .stderr(stderr_file)
            .spawn()
            .expect("start rt watch");
        Self { child, frames: frames.to_path_buf(), stderr }
    }

    fn stderr(&self) -> String {
        std::fs::read_to_string(&self.stderr).unwrap_or_default()
    }

    pub fn log(&self) -> Vec<String> {
        std::fs::read_to_string(self.frames.join(rt_watch::LOG_FILE))
            .unwrap_or_default()
            .lines()
            .map(str::to_owned)
            .collect()
    }

    /// Waits until a log line starts with `prefix`; returns it.
    pub fn wait_for(&mut self, prefix: &str) -> String {
        let deadline = Instant::now() + Duration::from_secs(120);
        loop {
            if let Some(line) = self.log().into_iter().find(|l| l.starts_with(prefix)) {
                return line;
            }
            if let Ok(Some(status)) = self.child.try_wait() {
                panic!(
                    "rt watch exited ({status}) before {prefix:?}; log:\n{}\n{}",
                    self.log().join("\n"),
                    self.stderr()
                );
            }
            assert!(Instant::now() < deadline, "no {prefix:?} after 120 s; log:\n{}", self.log().join("\n"));
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    pub fn frame(&self, number: u32) -> Vec<[f32; 3]> {
        let path = self.frames.join(format!("frame-{number:04}.exr"));
        let image = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).into_rgb32f();
        image.pixels().map(|p| p.0).collect()
    }

    pub fn stop(mut self) {
        std::fs::write(self.frames.join(rt_watch::STOP_FILE), "").expect("stop file");
        let status = self.child.wait().expect("wait for rt watch");
        assert!(status.success(), "rt watch: {status}\n{}", self.stderr());
        assert!(!self.stderr().contains("panicked"), "rt watch panicked:\n{}", self.stderr());
    }
}

impl Drop for Watcher {
    fn drop(&mut self) {
        let _ = std::fs::write(self.frames.join(rt_watch::STOP_FILE), "");
        let _ = self.child.kill();
        let _ = std::fs::remove_file(&self.stderr);
    }
}
