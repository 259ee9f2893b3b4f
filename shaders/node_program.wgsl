// Materials' shader node graphs, run at each shading point: the interpreter of the node
// programs that src/asset/node_graph.rs compiles (its header says how a program is laid
// out), the inputs it reads at a point, and how its outputs set the material. One
// interpreter for every material (as Cycles' SVM): editing a node's value rewrites the
// program table, never the pipeline. Vectors are in Blender's axes, as a graph expects.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "transform.wgsl"
//#include "motion.wgsl"
//#include "texture.wgsl"
//#include "node_noise.wgsl"
//#include "node_math.wgsl"
//#include "node_voronoi.wgsl"

@group(0) @binding(21) var<storage, read> node_programs: array<u32>;

const NODE_OP_END: u32 = 0u;
const NODE_OP_OUTPUT: u32 = 1u;
const NODE_OP_CONVERT: u32 = 2u;
const NODE_OP_COORDINATE: u32 = 3u;
const NODE_OP_MATH: u32 = 4u;
const NODE_OP_VECTOR_MATH: u32 = 5u;
const NODE_OP_MIX: u32 = 6u;
const NODE_OP_MAP_RANGE: u32 = 7u;
const NODE_OP_CLAMP: u32 = 8u;
const NODE_OP_INVERT: u32 = 9u;
const NODE_OP_RAMP: u32 = 10u;
const NODE_OP_SEPARATE: u32 = 11u;
const NODE_OP_COMBINE: u32 = 12u;
const NODE_OP_MAPPING: u32 = 13u;
const NODE_OP_NOISE: u32 = 14u;
const NODE_OP_CHECKER: u32 = 15u;
const NODE_OP_GRADIENT: u32 = 16u;
const NODE_OP_LAYER_WEIGHT: u32 = 17u;
const NODE_OP_FRESNEL: u32 = 18u;
const NODE_OP_HUE_SATURATION: u32 = 19u;
const NODE_OP_BRIGHT_CONTRAST: u32 = 20u;
const NODE_OP_GAMMA: u32 = 21u;
const NODE_OP_WHITE_NOISE: u32 = 22u;
const NODE_OP_VORONOI: u32 = 23u;
const NODE_OP_WAVE: u32 = 24u;
const NODE_OP_CURVES: u32 = 25u;
const NODE_OP_MAGIC: u32 = 26u;

const NODE_REGISTERS: u32 = 32u;
const NODE_CONSTANT: u32 = 0x80000000u;
// A bound on the instructions of one program, so that a corrupt one cannot hang the GPU.
const NODE_MAX_INSTRUCTIONS: u32 = 4096u;
const RAMP_TABLE_SIZE: u32 = 257u;
// Linear Rec. 709's luminance, as Cycles weighs a colour read as a value.
const NODE_LUMINANCE: vec3f = vec3f(0.2126729, 0.7151522, 0.0721750);

// Where a graph is evaluated, in Blender's axes.
struct NodePoint {
    position: vec3f,
    // Object space.
    object: vec3f,
    // The shading normal on the viewer's side, and the same in object space.
    normal: vec3f,
    object_normal: vec3f,
    true_normal: vec3f,
    // Towards the viewer.
    incoming: vec3f,
    uv: vec2f,
    backfacing: bool,
    // The ray that found the point (Light Path): NODE_RAY_* and whether its bounce was
    // singular (a mirror or clear glass), its length and the bounces before it.
    ray_from: u32,
    singular: bool,
    ray_length: f32,
    ray_depth: f32,
}

// What a ray found the point by: from the camera, after a lobe (LOBE_* + 1), or none of
// these (a light sample's point: every Light Path flag off, as Cycles evaluates emission).
const NODE_RAY_CAMERA: u32 = 0u;
const NODE_RAY_NONE: u32 = 255u;

