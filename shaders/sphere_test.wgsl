fn test_sphere(index: u32, origin: vec3f, direction: vec3f, hit: ptr<function, Hit>) {
    let s = spheres[index];
    let t = intersect_sphere(origin, direction, s.center, s.radius, (*hit).t);
    if t < INFINITY {
        *hit = Hit(t, HIT_SPHERE, index, 0u, 0.0, 0.0);
    }
}

fn sphere_surface(hit: Hit, origin: vec3f, direction: vec3f) -> Surface {
    let s = spheres[hit.primitive];
    let n = normalize(origin + hit.t * direction - s.center);
    // Re-projecting onto the sphere removes the error of origin + t·direction along the normal.
    return Surface(s.center + s.radius * n, n, n, s.material);
}
