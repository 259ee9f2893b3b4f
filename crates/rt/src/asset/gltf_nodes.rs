//! The glTF node hierarchy walked depth first: each mesh's triangle primitives placed by
//! their nodes' transforms and appended to one [`MeshData`], with the shading attributes
//! kept only where every primitive has them.

use super::MeshData;
use crate::scene::Material;
use glam::{Mat3, Mat4, Vec3};
use gltf::accessor::{DataType as T, Dimensions as D};
use gltf::mesh::{Mode, Semantic};
use std::path::Path;

/// The triangles of the default scene (else the first, else every root node) of
/// `document`, with node transforms applied, appended to `mesh` (which holds the
/// materials). `path` names the file in the warning about dropped attributes.
pub(super) fn place_meshes(
    document: &gltf::Document,
    buffers: &[gltf::buffer::Data],
    mesh: MeshData,
    path: &Path,
) -> Result<MeshData, String> {
    let mut walk = Walk::new(buffers, document.nodes().len(), mesh);
    for root in &root_nodes(document) {
        walk.visit(root, Mat4::IDENTITY, 0)?;
    }
    Ok(walk.finish(path))
}

/// The default scene's nodes, else the first scene's, else every node that is no child.
fn root_nodes(document: &gltf::Document) -> Vec<gltf::Node<'_>> {
    match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            let mut is_child = vec![false; document.nodes().len()];
            for child in document.nodes().flat_map(|n| n.children()) {
                is_child[child.index()] = true;
            }
            document.nodes().filter(|n| !is_child[n.index()]).collect()
        }
    }
}

/// State of the depth-first walk over the node hierarchy.
struct Walk<'a> {
    buffers: &'a [gltf::buffer::Data],
    node_count: usize,
    mesh: MeshData,
    normals: Vec<[f32; 3]>,
    uvs: Vec<[f32; 2]>,
    second_uvs: Vec<[f32; 2]>,
    tangents: Vec<[f32; 4]>,
    /// Shading attributes are kept only if every primitive has them.
    all_normals: bool,
    all_tangents: bool,
    all_uvs: bool,
    all_second_uvs: bool,
    default_material: Option<u32>,
}

/// Where a primitive lands: its world transform and what follows from it.
struct Placement {
    world: Mat4,
    normal_matrix: Mat3,
    /// A mirroring transform turns counter-clockwise triangles clockwise.
    flip: bool,
}

impl<'a> Walk<'a> {
    fn new(buffers: &'a [gltf::buffer::Data], node_count: usize, mesh: MeshData) -> Self {
        Walk {
            buffers,
            node_count,
            mesh,
            normals: Vec::new(),
            uvs: Vec::new(),
            second_uvs: Vec::new(),
            tangents: Vec::new(),
            all_normals: true,
            all_tangents: true,
            all_uvs: true,
            all_second_uvs: true,
            default_material: None,
        }
    }

    fn visit(&mut self, node: &gltf::Node, parent: Mat4, depth: usize) -> Result<(), String> {
        // A path longer than the node count must revisit a node.
        if depth > self.node_count {
            return Err("the node hierarchy has a cycle".into());
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            self.add_mesh(&mesh, node.index(), world)?;
        }
        for child in node.children() {
            self.visit(&child, world, depth + 1)?;
        }
        Ok(())
    }

    fn add_mesh(&mut self, mesh: &gltf::Mesh, node: usize, world: Mat4) -> Result<(), String> {
        let det = world.determinant();
        if !det.is_finite() {
            return Err(format!("node {node} has a non-finite transform"));
        }
        if det == 0.0 {
            // Every triangle would have zero area; zero scale is how animators hide things.
            log::warn!("node {node} scales mesh {} to nothing; skipped", mesh.index());
            return Ok(());
        }
        let place = Placement { world, normal_matrix: Mat3::from_mat4(world).inverse().transpose(), flip: det < 0.0 };
        for prim in mesh.primitives() {
            let at = format!("mesh {} primitive {}", mesh.index(), prim.index());
            if prim.mode() != Mode::Triangles {
                log::warn!("{at}: mode {:?} is not triangles; skipped", prim.mode());
                continue;
            }
            if prim.get(&Semantic::Positions).is_none() {
                log::warn!("{at}: no POSITION attribute; skipped");
                continue;
            }
            self.add_primitive(&prim, &place, &at)?;
        }
        Ok(())
    }

