//! rt scenes as Mitsuba 3 sees them, and Mitsuba's throughput on them through its
//! Python API (`mitsuba_throughput.py`, run as a child process).
//!
//! The translation covers what throughput comparisons use: meshes and spheres of
//! diffuse (and emitting) materials under a black or uniform sky, seen by a pinhole
//! camera. Anything else is refused with its name rather than approximated, so that
//! both renderers always do the same work.

use crate::asset::load_mesh;
use crate::scene::{Material, Projection, Scene, Sky};
use anyhow::{Context, Result, bail};
use glam::{Vec3, Vec4Swizzles};
use serde_json::{Value, json};
use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

const SCRIPT: &str = include_str!("mitsuba_throughput.py");

/// One measurement Mitsuba makes: a scene at a size, with rt's bounce limit.
pub struct MitsubaCase<'a> {
    pub name: &'a str,
    pub scene: &'a Scene,
    pub size: (u32, u32),
    pub spp: u32,
    pub runs: u32,
    pub rays: bool,
}

/// Mitsuba's figures for one case.
#[derive(Clone, Debug, Default)]
pub struct MitsubaFigures {
    pub camera_rays_per_s: Option<f64>,
    pub diffuse_rays_per_s: Option<f64>,
    pub paths_per_s: f64,
}

/// What came back from the child: the variant it ran and one result per case.
pub struct MitsubaRun {
    pub variant: String,
    pub figures: Vec<MitsubaFigures>,
}

/// Why Mitsuba gave no figures: not installed (a plain fact), or a failure.
pub enum MitsubaOutcome {
    Ran(MitsubaRun),
    Unavailable(String),
}

/// The diffuse reflectance of a material both renderers treat alike, or why not.
fn reflectance(name: &str, m: &Material) -> Result<[f32; 3]> {
    let t = &m.textures;
    if m.specular > 0.0 || m.reflection > 0.0 || m.transmission > 0.0 {
        bail!("material {name}: only diffuse materials are compared with Mitsuba");
    }
    if t.base_color.is_some() || t.metallic_roughness.is_some() || t.emission.is_some() || t.alpha_cutoff > 0.0 {
        bail!("material {name}: textured materials are not compared with Mitsuba");
    }
    if m.absorption.iter().chain(&m.volume_emission).any(|&c| c > 0.0) {
        bail!("material {name}: media are not compared with Mitsuba");
    }
    Ok(m.base_color.map(|c| c * m.diffuse.min(1.0)))
}

/// Writes a binary little-endian PLY of `triangles` (world space).
fn write_ply(path: &Path, positions: &[Vec3], triangles: &[[u32; 3]]) -> Result<()> {
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        positions.len(),
        triangles.len()
    )
    .into_bytes();
    for p in positions {
        out.extend(p.to_array().iter().flat_map(|c| c.to_le_bytes()));
    }
    for t in triangles {
        out.push(3);
        out.extend(t.iter().flat_map(|&i| (i as i32).to_le_bytes()));
    }
    std::fs::write(path, out).with_context(|| format!("writing {}", path.display()))
}

/// The JSON case `mitsuba_throughput.py` reads, with the scene's meshes written as PLY
/// files (one per mesh and material, in world space) into `dir`.
pub fn translate(case: &MitsubaCase, dir: &Path) -> Result<Value> {
    let scene = case.scene;
    let unsupported = |what: &str| -> Result<Value> { bail!("{}: {what} is not compared with Mitsuba", scene.origin) };
    if scene.sun.is_some() {
        return unsupported("a sun");
    }
    if !scene.lights.is_empty() {
        return unsupported("a lamp");
    }
    if !scene.instance_sets.is_empty() {
        return unsupported("an [[instances]] set");
    }
    let sky = match scene.sky {
        Sky::Black => Value::Null,
        Sky::Uniform { color } => json!(color.to_array()),
        Sky::Atmosphere(_) => return unsupported("an atmosphere"),
        Sky::Environment(_) => return unsupported("an environment map"),
    };
    let cam = &scene.camera;
    if matches!(cam.projection, Projection::Orthographic { .. } | Projection::Panoramic { .. })
        || cam.depth_of_field.is_some()
        || cam.shift != glam::Vec2::ZERO
    {
        return unsupported("a camera other than a centred pinhole");
    }
    let (width, height) = case.size;
    let fov_y_deg = 2.0 * cam.view_plane(width, height).half_extent.y.atan().to_degrees();
    let (_, up, _) = cam.basis();

    let scene_material = |name: &str| -> Result<&Material> {
        scene.material_index(name).map(|i| &scene.materials[i].1).with_context(|| format!("no material {name}"))
    };
    let mut shapes = Vec::new();
    for (i, mesh) in scene.meshes.iter().enumerate() {
        let data = load_mesh(&mesh.asset)?;
        let positions: Vec<Vec3> =
            data.positions.iter().map(|&p| (mesh.object_to_world * Vec3::from(p).extend(1.0)).xyz()).collect();
        for (m, (own_name, own)) in data.materials.iter().enumerate() {
            let triangles: Vec<[u32; 3]> = data
                .indices
                .iter()
                .zip(&data.material_ids)
                .filter(|&(_, &id)| id as usize == m)
                .map(|(t, _)| *t)
                .collect();
            if triangles.is_empty() {
                continue;
            }
            let (name, material) = match &mesh.material {
                Some(name) => (name.as_str(), scene_material(name)?),
                None => (own_name.as_str(), own),
            };
            let reflectance = reflectance(name, material)?;
            let ply = dir.join(format!("mesh{i}_{m}.ply"));
            write_ply(&ply, &positions, &triangles)?;
            shapes.push(json!({ "ply": ply, "reflectance": reflectance, "emission": material.emission }));
        }
    }
    let mut spheres = Vec::new();
    for sphere in &scene.spheres {
        let default = Material::default();
        let (name, material) = match &sphere.material {
            Some(name) => (name.as_str(), scene_material(name)?),
            None => ("default", &default),
        };
        spheres.push(json!({
            "center": sphere.center.to_array(),
            "radius": sphere.radius,
            "reflectance": reflectance(name, material)?,
            "emission": material.emission,
        }));
    }
    Ok(json!({
        "name": case.name,
        "width": width,
        "height": height,
        "spp": case.spp,
        "runs": case.runs.max(1),
        // Mitsuba counts the emitter seen by the camera as depth 1: rt's B bounces are B + 1.
        "max_depth": scene.render.max_bounces + 1,
        "rays": case.rays,
        "camera": {
            "position": cam.position.to_array(),
            "look_at": cam.look_at.to_array(),
            "up": up.to_array(),
            "fov_y_deg": fov_y_deg,
        },
        "sky": sky,
        "shapes": shapes,
        "spheres": spheres,
    }))
}

