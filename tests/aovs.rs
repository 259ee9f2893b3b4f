//! AOVs: the albedo and normal a denoiser is guided by, and the depth, as Open Image
//! Denoise expects them: from the first surface that is not a perfect mirror.

use crate::common;

use common::{gpu, scene_from, temp_dir};
use rt::bvh::BuildQuality;
use rt::render::{Aovs, Image, RenderRequest, Session};

/// A quad of side 40 at height `y`, facing +Y (or −Y with `down`), as OBJ text.
fn quad(y: f32, down: bool) -> String {
    let order = if down { "f 1 4 3 2" } else { "f 1 2 3 4" };
    format!("v -20 {y} -20\nv -20 {y} 20\nv 20 {y} 20\nv 20 {y} -20\n{order}\n")
}

fn render_with_aovs(text: &str, spp: u32) -> (Image, Aovs) {
    let mut session = Session::open(gpu(), scene_from(text), BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let request =
        RenderRequest { width: 32, height: 32, spp, aovs: true, ..RenderRequest::from_scene(session.scene()) };
    let (image, _) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    let aovs = session.aovs().unwrap_or_else(|e| panic!("{e:#}"));
    assert!(session.pipeline_features().aovs, "the pipeline that ran has no AOVs");
    (image, aovs)
}

/// The camera 1 m above a plane at y = 0, looking straight down.
const CAMERA_DOWN: &str =
    "[camera]\nposition = [0.0, 1.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, -1.0]\nfov_y_deg = 40.0\n";

#[test]
fn a_white_diffuse_plane_has_albedo_one_and_its_normal() {
    let dir = temp_dir("aov-plane");
    std::fs::write(dir.join("plane.obj"), quad(0.0, false)).expect("write");
    let text = format!(
        "{CAMERA_DOWN}[sky]\nkind = \"uniform\"\ncolor = [0.5, 0.5, 0.5]\n\
         [materials.white]\nbase_color = [1.0, 1.0, 1.0]\n[[mesh]]\nasset = {:?}\nmaterial = \"white\"\n",
        dir.join("plane.obj").display().to_string()
    );
    let (image, aovs) = render_with_aovs(&text, 4);
    let half_angle = 20f32.to_radians();
    for (i, ((albedo, normal), depth)) in aovs.albedo.iter().zip(&aovs.normal).zip(&aovs.depth).enumerate() {
        // A cosine-sampled Lambertian lobe's weight is its albedo exactly: no noise to allow for.
        for c in 0..3 {
            assert!((albedo[c] - 1.0).abs() < 1e-4, "pixel {i}: albedo {albedo:?}, not 1");
        }
        assert!(
            (normal[1] - 1.0).abs() < 1e-4 && normal[0].abs() < 1e-4 && normal[2].abs() < 1e-4,
            "pixel {i}: normal {normal:?}"
        );
        // Every ray meets the plane between 1 m (straight down) and the corner's slant.
        let corner = (1.0 + 2.0 * half_angle.tan().powi(2)).sqrt();
        assert!((1.0 - 1e-4..=corner + 1e-3).contains(depth), "pixel {i}: depth {depth}");
    }
    let centre = (16 * 32 + 16) as usize;
    assert!((aovs.depth[centre] - 1.0).abs() < 0.01, "centre depth {}", aovs.depth[centre]);
    assert!(image.sample_counts.iter().all(|&n| n == 4), "sample counts {:?}", &image.sample_counts[..4]);
}

/// Cycles' Position and Emission passes: where each camera ray met the scene, and the
/// light it saw emitted there, averaged over the pixel's samples.
#[test]
fn position_and_emission_are_where_the_camera_met_the_scene_and_what_it_saw_emitted() {
    let dir = temp_dir("aov-position");
    std::fs::write(dir.join("plane.obj"), quad(0.0, false)).expect("write");
    let text = format!(
        "{CAMERA_DOWN}[materials.glow]\nbase_color = [0.0, 0.0, 0.0]\nemission = [2.0, 1.0, 0.5]\n\
         [[mesh]]\nasset = {:?}\nmaterial = \"glow\"\n",
        dir.join("plane.obj").display().to_string()
    );
    let (image, aovs) = render_with_aovs(&text, 4);
    let reach = 20f32.to_radians().tan();
    for (i, (position, emission)) in aovs.position.iter().zip(&aovs.emission).enumerate() {
        let (x, y) = (i % 32, i / 32);
        assert!(position[1].abs() < 1e-5, "pixel {i}: the plane is at y = 0, not {position:?}");
        // The view is 2·tan(20°) across at 1 m: each pixel's mean lies inside its footprint.
        let expected_x = (2.0 * (x as f32 + 0.5) / 32.0 - 1.0) * reach;
        let expected_z = (2.0 * (y as f32 + 0.5) / 32.0 - 1.0) * reach;
        let footprint = reach / 32.0;
        assert!((position[0] - expected_x).abs() <= footprint, "pixel {i}: x {} vs {expected_x}", position[0]);
        assert!((position[2] - expected_z).abs() <= footprint, "pixel {i}: z {} vs {expected_z}", position[2]);
        for (c, want) in [2.0f32, 1.0, 0.5].into_iter().enumerate() {
            assert!((emission[c] - want).abs() < 1e-5 * want, "pixel {i}: emission {emission:?}");
            // The camera sees nothing but the emission: the image is the Emission pass.
            assert!((image.pixels[i][c] - want).abs() < 1e-5 * want, "pixel {i}: radiance {:?}", image.pixels[i]);
        }
    }
}

#[test]
fn albedo_seen_through_a_mirror_is_the_reflected_surface_s() {
    let dir = temp_dir("aov-mirror");
    std::fs::write(dir.join("mirror.obj"), quad(0.0, false)).expect("write");
    std::fs::write(dir.join("ceiling.obj"), quad(2.0, true)).expect("write");
    let text = format!(
        "{CAMERA_DOWN}[sky]\nkind = \"uniform\"\ncolor = [0.5, 0.5, 0.5]\n\
         [materials.mirror]\ndiffuse = 0.0\nreflection = 1.0\n\
         [materials.red]\nbase_color = [0.8, 0.2, 0.1]\n\
         [[mesh]]\nasset = {:?}\nmaterial = \"mirror\"\n[[mesh]]\nasset = {:?}\nmaterial = \"red\"\n",
        dir.join("mirror.obj").display().to_string(),
        dir.join("ceiling.obj").display().to_string()
    );
    let (_, aovs) = render_with_aovs(&text, 4);
    for (i, (albedo, normal)) in aovs.albedo.iter().zip(&aovs.normal).enumerate() {
        for (c, want) in [0.8, 0.2, 0.1].into_iter().enumerate() {
            assert!((albedo[c] - want).abs() < 1e-3, "pixel {i}: albedo {albedo:?}, not the red ceiling's");
        }
        // The ceiling faces the mirror, and so the ray that met it.
        assert!((normal[1] + 1.0).abs() < 1e-3, "pixel {i}: normal {normal:?}, not the ceiling's");
    }
    // Depth is the first surface's: the mirror's, 1 m below the camera.
    let centre = (16 * 32 + 16) as usize;
    assert!((aovs.depth[centre] - 1.0).abs() < 0.01, "centre depth {}", aovs.depth[centre]);
}

#[test]
fn aovs_leave_the_radiance_unchanged_and_are_absent_unless_asked() {
    let scene = rt::scene::load(&common::repo().join("scenes/cornell_glass.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let plain = RenderRequest { width: 24, height: 24, spp: 4, seed: 3, ..RenderRequest::from_scene(session.scene()) };
    let (without, _) = session.render(&plain, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(!session.pipeline_features().aovs);
    assert!(session.aovs().is_err(), "AOVs read from a render that did not ask for them");
    let (with, _) = session.render(&RenderRequest { aovs: true, ..plain }, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(without.pixels, with.pixels, "asking for AOVs changed the image");
    let aovs = session.aovs().unwrap_or_else(|e| panic!("{e:#}"));
    // The box's walls are diffuse: some albedo is coloured, every pixel's is in [0, 1].
    assert!(aovs.albedo.iter().flatten().all(|v| (0.0..=1.0).contains(v)));
    assert!(aovs.albedo.iter().any(|a| a[0] > a[1] + 0.2), "no red wall in the albedo");
}

#[test]
fn rt_render_aovs_writes_one_multilayer_exr_with_named_channels() {
    let dir = temp_dir("aov-exr");
    let out = dir.join("aovs.exr");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "--size", "16x12", "--spp", "2", "--aovs", "-o"])
        .arg(&out)
        .status()
        .expect("run rt");
    assert!(status.success());
    let image = exr::prelude::read_all_flat_layers_from_file(&out).expect("read the EXR");
    let layer = &image.layer_data[0];
    assert_eq!((layer.size.0, layer.size.1), (16, 12));
    let names: Vec<String> = layer.channel_data.list.iter().map(|c| c.name.to_string()).collect();
    for want in [
        "R",
        "G",
        "B",
        "albedo.R",
        "albedo.G",
        "albedo.B",
        "normal.X",
        "normal.Y",
        "normal.Z",
        "depth.Z",
        "position.X",
        "position.Y",
        "position.Z",
        "emission.R",
        "emission.G",
        "emission.B",
        "diffuse_color.R",
        "diffuse_color.G",
        "diffuse_color.B",
        "error.Y",
        "samples.Y",
    ] {
        assert!(names.iter().any(|n| n == want), "no {want} channel in {names:?}");
    }
    // A PNG cannot hold layers: refused before rendering.
    let png = std::process::Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "--size", "8x8", "--spp", "1", "--aovs", "-o"])
        .arg(dir.join("aovs.png"))
        .output()
        .expect("run rt");
    assert!(!png.status.success());
    assert!(String::from_utf8_lossy(&png.stderr).contains(".exr"), "{}", String::from_utf8_lossy(&png.stderr));
}
