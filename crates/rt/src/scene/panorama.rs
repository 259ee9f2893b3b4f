//! Blender's panoramic cameras, mapped as Cycles maps them
//! (`intern/cycles/kernel/camera/projection.h`): equirectangular (a window of latitudes
//! and longitudes), the equidistant and the equisolid fisheye, and the mirror ball.
//!
//! Cycles maps a point (u, v) of its screen, [0, 1]² with v up and the lens shift added,
//! to a direction in a panoramic camera space of its own: x along the view, y to the left,
//! z up (the mirror ball: x right, y back along the view, z up). `to_camera` turns that
//! into rt's camera frame, x right, y up, z along the view, as Cycles' camera matrix
//! (`blender_camera_matrix`) does with Blender's camera, which looks down its −Z.

use super::parse::{SceneError, Seg::Key, Source};
use super::schema;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_PI_2;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Panorama {
    /// Longitude runs left to right, latitude bottom to top, over these [min, max] degrees;
    /// (0, 0) is the view direction.
    Equirectangular { latitude_deg: [f32; 2], longitude_deg: [f32; 2] },
    /// The angle from the view grows with the distance from the image's centre: `fov_deg`
    /// across the ellipse inscribed in the image.
    FisheyeEquidistant { fov_deg: f32 },
    /// A fisheye lens of focal length `lens_mm` over the sensor, seeing `fov_deg` at most.
    FisheyeEquisolid { fov_deg: f32, lens_mm: f32 },
    /// What a mirror ball in front of the camera shows, in the disk inscribed in the image.
    MirrorBall,
}

impl Panorama {
    /// Cycles' `equirectangular_range` (`Camera::update`): φ = x·u + y, θ = z·v + w.
    pub fn equirectangular_range(&self) -> [f32; 4] {
        let Panorama::Equirectangular { latitude_deg: [lat_min, lat_max], longitude_deg: [lon_min, lon_max] } = *self
        else {
            return [0.0; 4];
        };
        let (lat_min, lat_max) = (lat_min.to_radians(), lat_max.to_radians());
        let (lon_min, lon_max) = (lon_min.to_radians(), lon_max.to_radians());
        [lon_min - lon_max, -lon_min, lat_min - lat_max, -lat_min + FRAC_PI_2]
    }

    /// The fisheye's field of view in radians (0 for the others).
    pub fn fisheye_fov(&self) -> f32 {
        match *self {
            Panorama::FisheyeEquidistant { fov_deg } | Panorama::FisheyeEquisolid { fov_deg, .. } => {
                fov_deg.to_radians()
            }
            _ => 0.0,
        }
    }

    /// The direction (not normalised) for the point `uv` of Cycles' screen, in rt's camera
    /// frame; `None` outside a fisheye's or a mirror ball's image, where Cycles sends no
    /// ray. `sensor_mm` is the sensor's width and height as the equisolid fisheye sees it.
    pub fn direction(&self, uv: Vec2, sensor_mm: Vec2) -> Option<Vec3> {
        self.cycles_direction(uv, sensor_mm).map(|d| self.to_camera(d))
    }

    /// Cycles' panoramic camera space to rt's camera frame.
    pub fn to_camera(&self, d: Vec3) -> Vec3 {
        match self {
            Panorama::MirrorBall => Vec3::new(d.x, d.z, -d.y),
            _ => Vec3::new(-d.y, d.z, d.x),
        }
    }

    /// Cycles' `panorama_to_direction`.
    fn cycles_direction(&self, uv: Vec2, sensor_mm: Vec2) -> Option<Vec3> {
        match *self {
            Panorama::Equirectangular { .. } => {
                let range = self.equirectangular_range();
                let phi = range[0] * uv.x + range[1];
                let theta = range[2] * uv.y + range[3];
                Some(Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()))
            }
            Panorama::FisheyeEquidistant { fov_deg } => {
                let p = (uv - 0.5) * 2.0;
                let r = p.length();
                (r <= 1.0).then(|| fisheye(r * fov_deg.to_radians() * 0.5, p, r))
            }
            Panorama::FisheyeEquisolid { fov_deg, lens_mm } => {
                let p = (uv - 0.5) * sensor_mm;
                let r = p.length();
                let r_max = 2.0 * lens_mm * (fov_deg.to_radians() * 0.25).sin();
                (r <= r_max).then(|| fisheye(2.0 * (r / (2.0 * lens_mm)).asin(), p, r))
            }
            Panorama::MirrorBall => {
                let (x, z) = (2.0 * uv.x - 1.0, 2.0 * uv.y - 1.0);
                if x * x + z * z > 1.0 {
                    return None;
                }
                // The ball's normal, facing the camera (−y), reflects the ray coming along +y.
                let n = Vec3::new(x, -(1.0 - x * x - z * z).max(0.0).sqrt(), z);
                let incoming = Vec3::NEG_Y;
                Some(2.0 * n.dot(incoming) * n - incoming)
            }
        }
    }
}

