//! Error of an image against the reference: on linear radiance (RMSE, and the
//! relative error of the image's mean, which shows bias such as missing bounces),
//! and after the PNG display transform (PSNR of what a viewer sees, and SSIM of its
//! luma: the structure a viewer sees, which blur and noise both lower).

use super::reference::Reference;
use rt::render::Image;
use rt::render::tonemap::{pbr_neutral, srgb_encode};

/// Errors of one image, or the average over repeats.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ErrorMetrics {
    /// Mean squared error of linear radiance over pixels and channels, less the
    /// reference's own noise: an estimate of the error against the converged image.
    pub mse: f64,
    /// (mean of the image − mean of the reference) / mean of the reference.
    pub relative_mean_error: f64,
    /// Mean squared error of display values in [0, 1] (exposed, tone-mapped, sRGB-encoded).
    pub display_mse: f64,
    /// Mean SSIM of the display luma against the reference's (1: the same picture).
    pub ssim: f64,
}

impl ErrorMetrics {
    pub fn of(image: &Image, reference: &Reference, exposure_ev: f32) -> Self {
        let values = (image.pixels.len() * 3).max(1) as f64;
        let (mut squared, mut sum, mut display_squared) = (0.0, 0.0, 0.0);
        for (p, r) in image.pixels.iter().zip(&reference.image.pixels) {
            let (dp, dr) = (display(*p, exposure_ev), display(*r, exposure_ev));
            for c in 0..3 {
                squared += (p[c] as f64 - r[c] as f64).powi(2);
                sum += p[c] as f64;
                display_squared += (dp[c] - dr[c]).powi(2);
            }
        }
        let (w, h) = (image.width as usize, image.height as usize);
        let ssim = super::ssim::ssim(
            &display_luma(&image.pixels, exposure_ev),
            &display_luma(&reference.image.pixels, exposure_ev),
            w,
            h,
        );
        Self {
            mse: (squared / values - reference.noise_mse).max(0.0),
            relative_mean_error: (sum / values - reference.mean) / reference.mean,
            display_mse: display_squared / values,
            ssim,
        }
    }

    /// The mean of several measurements (of squared errors, so RMSEs combine properly).
    pub fn mean(all: &[ErrorMetrics]) -> Self {
        let n = all.len().max(1) as f64;
        Self {
            mse: all.iter().map(|m| m.mse).sum::<f64>() / n,
            relative_mean_error: all.iter().map(|m| m.relative_mean_error).sum::<f64>() / n,
            display_mse: all.iter().map(|m| m.display_mse).sum::<f64>() / n,
            ssim: all.iter().map(|m| m.ssim).sum::<f64>() / n,
        }
    }

    pub fn rmse(&self) -> f64 {
        self.mse.sqrt()
    }

    /// RMSE over the reference's mean radiance: "1 %" is an RMSE of a hundredth of it.
    pub fn relative_rmse(&self, reference_mean: f64) -> f64 {
        self.rmse() / reference_mean
    }

    /// Peak signal-to-noise ratio of the display values, in dB (peak 1).
    pub fn psnr_db(&self) -> f64 {
        -10.0 * self.display_mse.max(1e-12).log10()
    }
}

/// Rec. 709 luma of the display values: the one channel SSIM is taken on.
pub fn display_luma(pixels: &[[f32; 3]], exposure_ev: f32) -> Vec<f64> {
    pixels
        .iter()
        .map(|p| {
            let d = display(*p, exposure_ev);
            0.2126 * d[0] + 0.7152 * d[1] + 0.0722 * d[2]
        })
        .collect()
}

/// The PNG display transform before 8-bit quantisation (which would add its own error floor).
fn display(radiance: [f32; 3], exposure_ev: f32) -> [f64; 3] {
    let scale = exposure_ev.exp2();
    pbr_neutral(radiance.map(|v| v.max(0.0) * scale)).map(|v| srgb_encode(v) as f64)
}
