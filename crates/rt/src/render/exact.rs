//! Exact sums of each pixel's samples (`shaders/exact_sums.wgsl`): integers in units of
//! 2^-32, so that sums of any parts of a render add up to the sums of the whole, and
//! the image made from them is the same bit for bit however the samples were split.

use super::{Aovs, Image};

/// Words of one sum on the GPU (a 96-bit two's-complement integer, least significant first).
pub const WORDS: usize = 3;
/// Sums per pixel of the radiance: red, green, blue and the luminance's square.
pub const RADIANCE_VALUES: usize = 4;
/// Sums per pixel of the AOVs: albedo (3), depth where hit, normal (3), hit count,
/// position (3), coverage, emission (3), diffuse colour (3).
pub const AOV_VALUES: usize = 18;
/// The sums' unit, 2^-32.
const UNIT: f64 = 1.0 / 4_294_967_296.0;

/// Sums per pixel, with or without the AOVs'.
pub fn values_per_pixel(aovs: bool) -> usize {
    RADIANCE_VALUES + if aovs { AOV_VALUES } else { 0 }
}

/// Words per pixel on the GPU.
pub fn words_per_pixel(aovs: bool) -> usize {
    values_per_pixel(aovs) * WORDS
}

/// One pixel's sums, and the samples it took.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExactSums {
    pub width: u32,
    pub height: u32,
    /// Whether the AOVs' sums follow the radiance's.
    pub aovs: bool,
    /// [`values_per_pixel`] sums per pixel, rows from the top.
    pub sums: Vec<i128>,
    /// Samples each pixel took, finite or not.
    pub taken: Vec<u32>,
    /// Of those, the non-finite ones (dropped: they are in no sum).
    pub dropped: Vec<u32>,
}

impl ExactSums {
    /// From the GPU's words (the buffer may be longer than the image needs).
    pub fn from_words(width: u32, height: u32, aovs: bool, words: &[u32], taken: Vec<u32>, dropped: Vec<u32>) -> Self {
        let count = width as usize * height as usize * values_per_pixel(aovs);
        let sums = words.chunks_exact(WORDS).take(count).map(|w| to_i128([w[0], w[1], w[2]])).collect();
        Self { width, height, aovs, sums, taken, dropped }
    }

    /// The mean radiance of each pixel over its finite samples, each pixel's standard
    /// error of its mean luminance, and with `alpha` its coverage.
    pub fn image(&self, samples: u32, alpha: bool) -> Image {
        let values = values_per_pixel(self.aovs);
        let mut image = Image {
            width: self.width,
            height: self.height,
            samples,
            pixels: Vec::with_capacity(self.taken.len()),
            std_error: Vec::with_capacity(self.taken.len()),
            sample_counts: Vec::with_capacity(self.taken.len()),
            alpha: None,
        };
        let mut coverage = Vec::new();
        for (i, pixel) in self.sums.chunks_exact(values).enumerate() {
            let finite = self.taken[i].saturating_sub(self.dropped[i]);
            let n = finite.max(1) as f64;
            let mean = |v: i128| (v as f64 * UNIT / n) as f32;
            let rgb = [mean(pixel[0]), mean(pixel[1]), mean(pixel[2])];
            let [r, g, b] = [pixel[0], pixel[1], pixel[2]].map(|v| v as f64 * UNIT / n);
            let y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
            let square = pixel[3] as f64 * UNIT / n;
            let variance = ((square - y * y) * n / (n - 1.0).max(1.0)).max(0.0);
            // Each sample's luminance and its square are rounded to f32 on the GPU, by parts
            // in 10⁷: samples that agree to a part in 10³ make a noiseless pixel.
            let variance = if variance <= 1e-6 * y * y { 0.0 } else { variance };
            image.pixels.push(rgb);
            image.std_error.push((variance / n).sqrt() as f32);
            image.sample_counts.push(finite);
            if self.aovs {
                coverage.push(mean(pixel[RADIANCE_VALUES + 11]).clamp(0.0, 1.0));
            }
        }
        if alpha && self.aovs {
            image.alpha = Some(coverage);
        }
        image
    }

