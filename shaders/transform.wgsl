// Affine transforms of points, vectors and normals by the 3×4 matrices of an
// instance, and the error bound of a transformed point.

//#include "ray.wgsl"

fn transform_point(m: array<vec4f, 3>, p: vec3f) -> vec3f {
    let h = vec4f(p, 1.0);
    return vec3f(dot(m[0], h), dot(m[1], h), dot(m[2], h));
}

fn transform_vector(m: array<vec4f, 3>, v: vec3f) -> vec3f {
    return vec3f(dot(m[0].xyz, v), dot(m[1].xyz, v), dot(m[2].xyz, v));
}

// Normals transform by the inverse transpose: with world_to_object = M⁻¹, that is vᵀM⁻¹.
fn transform_normal_to_world(world_to_object: array<vec4f, 3>, n: vec3f) -> vec3f {
    return world_to_object[0].xyz * n.x + world_to_object[1].xyz * n.y + world_to_object[2].xyz * n.z;
}

// Error bound of an affine transform of a point known within ±error (pbrt-v4 §6.8.5).
fn transform_point_error(m: array<vec4f, 3>, p: vec3f, error: vec3f) -> vec3f {
    let a0 = abs(m[0]);
    let a1 = abs(m[1]);
    let a2 = abs(m[2]);
    let rounding = gamma(3.0) * vec3f(dot(a0.xyz, abs(p)) + a0.w, dot(a1.xyz, abs(p)) + a1.w, dot(a2.xyz, abs(p)) + a2.w);
    let carried = (1.0 + gamma(3.0)) * vec3f(dot(a0.xyz, error), dot(a1.xyz, error), dot(a2.xyz, error));
    return rounding + carried;
}
