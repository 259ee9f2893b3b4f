//! Structural similarity (SSIM, Wang, Bovik, Sheikh and Simoncelli 2004, "Image quality
//! assessment: from error visibility to structural similarity"): the perceptual figure
//! beside RMSE and PSNR. As in the paper: on one channel (here the luma of the display
//! transform, in [0, 1]), local means, variances and covariance under an 11×11
//! circular Gaussian window of σ = 1.5 normalised to unit sum, C1 = (0.01 L)² and
//! C2 = (0.03 L)² with L = 1, and the mean over every window that lies inside the image
//! (the authors' code's "valid" filtering). Images smaller than the window use one as
//! wide or high as they are.

/// Side of the window and the Gaussian's standard deviation, in pixels.
const WINDOW: usize = 11;
const SIGMA: f64 = 1.5;
const C1: f64 = 0.01 * 0.01;
const C2: f64 = 0.03 * 0.03;

/// Mean SSIM of two single-channel images of `width`×`height`, rows from the top;
/// 1 when they are equal. Panics only if the slices are not of that size.
pub fn ssim(a: &[f64], b: &[f64], width: usize, height: usize) -> f64 {
    assert!(a.len() == width * height && b.len() == width * height, "images of {width}x{height} expected");
    if width == 0 || height == 0 {
        return 1.0;
    }
    let (wx, wy) = (WINDOW.min(width), WINDOW.min(height));
    let (kx, ky) = (gaussian(wx), gaussian(wy));
    // Products first, then one separable weighted sum of each over every valid window.
    let products: [Vec<f64>; 5] = [
        a.to_vec(),
        b.to_vec(),
        a.iter().map(|v| v * v).collect(),
        b.iter().map(|v| v * v).collect(),
        a.iter().zip(b).map(|(x, y)| x * y).collect(),
    ];
    let [mx, my, xx, yy, xy] = products.map(|p| filter_valid(&p, width, height, &kx, &ky));
    let n = mx.len();
    let mut sum = 0.0;
    for i in 0..n {
        let (mu_x, mu_y) = (mx[i], my[i]);
        let var_x = xx[i] - mu_x * mu_x;
        let var_y = yy[i] - mu_y * mu_y;
        let cov = xy[i] - mu_x * mu_y;
        sum += (2.0 * mu_x * mu_y + C1) * (2.0 * cov + C2) / ((mu_x * mu_x + mu_y * mu_y + C1) * (var_x + var_y + C2));
    }
    sum / n as f64
}

/// A Gaussian of σ = 1.5 over `n` taps, normalised to unit sum (a product of two is the
/// paper's circular window normalised the same way).
fn gaussian(n: usize) -> Vec<f64> {
    let centre = (n as f64 - 1.0) / 2.0;
    let taps: Vec<f64> = (0..n).map(|i| (-((i as f64 - centre).powi(2)) / (2.0 * SIGMA * SIGMA)).exp()).collect();
    let total: f64 = taps.iter().sum();
    taps.into_iter().map(|t| t / total).collect()
}

