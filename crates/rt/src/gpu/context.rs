//! Adapter selection and device creation, and what becomes of the device's errors:
//! wgpu's default handler panics on an error no scope caught; rt's records it, and the
//! next [`GpuContext::wait`] (or [`GpuContext::take_error`]) returns it as an `Err`.

use super::bind::Binding;
use super::scene_bindings::SCENE_BINDINGS;
use anyhow::{Context as _, Result, anyhow, bail};
use std::path::Path;
use std::sync::{Arc, Mutex};

/// The device rt renders with, and what it is.
pub struct GpuContext {
    /// Kept so that a window can make a surface that this adapter presents to.
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_info: wgpu::AdapterInfo,
    pub timestamps: bool,
    /// Uncaught validation and out-of-memory errors, and a lost device, since the last
    /// [`GpuContext::take_error`].
    errors: Arc<Mutex<Vec<String>>>,
}

/// Storage buffers the integrator binds in one stage, counted from the groups' declarations:
/// the scene's (`super::scene_bindings`), the accumulation's and the atmosphere's. lavapipe
/// offers 32, the NVIDIA driver far more.
const STORAGE_BUFFERS_NEEDED: u32 = Binding::storage_buffers(SCENE_BINDINGS)
    + super::buffers::ACCUMULATION_BUFFERS as u32
    + Binding::storage_buffers(&super::buffers::SKY_BINDINGS);

// lavapipe, the driver of machines without a GPU (CI's), offers 32: a binding past that is
// a build error, not a failure on the first such machine.
const _: () = assert!(STORAGE_BUFFERS_NEEDED <= 32, "more storage buffers in one stage than lavapipe offers");

const NO_ADAPTER_HELP: &str = "no GPU adapter found. rt needs Vulkan; on a machine without a GPU, \
install Mesa's CPU driver (lavapipe): `sudo apt-get install mesa-vulkan-drivers`";

/// Every Vulkan adapter wgpu finds, described as `rt info` prints the one it uses.
pub fn adapter_names() -> Vec<String> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends: wgpu::Backends::VULKAN,
        ..wgpu::InstanceDescriptor::new_without_display_handle_from_env()
    });
    let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
    adapters
        .iter()
        .map(|a| {
            let info = a.get_info();
            format!("{} ({:?}, {})", info.name, info.device_type, info.driver)
        })
        .collect()
}

impl GpuContext {
    /// Picks an adapter: the one whose name contains `wanted` (case-insensitive)
    /// if given, else a discrete GPU, else an integrated one, else any (lavapipe).
    pub fn new(wanted: Option<&str>) -> Result<Self> {
        pollster::block_on(Self::new_async(wanted, None))
    }

    /// [`Self::new`], with a device that binds at most `bytes` per storage buffer: what a
    /// smaller GPU allows, to see a scene refused as it would be there.
    pub fn with_binding_limit(wanted: Option<&str>, bytes: u64) -> Result<Self> {
        pollster::block_on(Self::new_async(wanted, Some(bytes)))
    }

