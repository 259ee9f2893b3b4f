//! The scene file as serde reads it (contract 3), before validation.
//!
//! Every struct denies unknown keys so that a typo is an error, not a silent default.

use super::{Material, RenderSettings};
use serde::Deserialize;
use std::collections::BTreeMap;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct File {
    #[serde(default)]
    pub render: RenderSettings,
    #[serde(default)]
    pub camera: Camera,
    pub sky: Option<Sky>,
    pub sun: Option<Sun>,
    /// File order is lost here; `parse` restores it from the document's spans.
    #[serde(default)]
    pub materials: BTreeMap<String, Material>,
    #[serde(default)]
    pub mesh: Vec<Mesh>,
    #[serde(default)]
    pub sphere: Vec<Sphere>,
    #[serde(default)]
    pub light: Vec<Light>,
    #[serde(default)]
    pub instances: Vec<Instances>,
}

/// Each key may be left out, and so may the whole `[camera]` table; `scene::camera`
/// checks which keys go together.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, default)]
pub(super) struct Camera {
    pub position: [f32; 3],
    pub look_at: [f32; 3],
    pub up: Option<[f32; 3]>,
    pub projection: Projection,
    pub fov_y_deg: Option<f32>,
    pub focal_length_mm: Option<f32>,
    pub ortho_scale: Option<f32>,
    pub sensor_fit: SensorFit,
    pub sensor_width_mm: f32,
    pub sensor_height_mm: f32,
    pub shift_x: f32,
    pub shift_y: f32,
    pub pixel_aspect: [f32; 2],
    pub fstop: Option<f32>,
    pub focus_distance: Option<f32>,
    pub blades: Option<u32>,
    pub blade_rotation_deg: Option<f32>,
    pub aperture_ratio: Option<f32>,
    pub clip_start: f32,
    pub clip_end: Option<f32>,
    pub latitude_min_deg: Option<f32>,
    pub latitude_max_deg: Option<f32>,
    pub longitude_min_deg: Option<f32>,
    pub longitude_max_deg: Option<f32>,
    pub fisheye_fov_deg: Option<f32>,
    pub fisheye_lens_mm: Option<f32>,
    pub motion: Option<Vec<CameraPose>>,
}

/// One key of `[camera] motion`: where the camera is and looks at one time of the shutter.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CameraPose {
    pub position: [f32; 3],
    pub look_at: [f32; 3],
    pub up: Option<[f32; 3]>,
}

impl Default for Camera {
    /// A person's eye height, looking at the origin from 5 m down +Z; Blender's
    /// full-frame sensor (36 × 24 mm).
    fn default() -> Self {
        Self {
            position: [0.0, 1.0, 5.0],
            look_at: [0.0, 1.0, 0.0],
            up: None,
            projection: Projection::Perspective,
            fov_y_deg: None,
            focal_length_mm: None,
            ortho_scale: None,
            sensor_fit: SensorFit::Auto,
            sensor_width_mm: 36.0,
            sensor_height_mm: 24.0,
            shift_x: 0.0,
            shift_y: 0.0,
            pixel_aspect: [1.0, 1.0],
            fstop: None,
            focus_distance: None,
            blades: None,
            blade_rotation_deg: None,
            aperture_ratio: None,
            clip_start: 0.0,
            clip_end: None,
            latitude_min_deg: None,
            latitude_max_deg: None,
            longitude_min_deg: None,
            longitude_max_deg: None,
            fisheye_fov_deg: None,
            fisheye_lens_mm: None,
            motion: None,
        }
    }
}

#[derive(Clone, Copy, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(super) enum Projection {
    Perspective,
    Orthographic,
    Equirectangular,
    FisheyeEquidistant,
    FisheyeEquisolid,
    MirrorBall,
}

pub(super) use super::camera::SensorFit;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Sky {
    pub kind: SkyKind,
    /// Only for `kind = "uniform"`; white when left out.
    pub color: Option<[f32; 3]>,
    /// Only for `kind = "uniform"`: next-event estimation samples the sky too; off when
    /// left out.
    pub sample_as_light: Option<bool>,
    // Only for `kind = "atmosphere"` (see `scene::Atmosphere`); its defaults when left out.
    pub turbidity: Option<f32>,
    pub rayleigh_scale: Option<f32>,
    pub mie_g: Option<f32>,
    pub mie_absorption: Option<bool>,
    pub ozone: Option<bool>,
    pub ground_albedo: Option<Color>,
    pub ground_altitude_m: Option<f32>,
    pub multiple_scattering: Option<bool>,
    pub steps: Option<u32>,
    pub transmittance_lut: Option<[u32; 2]>,
    pub multiple_scattering_lut: Option<[u32; 2]>,
    // Only for `kind = "environment"` (see `scene::Environment`).
    pub image: Option<String>,
    pub strength: Option<f32>,
    pub rotation_deg: Option<[f32; 3]>,
    pub importance_sampling: Option<bool>,
    pub color_space: Option<String>,
    /// Only for `kind = "graph"` (see `scene::WorldGraph`).
    pub graph: Option<String>,
}

