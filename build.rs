//! With the `denoise` feature, rt links Open Image Denoise from `$OIDN_DIR/lib`: the
//! binaries then look for it there at run time too, so that no LD_LIBRARY_PATH is needed.

fn main() {
    println!("cargo:rerun-if-env-changed=OIDN_DIR");
    if std::env::var_os("CARGO_FEATURE_DENOISE").is_none() {
        return;
    }
    if let Some(dir) = std::env::var_os("OIDN_DIR").filter(|d| !d.is_empty()) {
        let lib = std::path::Path::new(&dir).join("lib");
        println!("cargo:rustc-link-arg=-Wl,-rpath,{}", lib.display());
    }
}
