//! Copying GPU buffers back to the host through a staging buffer that is kept and
//! reused while it is large enough, so a session reading its image every frame
//! does not allocate one each time.

use super::GpuContext;
use anyhow::{Result, anyhow};
use bytemuck::Pod;
use std::cell::RefCell;

#[derive(Default)]
pub struct Readback {
    staging: RefCell<Option<wgpu::Buffer>>,
}

impl Readback {
    pub fn new() -> Self {
        Self::default()
    }

    /// The contents of `buffer` (which has COPY_SRC usage).
    pub fn read<T: Pod>(&self, ctx: &GpuContext, buffer: &wgpu::Buffer) -> Result<Vec<T>> {
        let size = buffer.size();
        let mut slot = self.staging.borrow_mut();
        let staging = match slot.as_ref() {
            Some(s) if s.size() >= size => s.clone(),
            _ => {
                let s = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("readback"),
                    size,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                *slot = Some(s.clone());
                s
            }
        };
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
        ctx.queue.submit([encoder.finish()]);
        let slice = staging.slice(..size);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        ctx.wait()?;
        rx.recv()?.map_err(|e| anyhow!("could not read a GPU buffer back: {e}"))?;
        let data = {
            let view = slice.get_mapped_range().map_err(|e| anyhow!("could not map a GPU buffer: {e}"))?;
            bytemuck::pod_collect_to_vec(&view)
        };
        staging.unmap();
        Ok(data)
    }
}

/// The contents of `buffer`, through a staging buffer of its own: for one-off reads.
pub fn read_buffer<T: Pod>(ctx: &GpuContext, buffer: &wgpu::Buffer) -> Result<Vec<T>> {
    Readback::new().read(ctx, buffer)
}
