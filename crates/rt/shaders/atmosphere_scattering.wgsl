// The multiple scattering table, at each altitude h and sun zenith cosine μs,
// per unit solar irradiance. Planes 0, 1, 2 hold the isotropic means L₂, L₃, L₄
// of the radiance arriving there scattered (by the air or the ground) once,
// twice and three times; L₂ is Hillaire's second order, with the real phase
// functions; each further order scatters the one before isotropically, as the
// march does with every order ≥ 2. The ground's rows 0, 1, 2 hold its
// irradiance E₁, E₂, E₃ by the sky's light of those orders.
//
// Then the seed's closure: each order is c times the one before, so
// Σᵢ≥₂ Lᵢ = L₂ / (1 − c). It holds from the third order on; the second is
// special (the sun's light scattered with the real phase functions, the ground
// lit by the sun), and L₃/L₂ is 0.29 at noon and 0.71 in twilight where the
// series settles at 0.41 (blue, at the ground: tests/atmosphere measures it).
// So plane 3 holds Ψ = L₂ + L₃ + L₄ / (1 − c) with c = L₄/L₃, and ground row 3
// E₂ + E₃ / (1 − c). (Hillaire's f_ms, the transfer of an L₂ assumed the same
// everywhere around, falls short of c at altitude — by 40% at 44 km in blue —
// since the air below is brighter: its skies reached 39.1 dB where these reach
// 47.8, worst cases against tests/atmosphere's reference.)
//
// One workgroup per table entry integrates over the sphere of directions: cells
// of equal solid angle in (cosine ν of the angle to the sun, azimuth about the
// sun), in which the phase functions are integrated exactly, so that the Mie
// forward peak (g = 0.8: most of it within 15° of the sun) is not undersampled.
//
// Its passes belong to the program of atmosphere_tables.wgsl, which declares the
// tables they write.

//#include "constants.wgsl"
//#include "segment.wgsl"
//#include "atmosphere.wgsl"
//#include "atmosphere_path.wgsl"
//#include "atmosphere_steps.wgsl"
//#include "atmosphere_lut.wgsl"

// 256 cells: 8 × 8 for the isotropic orders would halve their cost and lose 2 dB.
const SIDE: u32 = 16u;
const CELLS: u32 = SIDE * SIDE;
const LANES: u32 = 64u;
// Steps of each march over the sphere: the table is smooth, and every step is
// integrated exactly for its coefficients.
const TABLE_STEPS: u32 = 32u;
// The closure's c is capped where the orders do not decrease (deep night).
const MAX_RATIO: f32 = 0.9;

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

fn plane_index(plane: u32, entry: vec2u) -> u32 {
    let size = atmosphere.scattering_size;
    return atmosphere.scattering_offset + plane * size.x * size.y + entry.y * size.x + entry.x;
}

fn ground_index(row: u32, column: u32) -> u32 {
    return atmosphere.ground_offset + row * atmosphere.scattering_size.x + column;
}

// Radiance arriving at altitude h from the centre of cell `cell`, scattered
// `plane` + 1 times, and that cell's zenith cosine. Once: the sun's light
// scattered by the air, or reflected by the ground. More: the plane before,
// scattered isotropically, or the ground row before, reflected.
fn radiance_from_cell(h: f32, mu_s: f32, cell: u32, plane: u32) -> vec4f {
    let i_nu = cell / SIDE;
    let i_psi = cell % SIDE;
    let a = -1.0 + 2.0 * f32(i_nu) / f32(SIDE);
    let b = -1.0 + 2.0 * f32(i_nu + 1u) / f32(SIDE);
    let nu = 0.5 * (a + b);
    let psi = 2.0 * PI * (f32(i_psi) + 0.5) / f32(SIDE);
    // Zenith cosine of the direction at angle acos(ν) from a sun at zenith cosine μs.
    let sin_s = sqrt(max(0.0, 1.0 - mu_s * mu_s));
    let mu = clamp(nu * mu_s - sqrt(max(0.0, 1.0 - nu * nu)) * cos(psi) * sin_s, -1.0, 1.0);
    let phases = cell_phases(a, b);
    let ray = planet_ray(h, mu, mu_s, nu);
    var radiance = vec3f(0.0);
    var transmittance = vec3f(1.0);
    if ray.t_end > ray.t_start {
        let steps = march_steps(ray, TABLE_STEPS);
        var t0 = step_edge(steps, 0u);
        for (var i = 0u; i < steps.count; i++) {
            let t1 = step_edge(steps, i + 1u);
            let t = 0.5 * (t0 + t1);
            let ht = altitude_along(ray, t);
            let m = medium_at(ht);
            let mu_t = sun_cosine_along(ray, t, ht);
            var source: vec3f;
            if plane == 0u {
                source = (m.rayleigh * phases.x + m.mie * phases.y) * transmittance_to_space(ht, mu_t);
            } else {
                source = (m.rayleigh + m.mie) * scattering_plane(plane - 1u, ht, mu_t);
            }
            let s = integrate_segment(m.extinction, source, t1 - t0);
            radiance += transmittance * s.radiance;
            transmittance *= s.transmittance;
            t0 = t1;
        }
    }
    if ray.hits_ground {
        let mu_g = sun_cosine_along(ray, ray.t_end, 0.0);
        var irradiance: vec3f;
        if plane == 0u {
            irradiance = max(mu_g, 0.0) * transmittance_to_space(0.0, mu_g);
        } else {
            irradiance = ground_row(plane - 1u, mu_g);
        }
        radiance += transmittance * atmosphere.ground_albedo / PI * irradiance;
    }
    return vec4f(radiance, mu);
}

