//! Small images spread each pixel's samples over several invocations ("lanes") and add
//! them up in sample order: the image is the same bit for bit whatever the number of
//! lanes and however samples are split into dispatches.

use crate::common;

use common::{gpu, repo};
use rt::bvh::BuildQuality;
use rt::render::{RenderRequest, Session};

fn render(scene: &str, lanes: Option<u32>, samples_per_dispatch: u32) -> (Vec<[f32; 3]>, Vec<f32>) {
    let scene = rt::scene::load(&repo().join(scene)).unwrap_or_else(|e| panic!("{e}"));
    let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let request = RenderRequest {
        width: 24,
        height: 20,
        spp: 12,
        seed: 7,
        samples_per_dispatch: Some(samples_per_dispatch),
        sample_lanes: lanes,
        ..RenderRequest::from_scene(session.scene())
    };
    let (image, report) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(report.samples_per_pixel, 12);
    (image.pixels, image.std_error)
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
