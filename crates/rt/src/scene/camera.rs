//! `[camera]`: Blender's camera. Where it stands and looks, its roll, its projection
//! (perspective by a vertical angle or by a focal length over a sensor; orthographic;
//! panoramic, see `panorama`), lens shift, and depth of field as Cycles models it: a thin
//! lens whose aperture is a disk or a regular polygon.

use super::panorama::{self, Panorama};
use super::parse::{SceneError, Seg, Seg::Key, Source};
use super::schema;
use glam::{Vec2, Vec3};
use serde::Deserialize;

/// Which side of the image the sensor (or the orthographic scale) spans: Blender's sensor fit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SensorFit {
    /// The larger side, spanned by the sensor's width.
    #[default]
    Auto,
    Horizontal,
    Vertical,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Perspective with this vertical field of view, whatever the sensor fit.
    FovY { degrees: f32 },
    /// Perspective from a focal length over the sensor's side along the fit (Blender's).
    FocalLength { mm: f32 },
    /// Parallel rays; `scale` metres of view along the fit (Blender's `ortho_scale`).
    Orthographic { scale: f32 },
    /// Rays from the camera's centre in every direction the panorama maps the image to.
    /// `lens_mm` is Blender's (perspective) `lens`, from which Cycles sizes the aperture.
    Panoramic { panorama: Panorama, lens_mm: f32 },
}

/// A thin lens focused at `focus_distance`, its aperture from the f-number as in Cycles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthOfField {
    pub fstop: f32,
    /// Metres from the camera to the plane in focus, along the view direction.
    pub focus_distance: f32,
    /// 0: a round aperture; else a regular polygon of this many sides (at least 3).
    pub blades: u32,
    pub blade_rotation_deg: f32,
    /// Anamorphic bokeh: the aperture's height over its width (Blender's `aperture_ratio`).
    pub aperture_ratio: f32,
}

/// `[camera]`; when the table or a key is left out: at `[0, 1, 5]` looking at
/// `[0, 1, 0]` with a 40° vertical field of view, no shift, no depth of field.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    pub look_at: Vec3,
    /// What is up in the image, made perpendicular to the view: the camera's roll.
    /// `None`: the world's +Y (−Z when looking straight up or down).
    pub up: Option<Vec3>,
    pub projection: Projection,
    pub sensor_fit: SensorFit,
    /// Sensor width and height in millimetres.
    pub sensor_mm: Vec2,
    /// Lens shift (x right, y up) in units of the view's extent along the fit.
    pub shift: Vec2,
    /// Blender's pixel aspect (x, y): a pixel's width and height in the picture, so that
    /// a `width`×`height` image shows a picture of `width·x` by `height·y`.
    pub pixel_aspect: Vec2,
    pub depth_of_field: Option<DepthOfField>,
    /// Cycles' clip_start and clip_end: camera rays see only what lies between these
    /// planes along the view (metres); `clip_end` may be infinite.
    pub clip_start: f32,
    pub clip_end: f32,
    /// Its frames over the shutter (`motion`; columns right, up, forward and position):
    /// motion blur. `None`: it stands still.
    pub motion: Option<super::Motion>,
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            position: Vec3::new(0.0, 1.0, 5.0),
            look_at: Vec3::Y,
            up: None,
            projection: Projection::FovY { degrees: DEFAULT_FOV_Y_DEG },
            sensor_fit: SensorFit::Auto,
            sensor_mm: Vec2::new(36.0, 24.0),
            shift: Vec2::ZERO,
            pixel_aspect: Vec2::ONE,
            depth_of_field: None,
            clip_start: 0.0,
            clip_end: f32::INFINITY,
            motion: None,
        }
    }
}

/// A camera's image plane for an image of a given size: half its extent and the offset of
/// its centre, at distance 1 along the view (perspective) or in metres (orthographic).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewPlane {
    pub half_extent: Vec2,
    pub shift: Vec2,
}

impl Camera {
    /// The picture's width and height in pixels of the image's height: the image's size
    /// times the pixel aspect (Cycles' `xratio`, `yratio`), which every fit and extent uses.
    fn picture(&self, width: u32, height: u32) -> (f32, f32) {
        (width.max(1) as f32 * self.pixel_aspect.x, height.max(1) as f32 * self.pixel_aspect.y)
    }

