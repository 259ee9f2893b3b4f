//! The manual's scene-file reference (docs/scene-format.md, and the atmosphere's keys in
//! docs/atmosphere.md) against the code: every value it writes out must be the default
//! the code applies, every key the code accepts must be in it, and every key in it must be
//! one the code accepts. So the two cannot drift.

use crate::common;

use common::repo;

/// The `nth` (from 0) ```toml block after `marker` in a page of the manual.
fn block_after(page: &str, marker: &str, nth: usize) -> String {
    let text = std::fs::read_to_string(repo().join("docs").join(page)).unwrap_or_else(|e| panic!("docs/{page}: {e}"));
    let mut at = text.find(marker).unwrap_or_else(|| panic!("docs/{page} lost {marker:?}"));
    let mut block = String::new();
    for _ in 0..=nth {
        let start = text[at..].find("```toml\n").map(|i| at + i + "```toml\n".len()).expect("a toml block");
        let end = text[start..].find("```").map(|i| start + i).expect("the block's end");
        block = text[start..end].to_owned();
        at = end + 3;
    }
    block
}

fn keys_block() -> String {
    block_after("scene-format.md", "# The scene file", 0)
}

fn instances_block() -> String {
    block_after("scene-format.md", "# The scene file", 1)
}

fn atmosphere_block() -> String {
    block_after("atmosphere.md", "# The atmosphere", 0)
}

/// The block with only its table headers and `# required` keys: what the code must
/// fill in to give the same scene.
fn minimal(block: &str) -> String {
    block
        .lines()
        .filter(|l| l.trim_start().starts_with('[') || l.contains("# required"))
        .map(|l| format!("{l}\n"))
        .collect()
}

fn parse(text: &str) -> Result<rt::scene::Scene, String> {
    rt::scene::parse(text, "scene-format.md", &repo().join("scenes")).map_err(|e| e.to_string())
}

/// Every written-out value is the default: the block and its headers-and-required-keys
/// version give the same scene.
fn assert_defaults(block: &str) {
    let full = parse(block).unwrap_or_else(|e| panic!("the manual's block does not parse: {e}\n{block}"));
    let bare = parse(&minimal(block)).unwrap_or_else(|e| panic!("its required keys alone do not parse: {e}"));
    assert_eq!(full, bare, "a value in the manual's block is not the code's default");
}

/// The block with `line` inserted after the header line of the table `header`.
fn insert_after(block: &str, header: &str, line: &str) -> String {
    let mut out = String::new();
    let mut done = false;
    for l in block.lines() {
        out.push_str(l);
        out.push('\n');
        if !done && (l == header || l.starts_with(&format!("{header} "))) {
            out.push_str(line);
            out.push('\n');
            done = true;
        }
    }
    assert!(done, "{header} is not a line of the block");
    out
}

/// The keys the code accepts in the table opened by `header` (serde lists them when it
/// meets an unknown one, and "did you mean" needs a name close to none).
fn accepted_keys(block: &str, header: &str) -> Vec<String> {
    let message = parse(&insert_after(&minimal(block), header, "qqqqqqqqqqqqqqqqqqqq = 1")).expect_err("unknown key");
    let list = message.split("expected one of ").nth(1).unwrap_or_else(|| panic!("no key list in: {message}"));
    list.split('`').skip(1).step_by(2).map(str::to_owned).collect()
}

/// The lines of the table opened by `header`, up to the next header.
fn section(block: &str, header: &str) -> String {
    let mut lines = block.lines().skip_while(|l| !(*l == header || l.starts_with(&format!("{header} "))));
    let first = lines.next().unwrap_or_else(|| panic!("{header} missing"));
    let rest: Vec<&str> = lines.take_while(|l| !l.starts_with('[')).collect();
    format!("{first}\n{}", rest.join("\n"))
}

/// The keys a section documents: `key = …` lines, commented out or not.
fn documented_keys(section: &str) -> Vec<String> {
    section
        .lines()
        .skip(1)
        .map(|l| l.trim_start_matches('#').trim())
        .filter_map(|l| l.split_once(" =").map(|(key, _)| key.trim()))
        .filter(|key| !key.is_empty() && key.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_'))
        .map(str::to_owned)
        .collect()
}

const TABLES: [&str; 9] = [
    "[render]",
    "[camera]",
    "[sky]",
    "[sun]",
    "[materials.grey]",
    "[[mesh]]",
    "[[sphere]]",
    "[[light]]",
    "[[instances]]",
];

/// The block that holds `header`, and the keys the manual documents for it.
fn documented(header: &str) -> (String, String) {
    let (keys, instances, atmosphere) = (keys_block(), instances_block(), atmosphere_block());
    match header {
        "[[instances]]" => (instances.clone(), section(&instances, header)),
        "[sky]" => (keys.clone(), format!("{}\n{}", section(&keys, header), section(&atmosphere, header))),
        _ => (keys.clone(), section(&keys, header)),
    }
}

#[test]
fn every_value_in_the_scene_reference_is_the_default() {
    assert_defaults(&keys_block());
    assert_defaults(&atmosphere_block());
}

#[test]
fn every_key_the_code_accepts_is_in_the_reference_and_no_other() {
    for header in TABLES {
        let (block, documented) = documented(header);
        let accepted = accepted_keys(&block, header);
        assert!(accepted.len() >= 2, "{header}: {accepted:?}");
        for key in &accepted {
            assert!(documented.contains(&format!("{key} =")), "{header}: `{key}` is accepted but not in the manual");
        }
        for key in documented_keys(&documented) {
            assert!(accepted.contains(&key), "{header}: the manual documents `{key}`, which the code refuses");
        }
    }
}
