//! The thin lens on the GPU: camera rays from the trace program's `generate_camera_rays`
//! start on the aperture Cycles would sample (a disk, or the regular polygon with corners at
//! rotation + (2k + 1)π / blades, squeezed by the aperture ratio) and pass, where they meet
//! the plane in focus, through the pixel they belong to.

use crate::common;

use common::{gpu, scene_from};
use glam::{Vec2, Vec3};
use rt::bvh::BuildQuality;
use rt::gpu::read_buffer;
use rt::layout::GpuTraceRay;
use rt::render::{RenderRequest, Session};

const SIZE: u32 = 64;

/// Camera rays (one per pixel, rows from the top) of a camera at the origin looking down −Z.
fn camera_rays(lens: &str) -> (rt::scene::Camera, f32, Vec<GpuTraceRay>) {
    let scene = scene_from(&format!(
        "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nup = [0.3, 1, 0]\nfocal_length_mm = 50\n\
         focus_distance = 4\n{lens}\n[[sphere]]\ncenter = [0, 0, -4]\nradius = 1\n"
    ));
    let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let mut request = RenderRequest::from_scene(session.scene());
    (request.width, request.height) = (SIZE, SIZE);
    session.set_request(&request).unwrap_or_else(|e| panic!("{e:#}"));
    let io = session.trace_buffers(&vec![GpuTraceRay::default(); (SIZE * SIZE) as usize]);
    session.trace_pass(&io, "generate_camera_rays", 0, None).unwrap_or_else(|e| panic!("{e:#}"));
    let rays = read_buffer(gpu(), &io.rays).unwrap_or_else(|e| panic!("{e:#}"));
    (session.scene().camera.clone(), session.frame().aperture_radius, rays)
}

/// Each ray's start on the unit aperture (x right, y up), after checking that it passes
/// through its own pixel on the plane in focus.
fn lens_points(lens: &str) -> Vec<Vec2> {
    let (camera, radius, rays) = camera_rays(lens);
    let (right, up, forward) = camera.basis();
    let plane = camera.view_plane(SIZE, SIZE);
    let focus = camera.depth_of_field.expect("depth of field").focus_distance;
    rays.iter()
        .enumerate()
        .map(|(i, ray)| {
            let (origin, direction) = (Vec3::from(ray.origin), Vec3::from(ray.direction));
            let at = origin + direction * ((focus - origin.dot(forward)) / direction.dot(forward));
            // Back to the image plane at distance 1, then to pixels from the top left.
            let on_plane = (Vec2::new(at.dot(right), at.dot(up)) / focus - plane.shift) / plane.half_extent;
            let pixel = (Vec2::new(on_plane.x, -on_plane.y) + 1.0) * 0.5 * SIZE as f32;
            let expected = Vec2::new((i as u32 % SIZE) as f32, (i as u32 / SIZE) as f32);
            let inside = pixel - expected;
            assert!(inside.min_element() > -1e-2 && inside.max_element() < 1.0 + 1e-2, "ray {i} crosses pixel {pixel}");
            Vec2::new(origin.dot(right), origin.dot(up)) / radius
        })
        .collect()
}

/// Cycles' polygon: corners at `rotation + (2k + 1)π / n`, then x divided by `ratio`.
pub fn corners(n: u32, rotation_deg: f32, ratio: f32) -> Vec<Vec2> {
    (0..n)
        .map(|k| {
            let a = rotation_deg.to_radians() + (2 * k + 1) as f32 * std::f32::consts::PI / n as f32;
            Vec2::new(a.cos() / ratio, a.sin())
        })
        .collect()
}

/// Inside a convex polygon with counter-clockwise corners, within `slack`.
pub fn inside(p: Vec2, corners: &[Vec2], slack: f32) -> bool {
    (0..corners.len()).all(|k| {
        let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
        let edge = (b - a).normalize();
        edge.perp_dot(p - a) >= -slack
    })
}

#[test]
fn bladed_aperture_is_cycles_polygon_rotated_and_squeezed() {
    for (blades, rotation, ratio) in [(3, 0.0, 1.0), (3, 90.0, 1.0), (6, 20.0, 1.6), (5, -35.0, 0.7)] {
        let points = lens_points(&format!(
            "fstop = 2\nblades = {blades}\nblade_rotation_deg = {rotation}\naperture_ratio = {ratio}"
        ));
        let corners = corners(blades, rotation, ratio);
        for p in &points {
            assert!(inside(*p, &corners, 1e-4), "{blades} blades at {rotation}°, ratio {ratio}: {p} is outside");
        }
        // The samples fill the polygon: each corner has some close by.
        for c in &corners {
            let near = points.iter().filter(|p| p.distance(*c) < 0.2).count();
            assert!(near >= 3, "{blades} blades at {rotation}°, ratio {ratio}: {near} samples near the corner {c}");
        }
    }
}

#[test]
fn round_aperture_is_the_squeezed_disk_and_fills_it() {
    let points = lens_points("fstop = 2\naperture_ratio = 2");
    for p in &points {
        assert!(Vec2::new(p.x * 2.0, p.y).length() <= 1.0 + 1e-4, "{p} is outside the aperture");
    }
    // Uniform over the area: a quarter of the samples inside half the radius (4096 samples: σ ≈ 0.007).
    let inner = points.iter().filter(|p| Vec2::new(p.x * 2.0, p.y).length() < 0.5).count() as f32 / points.len() as f32;
    assert!((inner - 0.25).abs() < 0.03, "{inner} of the samples within half the radius");
    let widest = points.iter().map(|p| p.x.abs()).fold(0.0, f32::max);
    assert!(widest > 0.45 && widest <= 0.5 + 1e-4, "the aperture reaches x = {widest}, not 0.5");
}
