//! The converged reference that errors are measured against: rendered once with the
//! most accurate settings (next-event estimation, GGX rough glass, no clamp, many
//! bounces) as two halves of independent samples, and cached on disk as two EXR files
//! under a key that changes whenever the image could: the parsed scene, the bytes of
//! its assets, the size, the reference settings and the WGSL of the pipeline.
//!
//! The two halves give the reference's own noise: for independent halves A and B,
//! mean((A − B)²) / 4 estimates the mean squared error of (A + B) / 2, and metrics
//! subtract it so that errors are against the converged image, not this estimate of it.

use super::knobs::Trial;
use super::metrics::display_luma;
use super::timing::render_timed;
use anyhow::{Context, Result, bail};
use rt::asset::{AssetFiles, builtin};
use rt::gpu::GpuTimer;
use rt::gpu::shader::{Program, assemble};
use rt::render::{Image, Session, write_image};
use rt::scene::{RoughTransmission, Sampling, Scene};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Bump when the way references are made changes, so that old ones are not reused.
const FORMAT: &str = "rt reference v1";
/// Seeds of the two halves, far from the small seeds that sweeps use.
const HALF_SEEDS: [u32; 2] = [0x5eed_0a0a, 0x5eed_0b0b];

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceSettings {
    /// Samples per pixel of the whole reference (each half has half).
    pub spp: u32,
    pub max_bounces: u32,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReferenceOrigin {
    /// Read from the cache.
    Cached,
    /// Rendered now (and cached), in this much GPU time.
    Rendered(Duration),
}

pub struct Reference {
    pub image: Image,
    /// Mean over pixels and channels of the linear radiance.
    pub mean: f64,
    /// Estimated mean squared error of `image` against the converged image.
    pub noise_mse: f64,
    /// SSIM of one half against the other: how far the reference's own noise keeps
    /// anything from an SSIM of 1 (against the converged image it is about a quarter as far).
    pub halves_ssim: f64,
    pub settings: ReferenceSettings,
    /// The first half's file; the second is beside it.
    pub path: PathBuf,
    pub origin: ReferenceOrigin,
}

impl Reference {
    /// The reference's own noise as a relative RMSE.
    pub fn relative_noise(&self) -> f64 {
        self.noise_mse.sqrt() / self.mean
    }
}

/// The trial the reference renders: the scene with its most accurate settings.
pub fn reference_trial(scene: &Scene, size: (u32, u32), settings: ReferenceSettings) -> Trial {
    let mut scene = scene.clone();
    scene.render.sampling = Sampling::Nee;
    scene.render.rough_transmission = RoughTransmission::Ggx;
    let mut trial = Trial::baseline(&scene, size);
    trial.request.spp = settings.spp.div_ceil(2).max(1);
    trial.request.max_bounces = settings.max_bounces;
    // Every pixel to the full count: adaptive sampling's stopping is for the knobs to price.
    trial.request.noise_threshold = 0.0;
    trial
}

/// The reference from `cache_dir` if one with the same key is there, else rendered
/// with `session` (built for [`reference_trial`]'s scene) and written there.
pub fn obtain(
    session: &mut Session,
    trial: &Trial,
    settings: ReferenceSettings,
    cache_dir: &Path,
    timer: &GpuTimer,
) -> Result<Reference> {
    let request = &trial.request;
    let key = key(session, trial, settings)?;
    let stem = Path::new(&session.scene().origin).file_stem().map_or("scene".into(), |s| s.to_string_lossy());
    let paths = [format!("{stem}-{key}-a.exr"), format!("{stem}-{key}-b.exr")].map(|n| cache_dir.join(n));
    let (halves, origin) = match read_halves(&paths, request.width, request.height) {
        Some(halves) => (halves, ReferenceOrigin::Cached),
        None => {
            std::fs::create_dir_all(cache_dir).with_context(|| format!("cannot create {}", cache_dir.display()))?;
            let mut halves = Vec::new();
            let mut took = Duration::ZERO;
            for (seed, path) in HALF_SEEDS.iter().zip(&paths) {
                let half_request = rt::render::RenderRequest { seed: *seed, ..request.clone() };
                let render = render_timed(session, &half_request, timer)?;
                if render.dropped > 0 {
                    log::warn!("{}: {} non-finite samples dropped", path.display(), render.dropped);
                }
                write_image(&render.image, path, 0.0)?;
                halves.push(render.image.pixels);
                took += render.time;
            }
            (halves, ReferenceOrigin::Rendered(took))
        }
    };
    let (a, b) = (&halves[0], &halves[1]);
    let pixels: Vec<[f32; 3]> = a.iter().zip(b).map(|(a, b)| [0, 1, 2].map(|c| 0.5 * (a[c] + b[c]))).collect();
    let values = (pixels.len() * 3) as f64;
    let mean = pixels.iter().flatten().map(|&v| v as f64).sum::<f64>() / values;
    let half_difference: f64 =
        a.iter().zip(b).flat_map(|(a, b)| (0..3).map(|c| (a[c] as f64 - b[c] as f64).powi(2))).sum();
    if !(mean.is_finite() && mean > 0.0) {
        bail!("{}: the reference image is black or not finite; nothing to measure errors against", paths[0].display());
    }
    let samples = 2 * request.spp;
    let image = Image {
        width: request.width,
        height: request.height,
        samples,
        std_error: vec![0.0; pixels.len()],
        sample_counts: vec![samples; pixels.len()],
        alpha: None,
        pixels,
    };
    let noise_mse = half_difference / values / 4.0;
    let exposure = trial.scene.render.exposure;
    let (w, h) = (request.width as usize, request.height as usize);
    let halves_ssim = super::ssim::ssim(&display_luma(a, exposure), &display_luma(b, exposure), w, h);
    let path = paths[0].clone();
    Ok(Reference { image, mean, noise_mse, halves_ssim, settings, path, origin })
}

/// Both halves, if both files are there, readable and of the right size.
fn read_halves(paths: &[PathBuf; 2], width: u32, height: u32) -> Option<Vec<Vec<[f32; 3]>>> {
    let mut halves = Vec::new();
    for path in paths {
        if !path.is_file() {
            return None;
        }
        let image = match rt::files::image::read(path, "cached reference") {
            Ok(image) => image.into_rgb32f(),
            Err(e) => {
                log::warn!("{}: unreadable cached reference ({e}); rendering it again", path.display());
                return None;
            }
        };
        if image.dimensions() != (width, height) {
            log::warn!("{}: cached reference of the wrong size; rendering it again", path.display());
            return None;
        }
        halves.push(image.pixels().map(|p| p.0).collect());
    }
    Some(halves)
}

/// Hex of the first 64 bits of a BLAKE3 over everything that decides the reference.
fn key(session: &Session, trial: &Trial, settings: ReferenceSettings) -> Result<String> {
    let mut h = blake3::Hasher::new();
    let r = &trial.request;
    h.update(format!("{FORMAT} {}\n", env!("CARGO_PKG_VERSION")).as_bytes());
    // The parsed scene rather than its text: comments and layout do not change the image.
    // Where it came from does not either: paths give way to the bytes of the assets.
    let mut scene = session.scene().clone();
    scene.origin.clear();
    for mesh in &mut scene.meshes {
        for file in AssetFiles::resolve(&mesh.asset)?.source_files()? {
            let bytes = builtin::read(&file).with_context(|| format!("cannot read {}", file.display()))?;
            h.update(&(bytes.len() as u64).to_le_bytes());
            h.update(&bytes);
        }
        mesh.asset.clear();
    }
    h.update(format!("{scene:?}\n").as_bytes());
    h.update(format!("{}x{} {settings:?} {HALF_SEEDS:?}\n", r.width, r.height).as_bytes());
    h.update(assemble(Program::Integrator, &session.features()).as_bytes());
    Ok(h.finalize().to_hex()[..16].to_string())
}
