// The multiple scattering table: at each altitude h and sun zenith cosine μs,
// L₂ (the isotropic average of the once-scattered radiance arriving there, sun
// light reflected once by the ground included) and c (the fraction of an
// isotropic in-scattered radiance, assumed the same everywhere around, that
// comes back after one more scattering, in the air or on the ground). Then
// Σᵢ≥₂ Lᵢ ≈ L₂ (1 + c + c² + …) = L₂ / (1 − c): Hillaire's f_ms, with the seed's
// closure, the real phase functions for the first scattering, and the ground
// in c. Everything is per unit solar irradiance.
//
// One workgroup per table entry integrates over the sphere of directions: cells
// of equal solid angle in (cosine ν of the angle to the sun, azimuth about the
// sun), in which the phase functions are integrated exactly, so that the Mie
// forward peak (g = 0.8: most of it within 15° of the sun) is not undersampled.

const NU_CELLS: u32 = 16u;
const AZIMUTH_CELLS: u32 = 16u;
const CELLS: u32 = NU_CELLS * AZIMUTH_CELLS;
const LANES: u32 = 64u;
// Steps of each march over the sphere: the table is smooth, and every step is
// integrated exactly for its coefficients.
const TABLE_STEPS: u32 = 32u;

// What one direction contributes, before weighting by its solid angle.
struct Gathered {
    // Once-scattered radiance, with the cell's mean phase.
    single: vec3f,
    // Radiance from a unit isotropic in-scattered radiance everywhere.
    transfer: vec3f,
    // Cosine of the direction's zenith angle.
    mu: f32,
}

// Mean of each phase function over ν ∈ [a, b], from their integrals.
fn cell_phases(a: f32, b: f32) -> vec2f {
    let rayleigh = 3.0 / (16.0 * PI) * (1.0 + (a * a + a * b + b * b) / 3.0);
    let g = atmosphere.mie_g;
    if abs(g) < 1e-4 {
        return vec2f(rayleigh, 1.0 / (4.0 * PI));
    }
    // ∫ HG dν = (1 − g²) / (4πg) (1 + g² − 2gν)^(−1/2).
    let upper = inverseSqrt(max(1.0 + g * g - 2.0 * g * b, 1e-8));
    let lower = inverseSqrt(max(1.0 + g * g - 2.0 * g * a, 1e-8));
    return vec2f(rayleigh, (1.0 - g * g) / (4.0 * PI * g) * (upper - lower) / (b - a));
}

// March from altitude h along the centre of cell `cell`; `ground_transfer` is G.
fn gather(h: f32, mu_s: f32, cell: u32, ground_transfer: vec3f) -> Gathered {
    let i_nu = cell / AZIMUTH_CELLS;
    let i_psi = cell % AZIMUTH_CELLS;
    let a = -1.0 + 2.0 * f32(i_nu) / f32(NU_CELLS);
    let b = -1.0 + 2.0 * f32(i_nu + 1u) / f32(NU_CELLS);
    let nu = 0.5 * (a + b);
    let psi = 2.0 * PI * (f32(i_psi) + 0.5) / f32(AZIMUTH_CELLS);
    // Zenith cosine of the direction at angle acos(ν) from a sun at zenith cosine μs.
    let sin_s = sqrt(max(0.0, 1.0 - mu_s * mu_s));
    let mu = clamp(nu * mu_s - sqrt(max(0.0, 1.0 - nu * nu)) * cos(psi) * sin_s, -1.0, 1.0);
    let phases = cell_phases(a, b);
    let ray = planet_ray(h, mu, mu_s, nu);
    var out = Gathered(vec3f(0.0), vec3f(0.0), mu);
    var transmittance = vec3f(1.0);
    if ray.t_end > ray.t_start {
        let steps = march_steps(ray, TABLE_STEPS);
        var t0 = step_edge(steps, 0u);
        for (var i = 0u; i < steps.count; i++) {
            let t1 = step_edge(steps, i + 1u);
            let t = 0.5 * (t0 + t1);
            let ht = altitude_along(ray, t);
            let m = medium_at(ht);
            let sun = transmittance_to_space(ht, sun_cosine_along(ray, t, ht));
            let single = integrate_segment(m.extinction, (m.rayleigh * phases.x + m.mie * phases.y) * sun, t1 - t0);
            let transfer = integrate_segment(m.extinction, m.rayleigh + m.mie, t1 - t0);
            out.single += transmittance * single.radiance;
            out.transfer += transmittance * transfer.radiance;
            transmittance *= single.transmittance;
            t0 = t1;
        }
    }
    if ray.hits_ground {
        let mu_g = sun_cosine_along(ray, ray.t_end, 0.0);
        let lambert = transmittance * atmosphere.ground_albedo / PI;
        out.single += lambert * max(mu_g, 0.0) * transmittance_to_space(0.0, mu_g);
        out.transfer += lambert * ground_transfer;
    }
    return out;
}

