//! An image with the noise of each colour channel measured, not inferred: rt's
//! accumulation keeps the spread of a pixel's luminance only, so a comparison that holds
//! red, green and blue each to its own noise renders the image as `PARTS` disjoint sample
//! ranges (`first_sample`) of one session and reads each channel's standard error from how
//! the parts' means spread about their mean (batch means). The image itself is the render
//! of all the samples, at the same cost.

use rt::render::{Image, RenderRequest, Session};
use rt::scene::{FeatureSet, Scene};

/// Sample ranges per image: 7 degrees of freedom per pixel, ~450 per 8×8 block, so a
/// block's standard error is known within ~5 %.
pub const PARTS: u32 = 8;

pub struct Measured {
    /// The mean of every sample, with rt's error of luminance.
    pub image: Image,
    /// Each pixel's standard error of red, green and blue.
    pub channel_error: Vec<[f32; 3]>,
}

/// Renders `scene` with the request its own settings give, changed by `adjust` (whose
/// `spp` must be a multiple of [`PARTS`]), in [`PARTS`] sample ranges.
pub fn render_measured(scene: Scene, adjust: impl FnOnce(&mut RenderRequest)) -> (Measured, FeatureSet) {
    let mut session =
        Session::open(super::gpu(), scene, rt::bvh::BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let mut request = RenderRequest::from_scene(session.scene());
    adjust(&mut request);
    let spp = request.spp;
    assert!(spp.is_multiple_of(PARTS) && spp > 0, "{spp} spp do not split into {PARTS} parts");
    let parts: Vec<Image> = (0..PARTS)
        .map(|k| {
            let part = RenderRequest {
                spp: spp / PARTS,
                first_sample: request.first_sample + k * spp / PARTS,
                ..request.clone()
            };
            let (image, report) = session.render(&part, None).unwrap_or_else(|e| panic!("{e:#}"));
            assert!(report.dropped.is_clean(), "{}", report.dropped);
            image
        })
        .collect();
    (merge(&parts), session.features())
}

/// The parts' mean (they have equal sample counts: no adaptive sampling), alpha too, its
/// error of luminance from the parts' own, and each channel's from the parts' spread.
fn merge(parts: &[Image]) -> Measured {
    let k = parts.len() as f64;
    let first = &parts[0];
    let n = first.pixels.len();
    let mut pixels = Vec::with_capacity(n);
    let mut std_error = Vec::with_capacity(n);
    let mut channel_error = Vec::with_capacity(n);
    for i in 0..n {
        let mean = [0, 1, 2].map(|c| parts.iter().map(|p| p.pixels[i][c] as f64).sum::<f64>() / k);
        let spread = [0, 1, 2].map(|c| parts.iter().map(|p| (p.pixels[i][c] as f64 - mean[c]).powi(2)).sum::<f64>());
        pixels.push(mean.map(|v| v as f32));
        std_error.push((parts.iter().map(|p| (p.std_error[i] as f64).powi(2)).sum::<f64>().sqrt() / k) as f32);
        channel_error.push(spread.map(|s| (s / (k * (k - 1.0))).sqrt() as f32));
    }
    let sample_counts = (0..n).map(|i| parts.iter().map(|p| p.sample_counts[i]).sum()).collect();
    let samples = parts.iter().map(|p| p.samples).sum();
    let alpha = first.alpha.as_ref().map(|_| {
        let alpha = |p: &Image, i: usize| p.alpha.as_ref().map_or(1.0, |a| a[i] as f64);
        (0..n).map(|i| (parts.iter().map(|p| alpha(p, i)).sum::<f64>() / k) as f32).collect()
    });
    let image = Image { width: first.width, height: first.height, samples, pixels, std_error, sample_counts, alpha };
    Measured { image, channel_error }
}
