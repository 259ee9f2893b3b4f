// The local geometry at a hit, whatever the primitive.

struct Surface {
    position: vec3f,
    // Bound on the absolute error of each component of `position`.
    position_error: vec3f,
    // Outward normals: the winding's for triangles, radial for spheres.
    geometric_normal: vec3f,
    shading_normal: vec3f,
    material: u32,
}

fn surface_at(hit: Hit, origin: vec3f, direction: vec3f) -> Surface {
    //#if spheres
    if hit.kind == HIT_SPHERE {
        return sphere_surface(hit, origin, direction);
    }
    //#endif
    //#if triangles
    return triangle_surface(hit);
    //#else
    return Surface(vec3f(0.0), vec3f(0.0), vec3f(0.0, 1.0, 0.0), vec3f(0.0, 1.0, 0.0), 0u);
    //#endif
}
