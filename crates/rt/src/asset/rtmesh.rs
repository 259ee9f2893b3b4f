//! `.rtmesh` (contract 1): the exporter's vertex/index binary.
//!
//! ```text
//! bytes 0..8   magic b"RTMESH\0\0"
//! u32 version (=4) · u32 flags (bit0 normals, bit1 uvs, bit2 tangents, bit3 second uvs, bits 4-7 attribute count) · u32 vertex_count · u32 triangle_count
//! f32[3] × vertex_count     positions (object space, metres, Y up)
//! f32[3] × vertex_count     normals            (if bit0)
//! f32[2] × vertex_count     uvs                (if bit1)
//! f32[4] × vertex_count     tangents           (if bit2: xyz MikkTSpace tangent, w bitangent sign ±1)
//! f32[2] × vertex_count     second uvs         (if bit3, with bit1: glTF TEXCOORD_1, Blender's second uv map)
//! f32[4] × vertex_count     attribute k        (for k below the attribute count: a named mesh attribute
//!                                              the materials' Attribute and Color Attribute nodes read,
//!                                              as Cycles reads it: a colour's linear RGBA, a vector's
//!                                              xyz, a value in x; the exporter numbers them)
//! u32[3] × triangle_count   indices
//! u32    × triangle_count   material index into the sibling .gltf's `materials` array
//! ```
//!
//! Version 1 files (no tangents flag), version 2 files (no second uvs flag) and version 3
//! files (no attributes) are still read.
//!
//! Little-endian, no padding. Sections are copied with bytemuck, which reads them as
//! the host's byte order: rt runs on little-endian machines only (as wgpu's GPUs do).

use super::{AssetError, MeshData};
use std::path::Path;

pub const MAGIC: [u8; 8] = *b"RTMESH\0\0";
pub const VERSION: u32 = 4;
/// The oldest version this rt reads: version 1 differs only in having no tangents,
/// version 2 in having no second uvs, version 3 in having no attributes.
const OLDEST_VERSION: u32 = 1;
const HEADER_BYTES: u64 = 24;
const FLAG_NORMALS: u32 = 1;
const FLAG_UVS: u32 = 2;
const FLAG_TANGENTS: u32 = 4;
const FLAG_SECOND_UVS: u32 = 8;
/// Bits 4-7 of the flags: how many attributes follow the second uvs.
const ATTRIBUTE_COUNT_SHIFT: u32 = 4;
const ATTRIBUTE_COUNT_MASK: u32 = 0xf << ATTRIBUTE_COUNT_SHIFT;
/// The most attributes an `.rtmesh` carries.
pub const MAX_ATTRIBUTES: usize = 15;

/// Geometry read from a `.rtmesh`: everything but the materials, which live in the
/// sibling `.gltf`.
pub struct RtMesh {
    pub positions: Vec<[f32; 3]>,
    pub normals: Option<Vec<[f32; 3]>>,
    pub uvs: Option<Vec<[f32; 2]>>,
    pub tangents: Option<Vec<[f32; 4]>>,
    pub second_uvs: Option<Vec<[f32; 2]>>,
    pub attributes: Vec<Vec<[f32; 4]>>,
    pub indices: Vec<[u32; 3]>,
    pub material_ids: Vec<u32>,
}

fn attribute_count(flags: u32) -> u32 {
    (flags & ATTRIBUTE_COUNT_MASK) >> ATTRIBUTE_COUNT_SHIFT
}

/// The size a header implies, in u64 so that no count can overflow it.
fn implied_size(flags: u32, vertices: u32, triangles: u32) -> u64 {
    let bytes_if = |flag: u32, bytes: u64| if flags & flag != 0 { bytes } else { 0 };
    let per_vertex = 12
        + bytes_if(FLAG_NORMALS, 12)
        + bytes_if(FLAG_UVS, 8)
        + bytes_if(FLAG_TANGENTS, 16)
        + bytes_if(FLAG_SECOND_UVS, 8)
        + 16 * attribute_count(flags) as u64;
    HEADER_BYTES + per_vertex * vertices as u64 + 16 * triangles as u64
}

fn u32_at(bytes: &[u8], offset: usize) -> u32 {
    u32::from_le_bytes([bytes[offset], bytes[offset + 1], bytes[offset + 2], bytes[offset + 3]])
}