// What a program sets: `driven` bit i for target i (node_kinds::TARGETS).
struct NodeOutputs {
    base_color: vec3f,
    roughness: f32,
    emission: vec3f,
    metallic: f32,
    mix_factor: f32,
    driven: u32,
}

var<private> node_registers: array<vec4f, NODE_REGISTERS>;

fn blender_axes(v: vec3f) -> vec3f {
    return vec3f(v.x, -v.z, v.y);
}

fn node_word_f(at: u32) -> f32 {
    return bitcast<f32>(node_programs[at]);
}

fn node_vec4(at: u32) -> vec4f {
    return vec4f(node_word_f(at), node_word_f(at + 1u), node_word_f(at + 2u), node_word_f(at + 3u));
}

// Operand `i` of the instruction at `at`: a register or one of the program's constants.
fn node_in(start: u32, at: u32, i: u32) -> vec4f {
    let operand = node_programs[at + 3u + i];
    if operand >= NODE_CONSTANT {
        return node_vec4(start + node_programs[start] + 4u * (operand - NODE_CONSTANT));
    }
    return node_registers[min(operand, NODE_REGISTERS - 1u)];
}

fn node_store(slot: u32, value: vec4f) {
    node_registers[min(slot, NODE_REGISTERS - 1u)] = value;
}

// Texture Coordinate (modes 0-3: Generated, Normal, UV, Object) and Geometry (4-8:
// Position, Normal, True Normal, Incoming, Backfacing). Generated's texture space is in
// the instruction's extra words at `extra`.
fn node_coordinate(mode: u32, p: NodePoint, extra: u32) -> vec4f {
    switch mode {
        case 0u: {
            let scale = vec3f(node_word_f(extra), node_word_f(extra + 1u), node_word_f(extra + 2u));
            let offset = vec3f(node_word_f(extra + 3u), node_word_f(extra + 4u), node_word_f(extra + 5u));
            return vec4f(p.object * scale + offset, 0.0);
        }
        case 1u: { return vec4f(p.object_normal, 0.0); }
        case 2u: { return vec4f(p.uv, 0.0, 0.0); }
        case 3u: { return vec4f(p.object, 0.0); }
        case 4u: { return vec4f(p.position, 0.0); }
        case 5u: { return vec4f(p.normal, 0.0); }
        case 6u: { return vec4f(p.true_normal, 0.0); }
        case 7u: { return vec4f(p.incoming, 0.0); }
        case 8u: { return vec4f(select(0.0, 1.0, p.backfacing)); }
        default: { return vec4f(node_light_path(mode - 9u, p)); }
    }
}

// Light Path's outputs in node_kinds' order: Is Camera, Shadow, Diffuse, Glossy, Singular,
// Reflection, Transmission, Volume Scatter Ray, Ray Length, Ray Depth. A lobe's bounce is
// diffuse (diffuse, sheen) or glossy (the others, singular ones too, as in Cycles),
// transmission for the glass lobe.
fn node_light_path(output: u32, p: NodePoint) -> f32 {
    let bounced = p.ray_from != NODE_RAY_CAMERA && p.ray_from != NODE_RAY_NONE;
    let lobe = p.ray_from - 1u;
    let diffuse = bounced && (lobe == 0u || lobe == 5u);
    let transmission = bounced && lobe == 3u;
    var on = false;
    switch output {
        case 0u: { on = p.ray_from == NODE_RAY_CAMERA; }
        case 2u: { on = diffuse; }
        case 3u: { on = bounced && !diffuse; }
        case 4u: { on = bounced && p.singular; }
        case 5u: { on = bounced && !transmission; }
        case 6u: { on = transmission; }
        case 8u: { return p.ray_length; }
        case 9u: { return p.ray_depth; }
        default: {}
    }
    return select(0.0, 1.0, on);
}

