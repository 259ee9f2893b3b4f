//! `rt bench fireflies`: fireflies measured, not hidden. Per sampling strategy (and
//! with a luminance clamp, which is biased: it removes energy), the scene is rendered
//! one sample per pixel at a time with independent seeds, which gives every sample's
//! value. From them: the share of all energy carried by the brightest 0.01 % of
//! samples (near 0.01 % for a well-behaved estimator; fireflies push it up), and the
//! noise of a pixel's mean over several seeds.

use super::timing::{render_timed, warm_up};
use anyhow::Result;
use indicatif::ProgressBar;
use rt::bvh::BuildQuality;
use rt::gpu::{GpuContext, GpuTimer};
use rt::render::{RenderRequest, Session};
use rt::scene::{Sampling, Scene, luminance};
use std::fmt::Write as _;

/// The brightest share of samples whose energy is reported.
pub const TOP_FRACTION: f64 = 1e-4;

#[derive(Clone, Debug)]
pub struct FireflyOptions {
    pub size: (u32, u32),
    /// Samples per pixel of each seed's image.
    pub samples: u32,
    /// Independent images per strategy, for the noise of pixel means.
    pub seeds: u32,
    /// Clamp luminance; `None`: ten times the mean luminance of the NEE image.
    pub clamp: Option<f32>,
}

#[derive(Clone, Debug)]
pub struct FireflyRow {
    pub strategy: String,
    pub biased: bool,
    pub mean_luminance: f64,
    /// Share of the summed luminance of all samples in the brightest [`TOP_FRACTION`] of them.
    pub top_share: f64,
    /// The brightest sample over the mean.
    pub peak_over_mean: f64,
    /// Standard deviation of a pixel's mean across seeds, averaged over pixels, over the mean.
    pub pixel_noise: f64,
    pub ms_per_spp: f64,
}

pub struct FireflyReport {
    pub scene: String,
    pub adapter: String,
    pub options: FireflyOptions,
    pub clamp: f32,
    pub rows: Vec<FireflyRow>,
}

impl FireflyReport {
    pub fn markdown(&self) -> String {
        let o = &self.options;
        let mut md = format!(
            "# Fireflies: {}\n\n- adapter: {}\n- {}x{}, {} seeds × {} spp per strategy, every sample kept\n\
             - top 0.01 %: share of all energy in the brightest 0.01 % of samples (about 0.01 % without fireflies)\n\
             - pixel noise: standard deviation of a {}-spp pixel mean across seeds, over the mean\n\
             - clamp at luminance {:.3}: biased (bright light goes missing; see the mean)\n\n\
             | strategy | top 0.01 % | brightest / mean | pixel noise | mean luminance | vs NEE | ms/spp |\n\
             |---|---|---|---|---|---|---|\n",
            self.scene, self.adapter, o.size.0, o.size.1, o.seeds, o.samples, o.samples, self.clamp
        );
        let reference = self.rows.first().map_or(1.0, |r| r.mean_luminance);
        for r in &self.rows {
            let _ = writeln!(
                md,
                "| {}{} | {:.2} % | {:.0} | {:.1} % | {:.4} | {:+.1} % | {:.3} |",
                r.strategy,
                if r.biased { " (biased)" } else { "" },
                r.top_share * 100.0,
                r.peak_over_mean,
                r.pixel_noise * 100.0,
                r.mean_luminance,
                (r.mean_luminance / reference - 1.0) * 100.0,
                r.ms_per_spp
            );
        }
        md
    }
}

pub fn fireflies(
    ctx: &GpuContext,
    scene: &Scene,
    options: &FireflyOptions,
    bar: &ProgressBar,
) -> Result<FireflyReport> {
    let timer = GpuTimer::new(ctx);
    let per_strategy = (options.samples.max(1) * options.seeds.max(2)) as u64;
    bar.set_length(4 * per_strategy);
    let mut rows = Vec::new();
    let mut clamp = options.clamp;
    for sampling in [Sampling::Nee, Sampling::Resampled] {
        let mut scene = scene.clone();
        scene.render.sampling = sampling;
        let mut session = Session::open(ctx, scene, BuildQuality::default())?;
        let name = format!("{sampling:?}").to_lowercase();
        let unclamped = measure(&mut session, options, None, &timer, bar)?;
        let level = *clamp.get_or_insert((10.0 * unclamped.mean_luminance) as f32);
        rows.push(FireflyRow { strategy: name.clone(), ..unclamped });
        let clamped = measure(&mut session, options, Some(level), &timer, bar)?;
        rows.push(FireflyRow { strategy: format!("{name} + clamp"), biased: true, ..clamped });
    }
    Ok(FireflyReport {
        scene: scene.origin.clone(),
        adapter: ctx.describe(),
        options: options.clone(),
        clamp: clamp.unwrap_or(0.0),
        rows,
    })
}

fn measure(
    session: &mut Session,
    options: &FireflyOptions,
    clamp: Option<f32>,
    timer: &GpuTimer,
    bar: &ProgressBar,
) -> Result<FireflyRow> {
    let mut request = RenderRequest::from_scene(session.scene());
    (request.width, request.height, request.spp, request.clamp) = (options.size.0, options.size.1, 1, clamp);
    request.samples_per_dispatch = Some(1);
    warm_up(session, &request, timer)?;
    let (samples, seeds) = (options.samples.max(1), options.seeds.max(2));
    let pixels = (options.size.0 * options.size.1) as usize;
    let mut values: Vec<f32> = Vec::with_capacity(pixels * (samples * seeds) as usize);
    // Per seed, per pixel: the mean over that seed's samples.
    let mut means = vec![vec![0.0f64; pixels]; seeds as usize];
    let mut seconds = 0.0;
    for seed in 0..seeds {
        for sample in 0..samples {
            let r = RenderRequest { seed: 1 + seed * samples + sample, ..request.clone() };
            let render = render_timed(session, &r, timer)?;
            seconds += render.time.as_secs_f64();
            for (mean, p) in means[seed as usize].iter_mut().zip(&render.image.pixels) {
                let y = luminance(*p);
                values.push(y);
                *mean += y as f64 / samples as f64;
            }
            bar.inc(1);
        }
    }
    let total: f64 = values.iter().map(|&v| v as f64).sum();
    let mean_luminance = total / values.len().max(1) as f64;
    let top = ((values.len() as f64 * TOP_FRACTION).ceil() as usize).clamp(1, values.len().max(1));
    let top_share = if values.is_empty() || total <= 0.0 {
        0.0
    } else {
        let split = values.len() - top;
        values.select_nth_unstable_by(split, f32::total_cmp);
        values[split..].iter().map(|&v| v as f64).sum::<f64>() / total
    };
    let peak = values.iter().copied().fold(0.0f32, f32::max) as f64;
    let variance: f64 = (0..pixels)
        .map(|p| {
            let m: f64 = means.iter().map(|s| s[p]).sum::<f64>() / seeds as f64;
            means.iter().map(|s| (s[p] - m).powi(2)).sum::<f64>() / (seeds - 1) as f64
        })
        .sum::<f64>()
        / pixels.max(1) as f64;
    Ok(FireflyRow {
        strategy: String::new(),
        biased: clamp.is_some(),
        mean_luminance,
        top_share,
        peak_over_mean: if mean_luminance > 0.0 { peak / mean_luminance } else { 0.0 },
        pixel_noise: if mean_luminance > 0.0 { variance.sqrt() / mean_luminance } else { 0.0 },
        ms_per_spp: seconds * 1e3 / (samples * seeds) as f64,
    })
}
