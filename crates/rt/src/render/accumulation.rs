//! The running means per pixel that dispatches of samples add to, and what they
//! dropped as non-finite.

use super::Image;
use super::dropped::NonFiniteCause;
use super::request::{MAX_LANES, MAX_SAMPLES_PER_DISPATCH};
use crate::gpu::{GpuContext, Pipelines, Readback, SceneBuffers};
use crate::layout::GpuFrame;
use anyhow::{Result, bail};

/// Bytes per pixel of the means (RGB and the luminance's sum of squared deviations).
const MEAN_BYTES: u64 = 16;
/// Bytes of one sample in the lanes' scratch (radiance, and the event of a non-finite one).
const SAMPLE_BYTES: u64 = 16;
/// Bytes per pixel of the AOVs' means (albedo and depth, normal and hit count, position
/// and coverage, emission, diffuse colour), and of one sample's AOVs in the lanes' scratch.
const AOV_BYTES: u64 = 16 * super::aovs::MEANS_PER_PIXEL as u64;
/// The lanes' scratch at most: it holds pixels × samples per dispatch (a 128×128 image
/// takes its 1024 samples per dispatch in 256 MiB).
const LANE_SCRATCH_BYTES: u64 = 256 << 20;
/// Invocations that keep a large GPU busy (an H200 holds 132 × 2048 resident threads):
/// images with fewer pixels spread each pixel's samples over lanes. Since a path that
/// ends starts the pixel's next sample at once (path regeneration), an invocation with
/// several samples keeps its lane of the subgroup busy, and fewer, longer invocations
/// win (docs/measured-choices.md).
const GPU_INVOCATIONS: u64 = 1 << 18;
/// Samples one invocation takes in a dispatch at most on a CPU. lavapipe stops an
/// invocation's loops after 65,535 turns together (Mesa's `LP_MAX_TGSI_LOOP_ITERATIONS`)
/// and silently drops the rest: a Cornell-box pixel loses what comes after about 370
/// samples. A CPU gains nothing from longer dispatches, so it keeps a wide margin.
const CPU_SAMPLES_PER_INVOCATION: u32 = 64;

/// The outputs beside the means that a render asks the accumulation for.
#[derive(Clone, Copy, Debug, Default)]
pub struct Outputs {
    pub aovs: bool,
    pub adaptive: bool,
    pub exact_sums: bool,
}

