//! GPU limits: an image whose running means do not fit one storage binding of this GPU
//! (128 MiB on lavapipe: about 8.4 million pixels) is refused with a message naming the
//! limit before anything is rendered, and a scene edit asking for one in `rt watch` keeps
//! the last good image and is recovered from by the next good save.

use crate::common;

use common::{gpu, temp_dir};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A square side whose image needs more than this GPU binds in one buffer.
fn too_large_side() -> u32 {
    let max = gpu().device.limits().max_storage_buffer_binding_size;
    (((max / 16) as f64).sqrt().ceil() as u32 + 1).min(rt::scene::MAX_IMAGE_SIDE)
}

#[test]
fn an_image_beyond_the_binding_limit_is_refused_naming_it() {
    let side = too_large_side();
    let max_mib = gpu().device.limits().max_storage_buffer_binding_size >> 20;
    if side as u64 * side as u64 * 16 <= gpu().device.limits().max_storage_buffer_binding_size {
        eprintln!("this GPU binds {max_mib} MiB: every allowed size fits, nothing to refuse");
        return;
    }
    let dir = temp_dir("gpu-limit");
    let out = dir.join("huge.png");
    let run = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "--spp", "1", "--size", &format!("{side}x{side}"), "-o"])
        .arg(&out)
        .output()
        .expect("run rt");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.contains(&format!("binds at most {max_mib} MiB per buffer")), "{stderr}");
    assert!(stderr.contains("million pixels"), "{stderr}");
    assert!(!out.exists(), "a refused render wrote an image");
    let left: Vec<_> = std::fs::read_dir(&dir).expect("dir").collect();
    assert!(left.is_empty(), "the refused render left files behind");
}

fn wait_for(log: &Path, needle: &str, child: &mut std::process::Child) -> String {
    let deadline = Instant::now() + Duration::from_secs(120);
    loop {
        let text = std::fs::read_to_string(log).unwrap_or_default();
        if let Some(line) = text.lines().find(|l| l.contains(needle)) {
            return line.to_owned();
        }
        if let Ok(Some(status)) = child.try_wait() {
            panic!("rt watch exited ({status}) before {needle:?}; log:\n{text}");
        }
        assert!(Instant::now() < deadline, "no {needle:?} after 120 s; log:\n{text}");
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
fn a_watch_edit_beyond_the_limit_keeps_the_last_good_image() {
    let side = too_large_side();
    if side as u64 * side as u64 * 16 <= gpu().device.limits().max_storage_buffer_binding_size {
        return;
    }
    let dir = temp_dir("gpu-limit-watch");
    let frames = dir.join("frames");
    std::fs::create_dir_all(&frames).expect("frames");
    let scene = dir.join("scene.toml");
    let text = |w: u32, h: u32| {
        format!("[render]\nwidth = {w}\nheight = {h}\n\n[[sphere]]\ncenter = [0.0, 1.0, 0.0]\nradius = 0.5\n")
    };
    let save = |body: String| {
        let tmp = dir.join(".scene.toml.tmp");
        std::fs::write(&tmp, body).expect("write");
        std::fs::rename(&tmp, &scene).expect("rename");
    };
    save(text(8, 8));
    let mut child = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["watch", "--headless", "--spp", "1", "--frames-dir"])
        .arg(&frames)
        .arg(&scene)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start rt watch");
    let log = frames.join(rt_watch::LOG_FILE);
    wait_for(&log, "frame #0 ", &mut child);
    save(text(side, side));
    let error = wait_for(&log, "binds at most", &mut child);
    assert!(error.contains("million pixels"), "{error}");
    save(text(8, 4));
    wait_for(&log, "frame #1 ", &mut child);
    std::fs::write(frames.join(rt_watch::STOP_FILE), "").expect("stop");
    let out = child.wait_with_output().expect("rt watch ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let frame = image::open(frames.join("frame-0001.png")).expect("the recovered frame");
    assert_eq!((frame.width(), frame.height()), (8, 4));
}
