//! The knobs that trade accuracy for time. A knob is a name, its settings, and for
//! each setting a function that applies it to a [`Trial`]: what to render and how.
//! A knob that changes the scene (its render settings, or the atmosphere's steps
//! and table sizes) is measured on a session built for the
//! changed scene, so new knobs slot in without changes to the sweep.

use clap::ValueEnum;
use rt::bvh::BuildQuality;
use rt::render::RenderRequest;
use rt::scene::{
    Atmosphere, FeatureSet, LightSampler, RoughTransmission, Sampling, Scene, Sky, SkyFeature, Transmission,
};

/// One configuration to measure: the scene as the session is built for it, the
/// request, and how its BVHs are built.
#[derive(Clone, Debug)]
pub struct Trial {
    pub scene: Scene,
    pub request: RenderRequest,
    pub quality: BuildQuality,
    /// Build every BVH afresh in memory (and time it) rather than load caches.
    pub fresh_bvh: bool,
    /// Denoise each image with Open Image Denoise (its time counts) before measuring it.
    pub denoise: bool,
}

impl Trial {
    /// The scene as it is, at `width`×`height`.
    pub fn baseline(scene: &Scene, (width, height): (u32, u32)) -> Self {
        let mut request = RenderRequest::from_scene(scene);
        (request.width, request.height) = (width, height);
        Self { scene: scene.clone(), request, quality: BuildQuality::default(), fresh_bvh: false, denoise: false }
    }

    /// Whether `other` renders the same thing the same way (so its measurements can be reused).
    pub fn same_as(&self, other: &Trial) -> bool {
        self.scene == other.scene
            && self.quality == other.quality
            && self.fresh_bvh == other.fresh_bvh
            && self.denoise == other.denoise
            && self.request == other.request
    }
}

pub struct Setting {
    pub label: String,
    apply: Box<dyn Fn(&mut Trial)>,
}

impl Setting {
    fn new(label: impl Into<String>, apply: impl Fn(&mut Trial) + 'static) -> Self {
        Self { label: label.into(), apply: Box::new(apply) }
    }

    /// The trial with this setting applied to it.
    pub fn trial(&self, baseline: &Trial) -> Trial {
        let mut trial = baseline.clone();
        (self.apply)(&mut trial);
        trial
    }
}

pub struct Knob {
    /// As `--knob` names it.
    pub name: &'static str,
    pub about: &'static str,
    pub settings: Vec<Setting>,
    /// Samples per pixel to measure each setting at, instead of the sweep's levels.
    pub spp_levels: Option<Vec<u32>>,
    /// Why the knob changes nothing in a scene with these features, if it does not.
    pub inapplicable: fn(&FeatureSet) -> Option<&'static str>,
}

impl Knob {
    /// A knob measured at the sweep's own levels.
    fn new(
        name: &'static str,
        about: &'static str,
        settings: Vec<Setting>,
        inapplicable: fn(&FeatureSet) -> Option<&'static str>,
    ) -> Self {
        Knob { name, about, settings, spp_levels: None, inapplicable }
    }
}

fn always(_: &FeatureSet) -> Option<&'static str> {
    None
}

fn without_rough_glass(f: &FeatureSet) -> Option<&'static str> {
    match f.transmission {
        Transmission::Rough(_) => None,
        _ => Some("the scene has no rough glass"),
    }
}

fn without_atmosphere(f: &FeatureSet) -> Option<&'static str> {
    match f.sky {
        SkyFeature::Atmosphere => None,
        _ => Some("the sky is not an atmosphere"),
    }
}

fn without_tree_lights(f: &FeatureSet) -> Option<&'static str> {
    let lamps = f.lamps.point || f.lamps.spot || f.lamps.area;
    match (f.sampling, f.emission || lamps) {
        (Sampling::Nee, true) => None,
        (Sampling::Nee, false) => Some("the scene has no emitters nor lamps other than suns"),
        (Sampling::Resampled, _) => Some("resampled sampling samples no lights"),
    }
}

fn without_denoiser(_: &FeatureSet) -> Option<&'static str> {
    match rt::denoise::Denoiser::new(rt::denoise::DenoiseDevice::Auto) {
        Ok(_) => None,
        Err(_) => Some("this rt cannot denoise (built without Open Image Denoise, or it has no device)"),
    }
}

