//! Small images spread each pixel's samples over several invocations ("lanes") and add
//! them up in sample order: the image, and its AOVs, are the same bit for bit whatever
//! the number of lanes and however samples are split into dispatches.

use crate::common;

use common::{gpu, repo};
use rt::bvh::BuildQuality;
use rt::render::{Aovs, Image, RenderRequest, Session};

/// What a render gives: its image and, when asked for, its AOVs.
struct Rendered {
    image: Image,
    aovs: Option<Aovs>,
    /// Samples per pixel of the last dispatch.
    last_dispatch: u32,
}

fn render(scene: &str, lanes: Option<u32>, samples_per_dispatch: u32, aovs: bool, noise_threshold: f32) -> Rendered {
    render_sized(scene, (24, 20), 12, lanes, samples_per_dispatch, aovs, noise_threshold)
}

fn render_sized(
    scene: &str,
    (width, height): (u32, u32),
    spp: u32,
    lanes: Option<u32>,
    samples_per_dispatch: u32,
    aovs: bool,
    noise_threshold: f32,
) -> Rendered {
    let scene = rt::scene::load(&repo().join(scene)).unwrap_or_else(|e| panic!("{e}"));
    let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let request = RenderRequest {
        width,
        height,
        spp,
        seed: 7,
        samples_per_dispatch: Some(samples_per_dispatch),
        sample_lanes: lanes,
        aovs,
        noise_threshold,
        adaptive_min_samples: 4,
        ..RenderRequest::from_scene(session.scene())
    };
    let (image, report) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(report.samples_per_pixel, spp);
    let expected_lanes = lanes.unwrap_or(1).min(samples_per_dispatch);
    assert_eq!(report.max_lanes, expected_lanes, "the dispatches took the lanes asked for");
    let aovs = aovs.then(|| session.aovs().unwrap_or_else(|e| panic!("{e:#}")));
    Rendered { image, aovs, last_dispatch: session.last_step().samples }
}

const SPREADS: [(u32, u32); 5] = [(2, 12), (5, 12), (12, 12), (3, 5), (64, 4)];

#[test]
fn lanes_leave_the_image_unchanged_bit_for_bit() {
    for scene in ["scenes/cornell_glass.toml", "scenes/sunset.toml"] {
        let plain = render(scene, Some(1), 12, false, 0.0);
        assert!(plain.image.pixels.iter().any(|p| p.iter().any(|c| *c > 0.0)), "{scene}: a black image proves nothing");
        for (lanes, per_dispatch) in SPREADS {
            let spread = render(scene, Some(lanes), per_dispatch, false, 0.0);
            assert_eq!(plain.image.pixels, spread.image.pixels, "{scene}: {lanes} lanes, {per_dispatch} per dispatch");
            assert_eq!(plain.image.std_error, spread.image.std_error, "{scene}: standard errors with {lanes} lanes");
        }
    }
}

/// With AOVs asked for (as `--denoise` does), the lanes keep each sample's albedo, normal
/// and depth beside its radiance and add them in sample order: beauty and every AOV layer
/// are those of one invocation per pixel, bit for bit, also under adaptive sampling.
#[test]
fn lanes_leave_the_aovs_unchanged_bit_for_bit() {
    // Glass (followed to the surface behind it) and the Cornell box's walls; the sunset's
    // sky, where camera rays leave the scene (no depth, black albedo).
    for (scene, threshold) in
        [("scenes/cornell_glass.toml", 0.0), ("scenes/sunset.toml", 0.0), ("scenes/cornell_glass.toml", 0.3)]
    {
        let what = format!("{scene}, noise threshold {threshold}");
        // Pixels stop between dispatches: under adaptive sampling every spread takes the
        // plain render's dispatches, of 4 samples.
        let (plain_per_dispatch, spreads) = match threshold > 0.0 {
            true => (4, &[(2, 4), (3, 4), (4, 4), (64, 4)][..]),
            false => (12, &SPREADS[..]),
        };
        let plain = render(scene, Some(1), plain_per_dispatch, true, threshold);
        let aovs = plain.aovs.as_ref().expect("AOVs");
        // Every layer must carry something, or losing it would go unseen.
        assert!(aovs.albedo.iter().any(|a| a.iter().any(|c| *c > 0.05)), "{what}: a black albedo proves nothing");
        assert!(aovs.normal.iter().any(|n| n.iter().any(|c| c.abs() > 0.5)), "{what}: no normals");
        assert!(aovs.depth.iter().any(|d| d.is_finite() && *d > 0.0), "{what}: no depth");
        if threshold > 0.0 {
            let counts = &plain.image.sample_counts;
            assert!(counts.iter().any(|n| *n < 12) && counts.contains(&12), "{what}: no pixel stopped");
        }
        for &(lanes, per_dispatch) in spreads {
            let spread = render(scene, Some(lanes), per_dispatch, true, threshold);
            let how = format!("{what}: {lanes} lanes, {per_dispatch} samples per dispatch");
            let got = spread.aovs.as_ref().expect("AOVs");
            assert_eq!(plain.image.pixels, spread.image.pixels, "{how}: beauty");
            assert_eq!(plain.image.std_error, spread.image.std_error, "{how}: standard errors");
            assert_eq!(plain.image.sample_counts, spread.image.sample_counts, "{how}: samples per pixel");
            assert_eq!(aovs.albedo, got.albedo, "{how}: albedo");
            assert_eq!(aovs.normal, got.normal, "{how}: normal");
            // Infinite where no sample hit: compared by bits, so that those match too.
            let bits = |d: &[f32]| d.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&aovs.depth), bits(&got.depth), "{how}: depth");
        }
    }
}

// Small windows take up to 1024 samples per dispatch: the lanes' scratch then holds more
// than the 256 samples of a dispatch before, and they still add up in order. (The
// reference takes its samples 12 at a time: lavapipe ends an invocation's loop after
// 65,535 turns of its loops together, and one invocation taking 300 samples of this
// scene passes that.)
#[test]
fn dispatches_of_more_than_256_samples_keep_the_image_bit_for_bit() {
    let scene = "scenes/cornell_glass.toml";
    let plain = render_sized(scene, (6, 5), 300, Some(1), 12, false, 0.0);
    let spread = render_sized(scene, (6, 5), 300, Some(7), 300, false, 0.0);
    assert!(plain.image.pixels.iter().any(|p| p.iter().any(|c| *c > 0.0)), "a black image proves nothing");
    assert_eq!(spread.last_dispatch, 300, "the 300 samples were not taken in one dispatch");
    assert_eq!(
        (plain.image.pixels, plain.image.std_error),
        (spread.image.pixels, spread.image.std_error),
        "7 lanes, 300 samples in one dispatch"
    );
}

// lavapipe silently ends an invocation's loops after 65,535 turns together, about 370
// samples of this scene: on a CPU a dispatch asked for 1000 samples of one lane takes
// them in safe pieces, so the image is the one of 12 samples at a time.
#[test]
fn long_fixed_dispatches_on_a_cpu_lose_no_samples() {
    let scene = "scenes/cornell_glass.toml";
    let plain = render_sized(scene, (6, 5), 1000, Some(1), 12, false, 0.0);
    let long = render_sized(scene, (6, 5), 1000, Some(1), 1000, false, 0.0);
    assert!(plain.image.pixels.iter().any(|p| p.iter().any(|c| *c > 0.0)), "a black image proves nothing");
    assert_eq!(
        (plain.image.pixels, plain.image.std_error),
        (long.image.pixels, long.image.std_error),
        "1000 samples per dispatch asked for"
    );
}
