//! [`super::Denoiser`] on Open Image Denoise's C API: a device, and for one image size
//! the three `RT` filters (the albedo and the normals prefiltered, then the beauty) with
//! their buffers, committed once. Committing is what costs (weights loaded, memory
//! planned): while the size stays, a later denoise of the same device, as `rt watch`
//! makes of a refining image, only copies pixels in, executes and copies them out. The
//! functions come from the library loaded at run time ([`super::oidn_api`]).

use super::oidn_api::*;
use super::{DenoiseDevice, PhysicalDevice};
use crate::render::{Aovs, Image};
use anyhow::{Result, anyhow, bail};
use std::ffi::{CStr, c_char};

/// What Open Image Denoise says a device type is.
fn kind_name(kind: std::os::raw::c_int) -> &'static str {
    match kind {
        OIDN_DEVICE_TYPE_CPU => "CPU",
        OIDN_DEVICE_TYPE_SYCL => "SYCL",
        OIDN_DEVICE_TYPE_CUDA => "CUDA",
        OIDN_DEVICE_TYPE_HIP => "HIP",
        OIDN_DEVICE_TYPE_METAL => "Metal",
        _ => "unknown",
    }
}

/// The error Open Image Denoise last recorded on `device` (the null device: errors of
/// calls that had none), cleared as it is read.
fn take_error(api: &Api, device: OIDNDevice) -> Result<(), String> {
    let mut message: *const c_char = std::ptr::null();
    // SAFETY: `device` is live or null (the null device is valid here); the message is
    // a C string Open Image Denoise owns until its next call, copied at once.
    let code = unsafe { (api.oidnGetDeviceError)(device, &mut message) };
    if code == OIDN_ERROR_NONE {
        return Ok(());
    }
    let text = match message.is_null() {
        true => String::new(),
        // SAFETY: non-null, NUL-terminated (see above).
        false => unsafe { CStr::from_ptr(message) }.to_string_lossy().trim().to_string(),
    };
    Err(if text.is_empty() { format!("error {code}") } else { text })
}

/// The devices Open Image Denoise found, fastest first (its own order); an error saying
/// how to get the library when it cannot be loaded.
pub fn physical_devices() -> Result<Vec<PhysicalDevice>> {
    let api = api().map_err(anyhow::Error::msg)?;
    // SAFETY: these calls take no handles; the name is a C string Open Image Denoise
    // owns, copied at once.
    let devices = unsafe {
        let count = (api.oidnGetNumPhysicalDevices)().max(0);
        (0..count)
            .map(|i| {
                let kind = kind_name((api.oidnGetPhysicalDeviceInt)(i, c"type".as_ptr()));
                let name = (api.oidnGetPhysicalDeviceString)(i, c"name".as_ptr());
                let name = match name.is_null() {
                    true => String::new(),
                    false => CStr::from_ptr(name).to_string_lossy().trim().to_string(),
                };
                PhysicalDevice { kind, name }
            })
            .collect()
    };
    // Errors (none is expected) land on the null device: cleared, so no later call reports them.
    let _ = take_error(api, std::ptr::null_mut());
    Ok(devices)
}

/// A committed Open Image Denoise device, released when dropped.
struct Device {
    raw: OIDNDevice,
    api: &'static Api,
}

impl Device {
    fn new(api: &'static Api, kind: OIDNDeviceType) -> Result<Self, String> {
        // SAFETY: no handles in; the new device is committed before any use.
        let raw = unsafe { (api.oidnNewDevice)(kind) };
        if raw.is_null() {
            return Err(take_error(api, std::ptr::null_mut()).err().unwrap_or_else(|| "no device".into()));
        }
        let device = Self { raw, api };
        // SAFETY: `raw` is the live device just made.
        unsafe { (api.oidnCommitDevice)(raw) };
        take_error(api, raw)?;
        Ok(device)
    }

    fn check(&self) -> Result<(), String> {
        take_error(self.api, self.raw)
    }
}

