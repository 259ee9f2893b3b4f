//! The display pass (`shaders/display.wgsl`): the accumulation's running mean,
//! tone-mapped on the GPU, into the window's surface or into a texture that is read
//! back as a screenshot, with the same pipeline, so a screenshot is what the window shows.

use anyhow::{Result, anyhow};
use bytemuck::{Pod, Zeroable};
use rt::gpu::{Binding, GpuContext, bind_group, sequential_layout, validated};
use rt::render::Accumulation;
use std::path::Path;

const BUILT_IN: &str = include_str!("../../rt/shaders/display.wgsl");

/// The screenshot's format: 8-bit, encoded by the shader like a PNG.
const SCREENSHOT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Mirrors `Display` in `shaders/display.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
struct DisplayUniform {
    width: u32,
    height: u32,
    samples: u32,
    exposure_scale: f32,
    encode_srgb: u32,
    error: u32,
    _pad: [u32; 2],
}

pub struct Display {
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    /// For the surface's format, and for screenshots.
    to_surface: wgpu::RenderPipeline,
    to_screenshot: wgpu::RenderPipeline,
    surface_format: wgpu::TextureFormat,
}

impl Display {
    /// With `shader_dir`, `display.wgsl` is read from there (`--dev`); a shader that does
    /// not build is an error naming it.
    pub fn new(ctx: &GpuContext, surface_format: wgpu::TextureFormat, shader_dir: Option<&Path>) -> Result<Self> {
        let device = &ctx.device;
        let bindings = [Binding::Uniform, Binding::ReadOnly];
        let layout = sequential_layout(device, "display", wgpu::ShaderStages::FRAGMENT, &bindings);
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("display"),
            size: size_of::<DisplayUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let (to_surface, to_screenshot) = pipelines(ctx, &layout, surface_format, shader_dir)?;
        Ok(Self { layout, uniform, to_surface, to_screenshot, surface_format })
    }

    /// Builds the pipelines again from `shader_dir`; on an error the old ones stay.
    pub fn reload_shader(&mut self, ctx: &GpuContext, shader_dir: &Path) -> Result<()> {
        (self.to_surface, self.to_screenshot) = pipelines(ctx, &self.layout, self.surface_format, Some(shader_dir))?;
        Ok(())
    }

    /// Records drawing `acc` into `target` (a view of the surface's texture).
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        acc: &Accumulation,
        exposure_ev: f32,
        error: bool,
    ) {
        self.encode_from(ctx, encoder, target, acc, acc.means(), exposure_ev, error);
    }

    /// Records drawing `means` (of `acc`'s size, in its layout) into `target`: the
    /// denoised image instead of the running mean.
    #[allow(clippy::too_many_arguments)]
    pub fn encode_from(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        acc: &Accumulation,
        means: &wgpu::Buffer,
        exposure_ev: f32,
        error: bool,
    ) {
        self.write_uniform(ctx, acc, exposure_ev, error, !self.surface_format.is_srgb());
        self.draw(ctx, encoder, target, means, &self.to_surface);
    }

    /// The display of `acc` as 8-bit sRGB pixels, rows from the top, without the error frame.
    /// `means`: `acc`'s own, or an image of its size in its layout (the denoised one).
    pub fn screenshot(
        &self,
        ctx: &GpuContext,
        acc: &Accumulation,
        means: &wgpu::Buffer,
        exposure_ev: f32,
    ) -> Result<Vec<[u8; 3]>> {
        let (width, height) = (acc.width, acc.height);
        let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("screenshot"),
            size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: SCREENSHOT_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        // Rows of a texture copy are padded to 256 bytes.
        let row_bytes = (width * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let readback = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("screenshot readback"),
            size: row_bytes as u64 * height as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.write_uniform(ctx, acc, exposure_ev, false, true);
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let view = texture.create_view(&Default::default());
        self.draw(ctx, &mut encoder, &view, means, &self.to_screenshot);
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &readback,
                layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row_bytes), rows_per_image: None },
            },
            wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        );
        ctx.queue.submit([encoder.finish()]);
        let slice = readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        ctx.wait()?;
        rx.recv()?.map_err(|e| anyhow!("could not read the screenshot back: {e}"))?;
        let bytes = slice.get_mapped_range().map_err(|e| anyhow!("could not map the screenshot: {e}"))?;
        let mut pixels = Vec::with_capacity((width * height) as usize);
        for row in bytes.chunks(row_bytes as usize) {
            pixels.extend(row[..width as usize * 4].chunks(4).map(|p| [p[0], p[1], p[2]]));
        }
        Ok(pixels)
    }

    fn write_uniform(&self, ctx: &GpuContext, acc: &Accumulation, exposure_ev: f32, error: bool, encode_srgb: bool) {
        let uniform = DisplayUniform {
            width: acc.width,
            height: acc.height,
            samples: acc.samples,
            exposure_scale: exposure_ev.exp2(),
            encode_srgb: encode_srgb as u32,
            error: error as u32,
            _pad: [0; 2],
        };
        ctx.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
    }

    fn draw(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        means: &wgpu::Buffer,
        pipeline: &wgpu::RenderPipeline,
    ) {
        let bind_group = bind_group(ctx, "display", &self.layout, &[&self.uniform, means]);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("display"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::BLACK), store: wgpu::StoreOp::Store },
            })],
            ..Default::default()
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

fn pipelines(
    ctx: &GpuContext,
    layout: &wgpu::BindGroupLayout,
    surface_format: wgpu::TextureFormat,
    shader_dir: Option<&Path>,
) -> Result<(wgpu::RenderPipeline, wgpu::RenderPipeline)> {
    let source = match shader_dir {
        Some(dir) => {
            let path = dir.join(super::sources::DISPLAY_SHADER);
            rt::files::read_to_string(&path)?
        }
        None => BUILT_IN.to_owned(),
    };
    let device = &ctx.device;
    validated(ctx, "the display pipeline (shaders/display.wgsl)", || {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("display"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("display"),
            bind_group_layouts: &[Some(layout)],
            immediate_size: 0,
        });
        let pipeline = |format: wgpu::TextureFormat| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("display"),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vertex"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fragment"),
                    compilation_options: Default::default(),
                    targets: &[Some(format.into())],
                }),
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                multiview_mask: None,
                cache: None,
            })
        };
        (pipeline(surface_format), pipeline(SCREENSHOT_FORMAT))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rt::gpu::PipelineCache;
    use rt::render::tonemap::display_pixel;

    /// The display shader and `render::tonemap` agree to within rounding on the
    /// whole range: shadows, mid-tones, saturated colours and compressed highlights.
    #[test]
    fn display_shader_matches_the_png_tone_mapping() {
        let ctx = GpuContext::new(std::env::var("RT_ADAPTER").ok().as_deref()).expect("a Vulkan adapter");
        let (width, height, samples) = (64u32, 16u32, 3u32);
        let radiance: Vec<[f32; 3]> = (0..width * height)
            .map(|i| {
                let level = 1e-4 * 1e6f32.powf(i as f32 / (width * height) as f32);
                let tint = [[1.0, 1.0, 1.0], [1.0, 0.2, 0.05], [0.1, 0.9, 0.3], [0.02, 0.05, 1.0]][i as usize % 4];
                tint.map(|t| t * level)
            })
            .collect();
        let pipelines = PipelineCache::new(&ctx);
        let mut acc = Accumulation::new(&ctx, &pipelines.accumulation_layout, width, height).expect("accumulation");
        let means: Vec<[f32; 4]> = radiance.iter().map(|c| [c[0], c[1], c[2], 0.0]).collect();
        ctx.queue.write_buffer(acc.means(), 0, bytemuck::cast_slice(&means));
        acc.samples = samples;
        let display = Display::new(&ctx, wgpu::TextureFormat::Bgra8Unorm, None).expect("display pipelines");
        for exposure in [0.0, -2.0, 1.5] {
            let shown = display.screenshot(&ctx, &acc, acc.means(), exposure).expect("screenshot");
            for (i, (shown, linear)) in shown.iter().zip(&radiance).enumerate() {
                let expected = display_pixel(*linear, exposure);
                let worst = shown.iter().zip(expected).map(|(a, b)| (*a as i32 - b as i32).abs()).max();
                assert!(worst <= Some(1), "pixel {i} {linear:?} at {exposure} EV: {shown:?} vs {expected:?}");
            }
        }
    }
}
