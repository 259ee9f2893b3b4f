//! The `oidn` crate's side of [`super::Denoiser`].

use crate::render::{Aovs, Image};
use anyhow::{Result, anyhow, bail};
use oidn::sys;

pub struct OidnDenoiser {
    device: oidn::Device,
    name: &'static str,
}

impl OidnDenoiser {
    pub fn new() -> Result<Self> {
        // The default device is the fastest Open Image Denoise supports here: a GPU
        // (CUDA, HIP, SYCL) when it has one, else the CPU.
        let device = oidn::Device::new().map_err(|e| {
            anyhow!(
                "Open Image Denoise could make no device ({e}); its device libraries \
                 (libOpenImageDenoise_device_cpu.so.2.5.1 and others) must lie beside libOpenImageDenoise.so.2: \
                 scripts/fetch_oidn installs them into .oidn/lib"
            )
        })?;
        // SAFETY: the handle is the live device's; "type" is one of its integer parameters.
        let kind = unsafe { sys::oidnGetDeviceInt(device.raw(), c"type".as_ptr()) };
        let name = match kind as sys::OIDNDeviceType {
            sys::OIDNDeviceType_OIDN_DEVICE_TYPE_CPU => "CPU",
            sys::OIDNDeviceType_OIDN_DEVICE_TYPE_SYCL => "SYCL",
            sys::OIDNDeviceType_OIDN_DEVICE_TYPE_CUDA => "CUDA",
            sys::OIDNDeviceType_OIDN_DEVICE_TYPE_HIP => "HIP",
            sys::OIDNDeviceType_OIDN_DEVICE_TYPE_METAL => "Metal",
            _ => "unknown",
        };
        Ok(Self { device, name })
    }

    pub fn device_name(&self) -> &str {
        self.name
    }

    pub fn denoise(&self, image: &Image, aovs: &Aovs) -> Result<Vec<[f32; 3]>> {
        let (w, h) = (image.width as usize, image.height as usize);
        let flat = |v: &[[f32; 3]]| v.iter().flatten().copied().collect::<Vec<f32>>();
        let color = flat(&image.pixels);
        let mut albedo = flat(&aovs.albedo);
        let mut normal = flat(&aovs.normal);
        let error = |what: &str, e: oidn::Error| anyhow!("Open Image Denoise ({} device) {what}: {e}", self.name);
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
            bail!("Open Image Denoise ({} device): {e}", self.name);
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
