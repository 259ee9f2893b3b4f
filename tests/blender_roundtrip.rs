//! Blender → rt: a scene built with bpy, exported with blender/rt_export.py, packed and
//! rendered. Needs RT_BPY_PYTHON, a Python with `bpy` (scripts/test sets one up).

use crate::common;

use common::{bpy_python, render, repo};
use glam::{Mat4, Vec3};
use rt::asset::{MeshData, load_mesh};
use rt::bvh::{BuildQuality, Provenance, SceneGeometry};
use rt::scene::Scene;
use serde_json::Value;
use std::path::Path;
use std::process::Command;

/// Runs a command, failing the test with its output if it fails; returns stderr.
fn run(command: &mut Command) -> String {
    let out = command.output().unwrap_or_else(|e| panic!("cannot run {command:?}: {e}"));
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{command:?} failed:\n{stdout}\n{stderr}");
    stdout + &stderr
}

/// Blender's (x, y, z) is rt's (x, z, -y).
fn y_up(v: &Value) -> Vec3 {
    let c = |i: usize| v[i].as_f64().expect("number") as f32;
    Vec3::new(c(0), c(2), -c(1))
}

fn instance_matrix(scene: &Scene, name: &str) -> Mat4 {
    let m = scene.meshes.iter().find(|m| m.asset.ends_with(name)).unwrap_or_else(|| panic!("no [[mesh]] {name}"));
    m.object_to_world
}

/// World-space triangles with their material's name.
fn world_triangles(mesh: &MeshData, to_world: Mat4) -> Vec<([Vec3; 3], String)> {
    let p = |i: u32| to_world.transform_point3(Vec3::from(mesh.positions[i as usize]));
    let name = |t: usize| mesh.materials[mesh.material_ids[t] as usize].0.clone();
    mesh.indices.iter().enumerate().map(|(t, tri)| (tri.map(p), name(t))).collect()
}

/// Every triangle of `a` has one in `b` with the same corners (in the same winding,
/// from any starting corner) within `tolerance`, and the same material.
fn assert_same_triangles(what: &str, a: &[([Vec3; 3], String)], b: &[([Vec3; 3], String)], tolerance: f32) {
    assert_eq!(a.len(), b.len(), "{what}: triangle counts");
    for (tri, material) in a {
        let distance = |other: &[Vec3; 3]| {
            (0..3)
                .map(|r| (0..3).map(|k| tri[k].distance(other[(k + r) % 3])).fold(0.0, f32::max))
                .fold(f32::MAX, f32::min)
        };
        let (best, best_material) =
            b.iter().map(|(other, m)| (distance(other), m)).min_by(|x, y| x.0.total_cmp(&y.0)).expect("non-empty");
        assert!(best < tolerance, "{what}: no triangle matches {tri:?} (nearest off by {best})");
        assert_eq!(material, best_material, "{what}: material of {tri:?}");
    }
}

