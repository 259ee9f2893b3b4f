//! rt inside Blender as an artist meets it (`tests/blender/engine_ui.py` drives bpy): the
//! Shader Editor and Blender's and Cycles' panels show with rt picked, the render settings
//! laid out as Cycles' reach rt, a material preview renders through rt, F12 renders the
//! render's depsgraph (render-level modifiers, render visibility) as Cycles does, fills
//! the passes the view layer asks for with the content Blender expects, keeps Blender's
//! size rules (the percentage rounded down, border with and without crop) and refines
//! the image while it renders. Needs RT_BPY_PYTHON, a Python with `bpy`.

use crate::common;

use common::layers::{channel, channels};
use common::{bpy_python, empty_temp_dir, reference, repo};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Samples per pixel of the committed Cycles reference (`make_engine_refs.py --spp`).
const REFERENCE_SPP: f64 = 2048.0;
/// rt's samples per pixel in the F12 compared with it.
const SPP: u32 = 256;

fn out_dir(name: &str) -> PathBuf {
    empty_temp_dir(&format!("engine-ui-{name}"))
}

/// Runs tests/blender/engine_ui.py MODE ARGS; returns OUT/MODE.json.
fn engine_ui(out: &Path, mode: &str, args: &[&Path]) -> Value {
    let mut command = Command::new(bpy_python());
    command
        .arg(repo().join("tests/blender/engine_ui.py"))
        .arg(mode)
        .args(args)
        .arg(out)
        .env("RT_BINARY", env!("CARGO_BIN_EXE_rt"))
        .env("RT_TEST_SPP", SPP.to_string())
        .env("TMPDIR", out);
    let result = command.output().unwrap_or_else(|e| panic!("cannot run {command:?}: {e}"));
    let text = String::from_utf8_lossy(&result.stdout).into_owned() + &String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{command:?} failed:\n{text}");
    assert!(!text.contains("Traceback"), "a Python error in Blender:\n{text}");
    let path = out.join(format!("{mode}.json"));
    let json = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&json).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn the_shader_editor_and_blenders_panels_show_under_rt_and_its_settings_reach_rt() {
    let out = out_dir("ui");
    let report = engine_ui(&out, "ui", &[]);
    assert_eq!(report["shading_nodes_custom"], false, "the Shader Editor hides node trees unless this is False");
    assert_eq!(report["use_preview"], true, "material previews render through rt");
    let panels = report["panels"].as_object().expect("panels");
    for (name, shown) in panels {
        // Of Cycles' render panels, only Motion Blur's describes what rt renders.
        let must_show = (!name.starts_with("CYCLES_RENDER_PT") || name == "CYCLES_RENDER_PT_motion_blur")
            && !["DATA_PT_lightprobe", "RENDER_PT_stereoscopy", "CYCLES_LIGHT_PT_settings", "VIEWLAYER_PT_freestyle"]
                .contains(&name.as_str());
        assert_eq!(shown.as_bool(), Some(must_show), "{name}: shown under rt {shown}, expected {must_show}");
    }
    println!("{} of Blender's and Cycles' panels show under rt", report["shown_under_rt"]);
    let options = |key: &str| -> Vec<String> {
        report[key].as_array().expect(key).iter().map(|v| v.as_str().expect("option").to_owned()).collect()
    };
    let plain = options("options_plain").join(" ");
    assert_eq!(plain, "--spp 128 --max-bounces 13 --sampling nee --seed 0 --quality medium");
    let every = options("options_every").join(" ");
    for want in [
        "--max-bounces 5",
        "--seed 12",
        "--noise-threshold 0.02",
        "--time-limit 30",
        "--clamp 10",
        "--denoise --denoise-device cpu",
        "--adapter H200",
    ] {
        assert!(every.contains(want), "{want} missing from {every}");
    }
    assert_eq!(
        options("preview_options").join(" "),
        "--spp 16 --max-bounces 5 --sampling nee --seed 12 --quality medium"
    );
}

#[test]
fn a_material_preview_renders_through_rt() {
    let out = out_dir("preview");
    let report = engine_ui(&out, "preview", &[]);
    let scene = report["scene"].as_str().expect("the preview scene rt rendered");
    assert!(scene.contains("[[mesh]]") && scene.contains("[camera]"), "{scene}");
    let (lit, reddish, pixels) = (
        report["lit"].as_u64().unwrap_or(0),
        report["reddish"].as_u64().unwrap_or(0),
        report["pixels"].as_u64().unwrap_or(0),
    );
    println!(
        "preview {}: {lit} of {pixels} pixels lit, {reddish} red; icon and preview in {:.2} s",
        report["size"],
        report["seconds"].as_f64().unwrap_or(0.0)
    );
    assert!(pixels >= 128 * 128, "a preview of {pixels} pixels");
    // The red material on Blender's preview sphere covers a good part of the preview.
    assert!(reddish * 10 >= pixels, "{reddish} red pixels of {pixels}: not the material's preview");
}