// Cycles' ramp lookup in a table of RAMP_TABLE_SIZE RGBA entries at `table`.
fn node_ramp(table: u32, fac: f32, interpolate: bool) -> vec4f {
    let f = clamp(fac, 0.0, 1.0) * f32(RAMP_TABLE_SIZE - 1u);
    let i = u32(clamp(i32(f), 0, i32(RAMP_TABLE_SIZE) - 1));
    let t = f - f32(i);
    let a = node_vec4(table + 4u * i);
    if interpolate && t > 0.0 {
        return (1.0 - t) * a + t * node_vec4(table + 4u * (i + 1u));
    }
    return a;
}

// Cycles' ramp lookup with extrapolation: beyond [0, 1] the table's end slope continues.
fn node_ramp_extended(table: u32, fac: f32, extrapolate: bool) -> vec4f {
    let last = RAMP_TABLE_SIZE - 1u;
    if extrapolate && fac < 0.0 {
        let t0 = node_vec4(table);
        return t0 + (t0 - node_vec4(table + 4u)) * -fac * f32(last);
    }
    if extrapolate && fac > 1.0 {
        let t0 = node_vec4(table + 4u * last);
        return t0 + (t0 - node_vec4(table + 4u * (last - 1u))) * (fac - 1.0) * f32(last);
    }
    return node_ramp(table, fac, true);
}

// RGB and Vector Curves (mode 0: each channel through its curve) and Float Curve (mode 1),
// mixed with the input by `fac`; `extra` holds the curves' range, then their table.
fn node_curves(mode: u32, extrapolate: bool, extra: u32, fac: f32, v: vec3f) -> vec3f {
    let lo = node_word_f(extra);
    let relative = (v - lo) / (node_word_f(extra + 1u) - lo);
    let table = extra + 2u;
    var curved = vec3f(
        node_ramp_extended(table, relative.x, extrapolate).x,
        node_ramp_extended(table, relative.y, extrapolate).y,
        node_ramp_extended(table, relative.z, extrapolate).z,
    );
    if mode == 1u {
        curved = vec3f(node_ramp_extended(table, relative.x, extrapolate).x);
    }
    return mix(v, curved, fac);
}

// Blender's XYZ Euler rotation (Cycles' euler_to_transform), as rows.
fn euler_rows(e: vec3f) -> mat3x3f {
    let c = cos(e);
    let s = sin(e);
    return mat3x3f(
        vec3f(c.y * c.z, s.y * s.x * c.z - c.x * s.z, s.y * c.x * c.z + s.x * s.z),
        vec3f(c.y * s.z, s.y * s.x * s.z + c.x * c.z, s.y * c.x * s.z - s.x * c.z),
        vec3f(-s.y, c.y * s.x, c.y * c.x),
    );
}

// Mapping: mode 0 point, 1 texture, 2 vector, 3 normal.
fn node_mapping(mode: u32, v: vec3f, location: vec3f, rotation: vec3f, scale: vec3f) -> vec3f {
    let rows = euler_rows(rotation);
    // `m * x` with rows as columns is the transpose's product: the inverse rotation.
    switch mode {
        case 0u: { return v * scale * rows + location; }
        case 1u: { return safe_divide3(rows * (v - location), scale); }
        case 2u: { return v * scale * rows; }
        default: { return safe_normalize(safe_divide3(v, scale) * rows); }
    }
}

fn node_checker(co: vec3f) -> f32 {
    let p = (co + 0.000001) * 0.999999;
    let i = abs(vec3i(floor(p)));
    return select(0.0, 1.0, ((i.x % 2) == (i.y % 2)) == ((i.z % 2) != 0));
}

// Gradient Texture: types in the order of node_kinds' GRADIENT_TYPES.
fn node_gradient(kind: u32, p: vec3f) -> f32 {
    switch kind {
        case 1u: { let r = max(p.x, 0.0); return r * r; }
        case 2u: {
            let r = clamp(p.x, 0.0, 1.0);
            let t = r * r;
            return 3.0 * t - 2.0 * t * r;
        }
        case 3u: { return (p.x + p.y) * 0.5; }
        case 4u: { return max(0.999999 - length(p), 0.0); }
        case 5u: { let r = max(0.999999 - length(p), 0.0); return r * r; }
        case 6u: { return atan2(p.y, p.x) / (2.0 * PI) + 0.5; }
        default: { return p.x; }
    }
}

