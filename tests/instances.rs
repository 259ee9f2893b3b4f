//! Instance files (`.rtinst`) on lavapipe: they place exactly what `[[mesh]]` entries
//! with the same matrices place, bad files are errors that name them, and a million
//! instances of a 10⁴-triangle mesh pack and render; an entry's Shadow Terminator settings
//! reach every instance of its file.

use crate::common;

use common::{gpu, icosphere_obj, render, temp_dir, write};
use glam::{Mat4, Quat, Vec3};
use rt::asset::rtinst::{self, InstanceRecord, MaterialSets, OWN_MATERIALS};
use rt::bvh::{BuildQuality, SceneGeometry};
use rt::render::{RenderRequest, Session};
use std::path::Path;
use std::time::Instant;

const HEADER: &str = "[camera]\nposition = [0.0, 3.0, 7.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 50.0\n\n\
                      [sky]\nkind = \"uniform\"\ncolor = [0.8, 0.9, 1.0]\n\n\
                      [materials.red]\nbase_color = [0.9, 0.1, 0.1]\n\
                      [materials.lamp]\nemission = [4.0, 3.0, 2.0]\n\n";

/// Rotated, non-uniformly scaled, translated spheres; every third red, one a lamp.
fn placements() -> Vec<(Mat4, u32)> {
    (0..9)
        .map(|i| {
            let (x, z) = ((i % 3) as f32 * 2.2 - 2.2, (i / 3) as f32 * 2.2 - 2.2);
            let m = Mat4::from_scale_rotation_translation(
                Vec3::new(0.6, 0.9 + 0.1 * i as f32, 0.7),
                Quat::from_euler(glam::EulerRot::XYZ, 0.3 * i as f32, 0.5, -0.2),
                Vec3::new(x, 0.2 * i as f32 - 0.5, z),
            );
            let material = match i {
                4 => 1,
                _ if i % 3 == 0 => 0,
                _ => OWN_MATERIALS,
            };
            (m, material)
        })
        .collect()
}

fn sphere_asset(dir: &Path) -> String {
    let obj = dir.join("sphere.obj");
    write(&obj, &icosphere_obj(2).0);
    obj.display().to_string()
}

fn matrix_toml(m: &Mat4) -> String {
    let rows: Vec<String> = m.transpose().to_cols_array().iter().map(|v| format!("{v:e}")).collect();
    format!("[{}]", rows.join(", "))
}

#[test]
fn an_instance_file_places_what_mesh_entries_with_its_matrices_place() {
    let dir = temp_dir("instances-vs-meshes");
    let asset = sphere_asset(&dir);
    let placed = placements();

    let mut meshes = HEADER.to_owned();
    for (m, material) in &placed {
        meshes.push_str(&format!("[[mesh]]\nasset = {asset:?}\nmatrix = {}\n", matrix_toml(m)));
        match *material {
            0 => meshes.push_str("material = \"red\"\n"),
            1 => meshes.push_str("material = \"lamp\"\n"),
            _ => {}
        }
    }
    let records: Vec<InstanceRecord> = placed.iter().map(|(m, mat)| InstanceRecord::new(m, *mat)).collect();
    let file = dir.join("spheres.rtinst");
    rtinst::write(&file, &records, &MaterialSets::default()).expect("write .rtinst");
    let instanced = format!(
        "{HEADER}[[instances]]\nasset = {asset:?}\nfile = {:?}\nmaterials = [\"red\", \"lamp\"]\n",
        file.display().to_string()
    );

    let a = render(common::scene_from(&meshes), 64, 64, 4, 4);
    let b = render(common::scene_from(&instanced), 64, 64, 4, 4);
    let differing = a.pixels.iter().zip(&b.pixels).filter(|(p, q)| p != q).count();
    let lit = a.pixels.iter().filter(|p| p[0] > p[2] * 1.5).count();
    println!("9 instances, 64x64 at 4 spp: {differing} pixels differ; {lit} pixels red-dominant");
    assert_eq!(differing, 0, "the instance file and the [[mesh]] entries render differently");
    // The overrides reached the image: red spheres are seen under a bluish sky.
    assert!(lit > 20, "only {lit} red-dominant pixels: the material override was lost");
}

