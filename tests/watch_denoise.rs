//! `rt watch --denoise` through the real binary: the headless frame is the denoise of the
//! converged state, closer to a converged render than the raw frame of the same samples
//! written beside it; refinement goes on while the denoiser runs; a reload gets a denoise
//! of its own state, never one of the state before; and a missing library stops
//! `rt watch --denoise` at start, as it stops `rt render --denoise`. The window's test is
//! in `watch_denoise/window.rs`.

use crate::common;

use common::temp_dir;
use std::path::PathBuf;
use std::process::Command;

/// The Cornell box with a ball of `color` in it, refined to `spp` (its `[render]` spp).
fn scene_text(color: [f32; 3], spp: u32) -> String {
    let box_obj = common::repo().join("assets/cornell_box/cornell_box.obj");
    format!(
        r#"[render]
spp = {spp}
max_bounces = 6

[camera]
position = [0.0, 1.0, 4.0]
look_at = [0.0, 1.0, 0.0]
fov_y_deg = 36.0

[sky]
kind = "black"

[materials.ball]
base_color = [{}, {}, {}]

[[mesh]]
asset = "{}"

[[sphere]]
center = [0.0, 0.4, 0.0]
radius = 0.4
material = "ball"
"#,
        color[0],
        color[1],
        color[2],
        box_obj.display()
    )
}

/// A fresh folder with `scene.toml`; returns it and its frames folder.
fn project(name: &str, text: &str) -> (PathBuf, PathBuf) {
    let dir = temp_dir(name);
    let _ = std::fs::remove_dir_all(dir.join("frames"));
    std::fs::write(dir.join("scene.toml"), text).expect("scene");
    (dir.join("scene.toml"), dir.join("frames"))
}

/// A build without Open Image Denoise refuses `rt watch --denoise` as it refuses
/// `rt render --denoise`, before anything else.
#[cfg(not(feature = "denoise"))]
#[test]
fn a_build_without_open_image_denoise_refuses_watch_denoise() {
    let (scene, frames) = project("watch-no-oidn", &scene_text([0.8, 0.8, 0.8], 1));
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["watch", "--headless", "--denoise", "--frames-dir"])
        .arg(&frames)
        .arg(&scene)
        .output()
        .expect("run rt watch");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("built without Open Image Denoise") && stderr.contains("--features denoise"), "{stderr}");
    assert!(!frames.exists(), "{stderr}");
}

/// `--denoise` is for the window and headless mode: a stream's client gets raw frames.
#[test]
fn denoise_is_not_an_option_of_stream() {
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["watch", "--stream", "--denoise", "scene.toml"])
        .output()
        .expect("run rt watch");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--denoise") && stderr.contains("--stream"), "{stderr}");
}

#[cfg(feature = "denoise")]
mod window;

/// What needs Open Image Denoise.
#[cfg(feature = "denoise")]
mod with_open_image_denoise {
    use super::{common, project, scene_text, temp_dir};
    use std::path::Path;
    use std::process::{Child, Command, Stdio};
    use std::time::{Duration, Instant};

    pub(super) const SIZE: u32 = 64;

    /// `rt watch --headless --denoise` on `scene`, EXR frames, with `extra` flags.
    fn start(scene: &Path, frames: &Path, extra: &[&str]) -> Child {
        Command::new(env!("CARGO_BIN_EXE_rt"))
            .args(["watch", "--headless", "--denoise", "--format", "exr", "--size", &format!("{SIZE}x{SIZE}")])
            .args(extra)
            .arg("--frames-dir")
            .arg(frames)
            .arg(scene)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start rt watch")
    }

    fn log(frames: &Path) -> Vec<String> {
        let text = std::fs::read_to_string(frames.join(rt_watch::LOG_FILE)).unwrap_or_default();
        text.lines().map(str::to_owned).collect()
    }

