//! The sun's fields of the frame constants.

use crate::layout::GpuFrame;
use crate::scene::Sun;
use glam::DVec3;

/// Unit vector towards the sun: elevation above the horizon, azimuth from +Z towards +X.
pub fn sun_direction(sun: &Sun) -> DVec3 {
    let (el, az) = ((sun.elevation_deg as f64).to_radians(), (sun.azimuth_deg as f64).to_radians());
    DVec3::new(el.cos() * az.sin(), el.sin(), el.cos() * az.cos())
}

/// 1 − cos of the angular radius, from the angular diameter, without cancellation.
pub fn sun_one_minus_cos(sun: &Sun) -> f64 {
    let quarter = (sun.angular_diameter_deg as f64).to_radians() / 4.0;
    2.0 * quarter.sin().powi(2)
}

/// The default sun's disk radiance: it gives an irradiance of π on a plane facing
/// it above the atmosphere, so that a white Lambertian surface lit head-on by it
/// has radiance 1. This fixes rt's radiance unit at about 1361/π W m⁻² sr⁻¹.
pub fn default_sun_radiance(sun: &Sun) -> [f32; 3] {
    let solid_angle = 2.0 * std::f64::consts::PI * sun_one_minus_cos(sun);
    [(std::f64::consts::PI / solid_angle) as f32; 3]
}

pub fn set_sun(frame: &mut GpuFrame, sun: Option<&Sun>, has_emitters: bool) {
    let Some(sun) = sun else {
        frame.sun_select_probability = 0.0;
        return;
    };
    frame.sun_direction = sun_direction(sun).as_vec3().to_array();
    frame.sun_one_minus_cos = sun_one_minus_cos(sun) as f32;
    frame.sun_radiance = sun.radiance.map_or_else(|| default_sun_radiance(sun), |r| r.to_array());
    // With other emitters, half the light samples go to the sun.
    frame.sun_select_probability = if has_emitters { 0.5 } else { 1.0 };
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sun(elevation_deg: f32, azimuth_deg: f32) -> Sun {
        Sun { elevation_deg, azimuth_deg, angular_diameter_deg: 0.53, radiance: None }
    }

    #[test]
    fn direction_follows_elevation_and_azimuth() {
        assert!((sun_direction(&sun(90.0, 0.0)) - DVec3::Y).length() < 1e-12);
        assert!((sun_direction(&sun(0.0, 0.0)) - DVec3::Z).length() < 1e-12);
        assert!((sun_direction(&sun(0.0, 90.0)) - DVec3::X).length() < 1e-12);
    }

    #[test]
    fn default_radiance_gives_irradiance_pi() {
        let s = sun(45.0, 0.0);
        let irradiance = default_sun_radiance(&s)[0] as f64 * 2.0 * std::f64::consts::PI * sun_one_minus_cos(&s);
        assert!((irradiance - std::f64::consts::PI).abs() < 1e-5);
    }
}
