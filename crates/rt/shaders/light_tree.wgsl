// The light tree (src/bvh/light_tree.rs): light sampling walks it from the root,
// choosing each child in proportion to its importance seen from the shaded point
// (pbrt-v4 `LightBounds::Importance`, after Conty Estevez & Kulla 2018), and a BSDF
// ray that hits a light finds the probability of that walk by following the
// light's bit trail. Both read the point and normal of the last light sample's
// surface, set by `light_tree_set_point`: the probability that BSDF sampling weighs
// itself against is that of the light sample taken at the same vertex.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "rng.wgsl"
//#include "transform.wgsl"
//#include "motion.wgsl"

// LightTreeNode: declared in src/layout.rs (GpuLightTreeNode).
//#include "LightTreeNode.struct.wgsl"

//#include "light_tree.bindings.wgsl"

var<private> light_tree_point: vec3f;
var<private> light_tree_normal: vec3f;

fn light_tree_set_point(p: vec3f, n: vec3f) {
    light_tree_point = p;
    light_tree_normal = n;
}

// cos(max(0, a − b)) and sin(max(0, a − b)) from the cosines and sines of a and b.
fn cos_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        return 1.0;
    }
    return cos_a * cos_b + sin_a * sin_b;
}

fn sin_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        return 0.0;
    }
    return sin_a * cos_b - cos_a * sin_b;
}

fn safe_sqrt(x: f32) -> f32 {
    return sqrt(max(x, 0.0));
}

// How much the lights below `node` may bring to the point p of normal n: power ×
// the best cosine of emission towards p / squared distance × the best cosine at p.
// Never 0 where one of them lights p.
fn light_tree_importance(node: LightTreeNode) -> f32 {
    if node.power <= 0.0 {
        return 0.0;
    }
    let p = light_tree_point;
    let center = 0.5 * (node.bounds_min + node.bounds_max);
    let radius = 0.5 * length(node.bounds_max - node.bounds_min);
    let to_p = p - center;
    let raw_d2 = dot(to_p, to_p);
    // pbrt clamps the distance by the box's size, so that a point inside is not favoured without bound.
    let d2 = max(raw_d2, max(radius, 1e-9));
    var wi = node.axis;
    if raw_d2 > 0.0 {
        wi = to_p / sqrt(raw_d2);
    }
    var cos_w = dot(node.axis, wi);
    if (node.flags & LIGHT_TREE_TWO_SIDED) != 0u {
        cos_w = abs(cos_w);
    }
    let sin_w = safe_sqrt(1.0 - cos_w * cos_w);
    // The half-angle under which p sees the bounds' sphere; all directions from inside.
    var cos_b = -1.0;
    if raw_d2 > radius * radius {
        cos_b = safe_sqrt(1.0 - radius * radius / raw_d2);
    }
    let sin_b = safe_sqrt(1.0 - cos_b * cos_b);
    let sin_o = safe_sqrt(1.0 - node.cos_theta_o * node.cos_theta_o);
    let cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, node.cos_theta_o);
    let sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, node.cos_theta_o);
    let cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
    if cos_p < node.cos_theta_e {
        return 0.0;
    }
    var importance = node.power * max(cos_p, 0.0) / d2;
    if any(light_tree_normal != vec3f(0.0)) {
        let cos_i = abs(dot(wi, light_tree_normal));
        let sin_i = safe_sqrt(1.0 - cos_i * cos_i);
        importance *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
    }
    return max(importance, 0.0);
}

// The probability of taking the first child of inner node `node` (index `index`); < 0
// when neither child can light the point.
fn light_tree_first_child_probability(index: u32, node: LightTreeNode) -> f32 {
    let a = light_tree_importance(light_tree_nodes[index + 1u]);
    let b = light_tree_importance(light_tree_nodes[node.link]);
    if !(a + b > 0.0) {
        return -1.0;
    }
    return a / (a + b);
}

// A light picked by the walk (the leaf's link) and its probability; probability 0: none.
struct TreePick {
    light: u32,
    probability: f32,
}

// The one walk from the root to a leaf that both directions take: at each inner node
// to the first child or the second, with the probability of that choice. Sampling
// (`follow_trail` false) chooses with `rng`; otherwise `trail` chooses, bit d at depth d
// (1: the second child), and `rng` is not read.
fn light_tree_walk(follow_trail: bool, trail: u32, rng: ptr<function, Rng>) -> TreePick {
    var bits = trail;
    var index = 0u;
    var probability = 1.0;
    loop {
        let node = light_tree_nodes[index];
        if (node.flags & LIGHT_TREE_LEAF) != 0u {
            if index == 0u && light_tree_importance(node) <= 0.0 {
                return TreePick(0u, 0.0);
            }
            return TreePick(node.link, probability);
        }
        let first = light_tree_first_child_probability(index, node);
        if first < 0.0 {
            return TreePick(0u, 0.0);
        }
        var take_first: bool;
        if follow_trail {
            take_first = (bits & 1u) == 0u;
            bits >>= 1u;
        } else {
            take_first = rng_next(rng) < first;
        }
        if take_first {
            probability *= first;
            index += 1u;
        } else {
            probability *= 1.0 - first;
            index = node.link;
        }
    }
    return TreePick(0u, 0.0);
}

fn light_tree_pick(rng: ptr<function, Rng>) -> TreePick {
    return light_tree_walk(false, 0u, rng);
}

// The probability that `light_tree_pick` picks the light of trail entry `trail_index`
// (emitter j: j; lamp i: emitter count + i).
fn light_tree_probability(trail_index: u32) -> f32 {
    let trail = light_tree_trails[trail_index];
    if trail == LIGHT_TREE_ABSENT {
        return 0.0;
    }
    // Never read: the walk follows the trail.
    var unused = Rng(0u, 0u, 0u, 0u);
    return light_tree_walk(true, trail, &unused).probability;
}

// The index in `emitters` of the emitter that is triangle `primitive` of instance
// `instance` (or sphere `primitive` | SPHERE_BIT), or LIGHT_TREE_ABSENT: the table is
// sorted by (sphere or not, instance, primitive).
fn emitter_index_of(instance: u32, primitive: u32) -> u32 {
    let sphere = (primitive & SPHERE_BIT) != 0u;
    let key = vec2u(select(instance, 0xffffffffu, sphere), primitive);
    var lo = 0u;
    var hi = frame.emitter_count;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        let e = emitters[mid];
        let at = vec2u(select(e.instance, 0xffffffffu, (e.primitive & SPHERE_BIT) != 0u), e.primitive);
        if at.x < key.x || (at.x == key.x && at.y < key.y) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    if lo < frame.emitter_count && emitters[lo].primitive == primitive && (sphere || emitters[lo].instance == instance) {
        return lo;
    }
    return LIGHT_TREE_ABSENT;
}

// The world-space area of triangle `primitive` of instance `instance`.
fn triangle_world_area(instance: u32, primitive: u32) -> f32 {
    let to_world = affine_inverse(instance_at(instance).world_to_object).m;
    let tri = triangles[primitive];
    let v0 = transform_point(to_world, tri.v0);
    let v1 = transform_point(to_world, tri.v1);
    let v2 = transform_point(to_world, tri.v2);
    return 0.5 * length(cross(v1 - v0, v2 - v0));
}