    /// Waits until `count` log lines start with `prefix`.
    fn wait_for(child: &mut Child, frames: &Path, prefix: &str, count: usize) {
        let deadline = Instant::now() + Duration::from_secs(180);
        while log(frames).iter().filter(|l| l.starts_with(prefix)).count() < count {
            if let Ok(Some(status)) = child.try_wait() {
                panic!("rt watch exited ({status}) before {prefix:?}:\n{}", log(frames).join("\n"));
            }
            assert!(Instant::now() < deadline, "no {count} {prefix:?} lines:\n{}", log(frames).join("\n"));
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    fn stop(child: Child, frames: &Path) {
        std::fs::write(frames.join(rt_watch::STOP_FILE), "").expect("stop file");
        let out = child.wait_with_output().expect("wait for rt watch");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success() && !stderr.contains("panicked"), "rt watch: {}\n{stderr}", out.status);
    }

    fn exr(path: &Path) -> Vec<[f32; 3]> {
        let image = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).into_rgb32f();
        image.pixels().map(|p| p.0).collect()
    }

    /// `denoise #N spp=S ms=T refined_to=R` lines of state `number`: (S, R).
    fn denoises(log: &[String], number: u32) -> Vec<(u32, u32)> {
        let field = |line: &str, key: &str| -> u32 {
            let value = line.split(' ').find_map(|f| f.strip_prefix(key)).unwrap_or_else(|| panic!("{key} in {line}"));
            value.parse().unwrap_or_else(|e| panic!("{line}: {e}"))
        };
        let prefix = format!("denoise #{number} ");
        log.iter().filter(|l| l.starts_with(&prefix)).map(|l| (field(l, "spp="), field(l, "refined_to="))).collect()
    }

    /// What `rt watch --denoise` renders of `scene` at `spp` (seed 0, its AOVs), rendered here.
    pub(super) fn render_here(scene: &Path, spp: u32) -> (rt::render::Image, rt::render::Aovs) {
        let mut scene = rt::scene::load(scene).unwrap_or_else(|e| panic!("{e}"));
        let flags =
            rt::render::RenderFlags { spp: Some(spp), size: Some((SIZE, SIZE)), aovs: true, ..Default::default() };
        let request = flags.apply(&mut scene).unwrap_or_else(|e| panic!("{e:#}"));
        let mut session = rt::render::Session::open(common::gpu(), scene, rt::bvh::BuildQuality::default())
            .unwrap_or_else(|e| panic!("{e:#}"));
        let (image, _) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
        let aovs = session.aovs().unwrap_or_else(|e| panic!("{e:#}"));
        (image, aovs)
    }