/// Parses and checks the structure of a `.rtmesh`: header, exact size, flags.
/// Ranges of indices and finiteness are [`MeshData::validate`]'s job, once the
/// materials are known.
pub fn parse(path: &Path, bytes: &[u8]) -> Result<RtMesh, AssetError> {
    let fail = |message: String| Err(AssetError::new(path, message));
    if bytes.len() < HEADER_BYTES as usize {
        return fail(format!("truncated: {} bytes is shorter than the 24-byte .rtmesh header", bytes.len()));
    }
    if bytes[..8] != MAGIC {
        return fail("not an .rtmesh file (bad magic bytes)".into());
    }
    let [version, flags, vertex_count, triangle_count] = [8, 12, 16, 20].map(|o| u32_at(bytes, o));
    if !(OLDEST_VERSION..=VERSION).contains(&version) {
        return fail(format!(
            "unsupported .rtmesh version {version} (this rt reads versions {OLDEST_VERSION} to {VERSION})"
        ));
    }
    let known = match version {
        1 => FLAG_NORMALS | FLAG_UVS,
        2 => FLAG_NORMALS | FLAG_UVS | FLAG_TANGENTS,
        3 => FLAG_NORMALS | FLAG_UVS | FLAG_TANGENTS | FLAG_SECOND_UVS,
        _ => FLAG_NORMALS | FLAG_UVS | FLAG_TANGENTS | FLAG_SECOND_UVS | ATTRIBUTE_COUNT_MASK,
    };
    if flags & !known != 0 {
        return fail(format!(
            "unknown flags {flags:#x} for version {version} (known: bit 0 normals, bit 1 uvs, bit 2 tangents \
             from version 2, bit 3 second uvs from version 3, bits 4-7 attributes from version 4)"
        ));
    }
    if flags & FLAG_SECOND_UVS != 0 && flags & FLAG_UVS == 0 {
        return fail(format!("flags {flags:#x}: second uvs (bit 3) without uvs (bit 1)"));
    }
    // Checked before anything is allocated: a header cannot make rt reserve memory the
    // file does not back.
    let expected = implied_size(flags, vertex_count, triangle_count);
    if bytes.len() as u64 != expected {
        return fail(format!(
            "size is {} bytes but its header ({vertex_count} vertices, {triangle_count} triangles, flags {flags:#x}) \
             implies {expected} (truncated or corrupt)",
            bytes.len()
        ));
    }

    let mut rest = &bytes[HEADER_BYTES as usize..];
    let mut take = |len: usize| {
        let (section, tail) = rest.split_at(len);
        rest = tail;
        section
    };
    let (v, t) = (vertex_count as usize, triangle_count as usize);
    let positions = bytemuck::pod_collect_to_vec(take(12 * v));
    let normals = (flags & FLAG_NORMALS != 0).then(|| bytemuck::pod_collect_to_vec(take(12 * v)));
    let uvs = (flags & FLAG_UVS != 0).then(|| bytemuck::pod_collect_to_vec(take(8 * v)));
    let tangents = (flags & FLAG_TANGENTS != 0).then(|| bytemuck::pod_collect_to_vec(take(16 * v)));
    let second_uvs = (flags & FLAG_SECOND_UVS != 0).then(|| bytemuck::pod_collect_to_vec(take(8 * v)));
    let attributes = (0..attribute_count(flags)).map(|_| bytemuck::pod_collect_to_vec(take(16 * v))).collect();
    let indices = bytemuck::pod_collect_to_vec(take(12 * t));
    let material_ids = bytemuck::pod_collect_to_vec(take(4 * t));
    Ok(RtMesh { positions, normals, uvs, tangents, second_uvs, attributes, indices, material_ids })
}

/// Reads a `.rtmesh` file's geometry; see [`parse`].
pub fn read(path: &Path) -> Result<RtMesh, AssetError> {
    let bytes = crate::files::read(path).map_err(|e| AssetError::new(path, e.message()))?;
    parse(path, &bytes)
}

