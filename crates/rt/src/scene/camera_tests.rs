//! The camera's image plane, aperture and roll against Blender's and Cycles' definitions.

use super::*;
use glam::{Vec2, Vec3};

fn close(a: Vec2, b: Vec2) -> bool {
    (a - b).abs().max_element() < 1e-6
}

#[test]
fn sensor_fit_and_shift_follow_blender() {
    // 50 mm on 36 mm, landscape: the width spans the sensor, shift in units of the width.
    let camera =
        Camera { projection: Projection::FocalLength { mm: 50.0 }, shift: Vec2::new(0.1, -0.2), ..Camera::default() };
    let p = camera.view_plane(200, 100);
    assert!(close(p.half_extent, Vec2::new(0.36, 0.18)), "{p:?}");
    assert!(close(p.shift, Vec2::new(0.072, -0.144)), "{p:?}");
    // Portrait under AUTO: the sensor's width now spans the height.
    let p = camera.view_plane(100, 200);
    assert!(close(p.half_extent, Vec2::new(0.18, 0.36)), "{p:?}");
    // VERTICAL uses the sensor's height along the image's height.
    let vertical = Camera { sensor_fit: SensorFit::Vertical, ..camera.clone() };
    let p = vertical.view_plane(200, 100);
    assert!(close(p.half_extent, Vec2::new(0.48, 0.24)), "{p:?}");
    let ortho = Camera { projection: Projection::Orthographic { scale: 4.0 }, ..camera };
    let p = ortho.view_plane(200, 100);
    assert!(close(p.half_extent, Vec2::new(2.0, 1.0)) && close(p.shift, Vec2::new(0.4, -0.8)), "{p:?}");
}

#[test]
fn vertical_angle_holds_whatever_the_fit() {
    let camera = Camera { projection: Projection::FovY { degrees: 90.0 }, ..Camera::default() };
    for fit in [SensorFit::Auto, SensorFit::Horizontal, SensorFit::Vertical] {
        let p = Camera { sensor_fit: fit, ..camera.clone() }.view_plane(300, 100);
        assert!(close(p.half_extent, Vec2::new(3.0, 1.0)), "{fit:?}: {p:?}");
    }
}

#[test]
fn up_rolls_the_camera() {
    let camera = Camera { position: Vec3::ZERO, look_at: Vec3::NEG_Z, up: Some(Vec3::X), ..Camera::default() };
    let (right, up, forward) = camera.basis();
    assert!((right - Vec3::NEG_Y).length() < 1e-6 && (up - Vec3::X).length() < 1e-6, "{right} {up}");
    assert!((forward - Vec3::NEG_Z).length() < 1e-6);
}

fn parse_camera(text: &str) -> Result<Camera, String> {
    let text = format!("[camera]\n{}\n", text.split('|').map(str::trim).collect::<Vec<_>>().join("\n"));
    crate::scene::parse(&text, "scene.toml", std::path::Path::new("/")).map(|s| s.camera).map_err(|e| e.to_string())
}

/// Cycles' `xratio`/`yratio`: a 100×100 image of pixels twice as wide as high shows the
/// picture of a 200×100 image of square pixels, fit and all.
#[test]
fn pixel_aspect_widens_the_picture_as_in_cycles() {
    for projection in [Projection::FocalLength { mm: 35.0 }, Projection::FovY { degrees: 50.0 }] {
        for fit in [SensorFit::Auto, SensorFit::Horizontal, SensorFit::Vertical] {
            let square = Camera { projection, sensor_fit: fit, shift: Vec2::new(0.1, 0.2), ..Camera::default() };
            let wide = Camera { pixel_aspect: Vec2::new(2.0, 1.0), ..square.clone() };
            assert_eq!(wide.view_plane(100, 100), square.view_plane(200, 100), "{fit:?}");
            let tall = Camera { pixel_aspect: Vec2::new(1.0, 3.0), ..square.clone() };
            assert_eq!(tall.view_plane(90, 30), square.view_plane(90, 90), "{fit:?}");
        }
    }
    let message = parse_camera("pixel_aspect = [1, 0]").expect_err("a zero aspect");
    assert!(message.contains("pixel_aspect") && message.contains("positive"), "{message}");
}