// Cycles' fresnel_dielectric_cos.
fn node_fresnel(cos_i: f32, eta: f32) -> f32 {
    let c = abs(cos_i);
    var g = eta * eta - 1.0 + c * c;
    if g > 0.0 {
        g = sqrt(g);
        let a = (g - c) / (g + c);
        let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
        return 0.5 * a * a * (1.0 + b * b);
    }
    return 1.0;
}

// A Normal input the graph leaves unlinked reads 0: the point's own normal.
fn node_normal(n: vec3f, p: NodePoint) -> vec3f {
    return select(n, p.normal, all(n == vec3f(0.0)));
}

// Layer Weight's Fresnel (x) and Facing (y).
fn node_layer_weight(blend_in: f32, n: vec3f, p: NodePoint) -> vec2f {
    var eta = max(1.0 - blend_in, 1e-5);
    eta = select(1.0 / eta, eta, p.backfacing);
    let cos_i = dot(p.incoming, n);
    let fresnel = node_fresnel(cos_i, eta);
    var facing = abs(cos_i);
    if blend_in != 0.5 {
        var blend = clamp(blend_in, 0.0, 1.0 - 1e-5);
        blend = select(0.5 / (1.0 - blend), 2.0 * blend, blend < 0.5);
        facing = pow(facing, blend);
    }
    return vec2f(fresnel, 1.0 - facing);
}

fn node_noise(start: u32, at: u32, kind: u32, normalize: bool) -> vec4f {
    let scale = node_in(start, at, 2u).x;
    let s = NoiseSettings(
        clamp(node_in(start, at, 3u).x, 0.0, 15.0),
        max(node_in(start, at, 4u).x, 0.0),
        node_in(start, at, 5u).x,
        node_in(start, at, 6u).x,
        node_in(start, at, 7u).x,
        kind,
        normalize,
    );
    return noise_texture_3d(node_in(start, at, 0u).xyz * scale, node_in(start, at, 8u).x, s);
}

// Voronoi Texture: mode = feature | metric << 4 (node_kinds' VORONOI_FEATURES, _METRICS).
fn node_voronoi(start: u32, at: u32, mode: u32, normalize: bool) -> VoronoiResult {
    let p = VoronoiParams(
        node_in(start, at, 2u).x,
        node_in(start, at, 3u).x,
        node_in(start, at, 4u).x,
        node_in(start, at, 5u).x,
        node_in(start, at, 6u).x,
        node_in(start, at, 7u).x,
        node_in(start, at, 8u).x,
        0.0,
        normalize,
        mode & 15u,
        mode >> 4u,
    );
    return voronoi_texture(node_in(start, at, 0u).xyz, p);
}