/// The bytes of `mesh`'s geometry as a `.rtmesh`.
pub fn encode(mesh: &MeshData) -> Vec<u8> {
    let flags = mesh.normals.as_ref().map_or(0, |_| FLAG_NORMALS)
        | mesh.uvs.as_ref().map_or(0, |_| FLAG_UVS)
        | mesh.tangents.as_ref().map_or(0, |_| FLAG_TANGENTS)
        | mesh.second_uvs.as_ref().filter(|_| mesh.uvs.is_some()).map_or(0, |_| FLAG_SECOND_UVS)
        | (mesh.attributes.len() as u32) << ATTRIBUTE_COUNT_SHIFT;
    let (v, t) = (mesh.positions.len() as u32, mesh.indices.len() as u32);
    let mut out = Vec::with_capacity(implied_size(flags, v, t) as usize);
    out.extend_from_slice(&MAGIC);
    for word in [VERSION, flags, v, t] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(bytemuck::cast_slice(&mesh.positions));
    if let Some(normals) = &mesh.normals {
        out.extend_from_slice(bytemuck::cast_slice(normals));
    }
    if let Some(uvs) = &mesh.uvs {
        out.extend_from_slice(bytemuck::cast_slice(uvs));
    }
    if let Some(tangents) = &mesh.tangents {
        out.extend_from_slice(bytemuck::cast_slice(tangents));
    }
    if let (Some(second_uvs), Some(_)) = (&mesh.second_uvs, &mesh.uvs) {
        out.extend_from_slice(bytemuck::cast_slice(second_uvs));
    }
    for attribute in &mesh.attributes {
        out.extend_from_slice(bytemuck::cast_slice(attribute));
    }
    out.extend_from_slice(bytemuck::cast_slice(&mesh.indices));
    out.extend_from_slice(bytemuck::cast_slice(&mesh.material_ids));
    out
}

