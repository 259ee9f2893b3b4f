// The atmosphere's physical model (Hillaire, "A Scalable and Production Ready
// Sky and Atmosphere Rendering Technique", EGSR 2020): air molecules (Rayleigh)
// and aerosols (Mie) with exponential density profiles, an ozone layer that only
// absorbs, over a spherical Lambertian ground. Metres; altitudes are above the
// planet's surface. Shared by the table passes and the render march.
//
// The atmosphere's files use `atmosphere` (this struct) and `atmosphere_luts`
// (the tables) without including them: each program binds them its own way, and
// its entry file declares them (atmosphere_tables.wgsl: group 0, the tables
// writable; atmosphere_sky.wgsl, for the render programs: group 2, read-only).

//#include "constants.wgsl"

// Atmosphere: declared in src/layout.rs (GpuAtmosphere).
//#include "Atmosphere.struct.wgsl"

// Scattering and extinction coefficients at one altitude.
struct Medium {
    rayleigh: vec3f,
    mie: vec3f,
    extinction: vec3f,
}

fn medium_at(h: f32) -> Medium {
    let rayleigh = atmosphere.rayleigh_scattering * exp(-h / atmosphere.rayleigh_scale_height);
    let aerosols = exp(-h / atmosphere.mie_scale_height);
    let mie = atmosphere.mie_scattering * aerosols;
    let ozone = max(0.0, 1.0 - abs(h - atmosphere.ozone_center) / atmosphere.ozone_half_width);
    let absorption = atmosphere.mie_absorption * aerosols + atmosphere.ozone_absorption * ozone;
    return Medium(rayleigh, mie, rayleigh + mie + absorption);
}

// Phase functions of the cosine ν between the view and the sun directions (per steradian).
fn rayleigh_phase(nu: f32) -> f32 {
    return 3.0 / (16.0 * PI) * (1.0 + nu * nu);
}

// Henyey–Greenstein.
fn mie_phase(nu: f32) -> f32 {
    let g = atmosphere.mie_g;
    let denominator = max(1.0 + g * g - 2.0 * g * nu, 1e-8);
    return (1.0 - g * g) / (4.0 * PI * denominator * sqrt(denominator));
}
