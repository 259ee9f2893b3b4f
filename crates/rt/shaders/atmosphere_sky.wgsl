// The atmosphere as the integrator sees it: the sky along rays that leave the
// scene, the aerial perspective of segments that end on a surface, and the
// transmittance of sunlight. rt's y = 0 plane lies at `ground_altitude` above
// the planet's surface, tangent to it under the world origin.
//
// Along a ray, light is integrated step by step, exactly for coefficients held
// constant over each step (integrate_segment: the seed's solution of
// x' = −σₑx + σₛL), with L = L₁ p(ν) from the transmittance table and the phase
// functions, plus Σᵢ≥₂ Lᵢ = L₂ / (1 − c) from the multiple scattering table.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "rng.wgsl"
//#include "segment.wgsl"
//#include "atmosphere.wgsl"
//#include "atmosphere_path.wgsl"
//#include "atmosphere_steps.wgsl"
//#include "atmosphere_lut.wgsl"

@group(2) @binding(0) var<uniform> atmosphere: Atmosphere;
@group(2) @binding(1) var<storage, read> atmosphere_luts: array<vec4f>;

// The ray's geometry relative to the planet, from world coordinates.
fn world_ray(origin: vec3f, direction: vec3f) -> PlanetRay {
    let bottom = atmosphere.bottom_radius;
    let y = origin.y + atmosphere.ground_altitude;
    // r² − R² and r − R from the horizontal distance and the height, without cancellation.
    let excess = origin.x * origin.x + origin.z * origin.z + y * (2.0 * bottom + y);
    let r = sqrt(max(excess + bottom * bottom, 0.0));
    let up = vec3f(origin.x, y + bottom, origin.z) / r;
    let h = excess / (r + bottom);
    return planet_ray(h, dot(direction, up), dot(frame.sun_direction, up), dot(direction, frame.sun_direction));
}

// Irradiance of the sun's disk above the atmosphere (zero without a sun).
fn solar_irradiance() -> vec3f {
    return frame.sun_radiance * (2.0 * PI * frame.sun_one_minus_cos);
}

// Where in its steps a ray samples: a hash of the ray, so that the samples of a
// pixel (whose rays differ) spread over the steps and their mean converges.
fn march_jitter(origin: vec3f, direction: vec3f) -> f32 {
    let d = bitcast<vec3u>(direction);
    let o = bitcast<vec3u>(origin);
    let hash = pcg_hash(d.x ^ pcg_hash(d.y ^ pcg_hash(d.z ^ pcg_hash(o.x ^ pcg_hash(o.y ^ pcg_hash(o.z))))));
    return (f32(hash >> 8u) + 0.5) * (1.0 / 16777216.0);
}

// Transmittance and in-scattered radiance over [0, t_max] of `ray`; without
// `lit`, transmittance only.
fn atmosphere_march(ray: PlanetRay, t_max: f32, jitter: f32, lit: bool) -> Segment {
    var result = Segment(vec3f(1.0), vec3f(0.0));
    if ray.t_end <= ray.t_start || t_max <= ray.t_start {
        return result;
    }
    let steps = march_steps(ray, atmosphere.steps);
    let irradiance = solar_irradiance();
    let phase_rayleigh = rayleigh_phase(ray.nu);
    let phase_mie = mie_phase(ray.nu);
    var t0 = step_edge(steps, 0u);
    for (var i = 0u; i < steps.count && t0 < t_max; i++) {
        let t1 = min(step_edge(steps, i + 1u), t_max);
        let t = t0 + jitter * (t1 - t0);
        let h = altitude_along(ray, t);
        let m = medium_at(h);
        var source = vec3f(0.0);
        if lit {
            let mu_s = sun_cosine_along(ray, t, h);
            let single = (m.rayleigh * phase_rayleigh + m.mie * phase_mie) * transmittance_to_space(h, mu_s);
            source = irradiance * (single + (m.rayleigh + m.mie) * multiple_scattering(h, mu_s));
        }
        let s = integrate_segment(m.extinction, source, t1 - t0);
        result.radiance += result.transmittance * s.radiance;
        result.transmittance *= s.transmittance;
        t0 = t1;
    }
    return result;
}

// Radiance reaching `origin` along a ray that leaves the scene: the air's
// in-scattering, and the ground where the ray meets the planet. The sun's disk is
// not included (sun_radiance_at gives it).
fn atmosphere_sky_radiance(origin: vec3f, direction: vec3f) -> vec3f {
    return atmosphere_sky(world_ray(origin, direction), march_jitter(origin, direction));
}

fn atmosphere_sky(ray: PlanetRay, jitter: f32) -> vec3f {
    let air = atmosphere_march(ray, INFINITY, jitter, true);
    var radiance = air.radiance;
    if ray.hits_ground {
        let mu_s = sun_cosine_along(ray, ray.t_end, 0.0);
        let sun = max(mu_s, 0.0) * transmittance_to_space(0.0, mu_s);
        let lambert = atmosphere.ground_albedo / PI * solar_irradiance();
        radiance += air.transmittance * lambert * (sun + ground_sky_irradiance(mu_s));
    }
    return radiance;
}

// Aerial perspective over the first t metres of a ray that ends on a surface.
fn atmosphere_segment(origin: vec3f, direction: vec3f, t: f32) -> Segment {
    return atmosphere_march(world_ray(origin, direction), t, march_jitter(origin, direction), true);
}

// Transmittance of the air over the first t metres of a ray (for light samples).
fn atmosphere_transmittance_along(origin: vec3f, direction: vec3f, t: f32) -> vec3f {
    return atmosphere_march(world_ray(origin, direction), t, march_jitter(origin, direction), false).transmittance;
}

// Transmittance from `position` to space along `direction`: zero in the earth's shadow.
fn atmosphere_transmittance_to_space(position: vec3f, direction: vec3f) -> vec3f {
    let ray = world_ray(position, direction);
    return transmittance_to_space(ray.h0, ray.mu);
}
