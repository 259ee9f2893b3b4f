//! Each kind of lamp over a white-ish floor against its closed form: the irradiance
//! under it, seen through a narrow camera looking straight down, so every pixel sees
//! radiance albedo / π × E. Light sampling and BSDF sampling (`seed`) must both find it.

use crate::common;

use common::{render, scene_from, temp_dir, write};
use std::f64::consts::PI;
use std::path::PathBuf;
use std::sync::OnceLock;

const ALBEDO: f64 = 0.8;
const HEIGHT: f64 = 2.0;

/// The mean of the image's luminance and its standard error.
fn floor_radiance(light: &str, sampling: &str, spp: u32) -> (f64, f64) {
    // Written once: the tests run in parallel and share the file.
    static FLOOR: OnceLock<PathBuf> = OnceLock::new();
    let floor = FLOOR.get_or_init(|| {
        let path = temp_dir("lamps").join("floor.obj");
        write(&path, "v -20 0 -20\nv 20 0 -20\nv 20 0 20\nv -20 0 20\nf 1 3 2\nf 1 4 3\n");
        path
    });
    let text = format!(
        "[render]\nsampling = \"{sampling}\"\n\
         [camera]\nposition = [0.0, 1.0, 0.001]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 0.05\n\
         [materials.floor]\nbase_color = [{ALBEDO}, {ALBEDO}, {ALBEDO}]\n\
         [[mesh]]\nasset = \"{}\"\nmaterial = \"floor\"\n[[light]]\n{light}\n",
        floor.display()
    );
    let image = render(scene_from(&text), 8, 8, spp, 1);
    let n = image.pixels.len() as f64;
    let mean = image.pixels.iter().map(|p| p[1] as f64).sum::<f64>() / n;
    let error = image.std_error.iter().map(|e| (*e as f64).powi(2)).sum::<f64>().sqrt() / n;
    (mean, error)
}

/// Irradiance `e` on the floor, as rt renders it with either sampling scheme.
fn check(what: &str, light: &str, e: f64, samplings: &[&str]) {
    let expected = ALBEDO / PI * e;
    for sampling in samplings {
        let spp = if *sampling == "seed" { 1024 } else { 64 };
        let (mean, error) = floor_radiance(light, sampling, spp);
        let z = (mean - expected).abs() / (error + 2e-5 * expected + 1e-9);
        println!("{what:28} {sampling}: {mean:.6} vs {expected:.6} ({z:.2} σ)");
        assert!(z < 4.0, "{what} ({sampling}): {mean} vs {expected}, {z:.1} σ");
    }
}

const AT: &str = "position = [0.0, 2.0, 0.0]";

#[test]
fn point_lamps_give_power_over_four_pi_d_squared() {
    let p = 100.0;
    // A point has intensity P / 4π; no BSDF ray can find it.
    check("point", &format!("type = \"point\"\npower = {p}\n{AT}"), p / (4.0 * PI * HEIGHT * HEIGHT), &["nee"]);
    // A sphere of radiance P / (4π · π r²) gives E = L π sin²θ = P / (4π d²) outside it.
    let sphere = format!("type = \"point\"\npower = {p}\nradius = 0.3\nsoft_falloff = false\n{AT}");
    check("sphere", &sphere, p / (4.0 * PI * HEIGHT * HEIGHT), &["nee", "seed"]);
    // The disk facing the shaded point: E = L π r² / (r² + d²) on its axis.
    let disk = format!("type = \"point\"\npower = {p}\nradius = 0.3\n{AT}");
    check("soft falloff disk", &disk, p / (4.0 * PI * (0.09 + HEIGHT * HEIGHT)), &["nee", "seed"]);
}

#[test]
fn spot_edge_is_cycles_smoothstep() {
    let (size_deg, blend): (f64, f64) = (60.0, 0.5);
    let cos_half = (size_deg.to_radians() / 2.0).cos();
    for tilt_deg in [0.0f64, 22.0, 26.0, 29.0, 35.0] {
        let t = tilt_deg.to_radians();
        let f = ((t.cos() - cos_half) / ((1.0 - cos_half) * blend)).clamp(0.0, 1.0);
        let attenuation = f * f * (3.0 - 2.0 * f);
        let light = format!(
            "type = \"spot\"\npower = 100\nspot_size_deg = {size_deg}\nspot_blend = {blend}\n{AT}\ndirection = [{}, {}, 0.0]",
            t.sin(),
            -t.cos()
        );
        let e = 100.0 / (4.0 * PI * HEIGHT * HEIGHT) * attenuation;
        check(&format!("spot tilted {tilt_deg}°"), &light, e, &["nee"]);
    }
}

