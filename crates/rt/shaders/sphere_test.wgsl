// A sphere of the scene: the test traversal runs on it, and the surface at its hit.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "ray.wgsl"
//#include "sphere.wgsl"
//#include "hit.wgsl"

// Updates `hit` if the ray meets the sphere before it.
fn test_sphere(index: u32, origin: vec3f, direction: vec3f, hit: ptr<function, Hit>) {
    let s = spheres[index];
    let t = intersect_sphere(origin, direction, s.center, s.radius, s.k, (*hit).t);
    if t < INFINITY {
        *hit = Hit(t, HIT_SPHERE, index, 0u, 0.0, 0.0);
    }
}

fn sphere_surface(hit: Hit, origin: vec3f, direction: vec3f) -> Surface {
    let s = spheres[hit.primitive];
    let local = origin - s.center + hit.t * direction;
    let n = normalize(local);
    let on_sphere = s.radius * n;
    // Re-projected onto the sphere (pbrt-v4 §6.8.4), the point is as precise
    // as the centre's magnitude allows; for a sphere much larger than the
    // distance travelled (a planet under the camera) origin + t·direction is far
    // more precise. Its bound allows t a relative error of 8ε, 4× the largest
    // measured (tests/geometry_precision.rs).
    let reprojected_error = gamma(5.0) * abs(on_sphere) + gamma(3.0) * (abs(s.center) + abs(on_sphere));
    let along = origin + hit.t * direction;
    let along_error = gamma(3.0) * (abs(origin) + abs(hit.t * direction)) + 8.0 * 5.9604645e-8 * abs(hit.t * direction);
    if dot(along_error, along_error) < dot(reprojected_error, reprojected_error) {
        return Surface(along, along_error, n, n, s.material);
    }
    return Surface(s.center + on_sphere, reprojected_error, n, n, s.material);
}
