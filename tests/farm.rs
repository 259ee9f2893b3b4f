//! `rt farm` on a local Ray cluster of a head and two workers (lavapipe for their GPUs):
//! one worker is killed while it renders a part; the job still ends, and its merged image
//! is the one `rt render` gives, bit for bit.

use crate::common;

use common::{empty_temp_dir, repo};
use std::path::PathBuf;
use std::process::Command;

/// The Python with Ray that RT_FARM_PYTHON names (scripts/test makes `.venv-farm`).
fn farm_python() -> PathBuf {
    let Some(python) = std::env::var_os("RT_FARM_PYTHON") else {
        panic!(
            "RT_FARM_PYTHON is not set: it must name a Python with ray (scripts/test creates .venv-farm and sets it)"
        );
    };
    let python = PathBuf::from(python);
    if python.is_relative() { repo().join(python) } else { python }
}

#[test]
fn a_killed_worker_loses_no_part_and_the_merge_is_the_render_bit_for_bit() {
    let out = empty_temp_dir("farm");
    let rt = env!("CARGO_BIN_EXE_rt");
    let scene = repo().join("scenes/cornell_box.toml");
    let flags = ["--size", "32x24", "--seed", "2", "--noise-threshold", "0"];
    let whole = out.join("whole.exr");
    let rendered = Command::new(rt)
        .arg("render")
        .arg(&scene)
        .args(["--spp", "12", "--progress", "none", "-o"])
        .arg(&whole)
        .args(flags)
        .output()
        .expect("rt runs");
    assert!(rendered.status.success(), "{}", String::from_utf8_lossy(&rendered.stderr));

    let run = Command::new(farm_python())
        .arg(repo().join("tests/farm/kill_a_worker.py"))
        .arg(&out)
        .arg(rt)
        .arg(&scene)
        .args(["12", "6"])
        .args(flags)
        .env("RT_FARM_CACHE", out.join("cache"))
        .output()
        .expect("the farm's Python runs");
    let log = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "the farm job failed:\n{log}");
    let summary = std::fs::read(out.join("summary.json")).expect("the job's summary");
    let summary: serde_json::Value = serde_json::from_slice(&summary).expect("a JSON summary");
    println!("{summary:#}");

    let killed = summary["killed"].as_str().expect("a worker was killed");
    let parts = summary["parts"].as_array().expect("parts");
    assert_eq!(parts.len(), 6, "every part arrived");
    // The killed worker may have finished its part just before it died (its result then
    // still arrives); the rest is rendered by the survivor.
    let after: Vec<_> = parts.iter().filter(|p| p["after_kill"] == true).collect();
    assert_eq!(after.len(), 5, "the worker was killed as the first of six parts arrived");
    assert!(after.iter().filter(|p| p["node"] == killed).count() <= 1, "the dead worker rendered nothing more");
    assert!(log.contains("6/6 parts"), "progress is shown:\n{log}");
    let (farm, whole) = (std::fs::read(out.join("farm.exr")).expect("farm.exr"), std::fs::read(&whole).expect("whole"));
    assert!(farm == whole, "the farm's merged image is rt render's, bit for bit");
}
