// The local geometry at a hit, whatever the primitive.

struct Surface {
    position: vec3f,
    geometric_normal: vec3f,
    shading_normal: vec3f,
    material: u32,
}

fn surface_at(hit: Hit, origin: vec3f, direction: vec3f) -> Surface {
    if hit.kind == HIT_SPHERE {
        return sphere_surface(hit, origin, direction);
    }
    return triangle_surface(hit);
}
