//! The lamp table: each `[[light]]` as the GPU evaluates it, with Cycles' conversion
//! from Blender's units (`intern/cycles/scene/light.cpp`) done once here, and how
//! next-event estimation shares its samples between the sun, emitters and lamps.

use crate::layout::*;
use crate::scene::{AreaShape, Light, LightSampler, LightShape, luminance};
use glam::Vec3;
use std::f64::consts::PI;

pub struct LampTable {
    pub lamps: Vec<GpuLamp>,
    pub info: GpuLampInfo,
}

/// `scene_radius` sizes the share of samples a sun lamp gets: the power it sends
/// into a sphere of that radius. With the light tree, the lamps' own table picks suns
/// only and the emitters' share goes to the tree, which holds the other lamps.
pub fn lamp_table(
    lights: &[Light],
    has_sun: bool,
    has_emitters: bool,
    scene_radius: f32,
    sampler: LightSampler,
) -> LampTable {
    let mut lamps: Vec<GpuLamp> = lights.iter().map(gpu_lamp).collect();
    let in_tree = |l: &Light| sampler == LightSampler::Tree && !matches!(l.shape, LightShape::Sun { .. });
    let weights: Vec<f64> =
        lights.iter().map(|l| if in_tree(l) { 0.0 } else { selection_weight(l, scene_radius) }).collect();
    let total: f64 = weights.iter().sum();
    let mut running = 0.0;
    for (lamp, w) in lamps.iter_mut().zip(&weights) {
        // Lamps that emit nothing leave the others their samples; all dark, all alike.
        running += if total > 0.0 { *w / total } else { 1.0 / weights.len() as f64 };
        lamp.cdf = running as f32;
    }
    if let Some(last) = lamps.last_mut() {
        last.cdf = 1.0;
    }
    let mut info = shares(lamps.len() as u32, has_sun, has_emitters);
    if sampler == LightSampler::Tree && !lights.is_empty() {
        let suns = lights.iter().any(|l| !in_tree(l));
        info = tree_shares(info.count, has_sun, suns, has_emitters || lights.iter().any(in_tree));
    }
    LampTable { info, lamps }
}

/// With the light tree: an equal share to the `[sun]`, to sun lamps and to the tree
/// (in `emitter_share`), of those present.
fn tree_shares(count: u32, has_sun: bool, has_sun_lamps: bool, has_tree: bool) -> GpuLampInfo {
    let kinds = [has_sun, has_tree, has_sun_lamps].iter().filter(|k| **k).count().max(1) as f32;
    let share = |present: bool| if present { 1.0 / kinds } else { 0.0 };
    GpuLampInfo { count, sun_share: share(has_sun), emitter_share: share(has_tree), lamp_share: share(has_sun_lamps) }
}

/// Without lamps, the split the frame constants use (half to the sun when there are
/// emitters too); with lamps, an equal share to each kind of light present.
fn shares(count: u32, has_sun: bool, has_emitters: bool) -> GpuLampInfo {
    if count == 0 {
        let sun_share = match (has_sun, has_emitters) {
            (false, _) => 0.0,
            (true, true) => 0.5,
            (true, false) => 1.0,
        };
        return GpuLampInfo { count, sun_share, emitter_share: 1.0 - sun_share, lamp_share: 0.0 };
    }
    let kinds = 1.0 + f32::from(u8::from(has_sun)) + f32::from(u8::from(has_emitters));
    let share = |present: bool| if present { 1.0 / kinds } else { 0.0 };
    GpuLampInfo { count, sun_share: share(has_sun), emitter_share: share(has_emitters), lamp_share: 1.0 / kinds }
}

/// About the power a lamp brings into the scene, in luminance.
fn selection_weight(l: &Light, scene_radius: f32) -> f64 {
    let power = l.power as f64 * luminance(l.color.to_array()) as f64;
    match l.shape {
        LightShape::Sun { .. } => power * PI * (scene_radius as f64).powi(2),
        _ => power,
    }
}

