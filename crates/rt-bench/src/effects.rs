//! `rt bench effects`: the time per sample of the pipeline specialised to a scene's
//! feature set, of the all-features pipeline (the scene's sky and sampling kept), and
//! of the specialised one with each absent effect forced on: the measured price of
//! code that a scene does not need.

use super::timing::{render_timed, warm_up};
use anyhow::Result;
use indicatif::ProgressBar;
use rt::bvh::BuildQuality;
use rt::gpu::{GpuContext, GpuTimer};
use rt::gpu::{median, ms};
use rt::render::{RenderRequest, Session};
use rt::scene::{FLAGS, FeatureSet, RoughTransmission, Scene, Transmission};
use std::fmt::Write as _;
use std::time::Duration;

pub struct EffectTiming {
    pub label: String,
    pub features: FeatureSet,
    /// Median over repeats of the GPU time of one sample per pixel.
    pub ms_per_spp: f64,
    /// Mean luminance of the image: the same scene must give the same picture.
    pub mean_luminance: f64,
    /// Non-finite samples dropped over all repeats (a bug in that pipeline if above 0).
    pub dropped: u64,
}

pub struct EffectsReport {
    pub scene: String,
    pub adapter: String,
    pub timing: &'static str,
    pub size: (u32, u32),
    pub spp: u32,
    pub repeats: u32,
    /// Specialised first, all features second, then each forced effect.
    pub rows: Vec<EffectTiming>,
}

impl EffectsReport {
    /// How many times faster the specialised pipeline is than the all-features one.
    pub fn speedup(&self) -> f64 {
        self.rows[1].ms_per_spp / self.rows[0].ms_per_spp
    }

    pub fn markdown(&self) -> String {
        let mut md = format!(
            "# Cost of effects: {}\n\n- adapter: {}\n- timing: {}, median of {} repeats of {} spp at {}x{}\n\n\
             | pipeline | features | ms/spp | vs specialised | mean luminance | dropped samples |\n\
             |---|---|---|---|---|---|\n",
            self.scene, self.adapter, self.timing, self.repeats, self.spp, self.size.0, self.size.1
        );
        let base = self.rows[0].ms_per_spp;
        for r in &self.rows {
            let _ = writeln!(
                md,
                "| {} | {} | {:.3} | {:+.1} % | {:.4} | {} |",
                r.label,
                r.features,
                r.ms_per_spp,
                (r.ms_per_spp / base - 1.0) * 100.0,
                r.mean_luminance,
                r.dropped
            );
        }
        let _ = writeln!(
            md,
            "\nSpecialised over all-features: **{:.2}×** faster. Every pipeline but one without an \
             effect (−) renders the same picture: their mean luminances should differ by noise only.",
            self.speedup()
        );
        md
    }
}

/// The pipelines to time: the scene's, all features, the scene's plus each absent effect,
/// and, for a scene with node graphs, the scene's without them (each material's constants:
/// the graphs' price against the same materials without them; another picture); for a
/// scene that moves, the scene's without motion blur (its price; another picture); for
/// specialised node programs, the same programs interpreted.
pub fn variants(own: FeatureSet, rough: RoughTransmission) -> Vec<(String, FeatureSet)> {
    let mut v = vec![
        ("specialised".to_string(), own),
        ("all features".to_string(), FeatureSet::all(own.sky, own.sampling, rough)),
    ];
    if own.node_graphs {
        v.push(("−node graphs (constants)".to_string(), FeatureSet { node_graphs: false, ..own }));
    }
    if own.node_graphs && own.node_code != 0 {
        // The same programs through the interpreter, which scenes with many shapes run.
        v.push(("node graphs interpreted".to_string(), FeatureSet { node_code: 0, ..own }));
    }
    if own.camera_motion || own.object_motion {
        // Everything where the frame has it (another picture; the top level still bounds the sweeps).
        let sharp = FeatureSet { camera_motion: false, object_motion: false, ..own };
        v.push(("−motion (sharp)".to_string(), sharp));
    }
    if own.transmission == Transmission::None {
        v.push(("+glass".to_string(), FeatureSet { transmission: Transmission::Smooth, ..own }));
    }
    if !matches!(own.transmission, Transmission::Rough(_)) {
        v.push(("+rough glass".to_string(), FeatureSet { transmission: Transmission::Rough(rough), ..own }));
    }
    // Each priced flag the scene lacks, with what its code needs (media their glass,
    // normal maps the texture code).
    for flag in FLAGS.iter().filter(|flag| flag.priced() && !(flag.get)(&own)) {
        let mut forced = own;
        (flag.set)(&mut forced, true);
        forced.complete();
        v.push((format!("+{}", flag.words()), forced));
    }
    // Each lobe module the scene's materials do not use: its code behind its flag, untaken.
    for (i, lobe) in rt::scene::lobe::LOBES.iter().enumerate() {
        let bit = rt::scene::lobe::bit(i);
        if own.lobe_modules & bit == 0 {
            v.push((format!("+{} lobe", lobe.name), FeatureSet { lobe_modules: own.lobe_modules | bit, ..own }));
        }
    }
    v
}

