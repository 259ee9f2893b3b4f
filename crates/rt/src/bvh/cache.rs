//! `.rtbvh` (contract 2): a mesh's BVH as the GPU arrays it is uploaded as, so that a
//! render loads it with a read and a copy instead of importing and building again.
//!
//! ```text
//! header (328 bytes, see `Header`): magic b"RTBVH\0\0\0", format version, header size,
//!     BLAKE3 of the source files, of the build parameters, and of the whole file
//!     (with this checksum field zeroed), the node layout's name, the mesh's bounds,
//!     vertex and triangle counts of the source, BvhStats, and the section table
//! sections, each at a 16-byte-aligned offset, zero padding between them:
//!     nodes       GpuWideNode × n      (root first; layout `NODE_LAYOUT`)
//!     triangles   GpuTriangle × m      (leaf order; material index in each)
//!     shading     GpuTriangleShading × m
//!     materials   CachedMaterial × k      (the asset's materials, in its own order; their
//!                 layer textures and tangent kind from version 8 on, the film's weight,
//!                 the bump map correction and two more layer slots from version 9 on,
//!                 the coat's normal map and its scale, transmission and specular-level
//!                 slots, the indices' slot and its minimums, the transmission factor
//!                 and the anisotropy texture's kind from version 11 on, the Mix Shader's
//!                 second material from version 12 on, the holdout share from 13 on)
//!     names       k × (u32 byte length, UTF-8 bytes): the materials' names
//!     textures    CachedTexture × j      (size, wrap modes, colour space, texel range; its
//!                 uv transform from version 10 on, references to one image sharing a range)
//!     texels      u32 × (every image's mip chain, RGBA8, in table order, once each)
//!     tangents    GpuTriangleTangents × m, or none: only a mesh with tangents and a
//!                 normal-mapped material keeps them (version 5 on), or one anisotropic
//!                 along its uv map (version 8 on); each triangle's are of the uv set its
//!                 material's normal map reads (version 7 on; before, always of the first)
//!     second uvs  GpuTriangleUvs × m, or none: only a mesh with a second uv set that
//!                 some material's texture reads keeps it (version 6 on)
//!     programs    per material, u32 length then that many u32s: its compiled shader node
//!                 graph (`asset::node_graph`), length 0 for none (version 12 on)
//!     attributes  GpuTriangleAttribute × m × a: each triangle's a named attributes, one
//!                 after another, or none (version 14 on)
//! ```
//!
//! Textures are decoded and their mips built at pack time, so a render never decodes
//! an image; the source hash covers the image files, so a changed image re-packs the
//! assets that use it, and only those.
//!
//! Materials are in the cache rather than read from the `.gltf`/`.mtl` at load time:
//! an OBJ's material table depends on its faces (the default material it appends), so
//! reading it would mean importing the mesh again. The source hash covers those files,
//! so a changed material makes the cache stale like changed geometry does.
//!
//! Everything in the file is little-endian and written deterministically: the same
//! sources and parameters give the same bytes.

use super::cache_check::check_contents;
use super::cached_material::{CachedMaterial, NO_TEXTURE};
use super::cached_texture::{self, CachedTexture};
use super::mesh_bvh::{BuildQuality, MeshBvh};
use super::node::BvhStats;
use super::wide_node::NODE_LAYOUT;
use crate::asset::{AssetError, AssetFiles, TextureImage};
use crate::layout::{
    GpuTriangle, GpuTriangleAttribute, GpuTriangleShading, GpuTriangleTangents, GpuTriangleUvs, GpuWideNode,
};
use crate::scene::Material;
use crate::scene::lobe::LOBES;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use std::io::Read;
use std::mem::{offset_of, size_of};
use std::path::Path;
use std::time::Duration;

pub const MAGIC: [u8; 8] = *b"RTBVH\0\0\0";
pub const FORMAT_VERSION: u32 = 16;
const ALIGN: u64 = 16;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
struct Section {
    offset: u64,
    bytes: u64,
}

