//! What a BVH must satisfy before it may reach the GPU. The shaders index with these
//! values unchecked, so a cache that passed its checksum but came from a buggy or
//! hostile writer must still stop here, not as out-of-bounds reads or an endless loop.

use super::cached_material::CachedMaterial;
use crate::layout::{EMPTY_LINK, GpuBvhNode, GpuTriangle, GpuTriangleShading};

/// Every node link points forward to an existing node (so traversal terminates), every
/// leaf's triangle range is in bounds, every triangle's material exists, and every
/// number is finite.
pub(super) fn check_contents(
    nodes: &[GpuBvhNode],
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
        for (slot, (min, max, link, count)) in
            [("a", (n.a_min, n.a_max, n.a_link, n.a_count)), ("b", (n.b_min, n.b_max, n.b_link, n.b_count))]
        {
            let at = || format!("node {i} child {slot}");
            if !min.iter().chain(&max).all(|v| v.is_finite()) {
                return Err(format!("{}: non-finite box", at()));
            }
            let ok = match (link, count) {
                (EMPTY_LINK, 0) => true,
                (EMPTY_LINK, _) => false,
                (first, count @ 1..) => first as u64 + count as u64 <= triangle_count,
                // Children are stored after their parents, which also rules out cycles.
                (child, 0) => (child as usize) > i && (child as usize) < nodes.len(),
            };
            if !ok {
                return Err(format!(
                    "{}: link {link} with count {count} is out of range ({} nodes, {triangle_count} triangles)",
                    at(),
                    nodes.len()
                ));
            }
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
    use super::super::{BuildQuality, MeshBvh};
    use crate::asset::load_mesh;
    use crate::layout::EMPTY_LINK;
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
        mesh.bvh.nodes[0].a_count = 0;
        mesh.bvh.nodes[0].a_link = 0;
        assert!(invalid("cycle", &mesh).contains("node 0 child a: link 0 with count 0 is out of range"));

        let mut mesh = packed();
        let leaf = mesh.bvh.nodes.iter().position(|n| n.b_count > 0).expect("a leaf");
        mesh.bvh.nodes[leaf].b_link = mesh.bvh.triangles.len() as u32;
        assert!(invalid("leaf", &mesh).contains("is out of range"));

        let mut mesh = packed();
        mesh.bvh.nodes[0].b_link = EMPTY_LINK;
        mesh.bvh.nodes[0].b_count = 3;
        assert!(invalid("empty", &mesh).contains("is out of range"));

        let mut mesh = packed();
        mesh.bvh.triangles[7].material = 1;
        assert!(invalid("material", &mesh).contains("triangle 7 uses material 1 of 1"));

        let mut mesh = packed();
        mesh.bvh.shading[3].n1[2] = f32::NAN;
        assert!(invalid("normal", &mesh).contains("triangle 3 has a non-finite shading normal"));
    }
}
