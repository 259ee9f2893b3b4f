//! The trace-only program: rays in, closest hits out. Used to check traversal
//! against a CPU reference and to measure rays/s.

use super::Session;
use crate::gpu::shader::Program;
use crate::gpu::{GpuContext, GpuTimer, Pipelines, SceneBuffers, read_buffer};
use crate::layout::{GpuFrame, GpuTraceHit, GpuTraceRay};
use anyhow::Result;
use std::rc::Rc;
use std::time::{Duration, Instant};
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

impl Session<'_> {
    fn trace_pipelines(&mut self) -> Result<Rc<Pipelines>> {
        let features = self.features();
        let ctx = self.ctx();
        self.pipelines_mut().get(ctx, Program::Trace, features)
    }

    /// Buffers of `rays` and their hits for [`Self::trace_pass`].
    pub fn trace_buffers(&self, rays: &[GpuTraceRay]) -> TraceBuffers {
        TraceBuffers::new(self.ctx(), &self.pipeline_cache().trace_layout, rays)
    }

    /// Runs one entry point of the trace program over `io` with the frame constants of
    /// the current request (its random numbers drawn from `sample_base`), waits for it
    /// and returns how long it took (on the GPU with a timer that has timestamps).
    pub fn trace_pass(
        &mut self,
        io: &TraceBuffers,
        entry: &str,
        sample_base: u32,
        timer: Option<&GpuTimer>,
    ) -> Result<Duration> {
        let pipelines = self.trace_pipelines()?;
        let ctx = self.ctx();
        self.buffers().write_frame(ctx, &GpuFrame { sample_base, ..self.frame() });
        let buffers = self.buffers();
        match timer {
            Some(timer) => timer.time(ctx, |e, w| io.encode(e, &pipelines, buffers, entry, w)),
            None => {
                let start = Instant::now();
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                io.encode(&mut encoder, &pipelines, buffers, entry, None);
                ctx.queue.submit([encoder.finish()]);
                ctx.wait()?;
                Ok(start.elapsed())
            }
        }
    }

    /// Closest hits of `rays` (directions of unit length), traced on the GPU.
    pub fn trace(&mut self, rays: &[GpuTraceRay]) -> Result<Vec<GpuTraceHit>> {
        let io = self.trace_buffers(rays);
        self.trace_pass(&io, "trace", 0, None)?;
        read_buffer(self.ctx(), &io.hits)
    }

    /// Traces `rays`, spawns from each hit a ray as a path would (on the side
    /// the ray came from when `through` is false, else through the surface),
    /// and traces those: (first hits, spawned rays, their hits).
    pub fn trace_and_spawn(
        &mut self,
        rays: &[GpuTraceRay],
        through: bool,
    ) -> Result<(Vec<GpuTraceHit>, Vec<GpuTraceRay>, Vec<GpuTraceHit>)> {
        let io = self.trace_buffers(rays);
        self.trace_pass(&io, "trace", 0, None)?;
        let first = read_buffer(self.ctx(), &io.hits)?;
        self.trace_pass(&io, if through { "generate_through_rays" } else { "generate_diffuse_rays" }, 0, None)?;
        self.trace_pass(&io, "trace", 0, None)?;
        Ok((first, read_buffer(self.ctx(), &io.rays)?, read_buffer(self.ctx(), &io.hits)?))
    }
}
