//! Blender → rt for Worlds with an Environment Texture: `tests/blender/environment.py`
//! exports them with blender/rt_export.py. Needs RT_BPY_PYTHON, a Python with `bpy`.

use crate::common;

use common::temp_dir;
use rt::scene::Sky;
use rt::sky::EnvironmentImage;
use serde_json::Value;

/// Runs the export script into a folder of its own named `name`.
fn run_export(name: &str) -> (std::path::PathBuf, Value) {
    let out = temp_dir(name);
    common::run_bpy_script("environment.py", &out);
    let report = std::fs::read_to_string(out.join("report.json")).expect("report.json");
    (out.clone(), serde_json::from_str(&report).expect("report parses"))
}

fn environment(scene: &rt::scene::Scene) -> &rt::scene::Environment {
    match &scene.sky {
        Sky::Environment(e) => e,
        other => panic!("not an environment: {other:?}"),
    }
}

#[test]
fn environment_textures_export_with_their_image_strength_and_rotation() {
    let (out, report) = run_export("environment-export");
    let scene = rt::scene::load(&out.join("hdri.toml")).unwrap_or_else(|e| panic!("{e}"));
    let env = environment(&scene);
    assert!((env.strength - 2.5).abs() < 1e-6, "{}", env.strength);
    assert!((env.rotation_deg - glam::Vec3::new(10.0, 0.0, 45.0)).length() < 1e-4, "{}", env.rotation_deg);
    // A linear EXR is copied byte for byte, under a name of its content's hash.
    let name = env.image.file_name().and_then(|n| n.to_str()).expect("a file name");
    assert!(name.starts_with("courtyard-") && name.ends_with(".exr"), "{name}");
    let source = std::fs::read(report["courtyard"].as_str().expect("path")).expect("the HDRI");
    assert_eq!(std::fs::read(&env.image).expect("the copy"), source);
    let first: Vec<&str> = report["first"].as_array().expect("first").iter().filter_map(Value::as_str).collect();
    assert!(first.iter().any(|p| p.ends_with(name)), "the first export writes the image: {first:?}");
    assert_eq!(report["second"], serde_json::json!([]), "an unchanged export writes nothing");
    let image = EnvironmentImage::read(&env.image).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!((image.width, image.height), (1024, 512));

    // An 8-bit sRGB image becomes a float EXR of its sRGB codes, which rt interpolates and
    // decodes after, as Cycles does; decoded, they are the linear values Cycles reads.
    let scene = rt::scene::load(&out.join("ramp.toml")).unwrap_or_else(|e| panic!("{e}"));
    let ramp = environment(&scene);
    assert!(ramp.srgb, "an sRGB image keeps its codes");
    let image = EnvironmentImage::read(&ramp.image).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!((image.width, image.height), (8, 4));
    let expected = report["ramp_linear"].as_array().expect("ramp");
    for (x, want) in expected.iter().enumerate() {
        let want = want.as_f64().expect("number") as f32;
        for y in 0..4 {
            let got = image.texels[y * 8 + x].map(rt::scene::srgb_decode);
            assert!(got.iter().all(|c| (c - want).abs() < 0.01), "texel ({x}, {y}): {got:?} against {want}");
        }
    }
}

#[test]
fn exr_compressions_read_alike() {
    let (out, _) = run_export("environment-codecs");
    let read = |codec: &str| {
        EnvironmentImage::read(&out.join(format!("courtyard_{codec}.exr"))).unwrap_or_else(|e| panic!("{e:#}"))
    };
    let plain = read("none");
    assert_eq!((plain.width, plain.height), (1024, 512));
    for lossless in ["zip", "piz"] {
        assert_eq!(read(lossless), plain, "{lossless}");
    }
    // DWAB is lossy: the mean absolute difference stays within 1% of the mean.
    let dwab = read("dwab");
    let flat = |i: &EnvironmentImage| i.texels.iter().flatten().map(|c| *c as f64).collect::<Vec<_>>();
    let (a, b) = (flat(&dwab), flat(&plain));
    let mean = b.iter().sum::<f64>() / b.len() as f64;
    let error = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).sum::<f64>() / b.len() as f64;
    println!("DWAB against uncompressed: mean absolute difference {:.3}% of the mean", 100.0 * error / mean);
    assert!(error < 0.01 * mean, "DWAB differs by {error} on a mean of {mean}");
}
