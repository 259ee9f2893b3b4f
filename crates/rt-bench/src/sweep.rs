//! The sweep: each knob's settings rendered at several samples-per-pixel levels,
//! each level repeated with different seeds; the time is the median over repeats
//! (after a warm-up), the error the mean over them, against the reference.

use super::knobs::{Knob, Trial};
use super::metrics::ErrorMetrics;
use super::model::{Fit, Level};
use super::reference::{Reference, ReferenceSettings, obtain, reference_trial};
use super::timing::{render_timed, warm_up};
use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use rt::bvh::SceneGeometry;
use rt::gpu::median;
use rt::gpu::{GpuContext, GpuTimer};
use rt::render::Session;
use rt::scene::{FeatureSet, Scene};
use std::path::PathBuf;

#[derive(Clone, Debug)]
pub struct SweepOptions {
    pub size: (u32, u32),
    /// Samples per pixel each setting is measured at (at least three for the fits).
    pub levels: Vec<u32>,
    /// Renders per level, each with its own seed.
    pub repeats: u32,
    pub reference: ReferenceSettings,
    pub cache_dir: PathBuf,
    pub progress: bool,
}

/// One setting at one level.
#[derive(Clone, Debug)]
pub struct Measurement {
    pub spp: u32,
    /// Median over repeats, and the fastest and slowest.
    pub seconds: f64,
    pub seconds_min: f64,
    pub seconds_max: f64,
    /// Mean over repeats.
    pub error: ErrorMetrics,
    /// Standard error of `error.mse` over the repeats.
    pub mse_std_error: f64,
    /// Standard error of `error.relative_mean_error`.
    pub mean_error_std_error: f64,
    /// Standard error of `error.ssim` over the repeats.
    pub ssim_std_error: f64,
    /// Non-finite samples dropped, over all repeats (a bug to report if ever above 0).
    pub dropped: u64,
}

#[derive(Clone, Debug)]
pub struct SettingResult {
    pub label: String,
    pub features: FeatureSet,
    pub levels: Vec<Measurement>,
    /// In relative terms (over the reference's mean).
    pub fit: Option<Fit>,
    /// Summed BVH build time of the scene's meshes, for settings that build them.
    pub build_seconds: Option<f64>,
}

pub struct KnobResult {
    pub name: &'static str,
    pub about: &'static str,
    /// Why the knob was left out for this scene.
    pub skipped: Option<&'static str>,
    pub settings: Vec<SettingResult>,
}

pub struct Sweep {
    pub scene: Scene,
    pub adapter: String,
    pub timing: &'static str,
    pub options: SweepOptions,
    pub reference: Reference,
    pub baseline_features: FeatureSet,
    /// The scene's own settings at the sweep's levels.
    pub baseline: SettingResult,
    pub knobs: Vec<KnobResult>,
}

/// A session for the trial's scene, and the BVH build time when it built them afresh.
fn session_for<'a>(ctx: &'a GpuContext, trial: &Trial) -> Result<(Session<'a>, Option<f64>)> {
    let geometry = match trial.fresh_bvh {
        true => SceneGeometry::build_in_memory(&trial.scene, trial.quality)?,
        false => SceneGeometry::build(&trial.scene, trial.quality)?,
    };
    let build = trial.fresh_bvh.then(|| geometry.meshes.iter().map(|m| m.bvh.build_time.as_secs_f64()).sum());
    Ok((Session::with_geometry(ctx, trial.scene.clone(), geometry)?, build))
}

pub fn run(ctx: &GpuContext, scene: &Scene, knobs: &[Knob], options: &SweepOptions) -> Result<Sweep> {
    let timer = GpuTimer::new(ctx);
    let bar = progress_bar(options.progress, knobs, options);
    bar.set_message("reference");
    let ref_trial = reference_trial(scene, options.size, options.reference);
    let (mut ref_renderer, _) = session_for(ctx, &ref_trial)?;
    let reference = obtain(&mut ref_renderer, &ref_trial, options.reference, &options.cache_dir, &timer)?;
    drop(ref_renderer);

    let base = Trial::baseline(scene, options.size);
    let (mut base_session, _) = session_for(ctx, &base)?;
    let baseline_features = base_session.features();
    bar.set_message("baseline");
    let mut baseline = measure(&mut base_session, &base, &options.levels, options.repeats, &reference, &timer, &bar)?;
    baseline.label = "scene defaults".into();
    let mut measured = vec![(base.clone(), options.levels.clone(), baseline.clone())];
    let mut results = Vec::new();
    for knob in knobs {
        let levels = knob.spp_levels.clone().unwrap_or_else(|| options.levels.clone());
        let cost = levels.iter().sum::<u32>() as u64 * options.repeats as u64;
        let skipped = (knob.inapplicable)(&baseline_features);
        let mut settings = Vec::new();
        let mut own: Vec<(Trial, Session, Option<f64>)> = Vec::new();
        for setting in knob.settings.iter().filter(|_| skipped.is_none()) {
            bar.set_message(format!("{}: {}", knob.name, setting.label));
            let trial = setting.trial(&base);
            if let Some((_, _, earlier)) = measured.iter().find(|(t, l, _)| t.same_as(&trial) && *l == levels) {
                settings.push(SettingResult { label: setting.label.clone(), ..earlier.clone() });
                bar.inc(cost);
                continue;
            }
            let uses_base = trial.scene == base.scene && trial.quality == base.quality && !trial.fresh_bvh;
            let (session, build_seconds) = match uses_base {
                true => (&mut base_session, None),
                false => {
                    // Settings of a knob often share a scene (all RIS counts use seed sampling): one session.
                    let found = own.iter().position(|(t, _, _): &(Trial, _, _)| {
                        t.scene == trial.scene && t.quality == trial.quality && !t.fresh_bvh && !trial.fresh_bvh
                    });
                    let index = match found {
                        Some(i) => i,
                        None => {
                            let (r, build) = session_for(ctx, &trial)?;
                            own.push((trial.clone(), r, build));
                            own.len() - 1
                        }
                    };
                    let (_, r, build) = &mut own[index];
                    (r, *build)
                }
            };
            let mut result = measure(session, &trial, &levels, options.repeats, &reference, &timer, &bar)?;
            result.label = setting.label.clone();
            result.build_seconds = build_seconds;
            measured.push((trial, levels.clone(), result.clone()));
            settings.push(result);
        }
        if skipped.is_some() {
            bar.inc(cost * knob.settings.len() as u64);
        }
        results.push(KnobResult { name: knob.name, about: knob.about, skipped, settings });
    }
    bar.finish_and_clear();
    Ok(Sweep {
        scene: scene.clone(),
        adapter: ctx.describe(),
        timing: timer.method(),
        options: options.clone(),
        reference,
        baseline_features,
        baseline,
        knobs: results,
    })
}

