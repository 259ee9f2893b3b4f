//! `rt bench compare` without Mitsuba: it says so and prints rt's figures alone. The
//! scenes are translated for Mitsuba all the same (before it is run), so the held-in
//! dragon's translation is checked here too.

use std::process::Command;

#[test]
fn compare_without_mitsuba_prints_rt_alone() {
    let repo = env!("CARGO_MANIFEST_DIR");
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .current_dir(repo)
        .args(["bench", "compare", "tests/refs/scenes/cornell_diffuse.toml", "scenes/dragon_clay.toml"])
        .args(["--size", "16x16", "--runs", "1"])
        .args(["--python", "/nonexistent/python3"])
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("rt runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("Mitsuba  not available (cannot run /nonexistent/python3"), "{stdout}");
    let rows: Vec<_> = stdout
        .lines()
        .filter(|l| {
            l.starts_with("| tests/refs/scenes/cornell_diffuse.toml") || l.starts_with("| scenes/dragon_clay.toml")
        })
        .collect();
    assert_eq!(rows.len(), 6, "paths, camera and diffuse rays of each scene: {stdout}");
    for row in rows {
        let cells: Vec<_> = row.split('|').map(str::trim).collect();
        // rt's figure is a rate; Mitsuba's and the ratio are absent.
        assert!(cells[3].ends_with("/s") || cells[3].chars().next().is_some_and(|c| c.is_ascii_digit()), "{row}");
        assert_eq!((cells[4], cells[5]), ("—", "—"), "{row}");
    }
}
