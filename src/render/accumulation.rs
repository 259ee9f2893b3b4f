//! The running means per pixel that dispatches of samples add to, and what they
//! dropped as non-finite.

use super::Image;
use super::dropped::NonFiniteCause;
use crate::gpu::{GpuContext, Pipelines, Readback, SceneBuffers};
use crate::layout::GpuFrame;
use anyhow::{Result, bail};

/// Bytes per pixel of the means (RGB and the luminance's sum of squared deviations).
const MEAN_BYTES: u64 = 16;

pub struct Accumulation {
    pub width: u32,
    pub height: u32,
    pub samples: u32,
    means: wgpu::Buffer,
    non_finite: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

/// Refuses an image whose running means do not fit one GPU binding, naming the limit.
pub fn check_image_size(ctx: &GpuContext, width: u32, height: u32) -> Result<()> {
    let pixels = width as u64 * height as u64;
    let max = ctx.device.limits().max_storage_buffer_binding_size;
    if pixels * MEAN_BYTES > max {
        bail!(
            "a {width}x{height} image needs {} MiB of running means; this GPU ({}) binds at most {} MiB \
             per buffer, so at most {:.1} million pixels",
            (pixels * MEAN_BYTES) >> 20,
            ctx.adapter_info.name,
            max >> 20,
            (max / MEAN_BYTES) as f64 / 1e6
        );
    }
    Ok(())
}

impl Accumulation {
    /// Buffers for a `width`×`height` image; an image larger than one GPU binding holds
    /// is refused before anything is allocated, naming the limit.
    pub fn new(ctx: &GpuContext, layout: &wgpu::BindGroupLayout, width: u32, height: u32) -> Result<Self> {
        check_image_size(ctx, width, height)?;
        let pixels = width as u64 * height as u64;
        let buffer = |label, size| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let means = buffer("accumulation", pixels * MEAN_BYTES);
        let non_finite = buffer("non-finite samples", pixels * 4);
        let bind_group = crate::gpu::bind_group(ctx, "accumulation", layout, &[&means, &non_finite]);
        Ok(Self { width, height, samples: 0, means, non_finite, bind_group })
    }

    /// The running means per pixel (RGB, then the luminance's sum of squared deviations),
    /// rows from the top: what a display pass reads.
    pub fn means(&self) -> &wgpu::Buffer {
        &self.means
    }

    /// Records zeroing the means and the non-finite counts: the samples taken so far are dropped.
    pub fn clear(&mut self, encoder: &mut wgpu::CommandEncoder) {
        encoder.clear_buffer(&self.means, 0, None);
        encoder.clear_buffer(&self.non_finite, 0, None);
        self.samples = 0;
    }

    /// Records one dispatch of `frame.samples_per_dispatch` samples per pixel (and counts
    /// them as taken).
    pub fn encode(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        pipelines: &Pipelines,
        scene: &SceneBuffers,
        frame: &GpuFrame,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites>,
    ) {
        let n = frame.samples_per_dispatch;
        let frame = GpuFrame { sample_base: self.samples, ..*frame };
        scene.write_frame(ctx, &frame);
        let mut pass =
            encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("render"), timestamp_writes });
        pass.set_pipeline(pipelines.entry("render"));
        pass.set_bind_group(0, &scene.bind_group, &[]);
        pass.set_bind_group(1, &self.bind_group, &[]);
        if let Some(sky) = &scene.sky_bind_group {
            pass.set_bind_group(2, sky, &[]);
        }
        pass.dispatch_workgroups(self.width.div_ceil(8), self.height.div_ceil(8), 1);
        self.samples += n;
    }

    /// The mean radiance per pixel and the standard error of each pixel's mean luminance.
    pub fn image(&self, ctx: &GpuContext, readback: &Readback) -> Result<Image> {
        let means: Vec<[f32; 4]> = readback.read(ctx, &self.means)?;
        let dropped = self.non_finite(ctx, readback)?;
        let mut pixels = Vec::with_capacity(means.len());
        let mut std_error = Vec::with_capacity(means.len());
        for (m, (bad, _)) in means.iter().zip(&dropped) {
            // Dropped samples are not part of the mean: it is over the finite ones.
            let n = self.samples.saturating_sub(*bad).max(1) as f64;
            let variance = m[3].max(0.0) as f64 / (n - 1.0).max(1.0);
            pixels.push([m[0], m[1], m[2]]);
            std_error.push((variance / n).sqrt() as f32);
        }
        Ok(Image { width: self.width, height: self.height, samples: self.samples, pixels, std_error })
    }

    /// Dropped non-finite samples: per pixel, (count, the event that produced the first).
    pub fn non_finite(&self, ctx: &GpuContext, readback: &Readback) -> Result<Vec<(u32, NonFiniteCause)>> {
        let words: Vec<u32> = readback.read(ctx, &self.non_finite)?;
        Ok(words.iter().map(|w| (w & 0xff_ffff, NonFiniteCause::from_code(w >> 24))).collect())
    }
}
