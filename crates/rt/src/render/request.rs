//! What a render is asked for, resolved once: the scene's `[render]` table gives the
//! defaults, the command line's flags override them and are checked like the keys.

use super::Progress;
use crate::scene::{FeatureSet, LightSampler, Microfacet, RoughTransmission, Sampling, Scene};
use anyhow::{Result, bail};

/// Samples per pixel in one GPU dispatch at most. Large images reach their time target
/// with far fewer; a small window needs this many for its dispatches to last long
/// enough, since a dispatch's last invocations run alone and its reduction is paid once
/// per dispatch (docs/measured-choices.md).
pub const MAX_SAMPLES_PER_DISPATCH: u32 = 1024;
/// Invocations one pixel's samples are spread over at most.
pub const MAX_LANES: u32 = 256;

/// One render's settings, as the session runs them.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderRequest {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub max_bounces: u32,
    pub seed: u32,
    /// Candidates per resampled direction in `resampled` sampling.
    pub ris_candidates: u32,
    /// Scale samples down to this luminance (biased; `None`: off).
    pub clamp: Option<f32>,
    /// Run this feature set's pipeline instead of the scene's own (it must include it).
    pub features: Option<FeatureSet>,
    /// Samples per pixel in each GPU dispatch; `None`: as many as keep a dispatch near its target time.
    pub samples_per_dispatch: Option<u32>,
    /// Invocations each pixel's samples are spread over; `None`: as many as keep the GPU
    /// busy (small images on a GPU). The image is the same whatever the number.
    pub sample_lanes: Option<u32>,
    /// What stderr shows while the session renders.
    pub progress: Progress,
    /// Albedo, normal and depth images beside the radiance (see [`super::Aovs`]).
    pub aovs: bool,
    /// Adaptive sampling's relative standard error at which a pixel stops (0: off).
    pub noise_threshold: f32,
    /// Samples a pixel takes before adaptive sampling may stop it.
    pub adaptive_min_samples: u32,
    /// The image from exact sums of the samples (see [`super::exact`]): the same bit for
    /// bit however the samples are split into parts.
    pub exact_sums: bool,
    /// The index of the first sample: the render takes samples `first_sample..first_sample + spp`.
    pub first_sample: u32,
}

impl RenderRequest {
    pub fn from_scene(scene: &Scene) -> Self {
        let r = &scene.render;
        Self {
            width: r.width,
            height: r.height,
            spp: r.spp,
            max_bounces: r.max_bounces,
            seed: 0,
            ris_candidates: r.ris_candidates,
            clamp: None,
            features: None,
            samples_per_dispatch: None,
            sample_lanes: None,
            progress: Progress::Hidden,
            // A session counts them anyway where the image has an alpha (`Session`).
            aovs: false,
            noise_threshold: r.noise_threshold,
            adaptive_min_samples: r.adaptive_min_samples,
            exact_sums: false,
            first_sample: 0,
        }
    }

    /// Whether pixels stop taking samples once their noise is below the threshold.
    pub fn adaptive(&self) -> bool {
        self.noise_threshold > 0.0
    }

    /// Whether `other` renders the same image as `self` (only how it is reached differs).
    pub fn same_image(&self, other: &Self) -> bool {
        let driver_only = |r: &Self| Self {
            spp: 0,
            samples_per_dispatch: None,
            sample_lanes: None,
            progress: Progress::Hidden,
            ..r.clone()
        };
        driver_only(self) == driver_only(other)
    }
}

/// The command line's overrides of a scene's `[render]` keys, and the settings that
/// only the command line has.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderFlags {
    pub size: Option<(u32, u32)>,
    pub spp: Option<u32>,
    pub max_bounces: Option<u32>,
    pub exposure: Option<f32>,
    /// `--transparent`: a transparent film whatever the scene says.
    pub transparent: bool,
    pub sampling: Option<Sampling>,
    pub ris_candidates: Option<u32>,
    pub rough_transmission: Option<RoughTransmission>,
    pub light_sampler: Option<LightSampler>,
    pub microfacet: Option<Microfacet>,
    pub seed: u32,
    pub clamp: Option<f32>,
    pub samples_per_dispatch: Option<u32>,
    pub sample_lanes: Option<u32>,
    pub noise_threshold: Option<f32>,
    /// Ask for AOVs (what `--aovs` and `--denoise` need).
    pub aovs: bool,
}

impl RenderFlags {
    /// Writes the flags into `scene.render`, checked by the same rules as the scene's
    /// keys (an error names the flag), and returns the request they make.
    pub fn apply(&self, scene: &mut Scene) -> Result<RenderRequest> {
        let r = &mut scene.render;
        if let Some((w, h)) = self.size {
            (r.width, r.height) = (w, h);
        }
        let set = |value: Option<u32>, key: &mut u32| *key = value.unwrap_or(*key);
        set(self.spp, &mut r.spp);
        set(self.max_bounces, &mut r.max_bounces);
        set(self.ris_candidates, &mut r.ris_candidates);
        r.exposure = self.exposure.unwrap_or(r.exposure);
        r.transparent |= self.transparent;
        r.sampling = self.sampling.unwrap_or(r.sampling);
        r.rough_transmission = self.rough_transmission.unwrap_or(r.rough_transmission);
        r.light_sampler = self.light_sampler.unwrap_or(r.light_sampler);
        r.microfacet = self.microfacet.unwrap_or(r.microfacet);
        r.noise_threshold = self.noise_threshold.unwrap_or(r.noise_threshold);
        if let Err((key, message)) = r.check() {
            bail!("{}: {message}", flag_of(key));
        }
        if let Some(c) = self.clamp
            && !(c.is_finite() && c > 0.0)
        {
            bail!("--clamp: must be a positive, finite luminance, got {c}");
        }
        if let Some(n) = self.samples_per_dispatch
            && !(1..=MAX_SAMPLES_PER_DISPATCH).contains(&n)
        {
            bail!("--samples-per-dispatch: must be in 1..={MAX_SAMPLES_PER_DISPATCH}, got {n}");
        }
        if let Some(n) = self.sample_lanes
            && !(1..=MAX_LANES).contains(&n)
        {
            bail!("--sample-lanes: must be in 1..={MAX_LANES}, got {n}");
        }
        Ok(RenderRequest {
            seed: self.seed,
            clamp: self.clamp,
            samples_per_dispatch: self.samples_per_dispatch,
            sample_lanes: self.sample_lanes,
            aovs: self.aovs,
            ..RenderRequest::from_scene(scene)
        })
    }
}

/// The flag that sets a `[render]` key.
fn flag_of(key: &str) -> String {
    match key {
        "width" | "height" => "--size".to_owned(),
        key => format!("--{}", key.replace('_', "-")),
    }
}
