//! Timing GPU work: timestamp queries where the adapter has them, else the
//! wall-clock time from submission to completion.

use super::{GpuContext, read_buffer};
use anyhow::Result;
use std::time::{Duration, Instant};

pub struct GpuTimer {
    queries: Option<(wgpu::QuerySet, wgpu::Buffer)>,
}

impl GpuTimer {
    pub fn new(ctx: &GpuContext) -> Self {
        let queries = ctx.timestamps.then(|| {
            let set = ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("timer"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            });
            let resolve = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timer resolve"),
                size: 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            (set, resolve)
        });
        Self { queries }
    }

    /// "GPU timestamps" or "wall clock", for reports.
    pub fn method(&self) -> &'static str {
        if self.queries.is_some() { "GPU timestamps" } else { "wall clock (no timestamp queries)" }
    }

    /// Runs the compute pass that `record` encodes (with the timestamp writes it
    /// is given) and returns how long the GPU took.
    pub fn time(
        &self,
        ctx: &GpuContext,
        record: impl FnOnce(&mut wgpu::CommandEncoder, Option<wgpu::ComputePassTimestampWrites>),
    ) -> Result<Duration> {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let writes = self.queries.as_ref().map(|(set, _)| wgpu::ComputePassTimestampWrites {
            query_set: set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        });
        record(&mut encoder, writes);
        if let Some((set, resolve)) = &self.queries {
            encoder.resolve_query_set(set, 0..2, resolve, 0);
        }
        let start = Instant::now();
        ctx.queue.submit([encoder.finish()]);
        ctx.wait()?;
        let wall = start.elapsed();
        match &self.queries {
            Some((_, resolve)) => {
                let ticks: Vec<u64> = read_buffer(ctx, resolve)?;
                let ns = ticks[1].saturating_sub(ticks[0]) as f64 * ctx.queue.get_timestamp_period() as f64;
                Ok(Duration::from_nanos(ns as u64))
            }
            None => Ok(wall),
        }
    }
}

/// The median of timings (zero for none).
pub fn median(mut times: Vec<Duration>) -> Duration {
    times.sort();
    times.get(times.len() / 2).copied().unwrap_or_default()
}

/// A duration in milliseconds, for reports.
pub fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}
