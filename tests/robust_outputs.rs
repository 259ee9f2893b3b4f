//! Outputs are never lost or mixed: an unrelated `X.partial` survives a render of
//! `X.png`, renders of `X.png` and `X.exr` at once both land whole, a folder that does
//! not exist or cannot be written is an error before any rendering, a full disk is a
//! plain message with nothing left behind, SIGTERM exits cleanly, and files that look
//! like rt's leftovers are left alone.

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

/// Files that look like rt's leftovers, even one named exactly as rt names a temporary,
/// are a user's unless rt marked them: a render and a pack leave every one of them byte
/// for byte (rt's own marked leftovers are removed: `files::output`'s unit tests).
#[test]
fn files_that_look_like_leftovers_are_left_alone() {
    let dir = fresh_dir("look-alikes");
    std::fs::write(dir.join("m.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").expect("write");
    rt(&dir, &["pack", "m.obj"], DEADLINE).expect("first pack", 0);
    // PIDs on Linux stop below 2^22: 999999999 is gone.
    let users = [
        ".o.png.20240105.tmp",
        ".o.png.99999-backup.tmp",
        ".o.png.999999999.00ab.tmp",
        ".o.png.rt-999999999-00ab.tmp",
        ".o.png.rt-999999999-00000000000000AB.tmp",
        ".m.rtbvh.999999999.00ab.tmp",
        ".m.rtbvh.999999998-2.tmp",
        ".m.rtbvh.12345.tmp",
    ];
    // Named as rt names its temporary of m.rtbvh, but not made by rt (no mark): kept.
    let users = [users.as_slice(), &[".m.rtbvh.rt-999999999-00000000000000ab.tmp"]].concat();
    for name in &users {
        std::fs::write(dir.join(name), format!("someone's {name}")).expect("write");
    }
    rt(&dir, &args(&render("o.png")), DEADLINE).expect("render", 0);
    let outcome = rt(&dir, &["pack", "m.obj"], DEADLINE);
    outcome.expect("up-to-date pack", 0);
    assert!(outcome.stdout.contains("m.obj: up to date"), "{}", outcome.stdout);
    for name in &users {
        let kept = std::fs::read_to_string(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(kept, format!("someone's {name}"));
    }
    let mut expected: Vec<&str> = users.clone();
    expected.extend(["m.obj", "m.rtbvh", "o.png"]);
    expected.sort();
    assert_eq!(names(&dir), expected);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

/// Whatever files an output folder holds (random names, many shaped like rt's
/// temporaries, random bytes), renders of a PNG and an EXR there and a pack leave every
/// file they did not write byte for byte as it was.
#[test]
fn any_files_in_an_output_folder_survive_renders_byte_for_byte() {
    let dir = fresh_dir("any-files");
    let mut rng = common::TestRng(0x5eed);
    let mut pick = |n: usize| (rng.next_f64() * n as f64) as usize % n;
    let shapes =
        [".o.png.{n}.tmp", ".o.png.{n}-x.tmp", ".o.exr.rt-{n}-{h}.tmp", ".o.png.rt-{n}-{h}", "o.png.{n}", "{h}"];
    let mut files = std::collections::BTreeMap::new();
    for i in 0..200 {
        let n = [1, 42, 999_999_999, 4_194_304, 123_456_789][pick(5)];
        let h = format!("{:016x}", (i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> pick(8));
        let name = shapes[pick(shapes.len())].replace("{n}", &n.to_string()).replace("{h}", &h);
        let bytes: Vec<u8> = (0..pick(64)).map(|_| pick(256) as u8).collect();
        std::fs::write(dir.join(&name), &bytes).expect("write");
        files.insert(name, bytes);
    }
    std::fs::write(dir.join("m.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").expect("write");
    rt(&dir, &args(&render("o.png")), DEADLINE).expect("o.png", 0);
    rt(&dir, &args(&render("o.exr")), DEADLINE).expect("o.exr", 0);
    rt(&dir, &["pack", "m.obj"], DEADLINE).expect("pack", 0);
    for (name, bytes) in &files {
        let now = std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(&now == bytes, "{name} changed");
    }
    assert_eq!(names(&dir).len(), files.len() + 4, "only o.png, o.exr, m.obj and m.rtbvh besides");
    std::fs::remove_dir_all(&dir).expect("clean up");
}
