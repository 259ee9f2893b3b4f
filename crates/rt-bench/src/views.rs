//! The equal-time and equal-error views of a sweep: per setting, the error reached in
//! a fixed time budget and the time needed for a target error (from the fitted
//! models), and whether any of its measurements is on its knob's Pareto front.

use super::model::{pareto_front, spp_for_dssim};
use super::sweep::{SettingResult, Sweep};

/// What is compared: an error to reach, and a time to spend.
#[derive(Clone, Copy, Debug)]
pub struct Targets {
    /// Relative RMSE (0.01 = 1 % of the reference's mean radiance).
    pub error: f64,
    pub budget_seconds: f64,
    /// SSIM to reach (the perceptual view, which a denoiser's bias does not make unreachable).
    pub ssim: f64,
}

/// SSIM the perceptual view aims at by default (`--target-ssim`).
pub const DEFAULT_SSIM: f64 = 0.99;

impl Targets {
    /// `error` and `ssim`, and a budget of `budget_seconds` or else the baseline's time at its highest level.
    pub fn for_sweep(sweep: &Sweep, error: f64, ssim: f64, budget_seconds: Option<f64>) -> Self {
        let top = sweep.baseline.levels.iter().max_by_key(|m| m.spp).map(|m| m.seconds);
        Self { error, budget_seconds: budget_seconds.or(top).unwrap_or(1.0), ssim }
    }
}

/// Samples per pixel and seconds (from the setting's time model) to an SSIM of `ssim`,
/// and whether that lies beyond 4× its highest measured level.
fn to_ssim(s: &SettingResult, ssim: f64) -> Option<(f64, f64, bool)> {
    let points: Vec<(f64, f64)> = s.levels.iter().map(|m| (m.spp as f64, 1.0 - m.error.ssim)).collect();
    let spp = spp_for_dssim(&points, 1.0 - ssim)?;
    let fit = s.fit.as_ref()?;
    Some((spp, fit.seconds_at_spp(spp), spp > 4.0 * fit.max_spp))
}

#[derive(Clone, Debug)]
pub struct SettingView {
    pub label: String,
    pub seconds_per_spp: Option<f64>,
    /// Relative RMSE reached in the budget.
    pub error_in_budget: Option<f64>,
    /// Time and samples per pixel to the target error (`None`: not reachable, as the bias is above it).
    pub seconds_to_target: Option<f64>,
    pub spp_to_target: Option<f64>,
    /// The prediction reaches beyond 4× the highest measured level.
    pub extrapolated: bool,
    pub relative_bias: Option<f64>,
    /// No other setting of the knob is at least as fast and as accurate at any measured point.
    pub on_front: bool,
    /// Measured relative RMSE and PSNR at the highest level, and the relative error of the mean there.
    pub top_relative_rmse: f64,
    pub top_psnr_db: f64,
    pub top_relative_mean_error: f64,
    /// Measured SSIM at the highest level.
    pub top_ssim: f64,
    /// Time and samples per pixel to the target SSIM (`None`: more samples stopped helping).
    pub seconds_to_ssim: Option<f64>,
    pub spp_to_ssim: Option<f64>,
    pub ssim_extrapolated: bool,
    pub build_seconds: Option<f64>,
}

pub struct KnobView {
    pub name: &'static str,
    pub about: &'static str,
    pub skipped: Option<&'static str>,
    pub settings: Vec<SettingView>,
}

pub fn views(sweep: &Sweep, targets: Targets) -> Vec<KnobView> {
    let mean = sweep.reference.mean;
    sweep
        .knobs
        .iter()
        .map(|k| {
            let points: Vec<(usize, (f64, f64))> = k
                .settings
                .iter()
                .enumerate()
                .flat_map(|(i, s)| s.levels.iter().map(move |m| (i, (m.seconds, m.error.relative_rmse(mean)))))
                .collect();
            let front = pareto_front(&points.iter().map(|(_, p)| *p).collect::<Vec<_>>());
            let on_front = |i: usize| points.iter().zip(&front).any(|((j, _), f)| *j == i && *f);
            let settings =
                k.settings.iter().enumerate().map(|(i, s)| setting_view(s, targets, mean, on_front(i))).collect();
            KnobView { name: k.name, about: k.about, skipped: k.skipped, settings }
        })
        .collect()
}

