//! rt's camera against Cycles (`tests/cycles/make_camera_refs.py` renders the references
//! and exports the scenes with `blender/rt_export.py`): a rolled camera, an orthographic
//! one without and with depth of field, lens shift with a vertical sensor fit, and depth
//! of field through a round and a six-bladed anamorphic aperture, clip planes of a wide
//! perspective and of an orthographic camera; and the panoramas among boxes all around:
//! equirectangular (whole, a shifted window, with depth of field, clipped), both fisheyes
//! and the mirror ball. The scenes only emit, so
//! the images differ only where the camera's rays go. 8×8-block means and the global mean
//! must agree within bounds derived from the noise at the sample counts used.

use crate::common;

use common::measured::render_measured;
use common::reference::Noiseless;
use common::{reference, repo};

/// Samples per pixel of the committed references (`make_camera_refs.py --spp`).
const REFERENCE_SPP: f64 = 8192.0;
/// rt's samples per pixel here.
const SPP: u32 = 256;
fn check(name: &str) {
    check_with(name, Noiseless::Absolute(1e-5));
}

/// A panorama sees the scene's every edge small: a sliver of a box inside one pixel that
/// rt's samples all miss leaves rt's block noiseless but not Cycles'. rt misses a feature
/// covering 4/SPP of a pixel with probability e^-4 (2 %); in these scenes of emission at
/// most 1, such a sliver moves an 8×8 block's mean luminance by at most 4 / SPP / 64.
fn check_panorama(name: &str) {
    check_with(name, Noiseless::Absolute(4.0 / SPP as f64 / 64.0));
}

fn check_with(name: &str, noiseless: Noiseless) {
    let dir = repo().join(format!("tests/cycles/scenes/camera_{name}"));
    let scene = rt::scene::load(&dir.join("scene.toml")).unwrap_or_else(|e| panic!("{e}"));
    // Surfaces only emit: one bounce finds nothing more.
    let (ours, _) = render_measured(scene, |r| (r.spp, r.max_bounces) = (SPP, 1));
    let reference_file = repo().join(format!("tests/cycles/camera_{name}.exr"));
    reference::compare_measured(&ours, &reference_file, REFERENCE_SPP, noiseless)
        .check(&format!("camera_{name}"), "Cycles");
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
    // A block of one emitter's face, inside the defocused edge of another: Cycles' 8192
    // samples meet the edge a few times, rt's 256 stratified ones need not (it then has
    // no noise there), as in the panoramas.
    check_panorama("dof_blades");
}

#[test]
fn clip_planes_match_cycles() {
    check("clipped");
}

#[test]
fn orthographic_clip_planes_match_cycles() {
    check("ortho_clipped");
}

#[test]
fn panorama_equirectangular_matches_cycles() {
    check_panorama("pano_equirect");
}

#[test]
fn panorama_equirectangular_window_with_shift_matches_cycles() {
    check_panorama("pano_equirect_window");
}

#[test]
fn panorama_equidistant_fisheye_matches_cycles() {
    check_panorama("pano_fisheye_equidistant");
}

#[test]
fn panorama_equisolid_fisheye_matches_cycles() {
    check_panorama("pano_fisheye_equisolid");
}

#[test]
fn panorama_equisolid_fisheye_with_vertical_fit_matches_cycles() {
    check_panorama("pano_fisheye_equisolid_vertical");
}

#[test]
fn panorama_mirror_ball_matches_cycles() {
    check_panorama("pano_mirror_ball");
}

#[test]
fn panorama_depth_of_field_matches_cycles() {
    check_panorama("pano_equirect_dof");
}

#[test]
fn panorama_clip_spheres_match_cycles() {
    check_panorama("pano_equirect_clipped");
}

/// Blender's pixel aspect: 2:1 pixels turn a portrait image into a landscape picture, so
/// the automatic fit spans the width (exported as `pixel_aspect`; square pixels, as rt
/// had before, fit the height and see a different view).
#[test]
fn pixel_aspect_matches_cycles() {
    check("pixel_aspect");
}

#[test]
fn pixel_aspect_shapes_the_equisolid_fisheyes_sensor_as_in_cycles() {
    check_panorama("pano_fisheye_equisolid_pixel_aspect");
}
