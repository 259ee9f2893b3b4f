//! `[sky] kind = "environment"`: the equirectangular image read and checked, and the
//! piecewise-constant distribution over it that light sampling draws directions from
//! (Pharr, Jakob & Humphreys, PBRT 3rd ed. §13.6.7: a marginal density over rows and
//! one conditional density per row, weighted by sin θ so that the density is over the
//! sphere). The GPU side is `super::environment_map` and `shaders/environment.wgsl`.

use crate::scene::{luminance, srgb_decode};
use anyhow::{Context, Result, bail};
use std::path::Path;

/// The image's texels as linear RGB, in the decoder's own buffer where it can be (an
/// RGB float image is the texels already; RGBA is packed down in place), so that a large
/// environment is held once, not twice, while it is read.
fn rgb_texels(image: image::DynamicImage) -> Vec<[f32; 3]> {
    let mut floats = match image {
        image::DynamicImage::ImageRgb32F(rgb) => rgb.into_raw(),
        image::DynamicImage::ImageRgba32F(rgba) => {
            let mut floats = rgba.into_raw();
            let pixels = floats.len() / 4;
            for p in 0..pixels {
                floats.copy_within(4 * p..4 * p + 3, 3 * p);
            }
            floats.truncate(3 * pixels);
            floats
        }
        other => other.into_rgb32f().into_raw(),
    };
    floats.shrink_to_fit();
    match bytemuck::allocation::try_cast_vec::<f32, [f32; 3]>(floats) {
        Ok(texels) => texels,
        Err((_, floats)) => floats.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
    }
}

/// An equirectangular image: `width` × `height` linear RGB texels, rows from the top
/// (Blender's +Z) down, columns as Cycles' `direction_to_equirectangular` reads them.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentImage {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[f32; 3]>,
}

impl EnvironmentImage {
    /// Reads an OpenEXR (any compression the `exr` crate knows, DWAB included) or a
    /// Radiance `.hdr` file; every error names the file.
    pub fn read(path: &Path) -> Result<Self> {
        let what = format!("environment image {}", path.display());
        let bytes = crate::files::read(path).map_err(|e| anyhow::anyhow!("{what}: {}", e.message()))?;
        Self::decode(&bytes, &what)
    }

    /// The image in `bytes` (an .exr or .hdr file's); errors name `what`.
    pub fn decode(bytes: &[u8], what: &str) -> Result<Self> {
        let decoded = crate::files::image::decode(bytes, what).map_err(anyhow::Error::msg)?;
        let (width, height) = (decoded.width(), decoded.height());
        Self::new(width, height, rgb_texels(decoded)).with_context(|| what.to_owned())
    }

    /// Checks the texels: a non-finite one is an error; negative components (lossy
    /// compression leaves a few) emit nothing and become 0.
    pub fn new(width: u32, height: u32, mut texels: Vec<[f32; 3]>) -> Result<Self> {
        if width == 0 || height == 0 {
            bail!("the image is {width}×{height} texels: it has none");
        }
        if texels.len() as u64 != width as u64 * height as u64 {
            bail!("{} texels for a {width}×{height} image", texels.len());
        }
        if let Some(i) = texels.iter().position(|t| t.iter().any(|c| !c.is_finite())) {
            let (x, y) = (i as u32 % width, i as u32 / width);
            bail!("texel ({x}, {y}) is {:?}: an environment's texels must be finite", texels[i]);
        }
        let (mut negative, mut lowest) = (0usize, 0.0f32);
        for c in texels.iter_mut().flatten() {
            if *c < 0.0 {
                lowest = lowest.min(*c);
                *c = 0.0;
                negative += 1;
            }
        }
        // Lossy compression (DWAB) leaves tiny negatives in real HDRIs: not worth a warning.
        if lowest < -1e-3 {
            log::warn!("{negative} negative texel components (down to {lowest}) read as 0");
        } else if negative > 0 {
            log::debug!("{negative} slightly negative texel components read as 0");
        }
        Ok(Self { width, height, texels })
    }

