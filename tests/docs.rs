//! The front page and the manual against what they describe: every relative link of
//! README.md, CHANGELOG.md and docs/ leads to a file (and a heading, for `#anchor`s),
//! every command and flag of the README's quick start and commands table is in
//! `rt --help`, the versions the docs quote are scripts/versions' (and Cargo.toml's
//! rust-version), the README stays a front page, and `rt doctor` reports this machine,
//! with and without Open Image Denoise.

use crate::common;

use common::repo;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

fn pages() -> Vec<PathBuf> {
    let mut pages = vec![repo().join("README.md"), repo().join("CHANGELOG.md"), repo().join("fuzz/README.md")];
    let docs = std::fs::read_dir(repo().join("docs")).expect("docs/");
    pages.extend(docs.flatten().map(|e| e.path()).filter(|p| p.extension().is_some_and(|x| x == "md")));
    pages.sort();
    pages
}

/// GitHub's anchor of a heading: lower case, spaces to dashes, punctuation dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(text: &str) -> BTreeSet<String> {
    let mut in_code = false;
    let mut found = BTreeSet::new();
    for line in text.lines() {
        if line.starts_with("```") {
            in_code = !in_code;
        } else if !in_code && line.starts_with('#') {
            found.insert(anchor(line.trim_start_matches('#')));
        }
    }
    found
}

/// The targets of the page's markdown links `[text](target)` outside code blocks.
fn links(text: &str) -> Vec<String> {
    let mut in_code = false;
    let mut found = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code {
            continue;
        }
        let mut rest = line;
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let Some(end) = after.find(')') else { break };
            found.push(after[..end].to_owned());
            rest = &after[end..];
        }
    }
    found
}

#[test]
fn every_link_of_the_readme_and_the_manual_leads_somewhere() {
    let mut broken = Vec::new();
    let mut checked = 0;
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("page");
        for target in links(&text) {
            if target.starts_with("http://") || target.starts_with("https://") || target.starts_with("mailto:") {
                continue;
            }
            checked += 1;
            let (file, fragment) = target.split_once('#').unwrap_or((&target, ""));
            let path = if file.is_empty() { page.clone() } else { page.parent().expect("folder").join(file) };
            if !path.exists() {
                broken.push(format!("{}: {target}: no such file", page.display()));
                continue;
            }
            let is_page = path.extension().is_some_and(|x| x == "md");
            if !fragment.is_empty() && is_page {
                let headings = anchors(&std::fs::read_to_string(&path).expect("linked page"));
                if !headings.contains(fragment) {
                    broken.push(format!("{}: {target}: no heading #{fragment} in {}", page.display(), path.display()));
                }
            }
        }
    }
    println!("{checked} links checked in {} pages", pages().len());
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// `rt SUBCOMMAND --help` (or `rt --help`), as text.
fn help(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_rt")).args(args).arg("--help").output().expect("rt runs");
    assert!(out.status.success(), "rt {args:?} --help failed");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Every `rt …` command of the README (the quick start's and the table's): its subcommands
/// exist and each `--flag` it names is one its help lists.
#[test]
fn the_readmes_commands_and_flags_are_rts() {
    let readme = std::fs::read_to_string(repo().join("README.md")).expect("README.md");
    let mut commands = Vec::new();
    for line in readme.lines() {
        let line = line.trim_start_matches(['|', ' ', '`']);
        let line = line.strip_prefix("cargo run --release -- ").map(|l| format!("rt {l}")).unwrap_or(line.to_owned());
        if let Some(rest) = line.strip_prefix("rt ") {
            commands.push(rest.split(['`', '#', '|']).next().unwrap_or("").trim().to_owned());
        }
    }
    assert!(commands.len() >= 10, "the README's commands: {commands:?}");
    let top = help(&[]);
    for command in &commands {
        let words: Vec<&str> = command.split_whitespace().collect();
        let mut path: Vec<&str> = Vec::new();
        for word in
            words.iter().take_while(|w| !w.starts_with('-') && w.chars().all(|c| c.is_ascii_lowercase() || c == '-'))
        {
            let listed = help(&path);
            if listed.lines().any(|l| l.trim_start().starts_with(&format!("{word} "))) {
                path.push(word);
            } else {
                break;
            }
        }
        let listed = if path.is_empty() { top.clone() } else { help(&path) };
        for flag in words.iter().filter(|w| w.starts_with("--")) {
            let flag = flag.trim_end_matches(',');
            assert!(listed.contains(flag), "README: `rt {command}`: {flag} is not in `rt {} --help`", path.join(" "));
        }
    }
}

fn versions() -> Vec<(String, String)> {
    let text = std::fs::read_to_string(repo().join("scripts/versions")).expect("scripts/versions");
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| l.split_once('='))
        .map(|(k, v)| (k.to_owned(), v.trim_matches('"').to_owned()))
        .collect()
}

