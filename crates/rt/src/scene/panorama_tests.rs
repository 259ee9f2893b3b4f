//! Panoramic cameras against Cycles' formulas, and their keys.

use super::*;
use crate::scene::{Camera, Projection, SensorFit};
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::{FRAC_PI_2, PI};

/// Cycles' kernel for the pixel centre (`px`, `py`) (rows from the top) of a
/// `width`×`height` image, written out from `projection.h`, `camera.h` and
/// `blender/camera.cpp` independently of `Panorama`: raster rows from the bottom, the
/// viewplane [0, 1]² moved by the shift, the mapping in Cycles' panoramic camera space,
/// then `blender_camera_matrix`'s axes onto Blender's camera (columns right, up and
/// back along the view, as `camera_matrix` gives them).
fn cycles_direction(camera: &Camera, px: u32, py: u32, width: u32, height: u32) -> Option<Vec3> {
    let Projection::Panoramic { panorama, .. } = camera.projection else { panic!("a panorama") };
    let raster = Vec2::new(px as f32 + 0.5, (height - 1 - py) as f32 + 0.5);
    let (u, v) = (camera.shift.x + raster.x / width as f32, camera.shift.y + raster.y / height as f32);
    let safe_acos = |x: f32| x.clamp(-1.0, 1.0).acos();
    let fisheye_to_direction = |theta: f32, u: f32, v: f32, r: f32| {
        let mut phi = safe_acos(if r != 0.0 { u / r } else { 0.0 });
        if v < 0.0 {
            phi = -phi;
        }
        Vec3::new(theta.cos(), -phi.cos() * theta.sin(), phi.sin() * theta.sin())
    };
    let d = match panorama {
        Panorama::Equirectangular { latitude_deg, longitude_deg } => {
            let [lat_min, lat_max] = latitude_deg.map(f32::to_radians);
            let [lon_min, lon_max] = longitude_deg.map(f32::to_radians);
            let range = [lon_min - lon_max, -lon_min, lat_min - lat_max, -lat_min + FRAC_PI_2];
            let (phi, theta) = (range[0] * u + range[1], range[2] * v + range[3]);
            Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
        }
        Panorama::FisheyeEquidistant { fov_deg } => {
            let (u, v) = ((u - 0.5) * 2.0, (v - 0.5) * 2.0);
            let r = (u * u + v * v).sqrt();
            if r > 1.0 {
                return None;
            }
            fisheye_to_direction(r * fov_deg.to_radians() * 0.5, u, v, r)
        }
        Panorama::FisheyeEquisolid { fov_deg, lens_mm } => {
            // `blender_camera_sync`'s panorama sensor.
            let horizontal = match camera.sensor_fit {
                SensorFit::Auto => width > height,
                SensorFit::Horizontal => true,
                SensorFit::Vertical => false,
            };
            let size = if camera.sensor_fit == SensorFit::Vertical { camera.sensor_mm.y } else { camera.sensor_mm.x };
            let (w, h) = (width as f32, height as f32);
            let (sw, sh) = if horizontal { (size, size * h / w) } else { (size * w / h, size) };
            let (u, v) = ((u - 0.5) * sw, (v - 0.5) * sh);
            let r = (u * u + v * v).sqrt();
            if r > 2.0 * lens_mm * (fov_deg.to_radians() * 0.25).sin() {
                return None;
            }
            fisheye_to_direction(2.0 * (r / (2.0 * lens_mm)).asin(), u, v, r)
        }
        Panorama::MirrorBall => {
            let (x, z) = (2.0 * u - 1.0, 2.0 * v - 1.0);
            if x * x + z * z > 1.0 {
                return None;
            }
            let dir = Vec3::new(x, -(1.0 - x * x - z * z).max(0.0).sqrt(), z);
            let i = Vec3::new(0.0, -1.0, 0.0);
            2.0 * dir.dot(i) * dir - i
        }
    };
    // `make_transform`'s rows, onto Blender's camera axes.
    let rows = match panorama {
        Panorama::MirrorBall => Mat3::from_cols(Vec3::X, Vec3::Z, Vec3::Y).transpose(),
        _ => Mat3::from_cols(Vec3::new(0.0, -1.0, 0.0), Vec3::Z, Vec3::NEG_X).transpose(),
    };
    let local = rows * d;
    let (right, up, forward) = camera.basis();
    Some((right * local.x + up * local.y - forward * local.z).normalize())
}

