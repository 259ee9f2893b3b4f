//! The accuracy report: `report.md` (tables), `measurements.csv` (every setting at
//! every level), `settings.csv` (the fitted models and the two views) and one
//! error-against-time plot per knob.

use super::plot::{Curve, error_vs_time};
use super::reference::ReferenceOrigin;
use super::sweep::{SettingResult, Sweep};
use super::views::{KnobView, SettingView, Targets, equal_quality, fastest_to_target, setting_view, views};
use anyhow::{Context, Result};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// What the headline needs from one scene's sweep.
#[derive(Clone, Debug)]
pub struct AccuracySummary {
    pub scene: String,
    pub adapter: String,
    pub targets: Targets,
    /// (knob, setting, spp, seconds, extrapolated) of the fastest setting to reach the target.
    pub fastest: Option<(String, String, f64, f64, bool)>,
    /// The scene's own settings: seconds to the target (if reachable), and whether extrapolated.
    pub baseline: Option<(f64, bool)>,
    pub report: PathBuf,
}

pub fn write(dir: &Path, sweep: &Sweep, targets: Targets) -> Result<AccuracySummary> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let views = views(sweep, targets);
    let baseline = setting_view(&sweep.baseline, targets, sweep.reference.mean, true);
    for (knob, view) in sweep.knobs.iter().zip(&views).filter(|(k, _)| k.skipped.is_none()) {
        let curves: Vec<Curve> = knob
            .settings
            .iter()
            .zip(&view.settings)
            .map(|(s, v)| Curve { label: s.label.clone(), points: points(s, sweep), dominated: !v.on_front })
            .collect();
        let title = format!("{}: {}", scene_name(sweep), knob.name);
        error_vs_time(&dir.join(format!("{}.png", knob.name)), &title, &curves, targets.error, targets.budget_seconds)?;
    }
    let report = dir.join("report.md");
    write_file(&report, &markdown(sweep, &views, &baseline, targets))?;
    write_file(&dir.join("measurements.csv"), &measurements_csv(sweep))?;
    write_file(&dir.join("settings.csv"), &settings_csv(&views))?;
    let fastest = fastest_to_target(&views).map(|(knob, s)| {
        (
            knob.to_string(),
            s.label.clone(),
            s.spp_to_target.unwrap_or(0.0),
            s.seconds_to_target.unwrap_or(0.0),
            s.extrapolated,
        )
    });
    Ok(AccuracySummary {
        scene: sweep.scene.origin.clone(),
        adapter: sweep.adapter.clone(),
        targets,
        fastest,
        baseline: baseline.seconds_to_target.map(|t| (t, baseline.extrapolated)),
        report,
    })
}

fn points(s: &SettingResult, sweep: &Sweep) -> Vec<(f64, f64)> {
    s.levels.iter().map(|m| (m.seconds, m.error.relative_rmse(sweep.reference.mean))).collect()
}

fn scene_name(sweep: &Sweep) -> String {
    Path::new(&sweep.scene.origin).file_stem().map_or("scene".into(), |s| s.to_string_lossy().into_owned())
}

fn write_file(path: &Path, text: &str) -> Result<()> {
    Ok(rt::files::write_atomically(path, text.as_bytes())?)
}

/// The sweep's settings: adapter, timing, sizes, the reference and the models.
fn describe_sweep(md: &mut String, sweep: &Sweep, targets: Targets) {
    let o = &sweep.options;
    let r = &sweep.reference;
    let _ = writeln!(md, "# Accuracy against time: {}\n", sweep.scene.origin);
    let _ = writeln!(md, "- adapter: {}", sweep.adapter);
    let _ = writeln!(md, "- timing: {}, median of {} repeats (seeds 1..) after a warm-up", sweep.timing, o.repeats);
    let _ = writeln!(md, "- size: {}x{}; samples per pixel: {:?}", o.size.0, o.size.1, o.levels);
    let _ = writeln!(md, "- scene features: [{}]", sweep.baseline_features);
    let origin = match r.origin {
        ReferenceOrigin::Cached => "cached".to_string(),
        ReferenceOrigin::Rendered(t) => format!("rendered in {:.1} s", t.as_secs_f64()),
    };
    let _ = writeln!(
        md,
        "- reference: {} spp, {} bounces, NEE, GGX rough glass, no clamp ({origin}: `{}`); its own noise, \
         subtracted from every MSE: {} relative RMSE; SSIM of one half against the other {:.4}",
        r.settings.spp,
        r.settings.max_bounces,
        r.path.display(),
        percent(r.relative_noise()),
        r.halves_ssim
    );
    let _ = writeln!(
        md,
        "- equal error: time to a relative RMSE of {} (RMSE over the reference's mean radiance); \
         equal time: error reached in {:.1} ms (unless `--budget-ms`, the scene defaults' time at {} spp)",
        percent(targets.error),
        targets.budget_seconds * 1e3,
        o.levels.iter().max().unwrap_or(&0)
    );
    let dropped: u64 = sweep.knobs.iter().flat_map(|k| &k.settings).flat_map(|s| &s.levels).map(|m| m.dropped).sum();
    if dropped > 0 {
        let _ =
            writeln!(md, "- **{dropped} non-finite samples were dropped** (see `dropped_samples` in measurements.csv)");
    }
    let _ = writeln!(
        md,
        "- models: MSE = bias² + variance/spp, time = overhead + spp × time per spp, fitted per setting; \
         `~` marks predictions beyond 4× the highest level measured; ∞: the bias is above the target\n"
    );
    let _ = writeln!(
        md,
        "- perceptual: SSIM (Wang et al. 2004: 11×11 Gaussian window, σ 1.5) of the display transform's luma; \
         time to SSIM {} from the measured levels, log–log between them \
         and beyond the highest along the last slope (which errs towards more samples)\n",
        targets.ssim
    );
}

