//! The `oidn` crate's side of [`super::Denoiser`].

use super::{DenoiseDevice, PhysicalDevice};
use crate::render::{Aovs, Image};
use anyhow::{Result, anyhow, bail};
use oidn::sys;
use std::ffi::CStr;

pub struct OidnDenoiser {
    device: oidn::Device,
    physical: PhysicalDevice,
    /// Why `auto` took the CPU, when it did.
    fallback: Option<String>,
}

/// What Open Image Denoise says a device type is.
fn kind_name(kind: std::os::raw::c_int) -> &'static str {
    match kind as sys::OIDNDeviceType {
        sys::OIDNDeviceType_OIDN_DEVICE_TYPE_CPU => "CPU",
        sys::OIDNDeviceType_OIDN_DEVICE_TYPE_SYCL => "SYCL",
        sys::OIDNDeviceType_OIDN_DEVICE_TYPE_CUDA => "CUDA",
        sys::OIDNDeviceType_OIDN_DEVICE_TYPE_HIP => "HIP",
        sys::OIDNDeviceType_OIDN_DEVICE_TYPE_METAL => "Metal",
        _ => "unknown",
    }
}

/// The devices Open Image Denoise found, fastest first (its own order).
pub fn physical_devices() -> Vec<PhysicalDevice> {
    // SAFETY: these calls take no handles; the name is a C string Open Image Denoise
    // owns, copied at once. Errors (none is expected) land on the null device and
    // are cleared, so that no later call reports them.
    unsafe {
        let count = sys::oidnGetNumPhysicalDevices().max(0);
        let devices = (0..count)
            .map(|i| {
                let kind = kind_name(sys::oidnGetPhysicalDeviceInt(i, c"type".as_ptr()));
                let name = sys::oidnGetPhysicalDeviceString(i, c"name".as_ptr());
                let name = match name.is_null() {
                    true => String::new(),
                    false => CStr::from_ptr(name).to_string_lossy().trim().to_string(),
                };
                PhysicalDevice { kind, name }
            })
            .collect();
        sys::oidnGetDeviceError(std::ptr::null_mut(), std::ptr::null_mut());
        devices
    }
}

fn no_device(e: impl std::fmt::Display) -> anyhow::Error {
    anyhow!(
        "Open Image Denoise could make no device ({e}); its device libraries \
         (libOpenImageDenoise_device_cpu.so.2.5.1 and others) must lie beside libOpenImageDenoise.so.2: \
         scripts/fetch_oidn installs them into .oidn/lib"
    )
}

impl OidnDenoiser {
    pub fn new(choice: DenoiseDevice) -> Result<Self> {
        let found = physical_devices();
        let first = |kind: &str| found.iter().find(|d| d.kind == kind).cloned();
        let cpu = || -> Result<(oidn::Device, PhysicalDevice)> {
            let device = oidn::Device::cpu().map_err(no_device)?;
            let physical = first("CPU").unwrap_or(PhysicalDevice { kind: "CPU", name: String::new() });
            Ok((device, physical))
        };
        let cuda = || -> Result<(oidn::Device, PhysicalDevice)> {
            let Some(physical) = first("CUDA") else {
                let seen: Vec<String> = found.iter().map(|d| format!("{} ({})", d.kind, d.name)).collect();
                bail!(
                    "Open Image Denoise found no CUDA device (it found: {}); it needs an NVIDIA GPU of compute \
                     capability 7.0 or later with its driver, and libOpenImageDenoise_device_cuda.so.2.5.1 beside \
                     libOpenImageDenoise.so.2 (scripts/fetch_oidn installs it); `--denoise-device cpu` or `auto` \
                     denoise on the CPU",
                    if seen.is_empty() { "none".to_string() } else { seen.join(", ") }
                )
            };
            let device = oidn::Device::cuda()
                .map_err(|e| anyhow!("Open Image Denoise could not open its CUDA device {}: {e}", physical.name))?;
            Ok((device, physical))
        };
        let ((device, physical), fallback) = match choice {
            DenoiseDevice::Cpu => (cpu()?, None),
            DenoiseDevice::Cuda => (cuda()?, None),
            DenoiseDevice::Auto => match cuda() {
                Ok(d) => (d, None),
                Err(e) => {
                    // A listed CUDA device that fails to open is worth a warning; no CUDA device is the usual case.
                    let why = match first("CUDA") {
                        Some(_) => format!("{e:#}"),
                        None => "no CUDA device".to_string(),
                    };
                    (cpu()?, Some(why))
                }
            },
        };
        Ok(Self { device, physical, fallback })
    }

