//! rt's image against a reference renderer's (Mitsuba 3, Cycles) of the same scene:
//! the global mean and every 8×8 block's mean of luminance must agree within bounds
//! derived from the noise at the sample counts used, and those of each colour channel
//! too ([`Comparison::check`]: a hue error cannot pass for a right luminance).

use super::luminance;
use super::measured::Measured;
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

/// How far the colour channels are apart, each on its own (red, green, blue).
pub struct Channels {
    /// The largest |difference of the global means| over its standard error.
    pub global_z: f64,
    pub worst_block_z: f64,
    /// (x, y) of the worst block, with its mean of `worst_channel` in rt and in the reference.
    pub worst_block: (usize, usize, f64, f64),
    pub worst_channel: &'static str,
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
    /// The same of the colour channels, each on its own.
    pub channels: Channels,
    /// Every block's means in rt and in the reference, and the standard errors of their
    /// differences.
    blocks: Vec<Region>,
    global: Region,
    /// The standard error of the difference of the global means of luminance.
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
    compare_noise(ours, None, reference, reference_spp, noiseless)
}

/// [`compare_with`] for an image whose colour channels' noise was measured: each channel
/// is held to its own standard error instead of one inferred from luminance's.
pub fn compare_measured(ours: &Measured, reference: &Path, reference_spp: f64, noiseless: Noiseless) -> Comparison {
    compare_noise(&ours.image, Some(&ours.channel_error), reference, reference_spp, noiseless)
}

fn compare_noise(
    ours: &Image,
    channel_error: Option<&[[f32; 3]]>,
    reference: &Path,
    reference_spp: f64,
    noiseless: Noiseless,
) -> Comparison {
    let (w, h) = (ours.width as usize, ours.height as usize);
    let noise = Noise {
        channels: channel_error,
        reference: reference_error(reference, (w, h)),
        reference_share: ours.samples as f64 / reference_spp,
    };
    let reference = read_rgb(reference, (w, h));

    let everything: Vec<usize> = (0..ours.pixels.len()).collect();
    let global = Region::of(ours, &noise, &reference, &everything);
    let global_z = |channels: std::ops::Range<usize>| {
        channels.map(|c| (global.ours[c] - global.reference[c]).abs() / global.sigma[c].max(1e-12)).fold(0.0, f64::max)
    };
    let mut luminance = Worst::default();
    let mut colour = Worst::default();
    let mut blocks = Vec::new();
    for by in 0..h / BLOCK {
        for bx in 0..w / BLOCK {
            let pixels: Vec<usize> = (by * BLOCK..(by + 1) * BLOCK)
                .flat_map(|y| (bx * BLOCK..(bx + 1) * BLOCK).map(move |x| y * w + x))
                .collect();
            let block = Region::of(ours, &noise, &reference, &pixels);
            luminance.take(&block, block.worst_z(noiseless, 0..1), (bx, by));
            colour.take(&block, block.worst_z(noiseless, 1..4), (bx, by));
            blocks.push(block);
        }
    }
    Comparison {
        ours_mean: global.ours[0],
        reference_mean: global.reference[0],
        global_z: global_z(0..1),
        worst_block_z: luminance.z,
        worst_block: luminance.block,
        channels: Channels {
            global_z: global_z(1..4),
            worst_block_z: colour.z,
            worst_block: colour.block,
            worst_channel: CHANNELS[colour.channel],
        },
        blocks,
        global_sigma: global.sigma[0],
        global,
    }
}

/// An EXR of linear RGB of `size`.
fn read_rgb(path: &Path, size: (usize, usize)) -> Vec<[f32; 3]> {
    let image = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).into_rgb32f();
    assert_eq!((image.width() as usize, image.height() as usize), size, "{}: size", path.display());
    image.pixels().map(|p| p.0).collect()
}

/// The reference's own standard error of each channel, `NAME.error.exr` beside `NAME.exr`,
/// where its script measured it: a reference whose estimator is noisier than rt's (Mitsuba's
/// volumetric path tracer samples absorption by one channel) is not held to rt's noise.
fn reference_error(reference: &Path, size: (usize, usize)) -> Option<Vec<[f32; 3]>> {
    let path = reference.with_extension("error.exr");
    path.exists().then(|| read_rgb(&path, size))
}

/// Where a comparison's standard errors come from.
struct Noise<'a> {
    /// rt's measured error of each channel ([`Measured`]); without it, rt's error of
    /// luminance scaled to the channel by its share of the pixel's luminance (at least 1).
    channels: Option<&'a [[f32; 3]]>,
    /// The reference's measured error of each channel ([`reference_error`]); without it,
    /// rt's scaled by `reference_share`.
    reference: Option<Vec<[f32; 3]>>,
    /// rt's samples over the reference's.
    reference_share: f64,
}

