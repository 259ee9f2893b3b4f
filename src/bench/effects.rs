//! `rt bench effects`: the time per sample of the pipeline specialised to a scene's
//! feature set, of the all-features pipeline (the scene's sky and sampling kept), and
//! of the specialised one with each absent effect forced on: the measured price of
//! code that a scene does not need.

use super::timing::{render_timed, warm_up};
use crate::bvh::BuildQuality;
use crate::gpu::{GpuContext, GpuTimer};
use crate::gpu::{median, ms};
use crate::render::{RenderRequest, Session};
use crate::scene::{FeatureSet, RoughTransmission, Scene, Transmission};
use anyhow::Result;
use indicatif::ProgressBar;
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
    let mut force = |name: &str, on: bool, f: FeatureSet| {
        if !on {
            v.push((format!("+{name}"), f));
        }
    };
    force("triangles", own.triangles, FeatureSet { triangles: true, ..own });
    force("spheres", own.spheres, FeatureSet { spheres: true, ..own });
    force("emission", own.emission, FeatureSet { emission: true, ..own });
    force("sun", own.sun, FeatureSet { sun: true, ..own });
    force("glossy", own.glossy, FeatureSet { glossy: true, ..own });
    force("glass", own.transmission != Transmission::None, FeatureSet { transmission: Transmission::Smooth, ..own });
    let rough_on = matches!(own.transmission, Transmission::Rough(_));
    force("rough glass", rough_on, FeatureSet { transmission: Transmission::Rough(rough), ..own });
    // Media live inside glass: forcing them on forces (at least smooth) glass too.
    let glass = if own.transmission == Transmission::None { Transmission::Smooth } else { own.transmission };
    force("media", own.media, FeatureSet { media: true, transmission: glass, ..own });
    force("sheen", own.sheen, FeatureSet { sheen: true, ..own });
    force("anisotropy", own.anisotropy, FeatureSet { anisotropy: true, ..own });
    force("thin film", own.thin_film, FeatureSet { thin_film: true, ..own });
    force("rough diffuse", own.rough_diffuse, FeatureSet { rough_diffuse: true, ..own });
    // Smooth shading reads triangles' vertices and normals: forcing it on forces triangles too.
    force("smooth normals", own.smooth_normals, FeatureSet { smooth_normals: true, triangles: true, ..own });
    // The terminator shift reads the shaded instance's settings: triangles come with it.
    force("terminator offset", own.terminator_offset, FeatureSet { terminator_offset: true, triangles: true, ..own });
    // The holdout test of each shaded surface reads the instance's settings: triangles come with it.
    force("holdout", own.holdout, FeatureSet { holdout: true, triangles: true, ..own });
    // Motion blur's code where nothing moves: a time per sample, and the camera's frame or
    // each instance's motion looked up at it.
    force("camera motion", own.camera_motion, FeatureSet { camera_motion: true, ..own });
    force("object motion", own.object_motion, FeatureSet { object_motion: true, ..own });
    // Texture lookups alone, so that the normal maps' own share of their price shows.
    force("textures", own.textures, FeatureSet { textures: true, ..own });
    // Normal maps are texture lookups: forcing them on forces the texture code too.
    force("normal maps", own.normal_maps, FeatureSet { normal_maps: true, textures: true, ..own });
    force("second uv sets", own.uv_sets, FeatureSet { uv_sets: true, textures: true, ..own });
    force("layer textures", own.layer_textures, FeatureSet { layer_textures: true, textures: true, ..own });
    // The node programs' interpreter, present (its price where no material runs it).
    force("node graphs", own.node_graphs, FeatureSet { node_graphs: true, textures: true, glossy: true, ..own });
    // The coat's own normal map: the coat and the normal-map code come with it.
    force(
        "coat normal",
        own.coat_normal,
        FeatureSet { coat_normal: true, coat: true, normal_maps: true, textures: true, ..own },
    );
    force("uv tangents", own.uv_tangents, FeatureSet { uv_tangents: true, anisotropy: true, ..own });
    // `rt render`'s exact sums beside the running means (asked for by the request, see `effects`).
    force("exact sums", own.exact_sums, FeatureSet { exact_sums: true, ..own });
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
            let sum: f64 = pixels.iter().map(|p| crate::scene::luminance(*p) as f64).sum();
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
    use crate::scene::{Sampling, SkyFeature};

    /// A scene without the effect (`all` with it turned off) is timed with it forced on too,
    /// as variant `name` (the whole set again); one with it is not.
    fn forced_once(name: &str, off: impl Fn(FeatureSet) -> FeatureSet) {
        let all = FeatureSet::all(SkyFeature::Uniform, Sampling::Nee, RoughTransmission::Ggx);
        let forced: Vec<_> =
            variants(off(all), RoughTransmission::Ggx).into_iter().filter(|(n, _)| n == name).collect();
        assert!(matches!(&forced[..], [(_, f)] if *f == all), "{name}: {forced:?}");
        assert!(variants(all, RoughTransmission::Ggx).iter().all(|(n, _)| n != name), "{name}");
    }

    #[test]
    fn thin_film_is_among_the_forced_effects() {
        forced_once("+thin film", |f| FeatureSet { thin_film: false, ..f });
    }

    /// Likewise the rough (Oren-Nayar) diffuse.
    #[test]
    fn rough_diffuse_is_among_the_forced_effects() {
        forced_once("+rough diffuse", |f| FeatureSet { rough_diffuse: false, ..f });
    }

    #[test]
    fn coat_normal_is_among_the_forced_effects() {
        forced_once("+coat normal", |f| FeatureSet { coat_normal: false, ..f });
    }

    #[test]
    fn terminator_offset_is_among_the_forced_effects() {
        forced_once("+terminator offset", |f| FeatureSet { terminator_offset: false, ..f });
    }

    #[test]
    fn holdout_is_among_the_forced_effects() {
        forced_once("+holdout", |f| FeatureSet { holdout: false, ..f });
    }

    #[test]
    fn motion_is_among_the_forced_effects() {
        forced_once("+camera motion", |f| FeatureSet { camera_motion: false, ..f });
        forced_once("+object motion", |f| FeatureSet { object_motion: false, ..f });
    }
}
