//! Outputs are never lost or mixed: an unrelated `X.partial` survives a render of
//! `X.png`, renders of `X.png` and `X.exr` at once both land whole, a folder that does
//! not exist or cannot be written is an error before any rendering, a full disk is a
//! plain message with nothing left behind, SIGTERM exits cleanly, and the temporaries
//! of a killed `rt pack` are removed by the next run once their process is gone.

use crate::common;

use common::bounded::{fresh_dir, names, rt, run, run_signalled};
use std::process::Command;
use std::time::Duration;

const DEADLINE: Duration = Duration::from_secs(120);
const SMALL: [&str; 4] = ["--size", "16x16", "--spp", "1"];

fn render(output: &str) -> Vec<String> {
    let mut args = vec!["render", "-o", output];
    args.extend(SMALL);
    args.iter().map(|s| s.to_string()).collect()
}

fn args(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

#[test]
fn an_unrelated_partial_file_survives() {
    let dir = fresh_dir("partial");
    std::fs::write(dir.join("out.partial"), "someone's notes").expect("write");
    std::fs::create_dir(dir.join("pic.partial")).expect("a folder named like the old temporary");
    rt(&dir, &args(&render("out.png")), DEADLINE).expect("out.png", 0);
    rt(&dir, &args(&render("pic.exr")), DEADLINE).expect("pic.exr", 0);
    assert_eq!(std::fs::read_to_string(dir.join("out.partial")).expect("read"), "someone's notes");
    image::open(dir.join("out.png")).expect("a whole PNG");
    image::open(dir.join("pic.exr")).expect("a whole EXR");
    assert_eq!(names(&dir), ["out.partial", "out.png", "pic.exr", "pic.partial"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn png_and_exr_of_one_name_rendered_at_once_both_land() {
    let dir = fresh_dir("same-stem");
    let spawn = |output: &str| {
        let mut command = Command::new(env!("CARGO_BIN_EXE_rt"));
        command.args(render(output)).current_dir(&dir);
        std::thread::spawn(move || run(command, DEADLINE))
    };
    for round in 0..3 {
        let (png, exr) = (spawn("x.png"), spawn("x.exr"));
        png.join().expect("png run").expect(&format!("x.png, round {round}"), 0);
        exr.join().expect("exr run").expect(&format!("x.exr, round {round}"), 0);
        let png = image::open(dir.join("x.png")).expect("a whole PNG");
        let exr = image::open(dir.join("x.exr")).expect("a whole EXR");
        assert_eq!((png.width(), exr.width()), (16, 16));
        assert!(matches!(png, image::DynamicImage::ImageRgb8(_)), "the PNG holds 8-bit sRGB");
        assert!(matches!(exr, image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)));
        assert_eq!(names(&dir), ["x.exr", "x.png"]);
    }
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn an_output_folder_that_cannot_take_the_image_fails_before_rendering() {
    let dir = fresh_dir("folders");
    std::fs::write(dir.join("afile"), "").expect("write");
    std::fs::create_dir(dir.join("taken.png")).expect("folder");
    let cases: [(&str, &str); 4] = [
        ("missing/out.png", "missing/out.png: cannot write there: the folder missing does not exist"),
        ("afile/out.png", "afile/out.png: cannot write there: afile is a file, not a folder"),
        ("taken.png", "taken.png: is a folder, not a file: rt replaces only files"),
        // Nobody, root included, creates files in /proc.
        ("/proc/out.png", "/proc: cannot create files in this folder"),
    ];
    for (output, message) in cases {
        let outcome = rt(&dir, &args(&render(output)), DEADLINE);
        outcome.expect(output, 1).says(output, &[message]);
        assert!(!outcome.stderr.contains("GPU:"), "{output}: the GPU was opened before the check:\n{}", outcome.stderr);
    }
    assert_eq!(names(&dir), ["afile", "taken.png"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

/// In a private mount namespace (as root, or as a user through a user namespace), with
/// a 64 KiB tmpfs at `dir/full` filled but for 4 KiB: neither a 128x128 EXR (196 KiB of
/// pixels) nor the PNG fits.
#[test]
fn a_full_disk_is_named_and_leaves_nothing_behind() {
    let dir = fresh_dir("full-disk");
    std::fs::create_dir(dir.join("full")).expect("mount point");
    std::fs::write(dir.join("full/kept.png"), "an older render").expect("write");
    let script = format!(
        "cp full/kept.png kept && mount -t tmpfs -o size=64k tmpfs full && cp kept full/kept.png || exit 99
         head -c 57344 /dev/zero > full/filler
         {rt} render -o full/big.exr --size 128x128 --spp 1; echo status=$?
         {rt} render -o full/kept.png --size 128x128 --spp 1; echo status=$?
         echo files=$(ls -A full | tr '\\n' ' '); cat full/kept.png",
        rt = env!("CARGO_BIN_EXE_rt")
    );
    let mut command = Command::new("unshare");
    command.args(["-rm", "sh", "-c", &script]).current_dir(&dir);
    let outcome = run(command, DEADLINE);
    if outcome.code == Some(99) || outcome.stderr.contains("unshare:") {
        eprintln!("skipped: no tmpfs can be mounted here ({})", outcome.stderr.trim());
        return;
    }
    assert!(!outcome.stderr.contains("panicked"), "{}", outcome.stderr);
    assert_eq!(
        outcome.stderr.matches("no space left on device (nothing was left behind)").count(),
        2,
        "{}",
        outcome.stderr
    );
    assert!(outcome.stdout.contains("status=1\nstatus=1\n"), "{}", outcome.stdout);
    // The PNG that could not be replaced is still the older one, and no temporary is left.
    assert!(outcome.stdout.contains("files=filler kept.png\nan older render"), "{}", outcome.stdout);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn sigterm_and_sigint_exit_cleanly_with_nothing_left_behind() {
    let dir = fresh_dir("signals");
    for (signal, code) in [(libc::SIGTERM, 143), (libc::SIGINT, 130)] {
        let mut command = Command::new(env!("CARGO_BIN_EXE_rt"));
        command.args(["render", "-o", "long.exr", "--size", "64x64", "--spp", "100000"]).current_dir(&dir);
        let outcome = run_signalled(command, DEADLINE, Some((Duration::from_secs(3), signal)));
        outcome.expect(&format!("signal {signal}"), code).says("signal", &["rt: interrupted"]);
        assert!(names(&dir).is_empty(), "{:?}", names(&dir));
    }
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn temporaries_of_a_killed_pack_are_removed_once_their_process_is_gone() {
    let dir = fresh_dir("stale");
    std::fs::write(dir.join("m.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").expect("write");
    rt(&dir, &["pack", "m.obj"], DEADLINE).expect("first pack", 0);
    // PIDs on Linux stop below 2^22: 999999999 and 999999998 are gone; this test is not.
    let alive = format!(".m.rtbvh.{}.0123.tmp", std::process::id());
    for name in [".m.rtbvh.999999999.00ab.tmp", ".m.rtbvh.999999998-2.tmp", &alive] {
        std::fs::write(dir.join(name), "half a cache").expect("write");
    }
    let outcome = rt(&dir, &["pack", "m.obj"], DEADLINE);
    outcome.expect("up-to-date pack", 0);
    assert!(outcome.stdout.contains("m.obj: up to date"), "{}", outcome.stdout);
    assert_eq!(names(&dir), [alive.as_str(), "m.obj", "m.rtbvh"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}