pub fn setting_view(s: &SettingResult, targets: Targets, mean: f64, on_front: bool) -> SettingView {
    let top = s.levels.iter().max_by_key(|m| m.spp);
    let fit = s.fit.as_ref();
    let spp_to_target = fit.and_then(|f| f.spp_for(targets.error));
    let ssim = to_ssim(s, targets.ssim);
    SettingView {
        label: s.label.clone(),
        seconds_per_spp: fit.map(|f| f.seconds_per_spp),
        error_in_budget: fit.and_then(|f| f.relative_rmse_at_time(targets.budget_seconds)),
        seconds_to_target: fit.and_then(|f| f.seconds_for(targets.error)),
        spp_to_target,
        extrapolated: fit.zip(spp_to_target).is_some_and(|(f, spp)| spp > 4.0 * f.max_spp),
        relative_bias: fit.map(|f| f.relative_bias()),
        on_front,
        top_relative_rmse: top.map_or(f64::NAN, |m| m.error.relative_rmse(mean)),
        top_psnr_db: top.map_or(f64::NAN, |m| m.error.psnr_db()),
        top_relative_mean_error: top.map_or(f64::NAN, |m| m.error.relative_mean_error),
        top_ssim: top.map_or(f64::NAN, |m| m.error.ssim),
        seconds_to_ssim: ssim.map(|(_, t, _)| t),
        spp_to_ssim: ssim.map(|(spp, _, _)| spp),
        ssim_extrapolated: ssim.is_some_and(|(_, _, far)| far),
        build_seconds: s.build_seconds,
    }
}

/// The fastest setting of any knob to reach the target: (knob, setting view).
pub fn fastest_to_target(views: &[KnobView]) -> Option<(&'static str, &SettingView)> {
    views
        .iter()
        .flat_map(|k| k.settings.iter().map(move |s| (k.name, s)))
        .filter(|(_, s)| s.seconds_to_target.is_some())
        .min_by(|a, b| a.1.seconds_to_target.unwrap_or(f64::MAX).total_cmp(&b.1.seconds_to_target.unwrap_or(f64::MAX)))
}

/// One level of a setting beside the time its knob's plain setting needs for the same
/// SSIM: how a denoiser (or any biased shortcut) is priced at equal perceived quality.
#[derive(Clone, Copy, Debug)]
pub struct EqualQuality {
    pub spp: u32,
    pub seconds: f64,
    pub ssim: f64,
    /// Time and samples the plain setting needs for `ssim` (`None`: its fit never gets there).
    pub plain_seconds: Option<f64>,
    pub plain_spp: Option<f64>,
    /// The plain setting's prediction reaches beyond 4× its highest measured level.
    pub extrapolated: bool,
}

impl EqualQuality {
    /// How many times faster than the plain setting at the same SSIM.
    pub fn speed_up(&self) -> Option<f64> {
        self.plain_seconds.map(|t| t / self.seconds)
    }
}

/// Each level of `setting` against `plain`'s measured SSIM (see [`spp_for_dssim`]).
pub fn equal_quality(setting: &SettingResult, plain: &SettingResult) -> Vec<EqualQuality> {
    setting
        .levels
        .iter()
        .map(|m| {
            let plain_at = to_ssim(plain, m.error.ssim);
            EqualQuality {
                spp: m.spp,
                seconds: m.seconds,
                ssim: m.error.ssim,
                plain_seconds: plain_at.map(|(_, t, _)| t),
                plain_spp: plain_at.map(|(spp, _, _)| spp),
                extrapolated: plain_at.is_some_and(|(_, _, far)| far),
            }
        })
        .collect()
}