    async fn new_async(wanted: Option<&str>, binding_limit: Option<u64>) -> Result<Self> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            ..wgpu::InstanceDescriptor::new_without_display_handle_from_env()
        });
        let adapters = instance.enumerate_adapters(wgpu::Backends::VULKAN).await;
        if adapters.is_empty() {
            bail!(NO_ADAPTER_HELP);
        }
        let adapter = match wanted {
            Some(name) => {
                let needle = name.to_lowercase();
                let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
                adapters
                    .into_iter()
                    .find(|a| a.get_info().name.to_lowercase().contains(&needle))
                    .ok_or_else(|| anyhow!("no adapter matches {name:?}; available: {}", names.join(", ")))?
            }
            None => {
                let rank = |a: &wgpu::Adapter| match a.get_info().device_type {
                    wgpu::DeviceType::DiscreteGpu => 0,
                    wgpu::DeviceType::IntegratedGpu => 1,
                    wgpu::DeviceType::VirtualGpu => 2,
                    wgpu::DeviceType::Other => 3,
                    wgpu::DeviceType::Cpu => 4,
                };
                adapters.into_iter().min_by_key(rank).ok_or_else(|| anyhow!(NO_ADAPTER_HELP))?
            }
        };
        let info = adapter.get_info();
        let available = adapter.limits();
        if available.max_storage_buffers_per_shader_stage < STORAGE_BUFFERS_NEEDED {
            bail!(
                "the GPU {:?} offers {} storage buffers per shader stage; rt needs {STORAGE_BUFFERS_NEEDED}",
                info.name,
                available.max_storage_buffers_per_shader_stage
            );
        }
        let limits = wgpu::Limits {
            max_storage_buffers_per_shader_stage: STORAGE_BUFFERS_NEEDED,
            // The storage buffers above and the uniform ones together (wgpu's default, 28, is
            // one short with an environment's or an atmosphere's tables bound).
            max_buffers_and_acceleration_structures_per_shader_stage: available
                .max_buffers_and_acceleration_structures_per_shader_stage,
            max_storage_buffer_binding_size: binding_limit.map_or(available.max_storage_buffer_binding_size, |b| {
                b.min(available.max_storage_buffer_binding_size)
            }),
            max_buffer_size: available.max_buffer_size,
            ..wgpu::Limits::default()
        };
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let features = if timestamps { wgpu::Features::TIMESTAMP_QUERY } else { wgpu::Features::empty() };
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("rt"),
                required_features: features,
                required_limits: limits,
                ..Default::default()
            })
            .await
            .with_context(|| format!("could not open the GPU {:?}", info.name))?;
        let errors = Arc::new(Mutex::new(Vec::new()));
        let record = |errors: &Arc<Mutex<Vec<String>>>, message: String| {
            log::error!("{message}");
            errors.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).push(message);
        };
        let sink = errors.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| record(&sink, format!("GPU error: {e}"))));
        let sink = errors.clone();
        device.set_device_lost_callback(move |reason, message| {
            // Dropping the device at exit is not a failure.
            if reason != wgpu::DeviceLostReason::Destroyed {
                record(&sink, format!("the GPU device was lost ({reason:?}): {message}"));
            }
        });
        Ok(Self { instance, adapter, device, queue, adapter_info: info, timestamps, errors })
    }

    /// The GPU errors recorded since the last call, as one `Err`; `Ok` if there were none.
    /// Work submitted before an error may have produced garbage: callers drop its results.
    pub fn take_error(&self) -> Result<()> {
        let errors = std::mem::take(&mut *self.errors.lock().unwrap_or_else(|poisoned| poisoned.into_inner()));
        match errors.as_slice() {
            [] => Ok(()),
            [one] => bail!("{one}"),
            [first, rest @ ..] => bail!("{first} (and {} more GPU errors)", rest.len()),
        }
    }

    /// "NVIDIA H100 80GB HBM3 (DiscreteGpu, Vulkan, driver 580.159)".
    pub fn describe(&self) -> String {
        let i = &self.adapter_info;
        format!("{} ({:?}, {:?}, {} {})", i.name, i.device_type, i.backend, i.driver, i.driver_info)
    }

    /// Waits for the submitted work; an error it (or anything before it) raised is returned.
    pub fn wait(&self) -> Result<()> {
        self.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| anyhow!("GPU wait failed: {e}"))?;
        self.take_error()
    }
}

/// Mesa's Wayland code prints "XDG_RUNTIME_DIR is invalid or not set" (twice) on every
/// Vulkan start without a valid one. When it is unset or not an absolute path to a
/// folder, it is pointed at a private folder, `$TMPDIR/rt-runtime-UID` (mode 0700, owned
/// by this user; left alone if someone else owns it), before any Vulkan instance exists.
///
/// Must be called at the very start of `main`, before any thread is spawned.
pub fn ensure_runtime_dir() {
    use std::os::unix::fs::{DirBuilderExt, MetadataExt, PermissionsExt};
    let valid =
        std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| Path::new(&d).is_absolute() && Path::new(&d).is_dir());
    let Ok(me) = std::fs::metadata("/proc/self").map(|m| m.uid()) else { return };
    if valid {
        return;
    }
    let dir = std::env::temp_dir().join(format!("rt-runtime-{me}"));
    let _ = std::fs::DirBuilder::new().mode(0o700).create(&dir);
    // symlink_metadata: a link planted by another user must not be followed.
    let ours = std::fs::symlink_metadata(&dir)
        .is_ok_and(|m| m.is_dir() && m.uid() == me && m.permissions().mode() & 0o077 == 0);
    if ours {
        // SAFETY: `set_var` is unsound only while another thread reads or writes the
        // environment. `main` calls this first, before it spawns any thread, and the
        // Rust runtime starts none of its own before `main`.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", &dir) };
    }
}
