// Closest-hit traversal of the two-level BVH: a top level over instances and
// spheres, one bottom level per mesh. Iterative, with fixed-size stacks.

const HIT_NONE: u32 = 0u;
const HIT_TRIANGLE: u32 = 1u;
const HIT_SPHERE: u32 = 2u;

struct Hit {
    t: f32,
    kind: u32,
    // Triangle index (into `triangles`) or sphere index.
    primitive: u32,
    instance: u32,
    b1: f32,
    b2: f32,
}

// Set when a stack was full and a subtree had to be dropped (and counted in `stats`).
var<private> stack_overflowed: bool;
// Shadow rays need any hit, not the closest: traversal stops at the first.
// Set by the caller before `traverse_scene`.
var<private> any_hit_only: bool;

fn trace_scene(origin: vec3f, direction: vec3f, t_max: f32) -> Hit {
    any_hit_only = false;
    return traverse_scene(origin, direction, t_max);
}

fn traverse_scene(origin: vec3f, direction: vec3f, t_max: f32) -> Hit {
    var hit = Hit(t_max, HIT_NONE, 0u, 0u, 0.0, 0.0);
    stack_overflowed = false;
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
                test_top_level_primitive(tlas_primitives[node.a_link + i], origin, direction, &hit);
            }
            t_a = INFINITY;
        }
        if t_b < INFINITY && node.b_count > 0u {
            for (var i = 0u; i < node.b_count; i++) {
                test_top_level_primitive(tlas_primitives[node.b_link + i], origin, direction, &hit);
            }
            t_b = INFINITY;
        }
        if any_hit_only && hit.kind != HIT_NONE {
            break;
        }
        // Links are relative to the top level's first node.
        let next = next_node(node, t_a, t_b, &stack, &depth);
        if next == EMPTY_LINK {
            break;
        }
        node_index = frame.tlas_root + next;
    }
    if stack_overflowed {
        atomicAdd(&stats[STAT_STACK_OVERFLOW], 1u);
    }
    return hit;
}

// Chooses the nearer hit child, pushing the farther one; pops when neither was hit.
fn next_node(node: BvhNode, t_a: f32, t_b: f32, stack: ptr<function, array<u32, STACK_SIZE>>, depth: ptr<function, u32>) -> u32 {
    let hit_a = t_a < INFINITY;
    let hit_b = t_b < INFINITY;
    if hit_a && hit_b {
        var near = node.a_link;
        var far = node.b_link;
        if t_b < t_a {
            near = node.b_link;
            far = node.a_link;
        }
        if *depth < STACK_SIZE {
            (*stack)[*depth] = far;
            *depth += 1u;
        } else {
            stack_overflowed = true;
        }
        return near;
    }
    if hit_a {
        return node.a_link;
    }
    if hit_b {
        return node.b_link;
    }
    if *depth == 0u {
        return EMPTY_LINK;
    }
    *depth -= 1u;
    return (*stack)[*depth];
}

fn test_top_level_primitive(entry: u32, origin: vec3f, direction: vec3f, hit: ptr<function, Hit>) {
    if (entry & SPHERE_BIT) != 0u {
        //#if spheres
        test_sphere(entry & ~SPHERE_BIT, origin, direction, hit);
        //#endif
    } else {
        //#if triangles
        trace_instance(entry, origin, direction, hit);
        //#endif
    }
}

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
