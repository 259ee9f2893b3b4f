//! Timed renders: the integrator's dispatches timed one by one (GPU timestamps
//! where the adapter has them) and summed, so that a render's time is the GPU's
//! work alone, without shader compilation, uploads or read-backs.

use crate::gpu::GpuTimer;
use crate::gpu::shader::Program;
use crate::render::{Accumulation, Image, RenderRequest, Renderer};
use anyhow::Result;
use std::time::Duration;

/// A render, the summed time of its dispatches, and how many samples it dropped as non-finite.
pub struct TimedRender {
    pub image: Image,
    pub time: Duration,
    pub dropped: u64,
}

/// Renders `request`. Dispatch sizes follow `request.samples_per_dispatch`, or adapt as in `rt render`.
pub fn render_timed(renderer: &mut Renderer, request: &RenderRequest, timer: &GpuTimer) -> Result<TimedRender> {
    let ctx = renderer.ctx;
    let features = request.features.unwrap_or(renderer.geometry.features);
    let pipelines = renderer.pipelines.get(ctx, Program::Integrator, features)?;
    let frame = renderer.frame(request);
    let mut acc = Accumulation::new(ctx, &renderer.pipelines.accumulation_layout, request.width, request.height);
    if let Some(n) = request.samples_per_dispatch {
        acc.fix_samples_per_dispatch(n);
    }
    let mut total = Duration::ZERO;
    while acc.samples < request.spp {
        let (_, took) =
            acc.dispatch_timed(ctx, &pipelines, &renderer.buffers, &frame, request.spp - acc.samples, Some(timer))?;
        total += took;
    }
    let dropped = acc.non_finite(ctx)?.iter().map(|(n, _)| *n as u64).sum();
    Ok(TimedRender { image: acc.image(ctx)?, time: total, dropped })
}

/// Compiles the request's pipeline and runs one sample, so that the first timed
/// render pays for neither.
pub fn warm_up(renderer: &mut Renderer, request: &RenderRequest, timer: &GpuTimer) -> Result<()> {
    let one = RenderRequest { spp: 1, samples_per_dispatch: Some(1), ..request.clone() };
    render_timed(renderer, &one, timer).map(|_| ())
}

pub fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v.get(v.len() / 2).copied().unwrap_or_default()
}

pub fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}
