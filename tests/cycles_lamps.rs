//! rt against Cycles on scenes lit by Blender's lamps (`tests/cycles/make_refs.py`
//! builds them in bpy, renders the references with Cycles and exports the scenes with
//! `blender/rt_export.py`): the global mean and every 8×8 block's mean must agree
//! within bounds derived from the noise, in both of rt's sampling modes.

mod common;

use common::{gpu, reference, repo};
use rt::bvh::BuildQuality;
use rt::render::{Image, RenderRequest, Session};
use rt::scene::Sampling;

/// Samples per pixel of the committed references (`make_refs.py --spp`).
const REFERENCE_SPP: f64 = 4096.0;
/// Cycles' `max_bounces` in `make_refs.py` plus one: rt counts the first hit.
const MAX_BOUNCES: u32 = 5;
fn render(name: &str, sampling: Sampling, spp: u32) -> Image {
    let path = repo().join(format!("tests/cycles/scenes/{name}/{name}.toml"));
    let mut scene = rt::scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    scene.render.sampling = sampling;
    let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(session.features().lamps.any(), "{name}: no lamps");
    let mut request = RenderRequest::from_scene(session.scene());
    (request.spp, request.max_bounces) = (spp, MAX_BOUNCES);
    let (image, report) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(report.dropped.is_clean(), "{name}: {}", report.dropped);
    image
}

fn compare(name: &str, sampling: Sampling, spp: u32) -> reference::Comparison {
    let ours = render(name, sampling, spp);
    reference::compare(&ours, &repo().join(format!("tests/cycles/{name}.exr")), REFERENCE_SPP)
}

fn check(name: &str, sampling: Sampling, spp: u32) {
    compare(name, sampling, spp).check(&format!("{name} {sampling:?} {spp} spp"), "Cycles");
}

/// Without light sampling a small lamp is found by rare BSDF rays: the noise has a long
/// tail that 8×8 blocks at this sample count do not average out (their standard errors
/// are estimated low), so only the global mean is held to 4 σ.
fn check_mean(name: &str, sampling: Sampling, spp: u32) {
    compare(name, sampling, spp).check_mean(&format!("{name} {sampling:?} {spp} spp"), "Cycles");
}

#[test]
fn point_lamp_matches_cycles() {
    check("point", Sampling::Nee, 128);
}

#[test]
fn spot_lamp_matches_cycles() {
    check("spot", Sampling::Nee, 128);
}

#[test]
fn area_lamp_matches_cycles() {
    check("area", Sampling::Nee, 128);
}

#[test]
fn sun_lamp_matches_cycles() {
    check("sun", Sampling::Nee, 128);
}

#[test]
fn several_coloured_lamps_match_cycles() {
    check("several", Sampling::Nee, 128);
}

// Without light sampling only lamps with a shape light anything: BSDF rays must find
// them (the point, spot and sun here have a radius or an angle).

#[test]
fn area_and_sun_lamps_match_cycles_without_light_sampling() {
    check("area", Sampling::Resampled, 256);
    check("sun", Sampling::Resampled, 256);
}

#[test]
fn small_lamps_match_cycles_on_average_without_light_sampling() {
    check_mean("point", Sampling::Resampled, 128);
    check_mean("spot", Sampling::Resampled, 128);
}
