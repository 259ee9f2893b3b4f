//! `rt bench denoise`: milliseconds per frame of Open Image Denoise on each device it
//! has here, for a frame of the size asked (1024×720 by default). The frame is a real
//! render of the scene at a few samples per pixel with its albedo and normal AOVs, and
//! each timed run is the whole denoise as `rt render --denoise` does it: the albedo and
//! the normals prefiltered, then the beauty (HDR, clean guides), the filters made and
//! committed, the images copied to the device and back. The first run of each device
//! loads its kernels and weights and makes the filters, and is reported apart; the later
//! runs keep the filters (as `rt watch` does while the size stays), and the runs that
//! make them afresh each time are timed beside them.

use anyhow::{Result, bail};
use rt::bvh::BuildQuality;
use rt::denoise::{DenoiseDevice, Denoiser, PhysicalDevice, physical_devices};
use rt::gpu::{GpuContext, median};
use rt::render::{Aovs, Image, RenderRequest, Session};
use rt::scene::Scene;
use std::time::{Duration, Instant};

#[derive(Clone, Copy, Debug)]
pub struct DenoiseBenchOptions {
    pub size: (u32, u32),
    /// Timed runs per device after the first; the median and the fastest are reported.
    pub runs: u32,
    /// Samples per pixel of the frame that is denoised.
    pub spp: u32,
}

/// One device's times.
#[derive(Clone, Debug)]
pub struct DeviceTiming {
    pub device: String,
    pub first: Duration,
    pub median: Duration,
    pub min: Duration,
    /// Median of runs that make the filters afresh, as each denoise did before they were kept.
    pub rebuilt_median: Duration,
}

/// Renders the frame, then times each device; prints a table and returns its rows.
/// Devices that fail are reported and skipped; it is an error only when none works.
pub fn denoise_bench(scene: Scene, options: &DenoiseBenchOptions, adapter: Option<&str>) -> Result<Vec<DeviceTiming>> {
    let found = physical_devices()?;
    let listed: Vec<String> = found.iter().map(describe).collect();
    println!("Open Image Denoise devices found: {}", if listed.is_empty() { "none".into() } else { listed.join(", ") });
    let ctx = GpuContext::new(adapter)?;
    let (image, aovs, took) = frame(&ctx, scene, options)?;
    let (w, h) = options.size;
    println!(
        "frame: {w}x{h} ({:.2} Mpixel), {} spp with albedo and normal AOVs, rendered in {:.2} s on {}",
        (w as f64 * h as f64) / 1e6,
        options.spp,
        took.as_secs_f64(),
        ctx.describe()
    );
    println!(
        "each run: the whole denoise as `rt render --denoise` does it (albedo and normal prefiltered, then the \
         HDR beauty with clean guides; images copied to the device and back); the first run makes the filters, \
         later runs keep them, and the last column makes them afresh each run"
    );
    let runs = options.runs.max(1);
    println!(
        "\n| device | first run | median of {runs} | fastest | Mpixel/s (median) | filters made each run (median) |\n\
         |---|---|---|---|---|---|"
    );
    let mut kinds = vec![DenoiseDevice::Cpu];
    if found.iter().any(|d| d.kind == "CUDA") {
        kinds.insert(0, DenoiseDevice::Cuda);
    }
    let mut rows = Vec::new();
    let mut failures = Vec::new();
    for kind in kinds {
        match time_device(kind, &image, &aovs, runs) {
            Ok(row) => {
                let mpix = (w as f64 * h as f64) / 1e6 / row.median.as_secs_f64();
                let (first, median, min, rebuilt) =
                    (ms(row.first), ms(row.median), ms(row.min), ms(row.rebuilt_median));
                println!("| {} | {first} | {median} | {min} | {mpix:.3} | {rebuilt} |", row.device);
                rows.push(row);
            }
            Err(e) => {
                let name = if kind == DenoiseDevice::Cuda { "CUDA" } else { "CPU" };
                println!("| {name} | failed (below) | – | – | – | – |");
                failures.push(format!("{name}: {e:#}"));
            }
        }
    }
    for failure in &failures {
        println!("\n{failure}");
    }
    if rows.is_empty() {
        bail!("no Open Image Denoise device could denoise the frame");
    }
    Ok(rows)
}

fn describe(d: &PhysicalDevice) -> String {
    if d.name.is_empty() { d.kind.to_string() } else { format!("{} ({})", d.kind, d.name) }
}

fn ms(t: Duration) -> String {
    format!("{:.1} ms", t.as_secs_f64() * 1e3)
}

/// The scene at the bench's size and samples, with AOVs.
fn frame(ctx: &GpuContext, scene: Scene, options: &DenoiseBenchOptions) -> Result<(Image, Aovs, Duration)> {
    let mut session = Session::open(ctx, scene, BuildQuality::default())?;
    let (width, height) = options.size;
    let request = RenderRequest {
        width,
        height,
        spp: options.spp.max(1),
        aovs: true,
        ..RenderRequest::from_scene(session.scene())
    };
    let start = Instant::now();
    let (image, _) = session.render(&request, None)?;
    let took = start.elapsed();
    Ok((image, session.aovs()?, took))
}

fn time_device(kind: DenoiseDevice, image: &Image, aovs: &Aovs, runs: u32) -> Result<DeviceTiming> {
    let mut denoiser = Denoiser::new(kind)?;
    let mut run = |rebuild: bool| -> Result<Duration> {
        if rebuild {
            denoiser.release_filters();
        }
        let start = Instant::now();
        let pixels = denoiser.denoise(image, aovs)?;
        let took = start.elapsed();
        if let Some(bad) = pixels.iter().position(|p| !p.iter().all(|v| v.is_finite())) {
            bail!("the denoised frame has a non-finite pixel (the {bad}th)");
        }
        Ok(took)
    };
    let first = run(false)?;
    // Interleaved, so that a machine whose load changes weighs on both alike.
    let (mut times, mut rebuilt) = (Vec::new(), Vec::new());
    for _ in 0..runs {
        times.push(run(false)?);
        rebuilt.push(run(true)?);
    }
    let min = times.iter().min().copied().unwrap_or(first);
    let device = denoiser.describe();
    Ok(DeviceTiming { device, first, median: median(times), min, rebuilt_median: median(rebuilt) })
}
