//! rt against Cycles under a World with an Environment Texture
//! (`tests/cycles/make_environment_refs.py` builds the scenes in bpy, renders the
//! references with Cycles and exports the scenes with `blender/rt_export.py`): a real
//! HDRI (Blender's Poly Haven courtyard, DWAB, behind a rotating Mapping node, seen
//! directly and in a mirror ball) and a synthetic map with a tiny spot 10⁴ times
//! brighter than the rest. The global mean and every 8×8 block's mean must agree
//! within bounds derived from the noise, in both of rt's sampling modes.

use crate::common;

use common::measured::{Measured, render_measured};
use common::reference::{self, Noiseless};
use common::repo;
use rt::scene::{Sampling, SkyFeature};

/// Samples per pixel of the committed references (`make_environment_refs.py --spp`).
const REFERENCE_SPP: f64 = 2048.0;
/// Cycles' `max_bounces` in `make_refs.py` plus one: rt counts the first hit.
const MAX_BOUNCES: u32 = 5;

fn render(name: &str, sampling: Sampling, spp: u32) -> Measured {
    let path = repo().join(format!("tests/cycles/scenes/{name}/{name}.toml"));
    let mut scene = rt::scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    scene.render.sampling = sampling;
    let (image, features) = render_measured(scene, |r| (r.spp, r.max_bounces) = (spp, MAX_BOUNCES));
    assert_eq!(features.sky, SkyFeature::Environment, "{name}");
    image
}

fn check(name: &str, sampling: Sampling, spp: u32) {
    let ours = render(name, sampling, spp);
    let file = repo().join(format!("tests/cycles/{name}.exr"));
    let comparison = reference::compare_measured(&ours, &file, REFERENCE_SPP, Noiseless::Absolute(1e-5));
    comparison.check(&format!("{name} {sampling:?} {spp} spp"), "Cycles");
}

#[test]
fn courtyard_hdri_matches_cycles() {
    check("environment_courtyard", Sampling::Nee, 64);
}

#[test]
fn bright_spot_map_matches_cycles() {
    check("environment_spot", Sampling::Nee, 64);
}

/// Maps whose Color Space is sRGB, float and 8-bit: interpolated as codes and decoded
/// after, as Cycles does (decoding first lit the floor up to 49% brighter).
#[test]
fn srgb_maps_are_filtered_as_codes_as_in_cycles() {
    check("environment_srgb_spot", Sampling::Nee, 64);
    check("environment_srgb_stripes", Sampling::Nee, 64);
}

#[test]
fn courtyard_hdri_matches_cycles_without_light_sampling() {
    check("environment_courtyard", Sampling::Resampled, 128);
}
