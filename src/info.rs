//! `rt info`: what a scene contains and which effects it needs.

use crate::bvh::{BuildQuality, SceneGeometry};
use crate::gpu::GpuContext;
use crate::scene::Scene;
use anyhow::Result;

pub fn print_info(scene: Scene, quality: BuildQuality, adapter: Option<&str>) -> Result<()> {
    let g = SceneGeometry::build(&scene, quality)?;
    println!("scene      {}", scene.origin);
    println!("features   {}", g.features);
    println!(
        "contents   {} mesh instances of {} assets, {} spheres, {} triangles, {} materials",
        g.instances.len(),
        g.meshes.len(),
        g.spheres.len(),
        g.meshes.iter().map(|m| m.data.indices.len()).sum::<usize>(),
        g.materials.len()
    );
    println!("bounds     {:?} .. {:?}", g.bounds_min.to_array(), g.bounds_max.to_array());
    for m in &g.meshes {
        let s = m.bvh.stats;
        println!(
            "mesh       {}: {} triangles, BVH {} nodes, {} leaves, depth {}, SAH cost {:.2}, built in {:.1?}",
            m.path.display(),
            m.data.indices.len(),
            s.nodes,
            s.leaves,
            s.depth,
            s.sah_cost,
            m.bvh.build_time
        );
    }
    let t = g.tlas_stats;
    println!("top level  {} nodes, {} leaves, depth {}, SAH cost {:.2}", t.nodes, t.leaves, t.depth, t.sah_cost);
    match GpuContext::new(adapter) {
        Ok(ctx) => println!("GPU        {}", ctx.describe()),
        Err(e) => println!("GPU        none: {e:#}"),
    }
    Ok(())
}