    /// Whether the sensor spans the image's width (else its height), as Blender decides.
    fn fits_horizontally(&self, width: u32, height: u32) -> bool {
        let (w, h) = self.picture(width, height);
        match self.sensor_fit {
            SensorFit::Auto => w > h,
            SensorFit::Horizontal => true,
            SensorFit::Vertical => false,
        }
    }

    /// The sensor's side along the fit: Blender's `AUTO` fits the width to the larger side.
    fn sensor_along_fit(&self) -> f32 {
        match self.sensor_fit {
            SensorFit::Vertical => self.sensor_mm.y,
            SensorFit::Auto | SensorFit::Horizontal => self.sensor_mm.x,
        }
    }

    /// Blender's viewplane (`blender_camera_viewplane` in Cycles): the fit side spans the
    /// sensor (or `ortho_scale`), the other follows the image's aspect, and the shift is in
    /// units of the fit side.
    ///
    /// A panorama's plane is Cycles' screen, [0, 1]² moved by the shift, about its centre:
    /// a half extent of 0.5, and the shift as it is.
    pub fn view_plane(&self, width: u32, height: u32) -> ViewPlane {
        let horizontal = self.fits_horizontally(width, height);
        let (w, h) = self.picture(width, height);
        let half_fit = match self.projection {
            Projection::FovY { degrees } => {
                let half_y = (degrees.to_radians() * 0.5).tan();
                if horizontal { half_y * w / h } else { half_y }
            }
            Projection::FocalLength { mm } => 0.5 * self.sensor_along_fit() / mm,
            Projection::Orthographic { scale } => 0.5 * scale,
            Projection::Panoramic { .. } => {
                return ViewPlane { half_extent: Vec2::splat(0.5), shift: self.shift };
            }
        };
        let half_extent =
            if horizontal { Vec2::new(half_fit, half_fit * h / w) } else { Vec2::new(half_fit * w / h, half_fit) };
        ViewPlane { half_extent, shift: self.shift * 2.0 * half_fit }
    }

    /// The focal length in millimetres that gives this view over the sensor (perspective);
    /// a panorama's `lens_mm`.
    pub fn focal_length_mm(&self, width: u32, height: u32) -> f32 {
        if let Projection::FocalLength { mm } | Projection::Panoramic { lens_mm: mm, .. } = self.projection {
            return mm;
        }
        let half = self.view_plane(width, height).half_extent;
        0.5 * self.sensor_along_fit() / if self.fits_horizontally(width, height) { half.x } else { half.y }
    }

    /// The sensor's width and height in millimetres as the equisolid fisheye sees it
    /// (Cycles' panorama sensor): the side along the fit spans the sensor, the other
    /// follows the image's aspect.
    pub fn fisheye_sensor_mm(&self, width: u32, height: u32) -> Vec2 {
        let (w, h) = self.picture(width, height);
        let size = self.sensor_along_fit();
        if self.fits_horizontally(width, height) {
            Vec2::new(size, size * h / w)
        } else {
            Vec2::new(size * w / h, size)
        }
    }

    /// The pinhole ray (origin, unit direction) through the point (`x`, `y`) of a
    /// `width`×`height` image, in pixels from its top left: the camera's ray without its
    /// lens. `None` where a panorama sends no ray (outside a fisheye's image).
    pub fn pixel_ray(&self, x: f32, y: f32, width: u32, height: u32) -> Option<(Vec3, Vec3)> {
        let (right, up, forward) = self.basis();
        let plane = self.view_plane(width, height);
        let ndc = Vec2::new(x / width.max(1) as f32, y / height.max(1) as f32) * 2.0 - 1.0;
        let at = Vec2::new(ndc.x, -ndc.y) * plane.half_extent + plane.shift;
        let across = right * at.x + up * at.y;
        match self.projection {
            Projection::Orthographic { .. } => Some((self.position + across, forward)),
            Projection::Panoramic { panorama, .. } => {
                let d = panorama.direction(at + 0.5, self.fisheye_sensor_mm(width, height))?;
                Some((self.position, (right * d.x + up * d.y + forward * d.z).normalize()))
            }
            _ => Some((self.position, (forward + across).normalize())),
        }
    }

