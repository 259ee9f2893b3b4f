//! Two pipelines' renders of one scene compared colour channel by colour channel: both
//! render with the same seeds, so much of their noise is shared, and the spread of the
//! seed-by-seed differences of their means (over the image and each quarter) is the noise
//! the difference is judged by (a paired test).

use rt::render::{Image, RenderRequest, Session};
use rt::scene::FeatureSet;

/// Each channel's mean over the image and over its four quarters.
pub fn region_means(image: &Image) -> Vec<[f64; 3]> {
    let w = image.width as usize;
    let h = image.height as usize;
    let mut sums = vec![([0.0f64; 3], 0usize); 5];
    for (i, p) in image.pixels.iter().enumerate() {
        let (x, y) = (i % w, i / w);
        let quarter = 1 + usize::from(x >= w / 2) + 2 * usize::from(y >= h / 2);
        for region in [0, quarter] {
            for (sum, value) in sums[region].0.iter_mut().zip(p) {
                *sum += *value as f64;
            }
            sums[region].1 += 1;
        }
    }
    sums.into_iter().map(|(s, n)| s.map(|v| v / n.max(1) as f64)).collect()
}

/// The region means of `renders` renders of `features` by `request`, seeds 1, 2, …
pub fn renders(
    session: &mut Session,
    request: &RenderRequest,
    features: FeatureSet,
    renders: u32,
) -> Vec<Vec<[f64; 3]>> {
    (1..=renders)
        .map(|seed| {
            let r = RenderRequest { features: Some(features), seed, ..request.clone() };
            let (image, report) = session.render(&r, None).unwrap_or_else(|e| panic!("{e:#}"));
            assert!(report.dropped.is_clean(), "{}", report.dropped);
            assert_eq!(report.features, features);
            region_means(&image)
        })
        .collect()
}

fn mean_and_error(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (variance / n).sqrt())
}

/// The largest |z| of the seed-by-seed differences of `a` and `b` over channels and
/// regions, with where it is; a region without noise must agree to float rounding.
pub fn worst_z(a: &[Vec<[f64; 3]>], b: &[Vec<[f64; 3]>]) -> (f64, String) {
    let mut worst = (0.0, String::new());
    for region in 0..a[0].len() {
        for c in 0..3 {
            let differences: Vec<f64> = a.iter().zip(b).map(|(ra, rb)| ra[region][c] - rb[region][c]).collect();
            let (difference, error) = mean_and_error(&differences);
            let (mean, _) = mean_and_error(&a.iter().map(|r| r[region][c]).collect::<Vec<_>>());
            let sigma = error.max(1e-6 * mean.abs());
            let z = if sigma > 0.0 { difference.abs() / sigma } else { 0.0 };
            if z > worst.0 {
                let at =
                    format!("channel {c} of region {region}: {mean:.5} vs {:.5} (σ {sigma:.2e})", mean - difference);
                worst = (z, at);
            }
        }
    }
    worst
}

/// `renders` with channel `channel` of every region made `factor` times brighter.
pub fn scaled(renders: &[Vec<[f64; 3]>], channel: usize, factor: f64) -> Vec<Vec<[f64; 3]>> {
    let scale = |m: &[f64; 3]| std::array::from_fn(|c| m[c] * if c == channel { factor } else { 1.0 });
    renders.iter().map(|r| r.iter().map(scale).collect()).collect()
}