const NODES: usize = 0;
const TRIANGLES: usize = 1;
const SHADING: usize = 2;
const MATERIALS: usize = 3;
const NAMES: usize = 4;
const TEXTURES: usize = 5;
const TEXELS: usize = 6;
const TANGENTS: usize = 7;
const SECOND_UVS: usize = 8;
const PROGRAMS: usize = 9;
const ATTRIBUTES: usize = 10;
const SECTION_COUNT: usize = 11;

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Header {
    magic: [u8; 8],
    version: u32,
    header_bytes: u32,
    source_hash: [u8; 32],
    params_hash: [u8; 32],
    checksum: [u8; 32],
    /// NUL-padded [`NODE_LAYOUT`].
    node_layout: [u8; 32],
    bounds_min: [f32; 3],
    source_vertices: u32,
    bounds_max: [f32; 3],
    source_triangles: u32,
    stats_nodes: u32,
    stats_leaves: u32,
    stats_depth: u32,
    section_count: u32,
    sah_cost: f64,
    sections: [Section; SECTION_COUNT],
}

const HEADER_BYTES: u64 = size_of::<Header>() as u64;

/// What a cache holds: everything a render needs of the asset, without its geometry.
#[derive(Clone, Debug)]
pub struct PackedMesh {
    pub bvh: MeshBvh,
    pub materials: Vec<(String, Material)>,
    /// The images the materials' textures index, with their mips.
    pub textures: Vec<TextureImage>,
    /// Of the source mesh, for `rt info`.
    pub vertex_count: u32,
    pub triangle_count: u32,
}

/// Why a cache cannot be used.
#[derive(Debug)]
pub enum CacheProblem {
    Missing,
    /// Valid, but for other sources or build parameters.
    Stale(String),
    /// Unreadable, truncated, corrupt or from another format version.
    Invalid(String),
}

impl std::fmt::Display for CacheProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CacheProblem::Missing => write!(f, "no cache yet"),
            CacheProblem::Stale(why) => write!(f, "stale: {why}"),
            CacheProblem::Invalid(why) => write!(f, "invalid: {why}"),
        }
    }
}

/// BLAKE3 over the bytes of every source file of the asset, each preceded by its length
/// (and a missing one marked as such), so that no two file sets hash alike.
pub fn source_hash(files: &AssetFiles) -> Result<[u8; 32], AssetError> {
    let mut hasher = blake3::Hasher::new();
    for path in files.source_files()? {
        match crate::files::read(&path) {
            Ok(bytes) => {
                hasher.update(&(bytes.len() as u64).to_le_bytes());
                hasher.update(&bytes);
            }
            Err(e) if e.is_not_found() => {
                hasher.update(&u64::MAX.to_le_bytes());
            }
            // Named after the asset, so that a bad sidecar (an .mtl, a buffer) is traced to it.
            Err(e) if path == files.main => return Err(AssetError::new(&path, e.message())),
            Err(e) => return Err(AssetError::new(&files.main, e.to_string())),
        }
    }
    Ok(*hasher.finalize().as_bytes())
}

/// BLAKE3 of everything besides the sources that decides the cache's bytes.
pub fn params_hash(quality: BuildQuality) -> [u8; 32] {
    let sizes = [
        size_of::<GpuWideNode>(),
        size_of::<GpuTriangle>(),
        size_of::<GpuTriangleShading>(),
        size_of::<GpuTriangleTangents>(),
        size_of::<GpuTriangleUvs>(),
    ];
    // The node programs the cache holds are compiled by these tables.
    let params = format!(
        "rtbvh {FORMAT_VERSION} {NODE_LAYOUT} {quality:?} {sizes:?} {} {} {} {}",
        size_of::<CachedMaterial>(),
        size_of::<CachedTexture>(),
        super::binned_build::BUILDER,
        crate::asset::node_kinds::compiler_signature()
    );
    *blake3::hash(params.as_bytes()).as_bytes()
}

