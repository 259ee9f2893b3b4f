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

fn luminance(c: vec3f) -> f32 {
    return dot(c, vec3f(0.2126, 0.7152, 0.0722));
}

fn trace_path(pixel: vec2u, rng: ptr<function, Rng>) -> vec3f {
    var origin = frame.camera_position;
    var direction = camera_ray_direction(pixel, vec2f(rng_next(rng), rng_next(rng)));
    var radiance = vec3f(0.0);
    var throughput = vec3f(1.0);
    for (var bounce = 0u; ; bounce++) {
        let hit = trace_scene(origin, direction, INFINITY);
        if stack_overflowed {
            atomicAdd(&stats[STAT_STACK_OVERFLOW], 1u);
        }
        if hit.kind == HIT_NONE {
            radiance += throughput * sky_radiance(direction);
            break;
        }
        let surface = surface_at(hit, origin, direction);
        let m = materials[surface.material];
        radiance += throughput * surface_emission(m);
        if bounce >= frame.max_bounces {
            break;
        }
        // Both normals face the incoming ray, so every lobe works on one side.
        let n_geometric = select(surface.geometric_normal, -surface.geometric_normal, dot(surface.geometric_normal, direction) > 0.0);
        let n_shading = select(surface.shading_normal, -surface.shading_normal, dot(surface.shading_normal, n_geometric) < 0.0);
        let s = sample_bsdf(m, n_shading, n_geometric, rng);
        if !s.valid {
            break;
        }
        throughput *= s.weight;
        if bounce >= ROULETTE_START {
            let survival = min(max(throughput.x, max(throughput.y, throughput.z)), 0.95);
            if rng_next(rng) >= survival {
                break;
            }
            throughput /= survival;
        }
        origin = offset_ray_origin(surface.position, n_geometric);
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
