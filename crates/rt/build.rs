//! Build-time facts rt reports about itself: the commit it was built from (`rt --version`,
//! `rt doctor`), and, with the `denoise` feature, the `OIDN_DIR` it is built with, where
//! it looks for Open Image Denoise when none is set at run time (src/denoise/oidn_api.rs),
//! so that a build made with scripts/fetch_oidn's library runs with no setting.

use std::process::Command;

fn main() {
    println!("cargo:rerun-if-env-changed=OIDN_DIR");
    println!("cargo:rustc-env=RT_COMMIT={}", commit());
    // The package is crates/rt of the repository: its git files are two folders up.
    for path in ["../../.git/HEAD", "../../.git/index"] {
        if std::path::Path::new(path).exists() {
            println!("cargo:rerun-if-changed={path}");
        }
    }
    if std::env::var_os("CARGO_FEATURE_DENOISE").is_none() {
        return;
    }
    if let Some(dir) = std::env::var("OIDN_DIR").ok().filter(|d| !d.is_empty()) {
        println!("cargo:rustc-env=RT_OIDN_BUILD_DIR={dir}");
    }
}

/// The commit's short hash, with "+changes" when the work tree differs from it; "unknown"
/// outside a git checkout (a source tarball).
fn commit() -> String {
    let git =
        |args: &[&str]| Command::new("git").args(args).output().ok().filter(|o| o.status.success()).map(|o| o.stdout);
    let Some(hash) = git(&["rev-parse", "--short=12", "HEAD"]) else { return "unknown".into() };
    let hash = String::from_utf8_lossy(&hash).trim().to_owned();
    let dirty = git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|o| !o.is_empty());
    if dirty { format!("{hash}+changes") } else { hash }
}