    /// The focus distance that puts the point `t` along the unit `direction` from the
    /// camera in focus: Cycles' plane in focus is across the view (its distance along the
    /// view), a panorama's sphere in focus about the camera (its distance along the ray).
    pub fn focus_distance_of(&self, direction: Vec3, t: f32) -> f32 {
        match self.projection {
            Projection::Panoramic { .. } => t,
            _ => t * direction.dot(self.basis().2),
        }
    }

    /// Right, up and forward: `up` (world +Y by default) made perpendicular to the view.
    pub fn basis(&self) -> (Vec3, Vec3, Vec3) {
        let forward = (self.look_at - self.position).normalize();
        // Looking straight up or down, world up gives no right vector: use −Z then.
        let world_up = if forward.cross(Vec3::Y).length_squared() < 1e-12 { Vec3::NEG_Z } else { Vec3::Y };
        let right = forward.cross(self.up.unwrap_or(world_up)).normalize();
        (right, right.cross(forward), forward)
    }
}

const DEFAULT_FOV_Y_DEG: f32 = 40.0;
/// Blender's default `lens`.
const DEFAULT_LENS_MM: f32 = 50.0;
/// Blender's default `ortho_scale`.
const DEFAULT_ORTHO_SCALE: f32 = 6.0;
/// Blender's limit on `aperture_blades`.
pub const MAX_BLADES: u32 = 16;