#[test]
fn every_key_parses() {
    let text = "position = [1, 2, 3] | look_at = [1, 2, 0] | up = [1, 1, 0] | focal_length_mm = 35 | \
                sensor_fit = \"vertical\" | sensor_width_mm = 30 | sensor_height_mm = 20 | shift_x = 0.1 | \
                shift_y = -0.25 | fstop = 2.8 | focus_distance = 4 | blades = 6 | blade_rotation_deg = 15 | \
                aperture_ratio = 1.5 | clip_start = 0.25 | clip_end = 80 | pixel_aspect = [2, 1]";
    let expected = Camera {
        position: Vec3::new(1.0, 2.0, 3.0),
        look_at: Vec3::new(1.0, 2.0, 0.0),
        up: Some(Vec3::new(1.0, 1.0, 0.0)),
        projection: Projection::FocalLength { mm: 35.0 },
        sensor_fit: SensorFit::Vertical,
        sensor_mm: Vec2::new(30.0, 20.0),
        shift: Vec2::new(0.1, -0.25),
        pixel_aspect: Vec2::new(2.0, 1.0),
        depth_of_field: Some(DepthOfField {
            fstop: 2.8,
            focus_distance: 4.0,
            blades: 6,
            blade_rotation_deg: 15.0,
            aperture_ratio: 1.5,
        }),
        clip_start: 0.25,
        clip_end: 80.0,
        motion: None,
    };
    assert_eq!(parse_camera(text), Ok(expected));
    let unclipped = parse_camera("").expect("valid");
    assert_eq!((unclipped.clip_start, unclipped.clip_end), (0.0, f32::INFINITY));
    let ortho = parse_camera("projection = \"orthographic\" | ortho_scale = 3").expect("valid");
    assert_eq!(ortho.projection, Projection::Orthographic { scale: 3.0 });
    assert_eq!(
        parse_camera("projection = \"orthographic\"").map(|c| c.projection),
        Ok(Projection::Orthographic { scale: 6.0 })
    );
    // Focused on the point looked at unless told otherwise; round and unsqueezed.
    let dof = parse_camera("position = [0, 0, 3] | look_at = [0, 0, 0] | fstop = 4").expect("valid").depth_of_field;
    let round =
        DepthOfField { fstop: 4.0, focus_distance: 3.0, blades: 0, blade_rotation_deg: 0.0, aperture_ratio: 1.0 };
    assert_eq!(dof, Some(round));
}