#[test]
fn blender_scene_exports_packs_and_renders() {
    let python = bpy_python();
    let out = std::env::temp_dir().join(format!("rt-test-{}-blender-roundtrip", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let script = repo().join("tests/blender/roundtrip.py");
    run(Command::new(&python).arg(&script).arg("build").arg(&out));
    let export = |what: &str| {
        run(Command::new(&python)
            .arg(repo().join("blender/rt_export.py"))
            .arg(out.join("roundtrip.blend"))
            .arg("--out")
            .arg(out.join("assets"))
            .arg("--scene")
            .arg(out.join("scenes/roundtrip.toml")))
        .lines()
        .filter(|l| l.starts_with("rt_export:") && l.contains(what))
        .count()
    };
    assert_eq!(export("9 files written"), 1, "the first export writes 4 meshes, 4 material files and the scene");
    assert_eq!(export("0 files written"), 1, "exporting again changes nothing");
    let packed = run(Command::new(env!("CARGO_BIN_EXE_rt")).arg("pack").arg(out.join("assets")));
    assert_eq!(packed.matches("packed").count(), 4, "{packed}");

    let expected: Value = serde_json::from_str(&std::fs::read_to_string(out.join("expected.json")).expect("json"))
        .expect("expected.json parses");
    let scene = rt::scene::load(&out.join("scenes/roundtrip.toml")).unwrap_or_else(|e| panic!("{e}"));
    let asset = |name: &str| load_mesh(&out.join("assets").join(name)).unwrap_or_else(|e| panic!("{e}"));

    let instances_of = |name: &str| scene.meshes.iter().filter(|m| m.asset.ends_with(name)).count();
    assert_eq!(scene.meshes.len(), 5, "one [[mesh]] per object");
    assert_eq!(instances_of("plane"), 2, "both planes use the one plane asset");
    for (name, object) in expected["objects"].as_object().expect("objects") {
        let mesh = asset(name);
        assert_eq!(mesh.indices.len() as u64, object["triangles"].as_u64().expect("count"), "{name}: triangles");
    }

    suzanne_and_lamp_come_through(&asset("suzanne"), &asset("lamp"), &scene, &expected);

    cameras_come_through(&python, &out, &expected, &scene);
    assert_eq!(scene.sky, rt::scene::Sky::Uniform { color: Vec3::new(0.2, 0.25, 0.3), sample_as_light: false });
    // Under a plain sky, every lamp is a [[light]] (the sun too), with Blender's units.
    assert!(scene.sun.is_none());
    check_lights(&scene, &expected["lights"]);

    // The packed caches are what the renderer loads, with the same materials.
    let geometry = SceneGeometry::build(&scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    for mesh in &geometry.meshes {
        assert!(matches!(mesh.provenance, Provenance::Cache { .. }), "{}: {:?}", mesh.path.display(), mesh.provenance);
        assert_eq!(mesh.materials, load_mesh(&mesh.path).expect("loads").materials);
    }
    let image = render(scene.clone(), 64, 64, 4, 4);
    assert!(image.pixels.iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
    assert!(image.pixels.iter().flatten().sum::<f32>() > 0.0, "black image");

    // Blender's own glTF, GLB and OBJ exports of `probe` agree with the .rtmesh.
    let probe = world_triangles(&asset("probe"), instance_matrix(&scene, "probe"));
    for format in ["probe.gltf", "probe.glb", "probe.obj"] {
        let mesh = load_mesh(&out.join("formats").join(format)).unwrap_or_else(|e| panic!("{e}"));
        assert_same_triangles(format, &probe, &world_triangles(&mesh, Mat4::IDENTITY), 1e-4);
        let colour = |m: &MeshData, name: &str| m.materials.iter().find(|(n, _)| n == name).map(|(_, m)| m.base_color);
        for name in ["red", "blue"] {
            let (a, b) = (colour(&asset("probe"), name).expect("rtmesh"), colour(&mesh, name).expect(format));
            assert!(Vec3::from(a).distance(Vec3::from(b)) < 1e-4, "{format}: {name} is {b:?}, not {a:?}");
        }
    }

    live_export_writes_only_what_changed(&python, &script, &out);
    let _ = std::fs::remove_dir_all(&out);
}

/// Suzanne's vertex farthest along a fixed direction lands where Blender has it, in Y-up;
/// her glass and the lamp's emission are Blender's.
fn suzanne_and_lamp_come_through(suzanne: &MeshData, lamp: &MeshData, scene: &Scene, expected: &Value) {
    let to_world = instance_matrix(scene, "suzanne");
    let direction = Vec3::new(0.3, 0.5, 0.7);
    let farthest = |points: &mut dyn Iterator<Item = Vec3>| {
        points.max_by(|a, b| a.dot(direction).total_cmp(&b.dot(direction))).expect("vertices")
    };
    let ours = farthest(&mut suzanne.positions.iter().map(|p| to_world.transform_point3(Vec3::from(*p))));
    let blender = expected["objects"]["suzanne"]["world_positions"].as_array().expect("positions");
    let theirs = farthest(&mut blender.iter().map(y_up));
    assert!(ours.distance(theirs) < 1e-4, "known vertex: rt {ours} vs Blender {theirs}");

    let glass = &suzanne.materials[0].1;
    assert_eq!((glass.transmission, glass.diffuse, glass.reflection), (1.0, 0.0, 0.0), "{glass:?}");
    assert!((glass.ior - 1.45).abs() < 1e-6 && (glass.roughness - 0.05).abs() < 1e-6, "{glass:?}");
    let lamp = &lamp.materials[0].1;
    assert!(!glass.bump_map_correction && lamp.bump_map_correction, "Bump Map Correction: off on the glass only");
    for (got, want) in lamp.emission.iter().zip([5.0, 2.5, 1.25]) {
        assert!((got - want).abs() < 1e-5, "lamp emission {:?}", lamp.emission);
    }
}

/// The camera's position, view, roll, lens, shift and depth of field, an orthographic one
/// and an equirectangular panorama.
fn cameras_come_through(python: &Path, out: &Path, expected: &Value, scene: &Scene) {
    use rt::scene::{DepthOfField, Panorama, Projection, SensorFit};
    let column = |m: &Value, c: usize| {
        let m = m.as_array().expect("matrix");
        y_up(&Value::from((0..3).map(|r| m[r][c].clone()).collect::<Vec<_>>()))
    };
    let check_frame = |camera: &rt::scene::Camera, matrix: &Value| {
        assert!(camera.position.distance(column(matrix, 3)) < 1e-5, "camera at {}", camera.position);
        let (right, up, forward) = camera.basis();
        let axes = [(right, column(matrix, 0).normalize()), (up, column(matrix, 1).normalize())];
        for (ours, blender) in axes.into_iter().chain([(forward, -column(matrix, 2).normalize())]) {
            assert!(ours.distance(blender) < 1e-5, "camera axis {ours} vs Blender's {blender}");
        }
    };
    let camera = &expected["camera"];
    check_frame(&scene.camera, &camera["matrix_world"]);
    let f = |k: &str| camera[k].as_f64().expect("number") as f32;
    assert_eq!((scene.render.width, scene.render.height), (160, 90));
    assert_eq!(scene.camera.projection, Projection::FocalLength { mm: f("lens") });
    assert_eq!((scene.camera.sensor_fit, scene.camera.sensor_mm.x), (SensorFit::Auto, f("sensor_width")));
    assert!(scene.camera.shift.distance(glam::Vec2::new(0.1, -0.05)) < 1e-6, "{}", scene.camera.shift);
    // Cycles focuses on the focus object's distance along the camera's axis.
    let lamp = y_up(&camera["focus_object_location"]);
    let axis = -column(&camera["matrix_world"], 2).normalize();
    let focus_distance = axis.dot(lamp - scene.camera.position).abs();
    let dof = scene.camera.depth_of_field.expect("depth of field");
    assert!((dof.focus_distance - focus_distance).abs() < 1e-4, "focus {} vs {focus_distance}", dof.focus_distance);
    let want = DepthOfField {
        focus_distance: dof.focus_distance,
        fstop: 2.8,
        blades: 6,
        blade_rotation_deg: 0.3f32.to_degrees(),
        aperture_ratio: 1.2,
    };
    assert!(
        dof.blades == want.blades
            && [
                (dof.fstop, want.fstop),
                (dof.blade_rotation_deg, want.blade_rotation_deg),
                (dof.aperture_ratio, want.aperture_ratio)
            ]
            .iter()
            .all(|(a, b)| (a - b).abs() < 1e-4),
        "{dof:?} vs {want:?}"
    );

    run(Command::new(python)
        .arg(repo().join("blender/rt_export.py"))
        .arg(out.join("ortho.blend"))
        .arg("--out")
        .arg(out.join("assets"))
        .arg("--scene")
        .arg(out.join("scenes/ortho.toml")));
    let ortho = rt::scene::load(&out.join("scenes/ortho.toml")).unwrap_or_else(|e| panic!("{e}")).camera;
    check_frame(&ortho, &expected["ortho"]["matrix_world"]);
    assert_eq!((ortho.projection, ortho.sensor_fit), (Projection::Orthographic { scale: 5.0 }, SensorFit::Vertical));
    assert_eq!((ortho.shift.y, ortho.depth_of_field), (0.2, None));

    run(Command::new(python)
        .arg(repo().join("blender/rt_export.py"))
        .arg(out.join("pano.blend"))
        .arg("--out")
        .arg(out.join("assets"))
        .arg("--scene")
        .arg(out.join("scenes/pano.toml")));
    let pano = rt::scene::load(&out.join("scenes/pano.toml")).unwrap_or_else(|e| panic!("{e}")).camera;
    check_frame(&pano, &expected["pano"]["matrix_world"]);
    let Projection::Panoramic { panorama, lens_mm } = pano.projection else { panic!("{:?}", pano.projection) };
    let Panorama::Equirectangular { latitude_deg, longitude_deg } = panorama else { panic!("{panorama:?}") };
    let close = |a: [f32; 2], b: [f32; 2]| (a[0] - b[0]).abs() < 1e-4 && (a[1] - b[1]).abs() < 1e-4;
    assert!(close(latitude_deg, [-30.0, 60.0]) && close(longitude_deg, [-120.0, 75.0]), "{panorama:?}");
    let dof = pano.depth_of_field.expect("depth of field");
    assert_eq!((lens_mm, dof.fstop, dof.focus_distance), (24.0, 1.4, 2.0));
}

/// Each lamp's type, colour, power (exposure and "Normalize" folded in), shape and
/// placement, against the raw Blender values.
fn check_lights(scene: &Scene, expected: &Value) {
    use rt::scene::{AreaShape, LightShape};
    assert_eq!(scene.lights.len(), 4, "one [[light]] per lamp");
    let close =
        |a: f32, b: f64, what: &str| assert!((f64::from(a) - b).abs() < 1e-4 * b.abs().max(1.0), "{what}: {a} vs {b}");
    // Lamps are exported in name order: area, point, spot, sun.
    for (light, name) in scene.lights.iter().zip(["area", "point", "spot", "sun"]) {
        let e = &expected[name];
        let f = |k: &str| e[k].as_f64().unwrap_or_else(|| panic!("{name}.{k}"));
        let m = e["matrix_world"].as_array().expect("matrix");
        let column = |c: usize| y_up(&Value::from((0..3).map(|r| m[r][c].clone()).collect::<Vec<_>>()));
        assert!(light.position().distance(column(3)) < 1e-5, "{name}: at {}", light.position());
        let shines = -column(2).normalize();
        assert!(light.direction().distance(shines) < 1e-5, "{name}: shines along {}", light.direction());
        for (got, want) in light.color.to_array().iter().zip(e["color"].as_array().expect("colour")) {
            close(*got, want.as_f64().expect("number"), &format!("{name} colour"));
        }
        let mut power = f("energy") * 2f64.powf(f("exposure"));
        if !e["normalize"].as_bool().expect("normalize") {
            // Cycles' area of an area lamp: the sizes times the object's scale.
            power *= f("size") * column(0).length() as f64 * f("size_y") * column(1).length() as f64;
        }
        close(light.power, power, &format!("{name} power"));
        assert_eq!(light.visible_to_camera, e["visible_camera"].as_bool().expect("visibility"), "{name}");
        match (name, light.shape) {
            ("point", LightShape::Point { radius, soft_falloff }) => {
                close(radius, f("radius"), "point radius");
                assert!(soft_falloff);
            }
            ("spot", LightShape::Spot { radius, soft_falloff, size_deg, blend }) => {
                close(radius, f("radius"), "spot radius");
                assert!(!soft_falloff);
                close(size_deg, f("spot_size").to_degrees(), "spot size");
                close(blend, f("spot_blend"), "spot blend");
            }
            ("area", LightShape::Area { shape, size, size_y }) => {
                assert_eq!(shape, AreaShape::Rectangle);
                close(size, f("size"), "area size");
                close(size_y, f("size_y"), "area size_y");
            }
            ("sun", LightShape::Sun { angle_deg }) => close(angle_deg, f("angle").to_degrees(), "sun angle"),
            (name, shape) => panic!("{name} exported as {shape:?}"),
        }
    }
}

fn live_export_writes_only_what_changed(python: &Path, script: &Path, out: &Path) {
    run(Command::new(python).arg(script).arg("live").arg(out));
    let live: Value = serde_json::from_str(&std::fs::read_to_string(out.join("live.json")).expect("live.json"))
        .expect("live.json parses");
    assert_eq!(live["first"].as_array().map(Vec::len), Some(9), "the first save exports everything: {live}");
    // Both planes use the edited material; they share one asset, so one file changes.
    assert_eq!(live["changed"], serde_json::json!(["plane", "plane_twin"]), "{live}");
    let second = live["second"].as_array().expect("second");
    assert_eq!(second.len(), 1, "after a material edit only its .gltf is rewritten: {live}");
    assert!(second[0].as_str().is_some_and(|p| p.ends_with("plane/plane.gltf")), "{live}");
}
