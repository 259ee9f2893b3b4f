//! `.rtinst`: an instance table, the placements of one asset (the exporter's, or any
//! program's that scatters things by the million).
//!
//! ```text
//! bytes 0..8   magic b"RTINST\0\0"
//! u32 version (=5) · u32 instance_count · u32 slot_count · u32 set_count · u32 motion_keys
//! · u32 object_info
//! set_count × slot_count × u32   material sets: for each slot (the material index that
//!                                the asset's triangles carry), an index into the asset's
//!                                own materials (its `.gltf` `materials`)
//! instance_count × {
//!     f32[12]  object-to-world matrix, the top three rows of a 4×4, row-major
//!              (metres, Y up; the fourth row is [0, 0, 0, 1])
//!     u32      material: 0xFFFF_FFFF (OWN_MATERIALS) for the asset's own materials;
//!              MATERIAL_SET | k for material set k of this file; otherwise an index into
//!              the scene entry's `materials` list, which replaces all the asset's
//! }
//! instance_count × motion_keys × f32[12]   motion blur: each instance's matrices at
//!              evenly spaced times from the shutter's opening to its closing (as the
//!              scene file's `motion`), the instances in order; motion_keys is 0 (none)
//!              or 2 to 129
//! object_info (0 or 1) × instance_count × {
//!     f32      Object Info's Random, in [0, 1]
//!     f32[4]   Object Info's Color and Alpha
//!     u32      Object Info's Object Index (Blender's Pass Index), at most 32767
//! }            (without them, every instance has its scene entry's `random`,
//!              `object_color` and `object_index`)
//! ```
//!
//! Little-endian, no padding: 32 + 4 × slot_count × set_count + (52 + 48 × motion_keys +
//! 24 × object_info) × instance_count bytes exactly. Version 4 files (each instance's info
//! 20 bytes, without the Object Index: 0) are read too, as are version 3 files (a 28-byte header
//! without object_info), version 2 files (24 bytes, without motion_keys either) and version
//! 1 files (a 16-byte header: magic, version, instance_count; no sets) are read too. The size is checked against the header before anything is allocated,
//! and every matrix must be finite and invertible (an error names the file and the
//! instance's index).

use super::AssetError;
use crate::scene::ObjectInfo;
use bytemuck::{Pod, Zeroable};
use glam::{Mat3, Mat4, Vec3, Vec4};
use std::path::Path;

pub const MAGIC: [u8; 8] = *b"RTINST\0\0";
pub const VERSION: u32 = 5;
/// The header of versions 4 and 5; version 3's is 28 bytes (no object_info), version 2's 24 (no
/// motion_keys), version 1's 16 (no slot and set counts either).
pub const HEADER_BYTES: u64 = 32;
const HEADER_BYTES_V3: u64 = 28;
const HEADER_BYTES_V2: u64 = 24;
const HEADER_BYTES_V1: u64 = 16;
pub const RECORD_BYTES: u64 = 52;
/// One motion key: the top three rows of a matrix.
const KEY_BYTES: u64 = 48;
/// One instance's Object Info: Random, Color (RGBA) and Object Index; version 4's has no index.
const INFO_BYTES: u64 = 24;
const INFO_BYTES_V4: u64 = 20;
/// The material of an instance that keeps its asset's own materials.
pub const OWN_MATERIALS: u32 = u32::MAX;
/// Marks a record's material as `MATERIAL_SET | k`: material set `k` of its file.
pub const MATERIAL_SET: u32 = 0x8000_0000;

/// The material sets of an instance file: each maps the asset's material slots to
/// materials of the asset's own (a Blender object that shows a mesh with other
/// materials), so that one asset serves every instance whatever materials it shows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MaterialSets {
    slot_count: u32,
    /// `set_count × slot_count` indices into the asset's materials.
    indices: Vec<u32>,
}