/// An `[[instances]]` entry's Shadow Terminator settings are each of its instances', as a
/// `[[mesh]]` entry's are its one: the same image (and the settings change it: the Shading
/// Offset shifts every lobe, the pipeline runs the `terminator-offset` code).
#[test]
fn an_instance_files_shadow_terminator_settings_reach_every_instance() {
    let dir = temp_dir("instances-terminator");
    let asset = sphere_asset(&dir);
    let placed = placements();
    let settings = "shadow_terminator_shading_offset = 0.6\nshadow_terminator_geometry_offset = 0.5\n";
    let meshes = |with: &str| {
        let entries =
            placed.iter().map(|(m, _)| format!("[[mesh]]\nasset = {asset:?}\nmatrix = {}\n{with}", matrix_toml(m)));
        format!("{HEADER}{}", entries.collect::<String>())
    };
    let records: Vec<InstanceRecord> = placed.iter().map(|(m, _)| InstanceRecord::new(m, OWN_MATERIALS)).collect();
    let file = dir.join("spheres.rtinst");
    rtinst::write(&file, &records, &MaterialSets::default()).expect("write .rtinst");
    let instanced =
        format!("{HEADER}[[instances]]\nasset = {asset:?}\nfile = {:?}\n{settings}", file.display().to_string());

    let shot = |text: &str| {
        common::render_request(common::scene_from(text), |r| (r.width, r.height, r.spp, r.max_bounces) = (48, 48, 4, 4))
    };
    let (a, features) = shot(&meshes(settings));
    let (b, _) = shot(&instanced);
    let (plain, plain_features) = shot(&meshes(""));
    let differing = a.pixels.iter().zip(&b.pixels).filter(|(p, q)| p != q).count();
    let shifted = a.pixels.iter().zip(&plain.pixels).filter(|(p, q)| p != q).count();
    println!("48x48 at 4 spp: {differing} pixels differ between the entries, {shifted} from the defaults'");
    assert_eq!(differing, 0, "the instance file's settings and the [[mesh]] entries' render differently");
    assert!(shifted > 48 * 48 / 4, "the settings changed {shifted} pixels");
    assert!(features.terminator_offset && !plain_features.terminator_offset, "{features} / {plain_features}");
}

fn geometry_error(dir: &Path, asset: &str, bytes: &[u8], materials: &str) -> String {
    let file = dir.join("bad.rtinst");
    std::fs::write(&file, bytes).expect("write");
    let scene = common::scene_from(&format!(
        "{HEADER}[[instances]]\nasset = {asset:?}\nfile = {:?}\nmaterials = {materials}\n",
        file.display().to_string()
    ));
    match SceneGeometry::build(&scene, BuildQuality::Medium) {
        Ok(_) => panic!("a bad instance file was accepted"),
        Err(e) => format!("{e:#}"),
    }
}

