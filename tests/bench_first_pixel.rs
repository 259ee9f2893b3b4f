//! `rt bench first-pixel`: two fresh processes, the first with an empty driver shader
//! cache and the second with the cache it filled, each step of their start timed.

use std::process::Command;

#[test]
fn first_pixel_times_a_cold_and_a_warm_start() {
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["bench", "first-pixel", "tests/refs/scenes/cornell_diffuse.toml", "--size", "16x16"])
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("rt runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    for state in ["cold", "warm"] {
        let row = stdout.lines().find(|l| l.starts_with(&format!("| {state} |"))).unwrap_or_else(|| panic!("{stdout}"));
        let cells: Vec<&str> = row.split('|').map(str::trim).filter(|c| !c.is_empty()).collect();
        assert_eq!(cells.len(), 6, "{row}");
        // Every step has its time in milliseconds.
        assert!(cells[1..].iter().all(|c| c.ends_with(" ms") || c.ends_with(" ms)")), "{row}");
    }
}
