//! Mesh import: `.rtmesh` asset folders (the Blender exporter's), OBJ (tobj) and
//! glTF/GLB (gltf), each mapped to rt materials, plus the meshes embedded in the
//! binary for the built-in default scene.

pub mod builtin;
mod gltf_buffers;
mod gltf_extensions;
pub mod gltf_import;
mod gltf_layer_textures;
mod gltf_nodes;
mod gltf_texture_transform;
mod gltf_textures;
pub mod material_extras;
pub mod node_graph;
pub mod node_kinds;
mod node_modes;
pub mod node_program;
pub mod node_shift;
pub mod notes;
pub mod obj_import;
pub mod rtinst;
pub mod rtmesh;
mod source;
mod tangents;
pub mod texture;

pub use source::{AssetFiles, AssetKind};
pub use texture::{Filter, IDENTITY_UV_TRANSFORM, TextureImage, UvTransform, Wrap};

use crate::scene::{Material, UvSet, slots};
use std::path::{Path, PathBuf};

/// A triangle mesh in object space (metres, Y up), ready for BVH building.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    pub positions: Vec<[f32; 3]>,
    /// Per-vertex shading normals, if the source had them.
    pub normals: Option<Vec<[f32; 3]>>,
    /// Per-vertex texture coordinates with the origin at the bottom left (the OBJ and
    /// Blender convention); glTF's top-left ones are flipped on import.
    pub uvs: Option<Vec<[f32; 2]>>,
    /// A second set of texture coordinates (glTF `TEXCOORD_1`, Blender's second uv map),
    /// same convention, for the textures whose material reads it. Only with `uvs`.
    pub second_uvs: Option<Vec<[f32; 2]>>,
    /// Per-vertex MikkTSpace tangents (xyz) with the bitangent's sign (w, ±1):
    /// bitangent = w · cross(normal, tangent). Only with `uvs`.
    pub tangents: Option<Vec<[f32; 4]>>,
    /// The same of the second uv set, for normal maps that read it: MikkTSpace's, made at
    /// load (no file carries them). Only with `second_uvs`.
    pub second_tangents: Option<Vec<[f32; 4]>>,
    /// Per-vertex named attributes (Blender's colour and generic attributes) that the
    /// materials' node graphs read by number: a colour's linear RGBA, a vector's xyz, a
    /// value in x (`.rtmesh` version 4).
    pub attributes: Vec<Vec<[f32; 4]>>,
    pub indices: Vec<[u32; 3]>,
    /// Index into `materials` for each triangle.
    pub material_ids: Vec<u32>,
    /// The asset's own materials (at least one whenever there are triangles).
    pub materials: Vec<(String, Material)>,
    /// The images the materials' textures index.
    pub textures: Vec<TextureImage>,
}

/// An import failure, naming the file and what is wrong with it.
#[derive(Debug, thiserror::Error)]
#[error("{}: {message}", path.display())]
pub struct AssetError {
    pub path: PathBuf,
    pub message: String,
}

impl AssetError {
    pub fn new(path: &Path, message: impl Into<String>) -> Self {
        Self { path: path.to_path_buf(), message: message.into() }
    }
}

/// Loads a mesh asset: an asset folder `NAME/` (with `NAME.rtmesh` and `NAME.gltf`), an
/// `.rtmesh` file (with the `.gltf` of the same name beside it), a `.obj`, `.gltf` or
/// `.glb` file, or a built-in one (a path under [`crate::scene::BUILTIN_PREFIX`]).
pub fn load_mesh(path: &Path) -> Result<MeshData, AssetError> {
    let files = AssetFiles::resolve(path)?;
    let mut mesh = match files.kind {
        AssetKind::Obj => obj_import::load(&files.main)?,
        AssetKind::Gltf => gltf_import::load(&files.main)?,
        AssetKind::RtMesh { ref materials } => load_rtmesh(&files.main, materials)?,
    };
    mesh.validate(&files.main)?;
    keep_second_uvs_where_read(&mut mesh, &files.main);
    give_normal_maps_tangents(&mut mesh, &files.main);
    Ok(mesh)
}

