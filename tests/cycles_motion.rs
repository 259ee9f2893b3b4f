//! Motion blur against Cycles (`tests/cycles/make_motion_refs.py`): objects and the camera
//! keyframed in Blender, exported over the shutter by `blender/rt_export.py`, rendered by
//! both within the noise of both renders (luminance per 8×8 block); and a scene that does
//! not move renders bit for bit as it does without the motion code.

use crate::common;

use common::reference::check_against_cycles;
use common::{render_request, repo};
use rt::scene::FeatureSet;

const REFERENCE_SPP: f64 = 1024.0;
const SPP: u32 = 128;

fn check(name: &str) {
    check_against_cycles(name, SPP, 8, REFERENCE_SPP);
}

/// A sphere sliding, a cube turning 150° (nine keys), one growing, one moving with its
/// Motion Blur off and one still, the shutter starting on the frame.
#[test]
fn moving_objects_blur_as_in_cycles() {
    check("motion_objects");
}

/// The camera panning and sliding, the shutter (half a frame) ending on the frame.
#[test]
fn a_moving_camera_blurs_as_in_cycles() {
    check("motion_camera");
}

/// The motion code (a time per sample, instances and the camera looked up at it) leaves a
/// scene that stands still exactly as it was: the time is a draw of its own, outside the
/// sample's other random numbers.
#[test]
fn a_still_scene_is_bit_for_bit_the_same_with_the_motion_code() {
    let load = || rt::scene::load(&repo().join("tests/cycles/scenes/motion_objects/scene.toml")).unwrap();
    let mut still = load();
    still.camera.motion = None;
    for mesh in &mut still.meshes {
        mesh.motion = None;
    }
    let size = |r: &mut rt::render::RenderRequest| (r.width, r.height, r.spp) = (48, 32, 4);
    let (plain, features) = render_request(still.clone(), size);
    assert!(!features.camera_motion && !features.object_motion, "a still scene's pipeline has no motion code");
    let with_motion = FeatureSet { camera_motion: true, object_motion: true, ..features };
    let (moving_code, _) = render_request(still, |r| {
        size(r);
        r.features = Some(with_motion);
    });
    assert!(plain.pixels == moving_code.pixels, "the motion code changed a still scene's image");
    let (blurred, features) = render_request(load(), size);
    assert!(features.object_motion && !features.camera_motion);
    assert!(blurred.pixels != plain.pixels, "the moving scene renders as the still one");
}

/// The light tree bounds each light where the frame has it: a scene whose emissive mesh moves
/// samples its lights by power instead (and says so), and renders.
#[test]
fn a_moving_light_is_sampled_by_power() {
    let mut scene = rt::scene::load(&repo().join("tests/cycles/scenes/motion_objects/scene.toml")).unwrap();
    scene.render.light_sampler = rt::scene::LightSampler::Tree;
    let glow = rt::scene::Material { emission: [4.0, 3.0, 2.0], ..Default::default() };
    scene.materials.push(("glow".into(), glow));
    let sphere = scene.meshes.iter_mut().find(|m| m.asset.ends_with("Sphere")).expect("the sphere");
    assert!(sphere.motion.is_some(), "the sphere moves");
    sphere.material = Some("glow".into());
    let (image, features) = render_request(scene, |r| (r.width, r.height, r.spp) = (48, 32, 4));
    assert!(features.object_motion && features.emission && !features.light_tree, "{features}");
    assert!(image.pixels.iter().all(|p| p.iter().all(|c| c.is_finite())));
}

/// An instance file's records move as `[[mesh]]` entries do: the moving sphere placed from
/// an `.rtinst` with its motion keys renders the very image of the scene file's.
#[test]
fn instance_files_carry_motion_as_the_scene_file_does() {
    use rt::asset::rtinst::{self, InstanceRecord, MaterialSets, OWN_MATERIALS};
    let dir = common::empty_temp_dir("instance-motion");
    let mut scene = rt::scene::load(&repo().join("tests/cycles/scenes/motion_objects/scene.toml")).unwrap();
    let size = |r: &mut rt::render::RenderRequest| (r.width, r.height, r.spp) = (48, 32, 4);
    let (from_mesh, _) = render_request(scene.clone(), size);
    let at = scene.meshes.iter().position(|m| m.asset.ends_with("Sphere")).expect("the sphere");
    let sphere = scene.meshes.remove(at);
    let motion = sphere.motion.as_ref().expect("the sphere moves");
    let rows: Vec<[f32; 12]> = motion.keys().iter().map(|m| InstanceRecord::new(m, OWN_MATERIALS).rows).collect();
    let file = dir.join("sphere.rtinst");
    let record = [InstanceRecord::new(&sphere.object_to_world, OWN_MATERIALS)];
    let bytes = rtinst::encode_moving(&record, &MaterialSets::default(), rows.len() as u32, &rows);
    std::fs::write(&file, bytes).expect("write the instance file");
    scene.instance_sets.push(rt::scene::InstanceSet {
        asset: sphere.asset.clone(),
        file,
        materials: vec![],
        shadow_terminator: sphere.shadow_terminator,
        holdout: false,
        info: sphere.info,
    });
    let (from_file, features) = render_request(scene, size);
    assert!(features.object_motion);
    let worst =
        from_mesh.pixels.iter().zip(&from_file.pixels).flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs()));
    let worst = worst.fold(0.0f32, f32::max);
    assert!(worst <= 1e-5, "the instance file's sphere differs from the scene file's by {worst}");
}

/// `rt info` says what moves.
#[test]
fn rt_info_says_what_moves() {
    let scene = repo().join("tests/cycles/scenes/motion_objects/scene.toml");
    let scene = scene.to_str().expect("a path");
    let info = common::bounded::rt(&repo(), &["info", scene], std::time::Duration::from_secs(300));
    info.expect("rt info", 0);
    let line = "motion     3 moving instances (765 matrices over the shutter), the camera in 0 keys";
    assert!(info.stdout.contains(line), "{}", info.stdout);
}