// Runs one instruction (not END or OUTPUT) at `at`, whose extra words start at `extra`.
fn node_instruction(start: u32, at: u32, extra: u32, p: NodePoint) {
    let word = node_programs[at];
    let op = word & 0xffu;
    let mode = (word >> 8u) & 0xffffu;
    let flags = word >> 24u;
    let out = node_programs[at + 1u];
    let a = node_in(start, at, 0u);
    switch op {
        case NODE_OP_CONVERT: {
            node_store(out, vec4f(select(dot(a.xyz, vec3f(1.0 / 3.0)), dot(a.xyz, NODE_LUMINANCE), mode == 0u)));
        }
        case NODE_OP_COORDINATE: { node_store(out, node_coordinate(mode, p, extra)); }
        case NODE_OP_MATH: {
            var v = node_math(mode, a.x, node_in(start, at, 1u).x, node_in(start, at, 2u).x);
            if flags != 0u {
                v = clamp(v, 0.0, 1.0);
            }
            node_store(out, vec4f(v));
        }
        case NODE_OP_VECTOR_MATH: {
            let r = node_vector_math(mode, a.xyz, node_in(start, at, 1u).xyz, node_in(start, at, 2u).xyz, node_in(start, at, 3u).x);
            node_store(out, vec4f(r.xyz, 0.0));
            node_store(out + 1u, vec4f(r.w));
        }
        case NODE_OP_MIX: { node_store(out, node_mix(mode, flags, a, node_in(start, at, 1u), node_in(start, at, 2u))); }
        case NODE_OP_MAP_RANGE: {
            let v = node_map_range(mode, flags != 0u, a.x, node_in(start, at, 1u).x, node_in(start, at, 2u).x,
                node_in(start, at, 3u).x, node_in(start, at, 4u).x, node_in(start, at, 5u).x);
            node_store(out, vec4f(v));
        }
        case NODE_OP_CLAMP: {
            let lo = node_in(start, at, 1u).x;
            let hi = node_in(start, at, 2u).x;
            node_store(out, vec4f(select(min(max(a.x, lo), hi), clamp_range(a.x, lo, hi), mode == 1u)));
        }
        case NODE_OP_INVERT: {
            let c = node_in(start, at, 1u);
            node_store(out, vec4f(mix(c.xyz, 1.0 - c.xyz, a.x), c.w));
        }
        case NODE_OP_RAMP: {
            let c = node_ramp(extra, a.x, flags != 0u);
            node_store(out, vec4f(c.xyz, 1.0));
            node_store(out + 1u, vec4f(c.w));
        }
        case NODE_OP_SEPARATE: {
            // Mode 1: Separate Color in HSV.
            let c = select(a.xyz, rgb_to_hsv(a.xyz), mode == 1u);
            node_store(out, vec4f(c.x));
            node_store(out + 1u, vec4f(c.y));
            node_store(out + 2u, vec4f(c.z));
        }
        case NODE_OP_COMBINE: {
            let c = vec3f(a.x, node_in(start, at, 1u).x, node_in(start, at, 2u).x);
            node_store(out, vec4f(select(c, hsv_to_rgb(c), mode == 1u), 1.0));
        }
        case NODE_OP_HUE_SATURATION: {
            let c = node_in(start, at, 4u);
            let h = node_hue_saturation(a.x, node_in(start, at, 1u).x, node_in(start, at, 2u).x, node_in(start, at, 3u).x, c.xyz);
            node_store(out, vec4f(h, c.w));
        }
        case NODE_OP_BRIGHT_CONTRAST: {
            let contrast = node_in(start, at, 2u).x;
            let c = max((1.0 + contrast) * a.xyz + node_in(start, at, 1u).x - 0.5 * contrast, vec3f(0.0));
            node_store(out, vec4f(c, a.w));
        }
        case NODE_OP_GAMMA: { node_store(out, vec4f(node_gamma(a.xyz, node_in(start, at, 1u).x), a.w)); }
        case NODE_OP_VORONOI: {
            let v = node_voronoi(start, at, mode, flags != 0u);
            node_store(out, vec4f(v.distance));
            node_store(out + 1u, vec4f(v.color, 1.0));
            node_store(out + 2u, vec4f(v.position, 0.0));
            node_store(out + 3u, vec4f(0.0));
            node_store(out + 4u, vec4f(v.radius));
        }
        case NODE_OP_CURVES: {
            let v = node_in(start, at, 1u);
            let c = node_curves(mode, flags != 0u, extra, a.x, v.xyz);
            node_store(out, select(vec4f(c, v.w), vec4f(c.x), mode == 1u));
        }
        case NODE_OP_MAGIC: {
            let c = node_magic(a.xyz * node_in(start, at, 1u).x, i32(mode), node_in(start, at, 2u).x);
            node_store(out, vec4f(c, 1.0));
            node_store(out + 1u, vec4f((c.x + c.y + c.z) / 3.0));
        }
        case NODE_OP_WAVE: {
            let f = node_wave(mode, a.xyz * node_in(start, at, 1u).x, node_in(start, at, 2u).x, node_in(start, at, 3u).x,
                node_in(start, at, 4u).x, node_in(start, at, 5u).x, node_in(start, at, 6u).x);
            node_store(out, vec4f(f, f, f, 1.0));
            node_store(out + 1u, vec4f(f));
        }
        case NODE_OP_WHITE_NOISE: {
            node_store(out, vec4f(hash_float3_to_float(a.xyz)));
            node_store(out + 1u, vec4f(hash_float3_to_float3(a.xyz), 1.0));
        }
        case NODE_OP_MAPPING: {
            let v = node_mapping(mode, a.xyz, node_in(start, at, 1u).xyz, node_in(start, at, 2u).xyz, node_in(start, at, 3u).xyz);
            node_store(out, vec4f(v, 0.0));
        }
        case NODE_OP_NOISE: {
            let n = node_noise(start, at, mode, flags != 0u);
            node_store(out, vec4f(n.w));
            node_store(out + 1u, vec4f(n.xyz, 1.0));
        }
        case NODE_OP_CHECKER: {
            let f = node_checker(a.xyz * node_in(start, at, 3u).x);
            node_store(out, select(node_in(start, at, 2u), node_in(start, at, 1u), f == 1.0));
            node_store(out + 1u, vec4f(f));
        }
        case NODE_OP_GRADIENT: {
            let f = clamp(node_gradient(mode, a.xyz), 0.0, 1.0);
            node_store(out, vec4f(f, f, f, 1.0));
            node_store(out + 1u, vec4f(f));
        }
        case NODE_OP_LAYER_WEIGHT: {
            let w = node_layer_weight(a.x, node_normal(node_in(start, at, 1u).xyz, p), p);
            node_store(out, vec4f(w.x));
            node_store(out + 1u, vec4f(w.y));
        }
        case NODE_OP_FRESNEL: {
            let eta = max(a.x, 1e-5);
            let n = node_normal(node_in(start, at, 1u).xyz, p);
            node_store(out, vec4f(node_fresnel(dot(p.incoming, n), select(eta, 1.0 / eta, p.backfacing))));
        }
        default: {}
    }
}

