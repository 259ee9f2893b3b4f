//! The non-finite sentinel: samples that overflow are dropped and counted per
//! pixel with their cause, never written into the image; `--strict` fails on them with exit status 3.

use crate::common;

use common::{gpu, scene_from, temp_dir, write};
use rt::bvh::BuildQuality;
use rt::render::{NonFiniteCause, RenderRequest, Session};
use std::process::Command;

// Two emitters at f32's largest radiance: a path that sees one and then the
// other sums to infinity.
const OVERFLOWING: &str = "[sky]\nkind = \"black\"\n\
    [camera]\nposition = [0.0, 0.0, 4.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 30.0\n\
    [materials.blinding]\nemission = [3.4e38, 3.4e38, 3.4e38]\n\
    [[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"blinding\"\n\
    [[sphere]]\ncenter = [2.5, 0.0, 1.0]\nradius = 1.2\nmaterial = \"blinding\"\n";

#[test]
fn overflowing_samples_are_dropped_counted_and_attributed() {
    let mut renderer = Session::open(gpu(), scene_from(OVERFLOWING), BuildQuality::Medium).expect("renderer");
    let mut request = RenderRequest::from_scene(renderer.scene());
    (request.width, request.height, request.spp, request.max_bounces) = (16, 16, 4, 2);
    let (image, report) = renderer.render(&request, None).expect("render");
    let s = &report.dropped;
    println!("{s}");
    assert!(s.non_finite_samples > 0, "the overflow was not seen");
    assert!(s.pixels_with_non_finite > 0 && s.pixels_with_non_finite <= 256);
    // The sum overflows when the second emitter's light arrives, seen or sampled.
    let expected = [NonFiniteCause::Emission, NonFiniteCause::LightSample];
    assert!(s.first_causes.iter().all(|(c, _)| expected.contains(c)), "{:?}", s.first_causes);
    assert!(image.pixels.iter().flatten().all(|v| v.is_finite()), "a non-finite sample reached the image");
}

#[test]
fn strict_fails_on_dropped_samples() {
    let dir = temp_dir("strict");
    write(&dir.join("scene.toml"), OVERFLOWING);
    let run = |strict: bool| {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_rt"));
        cmd.args(["render", "--size", "16x16", "--spp", "2", "--max-bounces", "2", "-o"]).arg(dir.join("out.exr"));
        if strict {
            cmd.arg("--strict");
        }
        cmd.arg(dir.join("scene.toml")).output().expect("run rt")
    };
    let relaxed = run(false);
    assert!(relaxed.status.success(), "{}", String::from_utf8_lossy(&relaxed.stderr));
    assert!(String::from_utf8_lossy(&relaxed.stderr).contains("non-finite samples dropped"));
    let strict = run(true);
    assert_eq!(strict.status.code(), Some(3), "{}", String::from_utf8_lossy(&strict.stderr));
}
