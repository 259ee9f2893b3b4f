//! `[sky] kind = "atmosphere"`: the keys that tune the physically based sky,
//! and their validation. The physical model they select lives in `src/sky/`.

use super::parse::{SceneError, Seg, Source};
use super::schema;
use glam::Vec3;

/// The atmosphere's knobs; the defaults give Hillaire's Earth (EGSR 2020).
#[derive(Clone, Debug, PartialEq)]
pub struct Atmosphere {
    /// Scales the aerosol (Mie) density: 0 is a clean Rayleigh sky, 1 Earth's average haze.
    pub turbidity: f32,
    /// Scales the air molecules' (Rayleigh) density.
    pub rayleigh_scale: f32,
    /// Asymmetry of the aerosols' Henyey–Greenstein phase function.
    pub mie_g: f32,
    /// Whether aerosols absorb (σa = 4.4e-6 /m), or only scatter.
    pub mie_absorption: bool,
    /// Whether the ozone layer absorbs (what keeps the zenith blue at sunset).
    pub ozone: bool,
    /// Lambertian albedo of the planet's surface.
    pub ground_albedo: Vec3,
    /// Altitude of rt's y = 0 plane above the planet's surface, in metres.
    pub ground_altitude_m: f32,
    /// Whether light scattered more than once is added (by the L₂/(1 − c) closure).
    pub multiple_scattering: bool,
    /// March steps per ray.
    pub steps: u32,
    /// Transmittance table: [view zenith, altitude] entries.
    pub transmittance_lut: [u32; 2],
    /// Multiple scattering table: [sun zenith, altitude] entries.
    pub multiple_scattering_lut: [u32; 2],
}

impl Default for Atmosphere {
    fn default() -> Self {
        Self {
            turbidity: 1.0,
            rayleigh_scale: 1.0,
            mie_g: 0.8,
            mie_absorption: true,
            ozone: true,
            ground_albedo: Vec3::splat(0.3),
            ground_altitude_m: 0.0,
            multiple_scattering: true,
            steps: 32,
            transmittance_lut: [256, 64],
            multiple_scattering_lut: [32, 32],
        }
    }
}

/// The keys of `[sky]` that only an atmosphere takes, to refuse them for other kinds.
pub(super) fn keys_present(s: &schema::Sky) -> Option<&'static str> {
    let present = [
        ("turbidity", s.turbidity.is_some()),
        ("rayleigh_scale", s.rayleigh_scale.is_some()),
        ("mie_g", s.mie_g.is_some()),
        ("mie_absorption", s.mie_absorption.is_some()),
        ("ozone", s.ozone.is_some()),
        ("ground_albedo", s.ground_albedo.is_some()),
        ("ground_altitude_m", s.ground_altitude_m.is_some()),
        ("multiple_scattering", s.multiple_scattering.is_some()),
        ("steps", s.steps.is_some()),
        ("transmittance_lut", s.transmittance_lut.is_some()),
        ("multiple_scattering_lut", s.multiple_scattering_lut.is_some()),
    ];
    present.iter().find(|(_, on)| *on).map(|(key, _)| *key)
}

pub(super) fn validate(src: &Source, p: &[Seg], s: &schema::Sky) -> Result<Atmosphere, SceneError> {
    let d = Atmosphere::default();
    let scale = |field: &str, value: Option<f32>, default: f32| {
        let v = value.unwrap_or(default);
        src.check(p, field, &[v], "in [0, 100]", |v| (0.0..=100.0).contains(&v)).map(|_| v)
    };
    let turbidity = scale("turbidity", s.turbidity, d.turbidity)?;
    let rayleigh_scale = scale("rayleigh_scale", s.rayleigh_scale, d.rayleigh_scale)?;
    let mie_g = s.mie_g.unwrap_or(d.mie_g);
    src.check(p, "mie_g", &[mie_g], "in (-1, 1)", |g| g.abs() < 1.0)?;
    let albedo = s.ground_albedo.map_or(d.ground_albedo.to_array(), schema::Color::rgb);
    src.check(p, "ground_albedo", &albedo, "in [0, 1]", |a| (0.0..=1.0).contains(&a))?;
    let ground_altitude_m = s.ground_altitude_m.unwrap_or(d.ground_altitude_m);
    src.check(p, "ground_altitude_m", &[ground_altitude_m], "in [0, 1000000]", |a| (0.0..=1e6).contains(&a))?;
    let steps = s.steps.unwrap_or(d.steps);
    if !(2..=256).contains(&steps) {
        return Err(src.error(p, "steps", format!("must be in 2..=256, got {steps}")));
    }
    let size = |field: &str, value: Option<[u32; 2]>, default: [u32; 2], max: u32| {
        let v = value.unwrap_or(default);
        match v.iter().find(|n| !(4..=max).contains(*n)) {
            Some(n) => Err(src.error(p, field, format!("entries must be in 4..={max}, got {n}"))),
            None => Ok(v),
        }
    };
    Ok(Atmosphere {
        turbidity,
        rayleigh_scale,
        mie_g,
        mie_absorption: s.mie_absorption.unwrap_or(d.mie_absorption),
        ozone: s.ozone.unwrap_or(d.ozone),
        ground_albedo: albedo.into(),
        ground_altitude_m,
        multiple_scattering: s.multiple_scattering.unwrap_or(d.multiple_scattering),
        steps,
        transmittance_lut: size("transmittance_lut", s.transmittance_lut, d.transmittance_lut, 1024)?,
        multiple_scattering_lut: size(
            "multiple_scattering_lut",
            s.multiple_scattering_lut,
            d.multiple_scattering_lut,
            256,
        )?,
    })
}
