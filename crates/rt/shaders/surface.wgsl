// The local geometry at a hit, whatever the primitive.

//#include "hit.wgsl"
//#if spheres
//#include "sphere_test.wgsl"
//#endif
//#if triangles
//#include "bottom_level.wgsl"
//#endif

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