impl Noise<'_> {
    /// The variance of pixel `i`'s difference, luminance then R, G, B.
    fn variance(&self, ours: &Image, reference: &[[f32; 3]], i: usize) -> [f64; 4] {
        let error = (ours.std_error[i] as f64).powi(2);
        let lum = luminance(reference[i]).max(1e-12);
        let channel = |c: usize| match self.channels {
            Some(measured) => (measured[i][c] as f64).powi(2),
            None => error * (reference[i][c] as f64 / lum).max(1.0).powi(2),
        };
        let ours = [error, channel(0), channel(1), channel(2)];
        match &self.reference {
            // Luminance's error at most the sum of the channels' (they may go together).
            Some(r) => {
                let e = r[i].map(|v| v as f64);
                let lum = luminance(r[i]);
                [ours[0] + lum * lum, ours[1] + e[0] * e[0], ours[2] + e[1] * e[1], ours[3] + e[2] * e[2]]
            }
            None => ours.map(|v| v * (1.0 + self.reference_share)),
        }
    }
}

/// The worst block so far: its z, where it is with its means, and in which channel.
#[derive(Default)]
struct Worst {
    z: f64,
    block: (usize, usize, f64, f64),
    channel: usize,
}

impl Worst {
    fn take(&mut self, region: &Region, (z, channel): (f64, usize), (bx, by): (usize, usize)) {
        if z > self.z {
            *self = Worst { z, block: (bx, by, region.ours[channel], region.reference[channel]), channel };
        }
    }
}

/// How closely a colour channel's means agree beyond the noise, relative to themselves:
/// Cycles sums its samples in f32, and both renderers tabulate some functions (thin-film
/// interference, microfacet albedos); blocks of little noise resolve a part in 10³. A hue
/// error is some per cent.
const CHANNEL_PRECISION: f64 = 1e-3;
/// The same near black, where a relative precision is none: Cycles' held-out and shadowed
/// pixels leave a few 10⁻⁵ (luminance's own noiseless bound is 10⁻⁵).
const CHANNEL_FLOOR: f64 = 1e-5;

/// What a comparison reads: luminance, then each colour channel.
const CHANNELS: [&str; 4] = ["luminance", "red", "green", "blue"];

/// The means of a set of pixels in rt and in the reference, luminance then R, G, B, and
/// the standard error of each difference ([`Noise`]), each channel's no closer than its
/// precision.
struct Region {
    ours: [f64; 4],
    reference: [f64; 4],
    sigma: [f64; 4],
}

impl Region {
    fn of(ours: &Image, noise: &Noise, reference: &[[f32; 3]], pixels: &[usize]) -> Self {
        let n = pixels.len() as f64;
        let mean = |image: &dyn Fn(usize) -> [f32; 3]| {
            let mut m = [0.0f64; 4];
            for &i in pixels {
                let p = image(i);
                m[0] += luminance(p);
                for c in 0..3 {
                    m[1 + c] += p[c] as f64;
                }
            }
            m.map(|v| v / n)
        };
        let ours_mean = mean(&|i| ours.pixels[i]);
        let reference_mean = mean(&|i| reference[i]);
        let mut variance = [0.0f64; 4];
        for &i in pixels {
            let v = noise.variance(ours, reference, i);
            (0..4).for_each(|c| variance[c] += v[c]);
        }
        let sigma = variance.map(|v| v.sqrt() / n);
        let sigma = [0, 1, 2, 3].map(|c| match c {
            0 => sigma[0],
            _ => sigma[c].hypot(CHANNEL_PRECISION * reference_mean[c].abs()).hypot(CHANNEL_FLOOR),
        });
        Self { ours: ours_mean, reference: reference_mean, sigma }
    }

    /// The largest difference over its standard error, and its channel; a channel without
    /// noise (background, emitters seen directly) must match within `noiseless`.
    fn worst_z(&self, noiseless: Noiseless, channels: std::ops::Range<usize>) -> (f64, usize) {
        let mut worst = (0.0, channels.start);
        for c in channels {
            let diff = (self.ours[c] - self.reference[c]).abs();
            // A channel's bound is luminance's scaled by its share, plus its precision (a 0.125
            // background reads 0.12504 in Cycles).
            let share = if c == 0 { 1.0 } else { (self.reference[c] / self.reference[0].max(1e-12)).max(1.0) };
            let rounding = if c == 0 { 0.0 } else { CHANNEL_PRECISION * self.reference[c].abs() };
            let within = match noiseless {
                Noiseless::Absolute(bound) => diff < bound * share + rounding,
                Noiseless::Relative(fraction) => diff <= fraction * self.reference[c].abs() + rounding,
            };
            let z = if self.sigma[c] > 0.0 {
                diff / self.sigma[c]
            } else if within {
                0.0
            } else {
                f64::INFINITY
            };
            if z > worst.0 {
                worst = (z, c);
            }
        }
        worst
    }
}

impl Comparison {
    pub fn relative_mean_error(&self) -> f64 {
        (self.ours_mean - self.reference_mean) / self.reference_mean
    }