pub struct Accumulation {
    pub width: u32,
    pub height: u32,
    pub samples: u32,
    means: wgpu::Buffer,
    non_finite: wgpu::Buffer,
    /// Samples spread over lanes wait here for `reduce_lanes` (a token buffer when
    /// the image is large enough to keep the GPU busy on its own).
    lane_samples: wgpu::Buffer,
    /// Per pixel, the chunks of samples its lanes claimed (`next_sample` in
    /// `shaders/sample_lanes.wgsl`): zeroed before each dispatch over lanes.
    lane_chunks: wgpu::Buffer,
    /// The AOVs' running means (a token buffer until a render asks for them).
    aovs: wgpu::Buffer,
    /// Samples taken per pixel under adaptive sampling (a token buffer until then).
    pixel_samples: wgpu::Buffer,
    /// The samples' exact sums (`shaders/exact_sums.wgsl`; a token buffer until a render asks).
    exact: wgpu::Buffer,
    /// Whether the samples' exact sums are kept: asked for, and within one GPU binding.
    exact_kept: bool,
    bind_group: wgpu::BindGroup,
    /// Lanes per pixel that keep the GPU busy; 1 on a CPU adapter.
    lanes_wanted: u32,
    /// The device is a CPU (see `CPU_SAMPLES_PER_INVOCATION`).
    cpu: bool,
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

/// Bytes of the exact sums of a `width`×`height` image, with or without its AOVs'.
fn exact_sums_bytes(width: u32, height: u32, aovs: bool) -> u64 {
    width as u64 * height as u64 * 4 * super::exact::words_per_pixel(aovs) as u64
}

/// Refuses exact sums (what `--sample-range` needs) that do not fit one GPU binding,
/// naming the limit. Without them `rt render` makes its image from the running means.
pub fn check_exact_sums(ctx: &GpuContext, width: u32, height: u32, aovs: bool) -> Result<()> {
    // They are added up from the lanes' scratch, which must hold one sample at least.
    let per_sample = if aovs { SAMPLE_BYTES + AOV_BYTES } else { SAMPLE_BYTES };
    let bytes = exact_sums_bytes(width, height, aovs).max(width as u64 * height as u64 * per_sample);
    let max = ctx.device.limits().max_storage_buffer_binding_size;
    if bytes > max {
        let without = if aovs { ", or without AOVs" } else { "" };
        bail!(
            "a {width}x{height} image's exact sums need {} MiB; this GPU ({}) binds at most {} MiB per buffer: \
             split a smaller image{without}",
            bytes.div_ceil(1 << 20),
            ctx.adapter_info.name,
            max >> 20
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
        // A CPU runs one invocation per core at a time: lanes would only add the reduction.
        let cpu = ctx.adapter_info.device_type == wgpu::DeviceType::Cpu;
        let lanes_wanted = if cpu { 1 } else { GPU_INVOCATIONS.div_ceil(pixels).min(MAX_LANES as u64) as u32 };
        let lane_samples = buffer("lane samples", SAMPLE_BYTES);
        let lane_chunks = buffer("lane chunks", 16);
        let aovs = buffer("aovs", AOV_BYTES);
        let pixel_samples = buffer("pixel samples", 16);
        let exact = buffer("exact sums", 16);
        let buffers = [&means, &non_finite, &lane_samples, &aovs, &pixel_samples, &lane_chunks, &exact];
        let bind_group = crate::gpu::bind_group(ctx, "accumulation", layout, &buffers);
        let mut acc = Self {
            width,
            height,
            samples: 0,
            means,
            non_finite,
            lane_samples,
            lane_chunks,
            aovs,
            pixel_samples,
            exact,
            exact_kept: false,
            bind_group,
            lanes_wanted,
            cpu,
        };
        if lanes_wanted > 1 {
            acc.prepare_lanes(ctx, layout, false);
        }
        Ok(acc)
    }

    /// Makes room for samples spread over lanes (one sample per pixel at least, with its
    /// AOVs if `aovs`), if there is none yet.
    pub fn prepare_lanes(&mut self, ctx: &GpuContext, layout: &wgpu::BindGroupLayout, aovs: bool) {
        let pixels = self.width as u64 * self.height as u64;
        let one_sample = pixels * if aovs { SAMPLE_BYTES + AOV_BYTES } else { SAMPLE_BYTES };
        if self.lane_samples.size() >= one_sample {
            return;
        }
        let max = ctx.device.limits().max_storage_buffer_binding_size;
        let size = (pixels * SAMPLE_BYTES * MAX_SAMPLES_PER_DISPATCH as u64).max(one_sample);
        let size = size.min(LANE_SCRATCH_BYTES.max(one_sample)).min(max);
        self.lane_samples = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("lane samples"),
            size,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        self.lane_chunks = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("lane chunks"),
            size: pixels * 4,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.rebind(ctx, layout);
    }

    fn rebind(&mut self, ctx: &GpuContext, layout: &wgpu::BindGroupLayout) {
        let buffers = [
            &self.means,
            &self.non_finite,
            &self.lane_samples,
            &self.aovs,
            &self.pixel_samples,
            &self.lane_chunks,
            &self.exact,
        ];
        self.bind_group = crate::gpu::bind_group(ctx, "accumulation", layout, &buffers);
    }

    /// Makes room for the AOVs, the per-pixel sample counts of adaptive sampling and the
    /// exact sums, as asked and if there is none yet. Their contents start at zero: call
    /// before the first sample (they are kept from then on, like the means).
    pub fn prepare_outputs(&mut self, ctx: &GpuContext, layout: &wgpu::BindGroupLayout, outputs: Outputs) {
        let pixels = self.width as u64 * self.height as u64;
        let mut changed = false;
        let mut grow = |buffer: &mut wgpu::Buffer, label, size| {
            if buffer.size() < size {
                *buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                changed = true;
            }
        };
        if outputs.aovs {
            grow(&mut self.aovs, "aovs", pixels * AOV_BYTES);
        }
        if outputs.adaptive {
            grow(&mut self.pixel_samples, "pixel samples", pixels * 8);
        }
        self.exact_kept = outputs.exact_sums && check_exact_sums(ctx, self.width, self.height, outputs.aovs).is_ok();
        if self.exact_kept {
            grow(&mut self.exact, "exact sums", exact_sums_bytes(self.width, self.height, outputs.aovs));
        }
        if changed {
            self.rebind(ctx, layout);
        }
        if self.exact_kept {
            self.prepare_lanes(ctx, layout, outputs.aovs);
        }
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
        encoder.clear_buffer(&self.aovs, 0, None);
        encoder.clear_buffer(&self.pixel_samples, 0, None);
        encoder.clear_buffer(&self.exact, 0, None);
        self.samples = 0;
    }

    /// Lanes per pixel for a dispatch of `samples` samples per pixel: as many as keep the
    /// GPU busy, or `forced`; 1 runs the plain one-invocation-per-pixel kernel (unless
    /// the exact sums are kept, see [`Self::through_scratch`]).
    pub fn lanes(&self, samples: u32, forced: Option<u32>) -> u32 {
        forced.unwrap_or(self.lanes_wanted).clamp(1, samples.max(1))
    }

    /// Whether a dispatch over `lanes` lanes takes its samples through the lanes' scratch
    /// and `reduce_lanes`: with more than one lane, and always while the exact sums are
    /// kept, whose integer adds `reduce_lanes` alone makes: in the loop that traces paths
    /// they stall every lane of a subgroup whenever one of its paths ends, and doubled the
    /// time per sample (docs/splitting-renders.md).
    fn through_scratch(&self, lanes: u32) -> bool {
        lanes > 1 || self.exact_kept
    }

    /// Samples per pixel one dispatch with `lanes` lanes can take: as many as the lanes'
    /// scratch holds (with `aovs`, each sample's AOVs wait there beside its radiance),
    /// and on a CPU as many as its loop limit safely allows.
    pub fn max_samples(&self, lanes: u32, aovs: bool) -> u32 {
        let device = match self.cpu {
            true => CPU_SAMPLES_PER_INVOCATION.saturating_mul(lanes.max(1)).min(MAX_SAMPLES_PER_DISPATCH),
            false => MAX_SAMPLES_PER_DISPATCH,
        };
        if !self.through_scratch(lanes) {
            return device;
        }
        let bytes = if aovs { SAMPLE_BYTES + AOV_BYTES } else { SAMPLE_BYTES };
        let per_sample = self.width as u64 * self.height as u64 * bytes;
        (self.lane_samples.size() / per_sample).min(device as u64) as u32
    }

    /// Records one dispatch of `frame.samples_per_dispatch` samples per pixel over `lanes`
    /// lanes (and counts them as taken).
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        pipelines: &Pipelines,
        scene: &SceneBuffers,
        frame: &GpuFrame,
        lanes: u32,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites>,
    ) {
        let n = frame.samples_per_dispatch;
        let frame = GpuFrame { sample_base: self.samples, ..*frame };
        scene.write_frame(ctx, &frame);
        let scratch = self.through_scratch(lanes);
        if scratch {
            encoder.clear_buffer(&self.lane_chunks, 0, None);
        }
        let mut pass =
            encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("render"), timestamp_writes });
        pass.set_bind_group(0, &scene.bind_group, &[]);
        pass.set_bind_group(1, &self.bind_group, &[]);
        if let Some(sky) = &scene.sky_bind_group {
            pass.set_bind_group(2, sky, &[]);
        }
        let (x, y) = (self.width.div_ceil(8), self.height.div_ceil(8));
        // Adaptive sampling marks the pixels that stop before any sample of the dispatch.
        if let Some(mask) = pipelines.entries.get("adaptive_mask") {
            pass.set_pipeline(mask);
            pass.dispatch_workgroups(x, y, 1);
        }
        if scratch {
            pass.set_pipeline(pipelines.entry("render_lanes"));
            pass.dispatch_workgroups(x, y, lanes);
            pass.set_pipeline(pipelines.entry("reduce_lanes"));
            pass.dispatch_workgroups(x, y, 1);
        } else {
            pass.set_pipeline(pipelines.entry("render"));
            pass.dispatch_workgroups(x, y, 1);
        }
        self.samples += n;
    }

    /// The mean radiance per pixel and the standard error of each pixel's mean luminance.
    /// `adaptive`: the samples were taken with adaptive sampling (each pixel counts its own).
    pub fn image(&self, ctx: &GpuContext, readback: &Readback, adaptive: bool) -> Result<Image> {
        let means: Vec<[f32; 4]> = readback.read(ctx, &self.means)?;
        let dropped = self.non_finite(ctx, readback)?;
        let taken = self.taken(ctx, readback, adaptive)?;
        let mut pixels = Vec::with_capacity(means.len());
        let mut std_error = Vec::with_capacity(means.len());
        let mut sample_counts = Vec::with_capacity(means.len());
        for ((m, (bad, _)), taken) in means.iter().zip(&dropped).zip(&taken) {
            // Dropped samples are not part of the mean: it is over the finite ones.
            let finite = taken.saturating_sub(*bad);
            let n = finite.max(1) as f64;
            let variance = m[3].max(0.0) as f64 / (n - 1.0).max(1.0);
            pixels.push([m[0], m[1], m[2]]);
            std_error.push((variance / n).sqrt() as f32);
            sample_counts.push(finite);
        }
        let (width, height, samples) = (self.width, self.height, self.samples);
        Ok(Image { width, height, samples, pixels, std_error, sample_counts, alpha: None })
    }

    /// Samples each pixel took, finite or not; `adaptive`: counted per pixel.
    pub fn taken(&self, ctx: &GpuContext, readback: &Readback, adaptive: bool) -> Result<Vec<u32>> {
        let pixels = self.width as usize * self.height as usize;
        Ok(match adaptive {
            // Per pixel: samples taken, and whether it stopped.
            true => readback.read::<[u32; 2]>(ctx, &self.pixel_samples)?.iter().take(pixels).map(|p| p[0]).collect(),
            false => vec![self.samples; pixels],
        })
    }

    /// Whether the samples' exact sums are kept (asked for, and within one GPU binding).
    pub fn keeps_exact_sums(&self) -> bool {
        self.exact_kept
    }

    /// The exact sums' words (see [`super::exact`]); call only after
    /// [`Self::prepare_outputs`] asked for them.
    pub fn exact_words(&self, ctx: &GpuContext, readback: &Readback) -> Result<Vec<u32>> {
        readback.read(ctx, &self.exact)
    }

    /// The AOVs' means per pixel, five vec4 each (see `shaders/aovs.wgsl`); call only
    /// after [`Self::prepare_outputs`] asked for them.
    pub fn aov_means(&self, ctx: &GpuContext, readback: &Readback) -> Result<Vec<[f32; 4]>> {
        readback.read(ctx, &self.aovs)
    }

    /// Dropped non-finite samples: per pixel, (count, the event that produced the first).
    pub fn non_finite(&self, ctx: &GpuContext, readback: &Readback) -> Result<Vec<(u32, NonFiniteCause)>> {
        let words: Vec<u32> = readback.read(ctx, &self.non_finite)?;
        Ok(words.iter().map(|w| (w & 0xff_ffff, NonFiniteCause::from_code(w >> 24))).collect())
    }
}