/// The render and the viewport differ: Subdivision Surface 0 in the viewport and 3 in
/// renders, a sphere hidden in renders, one disabled in viewports. F12 through rt must
/// give Cycles' image of the .blend: before, it exported the viewport's cube
/// (`tests/cycles/make_engine_refs.py` makes the reference).
#[test]
fn f12_renders_the_renders_depsgraph_as_cycles_does() {
    let out = out_dir("levels");
    let blend = repo().join("tests/cycles/scenes/engine_levels/scene.blend");
    let report = engine_ui(&out, "levels", &[&blend]);
    let scene = report["scene"].as_str().expect("exported scene");
    assert!(scene.contains("# Rounded") && scene.contains("# RenderOnly"), "{scene}");
    assert!(!scene.contains("# ViewportOnly"), "an object hidden in renders was exported:\n{scene}");
    let (w, h, all) = channels(&out.join("levels.exr"));
    let (r, g, b) = (channel(&all, "Combined.R"), channel(&all, "Combined.G"), channel(&all, "Combined.B"));
    let (noise, counts) = (channel(&all, "Noise.X"), channel(&all, "Debug Sample Count.X"));
    // Blender's rows run from the top in the file, as rt's.
    let image = rt::render::Image {
        width: w as u32,
        height: h as u32,
        samples: SPP,
        pixels: (0..w * h).map(|i| [r[i], g[i], b[i]]).collect(),
        std_error: noise.to_vec(),
        sample_counts: counts.iter().map(|&c| c as u32).collect(),
        alpha: None,
    };
    assert!(image.sample_counts.iter().all(|&c| c == SPP), "every pixel took {SPP} samples");
    println!("F12 through rt in {:.2} s", report["seconds"].as_f64().unwrap_or(0.0));
    reference::compare(&image, &repo().join("tests/cycles/engine_levels.exr"), REFERENCE_SPP)
        .check("engine_levels", "Cycles");
}

/// A plane 5 m ahead, facing the camera: Blender's Depth pass is the distance along the
/// view axis (5 everywhere, as Cycles' camera_z_depth), its Normal the world normal
/// (0, -1, 0) in Blender's Z-up world; the denoising passes are rt's own AOVs.
/// F12 with the render's Motion Blur on: the engine evaluates the render's depsgraph over
/// the shutter (`RenderEngine.frame_set`, as Cycles' sync does) and the image is Cycles'
/// of the same scene (`tests/cycles/make_motion_refs.py`), the frame set back after.
#[test]
fn f12_blurs_moving_objects_as_cycles_does() {
    let out = out_dir("motion");
    let report = engine_ui(&out, "motion", &[]);
    let scene = report["scene"].as_str().expect("exported scene");
    assert_eq!(scene.matches("\nmotion = ").count(), 3, "three objects move with their blur on:\n{scene}");
    assert_eq!(report["frame"], serde_json::json!([2, 0.0]), "the frame is set back after the render");
    let (w, h, all) = channels(&out.join("motion.exr"));
    let (r, g, b) = (channel(&all, "Combined.R"), channel(&all, "Combined.G"), channel(&all, "Combined.B"));
    let image = rt::render::Image {
        width: w as u32,
        height: h as u32,
        samples: SPP,
        pixels: (0..w * h).map(|i| [r[i], g[i], b[i]]).collect(),
        std_error: channel(&all, "Noise.X").to_vec(),
        sample_counts: vec![SPP; w * h],
        alpha: None,
    };
    // make_motion_refs.py renders 1024 samples.
    reference::compare(&image, &repo().join("tests/cycles/motion_objects.exr"), 1024.0)
        .check("motion through F12", "Cycles");
}

