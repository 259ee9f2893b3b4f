//! `rt bench first-pixel`: how long an artist waits for the first image of a scene, cold
//! (the driver's shader cache empty, as on a fresh machine or after a feature-set change
//! the driver has not seen) and warm (the same again, its cache filled). Each is a fresh
//! process, as `rt render` is: the parent runs itself twice with a driver cache folder of
//! its own and reports each step of the child's start.

use anyhow::{Context, Result, bail};
use rt::bvh::BuildQuality;
use rt::gpu::GpuContext;
use rt::render::{RenderRequest, Session};
use rt::scene::Scene;
use serde_json::{Value, json};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// The drivers' shader caches, pointed at a folder of the bench's own: Mesa's
/// (lavapipe, RADV, ANV) and NVIDIA's.
const CACHE_VARIABLES: [&str; 2] = ["MESA_SHADER_CACHE_DIR", "__GL_SHADER_DISK_CACHE_PATH"];

/// The child's part: one first image, each step timed, printed as one JSON line.
pub fn child(scene: Scene, size: (u32, u32), adapter: Option<&str>) -> Result<()> {
    let start = Instant::now();
    let ctx = GpuContext::new(adapter)?;
    let context = start.elapsed();
    let mut session = Session::open(&ctx, scene, BuildQuality::default())?;
    let opened = start.elapsed();
    let mut request = RenderRequest::from_scene(session.scene());
    (request.width, request.height, request.spp) = (size.0, size.1, 1);
    let (image, _) = session.render(&request, None)?;
    let first = start.elapsed();
    session.render(&RenderRequest { seed: 1, ..request }, None)?;
    let again = start.elapsed() - first;
    let line = json!({
        "device": ctx.describe(), "features": session.features().to_string(), "pixels": image.pixels.len(),
        "context_s": context.as_secs_f64(), "open_s": (opened - context).as_secs_f64(),
        "first_image_s": (first - opened).as_secs_f64(), "total_s": first.as_secs_f64(),
        "next_image_s": again.as_secs_f64(),
    });
    println!("{line}");
    Ok(())
}

fn run_child(scene: Option<&Path>, size: (u32, u32), adapter: Option<&str>, cache: &Path) -> Result<(Value, f64)> {
    let mut command = Command::new(std::env::current_exe().context("finding rt's own executable")?);
    if let Some(adapter) = adapter {
        command.args(["--adapter", adapter]);
    }
    command.args(["bench", "first-pixel", "--child", "--size", &format!("{}x{}", size.0, size.1)]);
    command.args(scene);
    for variable in CACHE_VARIABLES {
        command.env(variable, cache);
    }
    let start = Instant::now();
    let out = command.output().context("running rt bench first-pixel's child")?;
    let wall = start.elapsed().as_secs_f64();
    if !out.status.success() {
        bail!("the child failed ({}):\n{}", out.status, String::from_utf8_lossy(&out.stderr).trim());
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text.lines().last().context("the child printed nothing")?;
    Ok((serde_json::from_str(line).context("reading the child's figures")?, wall))
}

/// Runs the child cold, then warm, and prints what each waited for.
pub fn first_pixel(scene: Option<&Path>, size: (u32, u32), adapter: Option<&str>) -> Result<()> {
    let cache = rt::files::ScratchDir::new("first-pixel")?;
    let ms = |v: &Value, key: &str| v[key].as_f64().map_or("—".into(), |s| format!("{:.0} ms", 1e3 * s));
    let mut printed_head = false;
    for state in ["cold", "warm"] {
        let (v, wall) = run_child(scene, size, adapter, cache.path())?;
        if !printed_head {
            println!("GPU       {}", v["device"].as_str().unwrap_or("?"));
            println!("features  {}", v["features"].as_str().unwrap_or("?"));
            println!(
                "\n| driver cache | process to first image | GPU context | scene, BVH, buffers | first 1-spp image (pipelines built) | next 1-spp image |"
            );
            println!("|---|---:|---:|---:|---:|---:|");
            printed_head = true;
        }
        println!(
            "| {state} | {:.0} ms ({}) | {} | {} | {} | {} |",
            1e3 * wall,
            ms(&v, "total_s"),
            ms(&v, "context_s"),
            ms(&v, "open_s"),
            ms(&v, "first_image_s"),
            ms(&v, "next_image_s")
        );
    }
    Ok(())
}
