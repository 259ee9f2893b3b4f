//! Normal maps through the whole pipeline on the GPU, against the closed form: a flat
//! diffuse quad whose normal map tilts its normal by a known angle, lit by the sun
//! alone, has radiance ρ · cos(mapped normal, sun) · G, with G Cycles' bump shadowing
//! (see `bump_shadowing` in `crates/rt/shaders/bsdf.wgsl`). The quad's glTF has no tangents, so
//! they come from MikkTSpace at import; tilting towards u and towards v, with the sun on
//! either side, checks the tangent, the bitangent's sign and the map's decoding.

use crate::common;

use common::quad_gltf::textured_quad;
use common::{render, scene_from, temp_dir, write};
use glam::DVec3;

const ALBEDO: f64 = 0.8;
const SUN_ELEVATION_DEG: f64 = 40.0;

/// A 4×4 PNG of one colour.
fn png(rgb: [u8; 3]) -> Vec<u8> {
    let image = image::RgbImage::from_pixel(4, 4, image::Rgb(rgb));
    let mut bytes = Vec::new();
    image.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png).expect("encode PNG");
    bytes
}

/// A 2 m quad in the y = 0 plane facing +y, u along +x and (rt's) v along +z, with
/// `normal.png` as its normal map of scale `scale`.
fn quad_gltf(scale: f64) -> String {
    let corners = [[-1.0f32, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 0.0, -1.0], [-1.0, 0.0, -1.0]];
    let material = format!(
        r#"{{ "name": "bumped", "normalTexture": {{ "index": 0, "scale": {scale} }},
    "pbrMetallicRoughness": {{ "baseColorFactor": [{ALBEDO}, {ALBEDO}, {ALBEDO}, 1.0], "metallicFactor": 0.0 }},
    "extensions": {{ "KHR_materials_specular": {{ "specularFactor": 0.0 }} }} }}"#
    );
    textured_quad(corners, &material, "normal.png", None)
}

/// The tangent-space normal `n` as 8-bit codes, and what they decode to.
fn encode(n: DVec3) -> ([u8; 3], DVec3) {
    let code = |c: f64| ((c + 1.0) * 0.5 * 255.0).round() as u8;
    let codes = [code(n.x), code(n.y), code(n.z)];
    (codes, DVec3::new(codes[0] as f64, codes[1] as f64, codes[2] as f64) / 255.0 * 2.0 - 1.0)
}

/// Mean radiance of the quad (the middle of the image) with a map tilting the normal
/// by `tilt_deg` towards +u (`along_u`) or +v, of scale `scale`, under a sun at
/// `azimuth_deg`; and what it must be.
fn render_tilted(
    name: &str,
    tilt_deg: f64,
    along_u: bool,
    scale: f64,
    azimuth_deg: f64,
    sampling: &str,
) -> (f64, f64, f64) {
    let t = tilt_deg.to_radians();
    let tangent_space = if along_u { DVec3::new(t.sin(), 0.0, t.cos()) } else { DVec3::new(0.0, t.sin(), t.cos()) };
    let (codes, c) = encode(tangent_space);
    let dir = temp_dir(&format!("normal-map-{name}"));
    std::fs::write(dir.join("normal.png"), png(codes)).expect("png");
    write(&dir.join("quad.gltf"), &quad_gltf(scale));
    let scene = scene_from(&format!(
        "[camera]\nposition = [0.0, 3.0, 0.5]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 15.0\n\
         [sky]\nkind = \"black\"\n\
         [sun]\nelevation_deg = {SUN_ELEVATION_DEG}\nazimuth_deg = {azimuth_deg}\n\
         [render]\nsampling = \"{sampling}\"\n\
         [[mesh]]\nasset = {:?}\n",
        dir.join("quad.gltf").display().to_string()
    ));
    let image = render(scene, 16, 16, 64, 1);
    let n = image.pixels.len() as f64;
    let mean = image.pixels.iter().map(|p| p[1] as f64).sum::<f64>() / n;
    let error = image.std_error.iter().map(|e| (*e as f64).powi(2)).sum::<f64>().sqrt() / n;

    // World frame: tangent +x, bitangent +z (rt's v), normal +y.
    let mapped = DVec3::new(c.x * scale, c.z, c.y * scale).normalize();
    let (e, a) = (SUN_ELEVATION_DEG.to_radians(), azimuth_deg.to_radians());
    let wi = DVec3::new(e.cos() * a.sin(), e.sin(), e.cos() * a.cos());
    let (cos_d, cos_i) = (mapped.y, wi.y);
    let alpha2 = (0.125 * (1.0 / (cos_d * cos_d) - 1.0)).clamp(0.0, 1.0);
    let shadowing = 2.0 / (1.0 + (1.0 + alpha2 * (1.0 - cos_i * cos_i) / (cos_i * cos_i)).sqrt());
    (mean, ALBEDO * mapped.dot(wi).max(0.0) * shadowing, error)
}

fn check(name: &str, tilt_deg: f64, along_u: bool, scale: f64, azimuth_deg: f64, sampling: &str) {
    let (ours, expected, error) = render_tilted(name, tilt_deg, along_u, scale, azimuth_deg, sampling);
    let flat = ALBEDO * SUN_ELEVATION_DEG.to_radians().sin();
    println!("{name}: {ours:.5} (± {error:.5}), expected {expected:.5}; without the map {flat:.5}");
    // The sun's disk (0.53°) spreads the cosine by under 1e-5; 4 standard errors for the rest.
    assert!(
        (ours - expected).abs() <= 1e-3 * expected + 4.0 * error,
        "{name}: {ours:.5} but the closed form gives {expected:.5}"
    );
}

#[test]
fn a_map_tilting_towards_u_turns_the_surface_to_a_sun_on_that_side() {
    check("u-towards", 20.0, true, 1.0, 90.0, "nee");
    check("u-away", 20.0, true, 1.0, 270.0, "nee");
}

#[test]
fn a_map_tilting_towards_v_follows_the_bitangent() {
    check("v-towards", 20.0, false, 1.0, 0.0, "nee");
    check("v-away", 20.0, false, 1.0, 180.0, "nee");
}

#[test]
fn the_scale_multiplies_the_maps_tilt() {
    check("scaled", 35.0, true, 0.5, 90.0, "nee");
}

#[test]
fn normal_maps_work_with_resampled_sampling() {
    check("resampled", 20.0, true, 1.0, 90.0, "resampled");
}