fn panoramic(panorama: Panorama) -> Camera {
    Camera {
        position: Vec3::new(0.5, 1.0, -2.0),
        look_at: Vec3::new(2.0, 1.7, -3.0),
        up: Some(Vec3::new(0.3, 1.0, 0.1)),
        projection: Projection::Panoramic { panorama, lens_mm: 50.0 },
        shift: Vec2::new(0.04, -0.07),
        ..Camera::default()
    }
}

#[test]
fn pixel_centres_look_where_cycles_looks() {
    let cameras = [
        panoramic(Panorama::Equirectangular { latitude_deg: [-90.0, 90.0], longitude_deg: [-180.0, 180.0] }),
        panoramic(Panorama::Equirectangular { latitude_deg: [-20.0, 70.0], longitude_deg: [-150.0, 40.0] }),
        panoramic(Panorama::FisheyeEquidistant { fov_deg: 230.0 }),
        panoramic(Panorama::FisheyeEquisolid { fov_deg: 180.0, lens_mm: 8.0 }),
        Camera {
            sensor_fit: SensorFit::Vertical,
            ..panoramic(Panorama::FisheyeEquisolid { fov_deg: 150.0, lens_mm: 6.0 })
        },
        panoramic(Panorama::MirrorBall),
    ];
    for camera in cameras {
        for (width, height) in [(24, 12), (10, 16)] {
            let (mut rays, mut none) = (0, 0);
            for py in 0..height {
                for px in 0..width {
                    let ours = camera.pixel_ray(px as f32 + 0.5, py as f32 + 0.5, width, height);
                    let expected = cycles_direction(&camera, px, py, width, height);
                    match (ours, expected) {
                        (Some((origin, d)), Some(e)) => {
                            assert!(
                                origin == camera.position && d.distance(e) < 1e-5,
                                "{camera:?} ({px}, {py}): {d} vs {e}"
                            );
                            rays += 1;
                        }
                        (None, None) => none += 1,
                        _ => panic!("{camera:?} ({px}, {py}) of {width}x{height}: {ours:?} vs Cycles' {expected:?}"),
                    }
                }
            }
            assert!(rays > 0, "{camera:?}: no ray");
            let whole_sphere =
                matches!(camera.projection, Projection::Panoramic { panorama: Panorama::Equirectangular { .. }, .. });
            assert_eq!(none == 0, whole_sphere, "{camera:?}: {none} pixels without a ray");
        }
    }
}

#[test]
fn the_image_centre_looks_along_the_view() {
    let camera = Camera {
        shift: Vec2::ZERO,
        ..panoramic(Panorama::Equirectangular { latitude_deg: [-90.0, 90.0], longitude_deg: [-180.0, 180.0] })
    };
    let (right, up, forward) = camera.basis();
    let ray = |x: f32, y: f32| camera.pixel_ray(x, y, 40, 20).expect("a ray").1;
    assert!(ray(20.0, 10.0).distance(forward) < 1e-6);
    // A quarter turn right of the centre, the top, the back.
    assert!(ray(30.0, 10.0).distance(right) < 1e-6, "{}", ray(30.0, 10.0));
    assert!(ray(20.0, 0.0).distance(up) < 1e-6);
    assert!(ray(0.0, 10.0).distance(-forward) < 1e-6);
    let ball = Camera { shift: Vec2::ZERO, ..panoramic(Panorama::MirrorBall) };
    let ray = |x: f32, y: f32| ball.pixel_ray(x, y, 40, 40).map(|r| r.1);
    assert!(ray(20.0, 20.0).is_some_and(|d| d.distance(forward) < 1e-6));
    assert!(ray(0.5, 0.5).is_none());
    // Half way out the ball's normal is 30° from the camera's: the ray turns 60° away.
    let half_way = ray(30.0, 20.0).expect("a ray");
    assert!((half_way.angle_between(forward) - PI / 3.0).abs() < 1e-5 && half_way.dot(right) > 0.0);
}

fn parse_camera(text: &str) -> Result<Camera, String> {
    let text = format!("[camera]\n{}\n", text.split('|').map(str::trim).collect::<Vec<_>>().join("\n"));
    crate::scene::parse(&text, "scene.toml", std::path::Path::new("/")).map(|s| s.camera).map_err(|e| e.to_string())
}

fn panorama_of(text: &str) -> Result<(Panorama, f32), String> {
    match parse_camera(text)?.projection {
        Projection::Panoramic { panorama, lens_mm } => Ok((panorama, lens_mm)),
        other => Err(format!("{other:?}")),
    }
}