/// A normal map needs a tangent frame of the uv set it reads, and anisotropy along the uv
/// map one of the first set (or, beside a normal map, of the map's set: a triangle carries
/// one): a mesh that uses one and brings no tangents of that set gets MikkTSpace's (which a
/// mesh without uvs cannot have: its maps are left out, and its anisotropy has no tangent to
/// follow). The second set's always come from here.
fn give_normal_maps_tangents(mesh: &mut MeshData, path: &Path) {
    for (name, m) in &mesh.materials {
        if m.reads_uv_tangents() && m.textures.normal_uv_set() == UvSet::Second {
            log::warn!(
                "{}: material {name:?} is anisotropic along its uv map and normal-mapped on the second; \
                 its anisotropy follows the second set's tangents",
                path.display()
            );
        }
    }
    for (name, m) in &mesh.materials {
        let t = &m.textures;
        if t.normal.is_some()
            && t.coat_normal.is_some()
            && t.reads_second_uv_set(slots::NORMAL) != t.reads_second_uv_set(slots::COAT_NORMAL)
        {
            log::warn!(
                "{}: material {name:?} has normal maps on two uv sets (the base's and the coat's); \
                 the coat's map is oriented by the base's set's tangents",
                path.display()
            );
        }
    }
    for set in [UvSet::First, UvSet::Second] {
        let readers: Vec<&str> = mesh
            .materials
            .iter()
            .filter(|(_, m)| m.reads_tangents() && m.textures.normal_uv_set() == set)
            .map(|(name, _)| name.as_str())
            .collect();
        if readers.is_empty() || mesh.tangents_of(set).is_some() {
            continue;
        }
        if mesh.uvs_of(set).is_none() {
            log::warn!(
                "{}: material {:?} has a normal map or uv tangents but the mesh has no texture coordinates; they are left out",
                path.display(),
                readers[0]
            );
        } else if tangents::generate(mesh, set) {
            log::info!(
                "{}: generated MikkTSpace tangents of uv set {} for its normal maps or uv tangents",
                path.display(),
                set as u8
            );
        } else {
            log::warn!(
                "{}: MikkTSpace could not make tangents for its normal maps or uv tangents; they are left out",
                path.display()
            );
        }
    }
}

/// A texture that reads the second uv set needs one: without it, the texture reads the
/// first set (with a warning). A second set no material reads is dropped, so that a scene
/// pays for it only where it is used.
fn keep_second_uvs_where_read(mesh: &mut MeshData, path: &Path) {
    let readers = mesh.materials.iter().filter(|(_, m)| m.textures.uses_second_uv_set());
    if mesh.second_uvs.is_none() || mesh.uvs.is_none() {
        for (name, _) in readers {
            log::warn!(
                "{}: material {name:?} reads a second uv set that the mesh does not have; it reads the first",
                path.display()
            );
        }
        mesh.materials.iter_mut().for_each(|(_, m)| m.textures.second_uv_set = 0);
        mesh.second_uvs = None;
    } else if readers.count() == 0 {
        mesh.second_uvs = None;
    }
}

/// An `.rtmesh`'s geometry with the materials of its sibling glTF, which holds no meshes.
fn load_rtmesh(path: &Path, materials_path: &Path) -> Result<MeshData, AssetError> {
    let geometry = rtmesh::read(path)?;
    let MeshData { mut materials, textures, .. } = gltf_import::load(materials_path)?;
    // An object with no material slots is exported with material index 0 throughout.
    if materials.is_empty() {
        materials.push(("default".into(), Material::default()));
    }
    Ok(MeshData {
        positions: geometry.positions,
        normals: geometry.normals,
        uvs: geometry.uvs,
        second_uvs: geometry.second_uvs,
        tangents: geometry.tangents,
        second_tangents: None,
        attributes: geometry.attributes,
        indices: geometry.indices,
        material_ids: geometry.material_ids,
        materials,
        textures,
    })
}

impl From<crate::files::OutputError> for AssetError {
    fn from(e: crate::files::OutputError) -> Self {
        Self { path: e.path, message: e.message }
    }
}

impl MeshData {
    pub fn uvs_of(&self, set: UvSet) -> Option<&Vec<[f32; 2]>> {
        match set {
            UvSet::First => self.uvs.as_ref(),
            UvSet::Second => self.second_uvs.as_ref(),
        }
    }

    pub fn tangents_of(&self, set: UvSet) -> Option<&Vec<[f32; 4]>> {
        match set {
            UvSet::First => self.tangents.as_ref(),
            UvSet::Second => self.second_tangents.as_ref(),
        }
    }