var<workgroup> radiance_sums: array<vec3f, LANES>;
var<workgroup> irradiance_sums: array<vec3f, LANES>;

// Over the sphere at the entry's (h, μs): the mean of the gathered radiance
// (the isotropic phase 1/4π times each cell's 4π/N) into `plane`, and at the
// ground its irradiance into row `plane`.
fn integrate_sphere(entry: vec2u, lane: u32, plane: u32) {
    // The inverse of `scattering_coords`.
    let coords = vec2f(entry) / vec2f(atmosphere.scattering_size - 1u);
    let x = 2.0 * coords.x - 1.0;
    let h = atmosphere.top_altitude * coords.y * coords.y;
    var radiance = vec3f(0.0);
    var irradiance = vec3f(0.0);
    for (var cell = lane; cell < CELLS; cell += LANES) {
        let g = radiance_from_cell(h, x * abs(x), cell, plane);
        radiance += g.rgb;
        irradiance += g.rgb * max(g.w, 0.0);
    }
    radiance_sums[lane] = radiance;
    irradiance_sums[lane] = irradiance;
    for (var stride = LANES / 2u; stride > 0u; stride /= 2u) {
        workgroupBarrier();
        if lane < stride {
            radiance_sums[lane] += radiance_sums[lane + stride];
            irradiance_sums[lane] += irradiance_sums[lane + stride];
        }
    }
    workgroupBarrier();
    if lane == 0u {
        atmosphere_luts[plane_index(plane, entry)] = vec4f(radiance_sums[0] / f32(CELLS), 1.0);
        if entry.y == 0u {
            atmosphere_luts[ground_index(plane, entry.x)] = vec4f(irradiance_sums[0] * (4.0 * PI / f32(CELLS)), 1.0);
        }
    }
}

// L₂ and E₁, L₃ and E₂, L₄ and E₃: one dispatch each, in that order.
@compute @workgroup_size(64)
fn build_second_order(@builtin(workgroup_id) entry: vec3u, @builtin(local_invocation_index) lane: u32) {
    integrate_sphere(entry.xy, lane, 0u);
}

@compute @workgroup_size(64)
fn build_third_order(@builtin(workgroup_id) entry: vec3u, @builtin(local_invocation_index) lane: u32) {
    integrate_sphere(entry.xy, lane, 1u);
}

@compute @workgroup_size(64)
fn build_fourth_order(@builtin(workgroup_id) entry: vec3u, @builtin(local_invocation_index) lane: u32) {
    integrate_sphere(entry.xy, lane, 2u);
}

// Ψ into plane 3 and the ground's higher orders into row 3.
@compute @workgroup_size(8, 8)
fn build_closure(@builtin(global_invocation_id) id: vec3u) {
    if any(id.xy >= atmosphere.scattering_size) {
        return;
    }
    let l2 = atmosphere_luts[plane_index(0u, id.xy)].rgb;
    let l3 = atmosphere_luts[plane_index(1u, id.xy)].rgb;
    let l4 = atmosphere_luts[plane_index(2u, id.xy)].rgb;
    let c = min(select(l4 / l3, vec3f(1.0), l3 <= vec3f(0.0)), vec3f(MAX_RATIO));
    atmosphere_luts[plane_index(3u, id.xy)] = vec4f(l2 + l3 + l4 / (1.0 - c), 1.0);
    if id.y == 0u {
        let e2 = atmosphere_luts[ground_index(1u, id.x)].rgb;
        let e3 = atmosphere_luts[ground_index(2u, id.x)].rgb;
        atmosphere_luts[ground_index(3u, id.x)] = vec4f(e2 + e3 / (1.0 - c), 1.0);
    }
}
