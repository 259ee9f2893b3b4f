// Rays, conservative ray–box tests and self-intersection-free ray origins.

struct Ray {
    origin: vec3f,
    direction: vec3f,
}

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

// Moves a ray origin off the surface along the geometric normal by a few ULPs
// of its own magnitude, so that no global epsilon is needed at any scale
// (Wächter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems, ch. 6). `n` points to the side the new ray leaves into.
fn offset_ray_origin(p: vec3f, n: vec3f) -> vec3f {
    let ORIGIN: f32 = 1.0 / 32.0;
    let FLOAT_SCALE: f32 = 1.0 / 65536.0;
    let INT_SCALE: f32 = 256.0;
    let of_i = vec3i(INT_SCALE * n);
    let p_i = bitcast<vec3f>(bitcast<vec3i>(p) + select(of_i, -of_i, p < vec3f(0.0)));
    return select(p_i, p + FLOAT_SCALE * n, abs(p) < vec3f(ORIGIN));
}
