//! `rt bench throughput`: rays/s through the BVH alone (camera rays, then
//! diffuse bounces from their hits) and paths/s of the whole integrator.

use crate::bvh::BuildQuality;
use crate::gpu::{GpuContext, GpuTimer, median, ms, read_buffer};
use crate::layout::{EMPTY_LINK, GpuTraceHit, GpuTraceRay};
use crate::render::{RenderRequest, Session, human};
use crate::scene::Scene;
use anyhow::Result;
use indicatif::ProgressBar;

pub fn throughput(scene: Scene, (width, height): (u32, u32), runs: u32, spp: u32, adapter: Option<&str>) -> Result<()> {
    let runs = runs.max(1);
    let ctx = GpuContext::new(adapter)?;
    let mut session = Session::open(&ctx, scene, BuildQuality::default())?;
    let timer = GpuTimer::new(&ctx);
    println!("GPU       {}", ctx.describe());
    println!("scene     {} [{}]", session.scene().origin, session.features());
    println!("size      {width}x{height}, median of {runs} runs after a warm-up, timed by {}", timer.method());

    let mut request = RenderRequest::from_scene(session.scene());
    (request.width, request.height) = (width, height);
    session.set_request(&request)?;
    let n = width * height;
    let io = session.trace_buffers(&vec![GpuTraceRay::default(); n as usize]);
    let bar = ProgressBar::new(3 * (runs as u64 + 1));

    let mut camera_times = Vec::new();
    let mut diffuse_times = Vec::new();
    let mut diffuse_rays = 0u64;
    for run in 0..=runs {
        let base = 2 * run;
        session.trace_pass(&io, "generate_camera_rays", base, Some(&timer))?;
        let camera = session.trace_pass(&io, "trace", base, Some(&timer))?;
        let hits: Vec<GpuTraceHit> = read_buffer(&ctx, &io.hits)?;
        let with_hit = hits.iter().filter(|h| h.primitive != EMPTY_LINK).count() as u64;
        session.trace_pass(&io, "generate_diffuse_rays", base, Some(&timer))?;
        let diffuse = session.trace_pass(&io, "trace", base, Some(&timer))?;
        // Run 0 warms caches and compiles lazily built state; it is not counted.
        if run > 0 {
            camera_times.push(camera);
            diffuse_times.push(diffuse);
            diffuse_rays = with_hit;
        }
        bar.inc(2);
    }
    // One dispatch of `spp` samples per pixel per run.
    let paths_request = RenderRequest { spp, samples_per_dispatch: Some(spp), ..request.clone() };
    let mut path_times = Vec::new();
    for run in 0..=runs {
        let (_, report) = session.render(&paths_request, Some(&timer))?;
        if run > 0 {
            path_times.push(report.dispatch_time);
        }
        bar.inc(1);
    }
    bar.finish_and_clear();

    let camera = median(camera_times);
    let diffuse = median(diffuse_times);
    let paths = median(path_times);
    println!("camera    {}rays/s ({n} rays in {:.3} ms)", human(n as f64 / camera.as_secs_f64()), ms(camera));
    println!(
        "diffuse   {}rays/s ({diffuse_rays} bounce rays from camera hits in {:.3} ms)",
        human(diffuse_rays as f64 / diffuse.as_secs_f64()),
        ms(diffuse)
    );
    println!(
        "paths     {}paths/s ({spp} spp x {n} pixels in {:.3} ms, up to {} bounces)",
        human(spp as f64 * n as f64 / paths.as_secs_f64()),
        ms(paths),
        request.max_bounces
    );
    Ok(())
}