#[test]
fn bad_instance_files_are_errors_that_name_the_file_and_the_instance() {
    let dir = temp_dir("instances-bad");
    let asset = sphere_asset(&dir);
    let good = rtinst::encode(
        &[InstanceRecord::new(&Mat4::IDENTITY, 0), InstanceRecord::new(&Mat4::IDENTITY, 1)],
        &MaterialSets::default(),
    );

    let truncated = geometry_error(&dir, &asset, &good[..good.len() - 3], "[\"red\", \"lamp\"]");
    assert!(
        truncated.contains(
            "bad.rtinst: size is 133 bytes but its header (2 instances, 0 material sets of 0 slots, 0 motion keys, \
             object info 0) implies 136"
        ),
        "{truncated}"
    );

    let mut lying = good.clone();
    lying[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    let lying = geometry_error(&dir, &asset, &lying, "[]");
    assert!(lying.contains("bad.rtinst: size is 136 bytes but its header (4294967295 instances"), "{lying}");

    let mut nan = vec![InstanceRecord::new(&Mat4::IDENTITY, 0); 3];
    nan[2].rows[7] = f32::NAN;
    let nan = geometry_error(&dir, &asset, &rtinst::encode(&nan, &MaterialSets::default()), "[\"red\"]");
    assert!(nan.contains("bad.rtinst: instance 2: its matrix is not finite"), "{nan}");

    let singular = [InstanceRecord::new(&Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0)), OWN_MATERIALS)];
    let singular = geometry_error(&dir, &asset, &rtinst::encode(&singular, &MaterialSets::default()), "[]");
    assert!(singular.contains("bad.rtinst: instance 0: its matrix is singular"), "{singular}");

    let out_of_range = geometry_error(&dir, &asset, &good, "[\"red\"]");
    assert!(out_of_range.contains("bad.rtinst: instance 1: material 1 is out of range"), "{out_of_range}");
    println!("{truncated}\n{lying}\n{nan}\n{singular}\n{out_of_range}");

    // Material sets: a set index past the file's sets, a set naming a material the asset
    // lacks, and more slots than the asset has materials.
    let sets = |slots: u32, sets: &[Vec<u32>]| MaterialSets::new(slots, sets).expect("sets");
    let one = [InstanceRecord::new(&Mat4::IDENTITY, rtinst::MATERIAL_SET | 1)];
    let missing_set = geometry_error(&dir, &asset, &rtinst::encode(&one, &sets(1, &[vec![0]])), "[]");
    assert!(
        missing_set.contains("bad.rtinst: instance 0: material set 1 is out of range: the file has 1"),
        "{missing_set}"
    );
    let one = [InstanceRecord::new(&Mat4::IDENTITY, rtinst::MATERIAL_SET)];
    let missing_material = geometry_error(&dir, &asset, &rtinst::encode(&one, &sets(1, &[vec![1]])), "[]");
    assert!(
        missing_material.contains("bad.rtinst: material set 0, slot 0: material 1 is out of range"),
        "{missing_material}"
    );
    let too_many = geometry_error(&dir, &asset, &rtinst::encode(&one, &sets(2, &[vec![0, 0]])), "[]");
    assert!(too_many.contains("bad.rtinst: its material sets have 2 slots but the asset"), "{too_many}");
    println!("{missing_set}\n{missing_material}\n{too_many}");
}

/// The icosphere with its first half of faces showing `first` and the rest `second`, from
/// a material library of red, blue and a lamp.
fn two_material_sphere(dir: &Path, name: &str, first: &str, second: &str) -> String {
    write(
        &dir.join("m.mtl"),
        "newmtl red\nKd 0.9 0.1 0.1\nnewmtl blue\nKd 0.1 0.2 0.9\nnewmtl lamp\nKd 0 0 0\nKe 4 3 2\n",
    );
    let (obj, _, faces) = icosphere_obj(2);
    let half = faces.len() / 2;
    let mut text = String::from("mtllib m.mtl\n");
    let mut face = 0;
    for line in obj.lines() {
        if line.starts_with("f ") {
            if face == 0 || face == half {
                text.push_str(&format!("usemtl {}\n", if face == 0 { first } else { second }));
            }
            face += 1;
        }
        text.push_str(line);
        text.push('\n');
    }
    let path = dir.join(format!("{name}.obj"));
    write(&path, &text);
    path.display().to_string()
}

