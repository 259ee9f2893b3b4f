// Mesh instances: their traversal (in wide_bvh.wgsl) and their surfaces.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "ray.wgsl"
//#include "triangle.wgsl"
//#include "transform.wgsl"
//#include "motion.wgsl"
//#include "hit.wgsl"
//#include "wide_bvh.wgsl"

fn triangle_surface(hit: Hit) -> Surface {
    let inst = instance_at(hit.instance);
    let tri = triangles[hit.primitive];
    let b0 = 1.0 - hit.b1 - hit.b2;
    // Interpolating the vertices is more accurate than origin + t·direction.
    let p_object = b0 * tri.v0 + hit.b1 * tri.v1 + hit.b2 * tri.v2;
    let error_object = gamma(7.0) * (abs(b0 * tri.v0) + abs(hit.b1 * tri.v1) + abs(hit.b2 * tri.v2));
    let n_geometric = transform_normal_to_world(inst.world_to_object, cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
    let sh = shading[hit.primitive];
    let n_shading = transform_normal_to_world(inst.world_to_object, b0 * sh.n0 + hit.b1 * sh.n1 + hit.b2 * sh.n2);
    var material = inst.material_override;
    if material == NO_MATERIAL {
        material = inst.material_base + tri.material;
    }
    let to_world = affine_inverse(inst.world_to_object);
    let p = transform_point(to_world.m, p_object);
    let error = inverse_transform_point_error(to_world, p_object, error_object);
    return Surface(p, error, normalize(n_geometric), normalize(n_shading), material);
}
