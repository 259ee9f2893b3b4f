//! Progressive accumulation: dispatches of several samples per pixel added to
//! running means, sized so that each dispatch stays far below a GPU watchdog.

use super::Image;
use super::sentinel::NonFiniteCause;
use crate::gpu::layout::GpuFrame;
use crate::gpu::{GpuContext, GpuTimer, Pipelines, SceneBuffers, read_buffer};
use anyhow::Result;
use std::time::{Duration, Instant};

/// Time one dispatch should take: long enough to keep the GPU busy, far
/// below the ~2 s after which drivers reset a GPU that does not answer.
const DISPATCH_TARGET: Duration = Duration::from_millis(80);
pub const MAX_SAMPLES_PER_DISPATCH: u32 = 256;

pub struct Accumulation {
    pub width: u32,
    pub height: u32,
    pub samples: u32,
    means: wgpu::Buffer,
    non_finite: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    samples_per_dispatch: u32,
    /// Whether dispatch sizes follow dispatch times (else they stay as fixed).
    adaptive: bool,
}

impl Accumulation {
    pub fn new(ctx: &GpuContext, layout: &wgpu::BindGroupLayout, width: u32, height: u32) -> Self {
        let means = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("accumulation"),
            size: width as u64 * height as u64 * 16,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let non_finite = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("non-finite samples"),
            size: width as u64 * height as u64 * 4,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("accumulation"),
            layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: means.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: non_finite.as_entire_binding() },
            ],
        });
        Self { width, height, samples: 0, means, non_finite, bind_group, samples_per_dispatch: 1, adaptive: true }
    }

    /// Every dispatch takes `n` samples per pixel (the last one fewer if the total
    /// asks for it), instead of as many as keep it near the target time.
    pub fn fix_samples_per_dispatch(&mut self, n: u32) {
        self.samples_per_dispatch = n.clamp(1, MAX_SAMPLES_PER_DISPATCH);
        self.adaptive = false;
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

    /// Adds up to `max_samples` samples per pixel in one dispatch and waits for it;
    /// returns how many it added. The next dispatch's size follows this one's time.
    pub fn dispatch(
        &mut self,
        ctx: &GpuContext,
        pipelines: &Pipelines,
        scene: &SceneBuffers,
        frame: &GpuFrame,
        max_samples: u32,
    ) -> Result<u32> {
        self.dispatch_timed(ctx, pipelines, scene, frame, max_samples, None).map(|(n, _)| n)
    }

    /// [`Self::dispatch`], also returning how long it took: the GPU's own time with a
    /// timer that has timestamp queries, else the wall-clock time until it finished.
    pub fn dispatch_timed(
        &mut self,
        ctx: &GpuContext,
        pipelines: &Pipelines,
        scene: &SceneBuffers,
        frame: &GpuFrame,
        max_samples: u32,
        timer: Option<&GpuTimer>,
    ) -> Result<(u32, Duration)> {
        let n = self.samples_per_dispatch.min(max_samples).max(1);
        let start = Instant::now();
        let took = match timer {
            Some(timer) => timer.time(ctx, |e, w| self.encode(ctx, e, pipelines, scene, frame, n, w))?,
            None => {
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                self.encode(ctx, &mut encoder, pipelines, scene, frame, n, None);
                ctx.queue.submit([encoder.finish()]);
                ctx.wait()?;
                start.elapsed()
            }
        };
        if self.adaptive {
            let wall = start.elapsed().max(Duration::from_micros(100));
            // Grow or shrink towards the target, by at most 2× a step so a slow frame cannot overshoot.
            let ratio = (DISPATCH_TARGET.as_secs_f64() / wall.as_secs_f64()).clamp(0.5, 2.0);
            self.samples_per_dispatch = ((n as f64 * ratio) as u32).clamp(1, MAX_SAMPLES_PER_DISPATCH);
        }
        Ok((n, took))
    }

    /// Records one dispatch of `n` samples per pixel (and counts them as taken).
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        pipelines: &Pipelines,
        scene: &SceneBuffers,
        frame: &GpuFrame,
        n: u32,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites>,
    ) {
        let frame = GpuFrame { sample_base: self.samples, samples_per_dispatch: n, ..*frame };
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
    pub fn image(&self, ctx: &GpuContext) -> Result<Image> {
        let means: Vec<[f32; 4]> = read_buffer(ctx, &self.means)?;
        let dropped = self.non_finite(ctx)?;
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
    pub fn non_finite(&self, ctx: &GpuContext) -> Result<Vec<(u32, NonFiniteCause)>> {
        let words: Vec<u32> = read_buffer(ctx, &self.non_finite)?;
        Ok(words.iter().map(|w| (w & 0xff_ffff, NonFiniteCause::from_code(w >> 24))).collect())
    }
}
