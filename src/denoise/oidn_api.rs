//! The C API of Open Image Denoise that rt calls, as the `oidn` crate declares it.

pub use oidn::sys::*;
