//! rt's image against a reference renderer's (Mitsuba 3, Cycles) of the same scene:
//! the global mean and every 8×8 block's mean of luminance must agree within bounds
//! derived from the noise at the sample counts used.

use super::luminance;
use rt::render::Image;
use std::path::Path;

const BLOCK: usize = 8;

/// How closely blocks without noise in rt (background, emitters seen directly) must match.
#[derive(Clone, Copy)]
pub enum Noiseless {
    /// Within this difference of mean luminance.
    Absolute(f64),
    /// Within this fraction of the reference's block mean (Cycles sums samples in f32).
    Relative(f64),
}

pub struct Comparison {
    pub ours_mean: f64,
    pub reference_mean: f64,
    /// |difference of the global means| over its standard error.
    pub global_z: f64,
    /// The same for the worst 8×8 block.
    pub worst_block_z: f64,
    /// (x, y) of the worst block, with its mean luminance in rt and in the reference.
    pub worst_block: (usize, usize, f64, f64),
    /// Every block's mean luminance in rt and in the reference, and the standard error of
    /// their difference.
    pub blocks: Vec<(f64, f64, f64)>,
    /// The standard error of the difference of the global means.
    pub global_sigma: f64,
}

/// Compares `ours` with the reference image at `reference` (an EXR of linear radiance)
/// rendered with `reference_spp` samples per pixel. The reference's own noise is
/// estimated from ours: similar estimators, more samples.
pub fn compare(ours: &Image, reference: &Path, reference_spp: f64) -> Comparison {
    compare_with(ours, reference, reference_spp, Noiseless::Absolute(1e-5))
}

/// [`compare`], with its own bound for blocks without noise.
pub fn compare_with(ours: &Image, reference: &Path, reference_spp: f64, noiseless: Noiseless) -> Comparison {
    let image = image::open(reference).unwrap_or_else(|e| panic!("{}: {e}", reference.display())).into_rgb32f();
    let (w, h) = (ours.width as usize, ours.height as usize);
    assert_eq!((image.width() as usize, image.height() as usize), (w, h), "{}: size", reference.display());
    let reference: Vec<[f32; 3]> = image.pixels().map(|p| p.0).collect();
    let noise_scale = (1.0 + ours.samples as f64 / reference_spp).sqrt();

    let n = ours.pixels.len() as f64;
    let ours_mean = ours.pixels.iter().map(|p| luminance(*p)).sum::<f64>() / n;
    let reference_mean = reference.iter().map(|p| luminance(*p)).sum::<f64>() / n;
    let global_sigma = ours.std_error.iter().map(|e| (*e as f64).powi(2)).sum::<f64>().sqrt() / n * noise_scale;
    let global_z = (ours_mean - reference_mean).abs() / global_sigma.max(1e-12);

    let mut worst_block_z: f64 = 0.0;
    let mut worst_block = (0, 0, 0.0, 0.0);
    let mut blocks = Vec::new();
    for by in 0..h / BLOCK {
        for bx in 0..w / BLOCK {
            let (mut a, mut b, mut var) = (0.0, 0.0, 0.0);
            for y in by * BLOCK..(by + 1) * BLOCK {
                for x in bx * BLOCK..(bx + 1) * BLOCK {
                    let i = y * w + x;
                    a += luminance(ours.pixels[i]);
                    b += luminance(reference[i]);
                    var += (ours.std_error[i] as f64).powi(2);
                }
            }
            let count = (BLOCK * BLOCK) as f64;
            let sigma = var.sqrt() / count * noise_scale;
            let diff = (a - b).abs() / count;
            blocks.push((a / count, b / count, sigma));
            // Blocks with no noise at all (background, emitters seen directly) must match to rounding.
            let within = match noiseless {
                Noiseless::Absolute(bound) => diff < bound,
                Noiseless::Relative(fraction) => diff <= fraction * (b / count).abs(),
            };
            let z = if sigma > 0.0 {
                diff / sigma
            } else if within {
                0.0
            } else {
                f64::INFINITY
            };
            if z > worst_block_z {
                worst_block_z = z;
                worst_block = (bx, by, a / count, b / count);
            }
        }
    }
    Comparison { ours_mean, reference_mean, global_z, worst_block_z, worst_block, blocks, global_sigma }
}

