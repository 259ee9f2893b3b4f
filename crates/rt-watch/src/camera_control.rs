//! Moving the viewer's camera: orbit about the point looked at, look around from where
//! the camera stands, pan, dolly, and fly. Each move takes a camera and gives the moved
//! one; the window decides which input makes which move.

use glam::Vec3;
use rt::scene::{Camera, Projection, Sun};

/// Radians per pixel of mouse drag.
const RADIANS_PER_PIXEL: f32 = 0.005;
/// Never quite straight up or down, where the view's roll is undefined.
const MAX_PITCH: f32 = 89.0_f32.to_radians();
/// Distance factor per wheel step.
const DOLLY_PER_STEP: f32 = 0.85;

/// Yaw (from +Z towards +X) and pitch (above the horizon) of a direction.
fn angles(direction: Vec3) -> (f32, f32) {
    let d = direction.normalize();
    (d.x.atan2(d.z), d.y.clamp(-1.0, 1.0).asin())
}

fn direction(yaw: f32, pitch: f32) -> Vec3 {
    Vec3::new(pitch.cos() * yaw.sin(), pitch.sin(), pitch.cos() * yaw.cos())
}

/// The direction `from` turned by a drag of (`dx`, `dy`) pixels, pitch kept off the poles.
fn turned(from: Vec3, dx: f32, dy: f32) -> Vec3 {
    let (yaw, pitch) = angles(from);
    direction(yaw - dx * RADIANS_PER_PIXEL, (pitch + dy * RADIANS_PER_PIXEL).clamp(-MAX_PITCH, MAX_PITCH))
}

/// Circles the camera about the point it looks at: the scene turns the way the mouse drags.
pub fn orbit(camera: &Camera, dx: f32, dy: f32) -> Camera {
    let offset = camera.position - camera.look_at;
    let position = camera.look_at + turned(offset, dx, dy) * offset.length();
    Camera { position, ..camera.clone() }
}

/// Turns the view from where the camera stands: dragging right looks right.
pub fn look(camera: &Camera, dx: f32, dy: f32) -> Camera {
    let view = camera.look_at - camera.position;
    let look_at = camera.position + turned(view, dx, -dy) * view.length();
    Camera { look_at, ..camera.clone() }
}

/// Slides camera and point looked at in the view plane, by `dx`, `dy` pixels of a
/// `width`×`height` image (so the point under the mouse follows it).
pub fn pan(camera: &Camera, dx: f32, dy: f32, width: u32, height: u32) -> Camera {
    let (right, up, _) = camera.basis();
    let plane_height = 2.0 * camera.view_plane(width, height).half_extent.y;
    // A perspective image plane is at distance 1: scale it out to the point looked at.
    let depth = match camera.projection {
        Projection::Orthographic { .. } => 1.0,
        _ => camera.position.distance(camera.look_at),
    };
    let metres_per_pixel = plane_height * depth / height.max(1) as f32;
    let shift = (-right * dx + up * dy) * metres_per_pixel;
    Camera { position: camera.position + shift, look_at: camera.look_at + shift, ..camera.clone() }
}

/// Moves towards the point looked at (positive steps) or away, never onto it.
pub fn dolly(camera: &Camera, steps: f32) -> Camera {
    let offset = camera.position - camera.look_at;
    let distance = (offset.length() * DOLLY_PER_STEP.powf(steps)).max(1e-3);
    Camera { position: camera.look_at + offset.normalize() * distance, ..camera.clone() }
}

/// Moves camera and point looked at by `along` (right, up, forward) metres, forward
/// being the view direction and up the world's.
pub fn fly(camera: &Camera, along: Vec3) -> Camera {
    let view = camera.look_at - camera.position;
    let (right, _) = basis(view);
    let shift = right * along.x + Vec3::Y * along.y + view.normalize() * along.z;
    Camera { position: camera.position + shift, look_at: camera.look_at + shift, ..camera.clone() }
}

/// Right and up of a view direction, as `render::set_camera` builds them.
fn basis(view: Vec3) -> (Vec3, Vec3) {
    let forward = view.normalize();
    let world_up = if forward.cross(Vec3::Y).length_squared() < 1e-12 { Vec3::NEG_Z } else { Vec3::Y };
    let right = forward.cross(world_up).normalize();
    (right, right.cross(forward))
}

/// The sun turned by `elevation` and `azimuth` degrees (elevation kept in [−90, 90]).
pub fn turn_sun(sun: &Sun, elevation: f32, azimuth: f32) -> Sun {
    Sun {
        elevation_deg: (sun.elevation_deg + elevation).clamp(-90.0, 90.0),
        azimuth_deg: (sun.azimuth_deg + azimuth).rem_euclid(360.0),
        ..sun.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera { position: Vec3::new(0.0, 1.0, 4.0), look_at: Vec3::new(0.0, 1.0, 0.0), ..Camera::default() }
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-4
    }

    #[test]
    fn orbit_keeps_the_distance_and_the_target() {
        let c = orbit(&camera(), 100.0, 40.0);
        assert!(close(c.look_at, camera().look_at));
        assert!(((c.position - c.look_at).length() - 4.0).abs() < 1e-4);
        assert!(c.position.x < 0.0 && c.position.y > 1.0, "{:?}", c.position);
        // A drag far past the pole stops short of it.
        let top = orbit(&camera(), 0.0, 1e6);
        assert!((top.position - top.look_at).normalize().y < 1.0);
    }

    #[test]
    fn look_keeps_the_position() {
        let c = look(&camera(), 50.0, 0.0);
        assert!(close(c.position, camera().position));
        assert!(c.look_at.x > 0.0, "dragging right looks right: {:?}", c.look_at);
    }

    #[test]
    fn pan_dolly_and_fly() {
        let c = pan(&camera(), 10.0, 0.0, 100, 100);
        assert!(close(c.position - camera().position, c.look_at - camera().look_at));
        assert!(c.position.x < 0.0);
        let c = dolly(&camera(), 1.0);
        assert!(((c.position - c.look_at).length() - 4.0 * DOLLY_PER_STEP).abs() < 1e-4);
        let c = fly(&camera(), Vec3::new(0.0, 0.0, 1.0));
        assert!(close(c.position, Vec3::new(0.0, 1.0, 3.0)) && close(c.look_at, Vec3::new(0.0, 1.0, -1.0)));
        let c = fly(&camera(), Vec3::new(1.0, 2.0, 0.0));
        assert!(close(c.position, Vec3::new(1.0, 3.0, 4.0)));
    }

    #[test]
    fn sun_turns_and_wraps() {
        let sun = Sun { elevation_deg: 89.0, azimuth_deg: 355.0, angular_diameter_deg: 0.53, radiance: None };
        let turned = turn_sun(&sun, 5.0, 10.0);
        assert_eq!((turned.elevation_deg, turned.azimuth_deg), (90.0, 5.0));
    }
}