    fn add_primitive(&mut self, prim: &gltf::Primitive, place: &Placement, at: &str) -> Result<(), String> {
        check_primitive_types(prim, at)?;
        let reader = prim.reader(|b| self.buffers.get(b.index()).map(|d| &d.0[..]));
        let positions: Vec<[f32; 3]> = reader
            .read_positions()
            .ok_or_else(|| unreadable(at, "POSITION"))?
            .map(|p| place.world.transform_point3(Vec3::from(p)).to_array())
            .collect();
        let count = positions.len();
        if u32::try_from(self.mesh.positions.len() + count).is_err() {
            return Err(format!("{at}: more than 2^32 vertices in all"));
        }
        let base = self.mesh.positions.len() as u32;
        // Read even once incomplete, so that the final warning knows what was dropped.
        let present = |semantic: Semantic| prim.get(&semantic).is_some();
        let normals = present(Semantic::Normals)
            .then(|| reader.read_normals().ok_or_else(|| unreadable(at, "NORMAL")))
            .transpose()?;
        self.add_normals(normals, place, count, at)?;
        let tangents = present(Semantic::Tangents)
            .then(|| reader.read_tangents().ok_or_else(|| unreadable(at, "TANGENT")))
            .transpose()?;
        self.add_tangents(tangents, place, count, at)?;
        for set in [0, 1] {
            let name = format!("TEXCOORD_{set}");
            let uvs = present(Semantic::TexCoords(set))
                .then(|| reader.read_tex_coords(set).map(|r| r.into_f32()).ok_or_else(|| unreadable(at, &name)))
                .transpose()?;
            self.add_uv_set(set, uvs, count, at)?;
        }
        let indices = prim
            .indices()
            .map(|_| reader.read_indices().map(|r| r.into_u32().collect()).ok_or_else(|| unreadable(at, "indices")))
            .transpose()?;
        let indices = checked_indices(indices, count, at)?;
        let material = self.material_of(prim);
        self.mesh.positions.extend(positions);
        for tri in indices.chunks_exact(3) {
            let [a, b, c] = [tri[0] + base, tri[1] + base, tri[2] + base];
            self.mesh.indices.push(if place.flip { [a, c, b] } else { [a, b, c] });
            self.mesh.material_ids.push(material);
        }
        Ok(())
    }

    fn add_normals(
        &mut self,
        normals: Option<impl Iterator<Item = [f32; 3]>>,
        place: &Placement,
        count: usize,
        at: &str,
    ) -> Result<(), String> {
        let Some(normals) = normals else {
            self.all_normals = false;
            return Ok(());
        };
        let start = self.normals.len();
        self.normals.extend(normals.map(|n| (place.normal_matrix * Vec3::from(n)).normalize_or_zero().to_array()));
        if self.normals.len() - start != count {
            return Err(format!("{at}: NORMAL and POSITION counts differ"));
        }
        Ok(())
    }

    fn add_tangents(
        &mut self,
        tangents: Option<impl Iterator<Item = [f32; 4]>>,
        place: &Placement,
        count: usize,
        at: &str,
    ) -> Result<(), String> {
        let Some(tangents) = tangents else {
            self.all_tangents = false;
            return Ok(());
        };
        let start = self.tangents.len();
        let to_world = Mat3::from_mat4(place.world);
        // A mirroring transform flips the bitangent against n × t.
        let handedness = if place.flip { -1.0 } else { 1.0 };
        self.tangents.extend(tangents.map(|[x, y, z, w]| {
            let t = (to_world * Vec3::new(x, y, z)).normalize_or_zero();
            [t.x, t.y, t.z, if w < 0.0 { -handedness } else { handedness }]
        }));
        if self.tangents.len() - start != count {
            return Err(format!("{at}: TANGENT and POSITION counts differ"));
        }
        Ok(())
    }

