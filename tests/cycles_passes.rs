//! rt's AOVs against Cycles' render passes of the same scene
//! (`tests/cycles/make_pass_refs.py`): the Diffuse Color pass, per colour channel and 8×8
//! block.

use crate::common;

use common::layers::{blocks, channel, channels};
use common::repo;

const SPP: u32 = 64;
const BLOCK: usize = 8;

/// Principled spheres of every layer that takes from the diffuse (dielectric specular, half
/// metal, coat, sheen, some transmission) and a Diffuse BSDF: every 8×8 block's mean
/// Diffuse Color within 0.004 + 1 % of Cycles' per channel. The pass has no noise but for
/// the pixels' area at edges (both renders sample it with a box of one pixel), so the
/// bound is that of edges sampled at 64 and 1024 spp.
#[test]
fn diffuse_color_is_cycles_diffuse_color_pass() {
    let scene = rt::scene::load(&repo().join("tests/cycles/scenes/pass_diffuse_color/scene.toml")).unwrap();
    let (w, h) = (scene.render.width as usize, scene.render.height as usize);
    let mut session = rt::render::Session::open(common::gpu(), scene, rt::bvh::BuildQuality::Medium).unwrap();
    let mut request = rt::render::RenderRequest::from_scene(session.scene());
    (request.spp, request.max_bounces, request.aovs) = (SPP, 5, true);
    session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    let aovs = session.aovs().unwrap();
    let (width, _, cycles) = channels(&repo().join("tests/cycles/pass_diffuse_color.exr"));
    assert_eq!(width, w);
    let theirs = ["R", "G", "B"].map(|c| channel(&cycles, &format!("Diffuse Color.{c}")));
    let mut worst = (0.0f64, String::new());
    for ((bx, by), pixels) in blocks(w, h, BLOCK) {
        let n = pixels.len() as f64;
        for (c, cycles_channel) in theirs.iter().enumerate() {
            let a = pixels.iter().map(|&i| aovs.diffuse_color[i][c] as f64).sum::<f64>() / n;
            let b = pixels.iter().map(|&i| cycles_channel[i] as f64).sum::<f64>() / n;
            let ratio = (a - b).abs() / (0.004 + 0.01 * b);
            if ratio > worst.0 {
                worst = (ratio, format!("block ({bx}, {by}) channel {c}: {a:.4} vs Cycles {b:.4}"));
            }
        }
    }
    println!("diffuse colour: worst block at {:.2} of its bound: {}", worst.0, worst.1);
    assert!(worst.0 <= 1.0, "{} is {:.2} times its bound", worst.1, worst.0);
}
