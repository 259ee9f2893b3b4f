//! Timed renders: the integrator's dispatches timed one by one (GPU timestamps
//! where the adapter has them) and summed, so that a render's time is the GPU's
//! work alone, without shader compilation, uploads or read-backs.

use anyhow::Result;
use rt::gpu::GpuTimer;
use rt::render::{Image, RenderRequest, Session};
use std::time::Duration;

/// A render, the summed time of its dispatches, and how many samples it dropped as non-finite.
pub struct TimedRender {
    pub image: Image,
    pub time: Duration,
    pub dropped: u64,
}

/// Renders `request`. Dispatch sizes follow `request.samples_per_dispatch`, or adapt as in `rt render`.
pub fn render_timed(session: &mut Session, request: &RenderRequest, timer: &GpuTimer) -> Result<TimedRender> {
    let (image, report) = session.render(request, Some(timer))?;
    Ok(TimedRender { image, time: report.dispatch_time, dropped: report.dropped.non_finite_samples })
}

/// Compiles the request's pipeline and runs one sample, so that the first timed
/// render pays for neither.
pub fn warm_up(session: &mut Session, request: &RenderRequest, timer: &GpuTimer) -> Result<()> {
    let one = RenderRequest { spp: 1, samples_per_dispatch: Some(1), ..request.clone() };
    render_timed(session, &one, timer).map(|_| ())
}
