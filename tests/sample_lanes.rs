//! Small images spread each pixel's samples over several invocations ("lanes") and add
//! them up in sample order: the image is the same bit for bit whatever the number of
//! lanes and however samples are split into dispatches.

use crate::common;

use common::{gpu, repo};
use rt::bvh::BuildQuality;
use rt::render::{RenderRequest, Session};

fn render(scene: &str, lanes: Option<u32>, samples_per_dispatch: u32) -> (Vec<[f32; 3]>, Vec<f32>) {
    let (pixels, std_error, _) = render_sized(scene, (24, 20), 12, lanes, samples_per_dispatch);
    (pixels, std_error)
}

fn render_sized(
    scene: &str,
    (width, height): (u32, u32),
    spp: u32,
    lanes: Option<u32>,
    samples_per_dispatch: u32,
) -> (Vec<[f32; 3]>, Vec<f32>, u32) {
    let scene = rt::scene::load(&repo().join(scene)).unwrap_or_else(|e| panic!("{e}"));
    let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let request = RenderRequest {
        width,
        height,
        spp,
        seed: 7,
        samples_per_dispatch: Some(samples_per_dispatch),
        sample_lanes: lanes,
        ..RenderRequest::from_scene(session.scene())
    };
    let (image, report) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(report.samples_per_pixel, spp);
    (image.pixels, image.std_error, session.last_step().samples)
}

#[test]
fn lanes_leave_the_image_unchanged_bit_for_bit() {
    for scene in ["scenes/cornell_glass.toml", "scenes/sunset.toml"] {
        let plain = render(scene, Some(1), 12);
        for (lanes, per_dispatch) in [(2, 12), (5, 12), (12, 12), (3, 5), (64, 4)] {
            let spread = render(scene, Some(lanes), per_dispatch);
            assert!(plain.0.iter().any(|p| p.iter().any(|c| *c > 0.0)), "{scene}: a black image proves nothing");
            assert_eq!(plain.0, spread.0, "{scene}: {lanes} lanes, {per_dispatch} samples per dispatch");
            assert_eq!(plain.1, spread.1, "{scene}: standard errors with {lanes} lanes");
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
    let plain = render_sized(scene, (6, 5), 300, Some(1), 12);
    let spread = render_sized(scene, (6, 5), 300, Some(7), 300);
    assert!(plain.0.iter().any(|p| p.iter().any(|c| *c > 0.0)), "a black image proves nothing");
    assert_eq!(spread.2, 300, "the 300 samples were not taken in one dispatch");
    assert_eq!((plain.0, plain.1), (spread.0, spread.1), "7 lanes, 300 samples in one dispatch");
}

// lavapipe silently ends an invocation's loops after 65,535 turns together, about 370
// samples of this scene: on a CPU a dispatch asked for 1000 samples of one lane takes
// them in safe pieces, so the image is the one of 12 samples at a time.
#[test]
fn long_fixed_dispatches_on_a_cpu_lose_no_samples() {
    let scene = "scenes/cornell_glass.toml";
    let plain = render_sized(scene, (6, 5), 1000, Some(1), 12);
    let long = render_sized(scene, (6, 5), 1000, Some(1), 1000);
    assert!(plain.0.iter().any(|p| p.iter().any(|c| *c > 0.0)), "a black image proves nothing");
    assert_eq!((plain.0, plain.1), (long.0, long.1), "1000 samples per dispatch asked for");
}