    pub fn device(&self) -> &PhysicalDevice {
        &self.physical
    }

    pub fn describe(&self) -> String {
        let name = match self.physical.name.is_empty() {
            true => self.physical.kind.to_string(),
            false => format!("{} ({})", self.physical.kind, self.physical.name),
        };
        match &self.fallback {
            Some(why) => format!("{name}; auto: {why}"),
            None => name,
        }
    }

    pub fn denoise(&self, image: &Image, aovs: &Aovs) -> Result<Vec<[f32; 3]>> {
        let (w, h) = (image.width as usize, image.height as usize);
        let flat = |v: &[[f32; 3]]| v.iter().flatten().copied().collect::<Vec<f32>>();
        let color = flat(&image.pixels);
        let mut albedo = flat(&aovs.albedo);
        let mut normal = flat(&aovs.normal);
        let error =
            |what: &str, e: oidn::Error| anyhow!("Open Image Denoise ({} device) {what}: {e}", self.physical.kind);
        // The guides are averages of few samples too: denoised first, they may then be
        // trusted as clean ("clean aux"), which keeps their noise out of the image.
        oidn::RayTracing::try_new(&self.device)
            .map_err(|e| error("made no filter", e))?
            .albedo(&albedo.clone())
            .image_dimensions(w, h)
            .filter_in_place(&mut albedo)
            .map_err(|e| error("could not prefilter the albedo", e))?;
        self.prefilter_normal(&mut normal, w, h).map_err(|e| error("could not prefilter the normals", e))?;
        let mut output = vec![0.0f32; color.len()];
        oidn::RayTracing::try_new(&self.device)
            .map_err(|e| error("made no filter", e))?
            .hdr(true)
            .clean_aux(true)
            .albedo_normal(&albedo, &normal)
            .image_dimensions(w, h)
            .filter(&color, &mut output)
            .map_err(|e| error("could not denoise", e))?;
        if let Err(e) = self.device.get_error() {
            bail!("Open Image Denoise ({} device): {e}", self.physical.kind);
        }
        Ok(output.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
    }

    /// The `RT` filter with a normal image alone denoises that image (the crate sets
    /// normals only together with an albedo, so this one is set up by hand).
    fn prefilter_normal(&self, normal: &mut [f32], w: usize, h: usize) -> Result<(), oidn::Error> {
        let input = self.device.create_buffer(normal)?;
        let output = self.device.create_buffer(normal)?;
        // SAFETY: the filter is made on the live device and released before returning; both
        // buffers hold w·h float3 pixels and outlive the filter's execution.
        unsafe {
            let filter = sys::oidnNewFilter(self.device.raw(), c"RT".as_ptr());
            if filter.is_null() {
                self.device.get_error()?;
                return Err(oidn::Error::from(oidn::ErrorKind::Unknown));
            }
            let image = |name: &std::ffi::CStr, buffer: &oidn::Buffer| {
                sys::oidnSetFilterImage(
                    filter,
                    name.as_ptr(),
                    buffer.raw(),
                    sys::OIDNFormat_OIDN_FORMAT_FLOAT3,
                    w,
                    h,
                    0,
                    0,
                    0,
                )
            };
            image(c"normal", &input);
            image(c"output", &output);
            sys::oidnCommitFilter(filter);
            sys::oidnExecuteFilter(filter);
            sys::oidnReleaseFilter(filter);
        }
        self.device.get_error()?;
        output.read_to_slice(normal)
    }
}