    fn print(&self, name: &str, against: &str) {
        let (bx, by, a, b) = self.worst_block;
        let c = &self.channels;
        let (cx, cy, ca, cb) = c.worst_block;
        println!(
            "{name:22} mean {:.5} vs {against} {:.5}: {:+.3}% ({:.2} σ); worst 8x8 block ({bx}, {by}): {a:.5} vs {b:.5}, {:.2} σ; channels: global {:.2} σ, worst block ({cx}, {cy}) in {}: {ca:.5} vs {cb:.5}, {:.2} σ",
            self.ours_mean,
            self.reference_mean,
            100.0 * self.relative_mean_error(),
            self.global_z,
            self.worst_block_z,
            c.global_z,
            c.worst_channel,
            c.worst_block_z
        );
    }

    /// Prints the figures, then fails if the global mean of luminance or of a colour channel
    /// is more than 4 σ off (for heavy-tailed noise whose blocks' standard errors are
    /// estimated low).
    pub fn check_mean(&self, name: &str, against: &str) {
        self.print(name, against);
        assert!(self.global_z <= 4.0, "{name}: global mean is {:.2} σ from {against}'s", self.global_z);
        let channels = self.channels.global_z;
        assert!(channels <= 4.0, "{name}: a channel's global mean is {channels:.2} σ from {against}'s");
    }

    /// [`Self::check`] for an image whose content rt reconstructs within `fraction`
    /// rather than exactly (a texture baked from what the reference computes per sample):
    /// in luminance and in each colour channel, the global mean may be off by 4 σ plus a
    /// fifth of `fraction`, each block by 5 σ plus `fraction` of the reference's block mean.
    pub fn check_within(&self, name: &str, against: &str, fraction: f64) {
        self.print(name, against);
        let off = |r: &Region, c: usize, sigmas: f64, share: f64| {
            (r.ours[c] - r.reference[c]).abs() / (sigmas * r.sigma[c] + share * fraction * r.reference[c].abs())
        };
        let each = self.blocks.iter().flat_map(|b| (0..4).map(move |c| (off(b, c, 5.0, 1.0), c)));
        let (worst, channel) = each.fold((0.0, 0), |worst, this| if this.0 > worst.0 { this } else { worst });
        let global = (0..4).map(|c| off(&self.global, c, 4.0, 0.2)).fold(0.0, f64::max);
        println!(
            "{name:22} worst block at {worst:.2} of its bound (in {}), global mean at {global:.2} of its bound",
            CHANNELS[channel]
        );
        assert!(global <= 1.0, "{name}: a global mean is {global:.2} times its bound from {against}'s");
        assert!(worst <= 1.0, "{name}: a block's {} is {worst:.2} times its bound from {against}'s", CHANNELS[channel]);
    }

    /// Prints the figures, then fails if the global mean of luminance is more than 4 σ off
    /// or a block more than 5 σ (with 48–64 blocks per image, a block fails by chance with
    /// probability ~6e-7 at 5 σ).
    fn check_luminance(&self, name: &str, against: &str) {
        self.print(name, against);
        assert!(self.global_z <= 4.0, "{name}: global mean is {:.2} σ from {against}'s", self.global_z);
        assert!(self.worst_block_z <= 5.0, "{name}: a block is {:.2} σ from {against}'s", self.worst_block_z);
    }

    /// [`Self::check_luminance`], and the same bounds for each colour channel on its own,
    /// so that a hue error cannot pass for a right luminance.
    pub fn check(&self, name: &str, against: &str) {
        self.check_luminance(name, against);
        let c = &self.channels;
        assert!(c.global_z <= 4.0, "{name}: a channel's global mean is {:.2} σ from {against}'s", c.global_z);
        assert!(
            c.worst_block_z <= 5.0,
            "{name}: a block's {} is {:.2} σ from {against}'s",
            c.worst_channel,
            c.worst_block_z
        );
    }
}

/// Renders `tests/cycles/scenes/NAME/scene.toml` at its size with `spp` samples and
/// `max_bounces`, and checks it against Cycles' `tests/cycles/NAME.exr` of `reference_spp`
/// samples (blocks without noise within 1e-4); returns the image for further checks.
pub fn check_against_cycles(name: &str, spp: u32, max_bounces: u32, reference_spp: f64) -> Image {
    let repo = super::repo();
    let scene = rt::scene::load(&repo.join(format!("tests/cycles/scenes/{name}/scene.toml"))).unwrap();
    let (w, h) = (scene.render.width, scene.render.height);
    let adjust =
        |r: &mut rt::render::RenderRequest| (r.width, r.height, r.spp, r.max_bounces) = (w, h, spp, max_bounces);
    let (ours, _) = super::measured::render_measured(scene, adjust);
    let file = repo.join(format!("tests/cycles/{name}.exr"));
    compare_measured(&ours, &file, reference_spp, Noiseless::Absolute(1e-4)).check(name, "Cycles");
    ours.image
}