/// Changes the scene's atmosphere, if its sky is one.
fn with_atmosphere(trial: &mut Trial, change: impl Fn(&mut Atmosphere)) {
    if let Sky::Atmosphere(a) = &mut trial.scene.sky {
        change(a);
    }
}

/// The noise threshold of the `clean-image` knob's adaptive settings: the loosest of the
/// `adaptive` knob's, the one that saves samples at the levels a denoiser is used at.
const CLEAN_IMAGE_THRESHOLD: f32 = 0.05;

/// Every knob, in report order; `levels` are the sweep's samples-per-pixel levels.
pub fn all_knobs(levels: &[u32]) -> Vec<Knob> {
    let (lo, hi) = (levels.iter().copied().min().unwrap_or(1), levels.iter().copied().max().unwrap_or(1));
    let ladder: Vec<u32> = (0..32).map(|i| 1u32 << i).filter(|s| (lo..=hi).contains(s)).collect();
    let spp = Knob {
        name: "spp",
        about: "samples per pixel, at the scene's own settings: the convergence of the baseline",
        settings: vec![Setting::new("scene defaults", |_| {})],
        spp_levels: Some(if ladder.len() >= 3 { ladder } else { levels.to_vec() }),
        inapplicable: always,
    };
    let groups = [vec![spp], estimator_knobs(), engine_knobs(), clean_image_knobs(), atmosphere_knobs()];
    groups.into_iter().flatten().collect()
}

/// The estimator's settings: path length, how paths find light, the rough-glass model.
fn estimator_knobs() -> Vec<Knob> {
    vec![
        Knob::new(
            "max-bounces",
            "path length cap (biased: light that needs more bounces is missing)",
            [1u32, 2, 3, 4, 6, 8, 12, 16]
                .into_iter()
                .map(|b| Setting::new(format!("{b}"), move |t| t.request.max_bounces = b))
                .collect(),
            always,
        ),
        Knob::new(
            "sampling",
            "how paths find light: resampled BSDF directions, or next-event estimation with MIS",
            [Sampling::Resampled, Sampling::Nee]
                .into_iter()
                .map(|s| Setting::new(format!("{s:?}").to_lowercase(), move |t| t.scene.render.sampling = s))
                .collect(),
            always,
        ),
        Knob::new(
            "light-sampler",
            "how light sampling picks a lamp or emitter: by power, or down the light tree by importance",
            [LightSampler::Power, LightSampler::Tree]
                .into_iter()
                .map(|s| Setting::new(format!("{s:?}").to_lowercase(), move |t| t.scene.render.light_sampler = s))
                .collect(),
            without_tree_lights,
        ),
        Knob::new(
            "ris-candidates",
            "candidates M per resampled direction, with resampled sampling",
            [1u32, 2, 4, 8, 16, 32]
                .into_iter()
                .map(|m| {
                    Setting::new(format!("M={m}"), move |t| {
                        t.scene.render.sampling = Sampling::Resampled;
                        t.request.ris_candidates = m;
                    })
                })
                .collect(),
            always,
        ),
        Knob::new(
            "rough-glass",
            "model of rough refraction: GGX microfacets, or the seed's cone (cheaper, biased)",
            [RoughTransmission::Ggx, RoughTransmission::Cone]
                .into_iter()
                .map(|r| Setting::new(format!("{r:?}").to_lowercase(), move |t| t.scene.render.rough_transmission = r))
                .collect(),
            without_rough_glass,
        ),
    ]
}

/// How the work is laid out on the GPU: the BVH's build quality and the dispatch size (the image does not change).
fn engine_knobs() -> Vec<Knob> {
    vec![
        Knob::new(
            "bvh-quality",
            "BVH build quality: build time against trace time (the image does not change)",
            [BuildQuality::Fastest, BuildQuality::Medium, BuildQuality::Slow, BuildQuality::VerySlow]
                .into_iter()
                .map(|q| {
                    let name = q.to_possible_value().map_or(format!("{q:?}"), |v| v.get_name().to_string());
                    Setting::new(name, move |t| {
                        t.quality = q;
                        t.fresh_bvh = true;
                    })
                })
                .collect(),
            always,
        ),
        Knob::new(
            "samples-per-dispatch",
            "samples per pixel in one GPU dispatch (auto: sized to ~80 ms, as `rt render` does)",
            [Some(1u32), Some(4), Some(16), Some(64), None]
                .into_iter()
                .map(|n| {
                    let label = n.map_or("auto".to_string(), |n| n.to_string());
                    Setting::new(label, move |t| t.request.samples_per_dispatch = n)
                })
                .collect(),
            always,
        ),
    ]
}