    /// The image at half the size (2×2 box filter; an odd last row or column is
    /// dropped), for a GPU that cannot hold it whole.
    pub fn halved(&self) -> Self {
        let (w, h) = ((self.width / 2).max(1), (self.height / 2).max(1));
        let mut texels = Vec::with_capacity(w as usize * h as usize);
        for y in 0..h {
            for x in 0..w {
                let mut sum = [0.0f64; 3];
                let mut n = 0.0;
                for sy in (2 * y).min(self.height - 1)..(2 * y + 2).min(self.height) {
                    for sx in (2 * x).min(self.width - 1)..(2 * x + 2).min(self.width) {
                        let t = self.texels[(sy * self.width + sx) as usize];
                        (0..3).for_each(|c| sum[c] += t[c] as f64);
                        n += 1.0;
                    }
                }
                texels.push(sum.map(|s| (s / n) as f32));
            }
        }
        Self { width: w, height: h, texels }
    }
}

/// Row-then-column cumulative distribution: `conditional[y · width + x]` is the
/// probability of columns 0..=x within row y, `marginal[y]` that of rows 0..=y. Both
/// end at exactly 1; an image that is black everywhere gets the uniform distribution
/// (it is then never light-sampled, see [`Distribution::total`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution {
    pub conditional: Vec<f32>,
    pub marginal: Vec<f32>,
    /// Sum of the cell weights; 0 for a black image.
    pub total: f64,
}

/// Each cell's weight: the largest luminance over it and its eight neighbours, times
/// sin θ at its centre. The lookup is bilinear, so a texel's radiance reaches half a
/// texel into its neighbours' cells: weighting by the neighbourhood's maximum keeps
/// radiance / density bounded there, and a tiny very bright region cannot leave
/// fireflies in the ring around it.
fn cell_weights(image: &EnvironmentImage, srgb: bool) -> Vec<f64> {
    let (w, h) = (image.width, image.height);
    let linear = |t: [f32; 3]| if srgb { t.map(srgb_decode) } else { t };
    let lum: Vec<f64> = image.texels.iter().map(|t| luminance(linear(*t)) as f64).collect();
    // Maximum along each row (wrapping around in u), then along columns (clamped at the poles).
    let mut row_max = vec![0.0f64; lum.len()];
    for y in 0..h {
        for x in 0..w {
            let at = |x: u32| lum[(y * w + x) as usize];
            let (left, right) = ((x + w - 1) % w, (x + 1) % w);
            row_max[(y * w + x) as usize] = at(left).max(at(x)).max(at(right));
        }
    }
    let mut weights = vec![0.0f64; lum.len()];
    for y in 0..h {
        let sin_theta = (std::f64::consts::PI * (y as f64 + 0.5) / h as f64).sin();
        for x in 0..w {
            let at = |y: u32| row_max[(y * w + x) as usize];
            let m = at(y.saturating_sub(1)).max(at(y)).max(at((y + 1).min(h - 1)));
            weights[(y * w + x) as usize] = m * sin_theta;
        }
    }
    weights
}

/// Cumulative sums of `values`, normalised to end at 1 (uniform steps if they sum to 0).
fn cumulative(values: &[f64]) -> (Vec<f32>, f64) {
    let total: f64 = values.iter().sum();
    let n = values.len() as f64;
    let mut running = 0.0;
    let mut cdf: Vec<f32> = values
        .iter()
        .enumerate()
        .map(|(i, v)| {
            running += v;
            if total > 0.0 { (running / total) as f32 } else { ((i + 1) as f64 / n) as f32 }
        })
        .collect();
    if let Some(last) = cdf.last_mut() {
        *last = 1.0;
    }
    (cdf, total)
}

impl Distribution {
    /// The distribution of `image`'s texels, sRGB codes where `srgb` (weighed decoded).
    pub fn new(image: &EnvironmentImage, srgb: bool) -> Self {
        let weights = cell_weights(image, srgb);
        let w = image.width as usize;
        let mut conditional = Vec::with_capacity(weights.len());
        let mut row_sums = Vec::with_capacity(image.height as usize);
        for row in weights.chunks_exact(w) {
            let (cdf, sum) = cumulative(row);
            conditional.extend(cdf);
            row_sums.push(sum);
        }
        let (marginal, total) = cumulative(&row_sums);
        Self { conditional, marginal, total }
    }