fn markdown(sweep: &Sweep, views: &[KnobView], baseline: &SettingView, targets: Targets) -> String {
    let mut md = String::new();
    describe_sweep(&mut md, sweep, targets);
    let _ = writeln!(
        &mut md,
        "**Scene defaults** reach {} in {}, SSIM {} in {}.",
        percent(targets.error),
        time_to(baseline),
        targets.ssim,
        time_to_ssim(baseline)
    );
    if let Some((knob, s)) = fastest_to_target(views) {
        let _ = writeln!(
            &mut md,
            "**Fastest setting to {}**: {knob} = {}, {}.\n",
            percent(targets.error),
            s.label,
            time_to(s)
        );
    }
    for (view, knob) in views.iter().zip(&sweep.knobs) {
        let _ = writeln!(md, "## {}\n\n{}\n", view.name, view.about);
        if let Some(why) = view.skipped {
            let _ = writeln!(md, "Left out: {why}.\n");
            continue;
        }
        if view.name == "spp" {
            spp_table(&mut md, sweep, &knob.settings);
        }
        settings_table(&mut md, view, targets);
        if view.name == "denoise" {
            denoise_table(&mut md, &knob.settings);
        }
        let _ = writeln!(md, "\n![{}]({}.png)\n", view.name, view.name);
    }
    md
}

/// One row per setting of a knob: its speed, errors, times to the targets and whether it is on the front.
fn settings_table(md: &mut String, view: &KnobView, targets: Targets) {
    let builds = view.settings.iter().any(|s| s.build_seconds.is_some());
    let _ = writeln!(
        md,
        "| setting | ms/spp | rel. RMSE @ top | PSNR @ top | SSIM @ top | rel. mean error | bias | error in budget \
         | time to {} | time to SSIM {} |{} front |",
        percent(targets.error),
        targets.ssim,
        if builds { " BVH build |" } else { "" }
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|---|{}---|", if builds { "---|" } else { "" });
    for s in &view.settings {
        let build = match (builds, s.build_seconds) {
            (false, _) => String::new(),
            (true, Some(b)) => format!(" {:.1} ms |", b * 1e3),
            (true, None) => " – |".into(),
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.2} dB | {:.4} | {:+.2} % | {} | {} | {} | {} |{build} {} |",
            s.label,
            s.seconds_per_spp.map_or("–".into(), |t| format!("{:.3}", t * 1e3)),
            percent(s.top_relative_rmse),
            s.top_psnr_db,
            s.top_ssim,
            s.top_relative_mean_error * 100.0,
            s.relative_bias.map_or("–".into(), |b| if b > 0.0 { percent(b) } else { "0".into() }),
            s.error_in_budget.map_or("–".into(), percent),
            time_to(s),
            time_to_ssim(s),
            if s.on_front { "yes" } else { "dominated" }
        );
    }
}

/// The baseline's convergence: one row per level, and the log–log slope (−½ for pure noise).
fn spp_table(md: &mut String, sweep: &Sweep, settings: &[SettingResult]) {
    let Some(s) = settings.first() else { return };
    let mean = sweep.reference.mean;
    let _ = writeln!(md, "| spp | ms | rel. RMSE | PSNR | SSIM | rel. mean error |\n|---|---|---|---|---|---|");
    for m in &s.levels {
        let (rmse, psnr, ssim) = (m.error.relative_rmse(mean), m.error.psnr_db(), m.error.ssim);
        let rel = m.error.relative_mean_error * 100.0;
        let (spp, ms) = (m.spp, m.seconds * 1e3);
        let _ = writeln!(md, "| {spp} | {ms:.2} | {} | {psnr:.2} dB | {ssim:.4} | {rel:+.2} % |", percent(rmse));
    }
    let pts: Vec<(f64, f64)> = s.levels.iter().map(|m| (m.spp as f64, m.error.rmse())).collect();
    if let Some(slope) = super::model::log_log_slope(&pts) {
        let _ = writeln!(md, "\nLog–log slope of RMSE against spp: {slope:.3} (−0.5 when noise dominates).\n");
    }
}

