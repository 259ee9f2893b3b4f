//! rt's AOVs against Cycles' render passes of the same scene
//! (`tests/cycles/make_pass_refs.py`): the Diffuse Color pass, per colour channel and 8×8
//! block.

use crate::common;

use common::repo;
use std::collections::BTreeMap;

const SPP: u32 = 64;
const BLOCK: usize = 8;

/// A multilayer EXR's channels by full name (`ViewLayer.DiffCol.R`, …).
fn channels(path: &std::path::Path) -> (usize, BTreeMap<String, Vec<f32>>) {
    let image =
        exr::prelude::read_all_flat_layers_from_file(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut all = BTreeMap::new();
    let mut width = 0;
    for layer in &image.layer_data {
        width = layer.size.0;
        let prefix = layer.attributes.layer_name.as_ref().map(|n| format!("{n}.")).unwrap_or_default();
        for channel in &layer.channel_data.list {
            all.insert(format!("{prefix}{}", channel.name), channel.sample_data.values_as_f32().collect());
        }
    }
    (width, all)
}

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
    let (width, cycles) = channels(&repo().join("tests/cycles/pass_diffuse_color.exr"));
    assert_eq!(width, w);
    let pass = |c: &str| {
        let found = cycles.iter().find(|(k, _)| k.ends_with(&format!("Diffuse Color.{c}")));
        found.unwrap_or_else(|| panic!("no Diffuse Color.{c} among {:?}", cycles.keys().collect::<Vec<_>>())).1
    };
    let theirs = [pass("R"), pass("G"), pass("B")];
    let mut worst = (0.0f64, String::new());
    for by in 0..h / BLOCK {
        for bx in 0..w / BLOCK {
            for (c, cycles_channel) in theirs.iter().enumerate() {
                let (mut a, mut b) = (0.0f64, 0.0f64);
                for y in by * BLOCK..(by + 1) * BLOCK {
                    for x in bx * BLOCK..(bx + 1) * BLOCK {
                        a += aovs.diffuse_color[y * w + x][c] as f64;
                        b += cycles_channel[y * w + x] as f64;
                    }
                }
                let n = (BLOCK * BLOCK) as f64;
                let ratio = (a - b).abs() / n / (0.004 + 0.01 * (b / n));
                if ratio > worst.0 {
                    worst = (ratio, format!("block ({bx}, {by}) channel {c}: {:.4} vs Cycles {:.4}", a / n, b / n));
                }
            }
        }
    }
    println!("diffuse colour: worst block at {:.2} of its bound: {}", worst.0, worst.1);
    assert!(worst.0 <= 1.0, "{} is {:.2} times its bound", worst.1, worst.0);
}