/// Writes `mesh`'s geometry (not its materials) as a `.rtmesh`, atomically.
pub fn write(path: &Path, mesh: &MeshData) -> Result<(), AssetError> {
    if u32::try_from(mesh.positions.len()).is_err() || u32::try_from(mesh.indices.len()).is_err() {
        return Err(AssetError::new(path, "more than 2^32 vertices or triangles do not fit an .rtmesh"));
    }
    if mesh.attributes.len() > MAX_ATTRIBUTES {
        return Err(AssetError::new(path, format!("more than {MAX_ATTRIBUTES} attributes do not fit an .rtmesh")));
    }
    Ok(crate::files::write_atomically(path, &encode(mesh))?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Material;

    fn quad() -> MeshData {
        MeshData {
            positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
            normals: Some(vec![[0.0, 0.0, 1.0]; 4]),
            uvs: Some(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]),
            tangents: Some(vec![[1.0, 0.0, 0.0, -1.0]; 4]),
            second_uvs: Some(vec![[0.5, 0.0], [1.0, 0.5], [0.5, 1.0], [0.0, 0.5]]),
            second_tangents: None,
            attributes: vec![vec![[0.25, 0.5, 1.0, 0.5]; 4], vec![[2.0, 0.0, 0.0, 1.0]; 4]],
            indices: vec![[0, 1, 2], [0, 2, 3]],
            material_ids: vec![0, 1],
            materials: vec![("a".into(), Material::default()), ("b".into(), Material::default())],
            textures: Vec::new(),
        }
    }

    fn error(bytes: &[u8]) -> String {
        parse(Path::new("m.rtmesh"), bytes).err().expect("invalid").to_string()
    }

    #[test]
    fn round_trips_every_section() {
        let mesh = quad();
        let bytes = encode(&mesh);
        assert_eq!(bytes.len(), 24 + 4 * (56 + 2 * 16) + 2 * 16);
        let back = parse(Path::new("m.rtmesh"), &bytes).expect("parses");
        assert_eq!(back.positions, mesh.positions);
        assert_eq!(back.normals, mesh.normals);
        assert_eq!(back.uvs, mesh.uvs);
        assert_eq!(back.tangents, mesh.tangents);
        assert_eq!(back.second_uvs, mesh.second_uvs);
        assert_eq!(back.attributes, mesh.attributes);
        assert_eq!(back.indices, mesh.indices);
        assert_eq!(back.material_ids, mesh.material_ids);

        let bare =
            MeshData { normals: None, uvs: None, tangents: None, second_uvs: None, attributes: Vec::new(), ..quad() };
        let back = parse(Path::new("m.rtmesh"), &encode(&bare)).expect("parses");
        assert!(back.normals.is_none() && back.uvs.is_none() && back.tangents.is_none());
        assert!(back.second_uvs.is_none() && back.attributes.is_empty());
        assert_eq!(back.indices, bare.indices);
    }

    #[test]
    fn header_that_lies_about_its_size_is_refused() {
        let mut bytes = encode(&quad());
        bytes.pop();
        assert!(error(&bytes).contains("implies"), "{}", error(&bytes));

        // Four billion vertices claimed by a 100-byte file: refused on the size alone.
        let mut bytes = vec![0u8; 100];
        bytes[..8].copy_from_slice(&MAGIC);
        bytes[8..12].copy_from_slice(&1u32.to_le_bytes());
        bytes[16..20].copy_from_slice(&4_000_000_000u32.to_le_bytes());
        let message = error(&bytes);
        assert!(message.starts_with("m.rtmesh: size is 100 bytes"), "{message}");
        assert!(message.contains("4000000000 vertices"), "{message}");
    }

    #[test]
    fn bad_magic_version_and_flags_are_named() {
        assert!(error(b"short").contains("truncated"));
        let good = encode(&quad());
        let mut bytes = good.clone();
        bytes[0] = b'X';
        assert!(error(&bytes).contains("bad magic"));
        let mut bytes = good.clone();
        bytes[8] = 5;
        assert!(error(&bytes).contains("unsupported .rtmesh version 5"));
        let mut bytes = good.clone();
        bytes[13] = 1;
        assert!(error(&bytes).contains("unknown flags 0x12f"), "{}", error(&bytes));
        let mut bytes = good;
        bytes[12] = 8 | 1;
        assert!(error(&bytes).contains("second uvs (bit 3) without uvs"), "{}", error(&bytes));
    }

    /// The exporter writes the version this rt writes, and carries no more attributes than
    /// a file holds (both are written in Python too).
    #[test]
    fn the_exporter_writes_this_version_and_attribute_limit() {
        let export = include_str!("../../../../blender/rt_blender/rt_export.py");
        assert!(export.contains(&format!("\nRTMESH_VERSION = {VERSION}\n")), "rt_export.py's RTMESH_VERSION");
        assert!(export.contains(&format!("\nRTINST_VERSION = {}\n", super::super::rtinst::VERSION)));
        let attributes = include_str!("../../../../blender/rt_blender/rt_attributes.py");
        assert!(attributes.contains(&format!("\nMAX_ATTRIBUTES = {MAX_ATTRIBUTES}\n")), "rt_attributes.py");
    }

    /// A version 1 file: the header says 1 and there is no tangents section.
    fn version_1(mesh: &MeshData) -> Vec<u8> {
        let mut bytes = encode(&MeshData { tangents: None, second_uvs: None, attributes: Vec::new(), ..mesh.clone() });
        bytes[8..12].copy_from_slice(&1u32.to_le_bytes());
        bytes
    }

    #[test]
    fn version_3_files_are_still_read() {
        let mesh = quad();
        let mut bytes = encode(&MeshData { attributes: Vec::new(), ..mesh.clone() });
        bytes[8..12].copy_from_slice(&3u32.to_le_bytes());
        let back = parse(Path::new("m.rtmesh"), &bytes).expect("version 3 parses");
        assert_eq!((back.second_uvs, back.attributes), (mesh.second_uvs.clone(), Vec::new()));

        // Bits 4-7 meant nothing in version 3.
        bytes[12] |= 0x10;
        assert!(error(&bytes).contains("unknown flags 0x1f for version 3"), "{}", error(&bytes));
    }

    #[test]
    fn version_2_files_are_still_read() {
        let mesh = quad();
        let mut bytes = encode(&MeshData { second_uvs: None, attributes: Vec::new(), ..mesh.clone() });
        bytes[8..12].copy_from_slice(&2u32.to_le_bytes());
        let back = parse(Path::new("m.rtmesh"), &bytes).expect("version 2 parses");
        assert_eq!((back.tangents, back.second_uvs), (mesh.tangents.clone(), None));

        // Bit 3 meant nothing in version 2.
        bytes[12] |= 8;
        assert!(error(&bytes).contains("unknown flags 0xf for version 2"), "{}", error(&bytes));
    }

    #[test]
    fn version_1_files_are_still_read() {
        let mesh = quad();
        let back = parse(Path::new("m.rtmesh"), &version_1(&mesh)).expect("version 1 parses");
        assert_eq!((back.normals, back.uvs, back.tangents), (mesh.normals.clone(), mesh.uvs.clone(), None));
        assert_eq!(back.indices, mesh.indices);

        // Bit 2 meant nothing in version 1.
        let mut bytes = version_1(&mesh);
        bytes[12] |= 4;
        assert!(error(&bytes).contains("unknown flags 0x7 for version 1"), "{}", error(&bytes));
    }
}