    /// The AOVs' means, as [`Aovs::from_means`] makes them from the running means; `None`
    /// without them.
    pub fn aovs(&self) -> Option<Aovs> {
        if !self.aovs {
            return None;
        }
        let mut aovs = Aovs { width: self.width, height: self.height, ..Default::default() };
        let values = values_per_pixel(true);
        for (i, pixel) in self.sums.chunks_exact(values).enumerate() {
            let a = &pixel[RADIANCE_VALUES..];
            let n = self.taken[i].max(1) as f64;
            let mean = |v: i128| (v as f64 * UNIT / n) as f32;
            let three = |at: usize| [mean(a[at]), mean(a[at + 1]), mean(a[at + 2])];
            let hits = a[7] as f64 * UNIT;
            aovs.albedo.push(three(0).map(|v| v.clamp(0.0, 1.0)));
            aovs.depth.push(if hits > 0.0 { (a[3] as f64 * UNIT / hits) as f32 } else { f32::INFINITY });
            aovs.normal.push(three(4));
            aovs.position.push(three(8));
            aovs.emission.push(three(12));
            aovs.diffuse_color.push(three(15));
        }
        Some(aovs)
    }

    /// Adds `other`'s sums and counts to these (the caller checks that they are of the
    /// same image).
    pub fn add(&mut self, other: &Self) {
        for (a, b) in self.sums.iter_mut().zip(&other.sums) {
            *a += b;
        }
        for (a, b) in self.taken.iter_mut().zip(&other.taken) {
            *a += b;
        }
        for (a, b) in self.dropped.iter_mut().zip(&other.dropped) {
            *a += b;
        }
    }
}

/// A 96-bit two's-complement integer from its words, least significant first.
pub fn to_i128(w: [u32; 3]) -> i128 {
    let unsigned = w[0] as u128 | (w[1] as u128) << 32 | (w[2] as u128) << 64;
    // Sign-extend from bit 95.
    ((unsigned << 32) as i128) >> 32
}

/// The three words of a sum (it must fit 96 bits, as every sum of a render does).
pub fn to_words(v: i128) -> [u32; 3] {
    [v as u32, (v >> 32) as u32, (v >> 64) as u32]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_round_trip_signed_sums() {
        for v in [0i128, 1, -1, 1 << 40, -(1 << 70), (1i128 << 95) - 1, -(1i128 << 95)] {
            assert_eq!(to_i128(to_words(v)), v, "{v}");
        }
    }

    #[test]
    fn the_shader_declares_the_same_layout() {
        let shader = include_str!("../../shaders/exact_sums.wgsl");
        for line in [
            format!("const EXACT_WORDS: u32 = {WORDS}u;"),
            format!("const EXACT_RADIANCE: u32 = {RADIANCE_VALUES}u;"),
            format!("const EXACT_AOVS: u32 = {AOV_VALUES}u;"),
        ] {
            assert!(shader.contains(&line), "exact_sums.wgsl lacks `{line}`");
        }
    }

    #[test]
    fn a_pixel_whose_samples_agree_has_no_noise() {
        // As the GPU adds them: the f32 luminance of each sample and its f32 square.
        let (n, v) = (64i128, 0.1f32);
        let y = 0.2126f32 * v + 0.7152 * v + 0.0722 * v;
        let unit = |x: f32| (x as f64 / UNIT).round() as i128;
        let sums = vec![n * unit(v), n * unit(v), n * unit(v), n * unit(y * y)];
        let pixel = ExactSums { width: 1, height: 1, aovs: false, sums, taken: vec![64], dropped: vec![0] };
        let image = pixel.image(64, false);
        assert_eq!((image.pixels[0], image.std_error[0]), ([v; 3], 0.0));
    }

    #[test]
    fn sums_of_parts_give_the_means_of_the_whole() {
        let unit = |v: f64| (v / UNIT) as i128;
        let part = |r: f64, taken| ExactSums {
            width: 1,
            height: 1,
            aovs: false,
            sums: vec![unit(r), unit(r), unit(r), unit(r * r)],
            taken: vec![taken],
            dropped: vec![0],
        };
        let mut whole = part(3.0, 2);
        whole.add(&part(1.0, 1));
        let image = whole.image(3, false);
        assert_eq!(image.pixels[0], [4.0 / 3.0; 3]);
        assert_eq!(image.sample_counts[0], 3);
    }
}
