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

// An instance keeps only its world-to-object matrix; the object-to-world one is derived
// here, where a hit or a light sample needs it (the adjugate over the determinant).
struct AffineInverse {
    m: array<vec4f, 3>,
    // Bound on |computed − exact| of each entry of `m`'s 3×3 part, and of its translation.
    linear_error: array<vec3f, 3>,
    translation_error: vec3f,
}

fn affine_inverse(w: array<vec4f, 3>) -> AffineInverse {
    // Meshes placed untransformed are the common case: their inverse is themselves,
    // exactly, and skipping the inversion is measurably faster (docs/measured-choices.md).
    if all(w[0] == vec4f(1.0, 0.0, 0.0, 0.0)) && all(w[1] == vec4f(0.0, 1.0, 0.0, 0.0)) && all(w[2] == vec4f(0.0, 0.0, 1.0, 0.0)) {
        return AffineInverse(w, array<vec3f, 3>(vec3f(0.0), vec3f(0.0), vec3f(0.0)), vec3f(0.0));
    }
    let a = w[0].xyz;
    let b = w[1].xyz;
    let c = w[2].xyz;
    // Columns of the adjugate: A·[b×c, c×a, a×b] = det·I.
    let k0 = cross(b, c);
    let k1 = cross(c, a);
    let k2 = cross(a, b);
    let det = dot(a, k0);
    let inv_det = 1.0 / det;
    // The same products in absolute value bound the rounding of each cofactor (one
    // multiplication each and a subtraction) and of the determinant.
    let abs_k0 = abs(b.yzx * c.zxy) + abs(b.zxy * c.yzx);
    let abs_k1 = abs(c.yzx * a.zxy) + abs(c.zxy * a.yzx);
    let abs_k2 = abs(a.yzx * b.zxy) + abs(a.zxy * b.yzx);
    let condition = dot(abs(a), abs_k0) * abs(inv_det);
    let relative = gamma(3.0) + gamma(6.0) * condition;
    let t = vec3f(w[0].w, w[1].w, w[2].w);
    var m: array<vec4f, 3>;
    var linear_error: array<vec3f, 3>;
    var translation_error = vec3f(0.0);
    for (var i = 0u; i < 3u; i++) {
        let row = vec3f(k0[i], k1[i], k2[i]) * inv_det;
        let row_error = relative * vec3f(abs_k0[i], abs_k1[i], abs_k2[i]) * abs(inv_det);
        m[i] = vec4f(row, -dot(row, t));
        linear_error[i] = row_error;
        translation_error[i] = dot(row_error, abs(t)) + gamma(3.0) * dot(abs(row), abs(t));
    }
    return AffineInverse(m, linear_error, translation_error);
}

// The error of `transform_point_error` for a derived matrix: its own rounding plus that
// of the matrix's entries.
fn inverse_transform_point_error(inv: AffineInverse, p: vec3f, error: vec3f) -> vec3f {
    let entries = vec3f(
        dot(inv.linear_error[0], abs(p) + error),
        dot(inv.linear_error[1], abs(p) + error),
        dot(inv.linear_error[2], abs(p) + error),
    );
    return transform_point_error(inv.m, p, error) + entries + inv.translation_error;
}
