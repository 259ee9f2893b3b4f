//! A transparent film (`[render] transparent`, `--transparent`, Blender's Film ›
//! Transparent): the background seen by camera rays adds nothing, and each pixel's alpha
//! is the share of its camera rays that met the scene. Same samples as an opaque film, so
//! the two images differ by exactly the sky the transparent one left out.

use crate::common;

use common::{render_request, repo, temp_dir};
use rt::render::Image;
use std::process::Command;

/// The clay dragon on its ground under a uniform sky, whose colour each background
/// sample of the opaque film adds.
const SKY: [f32; 3] = [0.55, 0.65, 0.85];

fn dragon(transparent: bool, lanes: Option<u32>) -> Image {
    let mut scene = rt::scene::load(&repo().join("scenes/dragon_clay.toml")).unwrap_or_else(|e| panic!("{e}"));
    scene.render.transparent = transparent;
    render_request(scene, |r| {
        (r.width, r.height, r.spp, r.sample_lanes) = (48, 32, 8, lanes);
        r.aovs = true;
    })
    .0
}

#[test]
fn the_film_leaves_out_exactly_the_sky_the_camera_sees() {
    let (opaque, film) = (dragon(false, None), dragon(true, None));
    assert!(opaque.alpha.is_none());
    let alpha = film.alpha.as_ref().expect("a transparent film has alpha");
    let count = |f: &dyn Fn(f32) -> bool| alpha.iter().filter(|&&a| f(a)).count();
    let (clear, covered, partial) = (count(&|a| a == 0.0), count(&|a| a == 1.0), count(&|a| a > 0.0 && a < 1.0));
    println!("{clear} pixels see only sky, {covered} only the scene, {partial} both");
    assert!(clear > 0 && covered > 0 && partial > 0, "the view has sky, scene and their edges");
    for (i, ((o, t), &a)) in opaque.pixels.iter().zip(&film.pixels).zip(alpha).enumerate() {
        for c in 0..3 {
            // The opaque pixel's mean has the sky in its (1 - alpha) share of samples.
            let expected = o[c] - (1.0 - a) * SKY[c];
            assert!((t[c] - expected).abs() <= 1e-5 * (1.0 + o[c]), "pixel {i} channel {c}: {} vs {expected}", t[c]);
        }
        if a == 1.0 {
            assert_eq!(o, t, "pixel {i}: a covered pixel is the opaque film's, bit for bit");
        }
    }
    // Samples spread over lanes count the same rays.
    let spread = dragon(true, Some(4));
    assert_eq!(spread.alpha.as_ref(), Some(alpha), "alpha under 4 lanes");
    assert_eq!(spread.pixels, film.pixels, "pixels under 4 lanes");
}

#[test]
fn rt_render_writes_alpha_into_exr_and_png() {
    let dir = temp_dir("transparent-film");
    for name in ["film.exr", "film.png"] {
        let status = Command::new(env!("CARGO_BIN_EXE_rt"))
            .arg("render")
            .arg(repo().join("scenes/dragon_clay.toml"))
            .args(["--transparent", "--size", "24x16", "--spp", "4", "--progress", "none", "-o"])
            .arg(dir.join(name))
            .status()
            .expect("rt runs");
        assert!(status.success(), "{name}");
    }
    let exr = image::open(dir.join("film.exr")).expect("exr").into_rgba32f();
    let png = image::open(dir.join("film.png")).expect("png");
    assert!(png.color().has_alpha(), "the PNG is RGBA");
    let png = png.into_rgba8();
    // The top row is sky, the bottom row ground.
    let (sky, ground) = ((12, 0), (12, 15));
    assert_eq!(exr.get_pixel(sky.0, sky.1).0, [0.0; 4], "the EXR's sky: premultiplied nothing");
    assert_eq!(exr.get_pixel(ground.0, ground.1).0[3], 1.0, "the EXR's ground is covered");
    assert_eq!(png.get_pixel(sky.0, sky.1).0, [0; 4], "the PNG's sky");
    assert_eq!(png.get_pixel(ground.0, ground.1).0[3], 255, "the PNG's ground");
    let _ = std::fs::remove_dir_all(&dir);
}
