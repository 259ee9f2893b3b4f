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

// Mirrored by `GpuAtmosphere` in src/layout.rs.
struct Atmosphere {
    // Scattering coefficients at the ground, per metre.
    rayleigh_scattering: vec3f,
    bottom_radius: f32,
    mie_scattering: vec3f,
    top_altitude: f32,
    mie_absorption: vec3f,
    rayleigh_scale_height: f32,
    ozone_absorption: vec3f,
    mie_scale_height: f32,
    ground_albedo: vec3f,
    mie_g: f32,
    // The ozone's density is a tent of this centre and half width.
    ozone_center: f32,
    ozone_half_width: f32,
    // Altitude of rt's y = 0 plane.
    ground_altitude: f32,
    // March steps per ray.
    steps: u32,
    // Entries of the tables in `atmosphere_luts`: transmittance, then the planes
    // of the multiple scattering table, then the ground's rows.
    transmittance_size: vec2u,
    scattering_size: vec2u,
    scattering_offset: u32,
    ground_offset: u32,
    // 1 to add light scattered more than once, 0 for single scattering only.
    multiple_scattering: f32,
    _pad0: u32,
}

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
