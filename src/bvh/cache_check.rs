//! What a BVH must satisfy before it may reach the GPU. The shaders index with these
//! values unchecked, so a cache that passed its checksum but came from a buggy or
//! hostile writer must still stop here, not as out-of-bounds reads or an endless loop.

use crate::gpu::layout::{EMPTY_LINK, GpuBvhNode, GpuMaterial, GpuTriangle, GpuTriangleShading};

/// Every node link points forward to an existing node (so traversal terminates), every
/// leaf's triangle range is in bounds, every triangle's material exists, and every
/// number is finite.
pub(super) fn check_contents(
    nodes: &[GpuBvhNode],
    triangles: &[GpuTriangle],
    shading: &[GpuTriangleShading],
    materials: &[GpuMaterial],
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
    let material_values = |m: &GpuMaterial| {
        let vectors = [m.base_color, m.emission, m.absorption, m.volume_emission];
        let scalars = [m.diffuse, m.specular, m.reflection, m.transmission, m.ior, m.roughness];
        vectors.into_iter().flatten().chain(scalars).all(f32::is_finite)
    };
    if let Some(i) = materials.iter().position(|m| !material_values(m)) {
        return Err(format!("material {i} has a non-finite value"));
    }
    Ok(())
}
