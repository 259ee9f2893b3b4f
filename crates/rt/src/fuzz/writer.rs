//! The writer target: whatever files a folder holds, writing one file there (or failing
//! to) leaves every other file byte for byte as it was. The input is lines: the first
//! names the file written, each other one a file that exists before the write (its bytes
//! are its own name and line number). Names are made valid file names first.

use super::Workspace;
use crate::files::output;
use std::collections::BTreeMap;
use std::path::Path;

pub fn run(workspace: &Workspace, input: &[u8]) -> Result<(), String> {
    let dir = workspace.dir().join("writes");
    // A fresh folder for each input: what the last one left must not count.
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut lines = input.split(|&b| b == b'\n').map(file_name);
    let target = lines.next().flatten().unwrap_or_else(|| "out.png".to_owned());
    for (n, name) in lines.flatten().enumerate() {
        if name != target {
            std::fs::write(dir.join(&name), format!("{n} {name}")).map_err(|e| format!("{name}: {e}"))?;
        }
    }
    let before = contents(&dir);
    let written = crate::files::write_atomically(&dir.join(&target), b"new");
    let failed = output::write_with(&dir.join(&target), |_| Err(std::io::Error::other("a failing write")));
    assert!(failed.is_err(), "a failing write reported success");
    check_untouched(&dir, &target, &before);
    written.map_err(|e| e.to_string())
}

/// Every file of `before` but `target`, and rt's own stale temporaries of it, is there
/// with the same bytes, and nothing else but `target` was added.
fn check_untouched(dir: &Path, target: &str, before: &BTreeMap<String, Vec<u8>>) {
    let after = contents(dir);
    for (name, bytes) in before {
        if name == target || output::is_stale_temporary(name, target) {
            continue;
        }
        assert_eq!(after.get(name), Some(bytes), "{name} was changed or removed by a write of {target}");
    }
    for name in after.keys() {
        assert!(before.contains_key(name) || name == target, "{name} was left by a write of {target}");
    }
}

fn contents(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let Ok(entries) = std::fs::read_dir(dir) else { return BTreeMap::new() };
    entries
        .flatten()
        .map(|e| (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap_or_default()))
        .collect()
}

/// `bytes` as a file name: printable, no `/`, not `.` or `..`, at most 200 bytes.
fn file_name(bytes: &[u8]) -> Option<String> {
    let name: String =
        String::from_utf8_lossy(bytes).chars().filter(|c| !c.is_control() && *c != '/').take(100).collect();
    let name = name.trim_end_matches('\u{fffd}').to_owned();
    (!name.is_empty() && name != "." && name != ".." && name.len() <= 200).then_some(name)
}
