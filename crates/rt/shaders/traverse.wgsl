// Traversal of the two-level BVH: a top level over instances and spheres, one
// bottom level per mesh. Iterative, with fixed-size stacks.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "ray.wgsl"
//#include "hit.wgsl"
//#include "bvh_walk.wgsl"
//#if spheres
//#include "sphere_test.wgsl"
//#endif
//#if triangles
//#include "bottom_level.wgsl"
//#endif

// The closest hit in (0, t_max), or with `any_hit` (shadow rays, which only ask
// whether something is in the way) the first one found. `overflowed` is set when a
// stack was full and a subtree had to be dropped; the drop is counted in `stats`.
fn intersect_scene(origin: vec3f, direction: vec3f, t_max: f32, any_hit: bool, overflowed: ptr<function, bool>) -> Hit {
    var hit = Hit(t_max, HIT_NONE, 0u, 0u, 0.0, 0.0);
    *overflowed = false;
    let ray = traversal_ray(origin, direction);
    var stack: array<u32, STACK_SIZE>;
    var depth = 0u;
    var node_index = frame.tlas_root;
    loop {
        let node = nodes[node_index];
        var t_a = ray_box_entry(ray, node.a_min, node.a_max, hit.t);
        var t_b = ray_box_entry(ray, node.b_min, node.b_max, hit.t);
        if t_a < INFINITY && node.a_count > 0u {
            for (var i = 0u; i < node.a_count; i++) {
                test_top_level_primitive(tlas_primitives[node.a_link + i], origin, direction, any_hit, &hit, overflowed);
            }
            t_a = INFINITY;
        }
        if t_b < INFINITY && node.b_count > 0u {
            for (var i = 0u; i < node.b_count; i++) {
                test_top_level_primitive(tlas_primitives[node.b_link + i], origin, direction, any_hit, &hit, overflowed);
            }
            t_b = INFINITY;
        }
        if any_hit && hit.kind != HIT_NONE {
            break;
        }
        // Links are relative to the top level's first node.
        let next = next_node(node, t_a, t_b, &stack, &depth, overflowed);
        if next == EMPTY_LINK {
            break;
        }
        node_index = frame.tlas_root + next;
    }
    if *overflowed {
        atomicAdd(&stats[STAT_STACK_OVERFLOW], 1u);
    }
    return hit;
}

fn test_top_level_primitive(entry: u32, origin: vec3f, direction: vec3f, any_hit: bool, hit: ptr<function, Hit>, overflowed: ptr<function, bool>) {
    if (entry & SPHERE_BIT) != 0u {
        //#if spheres
        test_sphere(entry & ~SPHERE_BIT, origin, direction, hit);
        //#endif
    } else {
        //#if triangles
        intersect_instance(entry, origin, direction, any_hit, hit, overflowed);
        //#endif
    }
}