fn measure(
    session: &mut Session,
    trial: &Trial,
    levels: &[u32],
    repeats: u32,
    reference: &Reference,
    timer: &GpuTimer,
    bar: &ProgressBar,
) -> Result<SettingResult> {
    warm_up(session, &trial.request, timer)?;
    let mut denoiser = match trial.denoise {
        true => Some(rt::denoise::Denoiser::new(rt::denoise::DenoiseDevice::Auto)?),
        false => None,
    };
    let features = trial.request.features.unwrap_or(session.features());
    let exposure = session.scene().render.exposure;
    let pixels = (trial.request.width * trial.request.height) as f64;
    let mut measurements = Vec::new();
    for &spp in levels {
        let mut times = Vec::new();
        let mut errors = Vec::new();
        let mut dropped = 0;
        for repeat in 0..repeats.max(1) {
            let request = rt::render::RenderRequest { spp, seed: repeat + 1, ..trial.request.clone() };
            let mut render = render_timed(session, &request, timer)?;
            if let Some(denoiser) = &mut denoiser {
                let start = std::time::Instant::now();
                render.image.pixels = denoiser.denoise(&render.image, &session.aovs()?)?;
                render.time += start.elapsed();
            }
            errors.push(ErrorMetrics::of(&render.image, reference, exposure));
            times.push(render.time);
            dropped += render.dropped;
            bar.inc(spp as u64);
        }
        let error = ErrorMetrics::mean(&errors);
        let n = errors.len() as f64;
        let spread = errors.iter().map(|e| (e.mse - error.mse).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
        // Three channels of a pixel are far from independent: count pixels, not values.
        let floor = error.mse * (2.0 / pixels).sqrt() / n.sqrt();
        let mean_spread =
            errors.iter().map(|e| (e.relative_mean_error - error.relative_mean_error).powi(2)).sum::<f64>();
        let mean_floor = (error.mse / pixels / n).sqrt() / reference.mean;
        let ssim_spread = errors.iter().map(|e| (e.ssim - error.ssim).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
        let (fastest, slowest) = (times.iter().min().copied(), times.iter().max().copied());
        measurements.push(Measurement {
            spp,
            seconds: median(times).as_secs_f64(),
            seconds_min: fastest.unwrap_or_default().as_secs_f64(),
            seconds_max: slowest.unwrap_or_default().as_secs_f64(),
            error,
            mse_std_error: (spread / n).sqrt().max(floor),
            dropped,
            mean_error_std_error: (mean_spread / (n - 1.0).max(1.0) / n).sqrt().max(mean_floor),
            ssim_std_error: (ssim_spread / n).sqrt(),
        });
    }
    let mean2 = reference.mean * reference.mean;
    let fit_levels: Vec<Level> = measurements
        .iter()
        .map(|m| Level {
            spp: m.spp as f64,
            seconds: m.seconds,
            mse: m.error.mse / mean2,
            mse_std_error: m.mse_std_error / mean2,
            mean_error: m.error.relative_mean_error,
            mean_error_std_error: m.mean_error_std_error,
        })
        .collect();
    Ok(SettingResult {
        label: String::new(),
        features,
        fit: Fit::of(&fit_levels),
        levels: measurements,
        build_seconds: None,
    })
}

/// Progress in samples per pixel rendered, which is what takes the time.
fn progress_bar(visible: bool, knobs: &[Knob], options: &SweepOptions) -> ProgressBar {
    if !visible {
        return ProgressBar::hidden();
    }
    let per_setting = |k: &Knob| k.spp_levels.as_ref().unwrap_or(&options.levels).iter().sum::<u32>() as u64;
    let baseline = options.levels.iter().sum::<u32>() as u64 * options.repeats as u64;
    let total: u64 =
        baseline + knobs.iter().map(|k| per_setting(k) * k.settings.len() as u64 * options.repeats as u64).sum::<u64>();
    let bar = ProgressBar::new(total.max(1));
    let style = ProgressStyle::with_template("{bar:40} {percent:>3}%  {msg}  ETA {eta}");
    bar.set_style(style.unwrap_or_else(|_| ProgressStyle::default_bar()));
    bar
}
