//! `[sky] kind = "environment"`: a white furnace under a constant environment (EXR and
//! Radiance .hdr), importance sampling against uniform sampling on a map with a tiny,
//! very bright spot, and bad images (missing, corrupt, NaN or negative texels, no texels).

use crate::common;

use common::{gpu, render, scene_from, temp_dir};
use rt::bvh::BuildQuality;
use rt::render::{Image, Session};
use rt::scene::Sampling;
use std::path::{Path, PathBuf};

/// Writes a `width` × `height` image whose texel (x, y) (rows from the top) is `f(x, y)`.
fn write_map(path: &Path, width: u32, height: u32, f: impl Fn(u32, u32) -> [f32; 3]) {
    let image = image::Rgb32FImage::from_fn(width, height, |x, y| image::Rgb(f(x, y)));
    image.save(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

fn map_path(name: &str) -> PathBuf {
    temp_dir("environment").join(name)
}

fn environment(image: &Path, extra: &str) -> String {
    format!("[sky]\nkind = \"environment\"\nimage = {:?}\n{extra}\n", image.display().to_string())
}

const SPHERE: &str = "[camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 45.0\n\
                      [[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\n";

/// The mean is 1 within 4 standard errors, and so is every 8×8 block's. (Single pixels
/// are not held to it: with light sampling a sample is not 1 but has expectation 1, and
/// 16 samples of its skewed distribution estimate a pixel's standard error poorly.)
fn assert_all_one(image: &Image, what: &str) {
    let lum = |p: &[f32; 3]| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64;
    let (w, h) = (image.width as usize, image.height as usize);
    let mut worst: f64 = 0.0;
    for by in 0..h / 8 {
        for bx in 0..w / 8 {
            let pixels = (by * 8..by * 8 + 8).flat_map(|y| (bx * 8..bx * 8 + 8).map(move |x| y * w + x));
            let (sum, var) = pixels
                .fold((0.0, 0.0), |(s, v), i| (s + lum(&image.pixels[i]), v + (image.std_error[i] as f64).powi(2)));
            let z = (sum / 64.0 - 1.0).abs() / (var.sqrt() / 64.0 + 1e-7);
            worst = worst.max(z);
        }
    }
    let n = image.pixels.len() as f64;
    let mean = image.pixels.iter().map(lum).sum::<f64>() / n;
    let se = image.std_error.iter().map(|e| (*e as f64).powi(2)).sum::<f64>().sqrt() / n;
    println!("{what}: mean {mean:.6}, standard error {se:.2e}; worst 8x8 block {worst:.2} σ");
    assert!((mean - 1.0).abs() <= 4.0 * se + 1e-5, "{what}: mean {mean}");
    assert!(worst <= 5.0, "{what}: a block is {worst:.2} σ from 1");
}

#[test]
fn white_sphere_under_a_constant_environment_is_one_everywhere() {
    // Radiance 2 at strength 0.5: the sphere reflects exactly what it receives.
    let exr = map_path("two.exr");
    write_map(&exr, 16, 8, |_, _| [2.0; 3]);
    for sampling in [Sampling::Nee, Sampling::Resampled] {
        let mut scene = scene_from(&format!("{}{SPHERE}", environment(&exr, "strength = 0.5")));
        scene.render.sampling = sampling;
        assert_all_one(&render(scene, 64, 64, 16, 64), &format!("EXR furnace, {sampling:?}"));
    }
    // Radiance .hdr, rotated: still 1.
    let hdr = map_path("one.hdr");
    write_map(&hdr, 16, 8, |_, _| [1.0; 3]);
    let scene = scene_from(&format!("{}{SPHERE}", environment(&hdr, "rotation_deg = [30.0, 10.0, 75.0]")));
    assert_all_one(&render(scene, 64, 64, 16, 64), ".hdr furnace, rotated");
}

/// A dim map with a 2×2-texel spot 10⁴ times brighter, over a white ball on a floor
/// (a large sphere), seen from above so that no pixel shows the sky.
fn spot_scene(map: &Path, importance: bool) -> rt::scene::Scene {
    scene_from(&format!(
        "{}[camera]\nposition = [0.0, 3.0, 2.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 40.0\n\
         [[sphere]]\ncenter = [0.0, 0.5, 0.0]\nradius = 0.5\n\
         [[sphere]]\ncenter = [0.0, -1000.0, 0.0]\nradius = 1000.0\n",
        environment(map, &format!("importance_sampling = {importance}"))
    ))
}

fn rmse(a: &Image, b: &Image) -> (f64, f64) {
    let errors: Vec<f64> = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(p, q)| p.iter().zip(q).map(|(x, y)| (*x as f64 - *y as f64).abs()))
        .collect();
    let rmse = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
    (rmse, errors.iter().cloned().fold(0.0, f64::max))
}

#[test]
fn importance_sampling_finds_a_tiny_bright_spot() {
    let map = map_path("spot.exr");
    // The spot sits about 32° above the horizon (rows 20..22 of 64: θ ≈ 58° from the zenith).
    write_map(&map, 128, 64, |x, y| if (40..42).contains(&x) && (20..22).contains(&y) { [1e3; 3] } else { [0.1; 3] });
    let (w, h, bounces) = (48, 48, 4);
    let reference = render(spot_scene(&map, true), w, h, 256, bounces);
    let sampled = render(spot_scene(&map, true), w, h, 16, bounces);
    let uniform = render(spot_scene(&map, false), w, h, 16, bounces);
    let (is_rmse, is_max) = rmse(&sampled, &reference);
    let (uniform_rmse, uniform_max) = rmse(&uniform, &reference);
    println!(
        "bright spot, 16 spp against 256: importance sampling RMSE {is_rmse:.4} (worst pixel {is_max:.3}), \
         uniform RMSE {uniform_rmse:.4} (worst {uniform_max:.3}): {:.1}x",
        uniform_rmse / is_rmse
    );
    // The reference's own noise is in both; the uniform estimate is still far worse.
    assert!(uniform_rmse > 4.0 * is_rmse, "importance sampling gains only {:.2}x", uniform_rmse / is_rmse);
    // No fireflies: the worst pixel stays within a few RMSE of the reference.
    assert!(is_max < 8.0 * is_rmse, "a firefly: worst pixel error {is_max} against RMSE {is_rmse}");
}

fn open_error(scene: rt::scene::Scene) -> String {
    match Session::open(gpu(), scene, BuildQuality::Medium) {
        Ok(_) => panic!("the session opened"),
        Err(e) => format!("{e:#}"),
    }
}

#[test]
fn bad_images_are_errors_that_name_the_file() {
    let missing = map_path("missing.exr");
    let e = open_error(scene_from(&format!("{}{SPHERE}", environment(&missing, ""))));
    assert!(e.contains("missing.exr") && e.contains("cannot read: No such file"), "{e}");

    let corrupt = map_path("corrupt.exr");
    std::fs::write(&corrupt, b"v/1\x01this is not an OpenEXR file").unwrap();
    let e = open_error(scene_from(&format!("{}{SPHERE}", environment(&corrupt, ""))));
    assert!(e.contains("corrupt.exr") && e.contains("cannot read the image's header"), "{e}");

    let nan = map_path("nan.exr");
    write_map(&nan, 8, 4, |x, y| if (x, y) == (5, 2) { [f32::NAN, 0.0, 0.0] } else { [1.0; 3] });
    let e = open_error(scene_from(&format!("{}{SPHERE}", environment(&nan, ""))));
    assert!(e.contains("nan.exr") && e.contains("texel (5, 2)") && e.contains("finite"), "{e}");

    let empty = map_path("empty.hdr");
    std::fs::write(&empty, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n").unwrap();
    let e = open_error(scene_from(&format!("{}{SPHERE}", environment(&empty, ""))));
    assert!(e.contains("empty.hdr"), "{e}");
}

#[test]
fn negative_texels_emit_nothing() {
    // Negative everywhere but one grey row: the image is that row's light alone, finite.
    let map = map_path("negative.exr");
    write_map(&map, 8, 4, |_, y| if y == 1 { [0.5; 3] } else { [-3.0; 3] });
    let image = render(scene_from(&format!("{}{SPHERE}", environment(&map, ""))), 32, 32, 8, 4);
    assert!(image.pixels.iter().flatten().all(|c| c.is_finite() && *c >= 0.0));
    let mean = image.pixels.iter().flatten().sum::<f32>() / (3 * image.pixels.len()) as f32;
    assert!(mean > 0.0 && mean < 0.5, "mean {mean}");
}

#[test]
fn scene_errors_name_the_key() {
    let parse = |text: &str| rt::scene::parse(text, "scene.toml", Path::new(".")).map(|_| ()).unwrap_err().to_string();
    let e = parse("[sky]\nkind = \"environment\"\n");
    assert!(e.contains("image") && e.contains("required"), "{e}");
    let e = parse("[sky]\nkind = \"environment\"\nimage = \"a.exr\"\nstrength = -1.0\n");
    assert!(e.starts_with("scene.toml:4:") && e.contains("strength"), "{e}");
    let e = parse("[sky]\nkind = \"uniform\"\nimage = \"a.exr\"\n");
    assert!(e.contains("only applies to kind = \"environment\""), "{e}");
    let e = parse("[sky]\nkind = \"environment\"\nimage = \"a.exr\"\nrotation = [0.0, 0.0, 1.0]\n");
    assert!(e.contains("rotation_deg"), "did you mean: {e}");
}

/// Light adds up: the environment with a sun, or with a lamp, renders as the sum of
/// each alone (every 8×8 block within 5 σ). Light samples are shared between them, so
/// this fails if either's density leaves out its share.
#[test]
fn environment_and_other_lights_add_up() {
    let map = map_path("sky.exr");
    write_map(&map, 32, 16, |x, y| [0.2 + 0.1 * (x % 4) as f32, 0.3, if y < 6 { 1.0 } else { 0.1 }]);
    let objects = "[camera]\nposition = [0.0, 2.0, 3.0]\nlook_at = [0.0, 0.3, 0.0]\nfov_y_deg = 45.0\n\
                   [[sphere]]\ncenter = [0.0, 0.5, 0.0]\nradius = 0.5\n\
                   [[sphere]]\ncenter = [0.0, -1000.0, 0.0]\nradius = 1000.0\n";
    let sun = "[sun]\nelevation_deg = 40.0\nazimuth_deg = 30.0\nangular_diameter_deg = 5.0\n";
    let lamp = "[[light]]\ntype = \"point\"\npower = 40.0\nradius = 0.1\nposition = [1.0, 1.5, 1.0]\n";
    let frame = |text: String| render(scene_from(&text), 32, 32, 64, 3);
    let env_alone = frame(format!("{}{objects}", environment(&map, "")));
    for (name, other) in [("sun", sun), ("lamp", lamp)] {
        let both = frame(format!("{}{objects}{other}", environment(&map, "")));
        let alone = frame(format!("{objects}{other}"));
        let mut worst: f64 = 0.0;
        for by in 0..4 {
            for bx in 0..4 {
                let (mut diff, mut var) = (0.0, 0.0);
                for i in (by * 8..by * 8 + 8).flat_map(|y| (bx * 8..bx * 8 + 8).map(move |x| y * 32 + x)) {
                    let lum = |p: [f32; 3]| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64;
                    diff += lum(both.pixels[i]) - lum(env_alone.pixels[i]) - lum(alone.pixels[i]);
                    var += [&both, &env_alone, &alone].iter().map(|im| (im.std_error[i] as f64).powi(2)).sum::<f64>();
                }
                worst = worst.max(diff.abs() / var.sqrt().max(1e-9));
            }
        }
        println!("environment + {name} against the sum of each alone: worst 8x8 block {worst:.2} σ");
        assert!(worst <= 5.0, "environment + {name}: a block is {worst:.2} σ from the sum");
    }
}

/// A live edit (as `rt watch` applies it) from a uniform sky to an environment, then of
/// its strength alone (the image is not read again), gives the images a fresh session
/// gives, bit for bit.
#[test]
fn live_edits_of_the_environment_match_fresh_sessions() {
    let map = map_path("live.exr");
    write_map(&map, 16, 8, |x, y| [0.1 * x as f32, 0.5, 0.1 * y as f32]);
    let with = |extra: &str| scene_from(&format!("{}{SPHERE}", environment(&map, extra)));
    let draw = |session: &mut Session| {
        let mut request = rt::render::RenderRequest::from_scene(session.scene());
        (request.width, request.height, request.spp, request.max_bounces) = (32, 32, 4, 3);
        session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}")).0.pixels
    };
    let fresh = |scene| draw(&mut Session::open(gpu(), scene, BuildQuality::Medium).expect("a session"));
    let mut live =
        Session::open(gpu(), scene_from(&format!("[sky]\nkind = \"uniform\"\n{SPHERE}")), BuildQuality::Medium)
            .expect("a session");
    draw(&mut live);
    for extra in ["", "strength = 3.0", "strength = 3.0\nimportance_sampling = false"] {
        let update = rt::render::SceneUpdate { scene: with(extra), geometry: None, shaders: None };
        live.apply(update).unwrap_or_else(|e| panic!("{e:#}"));
        assert_eq!(draw(&mut live), fresh(with(extra)), "after the edit to {extra:?}");
    }
}

/// `[sky] sample_as_light`: a uniform sky sampled by next-event estimation is still 1 in
/// the furnace.
#[test]
fn a_uniform_sky_sampled_as_a_light_keeps_the_furnace_at_one() {
    let sky = "[sky]\nkind = \"uniform\"\nsample_as_light = true\n";
    let scene = scene_from(&format!("{sky}{SPHERE}"));
    let (image, features) =
        common::render_request(scene, |r| (r.width, r.height, r.spp, r.max_bounces) = (64, 64, 16, 64));
    assert!(features.flag("sky_uniform_light") == Some(true), "{features}");
    // Without light sampling every sample of the white ball is exactly 1.
    assert!(image.std_error.iter().any(|&e| e > 1e-4), "the sky was not sampled as a light");
    assert_all_one(&image, "uniform sky as a light");
}

/// The same sky with and without light sampling, over a ball on a floor with an emitting
/// ball beside them (shadows, and light shared between the sky and an emitter): the same
/// image within noise, per 8×8 block.
#[test]
fn a_uniform_sky_sampled_as_a_light_gives_the_same_image() {
    let scene = |sampled: bool| {
        scene_from(&format!(
            "[sky]\nkind = \"uniform\"\ncolor = [0.4, 0.5, 0.7]\nsample_as_light = {sampled}\n\
             [camera]\nposition = [0.0, 2.0, 3.0]\nlook_at = [0.0, 0.3, 0.0]\nfov_y_deg = 45.0\n\
             [materials.lamp]\nbase_color = [0.0, 0.0, 0.0]\nemission = [4.0, 3.0, 2.0]\n\
             [[sphere]]\ncenter = [0.0, 0.5, 0.0]\nradius = 0.5\n\
             [[sphere]]\ncenter = [1.0, 0.3, 0.5]\nradius = 0.15\nmaterial = \"lamp\"\n\
             [[sphere]]\ncenter = [0.0, -1000.0, 0.0]\nradius = 1000.0\n"
        ))
    };
    let sampled = render(scene(true), 64, 64, 64, 8);
    let plain = render(scene(false), 64, 64, 64, 8);
    let mut worst: f64 = 0.0;
    for (_, pixels) in common::layers::blocks(64, 64, 8) {
        let diff: f64 =
            pixels.iter().map(|&i| common::luminance(sampled.pixels[i]) - common::luminance(plain.pixels[i])).sum();
        let var: f64 =
            pixels.iter().map(|&i| (sampled.std_error[i] as f64).powi(2) + (plain.std_error[i] as f64).powi(2)).sum();
        worst = worst.max(diff.abs() / var.sqrt().max(1e-9));
    }
    println!("sky sampled as a light against not: worst 8x8 block {worst:.2} σ");
    assert!(worst <= 5.0, "a block is {worst:.2} σ apart");
}