/// Where the camera's keys sit in the scene file, for errors.
const AT: [Seg<'static>; 1] = [Key("camera")];

pub(super) fn validate(src: &Source, c: schema::Camera) -> Result<Camera, SceneError> {
    let p = AT;
    src.finite(&p, "position", &c.position)?;
    src.finite(&p, "look_at", &c.look_at)?;
    if c.position == c.look_at {
        return Err(src.error(&p, "look_at", "must differ from position"));
    }
    let (position, look_at) = (Vec3::from(c.position), Vec3::from(c.look_at));
    let up = c.up.map(|up| validate_up(src, up, look_at - position)).transpose()?;
    let projection = validate_projection(src, &c)?;
    src.check(&p, "sensor_width_mm", &[c.sensor_width_mm], "positive", |s| s > 0.0)?;
    src.check(&p, "sensor_height_mm", &[c.sensor_height_mm], "positive", |s| s > 0.0)?;
    src.finite(&p, "shift_x", &[c.shift_x])?;
    src.finite(&p, "shift_y", &[c.shift_y])?;
    src.check(&p, "pixel_aspect", &c.pixel_aspect, "positive", |a| a > 0.0)?;
    let depth_of_field = validate_depth_of_field(src, &c, position.distance(look_at))?;
    src.check(&p, "clip_start", &[c.clip_start], "at least 0", |s| s >= 0.0)?;
    let clip_end = c.clip_end.unwrap_or(f32::INFINITY);
    if c.clip_end.is_some() {
        let beyond = format!("beyond clip_start ({})", c.clip_start);
        src.check(&p, "clip_end", &[clip_end], &beyond, |e| e > c.clip_start)?;
    }
    Ok(Camera {
        position,
        look_at,
        up,
        projection,
        sensor_fit: c.sensor_fit,
        sensor_mm: Vec2::new(c.sensor_width_mm, c.sensor_height_mm),
        shift: Vec2::new(c.shift_x, c.shift_y),
        pixel_aspect: Vec2::from(c.pixel_aspect),
        depth_of_field,
        clip_start: c.clip_start,
        clip_end,
        motion: c.motion.as_deref().map(|poses| super::motion::validate_camera(src, poses)).transpose()?,
    })
}

/// An error if `key` is `present` where it does not apply (`condition` says where it does).
fn only(src: &Source, key: &str, present: bool, condition: &str) -> Result<(), SceneError> {
    match present {
        true => Err(src.error(&AT, key, format!("only applies {condition}"))),
        false => Ok(()),
    }
}

fn validate_up(src: &Source, up: [f32; 3], view: Vec3) -> Result<Vec3, SceneError> {
    src.finite(&AT, "up", &up)?;
    let (up, forward) = (Vec3::from(up), view.normalize());
    if up.cross(forward).length_squared() <= 1e-12 * up.length_squared() {
        return Err(src.error(&AT, "up", "must be a direction not along the view (look_at − position)"));
    }
    Ok(up)
}

fn validate_projection(src: &Source, c: &schema::Camera) -> Result<Projection, SceneError> {
    let p = AT;
    let (perspective_only, orthographic_only) = ("to projection = \"perspective\"", "to projection = \"orthographic\"");
    Ok(match (panorama::validate(src, c)?, c.projection) {
        (Some(panorama), _) => {
            only(src, "fov_y_deg", c.fov_y_deg.is_some(), perspective_only)?;
            only(src, "ortho_scale", c.ortho_scale.is_some(), orthographic_only)?;
            // A panorama's focal length only sizes its aperture.
            let with_fstop = "to a panorama with fstop (its aperture)";
            only(src, "focal_length_mm", c.focal_length_mm.is_some() && c.fstop.is_none(), with_fstop)?;
            let lens_mm = c.focal_length_mm.unwrap_or(DEFAULT_LENS_MM);
            src.check(&p, "focal_length_mm", &[lens_mm], "positive", |f| f > 0.0)?;
            Projection::Panoramic { panorama, lens_mm }
        }
        (None, schema::Projection::Orthographic) => {
            only(src, "fov_y_deg", c.fov_y_deg.is_some(), perspective_only)?;
            only(src, "focal_length_mm", c.focal_length_mm.is_some(), perspective_only)?;
            let scale = c.ortho_scale.unwrap_or(DEFAULT_ORTHO_SCALE);
            src.check(&p, "ortho_scale", &[scale], "positive", |s| s > 0.0)?;
            Projection::Orthographic { scale }
        }
        (None, _) => {
            only(src, "ortho_scale", c.ortho_scale.is_some(), orthographic_only)?;
            match (c.fov_y_deg, c.focal_length_mm) {
                (Some(_), Some(_)) => return Err(src.error(&p, "focal_length_mm", "excludes fov_y_deg: give one")),
                (None, Some(mm)) => {
                    src.check(&p, "focal_length_mm", &[mm], "positive", |f| f > 0.0)?;
                    Projection::FocalLength { mm }
                }
                (fov, None) => {
                    let degrees = fov.unwrap_or(DEFAULT_FOV_Y_DEG);
                    src.check(&p, "fov_y_deg", &[degrees], "in (0, 180)", |f| f > 0.0 && f < 180.0)?;
                    Projection::FovY { degrees }
                }
            }
        }
    })
}

/// The aperture, with `fstop`; focus at `look_at_distance` unless given.
fn validate_depth_of_field(
    src: &Source,
    c: &schema::Camera,
    look_at_distance: f32,
) -> Result<Option<DepthOfField>, SceneError> {
    let p = AT;
    let Some(fstop) = c.fstop else {
        let with_fstop = "with fstop (depth of field)";
        only(src, "focus_distance", c.focus_distance.is_some(), with_fstop)?;
        only(src, "blades", c.blades.is_some(), with_fstop)?;
        only(src, "blade_rotation_deg", c.blade_rotation_deg.is_some(), with_fstop)?;
        only(src, "aperture_ratio", c.aperture_ratio.is_some(), with_fstop)?;
        return Ok(None);
    };
    src.check(&p, "fstop", &[fstop], "positive", |f| f > 0.0)?;
    let focus_distance = c.focus_distance.unwrap_or(look_at_distance);
    src.check(&p, "focus_distance", &[focus_distance], "positive", |d| d > 0.0)?;
    let blades = c.blades.unwrap_or(0);
    if blades == 1 || blades == 2 || blades > MAX_BLADES {
        let message = format!("must be 0 (round) or in 3..={MAX_BLADES}, got {blades}");
        return Err(src.error(&p, "blades", message));
    }
    let blade_rotation_deg = c.blade_rotation_deg.unwrap_or(0.0);
    src.finite(&p, "blade_rotation_deg", &[blade_rotation_deg])?;
    let aperture_ratio = c.aperture_ratio.unwrap_or(1.0);
    src.check(&p, "aperture_ratio", &[aperture_ratio], "positive", |r| r > 0.0)?;
    Ok(Some(DepthOfField { fstop, focus_distance, blades, blade_rotation_deg, aperture_ratio }))
}

#[cfg(test)]
#[path = "camera_tests.rs"]
mod tests;
