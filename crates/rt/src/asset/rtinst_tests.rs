//! Tests of `.rtinst` reading and writing (src/asset/rtinst.rs).

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
    assert_eq!(bytes.len(), 32 + 4 * 4 + 2 * 52);
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
    assert_eq!(bytes.len(), 32 + 2 * (52 + 2 * 48));
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

/// A version 3 file: the header without object_info.
fn version_3(records: &[InstanceRecord], motion_keys: u32, motion: &[[f32; 12]]) -> Vec<u8> {
    let mut out = MAGIC.to_vec();
    for word in [3, records.len() as u32, 0, 0, motion_keys] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(bytemuck::cast_slice(records));
    out.extend_from_slice(bytemuck::cast_slice(motion));
    out
}

#[test]
fn version_3_files_are_read_as_they_were() {
    let motion = [InstanceRecord::new(&Mat4::IDENTITY, 0).rows; 4];
    let back = parse(Path::new("t.rtinst"), &version_3(&two(), 2, &motion)).expect("parses");
    assert_eq!((back.records, back.motion_keys, back.motion, back.info), (two(), 2, motion.to_vec(), vec![]));
}

#[test]
fn object_info_round_trips_and_bad_values_are_refused() {
    let info = vec![
        ObjectInfo { random: 0.25, color: [1.0, 0.5, 0.0, 1.0], index: 7 },
        ObjectInfo { random: 1.0, color: [0.0, 0.0, 2.0, 0.5], index: 32767 },
    ];
    let file = InstanceFile { records: two(), info: info.clone(), ..Default::default() };
    let bytes = encode_file(&file);
    assert_eq!(bytes.len(), 32 + 2 * (52 + 24));
    assert_eq!(parse(Path::new("t.rtinst"), &bytes).expect("parses"), file);
    let mut bad = file.clone();
    bad.info[1].random = 1.5;
    let message = error(&encode_file(&bad));
    assert!(message.contains("instance 1: its object info [1.5, 0.0, 0.0, 2.0, 0.5] is not"), "{message}");
    let mut bad = file.clone();
    bad.info[0].index = 32768;
    let message = error(&encode_file(&bad));
    assert!(message.contains("instance 0: its object index 32768 is above 32767"), "{message}");
    let mut flag = bytes.clone();
    flag[28] = 2;
    assert!(error(&flag).contains("object_info must be 0 (none) or 1 (each instance's), got 2"));
    let mut cut = bytes;
    cut.pop();
    assert!(error(&cut).contains("object info 1) implies 184"), "{}", error(&cut));
}

/// Version 4 wrote each instance's info without its Object Index (20 bytes): read as index 0.
#[test]
fn version_4_object_info_is_read_without_an_index() {
    let info = vec![
        ObjectInfo { random: 0.25, color: [1.0, 0.5, 0.0, 1.0], index: 0 },
        ObjectInfo { random: 1.0, color: [0.0, 0.0, 2.0, 0.5], index: 0 },
    ];
    let file = InstanceFile { records: two(), info, ..Default::default() };
    let v5 = encode_file(&file);
    let records_end = v5.len() - 2 * 24;
    let mut v4 = v5[..records_end].to_vec();
    v4[8] = 4;
    for chunk in v5[records_end..].chunks(24) {
        v4.extend_from_slice(&chunk[..20]);
    }
    assert_eq!(parse(Path::new("t.rtinst"), &v4).expect("parses"), file);
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
    assert!(error(&bytes).contains("implies 136"), "{}", error(&bytes));
    // Four billion instances claimed by a 32-byte file: refused on the size alone.
    let mut bytes = plain(&[]);
    bytes[12..16].copy_from_slice(&4_000_000_000u32.to_le_bytes());
    let message = error(&bytes);
    assert!(message.starts_with("t.rtinst: size is 32 bytes"), "{message}");
    assert!(message.contains("4000000000 instances"), "{message}");
    // As many sets of as many slots: 2⁶⁶ bytes claimed, counted without overflow.
    let mut bytes = plain(&[]);
    bytes[16..24].copy_from_slice(&[0xff; 8]);
    let message = error(&bytes);
    assert!(message.contains("4294967295 material sets of 4294967295 slots"), "{message}");
    // A version 5 header cut short.
    assert!(error(&plain(&[])[..20]).contains("shorter than the 32-byte"));
}

#[test]
fn bad_magic_version_and_matrices_are_named() {
    assert!(error(b"short").contains("truncated"));
    let good = plain(&two());
    let mut bytes = good.clone();
    bytes[0] = b'X';
    assert!(error(&bytes).contains("bad magic"));
    let mut bytes = good.clone();
    bytes[8] = 6;
    assert!(error(&bytes).contains("unsupported .rtinst version 6"));

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