    /// Checks what the GPU relies on: finite positions, indices in range, one material per
    /// triangle. The shaders trust these, so a bad file must stop here rather than
    /// become NaNs or out-of-bounds reads on the GPU.
    pub fn validate(&self, path: &Path) -> Result<(), AssetError> {
        let fail = |message: String| Err(AssetError::new(path, message));
        let vertex_count = self.positions.len();

        if let Some((i, bad)) = first_non_finite(&self.positions) {
            return fail(format!("vertex {i} has a non-finite position ({bad:?})"));
        }
        if let Some(normals) = &self.normals {
            if normals.len() != vertex_count {
                return fail(format!("{} normals for {vertex_count} vertices", normals.len()));
            }
            if let Some((i, bad)) = first_non_finite(normals) {
                return fail(format!("vertex {i} has a non-finite normal ({bad:?})"));
            }
        }
        for (set, uvs) in [(0, &self.uvs), (1, &self.second_uvs)] {
            let Some(uvs) = uvs else { continue };
            if uvs.len() != vertex_count {
                return fail(format!("{} texture coordinates of set {set} for {vertex_count} vertices", uvs.len()));
            }
            if let Some((i, bad)) = first_non_finite(uvs) {
                return fail(format!("vertex {i} has a non-finite texture coordinate of set {set} ({bad:?})"));
            }
        }

        for (set, tangents) in [(0, &self.tangents), (1, &self.second_tangents)] {
            let Some(tangents) = tangents else { continue };
            if tangents.len() != vertex_count {
                return fail(format!("{} tangents of set {set} for {vertex_count} vertices", tangents.len()));
            }
            if let Some((i, bad)) = first_non_finite(tangents) {
                return fail(format!("vertex {i} has a non-finite tangent of set {set} ({bad:?})"));
            }
        }

        for (k, attribute) in self.attributes.iter().enumerate() {
            if attribute.len() != vertex_count {
                return fail(format!("{} values of attribute {k} for {vertex_count} vertices", attribute.len()));
            }
            if let Some((i, bad)) = first_non_finite(attribute) {
                return fail(format!("vertex {i} has a non-finite value of attribute {k} ({bad:?})"));
            }
        }

        if self.indices.is_empty() {
            return fail("contains no triangles".into());
        }
        for (t, tri) in self.indices.iter().enumerate() {
            if let Some(&v) = tri.iter().find(|&&v| v as usize >= vertex_count) {
                return fail(format!("triangle {t} refers to vertex {v} but there are only {vertex_count} vertices"));
            }
        }

        for (name, material) in &self.materials {
            let read = node_program::attributes_read(&material.node_program);
            if let Some(slot) = read.into_iter().find(|&s| s as usize >= self.attributes.len()) {
                return fail(format!(
                    "material `{name}` reads attribute {slot}, but the mesh has {} attributes (export it again)",
                    self.attributes.len()
                ));
            }
        }

        if self.material_ids.len() != self.indices.len() {
            return fail(format!("{} material indices for {} triangles", self.material_ids.len(), self.indices.len()));
        }
        let material_count = self.materials.len();
        if let Some((t, m)) = self.material_ids.iter().enumerate().find(|&(_, &m)| m as usize >= material_count) {
            return fail(format!("triangle {t} uses material {m} but there are only {material_count} materials"));
        }
        Ok(())
    }
}

/// The index and value of the first non-finite component, if any.
fn first_non_finite<const N: usize>(items: &[[f32; N]]) -> Option<(usize, f32)> {
    items.iter().enumerate().find_map(|(i, item)| item.iter().find(|c| !c.is_finite()).map(|&c| (i, c)))
}

/// Fixture files for the importers' tests.
#[cfg(test)]
pub(crate) mod fixture {
    use std::path::PathBuf;

    /// A fresh directory under the system temporary directory, removed on drop.
    /// Named after the test so that tests running in parallel never share one.
    pub struct TempDir(PathBuf);

    impl TempDir {
        pub fn new(test: &str) -> Self {
            let dir = std::env::temp_dir().join(format!("rt-asset-{}-{test}", std::process::id()));
            // A leftover from a crashed run must not leak stale files into this one.
            let _ = std::fs::remove_dir_all(&dir);
            std::fs::create_dir_all(&dir).expect("create temp dir");
            Self(dir)
        }

