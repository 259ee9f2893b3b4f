//! `rt bench accuracy`: the reference, the sweep over the knobs, and the report,
//! with defaults sized for the adapter (a CPU adapter gets a small image and few
//! samples; a GPU enough samples to reach 1 % error without extrapolating far).

use super::knobs::select;
use super::reference::ReferenceSettings;
use super::report::{AccuracySummary, write};
use super::sweep::{SweepOptions, run};
use super::views::{DEFAULT_SSIM, Targets};
use anyhow::{Result, bail};
use rt::gpu::GpuContext;
use rt::scene::Scene;
use std::path::PathBuf;

/// What the command line gives; `None` takes the adapter's default.
#[derive(Clone, Debug, Default)]
pub struct AccuracyOptions {
    pub knobs: Vec<String>,
    pub out: PathBuf,
    /// Where references are cached; `out/reference` when `None`.
    pub cache: Option<PathBuf>,
    pub size: Option<(u32, u32)>,
    pub levels: Option<Vec<u32>>,
    pub repeats: Option<u32>,
    pub reference_spp: Option<u32>,
    pub reference_bounces: Option<u32>,
    /// Target relative RMSE (0.01 for 1 %).
    pub target: Option<f64>,
    /// Target SSIM of the perceptual view (0.99 when `None`).
    pub target_ssim: Option<f64>,
    pub budget_seconds: Option<f64>,
    pub progress: bool,
}

/// Defaults per kind of adapter: (size, levels, repeats, reference spp).
pub struct Defaults {
    pub size: (u32, u32),
    pub levels: Vec<u32>,
    pub repeats: u32,
    pub reference_spp: u32,
}

impl Defaults {
    pub fn for_adapter(ctx: &GpuContext) -> Self {
        match ctx.adapter_info.device_type {
            wgpu::DeviceType::Cpu => Self { size: (160, 120), levels: vec![1, 4, 16], repeats: 2, reference_spp: 256 },
            // Sized so that `rt bench headline` (three scenes, every knob) stays within minutes on a GPU.
            _ => Self { size: (320, 240), levels: vec![16, 64, 256, 1024], repeats: 3, reference_spp: 16384 },
        }
    }
}

pub const DEFAULT_TARGET: f64 = 0.01;
/// Enough that paths which survive Russian roulette are almost never cut short.
pub const REFERENCE_BOUNCES: u32 = 64;

impl AccuracyOptions {
    pub fn sweep_options(&self, ctx: &GpuContext) -> Result<SweepOptions> {
        let d = Defaults::for_adapter(ctx);
        let mut levels = self.levels.clone().unwrap_or(d.levels);
        levels.sort_unstable();
        levels.dedup();
        if levels.len() < 3 || levels[0] == 0 {
            bail!("--spp needs at least three different levels of at least 1 sample per pixel, e.g. --spp 4,16,64");
        }
        let reference_spp = self.reference_spp.unwrap_or(d.reference_spp.max(16 * levels[levels.len() - 1]));
        if reference_spp < 2 * levels[levels.len() - 1] {
            bail!("--reference-spp must be at least twice the highest level ({})", levels[levels.len() - 1]);
        }
        Ok(SweepOptions {
            size: self.size.unwrap_or(d.size),
            levels,
            repeats: self.repeats.unwrap_or(d.repeats).max(1),
            reference: ReferenceSettings {
                spp: reference_spp,
                max_bounces: self.reference_bounces.unwrap_or(REFERENCE_BOUNCES),
            },
            cache_dir: self.cache.clone().unwrap_or_else(|| self.out.join("reference")),
            progress: self.progress,
        })
    }
}

/// Runs the sweep on `scene` and writes the report into `options.out`.
pub fn accuracy(ctx: &GpuContext, scene: &Scene, options: &AccuracyOptions) -> Result<AccuracySummary> {
    let sweep_options = options.sweep_options(ctx)?;
    let knobs = select(&sweep_options.levels, &options.knobs).map_err(anyhow::Error::msg)?;
    let target = options.target.unwrap_or(DEFAULT_TARGET);
    if !(target > 0.0 && target < 1.0) {
        bail!("--target-percent must be between 0 and 100");
    }
    let ssim = options.target_ssim.unwrap_or(DEFAULT_SSIM);
    if !(ssim > 0.0 && ssim < 1.0) {
        bail!("--target-ssim must be between 0 and 1 (exclusive), e.g. 0.99");
    }
    let sweep = run(ctx, scene, &knobs, &sweep_options)?;
    let targets = Targets::for_sweep(&sweep, target, ssim, options.budget_seconds);
    write(&options.out, &sweep, targets)
}
