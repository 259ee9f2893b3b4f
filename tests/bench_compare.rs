//! `rt bench compare`: without Mitsuba it says so and prints rt's figures alone (the
//! scenes are translated for Mitsuba all the same, before it is run, so the held-in
//! dragon's translation is checked too); with Mitsuba's `llvm_ad_rgb` (RT_MITSUBA_PYTHON,
//! which scripts/test sets up) the Cornell box's images agree and every figure gets its
//! ratio on both clocks.

use std::process::{Command, Output};

fn compare(args: &[&str], python: &std::ffi::OsStr) -> (Output, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["bench", "compare"])
        .args(args)
        .arg("--python")
        .arg(python)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("rt runs");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    (out, stdout)
}

/// The table's cells of the rows whose scene starts with one of `scenes`.
fn rows(stdout: &str, scenes: &[&str]) -> Vec<Vec<String>> {
    stdout
        .lines()
        .filter(|l| scenes.iter().any(|s| l.starts_with(&format!("| {s}"))))
        .map(|l| l.split('|').map(|c| c.trim().to_string()).collect())
        .collect()
}

fn is_rate(cell: &str) -> bool {
    cell.chars().next().is_some_and(|c| c.is_ascii_digit())
}

#[test]
fn compare_without_mitsuba_prints_rt_alone() {
    let scenes = ["tests/refs/scenes/cornell_diffuse.toml", "scenes/dragon_clay.toml"];
    let args = [scenes[0], scenes[1], "--size", "16x16", "--spp", "4", "--runs", "2"];
    let (_, stdout) = compare(&args, "/nonexistent/python3".as_ref());
    assert!(stdout.contains("Mitsuba  not available (cannot run /nonexistent/python3"), "{stdout}");
    let rows = rows(&stdout, &scenes);
    assert_eq!(rows.len(), 6, "paths, camera and diffuse rays of each scene: {stdout}");
    for cells in rows {
        // rt's figures (wall clock, device) are rates; Mitsuba's and the ratios are absent.
        assert!(is_rate(&cells[3]) && is_rate(&cells[6]), "{cells:?}");
        for i in [4, 5, 7, 8] {
            assert_eq!(cells[i], "—", "{cells:?}");
        }
    }
}

#[test]
fn compare_with_mitsuba_agrees_on_the_cornell_box_and_gives_ratios() {
    let Some(python) = std::env::var_os("RT_MITSUBA_PYTHON") else {
        panic!("RT_MITSUBA_PYTHON is not set: it must name a Python with mitsuba==3.9.1 (scripts/test sets it up)");
    };
    let scene = "tests/refs/scenes/cornell_diffuse.toml";
    let args = [scene, "--size", "32x32", "--spp", "64", "--runs", "2", "--variant", "llvm_ad_rgb"];
    let (_, stdout) = compare(&args, &python);
    assert!(stdout.contains("Mitsuba  llvm_ad_rgb 3.9.1"), "{stdout}");
    assert!(stdout.contains(&format!("images   {scene}: agree")), "{stdout}");
    let rows = rows(&stdout, &[scene]);
    assert_eq!(rows.len(), 3, "{stdout}");
    for cells in rows {
        // Both renderers' rates on both clocks, and both ratios.
        for i in [3, 4, 6, 7] {
            assert!(is_rate(&cells[i]), "{cells:?}");
        }
        assert!(cells[5].ends_with('×') && cells[8].ends_with('×'), "{cells:?}");
    }
}
