//! Bad input gives a clear error naming the file, a non-zero exit, and no panic.

use crate::common;

use common::{temp_dir, write};
use std::path::Path;
use std::process::Command;

/// Runs `rt render SCENE` and returns (exit code, stderr).
fn render(scene: &Path) -> (i32, String) {
    let out_png = scene.with_extension("png");
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "--size", "8x8", "--spp", "1", "-o"])
        .arg(&out_png)
        .arg(scene)
        .output()
        .expect("run rt");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "rt panicked:\n{stderr}");
    assert!(!out_png.exists() || out.status.success(), "a failed render left an image");
    (out.status.code().unwrap_or(-1), stderr)
}

fn expect_error(name: &str, files: &[(&str, &str)], needles: &[&str]) {
    let dir = temp_dir(&format!("bad-{name}"));
    for (file, text) in files {
        write(&dir.join(file), text);
    }
    let scene = dir.join("scene.toml");
    let (code, stderr) = render(&scene);
    assert_eq!(code, 1, "{name}: exit code {code}, stderr:\n{stderr}");
    for needle in needles {
        let needle = needle.replace("{dir}", &dir.display().to_string());
        assert!(stderr.contains(&needle), "{name}: {needle:?} missing from:\n{stderr}");
    }
}

const CAMERA: &str = "[camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\n";

#[test]
fn malformed_toml_names_file_and_line() {
    expect_error("malformed", &[("scene.toml", "[camera]\nposition = [0.0, 0.0\n")], &["{dir}/scene.toml:2:"]);
}

#[test]
fn unknown_key_suggests_the_right_one() {
    expect_error(
        "unknown-key",
        &[("scene.toml", "[camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_dg = 40.0\n")],
        &["{dir}/scene.toml:4:1:", "fov_y_dg", "did you mean `fov_y_deg`"],
    );
}

#[test]
fn negative_radius_names_the_line() {
    expect_error(
        "radius",
        &[("scene.toml", &format!("{CAMERA}[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = -1.0\n"))],
        &["{dir}/scene.toml:6:", "radius"],
    );
}

#[test]
fn missing_asset_names_the_file() {
    expect_error(
        "missing",
        &[("scene.toml", &format!("{CAMERA}[[mesh]]\nasset = \"nowhere/ghost.obj\"\n"))],
        &["{dir}/nowhere/ghost.obj"],
    );
}

#[test]
fn obj_with_out_of_range_index_names_the_file() {
    expect_error(
        "obj-index",
        &[
            ("scene.toml", &format!("{CAMERA}[[mesh]]\nasset = \"bad.obj\"\n")),
            ("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n"),
        ],
        &["{dir}/bad.obj"],
    );
}

#[test]
fn obj_with_nan_vertex_names_the_file() {
    expect_error(
        "obj-nan",
        &[
            ("scene.toml", &format!("{CAMERA}[[mesh]]\nasset = \"nan.obj\"\n")),
            ("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
        ],
        &["{dir}/nan.obj", "vertex 1"],
    );
}

#[test]
fn unknown_output_type_is_refused_before_rendering() {
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "--size", "8x8", "--spp", "1", "-o", "picture.jpg"])
        .output()
        .expect("run rt");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("picture.jpg"), "{stderr}");
}

/// Runs `rt render ARGS` on the built-in scene (at 8x8, 1 spp unless ARGS say otherwise)
/// and returns (exit code, stderr).
fn rt(args: &[&str]) -> (i32, String) {
    let dir = temp_dir("flags");
    let spp: &[&str] = if args.contains(&"--spp") { &[] } else { &["--spp", "1"] };
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "--size", "8x8", "-o"])
        .arg(dir.join("out.png"))
        .args(spp)
        .args(args)
        .output()
        .expect("run rt");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "rt panicked:\n{stderr}");
    (out.status.code().unwrap_or(-1), stderr)
}

/// Flags are checked by the rules of the keys they override, before any GPU work.
#[test]
fn flags_are_checked_like_keys() {
    for (args, needle) in [
        (&["--exposure", "nan"][..], "--exposure: must be finite, got NaN"),
        (&["--exposure", "inf"][..], "--exposure: must be finite, got inf"),
        (&["--ris-candidates", "0"][..], "--ris-candidates: must be in 1..=64, got 0"),
        (&["--spp", "0"][..], "--spp: must be at least 1, got 0"),
        (&["--clamp=-1"][..], "--clamp: must be a positive, finite luminance, got -1"),
        (&["--samples-per-dispatch", "0"][..], "--samples-per-dispatch: must be in 1..=1024, got 0"),
    ] {
        let (code, stderr) = rt(args);
        assert_eq!(code, 1, "{args:?}: exit code {code}, stderr:\n{stderr}");
        assert!(stderr.contains(needle), "{args:?}: {needle:?} missing from:\n{stderr}");
        assert!(!stderr.contains("GPU:"), "{args:?}: the GPU was opened before the flags were checked");
    }
}

/// A usage error is clap's exit status 2, not a failed render's 1.
#[test]
fn usage_errors_exit_with_status_2() {
    for args in [&["--no-such-flag"][..], &["--spp", "many"][..]] {
        let (code, stderr) = rt(args);
        assert_eq!(code, 2, "{args:?}: exit code {code}, stderr:\n{stderr}");
    }
}

/// `--microfacet` overrides the scene's `[render] microfacet`: a rough metal's pipeline
/// drops multiscatter GGX with `single` and keeps it by default.
#[test]
fn microfacet_flag_overrides_the_scene() {
    let dir = temp_dir("microfacet-flag");
    let scene = dir.join("scene.toml");
    write(
        &scene,
        &format!(
            "{CAMERA}[materials.metal]\nreflection = 1.0\ndiffuse = 0.0\nroughness = 0.5\n\
             [[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"metal\"\n"
        ),
    );
    let scene = scene.to_str().expect("utf-8 path");
    for (args, multiscatter) in
        [(&[][..], true), (&["--microfacet", "single"][..], false), (&["--microfacet", "multiscatter"][..], true)]
    {
        let (code, stderr) = rt(&[args, &[scene]].concat());
        assert_eq!(code, 0, "{args:?}: {stderr}");
        let features = stderr.lines().find(|l| l.contains("features [")).unwrap_or_else(|| panic!("{stderr}"));
        assert_eq!(features.contains("multiscatter"), multiscatter, "{args:?}: {features}");
    }
    let (code, stderr) = rt(&["--microfacet", "double", scene]);
    assert_eq!(code, 2, "{stderr}");
}