/// The ways to a clean image: denoising, adaptive sampling, and both.
fn clean_image_knobs() -> Vec<Knob> {
    vec![
        Knob::new(
            "denoise",
            "Open Image Denoise on the image, guided by albedo and normal AOVs (its time counts)",
            [false, true]
                .into_iter()
                .map(|on| {
                    Setting::new(if on { "on" } else { "off" }, move |t| {
                        t.denoise = on;
                        t.request.aovs = on;
                    })
                })
                .collect(),
            without_denoiser,
        ),
        Knob::new(
            "adaptive",
            "adaptive sampling: pixels stop at this relative standard error (after 16 samples)",
            [0.0f32, 0.05, 0.02, 0.01]
                .into_iter()
                .map(|threshold| {
                    let label = if threshold == 0.0 { "off".to_string() } else { format!("{threshold}") };
                    Setting::new(label, move |t| t.request.noise_threshold = threshold)
                })
                .collect(),
            always,
        ),
        Knob::new(
            "clean-image",
            "the ways to a clean image side by side: raw, adaptive sampling (stops at 0.05 relative \
                    standard error, after 16 samples), denoised, and adaptive sampling then denoised",
            [(false, false), (true, false), (false, true), (true, true)]
                .into_iter()
                .map(|(adaptive, denoise)| {
                    let label = match (adaptive, denoise) {
                        (false, false) => "raw",
                        (true, false) => "adaptive",
                        (false, true) => "denoised",
                        (true, true) => "adaptive+denoised",
                    };
                    Setting::new(label, move |t| {
                        t.request.noise_threshold = if adaptive { CLEAN_IMAGE_THRESHOLD } else { 0.0 };
                        t.denoise = denoise;
                        t.request.aovs = denoise;
                    })
                })
                .collect(),
            without_denoiser,
        ),
    ]
}

/// The atmosphere's cost against its accuracy (skies that are not one leave them out).
fn atmosphere_knobs() -> Vec<Knob> {
    vec![
        Knob::new(
            "atmosphere-steps",
            "march steps per ray through the atmosphere",
            [4u32, 8, 16, 32, 64]
                .into_iter()
                .map(|n| Setting::new(format!("{n}"), move |t| with_atmosphere(t, |a| a.steps = n)))
                .collect(),
            without_atmosphere,
        ),
        Knob::new(
            "atmosphere-tables",
            "sizes of the transmittance and multiple-scattering tables",
            [([64u32, 16u32], [8u32, 8u32]), ([128, 32], [16, 16]), ([256, 64], [32, 32]), ([512, 128], [64, 64])]
                .into_iter()
                .map(|(t_lut, ms_lut)| {
                    Setting::new(format!("{}x{}, {}x{}", t_lut[0], t_lut[1], ms_lut[0], ms_lut[1]), move |t| {
                        with_atmosphere(t, |a| (a.transmittance_lut, a.multiple_scattering_lut) = (t_lut, ms_lut))
                    })
                })
                .collect(),
            without_atmosphere,
        ),
        Knob::new(
            "multiple-scattering",
            "light scattered more than once in the air: the closure of the seed, or single scattering only",
            [true, false]
                .into_iter()
                .map(|on| {
                    Setting::new(if on { "on" } else { "off" }, move |t| {
                        with_atmosphere(t, |a| a.multiple_scattering = on)
                    })
                })
                .collect(),
            without_atmosphere,
        ),
    ]
}

/// The knobs named, in report order; an unknown name is an error listing the known ones.
pub fn select(levels: &[u32], names: &[String]) -> Result<Vec<Knob>, String> {
    let all = all_knobs(levels);
    if let Some(bad) = names.iter().find(|n| !all.iter().any(|k| k.name == n.as_str())) {
        let known: Vec<&str> = all.iter().map(|k| k.name).collect();
        return Err(format!("no knob named {bad:?}; the knobs are: {}", known.join(", ")));
    }
    Ok(all.into_iter().filter(|k| names.is_empty() || names.iter().any(|n| n == k.name)).collect())
}
