// The path-tracing megakernel: each invocation adds `samples_per_dispatch`
// samples to one pixel's running sums. Progressive: the host divides by the
// total sample count.

// rgb: sum of radiance; w: sum of squared luminance, for the standard error.
@group(1) @binding(0) var<storage, read_write> accumulation: array<vec4f>;

// Bounces after which Russian roulette may end a path.
const ROULETTE_START: u32 = 3u;

// Tested on the bits: compilers may fold `x != x` away under fast-math rules.
fn all_finite(v: vec3f) -> bool {
    let exponent = bitcast<vec3u>(v) & vec3u(0x7f800000u);
    return all(exponent != vec3u(0x7f800000u));
}

//#if emission
// Emission of the surface hit, MIS-weighted against light sampling when the
// bounce that found it could also have been found by next-event estimation.
fn emission_seen(m: Material, hit: Hit, surface: Surface, origin: vec3f, direction: vec3f, bsdf_pdf: f32) -> vec3f {
    var weight = 1.0;
    //#if nee
    if bsdf_pdf > 0.0 {
        var light_pdf = 0.0;
        if hit.kind == HIT_SPHERE {
            //#if spheres
            light_pdf = sphere_emitter_pdf(origin, spheres[hit.primitive], m.emission_luminance);
            //#endif
        } else {
            light_pdf = triangle_emitter_pdf(m.emission_luminance, hit.t, abs(dot(surface.geometric_normal, direction)));
        }
        weight = power_heuristic(bsdf_pdf, light_pdf);
    }
    //#endif
    return m.emission * weight;
}
//#endif

//#if sun
// The sun's disk seen by a ray that leaves the scene.
fn sun_seen(origin: vec3f, direction: vec3f, bsdf_pdf: f32) -> vec3f {
    if !in_sun_disk(direction) {
        return vec3f(0.0);
    }
    var weight = 1.0;
    //#if nee
    if bsdf_pdf > 0.0 {
        weight = power_heuristic(bsdf_pdf, frame.sun_select_probability / sun_solid_angle());
    }
    //#endif
    return sun_radiance_at(origin, direction) * weight;
}
//#endif

fn trace_path(pixel: vec2u, rng: ptr<function, Rng>) -> vec3f {
    var origin = frame.camera_position;
    var direction = camera_ray_direction(pixel, vec2f(rng_next(rng), rng_next(rng)));
    var radiance = vec3f(0.0);
    var throughput = vec3f(1.0);
    // Density of the last BSDF sample, for MIS; 0 after the camera and after delta lobes.
    var bsdf_pdf = 0.0;
    // The medium the path travels in: absorption and emission per metre.
    var medium_absorption = vec3f(0.0);
    var medium_emission = vec3f(0.0);
    for (var bounce = 0u; ; bounce++) {
        let hit = trace_scene(origin, direction, INFINITY);
        if stack_overflowed {
            atomicAdd(&stats[STAT_STACK_OVERFLOW], 1u);
        }
        //#if media
        let segment = integrate_segment(medium_absorption, medium_emission, hit.t);
        radiance += throughput * segment.radiance;
        throughput *= segment.transmittance;
        //#endif
        if hit.kind == HIT_NONE {
            radiance += throughput * sky_radiance(origin, direction);
            //#if sun
            radiance += throughput * sun_seen(origin, direction, bsdf_pdf);
            //#endif
            break;
        }
        //#if sky_atmosphere
        let air = atmosphere_segment(origin, direction, hit.t);
        radiance += throughput * air.radiance;
        throughput *= air.transmittance;
        //#endif
        let surface = surface_at(hit, origin, direction);
        let m = materials[surface.material];
        //#if emission
        radiance += throughput * emission_seen(m, hit, surface, origin, direction, bsdf_pdf);
        //#endif
        if bounce >= frame.max_bounces {
            break;
        }
        // The viewer is outside when the ray meets the outward normal head on.
        let entering = dot(surface.geometric_normal, direction) < 0.0;
        let n_geometric = select(-surface.geometric_normal, surface.geometric_normal, entering);
        let n_shading = select(-surface.shading_normal, surface.shading_normal, entering);
        let ctx = shading_context(m, n_shading, n_geometric, -direction, entering);
        //#if nee
        radiance += throughput * direct_light(ctx, surface.position, n_geometric, medium_absorption, rng);
        //#endif
        let s = bsdf_sample(ctx, rng);
        if !s.valid {
            break;
        }
        throughput *= s.weight;
        bsdf_pdf = s.pdf;
        //#if media
        // Crossing into a material adds its medium, leaving subtracts it: nested media add up.
        if s.transmitted {
            let sign = select(-1.0, 1.0, entering);
            medium_absorption = max(medium_absorption + sign * m.absorption, vec3f(0.0));
            medium_emission = max(medium_emission + sign * m.volume_emission, vec3f(0.0));
        }
        //#endif
        if bounce >= ROULETTE_START {
            let survival = min(max(throughput.x, max(throughput.y, throughput.z)), 0.95);
            if rng_next(rng) >= survival {
                break;
            }
            throughput /= survival;
        }
        origin = offset_ray_origin(surface.position, select(-n_geometric, n_geometric, dot(s.direction, n_geometric) > 0.0));
        direction = s.direction;
    }
    return radiance;
}

@compute @workgroup_size(8, 8)
fn render(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let pixel_index = id.y * frame.width + id.x;
    var sums = accumulation[pixel_index];
    for (var s = 0u; s < frame.samples_per_dispatch; s++) {
        var rng = rng_for_sample(pixel_index, frame.sample_base + s, frame.seed);
        let l = trace_path(id.xy, &rng);
        // A non-finite sample would poison the pixel for good: drop it and count it.
        if !all_finite(l) {
            atomicAdd(&stats[STAT_NON_FINITE], 1u);
            continue;
        }
        let y = luminance(l);
        // Added one sample at a time, so the sums do not depend on how samples are split into dispatches.
        sums += vec4f(l, y * y);
    }
    accumulation[pixel_index] = sums;
}
