//! `rt info`: what a scene contains and which effects it needs.

use crate::asset::AssetFiles;
use crate::bvh::{BuildQuality, Provenance, SceneGeometry};
use crate::gpu::GpuContext;
use crate::scene::Scene;
use anyhow::Result;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// `rt info --inputs`: every file rendering `scene` reads (the scene, its meshes and
/// materials, their textures and caches, an environment image), one absolute path a line:
/// what a farm ships to its workers. Stale or missing caches are packed first.
pub fn print_inputs(scene: Option<&Path>, quality: BuildQuality) -> Result<()> {
    crate::files::input::record_inputs();
    let scene = match scene {
        Some(path) => crate::scene::load(path)?,
        None => crate::scene::default_scene()?,
    };
    let geometry = SceneGeometry::build(&scene, quality)?;
    let mut inputs: BTreeSet<PathBuf> = crate::files::input::recorded_inputs().into_iter().collect();
    let caches = geometry.meshes.iter().filter_map(|m| AssetFiles::resolve(&m.path).ok()?.cache_path());
    let environment = match &scene.sky {
        crate::scene::Sky::Environment(e) => Some(e.image.clone()),
        crate::scene::Sky::Graph(g) => Some(g.graph.clone()),
        _ => None,
    };
    for path in caches.chain(environment) {
        if let Ok(path) = std::fs::canonicalize(&path) {
            inputs.insert(path);
        }
    }
    for path in inputs {
        println!("{}", path.display());
    }
    Ok(())
}

pub fn print_info(scene: Scene, quality: BuildQuality, adapter: Option<&str>) -> Result<()> {
    let g = SceneGeometry::build(&scene, quality)?;
    println!("scene      {}", scene.origin);
    println!("features   {}", crate::scene::FeatureSet::analyse(&scene, &g.summary()));
    println!(
        "contents   {} mesh instances of {} assets, {} spheres, {} triangles, {} materials, {} lamps",
        g.instances.len(),
        g.meshes.len(),
        g.spheres.len(),
        g.meshes.iter().map(|m| m.triangle_count).sum::<usize>(),
        g.materials.len(),
        g.lamps.len()
    );
    println!("bounds     {:?} .. {:?}", g.bounds_min.to_array(), g.bounds_max.to_array());
    let moving = g.instances.iter().filter(|i| i.is_moving()).count();
    let camera_keys = scene.camera.motion.as_ref().map_or(0, |m| m.keys().len());
    if moving > 0 || camera_keys > 0 {
        println!(
            "motion     {moving} moving instances ({} matrices over the shutter), the camera in {camera_keys} keys",
            g.motion_matrices.len()
        );
    }
    for m in &g.meshes {
        let s = m.bvh.stats;
        let provenance = match m.provenance {
            Provenance::Cache { load_time } => format!("loaded from its cache in {load_time:.1?}"),
            Provenance::Packed { build_time } => format!("built and cached in {build_time:.1?}"),
            Provenance::InMemory { build_time } => format!("built in {build_time:.1?}"),
        };
        println!(
            "mesh       {}: {} triangles, BVH {} nodes, {} leaves, depth {}, SAH cost {:.2}, {provenance}",
            m.path.display(),
            m.triangle_count,
            s.nodes,
            s.leaves,
            s.depth,
            s.sah_cost,
        );
        for (material, notes) in crate::asset::notes::material_notes(&m.path) {
            for note in notes {
                println!("  material `{material}`: {note}");
            }
        }
    }
    let t = g.tlas_stats;
    println!(
        "top level  {} nodes, {} leaves, depth {}, SAH cost {:.2}, built in {:.1?}",
        t.nodes, t.leaves, t.depth, t.sah_cost, g.tlas_build_time
    );
    let placed = (g.instances.len() + g.spheres.len()).max(1);
    println!(
        "GPU memory {:.1} MiB of meshes, {:.1} MiB of instances and top level ({:.1} bytes per instance)",
        g.mesh_bytes() as f64 / 1048576.0,
        g.top_level_bytes() as f64 / 1048576.0,
        g.top_level_bytes() as f64 / placed as f64
    );
    match GpuContext::new(adapter) {
        Ok(ctx) => println!("GPU        {}", ctx.describe()),
        Err(e) => println!("GPU        none: {e:#}"),
    }
    Ok(())
}
