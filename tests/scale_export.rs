//! Instances at scale, from Blender: a geometry-nodes scatter of 10³ and 10⁵ (and, in
//! the ignored test, 10⁶) instances of a 10,000-triangle sphere is built in bpy
//! (`tests/blender/scatter_scale.py`), exported, packed and rendered on lavapipe; each
//! prints its export time, pack time, top-level build time and memory. Needs
//! RT_BPY_PYTHON, a Python with `bpy` (scripts/test sets one up).

use crate::common;

use common::{bpy_python, gpu, repo, temp_dir};
use rt::bvh::{BuildQuality, SceneGeometry};
use rt::render::{RenderRequest, Session};
use std::process::Command;
use std::time::Instant;

/// The process's peak resident memory in MiB (Linux), or NaN where unknown.
fn peak_rss_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let kib = status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok());
    kib.map_or(f64::NAN, |k| k / 1024.0)
}

fn print_header() {
    println!(
        "| instances | export s | bpy peak MiB | read + place + top level ms | top level build ms | GPU MiB (meshes + instances and top level) | bytes/instance | peak rt MiB | paths/s (64x64, 1 spp) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
}

/// Exports a scatter of `count`, then packs and renders it, printing one table row.
fn scatter(count: usize) {
    let dir = temp_dir(&format!("scale-{count}"));
    let script = repo().join("tests/blender/scatter_scale.py");
    let out = Command::new(bpy_python()).arg(&script).arg(count.to_string()).arg(&dir).output().expect("run bpy");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{script:?} failed:\n{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value =
        stdout.lines().rev().find_map(|l| serde_json::from_str(l).ok()).expect("the script's JSON line");
    assert_eq!(report["instances"]["sphere"].as_u64(), Some(count as u64), "{report}");
    let export_s = report["export_s"].as_f64().expect("export_s");
    let bpy_peak = report["peak_mib"].as_f64().expect("peak_mib");

    let scene = rt::scene::load(&dir.join("scene.toml")).unwrap_or_else(|e| panic!("{e}"));
    let start = Instant::now();
    let geometry = SceneGeometry::build(&scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let pack = start.elapsed();
    assert_eq!((geometry.instances.len(), geometry.meshes[0].triangle_count), (count, 10_000));
    let (mesh, top) = (geometry.mesh_bytes(), geometry.top_level_bytes());
    let per_instance = top as f64 / count as f64;
    let tlas_ms = geometry.tlas_build_time.as_secs_f64() * 1e3;

    let mut session = Session::with_geometry(gpu(), scene, geometry).unwrap_or_else(|e| panic!("{e:#}"));
    let mut request = RenderRequest::from_scene(session.scene());
    (request.width, request.height, request.spp, request.max_bounces) = (64, 64, 1, 2);
    let (image, report) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(report.dropped.is_clean(), "{}", report.dropped);
    // The camera looks down on the field: most pixels see an orange sphere, not the bluish sky.
    let orange = image.pixels.iter().filter(|p| p[0] > 1.5 * p[2]).count();
    println!(
        "| {count} | {export_s:.2} | {bpy_peak:.0} | {:.0} | {tlas_ms:.0} | {:.1} + {:.1} | {per_instance:.1} | {:.0} | {:.0} |",
        pack.as_secs_f64() * 1e3,
        mesh as f64 / 1048576.0,
        top as f64 / 1048576.0,
        peak_rss_mib(),
        report.samples_per_second
    );
    assert!(orange > 64 * 64 / 3, "{count} instances: only {orange} of 4096 pixels see a sphere");
    assert!(per_instance < 100.0, "{per_instance} GPU bytes per instance");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn geometry_nodes_scatters_of_a_thousand_and_a_hundred_thousand_export_pack_and_render() {
    print_header();
    scatter(1_000);
    scatter(100_000);
}

#[test]
#[ignore = "about a minute of bpy export and 2 s of packing on 2 cores: run with --ignored"]
fn a_geometry_nodes_scatter_of_a_million_exports_packs_and_renders() {
    print_header();
    scatter(1_000_000);
}