    fn add_uv_set(
        &mut self,
        set: u32,
        read: Option<impl Iterator<Item = [f32; 2]>>,
        count: usize,
        at: &str,
    ) -> Result<(), String> {
        let (all, uvs) = match set {
            0 => (&mut self.all_uvs, &mut self.uvs),
            _ => (&mut self.all_second_uvs, &mut self.second_uvs),
        };
        let Some(read) = read else {
            *all = false;
            return Ok(());
        };
        let start = uvs.len();
        // As they are: each texture applies its own transform (`gltf_texture_transform`).
        uvs.extend(read.map(|[u, v]| [u, 1.0 - v]));
        if uvs.len() - start != count {
            return Err(format!("{at}: TEXCOORD_{set} and POSITION counts differ"));
        }
        Ok(())
    }

    /// The primitive's material, or rt's default one (added once, when first needed).
    fn material_of(&mut self, prim: &gltf::Primitive) -> u32 {
        match prim.material().index() {
            Some(i) => i as u32,
            None => *self.default_material.get_or_insert_with(|| {
                self.mesh.materials.push(("default".into(), Material::default()));
                (self.mesh.materials.len() - 1) as u32
            }),
        }
    }

    /// The mesh with the shading attributes every primitive had.
    fn finish(self, path: &Path) -> MeshData {
        let mut mesh = self.mesh;
        if (!self.all_normals && !self.normals.is_empty()) || (!self.all_uvs && !self.uvs.is_empty()) {
            log::warn!("{}: NORMAL or TEXCOORD_0 is missing on some primitives; dropped them all", path.display());
        }
        if !mesh.positions.is_empty() {
            mesh.normals = self.all_normals.then_some(self.normals);
            mesh.uvs = self.all_uvs.then_some(self.uvs);
            // Only if some material reads it: see `keep_second_uvs_where_read`.
            mesh.second_uvs = (self.all_second_uvs && self.all_uvs).then_some(self.second_uvs);
            // Tangents without the normals and uvs they belong to mean nothing.
            let frame = mesh.normals.is_some() && mesh.uvs.is_some();
            mesh.tangents = (self.all_tangents && frame).then_some(self.tangents);
        }
        mesh
    }
}

fn unreadable(at: &str, what: &str) -> String {
    format!("{at}: cannot read {what} (accessor outside its buffer?)")
}

/// gltf's readers assume the types the specification requires, and panic otherwise.
fn check_primitive_types(prim: &gltf::Primitive, at: &str) -> Result<(), String> {
    let attributes = [
        (Semantic::Positions, "POSITION", &[T::F32][..], D::Vec3),
        (Semantic::Normals, "NORMAL", &[T::F32][..], D::Vec3),
        (Semantic::TexCoords(0), "TEXCOORD_0", &[T::F32, T::U8, T::U16][..], D::Vec2),
        (Semantic::TexCoords(1), "TEXCOORD_1", &[T::F32, T::U8, T::U16][..], D::Vec2),
        (Semantic::Tangents, "TANGENT", &[T::F32][..], D::Vec4),
    ];
    for (semantic, name, types, dimensions) in attributes {
        if let Some(a) = prim.get(&semantic) {
            check_accessor(at, name, &a, types, dimensions)?;
        }
    }
    if let Some(a) = prim.indices() {
        check_accessor(at, "indices", &a, &[T::U8, T::U16, T::U32], D::Scalar)?;
    }
    Ok(())
}

/// Refuses an accessor whose component type or shape the specification does not allow for `name`.
fn check_accessor(at: &str, name: &str, a: &gltf::Accessor, types: &[T], dimensions: D) -> Result<(), String> {
    if !types.contains(&a.data_type()) || a.dimensions() != dimensions {
        return Err(format!("{at}: {name} is {:?} {:?}, which glTF does not allow", a.data_type(), a.dimensions()));
    }
    Ok(())
}

/// The primitive's triangles' vertex indices (`None`: not indexed), each checked against
/// its `count` vertices.
fn checked_indices(indices: Option<Vec<u32>>, count: usize, at: &str) -> Result<Vec<u32>, String> {
    let indices = indices.unwrap_or_else(|| (0..count as u32).collect());
    if !indices.len().is_multiple_of(3) {
        return Err(format!("{at}: {} indices is not a whole number of triangles", indices.len()));
    }
    // Checked here, per primitive: once offset, an index past this primitive's
    // vertices could land in the next one and pass the final validation.
    if let Some(&bad) = indices.iter().find(|&&i| i as usize >= count) {
        return Err(format!("{at}: index {bad} but the primitive has only {count} vertices"));
    }
    Ok(indices)
}
