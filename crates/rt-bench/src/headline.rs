//! `rt bench headline`: the three headline tables for three bundled scenes (an
//! interior with glass, the dragon among mirror spheres, and the sunlit pillars as
//! the outdoor scene until the atmosphere renders a sunset): the fastest setting to
//! reach 1 % RMSE, the speed-up of the specialised pipeline over the all-features
//! one, and the fireflies of each sampling strategy. Optionally spliced into docs/benchmarks.md.

use super::accuracy::{AccuracyOptions, accuracy};
use super::effects::{EffectsReport, effects};
use super::fireflies::{FireflyOptions, FireflyReport, fireflies};
use super::report::{AccuracySummary, percent};
use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
use rt::gpu::GpuContext;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

pub const HEADLINE_SCENES: [&str; 3] =
    ["scenes/cornell_glass.toml", "scenes/dragon_mirror_spheres.toml", "scenes/sunset.toml"];
/// The scene whose fireflies are measured: the seed's failure case.
pub const FIREFLY_SCENE: &str = "scenes/specular_pillars.toml";
pub const README_BEGIN: &str = "<!-- rt bench headline: begin -->";
pub const README_END: &str = "<!-- rt bench headline: end -->";

#[derive(Clone, Debug)]
pub struct HeadlineOptions {
    /// Reports go to `accuracy.out/<scene>/`, the tables to `accuracy.out/headline.md`.
    pub accuracy: AccuracyOptions,
    /// Repository root: the scenes are found under it.
    pub root: PathBuf,
    pub effects_spp: u32,
    pub effects_repeats: u32,
    pub fireflies: FireflyOptions,
    /// README to rewrite between its headline markers.
    pub readme: Option<PathBuf>,
}

pub fn headline(ctx: &GpuContext, options: &HeadlineOptions) -> Result<String> {
    let out = &options.accuracy.out;
    let mut summaries = Vec::new();
    let mut costs = Vec::new();
    for scene_file in HEADLINE_SCENES {
        let path = options.root.join(scene_file);
        let scene = rt::scene::load(&path)?;
        let stem = path.file_stem().map_or("scene".into(), |s| s.to_string_lossy().into_owned());
        eprintln!("{}: accuracy", path.display());
        let accuracy_options = AccuracyOptions { out: out.join(&stem), ..options.accuracy.clone() };
        summaries.push(accuracy(ctx, &scene, &accuracy_options)?);
        eprintln!("{}: effects", path.display());
        let size = accuracy_options.sweep_options(ctx)?.size;
        let bar = bar(options.accuracy.progress);
        let report = effects(ctx, scene, size, options.effects_spp, options.effects_repeats, &bar)?;
        bar.finish_and_clear();
        write(&out.join(&stem).join("effects.md"), &report.markdown())?;
        costs.push(report);
    }
    eprintln!("{FIREFLY_SCENE}: fireflies");
    let scene = rt::scene::load(&options.root.join(FIREFLY_SCENE))?;
    let bar = bar(options.accuracy.progress);
    let firefly = fireflies(ctx, &scene, &options.fireflies, &bar)?;
    bar.finish_and_clear();
    write(&out.join("fireflies.md"), &firefly.markdown())?;
    let tables = tables(&summaries, &costs, &firefly);
    write(&out.join("headline.md"), &tables)?;
    if let Some(readme) = &options.readme {
        splice_readme(readme, &tables)?;
    }
    Ok(tables)
}

fn bar(visible: bool) -> ProgressBar {
    if visible { ProgressBar::new(1) } else { ProgressBar::hidden() }
}

fn write(path: &Path, text: &str) -> Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    Ok(rt::files::write_atomically(path, text.as_bytes())?)
}

fn scene_name(origin: &str) -> String {
    Path::new(origin).file_stem().map_or(origin.to_string(), |s| s.to_string_lossy().into_owned())
}