fn align(offset: u64) -> u64 {
    offset.div_ceil(ALIGN) * ALIGN
}

fn encode_names(materials: &[(String, Material)]) -> Vec<u8> {
    let mut out = Vec::new();
    for (name, _) in materials {
        out.extend_from_slice(&(name.len() as u32).to_le_bytes());
        out.extend_from_slice(name.as_bytes());
    }
    out
}

fn encode_programs(materials: &[(String, Material)]) -> Vec<u32> {
    let mut out = Vec::new();
    for (_, m) in materials {
        out.push(m.node_program.len() as u32);
        out.extend_from_slice(&m.node_program);
    }
    out
}

/// `count` programs, each checked as the shader will walk it.
fn decode_programs(mut words: &[u32], count: usize) -> Result<Vec<Vec<u32>>, String> {
    let mut programs = Vec::with_capacity(count);
    for i in 0..count {
        let (&len, rest) = words.split_first().ok_or(format!("node programs: material {i} has none"))?;
        let (program, rest) = rest.split_at_checked(len as usize).ok_or("node programs: one runs past its section")?;
        if !program.is_empty() {
            crate::asset::node_graph::check_program(program)
                .map_err(|e| format!("node program of material {i}: {e}"))?;
        }
        programs.push(program.to_vec());
        words = rest;
    }
    if !words.is_empty() {
        return Err(format!("node programs: {} words after the last material's", words.len()));
    }
    Ok(programs)
}

fn decode_names(mut bytes: &[u8]) -> Result<Vec<String>, String> {
    let mut names = Vec::new();
    while !bytes.is_empty() {
        let (len, rest) = bytes.split_at_checked(4).ok_or("material names: truncated length")?;
        let len = u32::from_le_bytes([len[0], len[1], len[2], len[3]]) as usize;
        let (name, rest) = rest.split_at_checked(len).ok_or("material names: a name runs past its section")?;
        names.push(String::from_utf8(name.to_vec()).map_err(|_| "material names: not UTF-8")?);
        bytes = rest;
    }
    Ok(names)
}

/// The file's bytes. Deterministic: no times, zeroed padding.
pub fn encode(mesh: &PackedMesh, source_hash: [u8; 32], params_hash: [u8; 32]) -> Vec<u8> {
    let materials: Vec<CachedMaterial> = mesh.materials.iter().map(|(_, m)| CachedMaterial::from(m)).collect();
    let names = encode_names(&mesh.materials);
    let (texture_table, texels) = cached_texture::encode(&mesh.textures);
    let programs = encode_programs(&mesh.materials);
    let payloads: [&[u8]; SECTION_COUNT] = [
        bytemuck::cast_slice(&mesh.bvh.nodes),
        bytemuck::cast_slice(&mesh.bvh.triangles),
        bytemuck::cast_slice(&mesh.bvh.shading),
        bytemuck::cast_slice(&materials),
        &names,
        bytemuck::cast_slice(&texture_table),
        bytemuck::cast_slice(&texels),
        bytemuck::cast_slice(&mesh.bvh.tangents),
        bytemuck::cast_slice(&mesh.bvh.second_uvs),
        bytemuck::cast_slice(&programs),
        bytemuck::cast_slice(&mesh.bvh.attributes),
    ];
    let mut sections = [Section::default(); SECTION_COUNT];
    let mut offset = align(HEADER_BYTES);
    for (section, payload) in sections.iter_mut().zip(payloads) {
        *section = Section { offset, bytes: payload.len() as u64 };
        offset = align(offset + payload.len() as u64);
    }
    let mut layout = [0u8; 32];
    layout[..NODE_LAYOUT.len()].copy_from_slice(NODE_LAYOUT.as_bytes());
    let stats = mesh.bvh.stats;
    let mut header = Header {
        magic: MAGIC,
        version: FORMAT_VERSION,
        header_bytes: HEADER_BYTES as u32,
        source_hash,
        params_hash,
        checksum: [0; 32],
        node_layout: layout,
        bounds_min: mesh.bvh.bounds_min.to_array(),
        source_vertices: mesh.vertex_count,
        bounds_max: mesh.bvh.bounds_max.to_array(),
        source_triangles: mesh.triangle_count,
        stats_nodes: stats.nodes as u32,
        stats_leaves: stats.leaves as u32,
        stats_depth: stats.depth as u32,
        section_count: SECTION_COUNT as u32,
        sah_cost: stats.sah_cost,
        sections,
    };
    let mut out = vec![0u8; offset as usize];
    for (section, payload) in sections.iter().zip(payloads) {
        out[section.offset as usize..][..payload.len()].copy_from_slice(payload);
    }
    out[..HEADER_BYTES as usize].copy_from_slice(bytemuck::bytes_of(&header));
    header.checksum = *blake3::hash(&out).as_bytes();
    out[..HEADER_BYTES as usize].copy_from_slice(bytemuck::bytes_of(&header));
    out
}

