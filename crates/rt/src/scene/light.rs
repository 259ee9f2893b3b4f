//! `[[light]]`: Blender's lamps (point, spot, area, sun) in Blender's units, and their
//! validation. What each one emits is defined as Cycles defines it (see `shaders/lamps.wgsl`).

use super::parse::{SceneError, Seg, Seg::*, Source};
pub use super::schema::AreaShape;
use super::schema::{self, LightKind};
use super::validate::matrix;
use glam::{Mat4, Vec3};

/// A lamp: what it is, its colour and power, and where it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub shape: LightShape,
    pub color: Vec3,
    /// Radiant power in W for point, spot and area lamps; irradiance in W/m² (Blender's
    /// sun `strength`) for a sun.
    pub power: f32,
    /// Whether camera rays see the lamp's shape (Blender's "Visible to Camera", off by default).
    pub visible_to_camera: bool,
    /// Lamp to world. A lamp shines along its local −Z; an area lamp spans its local X
    /// (`size`) and Y (`size_y`), scaled by the matrix as in Blender.
    pub object_to_world: Mat4,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightShape {
    /// `radius` 0 is a point; otherwise, with `soft_falloff`, a disk of that radius facing
    /// each shaded point (Blender's default), without it a sphere.
    Point { radius: f32, soft_falloff: bool },
    /// A point lamp whose light is confined to a cone of `size_deg` (full angle), with a
    /// smooth edge over the `blend` fraction of it.
    Spot { radius: f32, soft_falloff: bool, size_deg: f32, blend: f32 },
    /// One-sided, emitting along −Z: a rectangle or an ellipse of `size` × `size_y`.
    Area { shape: AreaShape, size: f32, size_y: f32 },
    /// Light from a direction, in a cone of `angle_deg` (full angle; 0 is a delta direction).
    Sun { angle_deg: f32 },
}

impl Light {
    /// The unit direction the lamp shines towards (its local −Z in the world).
    pub fn direction(&self) -> Vec3 {
        (-self.object_to_world.z_axis.truncate()).normalize()
    }

    pub fn position(&self) -> Vec3 {
        self.object_to_world.w_axis.truncate()
    }

    pub fn is_sun(&self) -> bool {
        matches!(self.shape, LightShape::Sun { .. })
    }

    /// A point, or a sun of angle 0: only light sampling reaches it, no ray can hit it.
    pub fn is_delta(&self) -> bool {
        match self.shape {
            LightShape::Point { radius, .. } | LightShape::Spot { radius, .. } => radius == 0.0,
            LightShape::Sun { angle_deg } => angle_deg == 0.0,
            LightShape::Area { .. } => false,
        }
    }
}

/// Blender's defaults for a new lamp.
const DEFAULT_POWER: f32 = 10.0;
const DEFAULT_SPOT_SIZE_DEG: f32 = 45.0;
const DEFAULT_SPOT_BLEND: f32 = 0.15;
const DEFAULT_AREA_SIZE: f32 = 0.25;
const DEFAULT_SUN_ANGLE_DEG: f32 = 0.526;

