//! MikkTSpace tangents (Mikkelsen 2008, the `mikktspace` crate) for meshes that have a
//! normal-mapped material but no tangents of their own: the tangent space that Blender,
//! glTF and the tools that bake normal maps agree on, so that a map looks as it was made.
//!
//! MikkTSpace gives a tangent per triangle corner; corners that share a vertex may get
//! different ones (at a mirror seam of the uvs), and such a vertex is split in two.
//! Either uv set has its own: a normal map's frame is of the set it reads.

use super::MeshData;
use crate::scene::UvSet;
use glam::Vec3;
use std::collections::HashMap;

/// A mesh as MikkTSpace reads it, with the tangent it writes per corner.
struct Corners<'a> {
    mesh: &'a MeshData,
    uvs: &'a [[f32; 2]],
    tangents: Vec<[f32; 4]>,
}

impl Corners<'_> {
    fn vertex(&self, face: usize, corner: usize) -> usize {
        self.mesh.indices[face][corner] as usize
    }

    /// A mesh without normals is shaded flat: its face normals.
    fn face_normal(&self, face: usize) -> [f32; 3] {
        let p = self.mesh.indices[face].map(|k| Vec3::from_array(self.mesh.positions[k as usize]));
        (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero().to_array()
    }
}

impl mikktspace::Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.indices.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, corner: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, corner)]
    }

    fn normal(&self, face: usize, corner: usize) -> [f32; 3] {
        match &self.mesh.normals {
            Some(normals) => normals[self.vertex(face, corner)],
            None => self.face_normal(face),
        }
    }

    fn tex_coord(&self, face: usize, corner: usize) -> [f32; 2] {
        self.uvs[self.vertex(face, corner)]
    }

    fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, corner: usize) {
        self.tangents[face * 3 + corner] = tangent;
    }
}

/// Gives `mesh` MikkTSpace tangents of uv set `set` (it must have that set), splitting
/// the vertices whose corners disagree. Returns false, leaving the mesh as it was, when
/// MikkTSpace refuses it.
pub fn generate(mesh: &mut MeshData, set: UvSet) -> bool {
    let Some(uvs) = mesh.uvs_of(set).map(Vec::as_slice) else {
        return false;
    };
    let mut corners = Corners { mesh: &*mesh, uvs, tangents: vec![[0.0; 4]; mesh.indices.len() * 3] };
    if !mikktspace::generate_tangents(&mut corners) {
        return false;
    }
    let per_corner = corners.tangents;
    // Non-finite output (degenerate uvs) becomes "no tangent": the shader then leaves the
    // normal alone there.
    let clean = |t: [f32; 4]| if t.iter().all(|c| c.is_finite()) { t } else { [0.0; 4] };
    let mut tangents: Vec<Option<[f32; 4]>> = vec![None; mesh.positions.len()];
    let mut splits: HashMap<(u32, [u32; 4]), u32> = HashMap::new();
    for face in 0..mesh.indices.len() {
        for corner in 0..3 {
            let t = clean(per_corner[face * 3 + corner]);
            let v = mesh.indices[face][corner] as usize;
            match tangents[v] {
                None => tangents[v] = Some(t),
                Some(existing) if existing == t => {}
                Some(_) => {
                    let key = (v as u32, t.map(f32::to_bits));
                    let split = match splits.get(&key) {
                        Some(&split) => split,
                        None => {
                            tangents.push(Some(t));
                            let split = split_vertex(mesh, v);
                            splits.insert(key, split);
                            split
                        }
                    };
                    mesh.indices[face][corner] = split;
                }
            }
        }
    }
    let tangents = Some(tangents.into_iter().map(|t| t.unwrap_or([0.0; 4])).collect());
    match set {
        UvSet::First => mesh.tangents = tangents,
        UvSet::Second => mesh.second_tangents = tangents,
    }
    true
}