#[test]
fn the_versions_the_docs_quote_are_the_scripts() {
    let versions = versions();
    let get = |key: &str| versions.iter().find(|(k, _)| k == key).map(|(_, v)| v.clone()).expect(key);
    let cargo = std::fs::read_to_string(repo().join("Cargo.toml")).expect("Cargo.toml");
    assert!(cargo.contains(&format!("rust-version = \"{}\"", get("RUST_VERSION"))), "Cargo.toml's rust-version");
    let install = std::fs::read_to_string(repo().join("docs/install.md")).expect("docs/install.md");
    for key in
        ["RUST_VERSION", "PYTHON_VERSION", "BPY_VERSION", "PYOIDN_VERSION", "OIDN_VERSION", "BLENDER_MIN_VERSION"]
    {
        assert!(install.contains(&get(key)), "docs/install.md does not quote {key} = {}", get(key));
    }
    let readme = std::fs::read_to_string(repo().join("README.md")).expect("README.md");
    assert!(readme.contains(&get("RUST_VERSION")), "README.md's Rust version");
}

#[test]
fn the_readme_is_a_front_page() {
    let readme = std::fs::read_to_string(repo().join("README.md")).expect("README.md");
    let lines = readme.lines().count();
    assert!(lines <= 300, "README.md has {lines} lines: details belong in docs/");
    let quick = readme.split("## Quick start").nth(1).expect("a quick start").split("\n## ").next().unwrap_or("");
    let block = quick.split("```sh\n").nth(1).and_then(|b| b.split("```").next()).expect("its commands");
    let commands: Vec<&str> = block.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(commands.len(), 2, "the quick start is two commands: {commands:?}");
    for page in pages().iter().filter(|p| p.starts_with(repo().join("docs"))) {
        let n = std::fs::read_to_string(page).expect("page").lines().count();
        assert!(n <= 420, "{} has {n} lines: one topic a page", page.display());
    }
}

fn doctor(oidn: Option<&Path>) -> String {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rt"));
    command.arg("doctor");
    if let Some(dir) = oidn {
        command.env("OIDN_DIR", dir);
    }
    let out = command.output().expect("rt doctor runs");
    assert!(out.status.success(), "rt doctor failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn rt_doctor_reports_the_gpu_and_what_is_missing() {
    let report = doctor(None);
    println!("{report}");
    for what in ["build", "vulkan drivers", "gpu adapters", "gpu rt uses", "denoiser", "bpy", "blender"] {
        assert!(report.lines().any(|l| l.contains(what)), "no {what} line:\n{report}");
    }
    let gpu = report.lines().find(|l| l.contains("gpu rt uses")).expect("gpu line");
    assert!(gpu.starts_with("ok"), "rt found no GPU where the tests render: {gpu}");
    let version = Command::new(env!("CARGO_BIN_EXE_rt")).arg("--version").output().expect("rt --version");
    let version = String::from_utf8_lossy(&version.stdout);
    assert!(version.contains("(commit "), "{version}");
    // Without Open Image Denoise: its line says what to do.
    let without = doctor(Some(Path::new("/nonexistent/oidn")));
    let line = without.lines().find(|l| l.contains("denoiser")).expect("denoiser line");
    assert!(line.starts_with("missing") && line.contains("scripts/fetch_oidn"), "{line}");
    // With it (scripts/test installs it into .oidn and builds with the feature).
    let oidn = repo().join(".oidn");
    if cfg!(feature = "denoise") && oidn.join("lib").is_dir() {
        let with = doctor(Some(&oidn));
        let line = with.lines().find(|l| l.contains("denoiser")).expect("denoiser line");
        assert!(line.starts_with("ok") && line.contains("Open Image Denoise"), "{line}");
    }
}
