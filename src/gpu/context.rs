//! Adapter selection and device creation.

use anyhow::{Context as _, Result, anyhow, bail};

/// The device rt renders with, and what it is.
pub struct GpuContext {
    /// Kept so that a window can make a surface that this adapter presents to.
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_info: wgpu::AdapterInfo,
    pub timestamps: bool,
}

/// Storage buffers the integrator binds in one stage (see `shaders/common.wgsl`).
const STORAGE_BUFFERS_NEEDED: u32 = 16;

const NO_ADAPTER_HELP: &str = "no GPU adapter found. rt needs Vulkan; on a machine without a GPU, \
install Mesa's CPU driver (lavapipe): `sudo apt-get install mesa-vulkan-drivers`";

impl GpuContext {
    /// Picks an adapter: the one whose name contains `wanted` (case-insensitive)
    /// if given, else a discrete GPU, else an integrated one, else any (lavapipe).
    pub fn new(wanted: Option<&str>) -> Result<Self> {
        pollster::block_on(Self::new_async(wanted))
    }

    async fn new_async(wanted: Option<&str>) -> Result<Self> {
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
            max_storage_buffer_binding_size: available.max_storage_buffer_binding_size,
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
        Ok(Self { instance, adapter, device, queue, adapter_info: info, timestamps })
    }

    /// "NVIDIA H100 80GB HBM3 (DiscreteGpu, Vulkan, driver 580.159)".
    pub fn describe(&self) -> String {
        let i = &self.adapter_info;
        format!("{} ({:?}, {:?}, {} {})", i.name, i.device_type, i.backend, i.driver, i.driver_info)
    }

    pub fn wait(&self) -> Result<()> {
        self.device.poll(wgpu::PollType::wait_indefinitely()).map(|_| ()).map_err(|e| anyhow!("GPU wait failed: {e}"))
    }
}