impl Comparison {
    pub fn relative_mean_error(&self) -> f64 {
        (self.ours_mean - self.reference_mean) / self.reference_mean
    }

    fn print(&self, name: &str, against: &str) {
        let (bx, by, a, b) = self.worst_block;
        println!(
            "{name:22} mean {:.5} vs {against} {:.5}: {:+.3}% ({:.2} σ); worst 8x8 block ({bx}, {by}): {a:.5} vs {b:.5}, {:.2} σ",
            self.ours_mean,
            self.reference_mean,
            100.0 * self.relative_mean_error(),
            self.global_z,
            self.worst_block_z
        );
    }

    /// Prints the figures, then fails if the global mean is more than 4 σ off (for
    /// heavy-tailed noise whose blocks' standard errors are estimated low).
    pub fn check_mean(&self, name: &str, against: &str) {
        self.print(name, against);
        assert!(self.global_z <= 4.0, "{name}: global mean is {:.2} σ from {against}'s", self.global_z);
    }

    /// [`Self::check`] for an image whose content rt reconstructs within `fraction`
    /// rather than exactly (a texture baked from what the reference computes per sample):
    /// the global mean may be off by 4 σ plus a fifth of `fraction`, each block by 5 σ
    /// plus `fraction` of the reference's block mean.
    pub fn check_within(&self, name: &str, against: &str, fraction: f64) {
        self.print(name, against);
        let worst = self.blocks.iter().map(|&(a, b, sigma)| (a - b).abs() / (5.0 * sigma + fraction * b.abs()));
        let worst = worst.fold(0.0, f64::max);
        let global = (self.ours_mean - self.reference_mean).abs()
            / (4.0 * self.global_sigma + 0.2 * fraction * self.reference_mean.abs());
        println!("{name:22} worst block at {:.2} of its bound, global mean at {global:.2} of its bound", worst);
        assert!(global <= 1.0, "{name}: the global mean is {global:.2} times its bound from {against}'s");
        assert!(worst <= 1.0, "{name}: a block is {worst:.2} times its bound from {against}'s");
    }

    /// Prints the figures, then fails if the global mean is more than 4 σ off or a block
    /// more than 5 σ (with 48–64 blocks per image, a block fails by chance with
    /// probability ~6e-7 at 5 σ).
    pub fn check(&self, name: &str, against: &str) {
        self.print(name, against);
        assert!(self.global_z <= 4.0, "{name}: global mean is {:.2} σ from {against}'s", self.global_z);
        assert!(self.worst_block_z <= 5.0, "{name}: a block is {:.2} σ from {against}'s", self.worst_block_z);
    }
}

/// Renders `tests/cycles/scenes/NAME/scene.toml` at its size with `spp` samples and
/// `max_bounces`, and checks it against Cycles' `tests/cycles/NAME.exr` of `reference_spp`
/// samples (blocks without noise within 1e-4); returns the image for further checks.
pub fn check_against_cycles(name: &str, spp: u32, max_bounces: u32, reference_spp: f64) -> Image {
    let repo = super::repo();
    let scene = rt::scene::load(&repo.join(format!("tests/cycles/scenes/{name}/scene.toml"))).unwrap();
    let (w, h) = (scene.render.width, scene.render.height);
    let ours = super::render(scene, w, h, spp, max_bounces);
    let file = repo.join(format!("tests/cycles/{name}.exr"));
    compare_with(&ours, &file, reference_spp, Noiseless::Absolute(1e-4)).check(name, "Cycles");
    ours
}
