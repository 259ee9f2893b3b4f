//! Shadow rays towards emitters: a ray that leaves a surface starts a little off it, and
//! must still end short of the light's point, whatever the angle it arrives at and
//! however far from the origin the scene lies.

use crate::common;

use common::{gpu, scene_from, temp_dir, write};
use rt::bvh::BuildQuality;
use rt::render::{RenderRequest, Session};

/// Irradiance at (x, `h` above the lamp's plane, z), facing the lamp: a 1 m square of
/// radiance 1 centred under it, facing up (midpoint quadrature of h² / r⁴).
fn irradiance_from_the_square(x: f64, z: f64, h: f64) -> f64 {
    let n = 400;
    let step = 1.0 / n as f64;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let (u, v) = (-0.5 + (i as f64 + 0.5) * step, -0.5 + (j as f64 + 0.5) * step);
            let r2 = (u - x).powi(2) + (v - z).powi(2) + h * h;
            sum += h * h / (r2 * r2);
        }
    }
    sum * step * step
}

#[test]
fn a_ceiling_just_above_a_lamps_back_gets_its_grazing_light() {
    // A ceiling 1 cm above a two-sided square lamp, both 2 m up: the ceiling around the
    // lamp is lit only by the lamp's back, at 0.4° to 6°. Shadow rays aimed from where
    // the ray had left the ceiling, parallel to the line from the point itself, met the
    // lamp's own surface first and lost all of that light.
    let (lamp, ceiling) = (1.99f32, 2.0f32);
    let obj = format!(
        "mtllib plates.mtl\nv -0.5 {lamp} -0.5\nv -0.5 {lamp} 0.5\nv 0.5 {lamp} 0.5\nv 0.5 {lamp} -0.5\n\
         v -3 {ceiling} -3\nv 3 {ceiling} -3\nv 3 {ceiling} 3\nv -3 {ceiling} 3\n\
         usemtl lamp\nf 1 4 3\nf 1 3 2\nusemtl ceiling\nf 5 6 7\nf 5 7 8\n"
    );
    let dir = temp_dir("grazing-light");
    write(&dir.join("plates.obj"), &obj);
    write(&dir.join("plates.mtl"), "newmtl lamp\nKd 0 0 0\nKe 1 1 1\nnewmtl ceiling\nKd 0.5 0.5 0.5\n");
    let scene = scene_from(&format!(
        "[render]\nmax_bounces = 1\nnoise_threshold = 0.0\n[camera]\nposition = [0.0, 1.0, 1.1]\n\
         look_at = [0.0, 2.0, 1.1]\nup = [0.0, 0.0, -1.0]\nfov_y_deg = 60.0\n[sky]\nkind = \"black\"\n\
         [[mesh]]\nasset = {:?}\n",
        dir.join("plates.obj").display().to_string()
    ));
    let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let request =
        RenderRequest { width: 24, height: 24, spp: 512, aovs: true, ..RenderRequest::from_scene(session.scene()) };
    let (image, _) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    let aovs = session.aovs().unwrap_or_else(|e| panic!("{e:#}"));
    let (mut rendered, mut expected, mut variance, mut pixels) = (0.0, 0.0, 0.0, 0);
    for (i, p) in aovs.position.iter().enumerate() {
        let beyond = (p[0].abs().max(p[2].abs()) - 0.5) as f64;
        // Ceiling points 0.1 m or more beyond the lamp's edge (nearer, the pixels' footprints
        // span too steep a change of light for their centre to stand for them).
        if (p[1] - ceiling).abs() > 1e-4 || beyond < 0.1 {
            continue;
        }
        let e = irradiance_from_the_square(p[0] as f64, p[2] as f64, (ceiling - lamp) as f64);
        rendered += image.pixels[i][0] as f64;
        expected += 0.5 / std::f64::consts::PI * e;
        variance += (image.std_error[i] as f64).powi(2);
        pixels += 1;
    }
    let sigma = variance.sqrt();
    println!("{pixels} pixels: rendered {rendered:.6e}, expected {expected:.6e} (σ {sigma:.2e})");
    assert!(pixels > 100, "the view holds the ceiling beyond the lamp");
    // 4σ of the noise, and 2 % for the pixels' footprints against their centres.
    assert!((rendered - expected).abs() <= 4.0 * sigma + 0.02 * expected, "rendered {rendered} vs {expected}");
}