impl MaterialSets {
    /// Sets of `slot_count` entries each; `None` when one has another length.
    pub fn new(slot_count: u32, sets: &[Vec<u32>]) -> Option<Self> {
        if sets.iter().any(|s| s.len() != slot_count as usize) {
            return None;
        }
        Some(Self { slot_count, indices: sets.concat() })
    }

    pub fn slot_count(&self) -> u32 {
        self.slot_count
    }

    pub fn len(&self) -> usize {
        self.indices.len().checked_div(self.slot_count as usize).unwrap_or(0)
    }

    pub fn is_empty(&self) -> bool {
        self.indices.is_empty()
    }

    /// Set `k`: the asset material shown by each slot.
    pub fn get(&self, k: u32) -> Option<&[u32]> {
        let n = self.slot_count as usize;
        let start = (k as usize).checked_mul(n)?;
        self.indices.get(start..start.checked_add(n)?)
    }
}

/// An instance file's contents.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InstanceFile {
    pub records: Vec<InstanceRecord>,
    pub material_sets: MaterialSets,
    /// Motion blur: `motion_keys` matrices per instance (0: none), each as a record's rows.
    pub motion_keys: u32,
    pub motion: Vec<[f32; 12]>,
    /// Each instance's Object Info, or none (the scene entry's for all).
    pub info: Vec<ObjectInfo>,
}

impl InstanceFile {
    /// Instance `index`'s motion over the shutter, if the file has motion.
    pub fn motion_of(&self, index: usize) -> Option<crate::scene::Motion> {
        let k = self.motion_keys as usize;
        let keys = self.motion.get(index * k..(index + 1) * k).filter(|_| k > 0)?;
        Some(crate::scene::Motion::new(
            keys.iter().map(|rows| InstanceRecord { rows: *rows, material: 0 }.object_to_world()).collect(),
        ))
    }
}

/// One instance as the file stores it.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct InstanceRecord {
    /// Rows 0..3 of the object-to-world matrix, row-major.
    pub rows: [f32; 12],
    /// Index into the scene entry's `materials`, or [`OWN_MATERIALS`].
    pub material: u32,
}

impl InstanceRecord {
    pub fn new(object_to_world: &Mat4, material: u32) -> Self {
        let t = object_to_world.transpose();
        let mut rows = [0.0; 12];
        rows[0..4].copy_from_slice(&t.x_axis.to_array());
        rows[4..8].copy_from_slice(&t.y_axis.to_array());
        rows[8..12].copy_from_slice(&t.z_axis.to_array());
        Self { rows, material }
    }

    pub fn object_to_world(&self) -> Mat4 {
        let r = &self.rows;
        Mat4::from_cols_array(&[
            r[0], r[4], r[8], 0.0, //
            r[1], r[5], r[9], 0.0, //
            r[2], r[6], r[10], 0.0, //
            r[3], r[7], r[11], 1.0,
        ])
    }
}

/// What is wrong with a matrix, if anything: not finite, or (nearly) singular.
///
/// Singular is judged relative to the largest determinant columns of these lengths can
/// have (as the scene file's `matrix` is), so a uniform millimetre scale passes and a
/// flattened one does not.
pub fn matrix_problem(m: &Mat4) -> Option<&'static str> {
    if !m.is_finite() {
        return Some("is not finite");
    }
    let [a, b, c]: [Vec3; 3] = [m.x_axis, m.y_axis, m.z_axis].map(Vec4::truncate);
    let det = Mat3::from_cols(a, b, c).determinant().abs();
    let bound = 1e-6 * a.length() * b.length() * c.length();
    // Finite entries can still overflow these products: such a matrix is refused too.
    if !det.is_finite() || !bound.is_finite() || det <= bound {
        return Some("is singular (not invertible)");
    }
    None
}

fn u32_at(bytes: &[u8], offset: usize) -> u32 {
    u32::from_le_bytes([bytes[offset], bytes[offset + 1], bytes[offset + 2], bytes[offset + 3]])
}