impl Drop for Device {
    fn drop(&mut self) {
        // SAFETY: the device is live and released once; its filters and buffers went first.
        unsafe { (self.api.oidnReleaseDevice)(self.raw) }
    }
}

/// A device buffer of `bytes` bytes.
struct Buffer {
    raw: OIDNBuffer,
    bytes: usize,
    api: &'static Api,
}

impl Drop for Buffer {
    fn drop(&mut self) {
        // SAFETY: live, released once.
        unsafe { (self.api.oidnReleaseBuffer)(self.raw) }
    }
}

struct Filter {
    raw: OIDNFilter,
    api: &'static Api,
}

impl Drop for Filter {
    fn drop(&mut self) {
        // SAFETY: live, released once.
        unsafe { (self.api.oidnReleaseFilter)(self.raw) }
    }
}

/// The filters of one image size, committed, with the buffers they read and write.
/// (Fields drop in order: the filters before the buffers they hold.)
struct Filters {
    albedo_filter: Filter,
    normal_filter: Filter,
    beauty_filter: Filter,
    color: Buffer,
    albedo: Buffer,
    normal: Buffer,
    /// The prefiltered albedo and normals: only the filters write and read them.
    _clean_guides: [Buffer; 2],
    output: Buffer,
    size: (usize, usize),
}

impl Filters {
    fn new(device: &Device, (w, h): (usize, usize)) -> Result<Self, String> {
        let (api, bytes) = (device.api, w * h * 3 * std::mem::size_of::<f32>());
        let buffer = || -> Result<Buffer, String> {
            // SAFETY: the device is live.
            let raw = unsafe { (api.oidnNewBuffer)(device.raw, bytes) };
            if raw.is_null() {
                return Err(device.check().err().unwrap_or_else(|| format!("no buffer of {bytes} bytes")));
            }
            Ok(Buffer { raw, bytes, api })
        };
        let (color, albedo, normal) = (buffer()?, buffer()?, buffer()?);
        let (clean_albedo, clean_normal, output) = (buffer()?, buffer()?, buffer()?);
        let filter = |images: &[(&CStr, &Buffer)], hdr: bool| -> Result<Filter, String> {
            // SAFETY: the device and buffers are live; each buffer holds w·h float3 pixels.
            unsafe {
                let raw = (api.oidnNewFilter)(device.raw, c"RT".as_ptr());
                if raw.is_null() {
                    return Err(device.check().err().unwrap_or_else(|| "no RT filter".into()));
                }
                let filter = Filter { raw, api };
                for (name, buffer) in images {
                    (api.oidnSetFilterImage)(raw, name.as_ptr(), buffer.raw, OIDN_FORMAT_FLOAT3, w, h, 0, 0, 0);
                }
                if hdr {
                    (api.oidnSetFilterBool)(raw, c"hdr".as_ptr(), true);
                    // The guides were denoised first: trusted as clean, their noise stays out of the image.
                    (api.oidnSetFilterBool)(raw, c"cleanAux".as_ptr(), true);
                }
                (api.oidnCommitFilter)(raw);
                device.check()?;
                Ok(filter)
            }
        };
        // The `RT` filter given an albedo or a normal image alone denoises that image.
        let albedo_filter = filter(&[(c"albedo", &albedo), (c"output", &clean_albedo)], false)?;
        let normal_filter = filter(&[(c"normal", &normal), (c"output", &clean_normal)], false)?;
        let beauty_filter = filter(
            &[(c"color", &color), (c"albedo", &clean_albedo), (c"normal", &clean_normal), (c"output", &output)],
            true,
        )?;
        Ok(Self {
            albedo_filter,
            normal_filter,
            beauty_filter,
            color,
            albedo,
            normal,
            _clean_guides: [clean_albedo, clean_normal],
            output,
            size: (w, h),
        })
    }

