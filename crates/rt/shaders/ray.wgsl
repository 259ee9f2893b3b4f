// Rays, conservative ray–box tests and self-intersection-free ray origins.

//#include "constants.wgsl"

// What traversal needs of a ray, precomputed once per ray (and per instance).
struct TraversalRay {
    origin: vec3f,
    direction: vec3f,
    inv_direction: vec3f,
}

fn traversal_ray(origin: vec3f, direction: vec3f) -> TraversalRay {
    // A zero component would give 0 * inf = NaN in the slab test; a tiny
    // substitute keeps every slab finite and the test conservative.
    let tiny = vec3f(1e-30);
    let safe = select(direction, select(-tiny, tiny, direction >= vec3f(0.0)), abs(direction) < tiny);
    return TraversalRay(origin, direction, 1.0 / safe);
}

// (1 + 2γ₃) with γₙ = nε / (1 − nε), ε = 2⁻²⁴: the factor by which the far slab
// distance is grown so that rounding never makes a box hit a miss
// (Ize, "Robust BVH Ray Traversal", JCGT 2013).
const BOX_TMAX_SCALE: f32 = 1.0000003576;

// Distance at which the ray enters the box, or INFINITY if it misses it before t_max.
fn ray_box_entry(ray: TraversalRay, box_min: vec3f, box_max: vec3f, t_max: f32) -> f32 {
    let t0 = (box_min - ray.origin) * ray.inv_direction;
    let t1 = (box_max - ray.origin) * ray.inv_direction;
    let t_near = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
    let t_far = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), t_max)) * BOX_TMAX_SCALE;
    return select(INFINITY, t_near, t_near <= t_far);
}

// γₙ = nε / (1 − nε), ε = 2⁻²⁴: the bound on the relative error of n
// rounded f32 operations (Higham; pbrt-v4 §6.8).
fn gamma(n: f32) -> f32 {
    let e = n * 5.9604645e-8;
    return e / (1.0 - e);
}

// The next f32 above v (below, with `up` false). Zero steps to the smallest
// normal number, since GPUs flush denormals to zero.
fn next_float(v: f32, up: bool) -> f32 {
    if v == 0.0 {
        return select(-1.1754944e-38, 1.1754944e-38, up);
    }
    let bits = bitcast<u32>(v);
    return bitcast<f32>(select(bits - 1u, bits + 1u, (v > 0.0) == up));
}

// Moves a ray origin off the surface so that the new ray cannot hit the
// surface it leaves: `p` lies within ±`error` (per component) of the true
// surface point, so moving it by the error's extent along the normal, then one
// more float away, puts it strictly on the side `n` points to. No epsilon, at
// any scale (pbrt-v4's OffsetRayOrigin, §6.8.6). Wächter & Binder's fixed
// 256-ULP offset (Ray Tracing Gems ch. 6) fails where a point's components
// differ by orders of magnitude: an error of the large components projected on
// the normal outgrows the offset of the small ones.
fn offset_ray_origin(p: vec3f, error: vec3f, n: vec3f) -> vec3f {
    let offset = dot(abs(n), error) * n;
    let moved = p + offset;
    return vec3f(
        select(moved.x, next_float(moved.x, offset.x > 0.0), offset.x != 0.0),
        select(moved.y, next_float(moved.y, offset.y > 0.0), offset.y != 0.0),
        select(moved.z, next_float(moved.z, offset.z > 0.0), offset.z != 0.0),
    );
}