/// Parses and checks a `.rtinst`: header, exact size, and every matrix. Material
/// indices are checked by whoever knows the scene's `materials` list and the asset's.
pub fn parse(path: &Path, bytes: &[u8]) -> Result<InstanceFile, AssetError> {
    let fail = |message: String| Err(AssetError::new(path, message));
    if bytes.len() < HEADER_BYTES_V1 as usize {
        return fail(format!("truncated: {} bytes is shorter than the 16-byte .rtinst header", bytes.len()));
    }
    if bytes[..8] != MAGIC {
        return fail("not an .rtinst file (bad magic bytes)".into());
    }
    let [version, count] = [8, 12].map(|o| u32_at(bytes, o));
    let header = match version {
        1 => HEADER_BYTES_V1,
        2 => HEADER_BYTES_V2,
        3 => HEADER_BYTES_V3,
        4 | VERSION => HEADER_BYTES,
        _ => return fail(format!("unsupported .rtinst version {version} (this rt reads versions 1 to {VERSION})")),
    };
    if bytes.len() < header as usize {
        return fail(format!("truncated: {} bytes is shorter than the {header}-byte .rtinst header", bytes.len()));
    }
    let word = |offset: u64| if offset < header { u32_at(bytes, offset as usize) } else { 0 };
    let (slot_count, set_count, motion_keys, object_info) = (word(16), word(20), word(24), word(28));
    if motion_keys == 1 || motion_keys as usize > crate::scene::MAX_MOTION_KEYS {
        let most = crate::scene::MAX_MOTION_KEYS;
        return fail(format!("motion_keys must be 0 (no motion) or 2 to {most}, got {motion_keys}"));
    }
    if object_info > 1 {
        return fail(format!("object_info must be 0 (none) or 1 (each instance's), got {object_info}"));
    }
    // Checked before anything is allocated: a header cannot make rt reserve memory the
    // file does not back (in u128: the counts' product can pass u64).
    let set_bytes = 4 * slot_count as u128 * set_count as u128;
    let info_bytes = if version == VERSION { INFO_BYTES } else { INFO_BYTES_V4 };
    let record_bytes = (RECORD_BYTES + KEY_BYTES * motion_keys as u64 + info_bytes * object_info as u64) as u128;
    let expected = header as u128 + set_bytes + record_bytes * count as u128;
    if bytes.len() as u128 != expected {
        return fail(format!(
            "size is {} bytes but its header ({count} instances, {set_count} material sets of {slot_count} slots, \
             {motion_keys} motion keys, object info {object_info}) implies {expected} (truncated or corrupt)",
            bytes.len()
        ));
    }
    let records_at = header as usize + set_bytes as usize;
    let motion_at = records_at + RECORD_BYTES as usize * count as usize;
    let info_at = motion_at + (KEY_BYTES * motion_keys as u64) as usize * count as usize;
    let indices: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes[header as usize..records_at]);
    let records: Vec<InstanceRecord> = bytemuck::pod_collect_to_vec(&bytes[records_at..motion_at]);
    let motion: Vec<[f32; 12]> = bytemuck::pod_collect_to_vec(&bytes[motion_at..info_at]);
    let words: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes[info_at..]);
    let info = object_infos(&words, info_bytes as usize / 4).map_err(|m| AssetError::new(path, m))?;
    for (index, r) in records.iter().enumerate() {
        if let Some(problem) = matrix_problem(&r.object_to_world()) {
            return fail(format!("instance {index}: its matrix {problem}: {:?}", r.rows));
        }
    }
    for (i, rows) in motion.iter().enumerate() {
        let key = InstanceRecord { rows: *rows, material: 0 };
        if let Some(problem) = matrix_problem(&key.object_to_world()) {
            let (index, k) = (i / motion_keys as usize, i % motion_keys as usize);
            return fail(format!("instance {index}: its motion key {k} {problem}: {rows:?}"));
        }
    }
    Ok(InstanceFile { records, material_sets: MaterialSets { slot_count, indices }, motion_keys, motion, info })
}

