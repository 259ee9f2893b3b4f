//! The trace-only program: rays in, closest hits out. Used to check traversal
//! against a CPU reference and to measure rays/s.

use super::Renderer;
use crate::gpu::layout::{GpuTraceHit, GpuTraceRay};
use crate::gpu::shader::Program;
use crate::gpu::{GpuContext, Pipelines, SceneBuffers, read_buffer};
use anyhow::Result;
use std::rc::Rc;
use wgpu::util::DeviceExt;

pub struct TraceBuffers {
    pub count: u32,
    pub rays: wgpu::Buffer,
    pub hits: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

impl TraceBuffers {
    pub fn new(ctx: &GpuContext, layout: &wgpu::BindGroupLayout, rays: &[GpuTraceRay]) -> Self {
        let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST;
        let rays_buffer = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("trace rays"),
            contents: bytemuck::cast_slice(rays),
            usage,
        });
        let hits = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("trace hits"),
            size: (rays.len() * size_of::<GpuTraceHit>()) as u64,
            usage,
            mapped_at_creation: false,
        });
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("trace"),
            layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: rays_buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: hits.as_entire_binding() },
            ],
        });
        Self { count: rays.len() as u32, rays: rays_buffer, hits, bind_group }
    }

    /// Records one pass of an entry point of the trace program over all rays.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pipelines: &Pipelines,
        scene: &SceneBuffers,
        entry: &str,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites>,
    ) {
        let mut pass =
            encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(entry), timestamp_writes });
        pass.set_pipeline(pipelines.entry(entry));
        pass.set_bind_group(0, &scene.bind_group, &[]);
        pass.set_bind_group(1, &self.bind_group, &[]);
        // At most 65535 workgroups per dimension: larger launches spill into y (see `ray_index`).
        let groups = self.count.div_ceil(64);
        pass.dispatch_workgroups(groups.min(65535), groups.div_ceil(65535), 1);
    }
}

impl Renderer<'_> {
    pub fn trace_pipelines(&mut self) -> Result<Rc<Pipelines>> {
        self.pipelines.get(self.ctx, Program::Trace, self.geometry.features)
    }

    /// Closest hits of `rays` (directions of unit length), traced on the GPU.
    pub fn trace(&mut self, rays: &[GpuTraceRay]) -> Result<Vec<GpuTraceHit>> {
        let pipelines = self.trace_pipelines()?;
        let frame = self.frame(&super::RenderRequest::from_scene(&self.scene));
        self.buffers.write_frame(self.ctx, &frame);
        let io = TraceBuffers::new(self.ctx, &self.pipelines.trace_layout, rays);
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        io.encode(&mut encoder, &pipelines, &self.buffers, "trace", None);
        self.ctx.queue.submit([encoder.finish()]);
        read_buffer(self.ctx, &io.hits)
    }

    /// Traces `rays`, spawns from each hit a ray as a path would (on the side
    /// the ray came from when `through` is false, else through the surface),
    /// and traces those: (first hits, spawned rays, their hits).
    pub fn trace_and_spawn(
        &mut self,
        rays: &[GpuTraceRay],
        through: bool,
    ) -> Result<(Vec<GpuTraceHit>, Vec<GpuTraceRay>, Vec<GpuTraceHit>)> {
        let pipelines = self.trace_pipelines()?;
        let frame = self.frame(&super::RenderRequest::from_scene(&self.scene));
        self.buffers.write_frame(self.ctx, &frame);
        let io = TraceBuffers::new(self.ctx, &self.pipelines.trace_layout, rays);
        let run = |entry: &str| {
            let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
            io.encode(&mut encoder, &pipelines, &self.buffers, entry, None);
            self.ctx.queue.submit([encoder.finish()]);
        };
        run("trace");
        let first = read_buffer(self.ctx, &io.hits)?;
        run(if through { "generate_through_rays" } else { "generate_diffuse_rays" });
        run("trace");
        Ok((first, read_buffer(self.ctx, &io.rays)?, read_buffer(self.ctx, &io.hits)?))
    }
}
