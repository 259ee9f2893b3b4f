//! Open Image Denoise's C API, loaded at run time (`dlopen`) rather than linked: a build
//! with the `denoise` feature then starts, and renders without `--denoise`, on a machine
//! whose library is missing; only `--denoise` fails, saying what is missing and how to
//! get it. (The `oidn` crate links the library, so a missing one would stop rt in the
//! dynamic loader before `main`.) Only the functions rt calls are resolved.
//!
//! The library is `libOpenImageDenoise.so.2` in `$OIDN_DIR/lib`, with `OIDN_DIR` as the
//! environment has it at run time; without one, the `OIDN_DIR` rt was built with, when
//! the library is still there; else wherever the dynamic loader finds it
//! (`LD_LIBRARY_PATH`, the system's folders). Its devices load from beside it.

// The C API's own names, so that its documentation reads as the code.
#![allow(non_snake_case)]

use std::ffi::{c_char, c_int, c_void};
use std::path::PathBuf;
use std::sync::OnceLock;

pub type OIDNDevice = *mut c_void;
pub type OIDNBuffer = *mut c_void;
pub type OIDNFilter = *mut c_void;
pub type OIDNDeviceType = c_int;
pub type OIDNError = c_int;
pub type OIDNFormat = c_int;

pub const OIDN_DEVICE_TYPE_CPU: OIDNDeviceType = 1;
pub const OIDN_DEVICE_TYPE_SYCL: OIDNDeviceType = 2;
pub const OIDN_DEVICE_TYPE_CUDA: OIDNDeviceType = 3;
pub const OIDN_DEVICE_TYPE_HIP: OIDNDeviceType = 4;
pub const OIDN_DEVICE_TYPE_METAL: OIDNDeviceType = 5;
pub const OIDN_ERROR_NONE: OIDNError = 0;
pub const OIDN_FORMAT_FLOAT3: OIDNFormat = 3;

/// The library's file name (its soname: any 2.x).
pub const LIBRARY: &str = "libOpenImageDenoise.so.2";

/// Declares the table of functions and how each is resolved by its C name.
macro_rules! functions {
    ($($name:ident: fn($($arg:ty),*) $(-> $ret:ty)?;)*) => {
        /// The functions rt calls, resolved from the loaded library (kept loaded with them).
        pub struct Api {
            $(pub $name: unsafe extern "C" fn($($arg),*) $(-> $ret)?,)*
            _library: libloading::Library,
        }

        impl Api {
            /// SAFETY: `library` must be Open Image Denoise 2, whose functions have these signatures.
            unsafe fn resolve(library: libloading::Library) -> Result<Self, String> {
                $(
                    let name = concat!(stringify!($name), "\0");
                    // SAFETY: the signature is the one of Open Image Denoise 2's header; the
                    // pointer is used only while `library`, moved into the table, stays loaded.
                    let $name = unsafe {
                        *library
                            .get::<unsafe extern "C" fn($($arg),*) $(-> $ret)?>(name.as_bytes())
                            .map_err(|e| format!("it has no {} ({e}): not Open Image Denoise 2", stringify!($name)))?
                    };
                )*
                Ok(Self { $($name,)* _library: library })
            }
        }
    };
}

functions! {
    oidnGetNumPhysicalDevices: fn() -> c_int;
    oidnGetPhysicalDeviceInt: fn(c_int, *const c_char) -> c_int;
    oidnGetPhysicalDeviceString: fn(c_int, *const c_char) -> *const c_char;
    oidnNewDevice: fn(OIDNDeviceType) -> OIDNDevice;
    oidnCommitDevice: fn(OIDNDevice);
    oidnGetDeviceError: fn(OIDNDevice, *mut *const c_char) -> OIDNError;
    oidnReleaseDevice: fn(OIDNDevice);
    oidnNewBuffer: fn(OIDNDevice, usize) -> OIDNBuffer;
    oidnWriteBuffer: fn(OIDNBuffer, usize, usize, *const c_void);
    oidnReadBuffer: fn(OIDNBuffer, usize, usize, *mut c_void);
    oidnReleaseBuffer: fn(OIDNBuffer);
    oidnNewFilter: fn(OIDNDevice, *const c_char) -> OIDNFilter;
    oidnSetFilterImage: fn(OIDNFilter, *const c_char, OIDNBuffer, OIDNFormat, usize, usize, usize, usize, usize);
    oidnSetFilterBool: fn(OIDNFilter, *const c_char, bool);
    oidnCommitFilter: fn(OIDNFilter);
    oidnExecuteFilter: fn(OIDNFilter);
    oidnReleaseFilter: fn(OIDNFilter);
}

/// The `OIDN_DIR` of the build, if it had one (see build.rs).
const BUILD_DIR: Option<&str> = option_env!("RT_OIDN_BUILD_DIR");

/// Where the library is looked for, in words, for messages.
fn search_order() -> String {
    let built = match BUILD_DIR.filter(|d| !d.is_empty()) {
        Some(dir) => format!("else {dir}/lib, the OIDN_DIR this rt was built with, "),
        None => "else (this rt was built without OIDN_DIR) ".to_string(),
    };
    format!("rt loads {LIBRARY} from $OIDN_DIR/lib when OIDN_DIR is set, {built}from the system's library path")
}

/// The library to load: a path, or the bare name for the dynamic loader's search.
fn library_path() -> PathBuf {
    if let Some(dir) = std::env::var_os("OIDN_DIR").filter(|d| !d.is_empty()) {
        return PathBuf::from(dir).join("lib").join(LIBRARY);
    }
    BUILD_DIR
        .filter(|d| !d.is_empty())
        .map(|dir| PathBuf::from(dir).join("lib").join(LIBRARY))
        .filter(|path| path.exists())
        .unwrap_or_else(|| PathBuf::from(LIBRARY))
}

fn load() -> Result<Api, String> {
    let path = library_path();
    let how = "run scripts/fetch_oidn (it installs Open Image Denoise 2.5.1 into .oidn/lib) and set OIDN_DIR to \
               that .oidn folder (docs/denoising.md)";
    // SAFETY: loading runs the library's initialisers: Open Image Denoise's are sound to run.
    let library = unsafe { libloading::Library::new(&path) }.map_err(|e| {
        format!("Open Image Denoise is missing: cannot load {} ({e}); {}; {how}", path.display(), search_order())
    })?;
    // SAFETY: a library of that soname is Open Image Denoise 2.
    unsafe { Api::resolve(library) }.map_err(|e| format!("{} is not usable: {e}; {how}", path.display()))
}

static API: OnceLock<Result<Api, String>> = OnceLock::new();

/// The library's functions, loaded on first use; an error saying what is missing and how
/// to get it when it cannot be loaded.
pub fn api() -> Result<&'static Api, String> {
    API.get_or_init(load).as_ref().map_err(Clone::clone)
}
