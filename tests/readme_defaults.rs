//! The README's scene-file reference ("Every key, with its default" and the atmosphere's
//! keys) against the code: every value it writes out must be the default the code
//! applies, and every key the code accepts must be in it. So the two cannot drift.

use crate::common;

use common::repo;

/// The first ```toml block after `marker` in the README.
fn block_after(readme: &str, marker: &str) -> String {
    let at = readme.find(marker).unwrap_or_else(|| panic!("README lost {marker:?}"));
    let start = readme[at..].find("```toml\n").map(|i| at + i + "```toml\n".len()).expect("a toml block");
    let end = readme[start..].find("```").map(|i| start + i).expect("the block's end");
    readme[start..end].to_owned()
}

fn readme() -> String {
    std::fs::read_to_string(repo().join("README.md")).expect("README.md")
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
    rt::scene::parse(text, "README.md", &repo().join("scenes")).map_err(|e| e.to_string())
}

/// Every written-out value is the default: the block and its headers-and-required-keys
/// version give the same scene.
fn assert_defaults(block: &str) {
    let full = parse(block).unwrap_or_else(|e| panic!("the README block does not parse: {e}\n{block}"));
    let bare = parse(&minimal(block)).unwrap_or_else(|e| panic!("its required keys alone do not parse: {e}"));
    assert_eq!(full, bare, "a value in the README block is not the code's default");
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

#[test]
fn every_value_in_the_scene_reference_is_the_default() {
    let readme = readme();
    assert_defaults(&block_after(&readme, "Every key, with its default"));
    assert_defaults(&block_after(&readme, "### The atmosphere"));
}

#[test]
fn every_key_the_code_accepts_is_in_the_reference() {
    let readme = readme();
    let keys = block_after(&readme, "Every key, with its default");
    let atmosphere = block_after(&readme, "### The atmosphere");
    for header in ["[render]", "[camera]", "[sky]", "[sun]", "[materials.grey]", "[[mesh]]", "[[sphere]]"] {
        let documented = match header {
            "[sky]" => format!("{}{}", section(&keys, header), section(&atmosphere, header)),
            _ => section(&keys, header),
        };
        let accepted = accepted_keys(&keys, header);
        assert!(accepted.len() >= 2, "{header}: {accepted:?}");
        for key in accepted {
            assert!(documented.contains(&format!("{key} =")), "{header}: `{key}` is accepted but not in the README");
        }
    }
}