/// Cycles' `fisheye_to_direction`: `theta` from the view, turned towards `p` (at radius `r`).
fn fisheye(theta: f32, p: Vec2, r: f32) -> Vec3 {
    let cos_phi = if r != 0.0 { p.x / r } else { 0.0 };
    let mut phi = cos_phi.clamp(-1.0, 1.0).acos();
    if p.y < 0.0 {
        phi = -phi;
    }
    Vec3::new(theta.cos(), -phi.cos() * theta.sin(), phi.sin() * theta.sin())
}

/// Blender's defaults.
const DEFAULT_FISHEYE_FOV_DEG: f32 = 180.0;
const DEFAULT_FISHEYE_LENS_MM: f32 = 10.5;
/// Blender's limit on `fisheye_fov`: ten half turns.
const MAX_FISHEYE_FOV_DEG: f32 = 1800.0;

/// The panorama of `[camera]`'s `projection`, or `None` for a perspective or
/// orthographic camera, which must then carry none of the panoramic keys.
pub(super) fn validate(src: &Source, c: &schema::Camera) -> Result<Option<Panorama>, SceneError> {
    let p = [Key("camera")];
    let only = |key: &str, present: bool, condition: &str| match present {
        true => Err(src.error(&p, key, format!("only applies to {condition}"))),
        false => Ok(()),
    };
    let equirectangular = matches!(c.projection, schema::Projection::Equirectangular);
    let equisolid = matches!(c.projection, schema::Projection::FisheyeEquisolid);
    let fisheye = equisolid || matches!(c.projection, schema::Projection::FisheyeEquidistant);
    for (key, value) in [
        ("latitude_min_deg", c.latitude_min_deg),
        ("latitude_max_deg", c.latitude_max_deg),
        ("longitude_min_deg", c.longitude_min_deg),
        ("longitude_max_deg", c.longitude_max_deg),
    ] {
        only(key, value.is_some() && !equirectangular, "projection = \"equirectangular\"")?;
    }
    only("fisheye_fov_deg", c.fisheye_fov_deg.is_some() && !fisheye, "a fisheye projection")?;
    only("fisheye_lens_mm", c.fisheye_lens_mm.is_some() && !equisolid, "projection = \"fisheye_equisolid\"")?;
    let range = |name: &str, min: Option<f32>, max: Option<f32>, limit: f32| {
        let (min_key, max_key) = (format!("{name}_min_deg"), format!("{name}_max_deg"));
        let given_max = max.is_some();
        let (min, max) = (min.unwrap_or(-limit), max.unwrap_or(limit));
        let within = format!("in [-{limit}, {limit}]");
        src.check(&p, &min_key, &[min], &within, |a| (-limit..=limit).contains(&a))?;
        src.check(&p, &max_key, &[max], &within, |a| (-limit..=limit).contains(&a))?;
        if min >= max {
            // Located at the end the file gives (the upper one if both).
            return Err(match given_max {
                true => src.error(&p, &max_key, format!("must be above {min_key} ({min}), got {max}")),
                false => src.error(&p, &min_key, format!("must be below {max_key} ({max}), got {min}")),
            });
        }
        Ok([min, max])
    };
    let fov = || {
        let fov_deg = c.fisheye_fov_deg.unwrap_or(DEFAULT_FISHEYE_FOV_DEG);
        let within = format!("in (0, {MAX_FISHEYE_FOV_DEG}]");
        src.check(&p, "fisheye_fov_deg", &[fov_deg], &within, |f| f > 0.0 && f <= MAX_FISHEYE_FOV_DEG)?;
        Ok(fov_deg)
    };
    Ok(Some(match c.projection {
        schema::Projection::Perspective | schema::Projection::Orthographic => return Ok(None),
        schema::Projection::Equirectangular => Panorama::Equirectangular {
            latitude_deg: range("latitude", c.latitude_min_deg, c.latitude_max_deg, 90.0)?,
            longitude_deg: range("longitude", c.longitude_min_deg, c.longitude_max_deg, 180.0)?,
        },
        schema::Projection::FisheyeEquidistant => Panorama::FisheyeEquidistant { fov_deg: fov()? },
        schema::Projection::FisheyeEquisolid => {
            let lens_mm = c.fisheye_lens_mm.unwrap_or(DEFAULT_FISHEYE_LENS_MM);
            src.check(&p, "fisheye_lens_mm", &[lens_mm], "positive", |l| l > 0.0)?;
            Panorama::FisheyeEquisolid { fov_deg: fov()?, lens_mm }
        }
        schema::Projection::MirrorBall => Panorama::MirrorBall,
    }))
}

#[cfg(test)]
#[path = "panorama_tests.rs"]
mod tests;