#[test]
fn panoramic_keys_parse_with_blenders_defaults() {
    let whole = Panorama::Equirectangular { latitude_deg: [-90.0, 90.0], longitude_deg: [-180.0, 180.0] };
    assert_eq!(panorama_of("projection = \"equirectangular\""), Ok((whole, 50.0)));
    let window = "projection = \"equirectangular\" | latitude_min_deg = -30 | latitude_max_deg = 60 | \
                  longitude_min_deg = -120 | longitude_max_deg = 75 | fstop = 2 | focal_length_mm = 35";
    let expected = Panorama::Equirectangular { latitude_deg: [-30.0, 60.0], longitude_deg: [-120.0, 75.0] };
    assert_eq!(panorama_of(window), Ok((expected, 35.0)));
    assert_eq!(
        panorama_of("projection = \"fisheye_equidistant\" | fisheye_fov_deg = 220"),
        Ok((Panorama::FisheyeEquidistant { fov_deg: 220.0 }, 50.0))
    );
    assert_eq!(
        panorama_of("projection = \"fisheye_equisolid\""),
        Ok((Panorama::FisheyeEquisolid { fov_deg: 180.0, lens_mm: 10.5 }, 50.0))
    );
    assert_eq!(panorama_of("projection = \"mirror_ball\""), Ok((Panorama::MirrorBall, 50.0)));
}

#[test]
fn bad_panoramic_keys_are_located() {
    let equirect = "projection = \"equirectangular\"";
    for (text, expected) in [
        (
            &format!("{equirect} | latitude_min_deg = 40 | latitude_max_deg = 10") as &str,
            "scene.toml:4:20: [camera]: latitude_max_deg must be above latitude_min_deg (40), got 10",
        ),
        (
            &format!("{equirect} | longitude_min_deg = 180"),
            "scene.toml:3:21: [camera]: longitude_min_deg must be below longitude_max_deg (180), got 180",
        ),
        (
            &format!("{equirect} | latitude_max_deg = 91"),
            "scene.toml:3:20: [camera]: latitude_max_deg must be in [-90, 90], got 91",
        ),
        (
            &format!("{equirect} | longitude_min_deg = -190"),
            "scene.toml:3:21: [camera]: longitude_min_deg must be in [-180, 180], got -190",
        ),
        (
            &format!("{equirect} | latitude_min_deg = nan"),
            "scene.toml:3:20: [camera]: latitude_min_deg must be finite, got NaN",
        ),
        (
            "latitude_min_deg = 10",
            "scene.toml:2:20: [camera]: latitude_min_deg only applies to projection = \"equirectangular\"",
        ),
        (
            "projection = \"mirror_ball\" | fisheye_fov_deg = 90",
            "scene.toml:3:19: [camera]: fisheye_fov_deg only applies to a fisheye projection",
        ),
        (
            "projection = \"fisheye_equidistant\" | fisheye_lens_mm = 8",
            "scene.toml:3:19: [camera]: fisheye_lens_mm only applies to projection = \"fisheye_equisolid\"",
        ),
        (
            "projection = \"fisheye_equidistant\" | fisheye_fov_deg = 0",
            "scene.toml:3:19: [camera]: fisheye_fov_deg must be in (0, 1800], got 0",
        ),
        (
            "projection = \"fisheye_equisolid\" | fisheye_lens_mm = -1",
            "scene.toml:3:19: [camera]: fisheye_lens_mm must be positive, got -1",
        ),
        (
            &format!("{equirect} | fov_y_deg = 90"),
            "scene.toml:3:13: [camera]: fov_y_deg only applies to projection = \"perspective\"",
        ),
        (
            &format!("{equirect} | focal_length_mm = 35"),
            "scene.toml:3:19: [camera]: focal_length_mm only applies to a panorama with fstop (its aperture)",
        ),
        (
            "projection = \"equirectangle\"",
            "scene.toml:2:14: [camera]: unknown projection `equirectangle`; did you mean `equirectangular`?",
        ),
        (
            &format!("{equirect} | latitude_min = -10"),
            "scene.toml:3:1: unknown key `latitude_min` in [camera]; did you mean `latitude_min_deg`?",
        ),
    ] {
        assert_eq!(parse_camera(text).map(|_| ()), Err(expected.to_owned()), "{text}");
    }
}
