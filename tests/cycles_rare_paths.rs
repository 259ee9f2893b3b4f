//! Rows against Cycles whose light comes through rare paths: a sun seen through rough glass.
//! There a pixel's standard error, estimated from the samples it happened to take, misses
//! the rare bright ones: on the glass row at 128 spp it put an 8x8 block 34 σ from Cycles
//! while the block's mean moved by ±5–18% from one seed to the next. So the noise is
//! measured here from the spread of independent renders (batches, each with its own seed),
//! and the reference is rendered with 16,384 spp, its own noise scaled from one batch's
//! spread by the ratio of their samples (against the 2,048-spp reference, Cycles' own
//! blocks were 2–3% from its 16,384-spp ones). The row's mean and each sphere's must agree.
//! 8x8 blocks are printed, not checked: at 1024 spp they still scatter by ±2% between
//! seeds, with next-event estimation and with resampling alike, as far as they lie from
//! Cycles, and a spread of a few batches that mostly miss the rare paths underestimates
//! that (it put silhouette blocks 0.5–1.5% from Cycles at up to 14 σ).

use crate::common::{self, luminance, repo};
use rt::render::Image;

const BATCHES: u32 = 8;
const BATCH_SPP: u32 = 64;
const REFERENCE_SPP: f64 = 16384.0;
/// The references' bounce limit (`make_principled_refs.py`). Cycles' Max Bounces N shades
/// N + 1 surfaces along a path (0 is direct light), rt's `max_bounces` N shades N, so rt
/// renders with one more. On the glass rows the difference shows: light that grazes a
/// sphere's rim runs round inside it by near-total internal reflections, and at 12 in rt
/// the silhouettes' 8x8 blocks were 0.3–1.6% under Cycles' (pooled over the row's five
/// rims, 8192 spp: 0.7–1.9%); every bounce counts there (at 64 they are 10–22% over).
const CYCLES_MAX_BOUNCES: u32 = 12;
/// Each sphere is centred in its own 32-pixel-wide column of the 160 × 32 image.
const COLUMN: usize = 32;
const BLOCK: usize = 8;

/// A rectangle of pixels: x, y, width, height.
type Region = (usize, usize, usize, usize);

/// How far, in σ, rt's mean over `region` is from Cycles', σ measured from the batches.
fn sigmas(
    batches: &[Image],
    theirs: &image::Rgb32FImage,
    reference_spp: f64,
    (x0, y0, w, h): Region,
    relative: f64,
) -> (f64, f64, f64) {
    let width = batches[0].width as usize;
    let mean_of = |image: &Image| {
        let mut sum = 0.0;
        for y in y0..y0 + h {
            for x in x0..x0 + w {
                sum += luminance(image.pixels[y * width + x]);
            }
        }
        sum / (w * h) as f64
    };
    let means: Vec<f64> = batches.iter().map(mean_of).collect();
    let k = means.len() as f64;
    let ours = means.iter().sum::<f64>() / k;
    let spread = (means.iter().map(|m| (m - ours).powi(2)).sum::<f64>() / (k - 1.0)).sqrt();
    let mut cycles = 0.0;
    for y in y0..y0 + h {
        for x in x0..x0 + w {
            cycles += luminance(theirs.get_pixel(x as u32, y as u32).0);
        }
    }
    let cycles = cycles / (w * h) as f64;
    // rt's mean over all batches, and the reference's as many samples again as it has.
    let sigma =
        (spread * spread / k + spread * spread * BATCH_SPP as f64 / reference_spp + (relative * cycles).powi(2)).sqrt();
    (ours, cycles, (ours - cycles).abs() / sigma.max(1e-9))
}

/// rt against Cycles on the row `tests/cycles/scenes/NAME/`: its mean and each sphere
/// within 4 σ, σ from `BATCHES` renders of `BATCH_SPP` samples.
pub(crate) fn check_batched(name: &str, reference_spp: f64) {
    check_batched_against(name, name, reference_spp, CYCLES_MAX_BOUNCES, 0.0);
}