    fn run(&self, device: &Device, color: &[f32], albedo: &[f32], normal: &[f32]) -> Result<Vec<f32>, String> {
        let api = device.api;
        let write = |buffer: &Buffer, data: &[f32]| {
            debug_assert_eq!(std::mem::size_of_val(data), buffer.bytes);
            // SAFETY: `data` holds exactly the buffer's bytes (both are w·h float3 pixels).
            unsafe { (api.oidnWriteBuffer)(buffer.raw, 0, buffer.bytes, data.as_ptr().cast()) }
        };
        write(&self.color, color);
        write(&self.albedo, albedo);
        write(&self.normal, normal);
        // SAFETY: the filters are committed on the live device; the output fits the vector.
        let mut out = vec![0.0f32; color.len()];
        unsafe {
            (api.oidnExecuteFilter)(self.albedo_filter.raw);
            (api.oidnExecuteFilter)(self.normal_filter.raw);
            (api.oidnExecuteFilter)(self.beauty_filter.raw);
            (api.oidnReadBuffer)(self.output.raw, 0, self.output.bytes, out.as_mut_ptr().cast());
        }
        device.check()?;
        Ok(out)
    }
}

pub struct OidnDenoiser {
    // Dropped before the device they were made on.
    filters: Option<Filters>,
    device: Device,
    physical: PhysicalDevice,
    /// Why `auto` took the CPU, when it did.
    fallback: Option<String>,
    /// Times filters were made (and committed) for a new size.
    builds: u32,
}

// SAFETY: Open Image Denoise's devices, filters and buffers may be used from any thread,
// one at a time: the denoiser owns its handles (none is shared), and `&mut self` makes
// its uses one at a time (rt moves a denoiser to the viewer's denoising thread).
unsafe impl Send for OidnDenoiser {}

fn no_device(e: impl std::fmt::Display) -> anyhow::Error {
    anyhow!(
        "Open Image Denoise could make no device ({e}); its device libraries \
         (libOpenImageDenoise_device_cpu.so.2.5.1 and others) must lie beside libOpenImageDenoise.so.2: \
         scripts/fetch_oidn installs them into .oidn/lib"
    )
}

impl OidnDenoiser {
    pub fn new(choice: DenoiseDevice) -> Result<Self> {
        let found = physical_devices()?;
        let api = api().map_err(anyhow::Error::msg)?;
        let first = |kind: &str| found.iter().find(|d| d.kind == kind).cloned();
        let cpu = || -> Result<(Device, PhysicalDevice)> {
            let device = Device::new(api, OIDN_DEVICE_TYPE_CPU).map_err(no_device)?;
            let physical = first("CPU").unwrap_or(PhysicalDevice { kind: "CPU", name: String::new() });
            Ok((device, physical))
        };
        let cuda = || -> Result<(Device, PhysicalDevice)> {
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
            let device = Device::new(api, OIDN_DEVICE_TYPE_CUDA)
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
        Ok(Self { filters: None, device, physical, fallback, builds: 0 })
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

    pub fn filter_builds(&self) -> u32 {
        self.builds
    }

    pub fn release_filters(&mut self) {
        self.filters = None;
    }

    pub fn denoise(&mut self, image: &Image, aovs: &Aovs) -> Result<Vec<[f32; 3]>> {
        let size = (image.width as usize, image.height as usize);
        let kind = self.physical.kind;
        if self.filters.as_ref().is_none_or(|f| f.size != size) {
            // The old size's buffers go before the new ones are allocated.
            self.filters = None;
            let filters = Filters::new(&self.device, size)
                .map_err(|e| anyhow!("Open Image Denoise ({kind} device) made no filters: {e}"))?;
            self.filters = Some(filters);
            self.builds += 1;
        }
        let Some(filters) = &self.filters else { bail!("Open Image Denoise ({kind} device) has no filters") };
        let flat = |v: &[[f32; 3]]| v.iter().flatten().copied().collect::<Vec<f32>>();
        let result = filters.run(&self.device, &flat(&image.pixels), &flat(&aovs.albedo), &flat(&aovs.normal));
        let output = match result {
            Ok(output) => output,
            Err(e) => {
                // A failed run may leave the filters in any state: made afresh next time.
                self.filters = None;
                bail!("Open Image Denoise ({kind} device) could not denoise: {e}");
            }
        };
        Ok(output.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
    }
}