    /// Probability of cell (x, y), as the GPU computes it from the cumulative sums.
    pub fn cell_probability(&self, width: u32, x: u32, y: u32) -> f64 {
        let before = |cdf: &[f32], i: usize| if i == 0 { 0.0 } else { cdf[i - 1] as f64 };
        let row = &self.conditional[(y * width) as usize..((y + 1) * width) as usize];
        (self.marginal[y as usize] as f64 - before(&self.marginal, y as usize))
            * (row[x as usize] as f64 - before(row, x as usize))
    }
}

/// The GPU's view of an environment (see `shaders/environment.wgsl`): per texel its
/// RGB and, in w, its row's cumulative probability up to it; then the rows' cumulative
/// probabilities, four to an entry.
pub fn gpu_entries(image: &EnvironmentImage, distribution: &Distribution) -> Vec<[f32; 4]> {
    let mut entries: Vec<[f32; 4]> =
        image.texels.iter().zip(&distribution.conditional).map(|(t, c)| [t[0], t[1], t[2], *c]).collect();
    for rows in distribution.marginal.chunks(4) {
        let mut entry = [1.0; 4];
        entry[..rows.len()].copy_from_slice(rows);
        entries.push(entry);
    }
    entries
}

/// Bytes that [`gpu_entries`] takes for a `width` × `height` image.
pub fn gpu_bytes(width: u32, height: u32) -> u64 {
    (width as u64 * height as u64 + (height as u64).div_ceil(4)) * 16
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: u32, height: u32, f: impl Fn(u32, u32) -> f32) -> EnvironmentImage {
        let texels = (0..height).flat_map(|y| (0..width).map(move |x| (x, y))).map(|(x, y)| [f(x, y); 3]).collect();
        EnvironmentImage::new(width, height, texels).unwrap()
    }

    #[test]
    fn probabilities_follow_luminance_times_sin_theta() {
        let img = image(8, 4, |x, _| 1.0 + x as f32);
        let d = Distribution::new(&img, false);
        let total: f64 =
            (0..4).flat_map(|y| (0..8).map(move |x| (x, y))).map(|(x, y)| d.cell_probability(8, x, y)).sum();
        assert!((total - 1.0).abs() < 1e-6, "{total}");
        // Rows 1 and 2 are nearer the equator than 0 and 3: sin(3π/8) / sin(π/8).
        let ratio = d.cell_probability(8, 3, 1) / d.cell_probability(8, 3, 0);
        let expected = (3.0 * std::f64::consts::PI / 8.0).sin() / (std::f64::consts::PI / 8.0).sin();
        assert!((ratio - expected).abs() < 1e-5, "{ratio} vs {expected}");
        // Column 3's neighbourhood peaks at column 4 (luminance 5), column 6's at 7 (luminance 8).
        let cols = d.cell_probability(8, 6, 1) / d.cell_probability(8, 3, 1);
        assert!((cols - 8.0 / 5.0).abs() < 1e-5, "{cols}");
    }

    #[test]
    fn a_bright_spot_and_its_ring_take_the_samples() {
        let img = image(64, 32, |x, y| if (30..32).contains(&x) && (10..12).contains(&y) { 1e4 } else { 1.0 });
        let d = Distribution::new(&img, false);
        let spot: f64 =
            (9..13).flat_map(|y| (29..33).map(move |x| (x, y))).map(|(x, y)| d.cell_probability(64, x, y)).sum();
        assert!(spot > 0.95, "{spot}");
    }

    #[test]
    fn black_images_and_bad_texels() {
        let d = Distribution::new(&image(4, 2, |_, _| 0.0), false);
        assert_eq!(d.total, 0.0);
        assert!((d.cell_probability(4, 1, 1) - 1.0 / 8.0).abs() < 1e-7);
        assert!(EnvironmentImage::new(0, 4, vec![]).is_err());
        let nan = EnvironmentImage::new(2, 1, vec![[0.0; 3], [f32::NAN, 0.0, 0.0]]).unwrap_err();
        assert!(nan.to_string().contains("texel (1, 0)"), "{nan}");
        let neg = EnvironmentImage::new(1, 1, vec![[-1.0, 2.0, 0.0]]).unwrap();
        assert_eq!(neg.texels[0], [0.0, 2.0, 0.0]);
    }

    #[test]
    fn halving_averages_blocks() {
        let img = image(5, 2, |x, _| x as f32);
        let half = img.halved();
        assert_eq!((half.width, half.height), (2, 1));
        assert_eq!(half.texels, [[0.5; 3], [2.5; 3]]);
    }
}