/// Writes the cache atomically.
pub fn write(path: &Path, mesh: &PackedMesh, source_hash: [u8; 32], params_hash: [u8; 32]) -> Result<(), AssetError> {
    Ok(crate::files::write_atomically(path, &encode(mesh, source_hash, params_hash))?)
}

/// Reads a cache that must match `source_hash` and `params_hash`, and checks every
/// size, offset, link and index before anything of it is used.
pub fn read(path: &Path, source_hash: [u8; 32], params_hash: [u8; 32]) -> Result<PackedMesh, CacheProblem> {
    let invalid = |m: String| CacheProblem::Invalid(m);
    let (header, words) = read_words(path, source_hash, params_hash)?;
    let section = |i: usize| {
        let s = header.sections[i];
        &words[(s.offset / 4) as usize..((s.offset + s.bytes) / 4) as usize]
    };
    let nodes: Vec<GpuWideNode> = bytemuck::cast_slice(section(NODES)).to_vec();
    let triangles: Vec<GpuTriangle> = bytemuck::cast_slice(section(TRIANGLES)).to_vec();
    let shading: Vec<GpuTriangleShading> = bytemuck::cast_slice(section(SHADING)).to_vec();
    let materials: &[CachedMaterial] = bytemuck::cast_slice(section(MATERIALS));
    let names_section = header.sections[NAMES];
    let names_bytes: &[u8] = bytemuck::cast_slice(&words);
    let names =
        decode_names(&names_bytes[names_section.offset as usize..][..names_section.bytes as usize]).map_err(invalid)?;
    let bounds = [header.bounds_min, header.bounds_max];
    // CachedTexture holds u64s: copied out rather than cast in place from u32 words.
    let texture_table: Vec<CachedTexture> =
        bytemuck::pod_collect_to_vec(bytemuck::cast_slice::<u32, u8>(section(TEXTURES)));
    let textures = cached_texture::decode(&texture_table, section(TEXELS)).map_err(invalid)?;
    let tangents: Vec<GpuTriangleTangents> = bytemuck::cast_slice(section(TANGENTS)).to_vec();
    let second_uvs: Vec<GpuTriangleUvs> = bytemuck::cast_slice(section(SECOND_UVS)).to_vec();
    let attributes: Vec<GpuTriangleAttribute> = bytemuck::cast_slice(section(ATTRIBUTES)).to_vec();
    check_triangle_extras(&tangents, &second_uvs, triangles.len()).map_err(invalid)?;
    check_attributes(&attributes, triangles.len()).map_err(invalid)?;
    check_contents(&nodes, &triangles, &shading, materials, names.len(), bounds).map_err(invalid)?;
    check_material_links(materials, textures.len()).map_err(invalid)?;

    let stats = BvhStats {
        nodes: header.stats_nodes as usize,
        leaves: header.stats_leaves as usize,
        depth: header.stats_depth as usize,
        sah_cost: header.sah_cost,
    };
    let bvh = MeshBvh {
        nodes,
        triangles,
        shading,
        tangents,
        second_uvs,
        attributes,
        bounds_min: Vec3::from_array(header.bounds_min),
        bounds_max: Vec3::from_array(header.bounds_max),
        stats,
        build_time: Duration::ZERO,
    };
    let programs = decode_programs(section(PROGRAMS), materials.len()).map_err(invalid)?;
    let materials = names
        .into_iter()
        .zip(materials.iter().map(Material::from))
        .zip(programs)
        .map(|((name, material), node_program)| (name, Material { node_program, ..material }))
        .collect();
    Ok(PackedMesh {
        bvh,
        materials,
        textures,
        vertex_count: header.source_vertices,
        triangle_count: header.source_triangles,
    })
}