/// [`check_batched`] with each mean allowed `relative` of Cycles' beside its noise.
pub(crate) fn check_batched_within(name: &str, reference_spp: f64, relative: f64) {
    check_batched_against(name, name, reference_spp, CYCLES_MAX_BOUNCES, relative);
}

/// [`check_batched`] of the row `scene` against the reference `name`, rendered by Cycles
/// with Max Bounces `cycles_max_bounces`.
fn check_batched_against(scene: &str, name: &str, reference_spp: f64, cycles_max_bounces: u32, relative: f64) {
    let dir = repo().join(format!("tests/cycles/scenes/{scene}"));
    let scene = rt::scene::load(&dir.join("scene.toml")).unwrap_or_else(|e| panic!("{e}"));
    let (w, h) = (scene.render.width, scene.render.height);
    let batches: Vec<Image> = (1..=BATCHES)
        .map(|seed| {
            common::render_request(scene.clone(), |r| {
                (r.width, r.height, r.spp, r.max_bounces, r.seed) = (w, h, BATCH_SPP, cycles_max_bounces + 1, seed)
            })
            .0
        })
        .collect();
    let file = repo().join(format!("tests/cycles/{name}.exr"));
    let theirs = image::open(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display())).into_rgb32f();
    let (w, h) = (w as usize, h as usize);
    let mut worst_sphere: f64 = 0.0;
    for sphere in 0..w / COLUMN {
        let (ours, cycles, z) = sigmas(&batches, &theirs, reference_spp, (sphere * COLUMN, 0, COLUMN, h), relative);
        println!("{name} sphere {sphere}: rt {ours:.5} vs Cycles {cycles:.5}, {z:.2} σ");
        worst_sphere = worst_sphere.max(z);
    }
    let (ours, cycles, z) = sigmas(&batches, &theirs, reference_spp, (0, 0, w, h), relative);
    println!("{name}: mean rt {ours:.5} vs Cycles {cycles:.5} ({:+.3}%), {z:.2} σ", 100.0 * (ours / cycles - 1.0));
    let mut worst_block: (f64, usize, usize) = (0.0, 0, 0);
    for by in 0..h / BLOCK {
        for bx in 0..w / BLOCK {
            let z = sigmas(&batches, &theirs, reference_spp, (bx * BLOCK, by * BLOCK, BLOCK, BLOCK), relative).2;
            if z > worst_block.0 {
                worst_block = (z, bx, by);
            }
        }
    }
    println!("{name}: worst 8x8 block {:.2} σ at ({}, {}), not checked", worst_block.0, worst_block.1, worst_block.2);
    assert!(z <= 4.0, "{name}: the mean is {z:.2} σ from Cycles'");
    assert!(worst_sphere <= 4.0, "{name}: a sphere is {worst_sphere:.2} σ from Cycles'");
}

/// Specular Tint on rough glass under a sun: Cycles tints the reflection's F0 (a generalised
/// Schlick Fresnel that follows the real curve up to 1), so the highlight takes the tint.
#[test]
fn specular_tint_on_glass_matches_cycles() {
    check_batched("principled_glass_tint_sun", REFERENCE_SPP);
}

// The same row against Cycles at Max Bounces 1: the glass shows its reflections and what
// it lets through (two refractions), which rt shades at `max_bounces` 2; with 1, the
// spheres' insides were 83–96% under Cycles'.
#[test]
fn cycles_max_bounces_is_one_less_than_rts() {
    check_batched_against("principled_glass_tint_sun", "principled_glass_tint_sun_one_bounce", REFERENCE_SPP, 1, 0.0);
}

/// Glass of roughness 0.2 to 1 under a wide sun: what it lets through and its highlights.
#[test]
fn glass_roughness_under_a_sun_matches_cycles() {
    check_batched("principled_glass_roughness_sun", REFERENCE_SPP);
}
