//! `.rtinst`: an instance table, the placements of one asset (the exporter's, or any
//! program's that scatters things by the million).
//!
//! ```text
//! bytes 0..8   magic b"RTINST\0\0"
//! u32 version (=1) · u32 instance_count
//! instance_count × {
//!     f32[12]  object-to-world matrix, the top three rows of a 4×4, row-major
//!              (metres, Y up; the fourth row is [0, 0, 0, 1])
//!     u32      material: index into the scene entry's `materials` list, or
//!              0xFFFF_FFFF (NO_MATERIAL) for the asset's own materials
//! }
//! ```
//!
//! Little-endian, no padding: 16 + 52 × instance_count bytes exactly. The size is
//! checked against the header before anything is allocated, and every matrix must be
//! finite and invertible (an error names the file and the instance's index).

use super::AssetError;
use bytemuck::{Pod, Zeroable};
use glam::{Mat3, Mat4, Vec3, Vec4};
use std::path::Path;

pub const MAGIC: [u8; 8] = *b"RTINST\0\0";
pub const VERSION: u32 = 1;
pub const HEADER_BYTES: u64 = 16;
pub const RECORD_BYTES: u64 = 52;
/// The material of an instance that keeps its asset's own materials.
pub const OWN_MATERIALS: u32 = u32::MAX;

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
/// indices are checked by whoever knows the scene's `materials` list.
pub fn parse(path: &Path, bytes: &[u8]) -> Result<Vec<InstanceRecord>, AssetError> {
    let fail = |message: String| Err(AssetError::new(path, message));
    if bytes.len() < HEADER_BYTES as usize {
        return fail(format!("truncated: {} bytes is shorter than the 16-byte .rtinst header", bytes.len()));
    }
    if bytes[..8] != MAGIC {
        return fail("not an .rtinst file (bad magic bytes)".into());
    }
    let [version, count] = [8, 12].map(|o| u32_at(bytes, o));
    if version != VERSION {
        return fail(format!("unsupported .rtinst version {version} (this rt reads version {VERSION})"));
    }
    // Checked before anything is allocated: a header cannot make rt reserve memory the
    // file does not back.
    let expected = HEADER_BYTES + RECORD_BYTES * count as u64;
    if bytes.len() as u64 != expected {
        return fail(format!(
            "size is {} bytes but its header ({count} instances) implies {expected} (truncated or corrupt)",
            bytes.len()
        ));
    }
    let records: Vec<InstanceRecord> = bytemuck::pod_collect_to_vec(&bytes[HEADER_BYTES as usize..]);
    for (index, r) in records.iter().enumerate() {
        if let Some(problem) = matrix_problem(&r.object_to_world()) {
            return fail(format!("instance {index}: its matrix {problem}: {:?}", r.rows));
        }
    }
    Ok(records)
}

/// Reads a `.rtinst` file; see [`parse`].
pub fn read(path: &Path) -> Result<Vec<InstanceRecord>, AssetError> {
    let bytes = crate::files::read(path).map_err(|e| AssetError::new(path, e.message()))?;
    parse(path, &bytes)
}

/// The bytes of `records` as a `.rtinst`.
pub fn encode(records: &[InstanceRecord]) -> Vec<u8> {
    let mut out = Vec::with_capacity((HEADER_BYTES + RECORD_BYTES * records.len() as u64) as usize);
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&(records.len() as u32).to_le_bytes());
    out.extend_from_slice(bytemuck::cast_slice(records));
    out
}

/// Writes `records` as a `.rtinst`, atomically.
pub fn write(path: &Path, records: &[InstanceRecord]) -> Result<(), AssetError> {
    if u32::try_from(records.len()).is_err() {
        return Err(AssetError::new(path, "more than 2^32 instances do not fit an .rtinst"));
    }
    Ok(crate::files::write_atomically(path, &encode(records))?)
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

    #[test]
    fn round_trips_matrices_and_materials() {
        let bytes = encode(&two());
        assert_eq!(bytes.len(), 16 + 2 * 52);
        let back = parse(Path::new("t.rtinst"), &bytes).expect("parses");
        assert_eq!(back, two());
        let m = back[0].object_to_world();
        assert!((m.transform_point3(Vec3::ZERO) - Vec3::new(3.0, -1.0, 2.0)).length() < 1e-6);
        assert_eq!(m.row(3), Vec4::W);
        // Row-major on disk: the translation is the fourth float of each row.
        assert_eq!([back[0].rows[3], back[0].rows[7], back[0].rows[11]], [3.0, -1.0, 2.0]);
    }

    #[test]
    fn a_header_that_lies_about_its_size_is_refused_before_allocating() {
        let mut bytes = encode(&two());
        bytes.pop();
        assert!(error(&bytes).contains("implies 120"), "{}", error(&bytes));
        // Four billion instances claimed by a 16-byte file: refused on the size alone.
        let mut bytes = encode(&[]);
        bytes[12..16].copy_from_slice(&4_000_000_000u32.to_le_bytes());
        let message = error(&bytes);
        assert!(message.starts_with("t.rtinst: size is 16 bytes"), "{message}");
        assert!(message.contains("4000000000 instances"), "{message}");
    }

    #[test]
    fn bad_magic_version_and_matrices_are_named() {
        assert!(error(b"short").contains("truncated"));
        let good = encode(&two());
        let mut bytes = good.clone();
        bytes[0] = b'X';
        assert!(error(&bytes).contains("bad magic"));
        let mut bytes = good.clone();
        bytes[8] = 2;
        assert!(error(&bytes).contains("unsupported .rtinst version 2"));

        let mut records = two();
        records[1].rows[5] = f32::NAN;
        let message = error(&encode(&records));
        assert!(message.contains("instance 1: its matrix is not finite"), "{message}");
        let mut records = two();
        records[1].rows[0..3].copy_from_slice(&[0.0, 0.0, 0.0]);
        let message = error(&encode(&records));
        assert!(message.contains("instance 1: its matrix is singular"), "{message}");
        // A millimetre scale is fine; a scale of zero, or columns that nearly coincide, are not.
        let mm = [InstanceRecord::new(&Mat4::from_scale(Vec3::splat(1e-3)), OWN_MATERIALS)];
        assert!(parse(Path::new("t.rtinst"), &encode(&mm)).is_ok());
        let flat = [InstanceRecord::new(&Mat4::from_scale(Vec3::new(1.0, 1.0, 0.0)), OWN_MATERIALS)];
        assert!(error(&encode(&flat)).contains("instance 0: its matrix is singular"));
        let mut sheared = two();
        sheared[1].rows[0..3].copy_from_slice(&[1.0, 1.0, 0.0]);
        sheared[1].rows[4..7].copy_from_slice(&[0.0, 1e-7, 0.0]);
        assert!(error(&encode(&sheared)).contains("instance 1: its matrix is singular"));
    }
}