/// A grey level or an RGB triple.
#[derive(Clone, Copy, Deserialize)]
#[serde(untagged, expecting = "expected a number or an array [r, g, b]")]
pub(super) enum Color {
    Grey(f32),
    Rgb([f32; 3]),
}

impl Color {
    pub fn rgb(self) -> [f32; 3] {
        match self {
            Color::Grey(v) => [v; 3],
            Color::Rgb(c) => c,
        }
    }
}

#[derive(Clone, Copy, PartialEq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum SkyKind {
    Black,
    Uniform,
    Atmosphere,
    Environment,
    Graph,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Sun {
    pub elevation_deg: f32,
    pub azimuth_deg: f32,
    #[serde(default = "real_sun_diameter")]
    pub angular_diameter_deg: f32,
    pub radiance: Option<[f32; 3]>,
}

fn real_sun_diameter() -> f32 {
    0.53
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Mesh {
    pub asset: String,
    pub material: Option<String>,
    pub rotate_deg: Option<[f32; 3]>,
    pub translate: Option<[f32; 3]>,
    pub scale: Option<Scale>,
    /// Row-major; excludes `rotate_deg`, `translate` and `scale`.
    pub matrix: Option<[f32; 16]>,
    /// Row-major matrices over the shutter (motion blur).
    pub motion: Option<Vec<[f32; 16]>>,
    pub shadow_terminator_geometry_offset: Option<f32>,
    pub shadow_terminator_shading_offset: Option<f32>,
    #[serde(default)]
    pub holdout: bool,
    /// Object Info's Color (RGBA), Random and Object Index (Blender's Pass Index).
    pub object_color: Option<[f32; 4]>,
    pub random: Option<f32>,
    pub object_index: Option<u32>,
}

/// One asset placed by an instance file (`.rtinst`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Instances {
    pub asset: String,
    pub file: String,
    /// Scene materials that the file's material indices name, in order.
    #[serde(default)]
    pub materials: Vec<String>,
    /// For every instance of the file.
    pub shadow_terminator_geometry_offset: Option<f32>,
    pub shadow_terminator_shading_offset: Option<f32>,
    #[serde(default)]
    pub holdout: bool,
    /// Object Info's Color (RGBA), Random and Object Index (Blender's Pass Index).
    pub object_color: Option<[f32; 4]>,
    pub random: Option<f32>,
    pub object_index: Option<u32>,
}

#[derive(Clone, Copy, Deserialize)]
#[serde(untagged, expecting = "expected a number or an array [x, y, z]")]
pub(super) enum Scale {
    Uniform(f32),
    Axes([f32; 3]),
}

impl Scale {
    pub fn axes(self) -> [f32; 3] {
        match self {
            Scale::Uniform(s) => [s; 3],
            Scale::Axes(a) => a,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Sphere {
    pub center: [f32; 3],
    pub radius: f32,
    pub material: Option<String>,
}

/// One `[[light]]`: a Blender lamp. Which keys apply depends on `type`; `validate` says
/// which do not.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Light {
    #[serde(rename = "type")]
    pub kind: LightKind,
    pub color: Option<Color>,
    pub power: Option<f32>,
    pub strength: Option<f32>,
    pub radius: Option<f32>,
    pub soft_falloff: Option<bool>,
    pub spot_size_deg: Option<f32>,
    pub spot_blend: Option<f32>,
    pub shape: Option<AreaShape>,
    pub size: Option<f32>,
    pub size_y: Option<f32>,
    pub angle_deg: Option<f32>,
    pub visible_to_camera: Option<bool>,
    pub position: Option<[f32; 3]>,
    pub direction: Option<[f32; 3]>,
    /// Row-major; excludes `position` and `direction`.
    pub matrix: Option<[f32; 16]>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum LightKind {
    Point,
    Spot,
    Area,
    Sun,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AreaShape {
    Square,
    Rectangle,
    Disk,
    Ellipse,
}
