//! The camera's basis for the GPU.

use crate::layout::GpuFrame;
use crate::scene::Camera;
use glam::Vec3;

/// Fills the camera fields of `frame` for an image of `width`×`height`.
pub fn set_camera(frame: &mut GpuFrame, camera: &Camera, width: u32, height: u32) {
    let forward = (camera.look_at - camera.position).normalize();
    // Looking straight up or down, world up gives no right vector: use −Z then.
    let world_up = if forward.cross(Vec3::Y).length_squared() < 1e-12 { Vec3::NEG_Z } else { Vec3::Y };
    let right = forward.cross(world_up).normalize();
    let up = right.cross(forward);
    frame.camera_position = camera.position.to_array();
    frame.camera_forward = forward.to_array();
    frame.camera_right = right.to_array();
    frame.camera_up = up.to_array();
    frame.tan_half_fov_y = (camera.fov_y_deg.to_radians() * 0.5).tan();
    frame.aspect = width as f32 / height as f32;
    frame.width = width;
    frame.height = height;
}
