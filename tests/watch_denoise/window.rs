//! `rt watch --denoise`'s window on a virtual X server (Xvfb): a converged state's frame
//! is the display of its denoise, the title says `denoised` while it is shown, and `N`
//! (pressed through XTest) turns it to `raw` and back.

use super::with_open_image_denoise::{SIZE, denoise_here, render_here};
use super::{project, scene_text};
use rt::render::tonemap::display_pixel;
use std::ffi::{CStr, CString};
use std::io::{BufRead, BufReader};
use std::os::raw::c_ulong;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};
use x11_dl::{keysym, xlib, xtest};

const DEADLINE: Duration = Duration::from_secs(120);

/// A virtual X server on a display of its own choosing, killed when dropped.
struct Xvfb {
    child: Child,
    display: String,
}

impl Xvfb {
    fn start() -> Self {
        // `-displayfd 1`: it picks a free display and writes its number to our pipe.
        let mut child = Command::new("Xvfb")
            .args(["-displayfd", "1", "-screen", "0", "640x480x24", "-nolisten", "tcp"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("Xvfb is needed for the window test (scripts/test installs the xvfb package)");
        let mut line = String::new();
        BufReader::new(child.stdout.take().expect("Xvfb's stdout")).read_line(&mut line).expect("display number");
        Self { child, display: format!(":{}", line.trim()) }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A client of the X server: finds rt's window by its title and presses keys in it.
struct X {
    xlib: xlib::Xlib,
    xtest: xtest::Xf86vmode,
    display: *mut xlib::Display,
}

impl X {
    fn open(name: &str) -> Self {
        let xlib = xlib::Xlib::open().expect("libX11");
        let xtest = xtest::Xf86vmode::open().expect("libXtst (the libxtst6 package)");
        let name = CString::new(name).expect("display name");
        let display = unsafe { (xlib.XOpenDisplay)(name.as_ptr()) };
        assert!(!display.is_null(), "cannot open the X display {name:?}");
        Self { xlib, xtest, display }
    }

    /// The top-level window whose title starts with "rt watch", and its title.
    fn rt_window(&self) -> Option<(c_ulong, String)> {
        let x = &self.xlib;
        unsafe {
            let root = (x.XDefaultRootWindow)(self.display);
            let (mut root_out, mut parent, mut children, mut count) = (0, 0, std::ptr::null_mut(), 0);
            if (x.XQueryTree)(self.display, root, &mut root_out, &mut parent, &mut children, &mut count) == 0 {
                return None;
            }
            let windows: Vec<c_ulong> = if children.is_null() {
                Vec::new()
            } else {
                std::slice::from_raw_parts(children, count as usize).to_vec()
            };
            if !children.is_null() {
                (x.XFree)(children.cast());
            }
            windows.into_iter().find_map(|window| {
                let mut name = std::ptr::null_mut();
                if (x.XFetchName)(self.display, window, &mut name) == 0 || name.is_null() {
                    return None;
                }
                let title = CStr::from_ptr(name).to_string_lossy().into_owned();
                (x.XFree)(name.cast());
                title.starts_with("rt watch").then_some((window, title))
            })
        }
    }

    /// Waits until rt's window has a title that `wanted` accepts; returns it.
    fn wait_for_title(&self, rt: &mut Child, what: &str, wanted: impl Fn(&str) -> bool) -> (c_ulong, String) {
        let start = Instant::now();
        let mut last = None;
        loop {
            if let Some((window, title)) = self.rt_window() {
                if wanted(&title) {
                    return (window, title);
                }
                last = Some(title);
            }
            if let Ok(Some(status)) = rt.try_wait() {
                panic!("rt watch exited ({status}) before its title {what}; last title {last:?}");
            }
            assert!(start.elapsed() < DEADLINE, "the title never {what}; last title {last:?}");
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Presses and releases `key` (a keysym) in `window`, through XTest.
    fn press(&self, window: c_ulong, key: u32) {
        unsafe {
            (self.xlib.XSetInputFocus)(self.display, window, xlib::RevertToParent, xlib::CurrentTime);
            let code = (self.xlib.XKeysymToKeycode)(self.display, key.into()) as u32;
            (self.xtest.XTestFakeKeyEvent)(self.display, code, 1, 0);
            (self.xtest.XTestFakeKeyEvent)(self.display, code, 0, 0);
            (self.xlib.XSync)(self.display, 0);
        }
    }
}

impl Drop for X {
    fn drop(&mut self) {
        unsafe { (self.xlib.XCloseDisplay)(self.display) };
    }
}

fn log(frames: &Path) -> String {
    std::fs::read_to_string(frames.join(rt_watch::LOG_FILE)).unwrap_or_default()
}

#[test]
fn the_window_shows_the_denoise_says_so_and_n_toggles_it() {
    let spp = 16;
    let (scene, frames) = project("watch-denoise-window", &scene_text([0.8, 0.8, 0.8], spp));
    let xvfb = Xvfb::start();
    let x = X::open(&xvfb.display);
    let mut rt = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["watch", "--denoise", "--size", &format!("{SIZE}x{SIZE}"), "--frames-dir"])
        .arg(&frames)
        .arg(&scene)
        .env("DISPLAY", &xvfb.display)
        .env_remove("WAYLAND_DISPLAY")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start rt watch");
    let start = Instant::now();
    while !log(&frames).contains("frame #0 ") {
        if let Ok(Some(status)) = rt.try_wait() {
            panic!("rt watch exited ({status}):\n{}", log(&frames));
        }
        assert!(start.elapsed() < DEADLINE, "no frame:\n{}", log(&frames));
        std::thread::sleep(Duration::from_millis(20));
    }
    let converged = format!("{spp}/{spp} spp");
    let (window, title) =
        x.wait_for_title(&mut rt, "said denoised", |t| t.contains(&converged) && t.ends_with(" | denoised"));
    eprintln!("title: {title}");
    x.press(window, keysym::XK_n);
    let (_, title) = x.wait_for_title(&mut rt, "said raw after N", |t| t.ends_with(" | raw"));
    eprintln!("after N: {title}");
    x.press(window, keysym::XK_n);
    x.wait_for_title(&mut rt, "said denoised after N again", |t| t.ends_with(" | denoised"));

    std::fs::write(frames.join(rt_watch::STOP_FILE), "").expect("stop file");
    let out = rt.wait_with_output().expect("wait for rt watch");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !stderr.contains("panicked"), "rt watch: {}\n{stderr}", out.status);

    // The converged state's frame is the display of its own denoise, not of an earlier one.
    let shown = image::open(frames.join("frame-0000.png")).expect("the window's frame").into_rgb8();
    let (image, aovs) = render_here(&scene, spp);
    let denoised = denoise_here(&image, &aovs);
    let worst = shown
        .pixels()
        .zip(&denoised)
        .flat_map(|(shown, linear)| {
            let expected = display_pixel(*linear, 0.0);
            (0..3).map(move |c| (shown.0[c] as i32 - expected[c] as i32).abs())
        })
        .max()
        .unwrap_or(i32::MAX);
    assert!(worst <= 1, "the window's frame differs from the state's denoise by up to {worst}/255");
}
