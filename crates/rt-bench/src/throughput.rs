//! `rt bench throughput`: rays/s through the BVH alone (camera rays, then
//! diffuse bounces from their hits) and paths/s of the whole integrator.

use anyhow::Result;
use indicatif::ProgressBar;
use rt::bvh::BuildQuality;
use rt::gpu::{GpuContext, GpuTimer, median, ms, read_buffer};
use rt::layout::GpuTraceRay;
use rt::render::{RenderRequest, Session, human};
use rt::scene::Scene;
use std::time::{Duration, Instant};

/// Wall time of back-to-back path dispatches before anything is timed, and their number
/// at most. A GPU's driver lowers its clocks after idle moments and raises them only
/// under sustained work: an H200 measured at 345–495 MHz instead of 1980 MHz (a quarter
/// of the rate) when timing started after a scene's load; a continuous render keeps it
/// at 1980 MHz.
const WARM_UP: Duration = Duration::from_secs(1);
const WARM_UP_DISPATCHES: u32 = 500;

pub(super) fn warm_up(session: &mut Session) -> Result<()> {
    let start = Instant::now();
    for _ in 0..WARM_UP_DISPATCHES {
        session.step(None)?;
        if start.elapsed() >= WARM_UP {
            break;
        }
    }
    Ok(())
}

/// What one throughput measurement runs.
#[derive(Clone, Copy, Debug)]
pub struct ThroughputOptions {
    pub size: (u32, u32),
    /// Timed repetitions of each figure; the median is reported.
    pub runs: u32,
    /// Samples per pixel of each integrator dispatch.
    pub spp: u32,
    /// Lanes each pixel's samples are spread over; `None`: the renderer's choice.
    pub lanes: Option<u32>,
    /// Time the BVH alone too (camera and diffuse rays), not only paths.
    pub rays: bool,
}

/// Median GPU times of one measurement and what they counted.
#[derive(Clone, Debug)]
pub struct Throughput {
    pub pixels: u64,
    pub camera: Option<Duration>,
    pub diffuse: Option<(u64, Duration)>,
    pub paths: Duration,
    pub spp: u32,
    pub max_bounces: u32,
}

impl Throughput {
    pub fn camera_rays_per_s(&self) -> Option<f64> {
        self.camera.map(|t| self.pixels as f64 / t.as_secs_f64())
    }

    pub fn diffuse_rays_per_s(&self) -> Option<f64> {
        self.diffuse.map(|(n, t)| n as f64 / t.as_secs_f64())
    }

    pub fn paths_per_s(&self) -> f64 {
        self.spp as f64 * self.pixels as f64 / self.paths.as_secs_f64()
    }
}

/// Measures `session`'s scene once the GPU is warm; run 0 of each figure warms caches
/// and lazily built state too and is not counted.
pub fn measure(session: &mut Session, options: &ThroughputOptions, bar: &ProgressBar) -> Result<Throughput> {
    let ctx = session.ctx();
    let timer = GpuTimer::new(ctx);
    let runs = options.runs.max(1);
    let (width, height) = options.size;
    let mut request = RenderRequest::from_scene(session.scene());
    (request.width, request.height) = (width, height);
    let pixels = width as u64 * height as u64;
    // Dispatches of `spp` samples per pixel (fewer where the lanes' scratch holds fewer),
    // enough of them for the warm-up and every run.
    let paths_request = RenderRequest {
        spp: u32::MAX / 2,
        samples_per_dispatch: Some(options.spp),
        sample_lanes: options.lanes,
        ..request.clone()
    };
    session.set_request(&paths_request)?;
    warm_up(session)?;

    let (mut camera, mut diffuse) = (None, None);
    if options.rays {
        let io = session.trace_buffers(&vec![GpuTraceRay::default(); pixels as usize]);
        let mut camera_times = Vec::new();
        for run in 0..=runs {
            session.trace_pass(&io, "generate_camera_rays", 2 * run, None)?;
            let camera = session.trace_pass(&io, "trace", 2 * run, Some(&timer))?;
            if run > 0 {
                camera_times.push(camera);
            }
        }
        // Bounce rays from the camera rays' hits, as a path's next rays start; misses
        // start none and are left out, as `rt bench compare` has Mitsuba measure them.
        session.trace_pass(&io, "generate_diffuse_rays", 0, None)?;
        let rays: Vec<GpuTraceRay> = read_buffer(ctx, &io.rays)?;
        let bounces: Vec<GpuTraceRay> = rays.into_iter().filter(|r| r.t_max > 0.0).collect();
        let mut diffuse_times = Vec::new();
        if !bounces.is_empty() {
            let bounce_io = session.trace_buffers(&bounces);
            warm_up(session)?;
            for run in 0..=runs {
                let diffuse = session.trace_pass(&bounce_io, "trace", 0, Some(&timer))?;
                if run > 0 {
                    diffuse_times.push(diffuse);
                }
                bar.inc(1);
            }
        }
        camera = Some(median(camera_times));
        diffuse = (!diffuse_times.is_empty()).then(|| (bounces.len() as u64, median(diffuse_times)));
    }
    // Each run: dispatches until `spp` samples per pixel are taken; its time is scaled to
    // exactly `spp` where the last dispatch took more.
    let mut path_times = Vec::new();
    for run in 0..=runs {
        let (mut samples, mut took) = (0, Duration::ZERO);
        while samples < options.spp {
            let step = session.step(Some(&timer))?;
            (samples, took) = (samples + step.samples, took + step.took);
        }
        if run > 0 {
            path_times.push(took.mul_f64(options.spp as f64 / samples as f64));
        }
        bar.inc(1);
    }
    Ok(Throughput {
        pixels,
        camera,
        diffuse,
        paths: median(path_times),
        spp: options.spp,
        max_bounces: request.max_bounces,
    })
}

pub fn throughput(scene: Scene, options: &ThroughputOptions, adapter: Option<&str>) -> Result<()> {
    let ctx = GpuContext::new(adapter)?;
    let mut session = Session::open(&ctx, scene, BuildQuality::default())?;
    let (width, height) = options.size;
    println!("GPU       {}", ctx.describe());
    println!("scene     {} [{}]", session.scene().origin, session.features());
    println!(
        "size      {width}x{height}, median of {} runs after a warm-up, timed by {}",
        options.runs.max(1),
        GpuTimer::new(&ctx).method()
    );
    let bar = ProgressBar::new(2 * (options.runs.max(1) as u64 + 1));
    let t = measure(&mut session, &ThroughputOptions { rays: true, ..*options }, &bar)?;
    bar.finish_and_clear();
    if let (Some(rate), Some(time)) = (t.camera_rays_per_s(), t.camera) {
        println!("camera    {}rays/s ({} rays in {:.3} ms)", human(rate), t.pixels, ms(time));
    }
    if let (Some(rate), Some((n, time))) = (t.diffuse_rays_per_s(), t.diffuse) {
        println!("diffuse   {}rays/s ({n} bounce rays from camera hits in {:.3} ms)", human(rate), ms(time));
    }
    println!(
        "paths     {}paths/s ({} spp x {} pixels in {:.3} ms, up to {} bounces)",
        human(t.paths_per_s()),
        t.spp,
        t.pixels,
        ms(t.paths),
        t.max_bounces
    );
    Ok(())
}