#[test]
fn f12_fills_the_passes_blender_asks_for() {
    let out = out_dir("passes");
    let report = engine_ui(&out, "passes", &[]);
    let (w, h, all) = channels(&out.join("passes.exr"));
    assert_eq!((w, h), (48, 32));
    // Each pixel's depth is the mean over its samples, spread over the pixel: at the
    // edges of this wide view the distance changes by ~0.1 m across a pixel, so a pixel's
    // mean of 8 may be a few cm off; the image's mean is 5 m to a few mm. Without the
    // near clip plane's offset it was 4.90, without the cosine up to 7.1.
    let depth = channel(&all, "Depth.Z");
    let worst_depth = depth.iter().map(|z| (z - 5.0).abs()).fold(0.0, f32::max);
    let mean_depth = depth.iter().map(|&z| z as f64).sum::<f64>() / depth.len() as f64;
    println!("Depth pass: mean {mean_depth:.4} m, worst pixel off by {worst_depth:.4} m");
    assert!(worst_depth < 0.06, "depth along the view axis is 5 m everywhere (worst off by {worst_depth})");
    assert!((mean_depth - 5.0).abs() < 0.005, "mean depth {mean_depth}");
    let normal: Vec<[f32; 3]> = {
        let (x, y, z) = (channel(&all, "Normal.X"), channel(&all, "Normal.Y"), channel(&all, "Normal.Z"));
        (0..w * h).map(|i| [x[i], y[i], z[i]]).collect()
    };
    assert!(normal.iter().all(|n| (n[0].abs() + (n[1] + 1.0).abs() + n[2].abs()) < 1e-4), "normal (0, -1, 0)");
    // Position in Blender's axes: the plane is y = 0, the view 9 m × 6 m across at 5 m
    // (a 20 mm lens on a 36 mm sensor), its left column at x < 0 and top row at z > 0.
    let (px, py, pz) = (channel(&all, "Position.X"), channel(&all, "Position.Y"), channel(&all, "Position.Z"));
    assert!(py.iter().all(|y| y.abs() < 1e-4), "Position.Y is the plane's 0");
    assert!(px.iter().chain(pz).all(|v| v.abs() < 4.5), "positions inside the view");
    let (left, right) = (px[(h / 2) * w], px[(h / 2) * w + w - 1]);
    let (top, bottom) = (pz[w / 2], pz[(h - 1) * w + w / 2]);
    println!("Position pass: x from {left:.3} to {right:.3}, z from {top:.3} to {bottom:.3}");
    assert!(left < -4.0 && right > 4.0 && top > 2.5 && bottom < -2.5, "the view's extent in Blender's axes");
    assert!(channel(&all, "Emission.R").iter().all(|&e| e == 0.0), "the plane emits nothing");
    // The denoising passes against rt's own AOVs of the exported scene.
    let cache = PathBuf::from(report["cache"].as_str().expect("cache"));
    let aovs = out.join("aovs.exr");
    let status = Command::new(env!("CARGO_BIN_EXE_rt"))
        .arg("render")
        .arg(cache.join("scene.toml"))
        .args(["--aovs", "--progress", "none", "--spp", &report["spp"].to_string()])
        .args(["--max-bounces", &report["max_bounces"].to_string(), "-o"])
        .arg(&aovs)
        .status()
        .expect("rt runs");
    assert!(status.success());
    let (_, _, ours) = channels(&aovs);
    let (ax, ay, az) = (channel(&ours, "normal.X"), channel(&ours, "normal.Y"), channel(&ours, "normal.Z"));
    let denoising =
        [channel(&all, "Denoising Normal.X"), channel(&all, "Denoising Normal.Y"), channel(&all, "Denoising Normal.Z")];
    for i in 0..w * h {
        // rt's (x, y, z) is Blender's (x, -z, y).
        let expected = [ax[i], -az[i], ay[i]];
        for c in 0..3 {
            assert!((denoising[c][i] - expected[c]).abs() < 1e-6, "Denoising Normal at {i}: {c}");
        }
    }
    let (albedo, ours_albedo) = (channel(&all, "Denoising Albedo.R"), channel(&ours, "albedo.R"));
    assert!(albedo.iter().zip(ours_albedo).all(|(a, b)| (a - b).abs() < 1e-6), "Denoising Albedo is rt's albedo");
    let (diffuse, ours_diffuse) = (channel(&all, "Diffuse Color.G"), channel(&ours, "diffuse_color.G"));
    assert!(diffuse.iter().zip(ours_diffuse).all(|(a, b)| (a - b).abs() < 1e-6), "Diffuse Color is rt's");
    assert!(diffuse.iter().all(|&d| d > 0.5 && d < 0.8), "the grey plane's diffuse under its specular layer");
    let counts = channel(&all, "Debug Sample Count.X");
    assert!(counts.iter().all(|&c| c as u64 == report["spp"].as_u64().unwrap_or(0)), "{counts:?}");
    assert!(channel(&all, "Noise.X").iter().all(|e| e.is_finite() && *e >= 0.0));
}

