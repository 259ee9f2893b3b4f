// Bottom-level traversal of one mesh instance, in object space. The direction
// is transformed but not renormalised, so t means the same in both spaces.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "ray.wgsl"
//#include "triangle.wgsl"
//#include "transform.wgsl"
//#include "hit.wgsl"
//#include "bvh_walk.wgsl"
//#if alpha_mask
//#include "texture.wgsl"
//#endif

// Updates `hit` with a closer hit on the instance's triangles (with `any_hit`, the
// first one found); sets `overflowed` when a stack was full (see `intersect_scene`).
fn intersect_instance(
    instance_index: u32,
    world_origin: vec3f,
    world_direction: vec3f,
    any_hit: bool,
    hit: ptr<function, Hit>,
    overflowed: ptr<function, bool>,
) {
    let inst = instances[instance_index];
    let origin = transform_point(inst.world_to_object, world_origin);
    let direction = transform_vector(inst.world_to_object, world_direction);
    let ray = traversal_ray(origin, direction);
    let sheared = sheared_ray(origin, direction);
    var stack: array<u32, STACK_SIZE>;
    var depth = 0u;
    var node_index = inst.node_offset;
    loop {
        let node = nodes[node_index];
        var t_a = ray_box_entry(ray, node.a_min, node.a_max, (*hit).t);
        var t_b = ray_box_entry(ray, node.b_min, node.b_max, (*hit).t);
        if t_a < INFINITY && node.a_count > 0u {
            test_triangles(inst, instance_index, node.a_link, node.a_count, sheared, hit);
            t_a = INFINITY;
        }
        if t_b < INFINITY && node.b_count > 0u {
            test_triangles(inst, instance_index, node.b_link, node.b_count, sheared, hit);
            t_b = INFINITY;
        }
        if any_hit && (*hit).kind != HIT_NONE {
            break;
        }
        // Links are relative to the instance's mesh.
        let next = next_node(node, t_a, t_b, &stack, &depth, overflowed);
        if next == EMPTY_LINK {
            break;
        }
        node_index = inst.node_offset + next;
    }
}

fn test_triangles(inst: Instance, instance_index: u32, first: u32, count: u32, ray: ShearedRay, hit: ptr<function, Hit>) {
    for (var i = 0u; i < count; i++) {
        let index = inst.triangle_offset + first + i;
        let tri = triangles[index];
        let h = intersect_triangle(ray, tri.v0, tri.v1, tri.v2, (*hit).t);
        if h.t < INFINITY {
            //#if alpha_mask
            if !opaque_at(inst, index, h.b1, h.b2) {
                continue;
            }
            //#endif
            *hit = Hit(h.t, HIT_TRIANGLE, index, instance_index, h.b1, h.b2);
        }
    }
}

fn triangle_surface(hit: Hit) -> Surface {
    let inst = instances[hit.instance];
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
    let m = inst.object_to_world;
    let p = transform_point(m, p_object);
    let error = transform_point_error(m, p_object, error_object);
    return Surface(p, error, normalize(n_geometric), normalize(n_shading), material);
}