#[test]
fn material_sets_show_what_assets_with_those_materials_show() {
    let dir = temp_dir("instances-material-sets");
    let asset = two_material_sphere(&dir, "sphere", "red", "blue");
    let placed = placements();
    let (lit, blue) = placed.split_at(4);
    // Set 0 shows the lamp on the first half and red on the second; set 1 blue all over.
    let sets = MaterialSets::new(2, &[vec![2, 0], vec![1, 1]]).expect("sets");
    let records: Vec<InstanceRecord> = (lit.iter().map(|(m, _)| InstanceRecord::new(m, rtinst::MATERIAL_SET)))
        .chain(blue.iter().map(|(m, _)| InstanceRecord::new(m, rtinst::MATERIAL_SET | 1)))
        .collect();
    rtinst::write(&dir.join("sets.rtinst"), &records, &sets).expect("write .rtinst");
    let with_sets = format!("{HEADER}[[instances]]\nasset = {asset:?}\nfile = \"sets.rtinst\"\n");

    // The same placements as two assets whose own materials are those of the sets.
    let lamp_red = two_material_sphere(&dir, "lamp_red", "lamp", "red");
    let all_blue = two_material_sphere(&dir, "all_blue", "blue", "blue");
    let own = |part: &[(Mat4, u32)]| -> Vec<InstanceRecord> {
        part.iter().map(|(m, _)| InstanceRecord::new(m, OWN_MATERIALS)).collect()
    };
    rtinst::write(&dir.join("lit.rtinst"), &own(lit), &MaterialSets::default()).expect("write .rtinst");
    rtinst::write(&dir.join("blue.rtinst"), &own(blue), &MaterialSets::default()).expect("write .rtinst");
    let separate = format!(
        "{HEADER}[[instances]]\nasset = {lamp_red:?}\nfile = \"lit.rtinst\"\n\
         [[instances]]\nasset = {all_blue:?}\nfile = \"blue.rtinst\"\n"
    );

    let in_dir = |text: &str| {
        let path = dir.join("scene.toml");
        write(&path, text);
        rt::scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
    };
    let a = render(in_dir(&with_sets), 64, 64, 4, 4);
    let b = render(in_dir(&separate), 64, 64, 4, 4);
    let differing = a.pixels.iter().zip(&b.pixels).filter(|(p, q)| p != q).count();
    let bluish = a.pixels.iter().filter(|p| p[2] > p[0] * 2.0 && p[2] > 0.3 && p[1] < 0.6).count();
    let glowing = a.pixels.iter().filter(|p| p[0] > 1.5).count();
    println!(
        "9 instances in two material sets, 64x64 at 4 spp: {differing} pixels differ; {bluish} blue, {glowing} glowing"
    );
    assert_eq!(differing, 0, "material sets render otherwise than assets with those materials");
    assert!(bluish > 20 && glowing > 5, "{bluish} blue and {glowing} glowing pixels: a set was not shown");
}

/// A wavy tile of 100 × 50 quads: exactly 10⁴ triangles, one unit across.
fn tile_obj() -> String {
    let (nx, nz) = (100, 50);
    let mut text = String::new();
    for j in 0..=nz {
        for i in 0..=nx {
            let (x, z) = (i as f32 / nx as f32 - 0.5, j as f32 / nz as f32 - 0.5);
            let y = 0.1 * (x * 20.0).sin() * (z * 13.0).cos();
            text.push_str(&format!("v {x} {y} {z}\n"));
        }
    }
    let at = |i: usize, j: usize| j * (nx + 1) + i + 1;
    for j in 0..nz {
        for i in 0..nx {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            text.push_str(&format!("f {a} {d} {c}\nf {a} {c} {b}\n"));
        }
    }
    text
}