/// The instances' Object Info from (random, r, g, b, a[, object index]) each, `stride` words
/// a record, checked.
fn object_infos(words: &[u32], stride: usize) -> Result<Vec<ObjectInfo>, String> {
    let mut infos = Vec::with_capacity(words.len() / stride);
    for (index, w) in words.chunks_exact(stride).enumerate() {
        let f = w[..5].iter().map(|&b| f32::from_bits(b)).collect::<Vec<_>>();
        if !f.iter().all(|v| v.is_finite()) || !(0.0..=1.0).contains(&f[0]) {
            return Err(format!(
                "instance {index}: its object info {f:?} is not a random in [0, 1] and a finite colour"
            ));
        }
        let object_index = w.get(5).copied().unwrap_or(0);
        if object_index > crate::scene::MAX_OBJECT_INDEX {
            let most = crate::scene::MAX_OBJECT_INDEX;
            return Err(format!("instance {index}: its object index {object_index} is above {most}"));
        }
        infos.push(ObjectInfo { random: f[0], color: [f[1], f[2], f[3], f[4]], index: object_index });
    }
    Ok(infos)
}

/// Reads a `.rtinst` file; see [`parse`].
pub fn read(path: &Path) -> Result<InstanceFile, AssetError> {
    let bytes = crate::files::read(path).map_err(|e| AssetError::new(path, e.message()))?;
    parse(path, &bytes)
}

/// The bytes of `records` with `sets` as a `.rtinst`, without motion.
pub fn encode(records: &[InstanceRecord], sets: &MaterialSets) -> Vec<u8> {
    encode_moving(records, sets, 0, &[])
}

/// The bytes of `records` with `sets` and `motion_keys` matrices of `motion` per record
/// (record after record; see the format above) as a `.rtinst`.
pub fn encode_moving(
    records: &[InstanceRecord],
    sets: &MaterialSets,
    motion_keys: u32,
    motion: &[[f32; 12]],
) -> Vec<u8> {
    encode_file(&InstanceFile {
        records: records.to_vec(),
        material_sets: sets.clone(),
        motion_keys,
        motion: motion.to_vec(),
        info: Vec::new(),
    })
}

/// The bytes of `file` as a `.rtinst` (its `info` empty or one per record).
pub fn encode_file(file: &InstanceFile) -> Vec<u8> {
    let sets = &file.material_sets;
    let info: Vec<[u32; 6]> = file
        .info
        .iter()
        .map(|i| [i.random, i.color[0], i.color[1], i.color[2], i.color[3]].map(f32::to_bits))
        .zip(&file.info)
        .map(|(f, i)| [f[0], f[1], f[2], f[3], f[4], i.index])
        .collect();
    let mut out = Vec::with_capacity(
        HEADER_BYTES as usize
            + 4 * sets.indices.len()
            + size_of_val(file.records.as_slice())
            + KEY_BYTES as usize * file.motion.len()
            + INFO_BYTES as usize * info.len(),
    );
    out.extend_from_slice(&MAGIC);
    let count = file.records.len() as u32;
    for word in [VERSION, count, sets.slot_count, sets.len() as u32, file.motion_keys, u32::from(!info.is_empty())] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(bytemuck::cast_slice(&sets.indices));
    out.extend_from_slice(bytemuck::cast_slice(&file.records));
    out.extend_from_slice(bytemuck::cast_slice(&file.motion));
    out.extend_from_slice(bytemuck::cast_slice(&info));
    out
}

/// Writes `records` with `sets` as a `.rtinst`, atomically.
pub fn write(path: &Path, records: &[InstanceRecord], sets: &MaterialSets) -> Result<(), AssetError> {
    if u32::try_from(records.len()).is_err() {
        return Err(AssetError::new(path, "more than 2^32 instances do not fit an .rtinst"));
    }
    Ok(crate::files::write_atomically(path, &encode(records, sets))?)
}

#[cfg(test)]
#[path = "rtinst_tests.rs"]
mod tests;
