// Numerically robust ray–sphere intersection (Haines, Günther & Akenine-Möller,
// "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems, ch. 7),
// with c computed so that a ray from just above a planet-sized sphere keeps
// the digits of its height (see `sphere_c`).
// `direction` is unit length. Returns the nearest t in (0, t_max) or INFINITY.

//#include "constants.wgsl"

// c = |o − centre|² − r², the quantity whose cancellation ruins rays that
// start near a large sphere: in f32, o − centre keeps only the digits of the
// centre's magnitude (half a metre for a planet). Expanded as |o|² − 2 o·centre
// + k, with k = |centre|² − r² computed exactly on the host, nothing large
// cancels when the origin is near the world's origin; the direct form stays
// better when it is near the sphere's centre. The form with the smaller
// rounding bound is used.
fn sphere_c(origin: vec3f, center: vec3f, radius: f32, k: f32) -> f32 {
    let f = origin - center;
    let direct = dot(f, f) - radius * radius;
    let expanded = dot(origin, origin) - 2.0 * dot(origin, center) + k;
    // Rounding bounds up to constant factors, in max-norms to spare square roots.
    let o = max_component(abs(origin));
    let c = max_component(abs(center));
    let direct_error = max_component(abs(f)) * max(o, c);
    let expanded_error = o * (o + 2.0 * c) + abs(k);
    return select(direct, expanded, expanded_error < direct_error);
}

fn max_component(v: vec3f) -> f32 {
    return max(v.x, max(v.y, v.z));
}

fn intersect_sphere(origin: vec3f, direction: vec3f, center: vec3f, radius: f32, k: f32, t_max: f32) -> f32 {
    let f = origin - center;
    let b = -dot(f, direction);
    let c = sphere_c(origin, center, radius, k);
    var discriminant: f32;
    if dot(f, f) > 4.0 * radius * radius {
        // From afar, b² − c cancels: use the squared distance from the centre to the line.
        let l = f + b * direction;
        discriminant = radius * radius - dot(l, l);
    } else {
        discriminant = b * b - c;
    }
    if discriminant < 0.0 {
        return INFINITY;
    }
    let q = b + select(-1.0, 1.0, b >= 0.0) * sqrt(discriminant);
    var t0 = c / q;
    var t1 = q;
    if t0 > t1 {
        let t = t0;
        t0 = t1;
        t1 = t;
    }
    if t0 > 0.0 && t0 < t_max {
        return t0;
    }
    if t1 > 0.0 && t1 < t_max {
        return t1;
    }
    return INFINITY;
}