pub(super) fn validate(src: &Source, index: usize, l: schema::Light) -> Result<Light, SceneError> {
    let p = [Key("light"), Index(index)];
    let kind = l.kind;
    let name = match kind {
        LightKind::Point => "point",
        LightKind::Spot => "spot",
        LightKind::Area => "area",
        LightKind::Sun => "sun",
    };
    let only = |key: &str, present: bool, kinds: &[LightKind], what: &str| {
        if present && !kinds.contains(&kind) {
            return Err(src.error(&p, key, format!("only applies to {what}, not to type = \"{name}\"")));
        }
        Ok(())
    };
    use LightKind::{Area, Point, Spot, Sun};
    only("power", l.power.is_some(), &[Point, Spot, Area], "point, spot and area lamps (a sun has `strength`)")?;
    only("strength", l.strength.is_some(), &[Sun], "type = \"sun\" (other lamps have `power`)")?;
    only("radius", l.radius.is_some(), &[Point, Spot], "point and spot lamps")?;
    only("soft_falloff", l.soft_falloff.is_some(), &[Point, Spot], "point and spot lamps")?;
    only("spot_size_deg", l.spot_size_deg.is_some(), &[Spot], "type = \"spot\"")?;
    only("spot_blend", l.spot_blend.is_some(), &[Spot], "type = \"spot\"")?;
    only("shape", l.shape.is_some(), &[Area], "type = \"area\"")?;
    only("size", l.size.is_some(), &[Area], "type = \"area\"")?;
    only("size_y", l.size_y.is_some(), &[Area], "type = \"area\"")?;
    only("angle_deg", l.angle_deg.is_some(), &[Sun], "type = \"sun\"")?;
    only("position", l.position.is_some(), &[Point, Spot, Area], "point, spot and area lamps")?;

    let color = l.color.map_or([1.0; 3], schema::Color::rgb);
    src.check(&p, "color", &color, "non-negative", |c| c >= 0.0)?;
    let (power_key, power) = match kind {
        Sun => ("strength", l.strength.unwrap_or(DEFAULT_POWER)),
        _ => ("power", l.power.unwrap_or(DEFAULT_POWER)),
    };
    src.check(&p, power_key, &[power], "non-negative", |v| v >= 0.0)?;

    let radius = l.radius.unwrap_or(0.0);
    src.check(&p, "radius", &[radius], "non-negative", |r| r >= 0.0)?;
    let soft_falloff = l.soft_falloff.unwrap_or(true);
    let shape = match kind {
        Point => LightShape::Point { radius, soft_falloff },
        Spot => {
            let size_deg = l.spot_size_deg.unwrap_or(DEFAULT_SPOT_SIZE_DEG);
            src.check(&p, "spot_size_deg", &[size_deg], "in [1, 180]", |s| (1.0..=180.0).contains(&s))?;
            let blend = l.spot_blend.unwrap_or(DEFAULT_SPOT_BLEND);
            src.check(&p, "spot_blend", &[blend], "in [0, 1]", |b| (0.0..=1.0).contains(&b))?;
            LightShape::Spot { radius, soft_falloff, size_deg, blend }
        }
        Area => {
            let shape = l.shape.unwrap_or(AreaShape::Square);
            let round = matches!(shape, AreaShape::Square | AreaShape::Disk);
            if round && l.size_y.is_some() {
                return Err(src.error(&p, "size_y", "only applies to shape = \"rectangle\" or \"ellipse\""));
            }
            let size = l.size.unwrap_or(DEFAULT_AREA_SIZE);
            src.check(&p, "size", &[size], "positive", |s| s > 0.0)?;
            let size_y = if round { size } else { l.size_y.unwrap_or(DEFAULT_AREA_SIZE) };
            src.check(&p, "size_y", &[size_y], "positive", |s| s > 0.0)?;
            LightShape::Area { shape, size, size_y }
        }
        Sun => {
            let angle_deg = l.angle_deg.unwrap_or(DEFAULT_SUN_ANGLE_DEG);
            src.check(&p, "angle_deg", &[angle_deg], "in [0, 180]", |a| (0.0..=180.0).contains(&a))?;
            LightShape::Sun { angle_deg }
        }
    };
    Ok(Light {
        shape,
        color: color.into(),
        power,
        visible_to_camera: l.visible_to_camera.unwrap_or(false),
        object_to_world: placement(src, &p, &l)?,
    })
}

/// `matrix`, or a lamp at `position` shining along `direction` (default: straight down).
/// With `direction`, the lamp's local X is horizontal (perpendicular to +Y and to the
/// direction; +X when it points straight up or down).
fn placement(src: &Source, p: &[Seg], l: &schema::Light) -> Result<Mat4, SceneError> {
    if let Some(rows) = &l.matrix {
        if l.position.is_some() || l.direction.is_some() {
            return Err(src.error(p, "matrix", "excludes position and direction"));
        }
        return matrix(src, p, rows);
    }
    let position = l.position.unwrap_or_default();
    src.finite(p, "position", &position)?;
    let direction = l.direction.unwrap_or([0.0, -1.0, 0.0]);
    src.finite(p, "direction", &direction)?;
    let forward = Vec3::from(direction);
    if forward.length() <= 1e-6 {
        return Err(src.error(p, "direction", "must not be zero"));
    }
    let z = -forward.normalize();
    let across = Vec3::Y.cross(z);
    let x = if across.length() > 1e-4 { across.normalize() } else { Vec3::X };
    let y = z.cross(x);
    Ok(Mat4::from_cols(x.extend(0.0), y.extend(0.0), z.extend(0.0), Vec3::from(position).extend(1.0)))
}
