// Traversal alone, for throughput benchmarks and for checking traversal
// against a CPU reference: one ray in, its closest hit out.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "rng.wgsl"
//#include "ray.wgsl"
//#include "camera.wgsl"
//#include "directions.wgsl"
//#include "hit.wgsl"
//#include "traverse.wgsl"
//#include "surface.wgsl"

// TraceRay: declared in src/layout.rs (GpuTraceRay).
//#include "TraceRay.struct.wgsl"

// TraceHit: declared in src/layout.rs (GpuTraceHit).
//#include "TraceHit.struct.wgsl"

@group(1) @binding(0) var<storage, read_write> trace_rays: array<TraceRay>;
@group(1) @binding(1) var<storage, read_write> trace_hits: array<TraceHit>;

fn trace_one(i: u32) {
    let r = trace_rays[i];
    var overflowed = false;
    let hit = intersect_scene(r.origin, r.direction, r.t_max, false, &overflowed);
    var primitive = EMPTY_LINK;
    if hit.kind == HIT_TRIANGLE {
        primitive = hit.primitive;
    } else if hit.kind == HIT_SPHERE {
        primitive = hit.primitive | SPHERE_BIT;
    }
    trace_hits[i] = TraceHit(select(INFINITY, hit.t, hit.kind != HIT_NONE), primitive, hit.instance, u32(overflowed), hit.b1, hit.b2, 0u, 0u);
}

// Launches over 65535 workgroups spill into y.
fn ray_index(id: vec3u, groups: vec3u) -> u32 {
    return id.x + id.y * groups.x * 64u;
}

@compute @workgroup_size(64)
fn trace(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
    let i = ray_index(id, groups);
    if i < arrayLength(&trace_rays) {
        trace_one(i);
    }
}

// Camera rays for the throughput benchmark, one per pixel, written as TraceRays.
@compute @workgroup_size(64)
fn generate_camera_rays(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
    let i = ray_index(id, groups);
    if i >= frame.width * frame.height || i >= arrayLength(&trace_rays) {
        return;
    }
    let pixel = vec2u(i % frame.width, i / frame.width);
    var rng = rng_for_sample(i, frame.sample_base, frame.seed);
    let ray = camera_ray(pixel, &rng);
    trace_rays[i] = TraceRay(ray.origin, ray.t_max, ray.direction, 0u);
}

// Turns each ray with a hit into a new ray leaving that hit as a path would:
// its origin the surface point the integrator computes, moved off the surface
// by its error bound, and its direction cosine-distributed on the side the ray
// came from (`side` = 1: diffuse bounces, the incoherent rays a path tracer
// mostly traces) or the far side (`side` = −1: rays going through). Misses
// become rays with t_max = 0, which cost a root visit and nothing else.
fn spawn_ray(i: u32, side: f32) {
    let r = trace_rays[i];
    let h = trace_hits[i];
    if h.primitive == EMPTY_LINK {
        trace_rays[i] = TraceRay(r.origin, 0.0, r.direction, 0u);
        return;
    }
    let kind = select(HIT_TRIANGLE, HIT_SPHERE, (h.primitive & SPHERE_BIT) != 0u);
    let hit = Hit(h.t, kind, h.primitive & ~SPHERE_BIT, h.instance, h.b1, h.b2);
    let surface = surface_at(hit, r.origin, r.direction);
    let facing = select(surface.geometric_normal, -surface.geometric_normal, dot(surface.geometric_normal, r.direction) > 0.0);
    let n = side * facing;
    var rng = rng_for_sample(i, frame.sample_base + 1u, frame.seed);
    let d = tangent_frame(n) * sample_cosine_hemisphere(rng_next2(&rng));
    trace_rays[i] = TraceRay(offset_ray_origin(surface.position, surface.position_error, n), INFINITY, d, 0u);
}

@compute @workgroup_size(64)
fn generate_diffuse_rays(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
    let i = ray_index(id, groups);
    if i < arrayLength(&trace_rays) {
        spawn_ray(i, 1.0);
    }
}

@compute @workgroup_size(64)
fn generate_through_rays(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
    let i = ray_index(id, groups);
    if i < arrayLength(&trace_rays) {
        spawn_ray(i, -1.0);
    }
}