/// The cache's header and its whole contents as u32 words, once the header, the hashes
/// it must match and the checksum are checked.
fn read_words(path: &Path, source_hash: [u8; 32], params_hash: [u8; 32]) -> Result<(Header, Vec<u32>), CacheProblem> {
    let invalid = |m: String| CacheProblem::Invalid(m);
    // Reads below stop at this size: the header's sections are checked against it.
    let (mut file, len) = match crate::files::input::open(path) {
        Ok(opened) => opened,
        Err(e) if e.is_not_found() => return Err(CacheProblem::Missing),
        Err(e) => return Err(invalid(e.message())),
    };
    if len < HEADER_BYTES {
        return Err(invalid(format!("truncated: {len} bytes is shorter than the {HEADER_BYTES}-byte header")));
    }
    let mut header_bytes = [0u8; HEADER_BYTES as usize];
    file.read_exact(&mut header_bytes).map_err(|e| invalid(format!("cannot read the header: {e}")))?;
    let header: Header = bytemuck::pod_read_unaligned(&header_bytes);
    check_header(&header, len)?;
    if header.params_hash != params_hash {
        return Err(CacheProblem::Stale("built with other parameters (quality, node layout or rt version)".into()));
    }
    if header.source_hash != source_hash {
        return Err(CacheProblem::Stale("the source files changed since it was packed".into()));
    }

    // The size was checked against the header, so this allocation is what the file holds.
    // u32 words: every GPU struct is 4-byte aligned, so sections cast in place.
    let mut words = vec![0u32; (len / 4) as usize];
    let bytes: &mut [u8] = bytemuck::cast_slice_mut(&mut words);
    bytes[..HEADER_BYTES as usize].copy_from_slice(&header_bytes);
    file.read_exact(&mut bytes[HEADER_BYTES as usize..]).map_err(|e| invalid(format!("cannot read: {e}")))?;
    let checksum_at = offset_of!(Header, checksum);
    bytes[checksum_at..checksum_at + 32].fill(0);
    if *blake3::hash(bytes).as_bytes() != header.checksum {
        return Err(invalid("checksum mismatch: the file is corrupt".into()));
    }
    Ok((header, words))
}

/// Tangents and second uvs, where present, are one per triangle and finite.
fn check_triangle_extras(
    tangents: &[GpuTriangleTangents],
    second_uvs: &[GpuTriangleUvs],
    triangles: usize,
) -> Result<(), String> {
    if !tangents.is_empty() && tangents.len() != triangles {
        return Err(format!("{} triangle tangents for {triangles} triangles", tangents.len()));
    }
    if let Some(i) = tangents.iter().position(|t| ![t.t0, t.t1, t.t2].into_iter().flatten().all(f32::is_finite)) {
        return Err(format!("triangle {i} has a non-finite tangent"));
    }
    if !second_uvs.is_empty() && second_uvs.len() != triangles {
        return Err(format!("{} triangles' second uvs for {triangles} triangles", second_uvs.len()));
    }
    if let Some(i) = second_uvs.iter().position(|t| ![t.uv0, t.uv1, t.uv2].into_iter().flatten().all(f32::is_finite)) {
        return Err(format!("triangle {i} has a non-finite texture coordinate of set 1"));
    }
    Ok(())
}