/// `count` tiles on a square grid, each turned and scaled by its own amount.
fn tile_records(count: usize) -> Vec<InstanceRecord> {
    let side = (count as f64).sqrt().ceil() as usize;
    (0..count)
        .map(|k| {
            let (i, j) = ((k % side) as f32, (k / side) as f32);
            let h = (k as u32).wrapping_mul(2_654_435_761) as f32 / u32::MAX as f32;
            let m = Mat4::from_scale_rotation_translation(
                Vec3::splat(0.8 + 0.3 * h),
                Quat::from_rotation_y(std::f32::consts::TAU * h),
                Vec3::new(i - side as f32 / 2.0, 0.0, j - side as f32 / 2.0),
            );
            InstanceRecord::new(&m, if k % 7 == 0 { 0 } else { OWN_MATERIALS })
        })
        .collect()
}

#[test]
fn a_million_instances_of_ten_thousand_triangles_pack_and_render() {
    let dir = temp_dir("instances-scale");
    let obj = dir.join("tile.obj");
    write(&obj, &tile_obj());
    println!(
        "| instances | file MiB | read+place+top level ms | top level build ms | GPU MiB (instances + top level) | bytes/instance | paths/s (64x64, 2 spp) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for count in [1_000, 100_000, 1_000_000] {
        let file = dir.join(format!("tiles-{count}.rtinst"));
        rtinst::write(&file, &tile_records(count), &MaterialSets::default()).expect("write .rtinst");
        let side = (count as f32).sqrt() / 2.0;
        let scene = common::scene_from(&format!(
            "[camera]\nposition = [0.0, {}, {}]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 50.0\n\
             [sky]\nkind = \"uniform\"\ncolor = [0.1, 0.1, 0.1]\n\
             [sun]\nelevation_deg = 60.0\nazimuth_deg = 30.0\n[materials.red]\nbase_color = [0.9, 0.1, 0.1]\n\
             [[instances]]\nasset = {:?}\nfile = {:?}\nmaterials = [\"red\"]\n",
            side * 0.6 + 2.0,
            side * 1.2 + 2.0,
            obj.display().to_string(),
            file.display().to_string()
        ));
        let start = Instant::now();
        let geometry = SceneGeometry::build(&scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
        let pack = start.elapsed();
        assert_eq!(geometry.instances.len(), count);
        assert_eq!(geometry.meshes[0].triangle_count, 10_000);
        let top = geometry.top_level_bytes();
        let per_instance = top as f64 / count as f64;
        let tlas_ms = geometry.tlas_build_time.as_secs_f64() * 1e3;

        let mut session = Session::with_geometry(gpu(), scene, geometry).unwrap_or_else(|e| panic!("{e:#}"));
        let mut request = RenderRequest::from_scene(session.scene());
        (request.width, request.height, request.spp, request.max_bounces) = (64, 64, 2, 2);
        let (image, report) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
        assert!(report.dropped.is_clean(), "{}", report.dropped);
        // The camera looks down on the tiles: most pixels see a sunlit tile, far brighter than the sky's 0.1.
        let covered = image.pixels.iter().filter(|p| p[1] > 0.3).count();
        println!(
            "| {count} | {:.1} | {:.0} | {tlas_ms:.0} | {:.1} | {per_instance:.1} | {:.0} |",
            std::fs::metadata(&file).map_or(0, |m| m.len()) as f64 / 1048576.0,
            pack.as_secs_f64() * 1e3,
            top as f64 / 1048576.0,
            report.samples_per_second
        );
        assert!(covered > 64 * 64 / 3, "{count} instances: only {covered} of 4096 pixels see a tile");
        // Bounded, whatever the count: the record, about one top-level node and a leaf entry.
        assert!(per_instance < 200.0, "{per_instance} GPU bytes per instance");
    }
}

#[test]
fn an_edited_instance_file_re_places_instances_without_repacking_the_mesh() {
    let dir = temp_dir("instances-live");
    let asset = sphere_asset(&dir);
    let file = dir.join("spheres.rtinst");
    let records = |dx: f32| -> Vec<InstanceRecord> {
        placements().iter().map(|(m, _)| InstanceRecord::new(&(Mat4::from_translation(Vec3::X * dx) * *m), 0)).collect()
    };
    rtinst::write(&file, &records(0.0), &MaterialSets::default()).expect("write .rtinst");
    let scene_path = dir.join("scene.toml");
    let text = format!("{HEADER}[[instances]]\nasset = {asset:?}\nfile = \"spheres.rtinst\"\nmaterials = [\"red\"]\n");
    write(&scene_path, &text);
    let options = rt_watch::WatchOptions {
        scene: scene_path,
        quality: BuildQuality::Medium,
        shader_dir: None,
        frames_dir: None,
        flags: Default::default(),
        format: rt::render::ImageFormat::Exr,
        max_reloads: None,
    };
    let mut live = rt_watch::LiveScene::open(gpu(), &options).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(live.watched_files().contains(&file), "the instance file is not watched");
    let before = live.session.geometry().bounds_min;
    let mesh_before = live.session.geometry().meshes[0].provenance;

    rtinst::write(&file, &records(1.5), &MaterialSets::default()).expect("rewrite .rtinst");
    let report = live.reload(std::slice::from_ref(&file)).unwrap_or_else(|e| panic!("{e:#}"));
    let after = live.session.geometry().bounds_min;
    println!(
        "moved instances: reload {} in {:.1?}; bounds min x {} -> {}",
        report.reload.kind(),
        report.elapsed,
        before.x,
        after.x
    );
    assert_eq!(report.reload.kind(), "placement");
    assert!(report.reload.assets().next().is_none(), "the mesh was re-packed");
    // The same loaded BVH, not a fresh load: its provenance (and load time) is the one from opening.
    assert_eq!(live.session.geometry().meshes[0].provenance, mesh_before);
    assert!((after.x - before.x - 1.5).abs() < 1e-3, "instances did not move by 1.5: {} -> {}", before.x, after.x);

    // A broken instance file is refused, naming it, and the scene stays as it was.
    std::fs::write(&file, b"RTINST\0\0").expect("truncate");
    let message = match live.reload(std::slice::from_ref(&file)) {
        Ok(_) => panic!("a truncated instance file was accepted"),
        Err(e) => format!("{e:#}"),
    };
    assert!(message.contains("spheres.rtinst: truncated"), "{message}");
    assert_eq!(live.session.geometry().bounds_min, after);
}

/// On every GPU: a device of this GPU that binds 16 MiB per buffer (a small GPU's limit)
/// is given one instance more than that holds.
#[test]
fn more_instances_than_the_gpu_binds_is_an_error_not_a_crash() {
    let small = rt::gpu::GpuContext::with_binding_limit(None, 16 << 20).unwrap_or_else(|e| panic!("{e:#}"));
    let max = small.device.limits().max_storage_buffer_binding_size;
    assert_eq!(max, 16 << 20, "the device binds what was asked for");
    let count = (max / size_of::<rt::layout::GpuInstance>() as u64 + 1) as usize;
    let dir = temp_dir("instances-too-many");
    let obj = dir.join("tile.obj");
    write(&obj, &icosphere_obj(0).0);
    let file = dir.join("many.rtinst");
    rtinst::write(&file, &tile_records(count), &MaterialSets::default()).expect("write .rtinst");
    let scene = common::scene_from(&format!(
        "[materials.red]\n[[instances]]\nasset = {:?}\nfile = {:?}\nmaterials = [\"red\"]\n",
        obj.display().to_string(),
        file.display().to_string()
    ));
    let message = match Session::open(&small, scene, BuildQuality::Medium) {
        Ok(_) => panic!("{count} instances were bound in buffers of at most {max} bytes"),
        Err(e) => format!("{e:#}"),
    };
    println!("{count} instances: {message}");
    // ~100 MB of records: not left behind in the temporary directory.
    let _ = std::fs::remove_dir_all(&dir);
    assert!(message.contains("the scene's instances take") && message.contains("16.0 MiB"), "{message}");
}