/// The three tables, in Markdown.
pub fn tables(summaries: &[AccuracySummary], costs: &[EffectsReport], firefly: &FireflyReport) -> String {
    let mut md = String::new();
    let adapter = summaries.first().map_or(String::new(), |s| s.adapter.clone());
    let target = summaries.first().map_or(0.01, |s| s.targets.error);
    let _ = writeln!(md, "Measured on {adapter} by `rt bench headline` (GPU time).\n");
    let _ = writeln!(
        md,
        "| scene | scene defaults to {0} RMSE | fastest setting to {0} | its time | speed-up |\n|---|---|---|---|---|",
        percent(target)
    );
    for s in summaries {
        let base = s.baseline.map_or("∞".into(), |(t, extrapolated)| approx(t, extrapolated));
        let (setting, time, speedup) = match (&s.fastest, s.baseline) {
            (Some((knob, label, spp, t, extrapolated)), base) => (
                format!("{knob} = {label} ({spp:.0} spp)"),
                approx(*t, *extrapolated),
                base.map_or("–".into(), |(b, _)| format!("{:.2}×", b / t)),
            ),
            (None, _) => ("none reaches it".into(), "–".into(), "–".into()),
        };
        let _ = writeln!(md, "| {} | {base} | {setting} | {time} | {speedup} |", scene_name(&s.scene));
    }
    let _ = writeln!(
        md,
        "\nRMSE relative to the reference's mean radiance; times from the models fitted to each setting \
         (`~`: beyond 4× the highest spp measured); speed-up: the scene defaults' time over the fastest's."
    );
    let _ = writeln!(
        md,
        "\n| scene | features | specialised ms/spp | all-features ms/spp | speed-up |\n|---|---|---|---|---|"
    );
    for c in costs {
        let _ = writeln!(
            md,
            "| {} | {} | {:.3} | {:.3} | {:.2}× |",
            scene_name(&c.scene),
            c.rows[0].features,
            c.rows[0].ms_per_spp,
            c.rows[1].ms_per_spp,
            c.speedup()
        );
    }
    let _ = writeln!(
        md,
        "\n| {} | share of energy in the brightest 0.01 % of samples | pixel noise ({} spp) | mean vs NEE |\n|---|---|---|---|",
        scene_name(&firefly.scene),
        firefly.options.samples
    );
    let reference = firefly.rows.first().map_or(1.0, |r| r.mean_luminance);
    for r in &firefly.rows {
        let _ = writeln!(
            md,
            "| {}{} | {:.2} % | {:.1} % | {:+.1} % |",
            r.strategy,
            if r.biased { format!(" at {:.2} (biased)", firefly.clamp) } else { String::new() },
            r.top_share * 100.0,
            r.pixel_noise * 100.0,
            (r.mean_luminance / reference - 1.0) * 100.0
        );
    }
    md
}

/// `~` before a time predicted beyond 4× the highest level measured.
fn approx(seconds: f64, extrapolated: bool) -> String {
    let s = if seconds >= 1.0 { format!("{seconds:.2} s") } else { format!("{:.1} ms", seconds * 1e3) };
    if extrapolated { format!("~{s}") } else { s }
}

/// Replaces what lies between the headline markers of `readme` with `tables`.
pub fn splice_readme(readme: &Path, tables: &str) -> Result<()> {
    let text = rt::files::read_to_string(readme)?;
    let (Some(begin), Some(end)) = (text.find(README_BEGIN), text.find(README_END)) else {
        bail!("{}: no {README_BEGIN} … {README_END} section to replace", readme.display());
    };
    if end < begin {
        bail!("{}: {README_END} comes before {README_BEGIN}", readme.display());
    }
    let spliced = format!("{}{README_BEGIN}\n{tables}{}", &text[..begin], &text[end..]);
    Ok(rt::files::write_atomically(readme, spliced.as_bytes())?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splicing_replaces_only_the_marked_section() {
        let path = std::env::temp_dir().join(format!("rt-readme-{}.md", std::process::id()));
        std::fs::write(&path, format!("intro\n{README_BEGIN}\nold\n{README_END}\noutro\n")).expect("write");
        splice_readme(&path, "| new |\n").expect("splice");
        let text = std::fs::read_to_string(&path).expect("read");
        assert_eq!(text, format!("intro\n{README_BEGIN}\n| new |\n{README_END}\noutro\n"));
        std::fs::write(&path, "no markers\n").expect("write");
        assert!(splice_readme(&path, "x").is_err_and(|e| e.to_string().contains("rt-readme")));
        let _ = std::fs::remove_file(path);
    }
}
