//! Denoising with Intel Open Image Denoise: a render's radiance, guided by its albedo
//! and normal AOVs (each prefiltered first, so the guides are clean), on the device
//! asked for: `auto` takes a CUDA GPU where Open Image Denoise has one, else the CPU.
//!
//! Open Image Denoise is a shared library that rt loads at run time when built with the
//! `denoise` feature (`scripts/fetch_oidn` installs it, see docs/denoising.md); without the feature,
//! without the library, or when it cannot make a device, asking to denoise is an error
//! that says how to get it, and everything else works.

#[cfg(feature = "denoise")]
mod oidn_api;
#[cfg(feature = "denoise")]
mod oidn_filter;

use crate::render::{Aovs, Image};
use anyhow::{Result, bail};

/// How to get a denoising rt, for error messages.
pub const HOW_TO_GET_OIDN: &str = "run scripts/fetch_oidn (it unpacks Open Image Denoise 2.5.1 into .oidn/), \
     then build with `cargo build --release --features denoise` (docs/denoising.md)";

/// Which Open Image Denoise device denoises (`--denoise-device`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum DenoiseDevice {
    /// A CUDA GPU when Open Image Denoise has one, else the CPU.
    #[default]
    Auto,
    Cpu,
    /// A CUDA GPU; an error when Open Image Denoise has none.
    Cuda,
}

/// A device Open Image Denoise can denoise on here, as it reports it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PhysicalDevice {
    /// "CPU", "CUDA", "HIP", "SYCL" or "Metal".
    pub kind: &'static str,
    /// Its name, e.g. "NVIDIA H200" or the CPU's model.
    pub name: String,
}

/// The devices Open Image Denoise finds here (none: its device libraries are missing);
/// an error in a build without it.
pub fn physical_devices() -> Result<Vec<PhysicalDevice>> {
    #[cfg(feature = "denoise")]
    {
        oidn_filter::physical_devices()
    }
    #[cfg(not(feature = "denoise"))]
    {
        bail!("this rt was built without Open Image Denoise, so it cannot denoise: {HOW_TO_GET_OIDN}")
    }
}

/// An Open Image Denoise device, made once and reused for every image, with the filters
/// of the last image size: kept while the size stays (so that re-denoising a refining
/// image costs only the denoise), made again when it changes.
pub struct Denoiser {
    #[cfg(feature = "denoise")]
    inner: oidn_filter::OidnDenoiser,
}

impl Denoiser {
    /// A denoiser on `device`; an error naming what is missing when Open Image Denoise
    /// has no such device (or rt was built without it).
    pub fn new(device: DenoiseDevice) -> Result<Self> {
        #[cfg(feature = "denoise")]
        {
            Ok(Self { inner: oidn_filter::OidnDenoiser::new(device)? })
        }
        #[cfg(not(feature = "denoise"))]
        {
            let _ = device;
            bail!("this rt was built without Open Image Denoise, so it cannot denoise: {HOW_TO_GET_OIDN}")
        }
    }

    /// The device denoising runs on, in words ("CPU", "CUDA", ...).
    pub fn device(&self) -> &str {
        #[cfg(feature = "denoise")]
        {
            self.inner.device().kind
        }
        #[cfg(not(feature = "denoise"))]
        {
            unreachable!("a Denoiser cannot be made without Open Image Denoise")
        }
    }

    /// What was chosen and why, for the log: e.g. "CUDA (NVIDIA H200)", or
    /// "CPU (…; auto: no CUDA device)".
    pub fn describe(&self) -> String {
        #[cfg(feature = "denoise")]
        {
            self.inner.describe()
        }
        #[cfg(not(feature = "denoise"))]
        {
            unreachable!("a Denoiser cannot be made without Open Image Denoise")
        }
    }

    /// How many times filters were made: once per image size denoised in a row.
    pub fn filter_builds(&self) -> u32 {
        #[cfg(feature = "denoise")]
        {
            self.inner.filter_builds()
        }
        #[cfg(not(feature = "denoise"))]
        {
            unreachable!("a Denoiser cannot be made without Open Image Denoise")
        }
    }

    /// Frees the kept filters and their buffers: the next denoise makes them again.
    pub fn release_filters(&mut self) {
        #[cfg(feature = "denoise")]
        self.inner.release_filters();
    }

    /// The denoised radiance of `image`, guided by `aovs` (of the same render).
    pub fn denoise(&mut self, image: &Image, aovs: &Aovs) -> Result<Vec<[f32; 3]>> {
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
