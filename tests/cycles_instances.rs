//! rt against Cycles on scenes built from instances in Blender
//! (`tests/cycles/make_instance_refs.py` builds, exports and renders them): nested
//! collection instances with a material override, a geometry-nodes scatter and a hair
//! particle system. The global mean must agree within 4 σ and every 8×8 block within
//! 5 σ, σ estimated from rt's own noise at the sample counts used.

mod common;

use common::{render, repo};

/// Samples per pixel of the committed references (`make_instance_refs.py --spp`).
const REFERENCE_SPP: f64 = 8192.0;
const SPP: u32 = 256;
/// Cycles renders with 16 bounces of each kind.
const MAX_BOUNCES: u32 = 16;
const BLOCK: usize = 8;

fn luminance(p: [f32; 3]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// (global z, worst block z) of rt's render of `instances_{name}` against Cycles'.
fn compare(name: &str) -> (f64, f64) {
    let folder = repo().join(format!("tests/cycles/scenes/instances_{name}"));
    let scene = rt::scene::load(&folder.join("scene.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert!(!scene.instance_sets.is_empty(), "{name}: the export wrote no [[instances]]");
    let instances: usize = scene
        .instance_sets
        .iter()
        .map(|s| rt::asset::rtinst::read(&s.file).unwrap_or_else(|e| panic!("{e}")).len())
        .sum();
    let (w, h) = (scene.render.width, scene.render.height);
    let reference = image::open(repo().join(format!("tests/cycles/instances_{name}.exr")))
        .unwrap_or_else(|e| panic!("instances_{name}.exr: {e}"))
        .into_rgb32f();
    assert_eq!((reference.width(), reference.height()), (w, h), "{name}: reference size");
    let reference: Vec<[f32; 3]> = reference.pixels().map(|p| p.0).collect();
    let ours = render(scene, w, h, SPP, MAX_BOUNCES);
    // The reference's own noise, estimated from ours: similar estimators, more samples.
    let noise_scale = (1.0 + SPP as f64 / REFERENCE_SPP).sqrt();

    let n = ours.pixels.len() as f64;
    let ours_mean = ours.pixels.iter().map(|p| luminance(*p)).sum::<f64>() / n;
    let ref_mean = reference.iter().map(|p| luminance(*p)).sum::<f64>() / n;
    let global_sigma = ours.std_error.iter().map(|e| (*e as f64).powi(2)).sum::<f64>().sqrt() / n * noise_scale;
    let global_z = (ours_mean - ref_mean).abs() / global_sigma.max(1e-12);

    let (mut worst_z, mut worst) = (0.0f64, (0, 0, 0.0, 0.0));
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
            // Blocks with no noise in rt (sky seen directly) must match to rounding: Cycles'
            // f32 sums of 8192 samples leave it a few parts in 10⁴ (measured: up to 1.9e-4).
            let z = if sigma > 0.0 {
                diff / sigma
            } else if diff <= 5e-4 * b.abs() / count {
                0.0
            } else {
                f64::INFINITY
            };
            if z > worst_z {
                (worst_z, worst) = (z, (bx, by, a / count, b / count));
            }
        }
    }
    let (bx, by, a, b) = worst;
    println!(
        "instances_{name:12} {instances} instances; mean {ours_mean:.5} vs Cycles {ref_mean:.5}: {:+.3}% ({global_z:.2} σ); \
         worst 8x8 block ({bx}, {by}): {a:.5} vs {b:.5}, {worst_z:.2} σ",
        100.0 * (ours_mean - ref_mean) / ref_mean
    );
    (global_z, worst_z)
}

fn check(name: &str) {
    let (global_z, worst_block_z) = compare(name);
    // 64 blocks per image: at 5 σ a block fails by chance with probability ~6e-7.
    assert!(global_z <= 4.0, "{name}: global mean is {global_z:.2} σ from Cycles'");
    assert!(worst_block_z <= 5.0, "{name}: a block is {worst_block_z:.2} σ from Cycles'");
}

#[test]
fn nested_collection_instances_with_a_material_override_match_cycles() {
    check("collections");
}

#[test]
fn geometry_nodes_scatter_and_hair_particles_match_cycles() {
    // "pile" runs nodes that output only instances: its cones are placed, it is not a mesh.
    let folder = repo().join("tests/cycles/scenes/instances_scatter");
    assert!(!folder.join("assets/pile").exists(), "an object with only instances was exported as a mesh");
    let cones = rt::asset::rtinst::read(&folder.join("scene_instances/cone.rtinst")).unwrap_or_else(|e| panic!("{e}"));
    assert!(cones.len() > 40, "{} cones: the pile's instances are missing (the lawn's hair has 40)", cones.len());
    check("scatter");
}
