//! What a newcomer meets first: no Mesa complaint about XDG_RUNTIME_DIR on GPU
//! commands, help text for every render option, and a README that says how to get
//! `rt` on the PATH and what the first run costs.

use crate::common;

use common::bounded::{fresh_dir, names, run};
use std::os::unix::fs::{MetadataExt, PermissionsExt};
use std::process::Command;
use std::time::Duration;

const DEADLINE: Duration = Duration::from_secs(120);

#[test]
fn gpu_commands_start_quietly_without_a_runtime_dir() {
    let tmp = fresh_dir("xdg");
    for (case, value) in [("unset", None), ("relative", Some("not/absolute")), ("missing", Some("/nonexistent/xdg"))] {
        let mut command = Command::new(env!("CARGO_BIN_EXE_rt"));
        command.args(["info"]).env("TMPDIR", &tmp).env_remove("XDG_RUNTIME_DIR");
        if let Some(v) = value {
            command.env("XDG_RUNTIME_DIR", v);
        }
        let outcome = run(command, DEADLINE);
        outcome.expect(case, 0);
        assert!(!outcome.stderr.contains("XDG_RUNTIME_DIR"), "{case}: {}", outcome.stderr);
    }
    // One private folder, reused by every run.
    let uid = std::fs::metadata("/proc/self").expect("/proc").uid();
    let name = format!("rt-runtime-{uid}");
    assert_eq!(names(&tmp), [name.as_str()]);
    let meta = std::fs::metadata(tmp.join(&name)).expect("runtime folder");
    assert_eq!(meta.permissions().mode() & 0o777, 0o700);
    std::fs::remove_dir_all(&tmp).expect("clean up");
}

#[test]
fn every_render_option_has_help_text() {
    let out = Command::new(env!("CARGO_BIN_EXE_rt")).args(["render", "-h"]).output().expect("rt render -h");
    let help = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = help.lines().collect();
    let mut options = 0;
    for (i, line) in lines.iter().enumerate() {
        let option = line.trim_start();
        if !option.starts_with('-') {
            continue;
        }
        options += 1;
        // The text follows the value name on the same line, or on the next, indented.
        let same_line = option.split_whitespace().count() >= 3;
        let next = lines.get(i + 1).map_or("", |l| l.trim_start());
        assert!(same_line || !(next.is_empty() || next.starts_with('-')), "no help text: {option:?}");
    }
    assert!(options > 10, "{help}");
    assert!(help.contains("--max-bounces <MAX_BOUNCES>\n          Longest path, in bounces"), "{help}");
}

#[test]
fn the_readme_says_how_to_install_and_what_the_first_run_costs() {
    let readme = std::fs::read_to_string(common::repo().join("README.md")).expect("README");
    for needle in
        ["cargo install --path .", "rustup", "mesa-vulkan-drivers", "about 15 minutes", "~400 MB", "rt doctor"]
    {
        assert!(readme.contains(needle), "README lacks {needle:?}");
    }
    let install = std::fs::read_to_string(common::repo().join("docs/install.md")).expect("docs/install.md");
    for needle in ["target/release/rt", "uv", "python3.11", "npm", "scripts/test"] {
        assert!(install.contains(needle), "docs/install.md lacks {needle:?}");
    }
}
