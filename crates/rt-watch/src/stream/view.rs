//! A camera from what a 3D viewport knows: its view matrix (world to camera, the camera
//! looking down its −Z with +Y up, as OpenGL and Blender have it) and its lens, given
//! as Blender's camera settings or as the viewport's projection matrix, and its thin lens
//! when it has depth of field.

use glam::{Mat4, Vec2, Vec3, Vec4};
use rt::scene::{Camera, DepthOfField, MAX_BLADES, Projection, SensorFit};

/// How the camera projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lens {
    /// Millimetres over the sensor (Blender's `lens`).
    FocalLength(f32),
    /// Vertical field of view in degrees.
    FovY(f32),
    /// Orthographic: metres of view along the sensor fit (Blender's `ortho_scale`).
    Orthographic(f32),
    /// An OpenGL projection matrix (Blender's `RegionView3D.window_matrix`): perspective or
    /// orthographic, with an off-centre window (lens shift, a zoomed camera view) allowed.
    Matrix(Mat4),
}

/// Depth of field as a viewport knows it. A viewport's projection matrix changes with its
/// zoom, so the aperture comes as its size, not as an f-number over a focal length that
/// the matrix would imply: Cycles' aperture size, the scene camera's focal length over
/// twice its f-number (1 m over twice it, orthographic).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aperture {
    /// The aperture's radius in metres.
    pub radius: f32,
    /// Metres along the view to the plane in focus.
    pub focus_distance: f32,
    /// 0: round; else a regular polygon of this many sides.
    pub blades: u32,
    pub blade_rotation_deg: f32,
    /// Anamorphic bokeh: the aperture's height over its width.
    pub ratio: f32,
}

impl Aperture {
    /// The scene's depth of field that gives this aperture on a camera of `projection`:
    /// rt's renderer takes the f-number, and the aperture is half the focal length over it.
    fn depth_of_field(&self, projection: Projection) -> Result<DepthOfField, String> {
        let aperture_diameter = match projection {
            // A panorama's aperture is sized by its camera's ordinary lens, as in Cycles.
            Projection::FocalLength { mm } | Projection::Panoramic { lens_mm: mm, .. } => mm * 1e-3,
            Projection::Orthographic { .. } => 1.0,
            Projection::FovY { .. } => {
                return Err("aperture= needs lens=, ortho= or projection= (with fov= the focal length \
                            depends on the image's size)"
                    .into());
            }
        };
        if self.blades == 1 || self.blades == 2 || self.blades > MAX_BLADES {
            return Err(format!("blades must be 0 (round) or in 3..={MAX_BLADES}, not {}", self.blades));
        }
        Ok(DepthOfField {
            fstop: 0.5 * aperture_diameter / self.radius,
            focus_distance: self.focus_distance,
            blades: self.blades,
            blade_rotation_deg: self.blade_rotation_deg,
            aperture_ratio: self.ratio,
        })
    }
}

/// The view matrix of a camera at `position` looking at `target` with world +Y up.
pub fn look_at(position: Vec3, target: Vec3) -> Mat4 {
    let forward = (target - position).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    Mat4::from_cols(
        Vec4::new(right.x, up.x, -forward.x, 0.0),
        Vec4::new(right.y, up.y, -forward.y, 0.0),
        Vec4::new(right.z, up.z, -forward.z, 0.0),
        Vec4::new(-right.dot(position), -up.dot(position), forward.dot(position), 1.0),
    )
}

/// How far a matrix entry that must be 0 or 1 may stray (float noise of Blender's matrices).
const TOLERANCE: f32 = 1e-4;

fn near(a: Vec4, b: Vec4) -> bool {
    (a - b).abs().max_element() <= TOLERANCE * a.abs().max_element().max(1.0)
}

/// What a camera command says besides its view matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Optics {
    pub lens: Lens,
    /// Sensor width and height in millimetres.
    pub sensor: Vec2,
    pub fit: SensorFit,
    /// In units of the view's extent along the fit, as Blender's `shift_x`/`shift_y`; it adds
    /// to a projection matrix's own.
    pub shift: Vec2,
    /// `None`: a pinhole.
    pub aperture: Option<Aperture>,
}

impl Default for Optics {
    /// Blender's default camera: a 50 mm lens over a 36×24 mm sensor, a pinhole.
    fn default() -> Self {
        Self {
            lens: Lens::FocalLength(50.0),
            sensor: Vec2::new(36.0, 24.0),
            fit: SensorFit::Auto,
            shift: Vec2::ZERO,
            aperture: None,
        }
    }
}