fn figures(line: &Value) -> MitsubaFigures {
    MitsubaFigures {
        camera_rays_per_s: line["camera_rays_per_s"].as_f64(),
        diffuse_rays_per_s: line["diffuse_rays_per_s"].as_f64(),
        paths_per_s: line["paths_per_s"].as_f64().unwrap_or(f64::NAN),
    }
}

/// Runs the cases (translated into `dir`) with `python`, which must import `mitsuba`:
/// `variant`, or the first of `cuda_ad_rgb` and `llvm_ad_rgb` that works.
pub fn run(python: &str, variant: Option<&str>, cases: Vec<Value>, dir: &Path) -> Result<MitsubaOutcome> {
    let script = dir.join("mitsuba_throughput.py");
    std::fs::write(&script, SCRIPT)?;
    let child =
        Command::new(python).arg(&script).stdin(Stdio::piped()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn();
    let mut child = match child {
        Ok(c) => c,
        Err(e) => return Ok(MitsubaOutcome::Unavailable(format!("cannot run {python}: {e}"))),
    };
    let job = json!({ "variant": variant, "cases": cases });
    if let Some(mut stdin) = child.stdin.take() {
        // A child that exits at once (no mitsuba) closes its end: that is reported below.
        let _ = stdin.write_all(job.to_string().as_bytes());
    }
    let output = child.wait_with_output()?;
    let stderr = String::from_utf8_lossy(&output.stderr);
    if output.status.code() == Some(3) {
        return Ok(MitsubaOutcome::Unavailable(format!("{python}: {}", stderr.trim())));
    }
    if !output.status.success() {
        bail!("Mitsuba failed ({}):\n{}", output.status, stderr.trim());
    }
    let mut lines = std::str::from_utf8(&output.stdout)?
        .lines()
        .map(serde_json::from_str::<Value>)
        .collect::<Result<Vec<_>, _>>()
        .context("reading Mitsuba's figures")?
        .into_iter();
    let head = lines.next().context("Mitsuba printed nothing")?;
    let variant = format!("{} {}", head["variant"].as_str().unwrap_or("?"), head["version"].as_str().unwrap_or(""));
    Ok(MitsubaOutcome::Ran(MitsubaRun { variant, figures: lines.map(|l| figures(&l)).collect() }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(path: &str) -> Scene {
        crate::scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap_or_else(|e| panic!("{e}"))
    }

    fn case(scene: &Scene) -> MitsubaCase<'_> {
        MitsubaCase { name: "t", scene, size: (64, 48), spp: 4, runs: 1, rays: true }
    }

    #[test]
    fn cornell_box_translates_with_its_lamp_and_bounces() {
        let scene = scene("tests/refs/scenes/cornell_diffuse.toml");
        let dir = std::env::temp_dir().join(format!("rt-mitsuba-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let job = translate(&case(&scene), &dir).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        assert_eq!(job["max_depth"], scene.render.max_bounces + 1);
        assert!((job["camera"]["fov_y_deg"].as_f64().unwrap() - 36.0).abs() < 1e-4);
        let shapes = job["shapes"].as_array().unwrap();
        // One PLY per material group of the box; exactly one of them emits.
        assert!(shapes.len() >= 4, "{shapes:?}");
        let emitting =
            shapes.iter().filter(|s| s["emission"].as_array().unwrap().iter().any(|c| c.as_f64() > Some(0.0)));
        assert_eq!(emitting.count(), 1);
        assert_eq!(job["spheres"].as_array().unwrap().len(), 2);
        assert!(job["sky"].is_null());
    }

    #[test]
    fn what_mitsuba_would_render_differently_is_refused_by_name() {
        let mut scene = scene("tests/refs/scenes/cornell_diffuse.toml");
        scene.materials[0].1.reflection = 1.0;
        // A folder of its own: another user's files in the shared temporary folder cannot
        // be overwritten (nor should they be).
        let dir = std::env::temp_dir().join(format!("rt-mitsuba-refused-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let e = translate(&case(&scene), &dir).unwrap_err().to_string();
        assert!(e.contains(&scene.materials[0].0) && e.contains("only diffuse"), "{e}");
        let sunny =
            crate::scene::parse("[sun]\nelevation_deg = 30.0\nazimuth_deg = 0.0\n", "sunny.toml", Path::new("."))
                .unwrap();
        let e = translate(&case(&sunny), &dir).unwrap_err().to_string();
        let _ = std::fs::remove_dir_all(&dir);
        assert!(e.contains("sunny.toml") && e.contains("a sun"), "{e}");
    }
}
