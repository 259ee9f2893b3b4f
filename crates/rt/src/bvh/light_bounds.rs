//! The light tree's bounds of each light (pbrt-v4's `Light::Bounds`): where it is, which
//! way it emits and its power, in one unit for lamps and emitters alike (the power a
//! lamp of Blender's watts sends out, in luminance).

use super::light_tree::{DirectionCone, LightBounds};
use crate::layout::*;
use crate::scene::{Light, luminance};
use glam::{DVec3, Vec3};
use std::f64::consts::PI;

/// A point or spot lamp emits into every direction from its sphere (or facing disk); a
/// spot only within its cone, which the bounds of its position widen as seen from afar.
/// Area lamps emit on one side. Suns are not in the tree: `None`.
pub fn lamp_bounds(light: &Light, lamp: &GpuLamp) -> Option<LightBounds> {
    let phi = (light.power as f64 * luminance(light.color.to_array()) as f64) as f32;
    let p = Vec3::from(lamp.position);
    match lamp.kind & 0xff {
        LAMP_POINT | LAMP_SPOT => {
            let r = Vec3::splat(lamp.radius);
            let spot = lamp.kind & 0xff == LAMP_SPOT;
            let normals = if spot {
                DirectionCone { w: Vec3::from(lamp.axis_u), cos_theta: lamp.len_u }
            } else {
                DirectionCone::ENTIRE_SPHERE
            };
            // A spot's light leaves within its cone (as seen from the bounds, which the
            // importance accounts for); a point's, from a surface facing all ways.
            let cos_theta_e = if spot { 1.0 } else { 0.0 };
            Some(LightBounds { min: p - r, max: p + r, phi, normals, cos_theta_e, two_sided: false })
        }
        LAMP_AREA => {
            let (u, v) = (Vec3::from(lamp.axis_u) * lamp.len_u * 0.5, Vec3::from(lamp.axis_v) * lamp.len_v * 0.5);
            let corners = [p + u + v, p + u - v, p - u + v, p - u - v];
            let (min, max) = corners.iter().fold((p, p), |(lo, hi), c| (lo.min(*c), hi.max(*c)));
            let normals = DirectionCone { w: Vec3::from(lamp.normal), cos_theta: 1.0 };
            Some(LightBounds { min, max, phi, normals, cos_theta_e: 0.0, two_sided: false })
        }
        _ => None,
    }
}

/// An emissive triangle (world vertices) of radiance luminance `luminance`: both sides emit.
pub fn triangle_bounds(a: DVec3, b: DVec3, c: DVec3, luminance: f64) -> LightBounds {
    let n = (b - a).cross(c - a);
    let area = 0.5 * n.length();
    let (min, max) = (a.min(b).min(c).as_vec3(), a.max(b).max(c).as_vec3());
    // Lambertian, both sides: π L A each.
    let phi = (2.0 * PI * area * luminance) as f32;
    let normals = DirectionCone { w: n.normalize().as_vec3(), cos_theta: 1.0 };
    LightBounds { min, max, phi, normals, cos_theta_e: 0.0, two_sided: true }
}

/// An emissive sphere of radiance luminance `luminance`.
pub fn sphere_bounds(s: &GpuSphere, luminance: f64) -> LightBounds {
    let (c, r) = (Vec3::from(s.center), Vec3::splat(s.radius));
    let phi = (PI * 4.0 * PI * (s.radius as f64).powi(2) * luminance) as f32;
    LightBounds {
        min: c - r,
        max: c + r,
        phi,
        normals: DirectionCone::ENTIRE_SPHERE,
        cos_theta_e: 0.0,
        two_sided: false,
    }
}
