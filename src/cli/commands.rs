//! `rt watch`, `rt pack` and `rt bench`: each command's call into the library.

use super::args::WatchArgs;
use super::bench_args::{AccuracyArgs, BenchCommand};
use crate::load_scene;
use anyhow::{Context, Result, bail};
use rt::bvh::{BuildQuality, PackOutcome, PackReport};
use rt::denoise::Denoiser;
use rt::gpu::GpuContext;
use rt::render::RenderFlags;
use std::path::{Path, PathBuf};

pub(crate) fn watch(args: WatchArgs, adapter: Option<&str>) -> Result<()> {
    // Before any GPU or window: a missing denoiser is known at once, as with `rt render`.
    let denoiser = match args.denoise {
        true => Some(Denoiser::new(args.denoise_device).context("--denoise")?),
        false => None,
    };
    let options = rt_watch::WatchOptions {
        scene: args.scene,
        quality: args.quality,
        shader_dir: args.dev,
        frames_dir: args.frames_dir,
        flags: RenderFlags {
            spp: args.spp,
            size: args.size,
            seed: args.seed,
            noise_threshold: args.noise_threshold,
            aovs: args.denoise,
            ..Default::default()
        },
        format: args.format,
        max_reloads: args.max_reloads,
    };
    if args.stream {
        let ctx = GpuContext::new(adapter)?;
        eprintln!("GPU: {}", ctx.describe());
        rt_watch::stream::run(&ctx, &options, args.socket.as_deref())
    } else if args.headless {
        let ctx = GpuContext::new(adapter)?;
        eprintln!("GPU: {}", ctx.describe());
        rt_watch::run_headless(&ctx, &options, None, denoiser)
    } else {
        rt_watch::run_window(adapter, options, denoiser)
    }
}

pub(crate) fn bench_accuracy(args: AccuracyArgs, adapter: Option<&str>) -> Result<()> {
    let scene = load_scene(args.scene.as_deref())?;
    let stem = args.scene.as_deref().and_then(Path::file_stem).map_or("cornell_box".into(), |s| s.to_string_lossy());
    let options = rt_bench::AccuracyOptions {
        knobs: args.knobs,
        out: args.out.unwrap_or_else(|| Path::new("out/bench").join(&*stem)),
        cache: args.cache,
        size: args.size,
        levels: args.spp,
        repeats: args.repeats,
        reference_spp: args.reference_spp,
        reference_bounces: None,
        target: Some(args.target_percent / 100.0),
        target_ssim: Some(args.target_ssim),
        budget_seconds: args.budget_ms.map(|ms| ms / 1e3),
        progress: true,
    };
    rt_bench::commands::accuracy(&scene, &options, adapter)
}

pub(crate) fn pack(paths: &[PathBuf], quality: BuildQuality, force: bool) -> Result<()> {
    let assets = rt::bvh::pack::find_assets(paths)?;
    if assets.is_empty() {
        bail!("no assets (asset folders, .rtmesh, .gltf, .glb or .obj files) under the given paths");
    }
    let bar = rt::bvh::pack::asset_bar(assets.len(), "packing");
    let results = rt::bvh::pack::parallel_map(&assets, bar.as_ref(), |a| rt::bvh::pack::pack(a, quality, force));
    bar.finish();
    let mut failures = 0;
    for result in results {
        match result {
            Ok(PackReport { asset, outcome: PackOutcome::UpToDate, .. }) => println!("{}: up to date", asset.display()),
            Ok(PackReport { asset, cache, outcome: PackOutcome::Packed { reason, triangles, time } }) => println!(
                "{}: packed {triangles} triangles in {:.1?} into {} ({reason})",
                asset.display(),
                time,
                cache.display()
            ),
            Err(e) => {
                eprintln!("error: {e}");
                failures += 1;
            }
        }
    }
    if failures > 0 {
        bail!("{failures} of {} assets failed to pack", assets.len());
    }
    Ok(())
}

/// Runs one of `rt bench`'s measurements.
pub(crate) fn bench(command: BenchCommand, adapter: Option<&str>) -> Result<()> {
    match command {
        BenchCommand::Throughput { scene, size, runs, spp, sample_lanes } => {
            let options = rt_bench::ThroughputOptions { size, runs, spp, lanes: sample_lanes, rays: true };
            load_scene(scene.as_deref()).and_then(|s| rt_bench::throughput(s, &options, adapter))
        }
        BenchCommand::Instances { counts, size, runs, spp } => {
            rt_bench::instances(&rt_bench::InstanceScaleOptions { counts, size, runs, spp }, adapter)
        }
        BenchCommand::Compare { scenes, size, spp, runs, sampler, python, variant } => {
            let root = PathBuf::new();
            let options = rt_bench::CompareOptions { scenes, size, spp, runs, python, variant, sampler, root };
            rt_bench::compare(&options, adapter)
        }
        BenchCommand::MitsubaScene { scene, out, size } => {
            load_scene(Some(&scene)).and_then(|s| rt_bench::mitsuba_scene::write(&s, size, &out))
        }
        BenchCommand::Sky { scene, size, spp } => {
            load_scene(Some(&scene)).and_then(|s| rt_bench::sky(s, size, spp, adapter))
        }
        BenchCommand::WatchLatency { asset, size, runs } => {
            rt_watch::latency::watch_latency(&asset, size, runs, adapter)
        }
        BenchCommand::StreamLatency { scene, asset, size, runs } => {
            rt_watch::stream::latency::stream_latency(scene.as_deref(), &asset, size, runs, adapter)
        }
        BenchCommand::FirstPixel { scene, size, child: true } => {
            load_scene(scene.as_deref()).and_then(|s| rt_bench::first_pixel::child(s, size, adapter))
        }
        BenchCommand::FirstPixel { scene, size, child: false } => {
            rt_bench::first_pixel::first_pixel(scene.as_deref(), size, adapter)
        }
        BenchCommand::Denoise { scene, size, runs, spp } => {
            let options = rt_bench::DenoiseBenchOptions { size, runs, spp };
            load_scene(scene.as_deref()).and_then(|s| rt_bench::denoise_bench(s, &options, adapter).map(|_| ()))
        }
        BenchCommand::Accuracy(args) => bench_accuracy(args, adapter),
        BenchCommand::Effects { scene, size, spp, repeats } => {
            load_scene(scene.as_deref()).and_then(|s| rt_bench::commands::effects(s, size, spp, repeats, adapter))
        }
        BenchCommand::Fireflies(a) => load_scene(a.scene.as_deref()).and_then(|s| {
            let options = rt_bench::FireflyOptions { size: (0, 0), samples: a.samples, seeds: a.seeds, clamp: a.clamp };
            rt_bench::commands::fireflies(&s, options, a.size, a.out.as_deref(), adapter)
        }),
        BenchCommand::Headline { out, size, spp, reference_spp, docs } => {
            let accuracy = rt_bench::AccuracyOptions { out, size, levels: spp, reference_spp, ..Default::default() };
            rt_bench::commands::headline(accuracy, docs.then(|| PathBuf::from("docs/benchmarks.md")), adapter)
        }
    }
}