// Runs the program that starts at word `start` at point `p`.
fn run_node_program(start: u32, p: NodePoint) -> NodeOutputs {
    var outputs = NodeOutputs(vec3f(0.0), 0.0, vec3f(0.0), 0.0, 0.0, 0u);
    var at = start + 1u;
    for (var n = 0u; n < NODE_MAX_INSTRUCTIONS; n++) {
        let op = node_programs[at] & 0xffu;
        if op == NODE_OP_END {
            break;
        }
        let operands = node_programs[at + 2u];
        let extra = at + 4u + operands;
        if op == NODE_OP_OUTPUT {
            let goal = (node_programs[at] >> 8u) & 0xffffu;
            let v = node_in(start, at, 0u);
            outputs.driven |= 1u << goal;
            switch goal {
                case 0u: { outputs.base_color = v.xyz; }
                case 1u: { outputs.roughness = v.x; }
                case 2u: { outputs.metallic = v.x; }
                case 3u: { outputs.emission = v.xyz; }
                default: { outputs.mix_factor = v.x; }
            }
        } else {
            node_instruction(start, at, extra, p);
        }
        at = extra + node_programs[extra - 1u];
    }
    return outputs;
}

// `material` with what its node program sets at `p`: the base colour, the roughness, the
// metal (the host's lobe weights are the non-metal part's, as with a metallic texture),
// the emission's colour (times the host's emission, the strength).
fn node_graph_material(material: Material, p: NodePoint) -> Material {
    return node_graph_applied(material, run_node_program(material.node_program, p));
}

