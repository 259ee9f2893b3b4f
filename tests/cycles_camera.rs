//! rt's camera against Cycles (`tests/cycles/make_camera_refs.py` renders the references
//! and exports the scenes with `blender/rt_export.py`): a rolled camera, an orthographic
//! one without and with depth of field, lens shift with a vertical sensor fit, and depth
//! of field through a round and a six-bladed anamorphic aperture. The scenes only emit, so
//! the images differ only where the camera's rays go. 8×8-block means and the global mean
//! must agree within bounds derived from the noise at the sample counts used.

mod common;

use common::{render, repo};

/// Samples per pixel of the committed references (`make_camera_refs.py --spp`).
const REFERENCE_SPP: f64 = 8192.0;
/// rt's samples per pixel here.
const SPP: u32 = 256;
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
    let dir = repo().join(format!("tests/cycles/scenes/camera_{name}"));
    let scene = rt::scene::load(&dir.join("scene.toml")).unwrap_or_else(|e| panic!("{e}"));
    let (w, h) = (scene.render.width, scene.render.height);
    let reference = image::open(repo().join(format!("tests/cycles/camera_{name}.exr")))
        .unwrap_or_else(|e| panic!("camera_{name}.exr: {e}"))
        .into_rgb32f();
    assert_eq!((reference.width(), reference.height()), (w, h), "{name}: reference size");
    // Surfaces only emit: one bounce finds nothing more.
    let ours = render(scene, w, h, SPP, 1);
    // The reference's own noise, estimated from ours: the same estimator, more samples.
    let noise_scale = (1.0 + SPP as f64 / REFERENCE_SPP).sqrt();
    let reference: Vec<[f32; 3]> = reference.pixels().map(|p| p.0).collect();

    let n = ours.pixels.len() as f64;
    let ours_mean = ours.pixels.iter().map(|p| luminance(*p)).sum::<f64>() / n;
    let ref_mean = reference.iter().map(|p| luminance(*p)).sum::<f64>() / n;
    let global_sigma = ours.std_error.iter().map(|e| (*e as f64).powi(2)).sum::<f64>().sqrt() / n * noise_scale;
    let global_z = (ours_mean - ref_mean).abs() / global_sigma.max(1e-12);

    let mut worst_block_z: f64 = 0.0;
    // (x, y) of the worst block, with its luminance in rt and in Cycles.
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
            // Blocks with no noise at all (inside a face, the world) must match to rounding.
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
        "camera_{name:11} mean {ours_mean:.5} vs Cycles {ref_mean:.5}: {:+.3}% ({:.2} σ); worst 8x8 block ({bx}, {by}): {a:.5} vs {b:.5}, {:.2} σ",
        100.0 * c.relative_mean_error,
        c.global_z,
        c.worst_block_z
    );
    c
}

fn check(name: &str) {
    let c = compare(name);
    // 48–64 blocks per image: at 5 σ a block fails by chance with probability ~6e-7.
    assert!(c.global_z <= 4.0, "camera_{name}: global mean is {:.2} σ from Cycles'", c.global_z);
    assert!(c.worst_block_z <= 5.0, "camera_{name}: a block is {:.2} σ from Cycles'", c.worst_block_z);
}

#[test]
fn rolled_camera_matches_cycles() {
    check("rolled");
}

#[test]
fn orthographic_camera_matches_cycles() {
    check("ortho");
}

#[test]
fn orthographic_depth_of_field_matches_cycles() {
    check("ortho_dof");
}

#[test]
fn lens_shift_with_vertical_sensor_fit_matches_cycles() {
    check("shift");
}

#[test]
fn depth_of_field_round_aperture_matches_cycles() {
    check("dof_round");
}

#[test]
fn depth_of_field_six_blades_anamorphic_matches_cycles() {
    check("dof_blades");
}
