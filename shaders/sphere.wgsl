// Numerically robust ray–sphere intersection (Haines, Günther & Akenine-Möller,
// "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems, ch. 7).
// `direction` is unit length. Returns the nearest t in (0, t_max) or INFINITY.
fn intersect_sphere(origin: vec3f, direction: vec3f, center: vec3f, radius: f32, t_max: f32) -> f32 {
    let f = origin - center;
    let b = -dot(f, direction);
    // Squared distance from the centre to the line, from a vector rather than
    // from b² − c, which cancels catastrophically for far or large spheres.
    let l = f + b * direction;
    let discriminant = radius * radius - dot(l, l);
    if discriminant < 0.0 {
        return INFINITY;
    }
    let len_f = length(f);
    // |f|² − r² as a product, so that an origin on a planet-sized sphere keeps its digits.
    let c = (len_f - radius) * (len_f + radius);
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
