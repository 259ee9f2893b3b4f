// Principled's anisotropy: the rough lobes' GGX stretched along the surface's tangent, as
// Cycles stretches it (α / aspect along the tangent, α × aspect across, aspect =
// √(1 − 0.9 × anisotropy)), the tangent turned about the normal by rotation × 2π.
// The tangent is the one Cycles gives a Principled BSDF whose Tangent input is unlinked:
// its Tangent node (Radial, about Z) on the generated coordinates, (−y, x, 0) about the
// centre of the object's texture space, in Blender's axes; rt's Y is Blender's Z, so it
// is (z, 0, −x) of the position in object space. That is Cycles' tangent wherever the
// object's texture space is centred on its origin with equal x and y extents (a mesh
// centred on its origin and as wide as deep; Cycles scales x and y by the extents).
// Spheres of the scene file take their centre for the origin.

//#include "common.wgsl"
//#include "hit.wgsl"
//#include "transform.wgsl"
//#include "directions.wgsl"

// The tangent at the surface being shaded (world space, not yet made orthogonal to the
// normal); set by the integrator at each hit.
var<private> surface_tangent: vec3f;

fn set_surface_tangent(hit: Hit, position: vec3f) {
    if hit.kind == HIT_SPHERE {
        let p = position - spheres[hit.primitive].center;
        surface_tangent = vec3f(p.z, 0.0, -p.x);
        return;
    }
    let to_object = instances[hit.instance].world_to_object;
    let p = transform_point(to_object, position);
    // Cycles carries the tangent to world space as a normal.
    surface_tangent = transform_normal_to_world(to_object, vec3f(p.z, 0.0, -p.x));
}

// The shading frame of an anisotropic lobe: x along the tangent (made orthogonal to n)
// turned about n by `rotation` turns, y = n × x, z = n. Where the tangent is parallel to
// n (the poles of the radial tangent) any frame serves.
fn anisotropic_frame(n: vec3f, rotation: f32) -> mat3x3f {
    let t = surface_tangent - n * dot(n, surface_tangent);
    let len2 = dot(t, t);
    if !(len2 > 1e-20) {
        return tangent_frame(n);
    }
    let x0 = t * inverseSqrt(len2);
    let phi = 2.0 * PI * rotation;
    let x = x0 * cos(phi) + cross(n, x0) * sin(phi);
    return mat3x3f(x, cross(n, x), n);
}

// (αx, αy) of a lobe of GGX α.
fn anisotropic_alpha(alpha: f32, anisotropy: f32) -> vec2f {
    let aspect = sqrt(1.0 - 0.9 * saturate(anisotropy));
    return vec2f(alpha / aspect, alpha * aspect);
}