/// Appends a copy of vertex `v`'s attributes (but the tangent of the set being made,
/// which `generate` sets at the end); returns its index.
fn split_vertex(mesh: &mut MeshData, v: usize) -> u32 {
    mesh.positions.push(mesh.positions[v]);
    if let Some(n) = &mut mesh.normals {
        n.push(n[v]);
    }
    for uv in [&mut mesh.uvs, &mut mesh.second_uvs].into_iter().flatten() {
        uv.push(uv[v]);
    }
    for t in [&mut mesh.tangents, &mut mesh.second_tangents].into_iter().flatten() {
        t.push(t[v]);
    }
    (mesh.positions.len() - 1) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit quad in the xy plane facing +z, u along +x and v along +y.
    fn quad(uvs: Vec<[f32; 2]>) -> MeshData {
        MeshData {
            positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
            normals: Some(vec![[0.0, 0.0, 1.0]; 4]),
            uvs: Some(uvs),
            indices: vec![[0, 1, 2], [0, 2, 3]],
            material_ids: vec![0, 0],
            ..Default::default()
        }
    }

    #[test]
    fn tangent_follows_u_and_sign_follows_v() {
        let mut mesh = quad(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        assert!(generate(&mut mesh, UvSet::First));
        for t in mesh.tangents.as_ref().expect("tangents") {
            assert!((Vec3::new(t[0], t[1], t[2]) - Vec3::X).length() < 1e-5, "{t:?}");
            // bitangent = w · n × t = +y, where v grows.
            assert_eq!(t[3], 1.0);
        }
        // v running down the quad instead mirrors the frame: the sign flips.
        let mut mirrored = quad(vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
        assert!(generate(&mut mirrored, UvSet::First));
        assert!(mirrored.tangents.expect("tangents").iter().all(|t| t[3] == -1.0));
    }

    #[test]
    fn the_second_sets_tangents_follow_its_own_u() {
        // The second map turned a quarter: its u grows along +y, its v along -x.
        let mut mesh = MeshData {
            second_uvs: Some(vec![[0.0, 1.0], [0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]),
            ..quad(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
        };
        assert!(generate(&mut mesh, UvSet::First) && generate(&mut mesh, UvSet::Second));
        let (firsts, seconds) =
            (mesh.tangents.as_ref().expect("first"), mesh.second_tangents.as_ref().expect("second"));
        for (first, second) in firsts.iter().zip(seconds) {
            assert!((Vec3::new(first[0], first[1], first[2]) - Vec3::X).length() < 1e-5, "{first:?}");
            assert!((Vec3::new(second[0], second[1], second[2]) - Vec3::Y).length() < 1e-5, "{second:?}");
            // bitangent = w · n × t = -x, where the second map's v grows.
            assert_eq!(second[3], 1.0);
        }
    }

    #[test]
    fn a_uv_mirror_seam_splits_the_shared_vertices() {
        // Two quads side by side sharing the edge x = 1; the right one's u runs backwards.
        let mut mesh = MeshData {
            positions: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 1.0, 0.0],
            ],
            normals: Some(vec![[0.0, 0.0, 1.0]; 6]),
            uvs: Some(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0], [0.0, 1.0]]),
            indices: vec![[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]],
            material_ids: vec![0; 4],
            materials: vec![("flat".into(), crate::scene::Material::default())],
            ..Default::default()
        };
        assert!(generate(&mut mesh, UvSet::First));
        assert_eq!(mesh.positions.len(), 8, "the two seam vertices are split");
        let tangents = mesh.tangents.as_ref().expect("tangents");
        for (face, expected_x) in [(0, 1.0), (1, 1.0), (2, -1.0), (3, -1.0)] {
            for &v in &mesh.indices[face] {
                assert!((tangents[v as usize][0] - expected_x).abs() < 1e-5, "face {face}: {:?}", tangents[v as usize]);
            }
        }
        assert!(mesh.validate(std::path::Path::new("seam")).is_ok());
    }
}
