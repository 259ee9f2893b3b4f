//! What makes a render's image, hashed: the parts of one render carry it, so that a part
//! of another scene or of other settings is refused at the merge.

use super::super::Session;
use crate::layout::GpuFrame;
use crate::scene::Sky;
use anyhow::{Context, Result};

/// BLAKE3 (hex) of what the GPU renders from: the geometry, materials, lights and textures
/// as uploaded, the frame's constants (but the size, the seed and the samples, which a
/// merge names on their own), the pipeline's effects, the sky and the sun. Paths are not in
/// it: the same scene unpacked elsewhere has the same key.
pub fn image_key(session: &Session) -> Result<String> {
    let g = session.geometry();
    let mut h = blake3::Hasher::new();
    let mut pod = |label: &str, bytes: &[u8]| {
        h.update(label.as_bytes());
        h.update(&(bytes.len() as u64).to_le_bytes());
        h.update(bytes);
    };
    pod("nodes", bytemuck::cast_slice(&g.nodes));
    pod("wide nodes", bytemuck::cast_slice(&g.wide_nodes));
    pod("triangles", bytemuck::cast_slice(&g.triangles));
    pod("shading", bytemuck::cast_slice(&g.shading));
    pod("tangents", bytemuck::cast_slice(&g.tangents));
    pod("second uvs", bytemuck::cast_slice(&g.second_uvs));
    pod("instances", bytemuck::cast_slice(&g.instances));
    pod("object settings", bytemuck::cast_slice(&g.object_settings));
    pod("motion matrices", bytemuck::cast_slice(&g.motion_matrices));
    pod("tlas", bytemuck::cast_slice(&g.tlas_primitives));
    pod("spheres", bytemuck::cast_slice(&g.spheres));
    pod("materials", bytemuck::cast_slice(&g.materials));
    pod("node programs", bytemuck::cast_slice(&g.node_programs));
    pod("emitters", bytemuck::cast_slice(&g.emitters));
    pod("lamps", bytemuck::cast_slice(&g.lamps));
    pod("lamp info", bytemuck::bytes_of(&g.lamp_info));
    for t in g.textures() {
        let about = format!("{}x{} {:?} {} {:?}", t.width, t.height, t.wrap, t.srgb, t.uv_transform);
        pod("texture", about.as_bytes());
        pod("texels", bytemuck::cast_slice(&t.texels));
    }
    let frame = GpuFrame { width: 0, height: 0, seed: 0, first_sample: 0, ..session.frame() };
    pod("frame", bytemuck::bytes_of(&frame));
    pod("effects", session.pipeline_features().to_string().as_bytes());
    let scene = session.scene();
    let sky = match &scene.sky {
        Sky::Environment(e) => {
            let bytes = std::fs::read(&e.image).with_context(|| format!("{}: cannot read", e.image.display()))?;
            let params = format!("{} {:?} {} {}", e.strength, e.rotation_deg, e.importance_sampling, e.srgb);
            format!("environment {} {params}", blake3::hash(&bytes))
        }
        other => format!("{other:?}"),
    };
    pod("sky", sky.as_bytes());
    pod("sun", format!("{:?}", scene.sun).as_bytes());
    Ok(h.finalize().to_hex().to_string())
}

/// What identifies the build of rt that rendered: its version and the BLAKE3 of its
/// executable (another build may round differently).
pub fn build_id() -> Result<String> {
    let exe = std::env::current_exe().context("cannot find rt's own executable")?;
    let bytes = std::fs::read(&exe).with_context(|| format!("{}: cannot read rt's own executable", exe.display()))?;
    Ok(format!("rt {} {}", env!("CARGO_PKG_VERSION"), &blake3::hash(&bytes).to_hex()[..16]))
}
