//! With the `denoise` feature, rt loads Open Image Denoise at run time; the `OIDN_DIR` it
//! is built with is where it looks when none is set then (src/denoise/oidn_api.rs), so
//! that a build made with scripts/fetch_oidn's library runs with no setting.

fn main() {
    println!("cargo:rerun-if-env-changed=OIDN_DIR");
    if std::env::var_os("CARGO_FEATURE_DENOISE").is_none() {
        return;
    }
    if let Some(dir) = std::env::var("OIDN_DIR").ok().filter(|d| !d.is_empty()) {
        println!("cargo:rustc-env=RT_OIDN_BUILD_DIR={dir}");
    }
}
