//! `.rtinst`: an instance table, the placements of one asset (the exporter's, or any
//! program's that scatters things by the million).
//!
//! ```text
//! bytes 0..8   magic b"RTINST\0\0"
//! u32 version (=3) · u32 instance_count · u32 slot_count · u32 set_count · u32 motion_keys
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
//! ```
//!
//! Little-endian, no padding: 28 + 4 × slot_count × set_count + (52 + 48 × motion_keys) ×
//! instance_count bytes exactly. Version 2 files (a 24-byte header without motion_keys, no
//! motion) and version 1 files (a 16-byte header: magic, version, instance_count; no sets)
//! are read too. The size is checked against the header before anything is allocated,
//! and every matrix must be finite and invertible (an error names the file and the
//! instance's index).

use super::AssetError;
use bytemuck::{Pod, Zeroable};
use glam::{Mat3, Mat4, Vec3, Vec4};
use std::path::Path;

pub const MAGIC: [u8; 8] = *b"RTINST\0\0";
pub const VERSION: u32 = 3;
/// The header of version 3; version 2's is 24 bytes (no motion_keys), version 1's 16 (no
/// slot and set counts either).
pub const HEADER_BYTES: u64 = 28;
const HEADER_BYTES_V2: u64 = 24;
const HEADER_BYTES_V1: u64 = 16;
pub const RECORD_BYTES: u64 = 52;
/// One motion key: the top three rows of a matrix.
const KEY_BYTES: u64 = 48;
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
        VERSION => HEADER_BYTES,
        _ => return fail(format!("unsupported .rtinst version {version} (this rt reads versions 1 to {VERSION})")),
    };
    if bytes.len() < header as usize {
        return fail(format!("truncated: {} bytes is shorter than the {header}-byte .rtinst header", bytes.len()));
    }
    let word = |offset: u64| if offset < header { u32_at(bytes, offset as usize) } else { 0 };
    let (slot_count, set_count, motion_keys) = (word(16), word(20), word(24));
    if motion_keys == 1 || motion_keys as usize > crate::scene::MAX_MOTION_KEYS {
        let most = crate::scene::MAX_MOTION_KEYS;
        return fail(format!("motion_keys must be 0 (no motion) or 2 to {most}, got {motion_keys}"));
    }
    // Checked before anything is allocated: a header cannot make rt reserve memory the
    // file does not back (in u128: the counts' product can pass u64).
    let set_bytes = 4 * slot_count as u128 * set_count as u128;
    let record_bytes = (RECORD_BYTES + KEY_BYTES * motion_keys as u64) as u128;
    let expected = header as u128 + set_bytes + record_bytes * count as u128;
    if bytes.len() as u128 != expected {
        return fail(format!(
            "size is {} bytes but its header ({count} instances, {set_count} material sets of {slot_count} slots, \
             {motion_keys} motion keys) implies {expected} (truncated or corrupt)",
            bytes.len()
        ));
    }
    let records_at = header as usize + set_bytes as usize;
    let motion_at = records_at + RECORD_BYTES as usize * count as usize;
    let indices: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes[header as usize..records_at]);
    let records: Vec<InstanceRecord> = bytemuck::pod_collect_to_vec(&bytes[records_at..motion_at]);
    let motion: Vec<[f32; 12]> = bytemuck::pod_collect_to_vec(&bytes[motion_at..]);
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
    Ok(InstanceFile { records, material_sets: MaterialSets { slot_count, indices }, motion_keys, motion })
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
    let set_bytes = 4 * sets.indices.len() as u64;
    let motion_bytes = KEY_BYTES * motion.len() as u64;
    let mut out =
        Vec::with_capacity((HEADER_BYTES + set_bytes + RECORD_BYTES * records.len() as u64 + motion_bytes) as usize);
    out.extend_from_slice(&MAGIC);
    for word in [VERSION, records.len() as u32, sets.slot_count, sets.len() as u32, motion_keys] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(bytemuck::cast_slice(&sets.indices));
    out.extend_from_slice(bytemuck::cast_slice(records));
    out.extend_from_slice(bytemuck::cast_slice(motion));
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
mod tests {
    use super::*;