/// The camera `view` and `optics` describe.
pub fn camera_from_view(view: Mat4, optics: Optics) -> Result<Camera, String> {
    let Optics { lens, sensor, fit, shift, aperture } = optics;
    if !near(view.row(3), Vec4::W) {
        return Err("view: the last row must be 0,0,0,1 (a rigid world-to-camera matrix)".into());
    }
    let det = view.determinant();
    if !det.is_finite() || det <= 1e-12 {
        return Err(format!("view: determinant {det}: not a rotation and a translation"));
    }
    let to_world = view.inverse();
    let position = to_world.transform_point3(Vec3::ZERO);
    let forward = to_world.transform_vector3(Vec3::NEG_Z).normalize();
    let up = to_world.transform_vector3(Vec3::Y).normalize();
    if up.cross(forward).length_squared() < 1e-6 {
        return Err("view: the camera's up is along its view direction".into());
    }
    let mut camera = Camera {
        position,
        look_at: position + forward,
        up: Some(up),
        sensor_fit: fit,
        sensor_mm: sensor,
        shift,
        depth_of_field: None,
        ..Camera::default()
    };
    camera.projection = match lens {
        Lens::FocalLength(mm) => Projection::FocalLength { mm },
        Lens::FovY(degrees) => Projection::FovY { degrees },
        Lens::Orthographic(scale) => Projection::Orthographic { scale },
        Lens::Matrix(p) => {
            let (projection, window_shift) = from_projection_matrix(p, sensor.x)?;
            camera.sensor_fit = SensorFit::Horizontal;
            camera.shift += window_shift;
            projection
        }
    };
    camera.depth_of_field = aperture.map(|a| a.depth_of_field(camera.projection)).transpose()?;
    Ok(camera)
}

