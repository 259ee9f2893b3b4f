//! Panoramic cameras on the GPU: each camera ray from the trace program's
//! `generate_camera_rays` goes in a direction that Cycles' inverse mapping
//! (`direction_to_panorama`) takes back into the ray's own pixel, pixels outside a
//! fisheye's image get no ray, and with depth of field each ray starts on Cycles'
//! aperture set across the pinhole ray (its u axis towards the view) and meets that ray
//! on the sphere in focus.

use crate::camera_lens::{corners, inside};
use crate::common;

use common::{gpu, scene_from};
use glam::{Vec2, Vec3};
use rt::bvh::BuildQuality;
use rt::gpu::read_buffer;
use rt::layout::GpuTraceRay;
use rt::render::{RenderRequest, Session};
use rt::scene::{Camera, Panorama, Projection};

const CAMERA: &str = "position = [0.5, 1, -2]\nlook_at = [2, 1.7, -3]\nup = [0.3, 1, 0.1]";
/// A lens shift (not for the whole sphere, which it would move past a pole).
const SHIFT: &str = "shift_x = 0.04\nshift_y = -0.07";

/// The camera and its rays, one per pixel, rows from the top.
fn camera_rays(keys: &str, (width, height): (u32, u32)) -> (Camera, f32, Vec<GpuTraceRay>) {
    let scene = scene_from(&format!("[camera]\n{CAMERA}\n{keys}\n[[sphere]]\ncenter = [0, 0, -4]\nradius = 1\n"));
    let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let mut request = RenderRequest::from_scene(session.scene());
    (request.width, request.height) = (width, height);
    session.set_request(&request).unwrap_or_else(|e| panic!("{e:#}"));
    let io = session.trace_buffers(&vec![GpuTraceRay::default(); (width * height) as usize]);
    session.trace_pass(&io, "generate_camera_rays", 0, None).unwrap_or_else(|e| panic!("{e:#}"));
    let rays = read_buffer(gpu(), &io.rays).unwrap_or_else(|e| panic!("{e:#}"));
    (session.scene().camera.clone(), session.frame().aperture_radius, rays)
}

/// Cycles' `direction_to_panorama` for a unit direction in rt's camera frame (x right,
/// y up, z along the view): the point of Cycles' screen, [0, 1]² with v up.
fn screen_point(panorama: Panorama, d: Vec3, sensor_mm: Vec2) -> Vec2 {
    let towards = Vec2::new(d.x, d.y).normalize_or_zero();
    match panorama {
        Panorama::Equirectangular { latitude_deg: [lat_min, lat_max], longitude_deg: [lon_min, lon_max] } => {
            let (longitude, latitude) = (d.x.atan2(d.z).to_degrees(), d.y.asin().to_degrees());
            Vec2::new((longitude - lon_min) / (lon_max - lon_min), (latitude - lat_min) / (lat_max - lat_min))
        }
        Panorama::FisheyeEquidistant { fov_deg } => {
            let r = 2.0 * d.z.clamp(-1.0, 1.0).acos() / fov_deg.to_radians();
            towards * r * 0.5 + 0.5
        }
        Panorama::FisheyeEquisolid { lens_mm, .. } => {
            let r = 2.0 * lens_mm * (0.5 * d.z.clamp(-1.0, 1.0).acos()).sin();
            towards * r / sensor_mm + 0.5
        }
        Panorama::MirrorBall => {
            // The ball's normal n gives d = 2 (n·i) n − i: its x and z over 2 (n·i).
            let s = ((d.z + 1.0) * 0.5).max(0.0).sqrt();
            (Vec2::new(d.x, d.y) / (2.0 * s.max(1e-6)) + 1.0) * 0.5
        }
    }
}