// `material` with the outputs `out` of its program.
fn node_graph_applied(material: Material, out: NodeOutputs) -> Material {
    var m = material;
    if (out.driven & 1u) != 0u {
        m.base_color = max(out.base_color, vec3f(0.0));
    }
    if (out.driven & 2u) != 0u {
        let roughness = clamp(out.roughness, 0.0, 1.0);
        m.roughness = roughness;
        m.alpha = roughness * roughness;
    }
    if (out.driven & 4u) != 0u {
        let metal = clamp(out.metallic, 0.0, 1.0);
        let dielectric = 1.0 - metal;
        m.diffuse *= dielectric;
        m.specular *= dielectric;
        m.transmission *= dielectric;
        m.reflection = metal;
    }
    if (out.driven & 8u) != 0u {
        // Unclamped, as Cycles emits what a graph gives, below zero too (a Subtract blend).
        m.emission *= out.emission;
    }
    return m;
}

// Whether a Mix Shader's shading point is its second material (`mix_material`), with the
// probability its factor gives (Cycles weighs both closures; one picked by its weight is the
// same in expectation). The coin is a hash of the path and the bounce: no draw of the
// sampler's is spent.
fn node_mix_second(m: Material, out: NodeOutputs, path_key: u32, bounce: u32) -> bool {
    if m.mix_material == NO_MATERIAL || (out.driven & 16u) == 0u {
        return false;
    }
    let coin = f32(pcg_hash(path_key ^ pcg_hash(0x3c6ef372u + bounce)) >> 8u) * (1.0 / 16777216.0);
    return coin < clamp(out.mix_factor, 0.0, 1.0);
}

// The point on triangle `triangle` of instance `inst` at barycentrics (b1, b2), world
// position `position`, seen from direction `incoming` (towards the viewer, rt's axes),
// with its shading normal `normal` (world, rt's axes, before normal maps).
fn node_point_on_triangle(inst: Instance, triangle: u32, b1: f32, b2: f32, position: vec3f, normal: vec3f, incoming: vec3f) -> NodePoint {
    let tri = triangles[triangle];
    let sh = shading[triangle];
    let b0 = 1.0 - b1 - b2;
    let true_normal = normalize(transform_normal_to_world(inst.world_to_object, cross(tri.v1 - tri.v0, tri.v2 - tri.v0)));
    let backfacing = dot(true_normal, incoming) < 0.0;
    let side = select(1.0, -1.0, backfacing);
    var p: NodePoint;
    p.position = blender_axes(position);
    p.object = blender_axes(b0 * tri.v0 + b1 * tri.v1 + b2 * tri.v2);
    p.normal = blender_axes(side * normal);
    p.object_normal = blender_axes(side * normalize(b0 * sh.n0 + b1 * sh.n1 + b2 * sh.n2));
    p.true_normal = blender_axes(side * true_normal);
    p.incoming = blender_axes(incoming);
    p.uv = triangle_uv(triangle, 0u, b1, b2);
    p.backfacing = backfacing;
    p.ray_from = NODE_RAY_NONE;
    return p;
}

// A hit's point: on a triangle, or on a sphere (whose object space is the world's).
fn node_point_at(hit: Hit, surface: Surface, normal: vec3f, incoming: vec3f) -> NodePoint {
    if hit.kind == HIT_TRIANGLE {
        return node_point_on_triangle(instance_at(hit.instance), hit.primitive, hit.b1, hit.b2, surface.position, normal, incoming);
    }
    let backfacing = dot(surface.geometric_normal, incoming) < 0.0;
    let side = select(1.0, -1.0, backfacing);
    var p: NodePoint;
    p.position = blender_axes(surface.position);
    p.object = p.position;
    p.normal = blender_axes(side * normal);
    p.object_normal = p.normal;
    p.true_normal = blender_axes(side * surface.geometric_normal);
    p.incoming = blender_axes(incoming);
    p.backfacing = backfacing;
    p.ray_from = NODE_RAY_NONE;
    return p;
}
