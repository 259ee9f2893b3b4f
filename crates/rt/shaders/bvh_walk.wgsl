// One step of the iterative walk of a BVH2, the same at both levels: the nearer
// child that the ray hits next, the farther one pushed on a fixed-size stack.

//#include "constants.wgsl"
//#include "common.wgsl"

// Depth of the traversal stacks; a push beyond it is counted, never silent.
const STACK_SIZE: u32 = 32u;

// Chooses the nearer hit child, pushing the farther one; pops when neither was hit.
// A push onto a full stack drops that subtree and sets `overflowed`.
fn next_node(
    node: BvhNode,
    t_a: f32,
    t_b: f32,
    stack: ptr<function, array<u32, STACK_SIZE>>,
    depth: ptr<function, u32>,
    overflowed: ptr<function, bool>,
) -> u32 {
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
            *overflowed = true;
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