/// Weighted sums of `image` under the window at every position where it fits.
fn filter_valid(image: &[f64], width: usize, height: usize, kx: &[f64], ky: &[f64]) -> Vec<f64> {
    let (ow, oh) = (width + 1 - kx.len(), height + 1 - ky.len());
    let mut rows = vec![0.0; ow * height];
    for y in 0..height {
        let line = &image[y * width..(y + 1) * width];
        for x in 0..ow {
            rows[y * ow + x] = kx.iter().zip(&line[x..]).map(|(k, v)| k * v).sum();
        }
    }
    let mut out = vec![0.0; ow * oh];
    for y in 0..oh {
        for x in 0..ow {
            out[y * ow + x] = ky.iter().enumerate().map(|(j, k)| k * rows[(y + j) * ow + x]).sum();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic pattern with structure at several scales, in [0.1, 0.9].
    fn pattern(width: usize, height: usize) -> Vec<f64> {
        (0..width * height)
            .map(|i| {
                let (x, y) = ((i % width) as f64, (i / width) as f64);
                0.5 + 0.25 * (x * 0.7).sin() * (y * 0.3).cos() + 0.15 * ((x + 2.0 * y) * 0.11).sin()
            })
            .collect()
    }

    #[test]
    fn identical_images_have_ssim_one() {
        let a = pattern(40, 30);
        assert!((ssim(&a, &a, 40, 30) - 1.0).abs() < 1e-12);
        let flat = vec![0.3; 40 * 30];
        assert!((ssim(&flat, &flat, 40, 30) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn window_weights_sum_to_one_and_peak_in_the_middle() {
        let k = gaussian(WINDOW);
        assert!((k.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        // exp(-25 / 4.5) against the centre: the paper's window at its rim.
        assert!((k[0] / k[5] - (-25.0f64 / 4.5).exp()).abs() < 1e-15);
    }

    /// A constant offset d between flat images of level μ leaves only the luminance
    /// term: (2μ(μ+d) + C1) / (μ² + (μ+d)² + C1), worked out by hand.
    #[test]
    fn a_brightness_shift_of_flat_images_matches_the_luminance_term() {
        let (mu, d) = (0.4, 0.1);
        let a = vec![mu; 32 * 32];
        let b = vec![mu + d; 32 * 32];
        // 2·0.4·0.5 + 1e-4 = 0.4001; 0.16 + 0.25 + 1e-4 = 0.4101.
        let expected = 0.4001 / 0.4101;
        assert!((ssim(&a, &b, 32, 32) - expected).abs() < 1e-12, "{}", ssim(&a, &b, 32, 32));
    }

    /// A flat image against one with ±e noise in a checkerboard: no covariance and
    /// (nearly) equal means, so SSIM = C2 / (σ² + C2) times the luminance term, with σ²
    /// the checkerboard's variance under the window: e² less the square of its weighted
    /// mean offset. For e = 0.05: 9e-4 / (2.5e-3 + 9e-4) = 0.265.
    #[test]
    fn checkerboard_noise_on_a_flat_image_matches_the_contrast_term() {
        let (mu, e) = (0.5, 0.05);
        let (w, h) = (24, 24);
        let a = vec![mu; w * h];
        let b: Vec<f64> = (0..w * h).map(|i| if (i % w + i / w) % 2 == 0 { mu + e } else { mu - e }).collect();
        // Under a separable window, the weighted mean of (−1)^(x+y) is (Σ_i k_i (−1)^i)²
        // up to a sign, whichever window: every window has the same variance.
        let k = gaussian(WINDOW);
        let alternating: f64 = k.iter().enumerate().map(|(i, k)| if i % 2 == 0 { *k } else { -k }).sum();
        let offset = e * alternating * alternating;
        let var_b = e * e - offset * offset;
        // The offset's sign alternates from window to window; 14 × 14 windows, half of each.
        let luminance = |mean_b: f64| (2.0 * mu * mean_b + C1) / (mu * mu + mean_b * mean_b + C1);
        let expected = 0.5 * (luminance(mu + offset) + luminance(mu - offset)) * C2 / (var_b + C2);
        let got = ssim(&a, &b, w, h);
        assert!((got - expected).abs() < 1e-9, "SSIM {got}, by hand {expected}");
        assert!((got - 0.0009 / 0.0034).abs() < 1e-6, "{got}");
    }

    /// Shifting a textured image by one pixel lowers SSIM; it stays symmetric.
    #[test]
    fn a_one_pixel_shift_lowers_ssim_symmetrically() {
        let (w, h) = (40, 30);
        let a = pattern(w + 1, h);
        let left: Vec<f64> = (0..w * h).map(|i| a[(i / w) * (w + 1) + i % w]).collect();
        let right: Vec<f64> = (0..w * h).map(|i| a[(i / w) * (w + 1) + i % w + 1]).collect();
        let s = ssim(&left, &right, w, h);
        assert!((s - ssim(&right, &left, w, h)).abs() < 1e-12);
        assert!(s < 0.95 && s > 0.0, "{s}");
    }

    #[test]
    fn images_smaller_than_the_window_use_one_window() {
        let a = pattern(5, 4);
        assert!((ssim(&a, &a, 5, 4) - 1.0).abs() < 1e-12);
        let b: Vec<f64> = a.iter().map(|v| v * 0.5).collect();
        assert!(ssim(&a, &b, 5, 4) < 1.0);
    }
}
