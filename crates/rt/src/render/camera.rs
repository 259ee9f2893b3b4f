//! The camera's fields of the frame constants: its basis, its image plane (Blender's
//! sensor fit, focal length or orthographic scale, and lens shift) and its aperture
//! (Cycles' thin lens), and a panorama's mapping.

use crate::layout::{
    GpuFrame, PANORAMA_EQUIRECTANGULAR, PANORAMA_FISHEYE_EQUIDISTANT, PANORAMA_FISHEYE_EQUISOLID, PANORAMA_MIRROR_BALL,
    PANORAMA_NONE,
};
use crate::scene::{Camera, Panorama, Projection};

/// Fills the camera fields of `frame` for an image of `width`×`height`.
pub fn set_camera(frame: &mut GpuFrame, camera: &Camera, width: u32, height: u32) {
    let (right, up, forward) = camera.basis();
    let plane = camera.view_plane(width, height);
    frame.camera_position = camera.position.to_array();
    frame.camera_forward = forward.to_array();
    frame.camera_right = right.to_array();
    frame.camera_up = up.to_array();
    frame.camera_motion_steps = 0;
    if let Some(motion) = &camera.motion {
        frame.camera_motion_steps = motion.keys().len() as u32;
        for (slot, key) in frame.camera_motion.iter_mut().zip(motion.decomposed()) {
            *slot = key.into();
        }
    }
    frame.view_half_extent = plane.half_extent.to_array();
    frame.view_shift = plane.shift.to_array();
    frame.orthographic = u32::from(matches!(camera.projection, Projection::Orthographic { .. }));
    frame.width = width;
    frame.height = height;
    frame.clip_start = camera.clip_start;
    // The shader's INFINITY, f32's largest: no far plane.
    frame.clip_end = camera.clip_end.min(f32::MAX);
    frame.panorama = PANORAMA_NONE;
    if let Projection::Panoramic { panorama, .. } = camera.projection {
        frame.panorama = match panorama {
            Panorama::Equirectangular { .. } => PANORAMA_EQUIRECTANGULAR,
            Panorama::FisheyeEquidistant { .. } => PANORAMA_FISHEYE_EQUIDISTANT,
            Panorama::FisheyeEquisolid { .. } => PANORAMA_FISHEYE_EQUISOLID,
            Panorama::MirrorBall => PANORAMA_MIRROR_BALL,
        };
        frame.equirectangular_range = panorama.equirectangular_range();
        frame.fisheye_sensor = camera.fisheye_sensor_mm(width, height).to_array();
        frame.fisheye_fov = panorama.fisheye_fov();
        if let Panorama::FisheyeEquisolid { lens_mm, .. } = panorama {
            frame.fisheye_lens = lens_mm;
        }
    }
    // A pinhole, also for a pipeline that carries the lens code anyway (all features):
    // no aperture, and a plane in focus at any positive distance.
    frame.inv_aperture_ratio = 1.0;
    frame.focus_distance = 1.0;
    if let Some(dof) = &camera.depth_of_field {
        // Cycles (`blender_camera_from_object`): the aperture's radius is half the focal
        // length over the f-number; an orthographic camera has no focal length and uses 1 m.
        let aperture_diameter = match camera.projection {
            Projection::Orthographic { .. } => 1.0,
            _ => camera.focal_length_mm(width, height) * 1e-3,
        };
        frame.aperture_radius = 0.5 * aperture_diameter / dof.fstop;
        frame.focus_distance = dof.focus_distance;
        frame.aperture_blades = dof.blades;
        frame.blade_rotation = dof.blade_rotation_deg.to_radians();
        frame.inv_aperture_ratio = 1.0 / dof.aperture_ratio;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::DepthOfField;

    #[test]
    fn aperture_follows_cycles() {
        let dof =
            DepthOfField { fstop: 2.0, focus_distance: 3.0, blades: 6, blade_rotation_deg: 90.0, aperture_ratio: 2.0 };
        let camera =
            Camera { projection: Projection::FocalLength { mm: 50.0 }, depth_of_field: Some(dof), ..Camera::default() };
        let mut frame = GpuFrame::default();
        set_camera(&mut frame, &camera, 64, 64);
        assert!((frame.aperture_radius - 0.0125).abs() < 1e-7, "{}", frame.aperture_radius);
        assert_eq!((frame.aperture_blades, frame.inv_aperture_ratio), (6, 0.5));
        assert!((frame.blade_rotation - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
        // The same view given by its angle has the same focal length, so the same aperture.
        let half = camera.view_plane(64, 64).half_extent.y;
        let by_angle = Camera { projection: Projection::FovY { degrees: 2.0 * half.atan().to_degrees() }, ..camera };
        set_camera(&mut frame, &by_angle, 64, 64);
        assert!((frame.aperture_radius - 0.0125).abs() < 1e-6, "{}", frame.aperture_radius);
        let ortho = Camera { projection: Projection::Orthographic { scale: 2.0 }, ..by_angle };
        set_camera(&mut frame, &ortho, 64, 64);
        assert!((frame.aperture_radius - 0.25).abs() < 1e-7 && frame.orthographic == 1);
        let mut pinhole = GpuFrame::default();
        set_camera(&mut pinhole, &Camera::default(), 64, 64);
        assert!(pinhole.aperture_radius == 0.0 && pinhole.focus_distance > 0.0, "{pinhole:?}");
    }
}