        pub fn write(&self, name: &str, contents: &str) -> PathBuf {
            let path = self.0.join(name);
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent).expect("create fixture folder");
            }
            std::fs::write(&path, contents).expect("write fixture");
            path
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// Standard base64, for glTF data URIs.
    pub fn base64(bytes: &[u8]) -> String {
        const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut out = String::new();
        for chunk in bytes.chunks(3) {
            let n = chunk.iter().enumerate().fold(0u32, |n, (i, &b)| n | (b as u32) << (16 - 8 * i));
            for i in 0..=chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * i) & 63) as usize] as char);
            }
            out.push_str(&"=".repeat(3 - chunk.len()));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::fixture::TempDir;
    use super::*;

    fn triangle() -> MeshData {
        MeshData {
            positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            indices: vec![[0, 1, 2]],
            material_ids: vec![0],
            materials: vec![("default".into(), Material::default())],
            ..Default::default()
        }
    }

    fn validate_error(mesh: &MeshData) -> String {
        mesh.validate(Path::new("m.obj")).expect_err("invalid mesh").to_string()
    }

    #[test]
    fn validate_accepts_a_triangle() {
        triangle().validate(Path::new("m.obj")).expect("valid");
    }

    /// A material that reads an attribute the mesh lacks, or attributes of the wrong length
    /// or not finite, are refused with the material and the attribute named.
    #[test]
    fn validate_checks_the_attributes_and_who_reads_them() {
        let graph = serde_json::json!({ "version": 1,
            "nodes": [{ "name": "A", "type": "ATTRIBUTE", "settings": { "slot": 1, "data": "FLOAT3" } }],
            "outputs": { "base_color": { "link": [0, "Color"], "from": "RGBA", "to": "RGBA" } } });
        let mut mesh = triangle();
        mesh.materials[0].1.node_program = node_graph::compile_json(&graph).expect("compiles");
        mesh.attributes = vec![vec![[0.5; 4]; 3]];
        let e = validate_error(&mesh);
        assert!(e.contains("material `default` reads attribute 1, but the mesh has 1 attributes"), "{e}");
        mesh.attributes.push(vec![[0.5; 4]; 2]);
        assert!(validate_error(&mesh).contains("2 values of attribute 1 for 3 vertices"));
        mesh.attributes[1].push([f32::NAN; 4]);
        assert!(validate_error(&mesh).contains("vertex 2 has a non-finite value of attribute 1"));
        mesh.attributes[1][2] = [0.0; 4];
        mesh.validate(Path::new("m.obj")).expect("valid");
    }

    #[test]
    fn validate_names_what_is_wrong() {
        let mut mesh = triangle();
        mesh.indices.push([0, 2, 9]);
        mesh.material_ids.push(0);
        assert_eq!(validate_error(&mesh), "m.obj: triangle 1 refers to vertex 9 but there are only 3 vertices");

        let mut mesh = triangle();
        mesh.material_ids[0] = 1;
        assert!(validate_error(&mesh).contains("triangle 0 uses material 1"));

        let mut mesh = triangle();
        mesh.normals = Some(vec![[0.0, 0.0, 1.0]; 2]);
        assert!(validate_error(&mesh).contains("2 normals for 3 vertices"));

        let mut mesh = triangle();
        mesh.uvs = Some(vec![[0.0, 0.0], [1.0, f32::INFINITY], [0.0, 1.0]]);
        assert!(validate_error(&mesh).contains("vertex 1 has a non-finite texture coordinate"));

        let mut mesh = triangle();
        mesh.indices.clear();
        mesh.material_ids.clear();
        assert!(validate_error(&mesh).contains("contains no triangles"));
    }

    #[test]
    fn obj_index_out_of_range_is_an_error() {
        let dir = TempDir::new("obj_index_out_of_range");
        let path = dir.write("oob.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n");
        let message = load_mesh(&path).expect_err("index 99 of 3").to_string();
        assert!(message.contains("oob.obj"), "{message}");
        assert!(message.contains("line 4: triangle refers to vertex 99"), "{message}");
        assert!(message.contains("only 3 vertices"), "{message}");
    }

    #[test]
    fn obj_nan_vertex_is_an_error() {
        let dir = TempDir::new("obj_nan_vertex");
        let path = dir.write("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        let message = load_mesh(&path).expect_err("NaN vertex").to_string();
        assert!(message.contains("nan.obj"), "{message}");
        assert!(message.contains("vertex 0 has a non-finite position (NaN)"), "{message}");
    }

    #[test]
    fn unknown_extension_is_an_error() {
        let dir = TempDir::new("unknown_extension");
        let path = dir.write("mesh.stl", "solid x\nendsolid x\n");
        let message = load_mesh(&path).expect_err("unsupported type").to_string();
        assert!(message.contains("mesh.stl") && message.contains("unsupported"), "{message}");
    }

    #[test]
    fn missing_file_is_an_error() {
        let message = load_mesh(Path::new("/nonexistent/rt/a.obj")).expect_err("no file").to_string();
        assert_eq!(message, "/nonexistent/rt/a.obj: no such file or folder");
    }
}