/// The projection and lens shift of an OpenGL projection matrix, with the view's width
/// spanning a sensor `sensor_width` mm wide. With x_ndc = sx·x + cx, rt's view plane is
/// 1/sx wide each side of its centre −cx/sx, a shift of −cx/2 in units of its width 2/sx.
fn from_projection_matrix(p: Mat4, sensor_width: f32) -> Result<(Projection, Vec2), String> {
    let (r0, r1) = (p.row(0), p.row(1));
    if r0.y.abs() > TOLERANCE * r0.x.abs() || r1.x.abs() > TOLERANCE * r1.y.abs() {
        return Err("projection: a skewed projection is not a camera".into());
    }
    let (sx, sy) = (r0.x, r1.y);
    if !(sx > 0.0 && sy > 0.0) {
        return Err(format!("projection: scales {sx} and {sy} must be positive"));
    }
    let perspective = near(p.row(3), Vec4::new(0.0, 0.0, -1.0, 0.0));
    let orthographic = near(p.row(3), Vec4::W);
    // Where the window's centre is in NDC: perspective, x_ndc = sx·x/(−z) − cx (the third
    // column, times z, divided by w = −z); orthographic, x_ndc = sx·x + cx (the fourth).
    let (cx, cy) = match (perspective, orthographic) {
        (true, _) => (-r0.z, -r1.z),
        (_, true) => (r0.w, r1.w),
        _ => return Err("projection: the last row must be 0,0,-1,0 (perspective) or 0,0,0,1 (orthographic)".into()),
    };
    let shift = Vec2::new(-cx / 2.0, -cy * sx / (2.0 * sy));
    let projection = if perspective {
        Projection::FocalLength { mm: 0.5 * sensor_width * sx }
    } else {
        Projection::Orthographic { scale: 2.0 / sx }
    };
    Ok((projection, shift))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An OpenGL frustum (glFrustum) with near plane 0.1.
    fn frustum(left: f32, right: f32, bottom: f32, top: f32) -> Mat4 {
        let n = 0.1;
        Mat4::from_cols(
            Vec4::new(2.0 * n / (right - left), 0.0, 0.0, 0.0),
            Vec4::new(0.0, 2.0 * n / (top - bottom), 0.0, 0.0),
            Vec4::new((right + left) / (right - left), (top + bottom) / (top - bottom), -1.001, -1.0),
            Vec4::new(0.0, 0.0, -0.2, 0.0),
        )
    }

    /// An OpenGL orthographic projection (glOrtho), depth from 0.1 to 100.
    fn ortho(left: f32, right: f32, bottom: f32, top: f32) -> Mat4 {
        Mat4::from_cols(
            Vec4::new(2.0 / (right - left), 0.0, 0.0, 0.0),
            Vec4::new(0.0, 2.0 / (top - bottom), 0.0, 0.0),
            Vec4::new(0.0, 0.0, -2.0 / 99.9, 0.0),
            Vec4::new(-(right + left) / (right - left), -(top + bottom) / (top - bottom), -100.1 / 99.9, 1.0),
        )
    }

    /// The camera's pinhole ray through pixel (x, y) meets the frustum's near plane where
    /// the matrix's inverse says it does.
    fn check_rays(camera: &Camera, p: Mat4, view: Mat4, (w, h): (u32, u32)) {
        for (x, y) in [(0.0, 0.0), (w as f32, 0.0), (0.3 * w as f32, 0.8 * h as f32), (w as f32, h as f32)] {
            let (origin, dir) = camera.pixel_ray(x, y, w, h).expect("a ray");
            let ndc = Vec2::new(2.0 * x / w as f32 - 1.0, 1.0 - 2.0 * y / h as f32);
            let eye = p.inverse().project_point3(Vec3::new(ndc.x, ndc.y, -1.0));
            let world = view.inverse().transform_point3(eye);
            let expected = (world - view.inverse().transform_point3(Vec3::ZERO)).normalize();
            assert!((dir - expected).length() < 1e-4, "pixel ({x}, {y}): {dir} vs {expected}");
            assert!((origin - camera.position).length() < 1e-5);
        }
    }

    #[test]
    fn a_viewport_projection_gives_the_same_rays() {
        let view = look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.0, 0.5, 0.0));
        // Off-centre, as a zoomed and panned camera view in Blender is; 4:3 like the image.
        let p = frustum(-0.05, 0.09, -0.04, 0.065);
        let camera = camera_from_view(view, Optics { lens: Lens::Matrix(p), ..Optics::default() }).expect("a camera");
        check_rays(&camera, p, view, (140, 105));
        let (_, up, forward) = camera.basis();
        assert!((forward - (Vec3::new(0.0, 0.5, 0.0) - Vec3::new(1.0, 2.0, 3.0)).normalize()).length() < 1e-5);
        assert!(up.y > 0.0);
    }

    #[test]
    fn an_orthographic_projection_gives_parallel_rays_over_its_window() {
        let view = look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO);
        let p = ortho(-2.0, 4.0, -1.5, 3.0);
        let camera = camera_from_view(view, Optics { lens: Lens::Matrix(p), ..Optics::default() }).expect("a camera");
        assert_eq!(camera.projection, Projection::Orthographic { scale: 6.0 });
        let (origin, dir) = camera.pixel_ray(0.0, 0.0, 60, 45).expect("a ray");
        assert!((dir - Vec3::NEG_Z).length() < 1e-6);
        assert!((origin - Vec3::new(-2.0, 3.0, 5.0)).length() < 1e-4, "{origin}");
    }

    #[test]
    fn matrices_that_are_no_camera_are_refused() {
        let optics = Optics::default();
        let squashed = Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0));
        assert!(camera_from_view(squashed, optics).unwrap_err().contains("determinant"));
        let projective = frustum(-0.1, 0.1, -0.1, 0.1);
        assert!(camera_from_view(projective, optics).unwrap_err().contains("last row"));
        let mut skewed = frustum(-0.1, 0.1, -0.1, 0.1);
        skewed.y_axis.x = 0.5;
        let err = camera_from_view(Mat4::IDENTITY, Optics { lens: Lens::Matrix(skewed), ..optics }).unwrap_err();
        assert!(err.contains("skewed"), "{err}");
    }

    /// The renderer's aperture radius (from the f-number) is the one the command gave,
    /// whatever the viewport's zoom makes of the focal length.
    #[test]
    fn an_aperture_renders_at_its_own_radius() {
        let aperture = Aperture { radius: 0.02, focus_distance: 3.5, blades: 6, blade_rotation_deg: 30.0, ratio: 1.5 };
        let view = look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO);
        for lens in [
            Lens::FocalLength(35.0),
            Lens::Matrix(frustum(-0.05, 0.09, -0.04, 0.065)),
            Lens::Matrix(frustum(-0.02, 0.02, -0.015, 0.015)),
            Lens::Orthographic(4.0),
            Lens::Matrix(ortho(-2.0, 4.0, -1.5, 3.0)),
        ] {
            let camera = camera_from_view(view, Optics { lens, aperture: Some(aperture), ..Optics::default() })
                .expect("a camera");
            let mut frame = rt::layout::GpuFrame::default();
            rt::render::set_camera(&mut frame, &camera, 140, 105);
            assert!((frame.aperture_radius - 0.02).abs() < 1e-7, "{lens:?}: radius {}", frame.aperture_radius);
            assert_eq!((frame.focus_distance, frame.aperture_blades, frame.inv_aperture_ratio), (3.5, 6, 1.0 / 1.5));
            assert!((frame.blade_rotation - 30f32.to_radians()).abs() < 1e-6);
        }
        let by_angle = Optics { lens: Lens::FovY(40.0), aperture: Some(aperture), ..Optics::default() };
        assert!(camera_from_view(view, by_angle).unwrap_err().contains("aperture= needs lens=, ortho= or projection="));
        let two_blades = Optics { aperture: Some(Aperture { blades: 2, ..aperture }), ..Optics::default() };
        assert_eq!(camera_from_view(view, two_blades).unwrap_err(), "blades must be 0 (round) or in 3..=16, not 2");
    }
}