#[test]
fn bad_camera_keys_are_located() {
    for (text, expected) in [
        ("fstop = 0", "scene.toml:2:9: [camera]: fstop must be positive, got 0"),
        ("clip_start = -0.1", "scene.toml:2:14: [camera]: clip_start must be at least 0, got -0.1"),
        ("clip_start = 2 | clip_end = 2", "scene.toml:3:12: [camera]: clip_end must be beyond clip_start (2), got 2"),
        ("clip_end = inf", "scene.toml:2:12: [camera]: clip_end must be finite, got inf"),
        ("fstop = -1.4", "scene.toml:2:9: [camera]: fstop must be positive, got -1.4"),
        ("fstop = nan", "scene.toml:2:9: [camera]: fstop must be finite, got NaN"),
        ("fstop = 2 | focus_distance = 0", "scene.toml:3:18: [camera]: focus_distance must be positive, got 0"),
        ("fstop = 2 | blades = 2", "scene.toml:3:10: [camera]: blades must be 0 (round) or in 3..=16, got 2"),
        ("fstop = 2 | aperture_ratio = 0", "scene.toml:3:18: [camera]: aperture_ratio must be positive, got 0"),
        (
            "fstop = 2 | blade_rotation_deg = inf",
            "scene.toml:3:22: [camera]: blade_rotation_deg must be finite, got inf",
        ),
        ("blades = 6", "scene.toml:2:10: [camera]: blades only applies with fstop (depth of field)"),
        ("focus_distance = 3", "scene.toml:2:18: [camera]: focus_distance only applies with fstop (depth of field)"),
        ("focal_length_mm = 0", "scene.toml:2:19: [camera]: focal_length_mm must be positive, got 0"),
        (
            "fov_y_deg = 40 | focal_length_mm = 50",
            "scene.toml:3:19: [camera]: focal_length_mm excludes fov_y_deg: give one",
        ),
        ("ortho_scale = 2", "scene.toml:2:15: [camera]: ortho_scale only applies to projection = \"orthographic\""),
        (
            "projection = \"orthographic\" | fov_y_deg = 30",
            "scene.toml:3:13: [camera]: fov_y_deg only applies to projection = \"perspective\"",
        ),
        (
            "projection = \"orthographic\" | ortho_scale = -1",
            "scene.toml:3:15: [camera]: ortho_scale must be positive, got -1",
        ),
        ("sensor_width_mm = 0", "scene.toml:2:19: [camera]: sensor_width_mm must be positive, got 0"),
        ("shift_x = nan", "scene.toml:2:11: [camera]: shift_x must be finite, got NaN"),
        (
            "position = [0, 0, 3] | look_at = [0, 0, 0] | up = [0, 0, 2]",
            "scene.toml:4:6: [camera]: up must be a direction not along the view (look_at − position)",
        ),
        ("up = [0, 0, 0]", "scene.toml:2:6: [camera]: up must be a direction not along the view (look_at − position)"),
        (
            "projection = \"ortho\"",
            "scene.toml:2:14: [camera]: unknown projection `ortho`; expected one of `perspective`, `orthographic`, \
             `equirectangular`, `fisheye_equidistant`, `fisheye_equisolid`, `mirror_ball`",
        ),
        (
            "sensor_fit = \"horizontl\"",
            "scene.toml:2:14: [camera]: unknown sensor_fit `horizontl`; did you mean `horizontal`?",
        ),
        ("f_stop = 2", "scene.toml:2:1: unknown key `f_stop` in [camera]; did you mean `fstop`?"),
        (
            "focus_distanse = 2",
            "scene.toml:2:1: unknown key `focus_distanse` in [camera]; did you mean `focus_distance`?",
        ),
        ("shift = 0.1", "scene.toml:2:1: unknown key `shift` in [camera]; did you mean `shift_x`?"),
    ] {
        assert_eq!(parse_camera(text), Err(expected.to_owned()), "{text}");
    }
}

#[test]
fn pixel_rays_cross_the_image_plane() {
    let camera =
        Camera { position: Vec3::ZERO, look_at: Vec3::NEG_Z, shift: Vec2::new(0.25, 0.0), ..Camera::default() };
    let half = camera.view_plane(100, 50).half_extent;
    // The centre looks along the view, moved by the shift: a quarter of the width (the fit side).
    let (origin, direction) = camera.pixel_ray(50.0, 25.0, 100, 50).expect("a ray");
    let expected = Vec3::new(0.5 * half.x, 0.0, -1.0).normalize();
    assert!(origin == Vec3::ZERO && direction.distance(expected) < 1e-6, "{direction} vs {expected}");
    let ortho = Camera { projection: Projection::Orthographic { scale: 2.0 }, ..camera };
    let (origin, direction) = ortho.pixel_ray(0.0, 0.0, 100, 50).expect("a ray");
    assert!(origin.distance(Vec3::new(-0.5, 0.5, 0.0)) < 1e-6 && direction == Vec3::NEG_Z, "{origin} {direction}");
}

#[test]
fn focus_is_along_the_view_or_for_a_panorama_along_the_ray() {
    let camera = Camera { position: Vec3::ZERO, look_at: Vec3::NEG_Z, ..Camera::default() };
    let slanted = Vec3::new(0.6, 0.0, -0.8);
    // The plane in focus is across the view: a point 5 m out along a slanted ray is 4 m deep.
    assert!((camera.focus_distance_of(slanted, 5.0) - 4.0).abs() < 1e-6);
    let panorama =
        Camera { projection: Projection::Panoramic { panorama: Panorama::MirrorBall, lens_mm: 50.0 }, ..camera };
    assert_eq!(panorama.focus_distance_of(slanted, 5.0), 5.0);
}
