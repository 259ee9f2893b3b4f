// Traversal of a mesh's compressed 8-wide BVH, in object space (Ylitie, Karras & Laine,
// "Efficient Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs", HPG 2017).
//
// The state is a group: (base index, bit mask). In a node group, bits 24..32 are the hit
// inner children of one node, each at bit 24 + (slot ^ octant) so that the highest bit is
// the nearest child for the ray's octant (the builder sorts slots by octant), and bits
// 0..8 are that node's imask, which ranks a slot among the node's inner children. A
// triangle group's bits 0..24 are the triangles of the hit leaves. The stack holds node
// groups, at most one per level.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "ray.wgsl"
//#include "triangle.wgsl"
//#include "transform.wgsl"
//#include "motion.wgsl"
//#include "hit.wgsl"
//#if alpha_mask
//#include "texture.wgsl"
//#endif

// Depth of the stack of node groups: an 8-wide BVH of 16 levels holds 8^16 leaves.
// A push beyond it is counted, never silent.
const WIDE_STACK_SIZE: u32 = 16u;

// The ray's octant, inverted, in every byte: XOR with a slot gives its traversal rank.
fn wide_octant_inv4(direction: vec3f) -> u32 {
    return select(0x04040404u, 0u, direction.x < 0.0) | select(0x02020202u, 0u, direction.y < 0.0) | select(0x01010101u, 0u, direction.z < 0.0);
}

// The child planes of one axis, per slot: near (entered first) and far, for four slots.
struct WidePlanes {
    near: vec4f,
    far: vec4f,
}

fn wide_planes(min4: u32, max4: u32, negative: bool) -> WidePlanes {
    let lo = vec4f(unpack4xU8(min4));
    let hi = vec4f(unpack4xU8(max4));
    return WidePlanes(select(lo, hi, negative), select(hi, lo, negative));
}

// What the slab test needs of a node for one ray: t(q) = q · scale + offset is the
// distance to the plane origin + q · 2^(e − 127) along each axis.
struct WideSlabs {
    scale: vec3f,
    near_offset: vec3f,
    far_offset: vec3f,
    t_max: f32,
}

// Hit bits of four slots (one u32 of each per-slot byte array).
fn wide_four_hits(meta4: u32, x: WidePlanes, y: WidePlanes, z: WidePlanes, s: WideSlabs, octant_inv4: u32) -> u32 {
    let t_near = max(
        max(fma(x.near, vec4f(s.scale.x), vec4f(s.near_offset.x)), fma(y.near, vec4f(s.scale.y), vec4f(s.near_offset.y))),
        max(fma(z.near, vec4f(s.scale.z), vec4f(s.near_offset.z)), vec4f(0.0)),
    );
    let t_far = min(
        min(fma(x.far, vec4f(s.scale.x), vec4f(s.far_offset.x)), fma(y.far, vec4f(s.scale.y), vec4f(s.far_offset.y))),
        min(fma(z.far, vec4f(s.scale.z), vec4f(s.far_offset.z)), vec4f(s.t_max)),
    );
    // An inner child's meta is 0b001_11000 + slot; a leaf's never has bits 3 and 4 both set.
    let inner = ((meta4 & (meta4 << 1u)) & 0x10101010u) >> 4u;
    // Inner children: bit 24 + (slot ^ octant); leaves: their triangles' bits.
    let bit_index = unpack4xU8((meta4 ^ (octant_inv4 & (inner * 0xffu))) & 0x1f1f1f1fu);
    // Inner children: one bit; leaves: their triangle count in unary.
    let child_bits = unpack4xU8((meta4 >> 5u) & 0x07070707u);
    let bits = select(vec4u(0u), child_bits << bit_index, t_near <= t_far);
    return bits.x | bits.y | bits.z | bits.w;
}

