//! Denoising with Intel Open Image Denoise: a render's radiance, guided by its albedo
//! and normal AOVs (each prefiltered first, so the guides are clean), on a GPU device
//! where Open Image Denoise has one (CUDA, HIP, SYCL) and on the CPU otherwise.
//!
//! Open Image Denoise is a shared library that rt links when built with the `denoise`
//! feature (`scripts/fetch_oidn` installs it, see README); without it, or when the
//! library cannot make a device, asking to denoise is an error that says how to get it.

#[cfg(feature = "denoise")]
mod oidn_filter;

use crate::render::{Aovs, Image};
use anyhow::{Result, bail};

/// How to get a denoising rt, for error messages.
pub const HOW_TO_GET_OIDN: &str = "run scripts/fetch_oidn (it unpacks Open Image Denoise 2.5.1 into .oidn/), \
     then build with `cargo build --release --features denoise` (README: Denoising)";

/// An Open Image Denoise device, made once and reused for every image.
pub struct Denoiser {
    #[cfg(feature = "denoise")]
    inner: oidn_filter::OidnDenoiser,
}

impl Denoiser {
    /// The fastest device Open Image Denoise has here; an error naming what is missing
    /// when it has none (or rt was built without it).
    pub fn new() -> Result<Self> {
        #[cfg(feature = "denoise")]
        {
            Ok(Self { inner: oidn_filter::OidnDenoiser::new()? })
        }
        #[cfg(not(feature = "denoise"))]
        {
            bail!("this rt was built without Open Image Denoise, so it cannot denoise: {HOW_TO_GET_OIDN}")
        }
    }

    /// The device denoising runs on, in words ("CPU", "CUDA", ...).
    pub fn device(&self) -> &str {
        #[cfg(feature = "denoise")]
        {
            self.inner.device_name()
        }
        #[cfg(not(feature = "denoise"))]
        {
            unreachable!("a Denoiser cannot be made without Open Image Denoise")
        }
    }

    /// The denoised radiance of `image`, guided by `aovs` (of the same render).
    pub fn denoise(&self, image: &Image, aovs: &Aovs) -> Result<Vec<[f32; 3]>> {
        if (image.width, image.height) != (aovs.width, aovs.height) || image.pixels.len() != aovs.albedo.len() {
            bail!(
                "the AOVs ({}x{}) are not of the image ({}x{}) being denoised",
                aovs.width,
                aovs.height,
                image.width,
                image.height
            );
        }
        #[cfg(feature = "denoise")]
        {
            self.inner.denoise(image, aovs)
        }
        #[cfg(not(feature = "denoise"))]
        {
            unreachable!("a Denoiser cannot be made without Open Image Denoise")
        }
    }
}