    fn error(bytes: &[u8]) -> String {
        match parse(Path::new("t.rtinst"), bytes) {
            Ok(_) => panic!("parsed"),
            Err(e) => e.to_string(),
        }
    }

    fn two() -> Vec<InstanceRecord> {
        let a = Mat4::from_scale_rotation_translation(
            Vec3::new(1.0, 2.0, 0.5),
            glam::Quat::from_rotation_y(0.7),
            Vec3::new(3.0, -1.0, 2.0),
        );
        vec![InstanceRecord::new(&a, OWN_MATERIALS), InstanceRecord::new(&Mat4::IDENTITY, 3)]
    }

    fn plain(records: &[InstanceRecord]) -> Vec<u8> {
        encode(records, &MaterialSets::default())
    }

    /// `records` as version 1 wrote them: no slot and set counts, no sets.
    fn version_1(records: &[InstanceRecord]) -> Vec<u8> {
        let mut out = MAGIC.to_vec();
        out.extend_from_slice(&1u32.to_le_bytes());
        out.extend_from_slice(&(records.len() as u32).to_le_bytes());
        out.extend_from_slice(bytemuck::cast_slice(records));
        out
    }

    #[test]
    fn round_trips_matrices_materials_and_material_sets() {
        let sets = MaterialSets::new(2, &[vec![1, 0], vec![2, 2]]).expect("sets");
        let mut records = two();
        records[1].material = MATERIAL_SET | 1;
        let bytes = encode(&records, &sets);
        assert_eq!(bytes.len(), 28 + 4 * 4 + 2 * 52);
        let back = parse(Path::new("t.rtinst"), &bytes).expect("parses");
        assert_eq!(back.records, records);
        assert_eq!(back.material_sets, sets);
        assert_eq!(
            (back.material_sets.len(), back.material_sets.get(1), back.material_sets.get(2)),
            (2, Some(&[2, 2][..]), None)
        );
        let back = back.records;
        let m = back[0].object_to_world();
        assert!((m.transform_point3(Vec3::ZERO) - Vec3::new(3.0, -1.0, 2.0)).length() < 1e-6);
        assert_eq!(m.row(3), Vec4::W);
        // Row-major on disk: the translation is the fourth float of each row.
        assert_eq!([back[0].rows[3], back[0].rows[7], back[0].rows[11]], [3.0, -1.0, 2.0]);
        assert!(MaterialSets::new(2, &[vec![1]]).is_none());
    }

    /// `records` and `sets` as version 2 wrote them: no motion_keys.
    fn version_2(records: &[InstanceRecord], sets: &MaterialSets) -> Vec<u8> {
        let mut out = MAGIC.to_vec();
        for word in [2, records.len() as u32, sets.slot_count, sets.len() as u32] {
            out.extend_from_slice(&word.to_le_bytes());
        }
        out.extend_from_slice(bytemuck::cast_slice(&sets.indices));
        out.extend_from_slice(bytemuck::cast_slice(records));
        out
    }

    #[test]
    fn version_2_files_are_read_as_they_were() {
        let sets = MaterialSets::new(1, &[vec![0]]).expect("sets");
        let back = parse(Path::new("t.rtinst"), &version_2(&two(), &sets)).expect("parses");
        assert_eq!((back.records, back.material_sets, back.motion_keys), (two(), sets, 0));
    }