var<workgroup> single_sums: array<vec3f, LANES>;
var<workgroup> transfer_sums: array<vec3f, LANES>;
var<workgroup> irradiance_sums: array<vec3f, LANES>;

// Sums the three workgroup arrays into their first entries.
fn reduce_lanes(lane: u32) {
    for (var stride = LANES / 2u; stride > 0u; stride /= 2u) {
        workgroupBarrier();
        if lane < stride {
            single_sums[lane] += single_sums[lane + stride];
            transfer_sums[lane] += transfer_sums[lane + stride];
            irradiance_sums[lane] += irradiance_sums[lane + stride];
        }
    }
    workgroupBarrier();
}

// Integrates over the sphere at (h, μs): sums of single, transfer, and single × μ⁺.
fn integrate_sphere(h: f32, mu_s: f32, lane: u32, ground_transfer: vec3f) {
    var single = vec3f(0.0);
    var transfer = vec3f(0.0);
    var irradiance = vec3f(0.0);
    for (var cell = lane; cell < CELLS; cell += LANES) {
        let g = gather(h, mu_s, cell, ground_transfer);
        single += g.single;
        transfer += g.transfer;
        irradiance += g.single * max(g.mu, 0.0);
    }
    single_sums[lane] = single;
    transfer_sums[lane] = transfer;
    irradiance_sums[lane] = irradiance;
    reduce_lanes(lane);
}

// G: irradiance of the ground by a unit isotropic in-scattered radiance in the
// air above it (∫ transfer μ⁺ dω). One workgroup; the ground's own share is left
// out, as no ground lies above it.
@compute @workgroup_size(64)
fn build_ground_transfer(@builtin(local_invocation_index) lane: u32) {
    var transfer = vec3f(0.0);
    for (var cell = lane; cell < CELLS; cell += LANES) {
        let g = gather(0.0, 1.0, cell, vec3f(0.0));
        transfer += g.transfer * max(g.mu, 0.0);
    }
    transfer_sums[lane] = transfer;
    single_sums[lane] = vec3f(0.0);
    irradiance_sums[lane] = vec3f(0.0);
    reduce_lanes(lane);
    if lane == 0u {
        let index = atmosphere.ground_offset + atmosphere.scattering_size.x;
        atmosphere_luts[index] = vec4f(transfer_sums[0] * (4.0 * PI / f32(CELLS)), 1.0);
    }
}

// Entry (x, y) of the multiple scattering table: the inverse of `scattering_coords`.
@compute @workgroup_size(64)
fn build_multiple_scattering(@builtin(workgroup_id) entry: vec3u, @builtin(local_invocation_index) lane: u32) {
    let size = atmosphere.scattering_size;
    let coords = vec2f(entry.xy) / vec2f(size - 1u);
    let x = 2.0 * coords.x - 1.0;
    let mu_s = x * abs(x);
    let h = atmosphere.top_altitude * coords.y * coords.y;
    let ground_transfer = atmosphere_luts[atmosphere.ground_offset + size.x].rgb;
    integrate_sphere(h, mu_s, lane, ground_transfer);
    if lane == 0u {
        let index = entry.y * size.x + entry.x;
        let plane = size.x * size.y;
        // Uniform cells: the isotropic phase 1/4π times the solid angle 4π/N is 1/N.
        let mean = 1.0 / f32(CELLS);
        atmosphere_luts[atmosphere.scattering_offset + index] = vec4f(single_sums[0] * mean, 1.0);
        atmosphere_luts[atmosphere.scattering_offset + plane + index] = vec4f(transfer_sums[0] * mean, 1.0);
        if entry.y == 0u {
            let irradiance = irradiance_sums[0] * (4.0 * PI / f32(CELLS));
            atmosphere_luts[atmosphere.ground_offset + entry.x] = vec4f(irradiance, 1.0);
        }
    }
}