/// Film › Transparent: the sky behind a small plane is left out of Combined, whose alpha
/// is 0 there and 1 on the plane; the plane itself is lit by the sky as before.
#[test]
fn a_transparent_film_gives_combined_its_alpha() {
    let out = out_dir("transparent");
    let report = engine_ui(&out, "transparent", &[]);
    assert!(report["scene"].as_str().unwrap_or("").contains("transparent = true"), "{report}");
    let (w, h, all) = channels(&out.join("transparent.exr"));
    let (r, a) = (channel(&all, "Combined.R"), channel(&all, "Combined.A"));
    let (corner, centre) = (0, (h / 2) * w + w / 2);
    println!("alpha: corner {}, centre {}; red: corner {}, centre {}", a[corner], a[centre], r[corner], r[centre]);
    assert_eq!((a[corner], r[corner]), (0.0, 0.0), "the sky is transparent and adds nothing");
    assert_eq!(a[centre], 1.0, "the plane covers its pixels");
    assert!(r[centre] > 0.1, "the plane is lit by the sky: {}", r[centre]);
    let partial = a.iter().filter(|&&v| v > 0.0 && v < 1.0).count();
    assert!(partial > 0 && partial < w * h / 4, "{partial} pixels on the plane's edges are partly covered");
}

/// A collection's Holdout, the film opaque: Combined is black with alpha 0 where the
/// camera sees the held-out plane, and the sky around it stays, alpha 1.
#[test]
fn a_held_out_collection_cuts_a_hole_in_combined() {
    let out = out_dir("holdout");
    let report = engine_ui(&out, "holdout", &[]);
    assert!(report["scene"].as_str().unwrap_or("").contains("holdout = true"), "{report}");
    let (w, h, all) = channels(&out.join("holdout.exr"));
    let (r, a) = (channel(&all, "Combined.R"), channel(&all, "Combined.A"));
    let (corner, centre) = (0, (h / 2) * w + w / 2);
    println!("alpha: corner {}, centre {}; red: corner {}, centre {}", a[corner], a[centre], r[corner], r[centre]);
    assert_eq!((a[centre], r[centre]), (0.0, 0.0), "the held-out plane is a hole");
    assert_eq!(a[corner], 1.0, "the sky covers its pixels");
    assert!(r[corner] > 0.1, "the sky shows: {}", r[corner]);
}

#[test]
fn blenders_size_rules_hold() {
    let out = out_dir("size");
    let report = engine_ui(&out, "size", &[]);
    let size = |name: &str| (report["sizes"][name][0].as_u64(), report["sizes"][name][1].as_u64());
    // 103 x 79 at 50 %: Blender rounds down.
    assert_eq!(size("full"), (Some(51), Some(39)));
    assert_eq!(size("border"), (Some(51), Some(39)), "a border without crop keeps the full size");
    assert_eq!(size("crop"), (Some(26), Some(20)), "crop to the border");
    let rgb = |name: &str| image::open(out.join(format!("size_{name}.exr"))).expect("exr").into_rgb32f();
    let (full, border) = (rgb("full"), rgb("border"));
    // Inside the border (x 12..38, y 0..20 from the top) the border render is the full
    // one; outside it, nothing was rendered.
    for (x, y, p) in border.enumerate_pixels() {
        let inside = (12..38).contains(&x) && y < 20;
        let q = full.get_pixel(x, y);
        if inside {
            assert_eq!(p, q, "({x}, {y}) inside the border");
        } else {
            assert_eq!(p.0, [0.0; 3], "({x}, {y}) outside the border");
        }
    }
}

#[test]
fn f12_shows_the_image_while_it_refines() {
    let out = out_dir("progressive");
    let report = engine_ui(&out, "progressive", &[]);
    let snapshots: Vec<u64> =
        report["snapshots"].as_array().expect("snapshots").iter().filter_map(Value::as_u64).collect();
    println!(
        "{} updates of the Render Result in {:.2} s: {snapshots:?} spp",
        snapshots.len(),
        report["seconds"].as_f64().unwrap_or(0.0)
    );
    assert!(snapshots.len() >= 3, "the image was shown {} times while rendering", snapshots.len());
    assert!(snapshots.windows(2).all(|w| w[0] < w[1]), "each update has more samples: {snapshots:?}");
}