fn gpu_lamp(l: &Light) -> GpuLamp {
    let color = l.color.as_dvec3() * l.power as f64;
    let emission = |scale: f64| (color * scale).as_vec3().to_array();
    let camera = if l.visible_to_camera { LAMP_CAMERA } else { 0 };
    let direction = l.direction();
    let position = l.position().to_array();
    let mut lamp = GpuLamp { position, ..Default::default() };
    match l.shape {
        LightShape::Point { radius, soft_falloff } | LightShape::Spot { radius, soft_falloff, .. } => {
            let sphere = if soft_falloff || radius == 0.0 { 0 } else { LAMP_SPHERE };
            let kind = if matches!(l.shape, LightShape::Spot { .. }) { LAMP_SPOT } else { LAMP_POINT };
            lamp.kind = kind | sphere | camera;
            lamp.radius = radius;
            // Cycles: radiance = power / (π · 4π r²); a point (r = 0) has intensity power / 4π.
            let r2 = (radius as f64).powi(2);
            lamp.emission = emission(if radius > 0.0 { 1.0 / (4.0 * PI * PI * r2) } else { 1.0 / (4.0 * PI) });
            if let LightShape::Spot { size_deg, blend, .. } = l.shape {
                let cos_half = ((size_deg as f64).to_radians() * 0.5).cos();
                lamp.axis_u = direction.to_array();
                lamp.len_u = cos_half as f32;
                // A blend of 0 is a hard edge: a scale so large that the smoothstep is a step.
                let scale = 1.0 / ((1.0 - cos_half) * blend as f64);
                lamp.len_v = scale.min(1e30) as f32;
            }
        }
        LightShape::Area { shape, size, size_y } => {
            let ellipse = matches!(shape, AreaShape::Disk | AreaShape::Ellipse);
            lamp.kind = LAMP_AREA | camera | if ellipse { LAMP_ELLIPSE } else { 0 };
            let m = l.object_to_world;
            let (u, v) = (m.x_axis.truncate(), m.y_axis.truncate());
            let (len_u, len_v) = (u.length() * size, v.length() * size_y);
            lamp.axis_u = u.normalize().to_array();
            lamp.axis_v = v.normalize().to_array();
            lamp.len_u = len_u;
            lamp.len_v = len_v;
            lamp.normal = direction.to_array();
            let area = len_u as f64 * len_v as f64 * if ellipse { PI / 4.0 } else { 1.0 };
            // One-sided Lambertian: power = π · radiance · area.
            lamp.emission = emission(1.0 / (PI * area));
        }
        LightShape::Sun { angle_deg } => {
            lamp.kind = LAMP_SUN | camera;
            lamp.position = (-direction).to_array();
            let half = (angle_deg as f64).to_radians() * 0.5;
            lamp.radius = (2.0 * (half * 0.5).sin().powi(2)) as f32;
            // Cycles: radiance = strength / (π sin² of the half-angle); a delta sun gives
            // the irradiance `strength` on a plane facing it.
            lamp.emission = emission(if half > 0.0 { 1.0 / (PI * half.sin().powi(2)) } else { 1.0 });
        }
    }
    lamp
}

/// Half the diagonal of a box, for [`lamp_table`]; 1 m when the box is empty.
pub fn scene_radius(bounds_min: Vec3, bounds_max: Vec3) -> f32 {
    let half = 0.5 * (bounds_max - bounds_min).length();
    if half.is_finite() && bounds_max.cmpge(bounds_min).all() && half > 0.0 { half } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Mat4;

    fn light(shape: LightShape, power: f32) -> Light {
        Light { shape, color: Vec3::ONE, power, visible_to_camera: false, object_to_world: Mat4::IDENTITY }
    }

    #[test]
    fn shares_without_lamps_are_the_frames() {
        for (sun, emitters, expected) in [(false, false, 0.0), (true, false, 1.0), (true, true, 0.5)] {
            let info = lamp_table(&[], sun, emitters, 1.0, LightSampler::Power).info;
            assert_eq!((info.sun_share, info.emitter_share, info.lamp_share), (expected, 1.0 - expected, 0.0));
        }
        let info =
            lamp_table(&[light(LightShape::Sun { angle_deg: 1.0 }, 1.0)], true, true, 1.0, LightSampler::Power).info;
        assert_eq!((info.sun_share, info.emitter_share, info.lamp_share), (1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0));
    }

    #[test]
    fn with_the_tree_the_lamp_table_picks_suns_only() {
        let sun = light(LightShape::Sun { angle_deg: 1.0 }, 1.0);
        let point = light(LightShape::Point { radius: 0.1, soft_falloff: false }, 100.0);
        let table = lamp_table(&[point.clone(), sun, point.clone()], true, false, 1.0, LightSampler::Tree);
        assert_eq!(table.lamps.iter().map(|l| l.cdf).collect::<Vec<_>>(), [0.0, 1.0, 1.0]);
        let info = table.info;
        assert_eq!((info.sun_share, info.emitter_share, info.lamp_share), (1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0));
        let info = lamp_table(&[point], false, false, 1.0, LightSampler::Tree).info;
        assert_eq!((info.sun_share, info.emitter_share, info.lamp_share), (0.0, 1.0, 0.0));
    }

    #[test]
    fn cycles_unit_conversions() {
        let point = |radius| light(LightShape::Point { radius, soft_falloff: true }, 100.0);
        let intensity = gpu_lamp(&point(0.0)).emission[0] as f64;
        assert!((intensity - 100.0 / (4.0 * PI)).abs() < 1e-5);
        // A sphere of radius r and radiance L sends out L · π · 4π r².
        let l = gpu_lamp(&point(0.5)).emission[0] as f64;
        assert!((l * PI * 4.0 * PI * 0.25 - 100.0).abs() < 1e-3);
        let area = light(LightShape::Area { shape: AreaShape::Disk, size: 2.0, size_y: 2.0 }, 100.0);
        assert!((gpu_lamp(&area).emission[0] as f64 * PI * PI - 100.0).abs() < 1e-3);
        let lamps = lamp_table(&[point(0.0), point(0.0), area], false, false, 1.0, LightSampler::Power).lamps;
        assert_eq!(lamps.iter().map(|l| l.cdf).collect::<Vec<_>>(), [1.0 / 3.0, 2.0 / 3.0, 1.0]);
    }
}