pub fn effects(
    ctx: &GpuContext,
    scene: Scene,
    (width, height): (u32, u32),
    spp: u32,
    repeats: u32,
    bar: &ProgressBar,
) -> Result<EffectsReport> {
    let timer = GpuTimer::new(ctx);
    let rough = scene.render.rough_transmission;
    let origin = scene.origin.clone();
    let mut session = Session::open(ctx, scene, BuildQuality::default())?;
    let mut request = RenderRequest::from_scene(session.scene());
    (request.width, request.height, request.spp) = (width, height, spp.max(1));
    // Fixed dispatches: every pipeline does the same work in the same steps.
    request.samples_per_dispatch = Some(request.spp.min(16));
    let variants = variants(session.features(), rough);
    bar.set_length((variants.len() as u64) * (repeats.max(1) as u64 + 1));
    for (_, features) in &variants {
        let exact_sums = features.exact_sums;
        warm_up(&mut session, &RenderRequest { features: Some(*features), exact_sums, ..request.clone() }, &timer)?;
        bar.inc(1);
    }
    // Interleaved, so that a machine growing busier or cooler does not favour one pipeline.
    let mut times: Vec<Vec<Duration>> = vec![Vec::new(); variants.len()];
    let mut luminance = vec![0.0; variants.len()];
    let mut dropped = vec![0u64; variants.len()];
    for repeat in 0..repeats.max(1) {
        for (i, (_, features)) in variants.iter().enumerate() {
            let exact_sums = features.exact_sums;
            let r = RenderRequest { features: Some(*features), exact_sums, seed: repeat + 1, ..request.clone() };
            let render = render_timed(&mut session, &r, &timer)?;
            times[i].push(render.time);
            dropped[i] += render.dropped;
            let pixels = &render.image.pixels;
            let sum: f64 = pixels.iter().map(|p| rt::scene::luminance(*p) as f64).sum();
            luminance[i] += sum / pixels.len().max(1) as f64 / repeats.max(1) as f64;
            bar.inc(1);
        }
    }
    let rows = variants
        .into_iter()
        .zip(times)
        .zip(luminance)
        .zip(dropped)
        .map(|((((label, features), t), mean_luminance), dropped)| EffectTiming {
            label,
            features,
            ms_per_spp: ms(median(t)) / request.spp as f64,
            mean_luminance,
            dropped,
        })
        .collect();
    Ok(EffectsReport {
        scene: origin,
        adapter: ctx.describe(),
        timing: timer.method(),
        size: (width, height),
        spp: request.spp,
        repeats: repeats.max(1),
        rows,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rt::scene::{Sampling, SkyFeature};

    /// Every priced flag of the declaration: a scene without it (all features but it) is
    /// timed with it forced on too, as variant `+name` (the whole set again); one with it is not.
    #[test]
    fn every_priced_flag_is_among_the_forced_effects() {
        let all = FeatureSet::all(SkyFeature::Uniform, Sampling::Nee, RoughTransmission::Ggx);
        for flag in FLAGS.iter().filter(|flag| flag.priced()) {
            let (mut with, mut without) = (all, all);
            (flag.set)(&mut with, true);
            (flag.set)(&mut without, false);
            let name = format!("+{}", flag.words());
            let forced: Vec<_> =
                variants(without, RoughTransmission::Ggx).into_iter().filter(|(n, _)| *n == name).collect();
            assert!(matches!(&forced[..], [(_, f)] if *f == with), "{name}: {forced:?}");
            assert!(variants(with, RoughTransmission::Ggx).iter().all(|(n, _)| *n != name), "{name}");
        }
        assert!(FLAGS.iter().filter(|flag| flag.priced()).count() > 20);
        // And every lobe module: forced where no material uses it, not where one does.
        let plain = FeatureSet { lobe_modules: 0, ..all };
        let forced: Vec<_> =
            variants(plain, RoughTransmission::Ggx).into_iter().filter(|(n, _)| n == "+toon lobe").collect();
        assert!(matches!(&forced[..], [(_, f)] if f.lobe_modules == 1), "{forced:?}");
        assert!(variants(all, RoughTransmission::Ggx).iter().all(|(n, _)| n != "+toon lobe"));
    }
}