// The node's hit mask: bits 24..32 its hit inner children, bits 0..24 its hit leaves'
// triangles. Conservative: a ray that passes through a child's dequantised box (which
// the builder made contain the child's geometry) never misses it. Against the exact
// distance (p + q·2^e − o)/d, fma(q, scale, offset) errs by less than γ₄(255|scale| +
// |offset|): the reciprocal's rounding, (p − o)'s, the product's and the fma's, with
// q ≤ 255. `slack` is γ₇ of that sum, which also covers its own rounding and that of
// offset ± slack; the entry is moved down by it and the exit up.
fn wide_node_hits(node: WideNode, ray: TraversalRay, octant_inv4: u32, t_max: f32) -> u32 {
    let w = node.exponents_imask;
    let exponents = vec3u(w & 0xffu, (w >> 8u) & 0xffu, (w >> 16u) & 0xffu);
    let scale = bitcast<vec3f>(exponents << vec3u(23u)) * ray.inv_direction;
    let offset = (node.origin - ray.origin) * ray.inv_direction;
    let slack = gamma(7.0) * (255.0 * abs(scale) + abs(offset));
    let s = WideSlabs(scale, offset - slack, offset + slack, t_max * BOX_TMAX_SCALE);
    let negative = ray.inv_direction < vec3f(0.0);
    let low = wide_four_hits(
        node.child_meta.x,
        wide_planes(node.child_min_x.x, node.child_max_x.x, negative.x),
        wide_planes(node.child_min_y.x, node.child_max_y.x, negative.y),
        wide_planes(node.child_min_z.x, node.child_max_z.x, negative.z),
        s,
        octant_inv4,
    );
    let high = wide_four_hits(
        node.child_meta.y,
        wide_planes(node.child_min_x.y, node.child_max_x.y, negative.x),
        wide_planes(node.child_min_y.y, node.child_max_y.y, negative.y),
        wide_planes(node.child_min_z.y, node.child_max_z.y, negative.z),
        s,
        octant_inv4,
    );
    return low | high;
}

// Updates `hit` with a closer hit on the instance's triangles (with `any_hit`, the first
// one found); sets `overflowed` when the stack was full (see `intersect_scene`). In
// object space: the direction is transformed but not renormalised, so t means the same
// in both spaces.
fn intersect_instance(
    instance_index: u32,
    world_origin: vec3f,
    world_direction: vec3f,
    any_hit: bool,
    hit: ptr<function, Hit>,
    overflowed: ptr<function, bool>,
) {
    let inst = instance_at(instance_index);
    let origin = transform_point(inst.world_to_object, world_origin);
    let direction = transform_vector(inst.world_to_object, world_direction);
    let ray = traversal_ray(origin, direction);
    let sheared = sheared_ray(origin, direction);
    let octant_inv4 = wide_octant_inv4(direction);
    var stack: array<vec2u, WIDE_STACK_SIZE>;
    var depth = 0u;
    // The root: a group of one hit child (bit 31) whose imask ranks nothing before it.
    var node_group = vec2u(0u, 0x80000000u);
    loop {
        let child_bit = firstLeadingBit(node_group.y);
        let slot = (child_bit - 24u) ^ (octant_inv4 & 0xffu);
        let child = node_group.x + countOneBits(node_group.y & ~(0xffffffffu << slot));
        node_group.y &= ~(1u << child_bit);
        if (node_group.y & 0xff000000u) != 0u {
            if depth < WIDE_STACK_SIZE {
                stack[depth] = node_group;
                depth += 1u;
            } else {
                *overflowed = true;
            }
        }
        let node = wide_nodes[inst.node_offset + child];
        let hits = wide_node_hits(node, ray, octant_inv4, (*hit).t);
        node_group = vec2u(node.child_base, (hits & 0xff000000u) | (node.exponents_imask >> 24u));
        var triangle_bits = hits & 0x00ffffffu;
        while triangle_bits != 0u {
            let bit = firstLeadingBit(triangle_bits);
            triangle_bits &= ~(1u << bit);
            let index = inst.triangle_offset + node.primitive_base + bit;
            let tri = triangles[index];
            let h = intersect_triangle(sheared, tri.v0, tri.v1, tri.v2, (*hit).t);
            if h.t < INFINITY {
                //#if alpha_mask
                // A cut-out texel lets every ray through, shadow rays too.
                if !opaque_at(inst, index, h.b1, h.b2) {
                    continue;
                }
                //#endif
                *hit = Hit(h.t, HIT_TRIANGLE, index, instance_index, h.b1, h.b2);
                if any_hit {
                    break;
                }
            }
        }
        if any_hit && (*hit).kind != HIT_NONE {
            break;
        }
        if (node_group.y & 0xff000000u) == 0u {
            if depth == 0u {
                break;
            }
            depth -= 1u;
            node_group = stack[depth];
        }
    }
}