#[test]
fn a_spot_with_a_radius_is_the_point_it_is_made_of_inside_its_cone() {
    // Blender's default spot: soft falloff, so a disk facing the shaded point.
    let spot = format!("type = \"spot\"\npower = 100\nradius = 0.3\nspot_size_deg = 90\n{AT}");
    check("spot with a radius", &spot, 100.0 / (4.0 * PI * (0.09 + HEIGHT * HEIGHT)), &["nee", "seed"]);
}

#[test]
fn camera_rays_see_only_lamps_visible_to_the_camera() {
    // A 1 m² area lamp between the camera and the floor, facing the camera: a path passes
    // through it to the floor, which it does not light; the pixel is the lamp's radiance.
    let facing_up = "type = \"area\"\nsize = 1.0\npower = 30\nposition = [0.0, 0.5, 0.0]\ndirection = [0.0, 1.0, 0.0]";
    for sampling in ["nee", "seed"] {
        let (seen, _) = floor_radiance(&format!("{facing_up}\nvisible_to_camera = true"), sampling, 4);
        assert!((seen - 30.0 / PI).abs() < 1e-4 * seen, "{sampling}: a visible lamp shows {seen}, not {}", 30.0 / PI);
        let (hidden, _) = floor_radiance(facing_up, sampling, 4);
        assert_eq!(hidden, 0.0, "{sampling}: a lamp hidden from the camera shows");
    }
}

#[test]
fn area_lamps_give_power_over_pi_area_radiance_from_their_front_only() {
    // A disk of radius R and radiance P / (π · π R²) facing the floor: E = P / (π (R² + h²)).
    let (p, r) = (50.0, 0.5);
    let disk = format!("type = \"area\"\nshape = \"disk\"\nsize = {}\npower = {p}\n{AT}", 2.0 * r);
    check("disk", &disk, p / (PI * (r * r + HEIGHT * HEIGHT)), &["nee", "seed"]);
    // An ellipse and a rectangle, their radiance P / (π · area) integrated numerically:
    // E = L ∫ h² / (x² + y² + h²)² dA right under the centre.
    let (a, b) = (0.6f64, 0.25f64);
    let steps = 400;
    let kernel = |x: f64, y: f64| HEIGHT * HEIGHT / (x * x + y * y + HEIGHT * HEIGHT).powi(2);
    let (mut ellipse_integral, mut rectangle_integral) = (0.0, 0.0);
    for i in 0..steps {
        for j in 0..steps {
            let (u, v) = ((i as f64 + 0.5) / steps as f64, (j as f64 + 0.5) / steps as f64);
            let (rho, phi) = (u, 2.0 * PI * v);
            let jacobian = a * b * rho * 2.0 * PI / (steps * steps) as f64;
            ellipse_integral += kernel(a * rho * phi.cos(), b * rho * phi.sin()) * jacobian;
            rectangle_integral +=
                kernel(a * (2.0 * u - 1.0), b * (2.0 * v - 1.0)) * 4.0 * a * b / (steps * steps) as f64;
        }
    }
    let ellipse =
        format!("type = \"area\"\nshape = \"ellipse\"\nsize = {}\nsize_y = {}\npower = {p}\n{AT}", 2.0 * a, 2.0 * b);
    check("ellipse", &ellipse, p / (PI * PI * a * b) * ellipse_integral, &["nee", "seed"]);
    let rectangle =
        format!("type = \"area\"\nshape = \"rectangle\"\nsize = {}\nsize_y = {}\npower = {p}\n{AT}", 2.0 * a, 2.0 * b);
    check("rectangle", &rectangle, p / (PI * 4.0 * a * b) * rectangle_integral, &["nee", "seed"]);
    // Facing up, it lights nothing below.
    let away = format!("{disk}\ndirection = [0.0, 1.0, 0.0]");
    check("disk facing away", &away, 0.0, &["nee", "seed"]);
}

#[test]
fn sun_lamps_give_their_strength() {
    let elevation = 60f64.to_radians();
    let direction = format!("direction = [{}, {}, 0.0]", -elevation.cos(), -elevation.sin());
    check(
        "sun of angle 0",
        &format!("type = \"sun\"\nstrength = 3\nangle_deg = 0\n{direction}"),
        3.0 * elevation.sin(),
        &["nee"],
    );
    // A disk of angular radius θ and radiance S / (π sin²θ) above the horizon: the cone's
    // ∫ cos dω is π sin²θ times the cosine of its axis, so E is the same.
    let sun = format!("type = \"sun\"\nstrength = 3\nangle_deg = 10\n{direction}");
    check("sun of angle 10°", &sun, 3.0 * elevation.sin(), &["nee", "seed"]);
}
