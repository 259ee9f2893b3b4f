//! What a BVH must satisfy before it may reach the GPU. The shaders index with these
//! values unchecked, so a cache that passed its checksum but came from a buggy or
//! hostile writer must still stop here, not as out-of-bounds reads or an endless loop.

use super::cached_material::CachedMaterial;
use super::wide_node::{MAX_NODE_TRIANGLES, Slot, WIDTH, slot, slot_is_well_formed};
use crate::layout::{GpuTriangle, GpuTriangleShading, GpuWideNode};

/// Every node's child slots decode as the shader decodes them, every child link points
/// forward to an existing node (so traversal terminates), every leaf's triangle range is
/// in bounds, every triangle's material exists, and every number is finite.
pub(super) fn check_contents(
    nodes: &[GpuWideNode],
    triangles: &[GpuTriangle],
    shading: &[GpuTriangleShading],
    materials: &[CachedMaterial],
    material_names: usize,
    bounds: [[f32; 3]; 2],
) -> Result<(), String> {
    if nodes.is_empty() {
        return Err("no BVH nodes (even an empty mesh has a root)".into());
    }
    if shading.len() != triangles.len() {
        return Err(format!("{} shading records for {} triangles", shading.len(), triangles.len()));
    }
    if material_names != materials.len() {
        return Err(format!("{material_names} material names for {} materials", materials.len()));
    }
    if !bounds.as_flattened().iter().all(|v| v.is_finite()) {
        return Err("non-finite bounds".into());
    }
    let triangle_count = triangles.len() as u64;
    for (i, n) in nodes.iter().enumerate() {
        if !n.origin.iter().all(|v| v.is_finite()) {
            return Err(format!("node {i}: non-finite origin"));
        }
        // Steps of 2^(e − 127) with e in 1..=254: normal floats, never zero or infinite.
        if n.exponents_imask[..3].iter().any(|&e| e == 0 || e == 255) {
            return Err(format!("node {i}: step exponents {:?} out of range", &n.exponents_imask[..3]));
        }
        let mut leaf_triangles = 0;
        for s in 0..WIDTH {
            if !slot_is_well_formed(n, s) {
                return Err(format!("node {i} slot {s}: malformed child meta {:#010b}", n.child_meta[s]));
            }
            let ok = match slot(n, s) {
                Slot::Empty => true,
                // Children are stored after their parents, which also rules out cycles.
                Slot::Inner(child) => (child as usize) > i && (child as usize) < nodes.len(),
                Slot::Leaf(first, count) => {
                    leaf_triangles += count;
                    first as u64 + count as u64 <= triangle_count
                }
            };
            if !ok {
                return Err(format!(
                    "node {i} slot {s}: {:?} is out of range ({} nodes, {triangle_count} triangles)",
                    slot(n, s),
                    nodes.len()
                ));
            }
        }
        if leaf_triangles > MAX_NODE_TRIANGLES {
            return Err(format!(
                "node {i}: its leaves hold {leaf_triangles} triangles, more than {MAX_NODE_TRIANGLES}"
            ));
        }
    }
    for (i, t) in triangles.iter().enumerate() {
        if t.material as usize >= materials.len() {
            return Err(format!("triangle {i} uses material {} of {}", t.material, materials.len()));
        }
        if ![t.v0, t.v1, t.v2].as_flattened().iter().all(|v| v.is_finite()) {
            return Err(format!("triangle {i} has a non-finite vertex"));
        }
    }
    if let Some(i) = shading.iter().position(|s| ![s.n0, s.n1, s.n2].as_flattened().iter().all(|v| v.is_finite())) {
        return Err(format!("triangle {i} has a non-finite shading normal"));
    }
    if let Some(i) = shading.iter().position(|s| ![s.u0, s.u1, s.u2].iter().chain(&s.v).all(|v| v.is_finite())) {
        return Err(format!("triangle {i} has a non-finite texture coordinate"));
    }
    if let Some(i) = materials.iter().position(|m| !m.all_finite()) {
        return Err(format!("material {i} has a non-finite value"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::cache::{self, CacheProblem, PackedMesh};
    use super::super::wide_node::{Slot, imask, slot};
    use super::super::{BuildQuality, MeshBvh};
    use crate::asset::load_mesh;
    use std::path::Path;

    fn packed() -> PackedMesh {
        let mesh = load_mesh(Path::new("<built-in>/assets/bunny/bunny.obj")).expect("bunny");
        PackedMesh {
            bvh: MeshBvh::build(&mesh, BuildQuality::Fastest),
            vertex_count: mesh.positions.len() as u32,
            triangle_count: mesh.indices.len() as u32,
            materials: mesh.materials,
            textures: mesh.textures,
        }
    }

    /// Written with a valid checksum, then read back.
    fn read_back(test: &str, mesh: &PackedMesh) -> Result<PackedMesh, CacheProblem> {
        let path = std::env::temp_dir().join(format!("rt-cache-{}-{test}.rtbvh", std::process::id()));
        cache::write(&path, mesh, [1; 32], [2; 32]).expect("write");
        let result = cache::read(&path, [1; 32], [2; 32]);
        let _ = std::fs::remove_file(&path);
        result
    }

    fn invalid(test: &str, mesh: &PackedMesh) -> String {
        match read_back(test, mesh) {
            Err(CacheProblem::Invalid(why)) => why,
            other => panic!("{test}: expected an invalid cache, got {other:?}"),
        }
    }

    #[test]
    fn round_trip_keeps_every_array() {
        let mesh = packed();
        let back = read_back("round_trip", &mesh).expect("valid");
        assert_eq!(back.bvh.nodes, mesh.bvh.nodes);
        assert_eq!(back.bvh.triangles, mesh.bvh.triangles);
        assert_eq!(back.bvh.shading, mesh.bvh.shading);
        assert_eq!(back.bvh.stats, mesh.bvh.stats);
        assert_eq!((back.bvh.bounds_min, back.bvh.bounds_max), (mesh.bvh.bounds_min, mesh.bvh.bounds_max));
        assert_eq!(back.materials, mesh.materials);
        assert_eq!((back.vertex_count, back.triangle_count), (1839, 3674));
    }

    /// A material's compiled node graph is kept as written; one the shader could not walk
    /// (an operand past the registers, a program running past its end) is refused.
    #[test]
    fn node_programs_round_trip_and_bad_ones_are_refused() {
        let graph = serde_json::json!({ "version": 1, "nodes": [
            { "name": "Noise", "type": "TEX_NOISE", "settings": { "noise_dimensions": "3D", "noise_type": "FBM" } } ],
            "outputs": { "base_color": { "link": [0, "Color"], "from": "RGBA", "to": "RGBA" } } });
        let program = crate::asset::node_graph::compile_json(&graph).expect("compiles");
        let mut mesh = packed();
        mesh.materials[0].1.node_program = program.clone();
        let back = read_back("programs", &mesh).expect("valid");
        assert_eq!(back.materials[0].1.node_program, program);

        let mut bad = program.clone();
        bad[4] = crate::asset::node_graph::REGISTERS + 3;
        mesh.materials[0].1.node_program = bad;
        assert!(invalid("operand", &mesh).contains("node program of material 0"), "{}", invalid("operand", &mesh));
        mesh.materials[0].1.node_program = program[..program.len() / 2].to_vec();
        assert!(invalid("short", &mesh).contains("node program of material 0"));
    }

    #[test]
    fn stale_hashes_are_reported_as_stale() {
        let path = std::env::temp_dir().join(format!("rt-cache-{}-stale.rtbvh", std::process::id()));
        cache::write(&path, &packed(), [1; 32], [2; 32]).expect("write");
        assert!(matches!(cache::read(&path, [9; 32], [2; 32]), Err(CacheProblem::Stale(_))));
        assert!(matches!(cache::read(&path, [1; 32], [9; 32]), Err(CacheProblem::Stale(_))));
        let _ = std::fs::remove_file(&path);
        assert!(matches!(cache::read(&path, [1; 32], [2; 32]), Err(CacheProblem::Missing)));
    }

    /// A writer with a bug produces a valid checksum over bad contents: still refused.
    #[test]
    fn out_of_range_contents_are_refused_despite_a_valid_checksum() {
        let mut mesh = packed();
        let inner = (0..8).find(|&s| imask(&mesh.bvh.nodes[0]) & (1 << s) != 0).expect("an inner child");
        mesh.bvh.nodes[0].child_base = 0;
        assert!(
            invalid("cycle", &mesh).contains(&format!("node 0 slot {inner}: Inner(")),
            "{}",
            invalid("cycle", &mesh)
        );

        let mut mesh = packed();
        let leaf =
            mesh.bvh.nodes.iter().position(|n| (0..8).any(|s| matches!(slot(n, s), Slot::Leaf(..)))).expect("a leaf");
        mesh.bvh.nodes[leaf].primitive_base = mesh.bvh.triangles.len() as u32;
        assert!(invalid("leaf", &mesh).contains("is out of range"));

        let mut mesh = packed();
        let not_inner = (0..8).find(|&s| imask(&mesh.bvh.nodes[leaf]) & (1 << s) == 0).expect("slot");
        mesh.bvh.nodes[leaf].child_meta[not_inner] = 0b1011_0000;
        assert!(invalid("meta", &mesh).contains("malformed child meta"));

        let mut mesh = packed();
        mesh.bvh.nodes[0].exponents_imask[1] = 255;
        assert!(invalid("exponent", &mesh).contains("node 0: step exponents"));

        let mut mesh = packed();
        mesh.bvh.triangles[7].material = 1;
        assert!(invalid("material", &mesh).contains("triangle 7 uses material 1 of 1"));

        let mut mesh = packed();
        mesh.bvh.shading[3].n1[2] = f32::NAN;
        assert!(invalid("normal", &mesh).contains("triangle 3 has a non-finite shading normal"));

        let mut mesh = packed();
        mesh.bvh.tangents = vec![crate::layout::GpuTriangleTangents::default(); 5];
        assert!(invalid("tangent count", &mesh).contains("5 triangle tangents for"));
        let mut mesh = packed();
        mesh.bvh.tangents = vec![crate::layout::GpuTriangleTangents::default(); mesh.bvh.triangles.len()];
        mesh.bvh.tangents[4].t2[3] = f32::INFINITY;
        assert!(invalid("tangent", &mesh).contains("triangle 4 has a non-finite tangent"));
    }

    /// A material's tangent kind comes back; a layer texture it lacks is refused, as a base one is.
    #[test]
    fn tangent_kinds_and_layer_textures_are_kept_and_checked() {
        let mut mesh = packed();
        mesh.materials[0].1.tangent = crate::scene::Tangent::RadialY;
        mesh.materials[0].1.anisotropy = 0.5;
        let back = read_back("tangent_kind", &mesh).expect("valid");
        assert_eq!(back.materials, mesh.materials);
        mesh.materials[0].1.textures.layers.sheen_tint = Some(0);
        assert!(invalid("layer texture", &mesh).contains("material 0 uses texture 0 of 0"));
    }

    #[test]
    fn tangents_round_trip() {
        let mut mesh = packed();
        let tangent = |i: usize| [i as f32, 0.0, 1.0, -1.0];
        mesh.bvh.tangents = (0..mesh.bvh.triangles.len())
            .map(|i| crate::layout::GpuTriangleTangents { t0: tangent(i), t1: tangent(i + 1), t2: tangent(i + 2) })
            .collect();
        let back = read_back("tangents", &mesh).expect("valid");
        assert_eq!(back.bvh.tangents, mesh.bvh.tangents);
        // The bunny has no normal map: it keeps no tangents.
        assert!(packed().bvh.tangents.is_empty());
    }
}
