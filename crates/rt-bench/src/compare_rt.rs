//! rt's side of `rt bench compare`: the same work Mitsuba is given, timed by both clocks
//! after the same warm-up, with the first two renders' images kept for the comparison
//! of the images.

use super::clocks::Timed;
use super::throughput::warm_up;
use anyhow::Result;
use indicatif::ProgressBar;
use rt::gpu::GpuTimer;
use rt::layout::GpuTraceRay;
use rt::render::{RenderRequest, Session};
use std::time::Duration;

/// rt's figures for one case, and its first two renders (seeds 1 and 2).
pub struct RtFigures {
    pub paths: Timed,
    pub camera_rays: Option<Timed>,
    pub diffuse_rays: Option<Timed>,
    pub renders: [Vec<[f32; 3]>; 2],
}

/// The device's time where the adapter has timestamp queries; none where `took` is the
/// wall clock's too.
fn device(ctx_has_timestamps: bool, took: Duration) -> Vec<f64> {
    if ctx_has_timestamps { vec![took.as_secs_f64()] } else { Vec::new() }
}

/// Camera rays, then diffuse bounces from their hits (misses start none), each traced
/// `runs` times timed by the device and `runs` times by the wall clock, after a warm-up.
fn rays(session: &mut Session, size: (u32, u32), runs: u32) -> Result<(Timed, Timed)> {
    let ctx = session.ctx();
    let timer = GpuTimer::new(ctx);
    let pixels = size.0 as usize * size.1 as usize;
    let io = session.trace_buffers(&vec![GpuTraceRay::default(); pixels]);
    session.trace_pass(&io, "generate_camera_rays", 0, None)?;
    let mut camera = Timed { count: pixels as u64, ..Default::default() };
    warm_up(session)?;
    for _ in 0..runs {
        camera.device.extend(device(ctx.timestamps, session.trace_pass(&io, "trace", 0, Some(&timer))?));
        camera.wall.push(session.trace_pass(&io, "trace", 0, None)?.as_secs_f64());
    }
    session.trace_pass(&io, "generate_diffuse_rays", 0, None)?;
    let bounces: Vec<GpuTraceRay> =
        rt::gpu::read_buffer::<GpuTraceRay>(ctx, &io.rays)?.into_iter().filter(|r| r.t_max > 0.0).collect();
    let mut diffuse = Timed { count: bounces.len() as u64, ..Default::default() };
    if !bounces.is_empty() {
        let bounce_io = session.trace_buffers(&bounces);
        warm_up(session)?;
        for _ in 0..runs {
            diffuse.device.extend(device(ctx.timestamps, session.trace_pass(&bounce_io, "trace", 0, Some(&timer))?));
            diffuse.wall.push(session.trace_pass(&bounce_io, "trace", 0, None)?.as_secs_f64());
        }
    }
    Ok((camera, diffuse))
}

/// Renders `spp` samples per pixel at `size` `runs` times (seeds 1, 2, …) as `rt render`
/// does, after the warm-up; with `rays`, times the BVH alone too.
pub fn measure(
    session: &mut Session,
    size: (u32, u32),
    spp: u32,
    runs: u32,
    rays_too: bool,
    bar: &ProgressBar,
) -> Result<RtFigures> {
    let ctx = session.ctx();
    let timer = GpuTimer::new(ctx);
    let mut request = RenderRequest::from_scene(session.scene());
    (request.width, request.height, request.spp) = (size.0, size.1, spp);
    // The rays' passes read the image size from the request's frame.
    session.set_request(&RenderRequest { spp: u32::MAX / 2, ..request.clone() })?;
    let (camera_rays, diffuse_rays) = match rays_too {
        true => {
            let (c, d) = rays(session, size, runs)?;
            (Some(c), Some(d))
        }
        false => (None, None),
    };
    warm_up(session)?;
    let mut paths = Timed { count: size.0 as u64 * size.1 as u64 * spp as u64, ..Default::default() };
    let mut renders = Vec::new();
    for seed in 1..=runs {
        let (image, report) = session.render(&RenderRequest { seed, ..request.clone() }, Some(&timer))?;
        paths.wall.push(report.elapsed.as_secs_f64());
        paths.device.extend(device(ctx.timestamps, report.dispatch_time));
        if renders.len() < 2 {
            renders.push(image.pixels);
        }
        bar.inc(1);
    }
    let renders: [Vec<[f32; 3]>; 2] =
        renders.try_into().map_err(|_| anyhow::anyhow!("a comparison takes at least 2 runs"))?;
    Ok(RtFigures { paths, camera_rays, diffuse_rays, renders })
}