    #[test]
    fn motion_keys_round_trip_and_bad_ones_are_refused() {
        let keys = |x: f32| [Mat4::IDENTITY, Mat4::from_translation(Vec3::new(x, 0.0, 0.0))];
        let rows = |m: &Mat4| InstanceRecord::new(m, 0).rows;
        let motion: Vec<[f32; 12]> = [1.0, 2.0].iter().flat_map(|&x| keys(x).map(|m| rows(&m))).collect();
        let bytes = encode_moving(&two(), &MaterialSets::default(), 2, &motion);
        assert_eq!(bytes.len(), 28 + 2 * (52 + 2 * 48));
        let back = parse(Path::new("t.rtinst"), &bytes).expect("parses");
        assert_eq!(back.motion_of(1).map(|m| m.keys().to_vec()), Some(keys(2.0).to_vec()));
        assert_eq!(parse(Path::new("t.rtinst"), &plain(&two())).expect("parses").motion_of(0), None);
        let mut one_key = bytes.clone();
        one_key[24] = 1;
        assert!(error(&one_key).contains("motion_keys must be 0 (no motion) or 2 to 129, got 1"));
        let mut flat = motion.clone();
        flat[3][0] = 0.0;
        let message = error(&encode_moving(&two(), &MaterialSets::default(), 2, &flat));
        assert!(message.contains("instance 1: its motion key 1 is singular"), "{message}");
    }

    #[test]
    fn version_1_files_are_read_as_they_were() {
        let back = parse(Path::new("t.rtinst"), &version_1(&two())).expect("parses");
        assert_eq!((back.records, back.material_sets), (two(), MaterialSets::default()));
        let mut bytes = version_1(&two());
        bytes.pop();
        assert!(error(&bytes).contains("implies 120"), "{}", error(&bytes));
    }

    #[test]
    fn a_header_that_lies_about_its_size_is_refused_before_allocating() {
        let mut bytes = plain(&two());
        bytes.pop();
        assert!(error(&bytes).contains("implies 132"), "{}", error(&bytes));
        // Four billion instances claimed by a 28-byte file: refused on the size alone.
        let mut bytes = plain(&[]);
        bytes[12..16].copy_from_slice(&4_000_000_000u32.to_le_bytes());
        let message = error(&bytes);
        assert!(message.starts_with("t.rtinst: size is 28 bytes"), "{message}");
        assert!(message.contains("4000000000 instances"), "{message}");
        // As many sets of as many slots: 2⁶⁶ bytes claimed, counted without overflow.
        let mut bytes = plain(&[]);
        bytes[16..24].copy_from_slice(&[0xff; 8]);
        let message = error(&bytes);
        assert!(message.contains("4294967295 material sets of 4294967295 slots"), "{message}");
        // A version 3 header cut short.
        assert!(error(&plain(&[])[..20]).contains("shorter than the 28-byte"));
    }

    #[test]
    fn bad_magic_version_and_matrices_are_named() {
        assert!(error(b"short").contains("truncated"));
        let good = plain(&two());
        let mut bytes = good.clone();
        bytes[0] = b'X';
        assert!(error(&bytes).contains("bad magic"));
        let mut bytes = good.clone();
        bytes[8] = 4;
        assert!(error(&bytes).contains("unsupported .rtinst version 4"));

        let mut records = two();
        records[1].rows[5] = f32::NAN;
        let message = error(&plain(&records));
        assert!(message.contains("instance 1: its matrix is not finite"), "{message}");
        let mut records = two();
        records[1].rows[0..3].copy_from_slice(&[0.0, 0.0, 0.0]);
        let message = error(&plain(&records));
        assert!(message.contains("instance 1: its matrix is singular"), "{message}");
        // A millimetre scale is fine; a scale of zero, or columns that nearly coincide, are not.
        let mm = [InstanceRecord::new(&Mat4::from_scale(Vec3::splat(1e-3)), OWN_MATERIALS)];
        assert!(parse(Path::new("t.rtinst"), &plain(&mm)).is_ok());
        let flat = [InstanceRecord::new(&Mat4::from_scale(Vec3::new(1.0, 1.0, 0.0)), OWN_MATERIALS)];
        assert!(error(&plain(&flat)).contains("instance 0: its matrix is singular"));
        let mut sheared = two();
        sheared[1].rows[0..3].copy_from_slice(&[1.0, 1.0, 0.0]);
        sheared[1].rows[4..7].copy_from_slice(&[0.0, 1e-7, 0.0]);
        assert!(error(&plain(&sheared)).contains("instance 1: its matrix is singular"));
    }
}
