//! `rt bench watch-latency`: how long from a file written to the first frame of the new
//! state in `rt watch`, for the three edits an artist makes most: a camera move, a
//! material change, and a re-export of a mesh (the 46k-triangle dragon by default).
//!
//! A copy of the asset and a small scene go to a temporary folder; `rt watch`'s headless
//! loop runs on them here while another thread edits the files (each written to a
//! temporary name and renamed, as the Blender exporter does) and notes when the first
//! frame of each new state is done. The numbers include the watcher's debouncing.

use super::{STOP_FILE, WatchOptions, run_headless};
use anyhow::{Context, Result, anyhow, bail};
use rt::gpu::{GpuContext, median};
use rt::render::{ImageFormat, RenderFlags};
use std::path::Path;
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

/// Byte offset of the first vertex's x in an `.rtmesh` (contract 1: magic, 4 u32s).
const FIRST_VERTEX_X: usize = 24;

/// The benchmarks' scene: `asset` under a sun and a uniform sky, seen from `camera_x`.
pub(super) fn scene_text(asset: &str, camera_x: f32, red: f32) -> String {
    format!(
        r#"[render]
max_bounces = 4

[camera]
position = [{camera_x}, 0.6, 3.0]
look_at = [0.0, 0.3, 0.0]
fov_y_deg = 40.0

[sky]
kind = "uniform"
color = [0.6, 0.7, 0.9]

[sun]
elevation_deg = 35.0
azimuth_deg = 140.0

[materials.paint]
base_color = [{red}, 0.5, 0.3]

[[mesh]]
asset = "{asset}"
material = "paint"
"#
    )
}

fn write_by_rename(path: &Path, bytes: &[u8]) -> Result<()> {
    Ok(rt::files::write_atomically(path, bytes)?)
}

pub fn watch_latency(asset: &Path, (width, height): (u32, u32), runs: u32, adapter: Option<&str>) -> Result<()> {
    let name = asset
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| anyhow!("{}: not an asset folder", asset.display()))?;
    let mesh_name = format!("{name}.rtmesh");
    let scratch = rt::files::ScratchDir::new("watch-latency").context("cannot make a scratch folder")?;
    let dir = scratch.path();
    let copy = dir.join(name);
    std::fs::create_dir_all(&copy).with_context(|| format!("cannot create {}", copy.display()))?;
    for file in [mesh_name.clone(), format!("{name}.gltf")] {
        rt::files::write_atomically(&copy.join(&file), &rt::files::read(&asset.join(&file))?)?;
    }
    let scene = dir.join("scene.toml");
    write_by_rename(&scene, scene_text(name, 0.0, 0.8).as_bytes())?;
    let ctx = GpuContext::new(adapter)?;
    println!("GPU       {}", ctx.describe());
    println!(
        "scene     {name} at {width}x{height}, median of {runs} edits of each kind; each time includes debouncing"
    );

    let options = WatchOptions {
        scene: scene.clone(),
        quality: Default::default(),
        shader_dir: None,
        frames_dir: Some(dir.join("frames")),
        flags: RenderFlags { spp: Some(4), size: Some((width, height)), ..Default::default() },
        format: ImageFormat::Png,
        max_reloads: None,
    };
    let (tx, rx) = channel();
    let frames_dir = dir.join("frames");
    let mesh = copy.join(&mesh_name);
    let asset_name = name.to_owned();
    let editor = std::thread::spawn(move || {
        let result = edit(&rx, &scene, &asset_name, &mesh, runs.max(1));
        // Stops the watcher whatever happened.
        let _ = std::fs::write(frames_dir.join(STOP_FILE), "");
        result
    });
    let watched = run_headless(&ctx, &options, Some(tx), None);
    let latencies = editor.join().map_err(|_| anyhow!("the editing thread panicked"))??;
    watched?;
    for (what, times) in ["camera move", "material change", &format!("{name} re-export")].iter().zip(latencies) {
        println!("{what:<20} {:>8.1} ms", median(times).as_secs_f64() * 1000.0);
    }
    Ok(())
}

/// Makes `runs` edits of each kind, each after the last one's first frame; returns the
/// latencies of camera moves, material changes and re-exports.
fn edit(
    first_frames: &Receiver<(u32, Instant)>,
    scene: &Path,
    asset: &str,
    mesh: &Path,
    runs: u32,
) -> Result<[Vec<Duration>; 3]> {
    let timeout = Duration::from_secs(600);
    let wait = |after: u32| -> Result<(u32, Instant)> {
        loop {
            let (number, at) = first_frames.recv_timeout(timeout).context("no new frame within 10 minutes")?;
            if number > after {
                return Ok((number, at));
            }
        }
    };
    let (mut state, _) = first_frames.recv_timeout(timeout).context("the first frame never came")?;
    let mut latencies: [Vec<Duration>; 3] = Default::default();
    let mut bytes = rt::files::read(mesh)?;
    if bytes.len() < FIRST_VERTEX_X + 4 {
        bail!("{}: too short for an .rtmesh with a vertex", mesh.display());
    }
    let (mut camera_x, mut red) = (0.0, 0.8);
    for run in 0..runs {
        for (kind, times) in latencies.iter_mut().enumerate() {
            let start = Instant::now();
            match kind {
                0 => {
                    camera_x += 0.1;
                    write_by_rename(scene, scene_text(asset, camera_x, red).as_bytes())?;
                }
                1 => {
                    red = if run % 2 == 0 { 0.2 } else { 0.8 };
                    write_by_rename(scene, scene_text(asset, camera_x, red).as_bytes())?;
                }
                _ => {
                    // A re-export with a vertex moved by a hair: new bytes, so the BVH is re-packed.
                    let x = f32::from_le_bytes(bytes[FIRST_VERTEX_X..FIRST_VERTEX_X + 4].try_into()?);
                    bytes[FIRST_VERTEX_X..FIRST_VERTEX_X + 4].copy_from_slice(&(x + 1e-4).to_le_bytes());
                    write_by_rename(mesh, &bytes)?;
                }
            }
            let (number, at) = wait(state)?;
            state = number;
            times.push(at - start);
        }
    }
    Ok(latencies)
}
