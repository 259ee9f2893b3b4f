//! rt against Mitsuba 3 on matched scenes (`tests/refs/make_refs.py` renders
//! the references): 8×8-block means and the global mean must agree within
//! bounds derived from the noise at the sample counts used.

mod common;

use common::{render, repo};

/// Samples per pixel of the committed references (`make_refs.py --spp`).
const REFERENCE_SPP: f64 = 8192.0;
const BLOCK: usize = 8;

fn luminance(p: [f32; 3]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

struct Comparison {
    relative_mean_error: f64,
    global_z: f64,
    worst_block_z: f64,
}

fn compare(name: &str) -> Comparison {
    let scene =
        rt::scene::load(&repo().join(format!("tests/refs/scenes/{name}.toml"))).unwrap_or_else(|e| panic!("{e}"));
    let (w, h, spp, bounces) = (scene.render.width, scene.render.height, scene.render.spp, scene.render.max_bounces);
    let reference = image::open(repo().join(format!("tests/refs/{name}.exr")))
        .unwrap_or_else(|e| panic!("{name}.exr: {e}"))
        .into_rgb32f();
    assert_eq!((reference.width(), reference.height()), (w, h), "{name}: reference size");
    let ours = render(scene, w, h, spp, bounces);
    // The reference's own noise, estimated from ours: similar estimators, more samples.
    let noise_scale = (1.0 + spp as f64 / REFERENCE_SPP).sqrt();
    let reference: Vec<[f32; 3]> = reference.pixels().map(|p| p.0).collect();

    let n = ours.pixels.len() as f64;
    let ours_mean = ours.pixels.iter().map(|p| luminance(*p)).sum::<f64>() / n;
    let ref_mean = reference.iter().map(|p| luminance(*p)).sum::<f64>() / n;
    let global_sigma = ours.std_error.iter().map(|e| (*e as f64).powi(2)).sum::<f64>().sqrt() / n * noise_scale;
    let global_z = (ours_mean - ref_mean).abs() / global_sigma.max(1e-12);

    let mut worst_block_z: f64 = 0.0;
    // (x, y) of the worst block, with its luminance in rt and in Mitsuba.
    let mut worst_block = (0, 0, 0.0, 0.0);
    for by in 0..h as usize / BLOCK {
        for bx in 0..w as usize / BLOCK {
            let (mut a, mut b, mut var) = (0.0, 0.0, 0.0);
            for y in by * BLOCK..(by + 1) * BLOCK {
                for x in bx * BLOCK..(bx + 1) * BLOCK {
                    let i = y * w as usize + x;
                    a += luminance(ours.pixels[i]);
                    b += luminance(reference[i]);
                    var += (ours.std_error[i] as f64).powi(2);
                }
            }
            let count = (BLOCK * BLOCK) as f64;
            let sigma = var.sqrt() / count * noise_scale;
            let diff = (a - b).abs() / count;
            // Blocks with no noise at all (background, emitters seen directly) must match to rounding.
            let z = if sigma > 0.0 {
                diff / sigma
            } else if diff < 1e-5 {
                0.0
            } else {
                f64::INFINITY
            };
            if z > worst_block_z {
                worst_block_z = z;
                worst_block = (bx, by, a / count, b / count);
            }
        }
    }
    let c = Comparison { relative_mean_error: (ours_mean - ref_mean) / ref_mean, global_z, worst_block_z };
    let (bx, by, a, b) = worst_block;
    println!(
        "{name:22} mean {ours_mean:.5} vs Mitsuba {ref_mean:.5}: {:+.3}% ({:.2} σ); worst 8x8 block ({bx}, {by}): {a:.5} vs {b:.5}, {:.2} σ",
        100.0 * c.relative_mean_error,
        c.global_z,
        c.worst_block_z
    );
    c
}

fn check(name: &str) {
    let c = compare(name);
    // 64 blocks per image: at 5 σ a block fails by chance with probability ~6e-7.
    assert!(c.global_z <= 4.0, "{name}: global mean is {:.2} σ from Mitsuba's", c.global_z);
    assert!(c.worst_block_z <= 5.0, "{name}: a block is {:.2} σ from Mitsuba's", c.worst_block_z);
}

#[test]
fn cornell_diffuse_matches_mitsuba() {
    check("cornell_diffuse");
}

#[test]
fn glass_and_tinted_mirror_match_mitsuba() {
    check("cornell_glass_mirror");
}

#[test]
fn rough_glass_matches_mitsuba() {
    check("rough_glass");
}

#[test]
fn absorbing_glass_matches_mitsuba() {
    check("absorbing_glass");
}

#[test]
fn rough_conductor_matches_mitsuba() {
    check("rough_conductor");
}

#[test]
fn diffuse_plus_glossy_matches_mitsuba() {
    check("glossy_mix");
}
