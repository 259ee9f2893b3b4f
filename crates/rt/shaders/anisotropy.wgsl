// Principled's anisotropy: the rough lobes' GGX stretched along the surface's tangent, as
// Cycles stretches it (α / aspect along the tangent, α × aspect across, aspect =
// √(1 − 0.9 × anisotropy)), the tangent turned about the normal by rotation × 2π.
// The tangent is the material's (`tangent`); unlinked, Cycles gives a Principled BSDF's
// Tangent input its Tangent node, Radial about Z, on the generated coordinates: (−y, x, 0)
// about the centre of the object's texture space, in Blender's axes; rt's Y is Blender's Z,
// so it is (z, 0, −x) of the position in object space. A radial tangent is Cycles' wherever
// the object's texture space is centred on its origin with equal extents across the axis
// (Cycles scales the generated coordinates by the extents). Spheres of the scene file take
// their centre for the origin.

//#include "common.wgsl"
//#include "hit.wgsl"
//#include "transform.wgsl"
//#include "motion.wgsl"
//#include "directions.wgsl"

// The tangent at the surface being shaded (world space, not yet made orthogonal to the
// normal); set by the integrator at each hit.
var<private> surface_tangent: vec3f;

// The radial tangent of `kind` at `p`, a point in object space (rt's axes).
fn radial_tangent(kind: u32, p: vec3f) -> vec3f {
    if kind == TANGENT_RADIAL_X {
        // Blender's (0, −z, y) about X.
        return vec3f(0.0, -p.z, p.y);
    }
    if kind == TANGENT_RADIAL_Y {
        // Blender's (−z, 0, x) about Y.
        return vec3f(-p.y, p.x, 0.0);
    }
    // Blender's (−y, x, 0) about Z.
    return vec3f(p.z, 0.0, -p.x);
}

fn set_surface_tangent(hit: Hit, position: vec3f, kind: u32) {
    if hit.kind == HIT_SPHERE {
        // A sphere of the scene file has no uv map: its uv tangent is the radial one about Z.
        let p = position - spheres[hit.primitive].center;
        surface_tangent = radial_tangent(select(kind, TANGENT_RADIAL_Z, kind == TANGENT_UV), p);
        return;
    }
    let to_object = instance_at(hit.instance).world_to_object;
    var t = vec3f(0.0);
    //#if uv_tangents
    if kind == TANGENT_UV {
        // Zero where the mesh has no tangents: then any frame serves (`anisotropic_frame`).
        let frame = tangent_frames[hit.primitive];
        t = ((1.0 - hit.b1 - hit.b2) * frame.t0 + hit.b1 * frame.t1 + hit.b2 * frame.t2).xyz;
    } else {
        t = radial_tangent(kind, transform_point(to_object, position));
    }
    //#else
    t = radial_tangent(kind, transform_point(to_object, position));
    //#endif
    // Cycles carries the tangent to world space as a normal.
    surface_tangent = transform_normal_to_world(to_object, t);
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