/// Attributes, where present, are a whole number per triangle, no more than a mesh
/// carries, and finite.
fn check_attributes(attributes: &[GpuTriangleAttribute], triangles: usize) -> Result<(), String> {
    let whole = triangles > 0 && attributes.len().is_multiple_of(triangles);
    if !attributes.is_empty() && (!whole || attributes.len() / triangles > crate::asset::rtmesh::MAX_ATTRIBUTES) {
        return Err(format!("{} triangle attributes for {triangles} triangles", attributes.len()));
    }
    if let Some(i) = attributes.iter().position(|t| ![t.a0, t.a1, t.a2].into_iter().flatten().all(f32::is_finite)) {
        return Err(format!("triangle attribute {i} is not finite"));
    }
    Ok(())
}

/// Every texture and mix material a material names exists, and its tangent kind is known.
fn check_material_links(materials: &[CachedMaterial], textures: usize) -> Result<(), String> {
    if let Some((i, t)) =
        materials.iter().enumerate().find_map(|(i, m)| m.textures().find(|&t| t as usize >= textures).map(|t| (i, t)))
    {
        return Err(format!("material {i} uses texture {t} of {textures}"));
    }
    if let Some(i) =
        materials.iter().position(|m| m.mix_material != NO_TEXTURE && m.mix_material as usize >= materials.len())
    {
        return Err(format!("material {i} mixes with material {} of {}", materials[i].mix_material, materials.len()));
    }
    if let Some(i) = materials.iter().position(|m| !m.tangent_known()) {
        return Err(format!("material {i} has an unknown tangent kind"));
    }
    if let Some(i) = materials.iter().position(|m| !m.lobe_known()) {
        return Err(format!("material {i} names lobe module {} of {}", materials[i].lobe_module, LOBES.len()));
    }
    Ok(())
}

/// Magic, version, layout and a section table that tiles the file exactly.
fn check_header(header: &Header, len: u64) -> Result<(), CacheProblem> {
    let invalid = |m: String| Err(CacheProblem::Invalid(m));
    if header.magic != MAGIC {
        return invalid("not an .rtbvh file (bad magic bytes)".into());
    }
    if header.version != FORMAT_VERSION {
        return invalid(format!("format version {} (this rt writes version {FORMAT_VERSION})", header.version));
    }
    if header.header_bytes as u64 != HEADER_BYTES || header.section_count as usize != SECTION_COUNT {
        return invalid(format!("header of {} bytes with {} sections", header.header_bytes, header.section_count));
    }
    let layout_len = header.node_layout.iter().position(|&b| b == 0).unwrap_or(32);
    if &header.node_layout[..layout_len] != NODE_LAYOUT.as_bytes() {
        let found = String::from_utf8_lossy(&header.node_layout[..layout_len]);
        return Err(CacheProblem::Stale(format!("node layout `{found}`, not `{NODE_LAYOUT}`")));
    }
    let element_sizes = [
        size_of::<GpuWideNode>(),
        size_of::<GpuTriangle>(),
        size_of::<GpuTriangleShading>(),
        size_of::<CachedMaterial>(),
        1,
        size_of::<CachedTexture>(),
        4,
        size_of::<GpuTriangleTangents>(),
        size_of::<GpuTriangleUvs>(),
        4,
    ];
    let mut end = align(HEADER_BYTES);
    for (i, (s, size)) in header.sections.iter().zip(element_sizes).enumerate() {
        let Some(section_end) = s.offset.checked_add(s.bytes) else {
            return invalid(format!("section {i} ends past 2^64 bytes"));
        };
        if section_end > len {
            return invalid(format!("truncated: section {i} ends at byte {section_end} but the file has {len}"));
        }
        if s.offset != end || s.bytes % size as u64 != 0 {
            return invalid(format!("section {i} (offset {}, {} bytes) is misplaced or misaligned", s.offset, s.bytes));
        }
        end = align(section_end);
    }
    if end != len {
        return invalid(format!("the sections end at byte {end} but the file has {len} (truncated or corrupt)"));
    }
    Ok(())
}