/// Checks that every ray with a direction lands back in its pixel, and returns how many
/// pixels got no ray.
fn check_pixels(keys: &str, size: (u32, u32)) -> usize {
    let (camera, _, rays) = camera_rays(keys, size);
    let Projection::Panoramic { panorama, .. } = camera.projection else { panic!("{keys}: not a panorama") };
    let (right, up, forward) = camera.basis();
    let sensor = camera.fisheye_sensor_mm(size.0, size.1);
    let mut none = 0;
    for (i, ray) in rays.iter().enumerate() {
        let direction = Vec3::from(ray.direction);
        let expected = Vec2::new((i as u32 % size.0) as f32, (i as u32 / size.0) as f32);
        if direction == Vec3::ZERO {
            // Cycles sends no ray there; rt's pixel centre agrees (up to pixels the edge crosses).
            none += 1;
            continue;
        }
        assert!(Vec3::from(ray.origin).distance(camera.position) < 1e-5, "{keys}: ray {i} starts elsewhere");
        let d = Vec3::new(direction.dot(right), direction.dot(up), direction.dot(forward));
        let uv = screen_point(panorama, d, sensor) - camera.shift;
        let mut pixel = Vec2::new(uv.x, 1.0 - uv.y) * Vec2::new(size.0 as f32, size.1 as f32);
        if let Panorama::Equirectangular { longitude_deg: [min, max], .. } = panorama {
            // Longitudes come back in (−180°, 180°]: a shifted image's edge lies a turn away.
            let turn = size.0 as f32 * 360.0 / (max - min);
            pixel.x -= ((pixel.x - expected.x - 0.5) / turn).round() * turn;
        }
        let within = pixel - expected;
        assert!(
            within.min_element() > -2e-3 && within.max_element() < 1.0 + 2e-3,
            "{keys}: ray {i} of pixel {expected} goes to {pixel}"
        );
    }
    none
}

#[test]
fn panorama_rays_land_in_their_own_pixels() {
    let whole = "projection = \"equirectangular\"\nshift_x = 0.04";
    assert_eq!(check_pixels(whole, (48, 24)), 0);
    let window = format!(
        "projection = \"equirectangular\"\nlatitude_min_deg = -20\nlatitude_max_deg = 70\n\
         longitude_min_deg = -150\nlongitude_max_deg = 40\n{SHIFT}"
    );
    assert_eq!(check_pixels(&window, (48, 24)), 0);
    // The fisheyes and the ball leave the corners of the image black.
    let (w, h) = (40, 24);
    for keys in [
        "projection = \"fisheye_equidistant\"\nfisheye_fov_deg = 230",
        "projection = \"fisheye_equisolid\"\nfisheye_fov_deg = 180\nfisheye_lens_mm = 8",
        "projection = \"fisheye_equisolid\"\nfisheye_fov_deg = 150\nfisheye_lens_mm = 10\nsensor_fit = \"vertical\"",
        "projection = \"mirror_ball\"",
    ] {
        let none = check_pixels(&format!("{keys}\n{SHIFT}"), (w, h));
        assert!(none > 0 && none < (w * h * 3 / 4) as usize, "{keys}: {none} pixels without a ray");
    }
}

#[test]
fn panorama_depth_of_field_is_cycles_aperture_across_each_ray() {
    let (blades, rotation) = (5, 25.0);
    let keys = format!(
        "projection = \"equirectangular\"\nfocal_length_mm = 40\nfstop = 0.5\nfocus_distance = 3\n\
         blades = {blades}\nblade_rotation_deg = {rotation}\n{SHIFT}"
    );
    let (camera, radius, rays) = camera_rays(&keys, (48, 24));
    assert!((radius - 0.04).abs() < 1e-7, "aperture radius {radius}: Cycles' lens / (2 fstop)");
    let forward = camera.basis().2;
    let corners = corners(blades, rotation, 1.0);
    let mut points = Vec::new();
    for (i, ray) in rays.iter().enumerate() {
        let (origin, direction) = (Vec3::from(ray.origin) - camera.position, Vec3::from(ray.direction));
        // Where the ray meets the sphere in focus (origin inside it): the pinhole ray's end.
        let b = origin.dot(direction);
        let t = -b + (b * b - origin.length_squared() + 9.0).sqrt();
        let pinhole = (origin + direction * t) / 3.0;
        assert!(origin.dot(pinhole).abs() < 1e-4, "ray {i}: the aperture is not across the ray");
        // Cycles' axes across the ray: u towards the view, v = the ray × u (Cycles' camera
        // space goes onto Blender's camera by a rotation).
        let u = (forward - forward.dot(pinhole) * pinhole).normalize();
        let v = pinhole.cross(u);
        let lens = Vec2::new(origin.dot(u), origin.dot(v)) / radius;
        assert!(inside(lens, &corners, 1e-3), "ray {i}: {lens} is outside the aperture's polygon");
        points.push(lens);
    }
    for c in &corners {
        let near = points.iter().filter(|p| p.distance(*c) < 0.3).count();
        assert!(near >= 3, "{near} samples near the corner {c}");
    }
}
