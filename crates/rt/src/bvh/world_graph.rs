//! `[sky] kind = "graph"`: the World's node graph as a material of its own, last in the
//! material table, whose node program the shaders run for every ray that leaves the scene
//! (its `emission` output is the Background's radiance there).

use crate::asset::{node_graph, node_program};
use crate::scene::{Material, Scene, Sky};
use anyhow::{Result, anyhow};

/// The world's material, or `None` for a sky of another kind. It scatters nothing and
/// emits nothing as a surface: only its program is read.
pub fn material(scene: &Scene) -> Result<Option<Material>> {
    let Sky::Graph(world) = &scene.sky else { return Ok(None) };
    let path = world.graph.display();
    let bytes = crate::files::read(&world.graph)?;
    let json: serde_json::Value =
        serde_json::from_slice(&bytes).map_err(|e| anyhow!("{path}: not a node graph's JSON: {e}"))?;
    let node_program = node_graph::compile_json(&json).map_err(|e| anyhow!("{path}: {e}"))?;
    if !node_program::drives(&node_program, "emission") {
        return Err(anyhow!("{path}: the world's graph drives no `emission` (the Background's colour)"));
    }
    if node_program::reads_attributes(&node_program) {
        return Err(anyhow!("{path}: the world's graph reads a mesh attribute, which the world has none of"));
    }
    Ok(Some(Material { node_program, diffuse: 0.0, ..Material::default() }))
}
