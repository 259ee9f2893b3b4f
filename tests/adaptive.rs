//! Adaptive sampling: pixels whose noise is below the threshold stop taking samples,
//! and the image converges to the same one.

use crate::common;

use common::{gpu, luminance, repo};
use rt::bvh::BuildQuality;
use rt::render::{Image, RenderReport, RenderRequest, Session};

const SIZE: u32 = 32;

fn render(scene: &str, spp: u32, noise_threshold: f32, seed: u32) -> Image {
    render_spread(scene, spp, noise_threshold, seed, Some(1), 8).0
}

/// A render with `lanes` invocations per pixel, `samples_per_dispatch` samples each dispatch.
fn render_spread(
    scene: &str,
    spp: u32,
    noise_threshold: f32,
    seed: u32,
    lanes: Option<u32>,
    samples_per_dispatch: u32,
) -> (Image, RenderReport) {
    let scene = rt::scene::load(&repo().join(scene)).unwrap_or_else(|e| panic!("{e}"));
    let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let request = RenderRequest {
        width: SIZE,
        height: SIZE,
        spp,
        seed,
        noise_threshold,
        adaptive_min_samples: 16,
        samples_per_dispatch: Some(samples_per_dispatch),
        sample_lanes: lanes,
        ..RenderRequest::from_scene(session.scene())
    };
    let (image, report) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(report.features.adaptive, noise_threshold > 0.0);
    (image, report)
}

/// A GPU spreads a small image's samples over lanes; adaptive sampling must keep them
/// (stopped pixels skipped, samples numbered per pixel) and give the same image bit for
/// bit as one invocation per pixel: values, standard errors and per-pixel counts.
#[test]
fn adaptive_sampling_spread_over_lanes_is_the_same_image_bit_for_bit() {
    let scene = "scenes/cornell_box.toml";
    for (lanes, per_dispatch) in [(4, 8), (3, 5)] {
        let (one, _) = render_spread(scene, 64, 0.1, 3, Some(1), per_dispatch);
        let (spread, report) = render_spread(scene, 64, 0.1, 3, Some(lanes), per_dispatch);
        assert_eq!(report.max_lanes, lanes, "the adaptive render did not use the lanes asked for");
        let stopped = one.sample_counts.iter().filter(|&&n| n < 64).count();
        assert!(stopped > 0, "no pixel stopped early: the case proves nothing");
        assert_eq!(one.sample_counts, spread.sample_counts, "{lanes} lanes: per-pixel sample counts");
        assert_eq!(one.pixels, spread.pixels, "{lanes} lanes, {per_dispatch} samples per dispatch");
        assert_eq!(one.std_error, spread.std_error, "{lanes} lanes: standard errors");
        eprintln!(
            "{lanes} lanes, {per_dispatch} per dispatch: identical; {stopped} of {} pixels stopped early",
            SIZE * SIZE
        );
    }
}

#[test]
fn a_threshold_no_pixel_reaches_changes_nothing() {
    let plain = render("scenes/cornell_box.toml", 24, 0.0, 5);
    let adaptive = render("scenes/cornell_box.toml", 24, 1e-9, 5);
    assert_eq!(plain.pixels, adaptive.pixels, "per-pixel sample counts changed the samples taken");
    assert!(adaptive.sample_counts.iter().all(|&n| n == 24));
}

#[test]
fn adaptive_matches_the_full_render_within_noise_with_fewer_samples_where_it_is_flat() {
    let spp = 256;
    let full = render("scenes/cornell_box.toml", spp, 0.0, 1);
    let adaptive = render("scenes/cornell_box.toml", spp, 0.1, 2);
    let n = full.pixels.len();
    // Same image: 4×4 blocks of luminance agree within their standard errors.
    let mut z2 = Vec::new();
    for by in 0..SIZE / 4 {
        for bx in 0..SIZE / 4 {
            let (mut diff, mut var) = (0.0, 0.0);
            for y in by * 4..by * 4 + 4 {
                for x in bx * 4..bx * 4 + 4 {
                    let i = (y * SIZE + x) as usize;
                    diff += luminance(adaptive.pixels[i]) - luminance(full.pixels[i]);
                    var += (adaptive.std_error[i] as f64).powi(2) + (full.std_error[i] as f64).powi(2);
                }
            }
            if var > 0.0 {
                z2.push(diff * diff / var);
            }
        }
    }
    let worst = z2.iter().cloned().fold(0.0, f64::max).sqrt();
    let mean_z2 = z2.iter().sum::<f64>() / z2.len() as f64;
    let taken: u64 = adaptive.sample_counts.iter().map(|&c| c as u64).sum();
    let share = taken as f64 / (n as u64 * spp as u64) as f64;
    eprintln!(
        "adaptive vs full: mean z² {mean_z2:.2} over {} blocks, worst |z| {worst:.2}; samples taken {:.0}%",
        z2.len(),
        share * 100.0
    );
    assert!(worst < 4.5, "a block differs by {worst:.1} sigma");
    assert!(mean_z2 < 1.6, "blocks differ by more than their noise: mean z² {mean_z2:.2}");
    assert!(share < 0.8, "adaptive sampling took {:.0}% of the samples", share * 100.0);
    // Where the full render is least noisy (relative to its brightness) pixels stopped
    // early; where it is noisiest they kept sampling.
    let mut by_noise: Vec<usize> = (0..n).filter(|&i| luminance(full.pixels[i]) > 1e-3).collect();
    by_noise.sort_by(|&a, &b| {
        let rel = |i: usize| full.std_error[i] as f64 / luminance(full.pixels[i]);
        rel(a).total_cmp(&rel(b))
    });
    let quarter = by_noise.len() / 4;
    let mean_count =
        |ids: &[usize]| ids.iter().map(|&i| adaptive.sample_counts[i] as f64).sum::<f64>() / ids.len() as f64;
    let (flat, noisy) = (mean_count(&by_noise[..quarter]), mean_count(&by_noise[by_noise.len() - quarter..]));
    eprintln!("mean samples: flattest quarter {flat:.0}, noisiest quarter {noisy:.0}");
    assert!(flat < 0.5 * noisy, "flat pixels took {flat:.0} samples, noisy ones {noisy:.0}");
    assert!(adaptive.sample_counts.iter().all(|&c| c >= 16), "a pixel stopped before the minimum");
}
