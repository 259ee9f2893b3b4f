//! The film's alpha against Cycles (`tests/cycles/make_film_refs.py`): holdouts, and
//! Film › Transparent Glass. Colour within the noise of both renders (luminance per 8×8
//! block), and alpha per 8×8 block within 5 σ of Cycles' (σ of a sample's coverage at most
//! √(α(1 − α)), at both renders' sample counts).

use crate::common;

use common::layers::blocks;
use common::reference::check_against_cycles;
use common::repo;

const REFERENCE_SPP: f64 = 1024.0;
const SPP: u32 = 128;
const BLOCK: usize = 8;

fn check(name: &str) {
    let ours = check_against_cycles(name, SPP, 8, REFERENCE_SPP);
    let (w, h) = (ours.width, ours.height);
    let file = repo().join(format!("tests/cycles/{name}.exr"));
    let alpha = ours.alpha.as_ref().expect("the image has an alpha");
    let cycles = image::open(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display())).into_rgba32f();
    let cycles: Vec<f32> = cycles.pixels().map(|p| p.0[3]).collect();
    let per_sample = 1.0 / SPP as f64 + 1.0 / REFERENCE_SPP;
    let mut worst = (0.0f64, String::new());
    for ((bx, by), block) in blocks(w as usize, h as usize, BLOCK) {
        let n = block.len() as f64;
        let ours_mean = block.iter().map(|&i| alpha[i] as f64).sum::<f64>() / n;
        let theirs = block.iter().map(|&i| cycles[i] as f64).sum::<f64>() / n;
        let variance = block.iter().map(|&i| (cycles[i] * (1.0 - cycles[i])).max(0.0) as f64).sum::<f64>() / n;
        let bound = 5.0 * (variance / n * per_sample).sqrt() + 2e-3;
        let ratio = (ours_mean - theirs).abs() / bound;
        if ratio > worst.0 {
            worst = (ratio, format!("block ({bx}, {by}): alpha {ours_mean:.4} vs Cycles {theirs:.4}"));
        }
    }
    println!("{name} alpha: worst block at {:.2} of its bound: {}", worst.0, worst.1);
    assert!(worst.0 <= 1.0, "{name}: {} is {:.2} times its bound", worst.1, worst.0);
}

/// Holdouts with an opaque film: the Holdout shader, a constant Mix Shader share of it,
/// holes picked by noise, a held-out object and a held-out collection, in front of a mirror
/// that shows the objects' own materials.
#[test]
fn holdouts_cut_cycles_holes_in_colour_and_alpha() {
    check("holdouts");
}

/// Film › Transparent Glass: the sky seen through clear glass is left out, rough glass
/// over the Roughness Threshold stays opaque, and a holdout seen through the glass is a hole.
#[test]
fn transparent_glass_leaves_out_what_clear_glass_shows() {
    check("transparent_glass");
}
