//! The atmosphere's tables on the GPU: built by compute passes
//! (`shaders/atmosphere_tables.wgsl`) when the atmosphere's parameters change,
//! never per frame. They do not depend on the sun, which may move freely.

use super::model::{TableLayout, gpu_atmosphere};
use crate::gpu::shader::atmosphere_tables_source;
use crate::gpu::{GpuContext, GpuTimer, compute_pipelines, sky_bind_group_layout};
use crate::scene::Atmosphere;
use anyhow::{Result, anyhow};
use std::time::Duration;
use wgpu::util::DeviceExt;

/// The transmittance and closure passes' workgroups are 8×8.
const TILE: u32 = 8;

pub struct AtmosphereTables {
    /// What the tables were built for.
    params: Atmosphere,
    pub uniform: wgpu::Buffer,
    /// Every table, as vec4 entries (see [`TableLayout`]).
    pub tables: wgpu::Buffer,
    /// Group 2 of the integrator.
    pub bind_group: wgpu::BindGroup,
    /// GPU time of the last build, all passes.
    pub build_time: Duration,
    passes: Passes,
}

/// The table program's pipelines.
struct Passes {
    layout: wgpu::BindGroupLayout,
    transmittance: wgpu::ComputePipeline,
    second_order: wgpu::ComputePipeline,
    third_order: wgpu::ComputePipeline,
    fourth_order: wgpu::ComputePipeline,
    closure: wgpu::ComputePipeline,
}

impl Passes {
    fn new(ctx: &GpuContext) -> Result<Self> {
        let layout = sky_bind_group_layout(&ctx.device, true);
        let names =
            ["build_transmittance", "build_second_order", "build_third_order", "build_fourth_order", "build_closure"];
        let mut built =
            compute_pipelines(ctx, "the atmosphere's table passes", atmosphere_tables_source(), &[&layout], &names)?;
        let mut take = |name| built.remove(name).ok_or_else(|| anyhow!("no table pass {name}"));
        Ok(Self {
            transmittance: take("build_transmittance")?,
            second_order: take("build_second_order")?,
            third_order: take("build_third_order")?,
            fourth_order: take("build_fourth_order")?,
            closure: take("build_closure")?,
            layout,
        })
    }
}

impl AtmosphereTables {
    /// Uploads the parameters and builds the tables; `render_layout` is the
    /// integrator's group 2 layout.
    pub fn new(ctx: &GpuContext, render_layout: &wgpu::BindGroupLayout, params: &Atmosphere) -> Result<Self> {
        let passes = Passes::new(ctx)?;
        let (uniform, tables, bind_group) = Self::buffers(ctx, render_layout, params)?;
        let mut built =
            Self { params: params.clone(), uniform, tables, bind_group, build_time: Duration::ZERO, passes };
        built.build(ctx)?;
        Ok(built)
    }

    /// Takes new parameters: the tables are rebuilt only if they depend on what
    /// changed (not the march's steps, the ground's altitude or the switch of
    /// multiple scattering). Returns whether they were.
    pub fn update(
        &mut self,
        ctx: &GpuContext,
        render_layout: &wgpu::BindGroupLayout,
        params: &Atmosphere,
    ) -> Result<bool> {
        let march_only =
            |a: &Atmosphere| Atmosphere { steps: 0, ground_altitude_m: 0.0, multiple_scattering: false, ..a.clone() };
        if march_only(params) == march_only(&self.params) {
            ctx.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&gpu_atmosphere(params)));
            self.params = params.clone();
            return Ok(false);
        }
        (self.uniform, self.tables, self.bind_group) = Self::buffers(ctx, render_layout, params)?;
        self.params = params.clone();
        self.build(ctx)?;
        Ok(true)
    }

    pub fn layout(&self) -> TableLayout {
        TableLayout::of(&self.params)
    }

    fn buffers(
        ctx: &GpuContext,
        render_layout: &wgpu::BindGroupLayout,
        params: &Atmosphere,
    ) -> Result<(wgpu::Buffer, wgpu::Buffer, wgpu::BindGroup)> {
        let bytes = TableLayout::of(params).entries as u64 * 16;
        let max = ctx.device.limits().max_storage_buffer_binding_size;
        crate::gpu::check_binding("the atmosphere's tables", bytes, max)?;
        let uniform = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("atmosphere"),
            contents: bytemuck::bytes_of(&gpu_atmosphere(params)),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let tables = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("atmosphere tables"),
            size: bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let bind_group = bind_group(ctx, render_layout, &uniform, &tables);
        Ok((uniform, tables, bind_group))
    }

    /// Runs the passes in order, each after the previous one has finished.
    fn build(&mut self, ctx: &GpuContext) -> Result<()> {
        let layout = self.layout();
        let group = bind_group(ctx, &self.passes.layout, &self.uniform, &self.tables);
        let [tw, th] = layout.transmittance;
        let [sw, sh] = layout.scattering;
        let passes = [
            (&self.passes.transmittance, [tw.div_ceil(TILE), th.div_ceil(TILE)]),
            (&self.passes.second_order, [sw, sh]),
            (&self.passes.third_order, [sw, sh]),
            (&self.passes.fourth_order, [sw, sh]),
            (&self.passes.closure, [sw.div_ceil(TILE), sh.div_ceil(TILE)]),
        ];
        let timer = GpuTimer::new(ctx);
        let mut total = Duration::ZERO;
        for (pipeline, [x, y]) in passes {
            let took = timer.time(ctx, |encoder, timestamp_writes| {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("atmosphere tables"),
                    timestamp_writes,
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &group, &[]);
                pass.dispatch_workgroups(x, y, 1);
            })?;
            total += took;
        }
        self.build_time = total;
        log::info!("atmosphere tables ({} entries) built in {:.2?}", layout.entries, total);
        Ok(())
    }
}

fn bind_group(
    ctx: &GpuContext,
    layout: &wgpu::BindGroupLayout,
    uniform: &wgpu::Buffer,
    tables: &wgpu::Buffer,
) -> wgpu::BindGroup {
    ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("atmosphere"),
        layout,
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: tables.as_entire_binding() },
        ],
    })
}