    fn worst_difference(a: &[[f32; 3]], b: &[[f32; 3]]) -> f32 {
        a.iter()
            .zip(b)
            .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs() / (1.0 + b[c].abs())))
            .fold(0.0, f32::max)
    }

    pub(super) fn denoise_here(image: &rt::render::Image, aovs: &rt::render::Aovs) -> Vec<[f32; 3]> {
        let mut denoiser =
            rt::denoise::Denoiser::new(rt::denoise::DenoiseDevice::Auto).unwrap_or_else(|e| panic!("{e:#}"));
        denoiser.denoise(image, aovs).unwrap_or_else(|e| panic!("{e:#}"))
    }

    #[test]
    fn the_headless_frame_is_denoised_and_refinement_goes_on_while_the_denoiser_runs() {
        let spp = 32;
        let (scene, frames) = project("watch-denoise-frame", &scene_text([0.8, 0.8, 0.8], spp));
        let mut child = start(&scene, &frames, &["--max-reloads", "0"]);
        wait_for(&mut child, &frames, "frame #0 ", 1);
        stop(child, &frames);
        let log = log(&frames);
        let frame_line = log.iter().find(|l| l.starts_with("frame #0 ")).expect("frame line");
        assert!(frame_line.contains("file=frame-0000.exr raw=frame-0000-raw.exr"), "{frame_line}");
        assert!(log.iter().any(|l| l.starts_with("denoising with Open Image Denoise on ")), "{log:#?}");

        // Denoised from 4 samples on, again once they doubled (a dispatch takes several, so
        // at the first dispatch past each mark), then the converged image; each but the last
        // came back after refinement had gone past it: it never waited for the denoiser.
        let runs = denoises(&log, 0);
        let samples: Vec<u32> = runs.iter().map(|r| r.0).collect();
        eprintln!("denoises (spp, refined to when it came back): {runs:?}");
        assert!(samples.len() >= 2 && samples[0] >= 4 && samples[0] < spp, "{log:#?}");
        assert_eq!(samples.last(), Some(&spp), "the converged image is denoised: {log:#?}");
        assert!(samples.windows(2).all(|w| w[1] >= 2 * w[0] || w[1] == spp), "{samples:?}");
        for &(denoised, refined) in &runs {
            if denoised < spp {
                assert!(refined > denoised, "refinement waited for the denoise of {denoised} spp: {runs:?}");
            }
        }

        // The raw frame is the render of the state; the frame is its denoise.
        let (denoised, raw) = (exr(&frames.join("frame-0000.exr")), exr(&frames.join("frame-0000-raw.exr")));
        let (image, aovs) = render_here(&scene, spp);
        assert!(worst_difference(&raw, &image.pixels) < 1e-5, "the raw frame is not the state's render");
        let expected = denoise_here(&image, &aovs);
        let off = worst_difference(&denoised, &expected);
        eprintln!("the frame vs the denoise of the same render made here: worst relative difference {off:.2e}");
        assert!(off < 1e-3, "the frame is not the denoise of the converged image: off by {off}");

        // Against a converged render (two halves of independent samples: their difference
        // measures its own noise, taken off each error).
        let mut reference = rt::scene::load(&scene).unwrap_or_else(|e| panic!("{e}"));
        reference.render.spp = 256;
        let half = |seed: u32| {
            common::render_request(reference.clone(), |r| (r.width, r.height, r.seed) = (SIZE, SIZE, seed)).0.pixels
        };
        let (a, b) = (half(11), half(12));
        let converged: Vec<[f32; 3]> = a.iter().zip(&b).map(|(a, b)| [0, 1, 2].map(|c| 0.5 * (a[c] + b[c]))).collect();
        let own_noise = common::display_mse(&a, &b) / 4.0;
        let error = |pixels: &[[f32; 3]]| (common::display_mse(pixels, &converged) - own_noise).max(0.0).sqrt();
        let (raw_error, denoised_error) = (error(&raw), error(&denoised));
        eprintln!(
            "display RMSE against 512 spp (its own noise {:.2}): raw {spp} spp {raw_error:.2}, denoised {denoised_error:.2}",
            own_noise.sqrt()
        );
        assert!(denoised_error < 0.7 * raw_error, "denoised {denoised_error:.2} vs raw {raw_error:.2}");
    }

    #[test]
    fn a_reload_gets_a_denoise_of_its_own_state_never_of_the_last() {
        // The first state refines on and on, denoised as it goes; the edit turns the ball red
        // and asks for 64 spp, so its frame comes soon.
        let (scene, frames) = project("watch-denoise-reload", &scene_text([0.8, 0.8, 0.8], 100_000));
        let mut child = start(&scene, &frames, &[]);
        wait_for(&mut child, &frames, "denoise #0 ", 3);
        let red = scene_text([0.9, 0.1, 0.1], 64);
        let tmp = scene.with_file_name(".scene.toml.tmp");
        std::fs::write(&tmp, &red).expect("edit");
        std::fs::rename(&tmp, &scene).expect("save");
        wait_for(&mut child, &frames, "frame #1 ", 1);
        stop(child, &frames);
        let log = log(&frames);
        let old = denoises(&log, 0);
        let new = denoises(&log, 1);
        eprintln!("state 0 denoised at {old:?}, state 1 at {new:?}");
        // The new state's denoises count its own samples from none, up to the converged
        // image's. With no denoise of the old state in flight at the reload (none dropped),
        // the first is sent at the first dispatch past 4 samples: 4 to 7, since a dispatch
        // after a restart takes one sample and each next at most twice the last's (counting
        // on from the old state's, whose last was at 16 or more, it would wait for 32).
        let samples: Vec<u32> = new.iter().map(|r| r.0).collect();
        assert!(old.last().is_some_and(|o| o.0 >= 16), "{log:#?}");
        assert!(samples.iter().all(|s| (4..=64).contains(s)) && samples.last() == Some(&64), "{log:#?}");
        let at = |prefix: &str| log.iter().position(|l| l.starts_with(prefix));
        let reload = at("reload #1 ").expect("reload line");
        assert!(at("denoise #1 ").is_some_and(|first| reload < first), "{log:#?}");
        match at("denoise dropped ") {
            None => assert!((4..=7).contains(&samples[0]), "{log:#?}"),
            Some(dropped) => assert!(reload < dropped, "a denoise dropped before the reload: {log:#?}"),
        }
        assert!(!frames.join("frame-0000.exr").exists(), "the first state never converged");

        let frame = exr(&frames.join("frame-0001.exr"));
        let (image, aovs) = render_here(&scene, 64);
        let expected = denoise_here(&image, &aovs);
        let off = worst_difference(&frame, &expected);
        // The state before, at the same samples: what a stale denoise would look like.
        let old_scene = scene.with_file_name("old.toml");
        std::fs::write(&old_scene, scene_text([0.8, 0.8, 0.8], 64)).expect("old state");
        let (old_image, old_aovs) = render_here(&old_scene, 64);
        let stale = worst_difference(&frame, &denoise_here(&old_image, &old_aovs));
        eprintln!("frame 1 vs the new state's denoise: {off:.2e}; vs the old state's: {stale:.2e}");
        assert!(off < 1e-3 && stale > 0.1, "frame 1 is not the new state's denoise: {off} (old state: {stale})");
    }

    /// Without the library, `--denoise` stops `rt watch` before any GPU or window, with what
    /// is missing and how to get it; headless, it writes nothing.
    #[test]
    fn a_missing_library_stops_watch_at_start() {
        let dir = temp_dir("watch-oidn-gone");
        let (scene, frames) = project("watch-oidn-gone-scene", &scene_text([0.8, 0.8, 0.8], 1));
        let run = |args: &[&str]| {
            let out = Command::new(env!("CARGO_BIN_EXE_rt"))
                .arg("watch")
                .args(args)
                .arg(&scene)
                .env("OIDN_DIR", &dir)
                .env_remove("LD_LIBRARY_PATH")
                // No display: the error must come before any window is opened.
                .env_remove("DISPLAY")
                .env_remove("WAYLAND_DISPLAY")
                .output()
                .expect("run rt watch");
            (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
        };
        let frames_dir = frames.to_str().expect("a UTF-8 path");
        for args in [&["--headless", "--denoise", "--frames-dir", frames_dir][..], &["--denoise"][..]] {
            let (code, stderr) = run(args);
            assert_eq!(code, Some(1), "{args:?}: {stderr}");
            let missing = dir.join("lib").join("libOpenImageDenoise.so.2");
            for part in
                ["--denoise", "Open Image Denoise is missing", &missing.display().to_string(), "scripts/fetch_oidn"]
            {
                assert!(stderr.contains(part), "{args:?}: no {part:?} in: {stderr}");
            }
            assert!(!stderr.contains("GPU:") && !stderr.contains("window"), "{args:?}: not at start: {stderr}");
        }
        assert!(!frames.exists(), "headless wrote into its frames folder");
        let _ = std::fs::remove_dir_all(dir);
    }
}
