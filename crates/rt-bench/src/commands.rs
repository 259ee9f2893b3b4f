//! The `rt bench` commands below `throughput`: each opens the GPU, runs, and prints
//! or writes its report, so that `main.rs` only parses.

use super::accuracy::{AccuracyOptions, Defaults};
use super::fireflies::FireflyOptions;
use super::headline::HeadlineOptions;
use anyhow::{Result, bail};
use indicatif::ProgressBar;
use rt::gpu::GpuContext;
use rt::scene::Scene;
use std::path::{Path, PathBuf};

fn open(adapter: Option<&str>) -> Result<GpuContext> {
    let ctx = GpuContext::new(adapter)?;
    eprintln!("GPU: {}", ctx.describe());
    Ok(ctx)
}

pub fn accuracy(scene: &Scene, options: &AccuracyOptions, adapter: Option<&str>) -> Result<()> {
    let ctx = open(adapter)?;
    let options = AccuracyOptions { progress: true, ..options.clone() };
    let summary = super::accuracy(&ctx, scene, &options)?;
    println!("wrote {}", summary.report.display());
    Ok(())
}

pub fn effects(scene: Scene, size: Option<(u32, u32)>, spp: u32, repeats: u32, adapter: Option<&str>) -> Result<()> {
    let ctx = open(adapter)?;
    let size = size.unwrap_or(Defaults::for_adapter(&ctx).size);
    let bar = ProgressBar::new(1);
    let report = super::effects(&ctx, scene, size, spp, repeats, &bar)?;
    bar.finish_and_clear();
    print!("{}", report.markdown());
    Ok(())
}

/// `options.size` is replaced by `size` or the adapter's default.
pub fn fireflies(
    scene: &Scene,
    options: FireflyOptions,
    size: Option<(u32, u32)>,
    out: Option<&Path>,
    adapter: Option<&str>,
) -> Result<()> {
    if options.clamp.is_some_and(|c| !(c.is_finite() && c > 0.0)) {
        bail!("--clamp must be a positive luminance");
    }
    let ctx = open(adapter)?;
    let options = FireflyOptions { size: size.unwrap_or(Defaults::for_adapter(&ctx).size), ..options };
    let bar = ProgressBar::new(1);
    let report = super::fireflies(&ctx, scene, &options, &bar)?;
    bar.finish_and_clear();
    let md = report.markdown();
    if let Some(out) = out {
        rt::files::write_atomically(out, md.as_bytes())?;
    }
    print!("{md}");
    Ok(())
}

/// Runs from the repository root (the scenes are found under `scenes/`).
pub fn headline(accuracy: AccuracyOptions, readme: Option<PathBuf>, adapter: Option<&str>) -> Result<()> {
    let ctx = open(adapter)?;
    let size = accuracy.size.unwrap_or(Defaults::for_adapter(&ctx).size);
    let options = HeadlineOptions {
        accuracy: AccuracyOptions { progress: true, ..accuracy },
        root: PathBuf::new(),
        effects_spp: 16,
        effects_repeats: 5,
        fireflies: FireflyOptions { size, samples: 16, seeds: 8, clamp: None },
        readme,
    };
    print!("{}", super::headline(&ctx, &options)?);
    Ok(())
}