/// The denoised images beside the time the raw render needs to look as good (same SSIM).
fn denoise_table(md: &mut String, settings: &[SettingResult]) {
    let (Some(off), Some(on)) = (settings.iter().find(|s| s.label == "off"), settings.iter().find(|s| s.label == "on"))
    else {
        return;
    };
    let _ = writeln!(
        md,
        "\nDenoised against raw at equal perceived quality: the raw render's time (and spp) to the SSIM the \
         denoised one has (from the raw levels, as above); a denoiser's bias keeps its RMSE above a few percent, \
         so this, not the time to 1 % RMSE, is what it buys.\n\n\
         | spp | denoised ms | SSIM | raw needs | speed-up |\n|---|---|---|---|---|"
    );
    for q in equal_quality(on, off) {
        let raw = match (q.plain_seconds, q.plain_spp) {
            (Some(t), Some(spp)) => format!("{}{} ({spp:.0} spp)", if q.extrapolated { "~" } else { "" }, duration(t)),
            _ => "∞".into(),
        };
        let speed_up = q.speed_up().map_or("–".into(), |x| format!("{x:.1}×"));
        let _ = writeln!(md, "| {} | {:.2} | {:.4} | {raw} | {speed_up} |", q.spp, q.seconds * 1e3, q.ssim);
    }
}

fn time_to_ssim(s: &SettingView) -> String {
    match (s.seconds_to_ssim, s.spp_to_ssim) {
        (Some(t), Some(spp)) => {
            format!("{}{} ({:.0} spp)", if s.ssim_extrapolated { "~" } else { "" }, duration(t), spp)
        }
        _ => "∞".into(),
    }
}

fn time_to(s: &SettingView) -> String {
    match (s.seconds_to_target, s.spp_to_target) {
        (Some(t), Some(spp)) => format!("{}{} ({:.0} spp)", if s.extrapolated { "~" } else { "" }, duration(t), spp),
        _ => "∞".into(),
    }
}

fn duration(seconds: f64) -> String {
    if seconds >= 1.0 { format!("{seconds:.2} s") } else { format!("{:.1} ms", seconds * 1e3) }
}

pub fn percent(v: f64) -> String {
    match v * 100.0 {
        p if !p.is_finite() => "–".into(),
        p if p >= 10.0 => format!("{p:.1} %"),
        p if p >= 0.1 => format!("{p:.2} %"),
        p => format!("{p:.3} %"),
    }
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) { format!("\"{}\"", s.replace('"', "\"\"")) } else { s.to_string() }
}

fn opt(v: Option<f64>) -> String {
    v.map_or(String::new(), |v| format!("{v:e}"))
}

pub const MEASUREMENT_COLUMNS: &str = "knob,setting,features,spp,seconds,seconds_min,seconds_max,rmse,relative_rmse,\
relative_mean_error,psnr_db,mse_std_error,build_seconds,dropped_samples,ssim,ssim_std_error";

fn measurements_csv(sweep: &Sweep) -> String {
    let mut csv = format!("{MEASUREMENT_COLUMNS}\n");
    let all = std::iter::once(("baseline", &sweep.baseline))
        .chain(sweep.knobs.iter().flat_map(|k| k.settings.iter().map(move |s| (k.name, s))));
    for (knob, s) in all {
        for m in &s.levels {
            let e = &m.error;
            let _ = writeln!(
                csv,
                "{knob},{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:.4},{:e},{},{},{:.6},{:e}",
                csv_field(&s.label),
                csv_field(&s.features.to_string()),
                m.spp,
                m.seconds,
                m.seconds_min,
                m.seconds_max,
                e.rmse(),
                e.relative_rmse(sweep.reference.mean),
                e.relative_mean_error,
                e.psnr_db(),
                m.mse_std_error,
                opt(s.build_seconds),
                m.dropped,
                e.ssim,
                m.ssim_std_error
            );
        }
    }
    csv
}

pub const SETTING_COLUMNS: &str = "knob,setting,seconds_per_spp,relative_bias,top_relative_rmse,top_psnr_db,\
error_in_budget,seconds_to_target,spp_to_target,extrapolated,on_front,build_seconds,top_ssim,seconds_to_ssim,\
spp_to_ssim";

fn settings_csv(views: &[KnobView]) -> String {
    let mut csv = format!("{SETTING_COLUMNS}\n");
    for k in views {
        for s in &k.settings {
            let _ = writeln!(
                csv,
                "{},{},{},{},{:e},{:.4},{},{},{},{},{},{},{:.6},{},{}",
                k.name,
                csv_field(&s.label),
                opt(s.seconds_per_spp),
                opt(s.relative_bias),
                s.top_relative_rmse,
                s.top_psnr_db,
                opt(s.error_in_budget),
                opt(s.seconds_to_target),
                opt(s.spp_to_target),
                s.extrapolated,
                s.on_front,
                opt(s.build_seconds),
                s.top_ssim,
                opt(s.seconds_to_ssim),
                opt(s.spp_to_ssim)
            );
        }
    }
    csv
}
