// Each node operation as a function of one instruction (`node_op_NAME`, called by the
// interpreter's `node_instruction` or directly by a shape's specialised code,
// src/gpu/node_code.rs), and Output.

//#include "node_inputs.wgsl"
//#include "node_bump.wgsl"
//#include "node_attribute.wgsl"

// Runs one instruction (not END or OUTPUT) at `at`, whose extra words start at `extra`.
fn node_instruction(start: u32, step: NodeStep, p: NodePoint) {
    switch step.op {
        case NODE_OP_CONVERT: { node_op_convert(start, step, p); }
        case NODE_OP_COORDINATE: { node_op_coordinate(start, step, p); }
        case NODE_OP_MATH: { node_op_math(start, step, p); }
        case NODE_OP_VECTOR_MATH: { node_op_vector_math(start, step, p); }
        case NODE_OP_MIX: { node_op_mix(start, step, p); }
        case NODE_OP_MAP_RANGE: { node_op_map_range(start, step, p); }
        case NODE_OP_CLAMP: { node_op_clamp(start, step, p); }
        case NODE_OP_INVERT: { node_op_invert(start, step, p); }
        case NODE_OP_RAMP: { node_op_ramp(start, step, p); }
        case NODE_OP_SEPARATE: { node_op_separate(start, step, p); }
        case NODE_OP_COMBINE: { node_op_combine(start, step, p); }
        case NODE_OP_HUE_SATURATION: { node_op_hue_saturation(start, step, p); }
        case NODE_OP_BRIGHT_CONTRAST: { node_op_bright_contrast(start, step, p); }
        case NODE_OP_GAMMA: { node_op_gamma(start, step, p); }
        case NODE_OP_VORONOI: { node_op_voronoi(start, step, p); }
        case NODE_OP_CURVES: { node_op_curves(start, step, p); }
        case NODE_OP_MAGIC: { node_op_magic(start, step, p); }
        case NODE_OP_WAVE: { node_op_wave(start, step, p); }
        case NODE_OP_WHITE_NOISE: { node_op_white_noise(start, step, p); }
        case NODE_OP_MAPPING: { node_op_mapping(start, step, p); }
        case NODE_OP_NOISE: { node_op_noise(start, step, p); }
        case NODE_OP_CHECKER: { node_op_checker(start, step, p); }
        case NODE_OP_GRADIENT: { node_op_gradient(start, step, p); }
        case NODE_OP_LAYER_WEIGHT: { node_op_layer_weight(start, step, p); }
        case NODE_OP_FRESNEL: { node_op_fresnel(start, step, p); }
        case NODE_OP_BRICK: { node_op_brick(start, step, p); }
        case NODE_OP_SPECTRUM: { node_op_spectrum(start, step, p); }
        case NODE_OP_BUMP: { node_op_bump(start, step, p); }
        case NODE_OP_VORONOI_DIMENSIONS: { node_op_voronoi_dimensions(start, step, p); }
        case NODE_OP_VECTOR_TRANSFORM: { node_op_vector_transform(start, step, p); }
        case NODE_OP_ATTRIBUTE: { node_op_attribute(start, step, p); }
        default: {}
    }
}

// Each operation: what instruction `step` of the program at `start` stores at point `p`.
fn node_op_convert(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    node_store(step.out, vec4f(select(dot(a.xyz, vec3f(1.0 / 3.0)), dot(a.xyz, NODE_LUMINANCE), step.mode == 0u)));
}

// Flags 1 and 2: at a Bump's step along x or y, its filter width the operand.
fn node_op_coordinate(start: u32, step: NodeStep, p: NodePoint) {
    var at = p;
    if step.flags != 0u {
        at = node_point_stepped(p, step.flags, node_in(start, step, 0u).x);
    }
    node_store(step.out, node_coordinate(step.mode, at, step.extra));
}

// Attribute and Color Attribute (node_attribute.wgsl). Mode: what it reads | data << 2; its extra word, the attribute's number; flags 1 and 2:
// at a Bump's step along x or y, its filter width the operand.
fn node_op_attribute(start: u32, step: NodeStep, p: NodePoint) {
    var at = p;
    if step.flags != 0u {
        at = node_point_stepped(p, step.flags, node_in(start, step, 0u).x);
    }
    let a = node_attribute_at(at, node_programs[step.extra]);
    node_store(step.out, node_attribute_output(step.mode & 3u, step.mode >> 2u, a));
}

// Operands: Strength, Distance, Filter Width, the heights at the point and its steps along
// x and y, Normal; flags: inverted.
fn node_op_bump(start: u32, step: NodeStep, p: NodePoint) {
    let h = vec3f(node_in(start, step, 3u).x, node_in(start, step, 4u).x, node_in(start, step, 5u).x);
    let distance = select(1.0, -1.0, step.flags != 0u) * node_in(start, step, 1u).x;
    let n = node_normal(node_in(start, step, 6u).xyz, p);
    let bumped = node_bump(p, h, node_in(start, step, 2u).x, node_in(start, step, 0u).x, distance, n);
    node_store(step.out, vec4f(bumped, 0.0));
}

fn node_op_math(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    var v = node_math(step.mode, a.x, node_in(start, step, 1u).x, node_in(start, step, 2u).x);
    if step.flags != 0u {
        v = clamp(v, 0.0, 1.0);
    }
    node_store(step.out, vec4f(v));
}

fn node_op_vector_math(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let r = node_vector_math(step.mode, a.xyz, node_in(start, step, 1u).xyz, node_in(start, step, 2u).xyz, node_in(start, step, 3u).x);
    node_store(step.out, vec4f(r.xyz, 0.0));
    node_store(step.out + 1u, vec4f(r.w));
}

fn node_op_mix(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    node_store(step.out, node_mix(step.mode, step.flags, a, node_in(start, step, 1u), node_in(start, step, 2u)));
}

// Flags: clamped (1), of vectors (2: each component mapped, Cycles' vector Map Range).
fn node_op_map_range(start: u32, step: NodeStep, p: NodePoint) {
    let value = node_in(start, step, 0u);
    let from_min = node_in(start, step, 1u);
    let from_max = node_in(start, step, 2u);
    let to_min = node_in(start, step, 3u);
    let to_max = node_in(start, step, 4u);
    let steps = node_in(start, step, 5u);
    let clamped = (step.flags & 1u) != 0u;
    if (step.flags & 2u) == 0u {
        node_store(step.out, vec4f(node_map_range(step.mode, clamped, value.x, from_min.x, from_max.x, to_min.x, to_max.x, steps.x)));
        return;
    }
    var v = vec3f(0.0);
    for (var c = 0; c < 3; c++) {
        // A component whose range is empty is To Min's (the float node's is 0).
        v[c] = select(node_map_range(step.mode, clamped, value[c], from_min[c], from_max[c], to_min[c], to_max[c], steps[c]), to_min[c], from_min[c] == from_max[c]);
    }
    node_store(step.out, vec4f(v, 0.0));
}

fn node_op_clamp(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let lo = node_in(start, step, 1u).x;
    let hi = node_in(start, step, 2u).x;
    node_store(step.out, vec4f(select(min(max(a.x, lo), hi), clamp_range(a.x, lo, hi), step.mode == 1u)));
}

fn node_op_invert(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let c = node_in(start, step, 1u);
    node_store(step.out, vec4f(mix(c.xyz, 1.0 - c.xyz, a.x), c.w));
}

fn node_op_ramp(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let c = node_ramp(step.extra, a.x, step.flags != 0u);
    node_store(step.out, vec4f(c.xyz, 1.0));
    node_store(step.out + 1u, vec4f(c.w));
}

fn node_op_separate(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    // Mode 1: Separate Color in HSV, 2 in HSL.
    var c = a.xyz;
    switch step.mode {
        case 1u: { c = rgb_to_hsv(a.xyz); }
        case 2u: { c = rgb_to_hsl(a.xyz); }
        default: {}
    }
    node_store(step.out, vec4f(c.x));
    node_store(step.out + 1u, vec4f(c.y));
    node_store(step.out + 2u, vec4f(c.z));
}

fn node_op_combine(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    var c = vec3f(a.x, node_in(start, step, 1u).x, node_in(start, step, 2u).x);
    switch step.mode {
        case 1u: { c = hsv_to_rgb(c); }
        case 2u: { c = hsl_to_rgb(c); }
        default: {}
    }
    node_store(step.out, vec4f(c, 1.0));
}

fn node_op_hue_saturation(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let c = node_in(start, step, 4u);
    let h = node_hue_saturation(a.x, node_in(start, step, 1u).x, node_in(start, step, 2u).x, node_in(start, step, 3u).x, c.xyz);
    node_store(step.out, vec4f(h, c.w));
}

fn node_op_bright_contrast(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let contrast = node_in(start, step, 2u).x;
    let c = max((1.0 + contrast) * a.xyz + node_in(start, step, 1u).x - 0.5 * contrast, vec3f(0.0));
    node_store(step.out, vec4f(c, a.w));
}

fn node_op_gamma(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    node_store(step.out, vec4f(node_gamma(a.xyz, node_in(start, step, 1u).x), a.w));
}

fn node_op_voronoi(start: u32, step: NodeStep, p: NodePoint) {
    node_voronoi_store(step, voronoi_texture(node_in(start, step, 0u).xyz, node_voronoi_params(start, step)));
}

fn node_op_voronoi_dimensions(start: u32, step: NodeStep, p: NodePoint) {
    let params = node_voronoi_params(start, step);
    node_voronoi_store(step, voronoi_texture_of_dimensions(node_in(start, step, 0u).xyz, node_in(start, step, 1u).x, params));
}

fn node_voronoi_store(step: NodeStep, v: VoronoiResult) {
    node_store(step.out, vec4f(v.distance));
    node_store(step.out + 1u, vec4f(v.color, 1.0));
    node_store(step.out + 2u, vec4f(v.position, 0.0));
    node_store(step.out + 3u, vec4f(v.w));
    node_store(step.out + 4u, vec4f(v.radius));
}

fn node_op_curves(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let v = node_in(start, step, 1u);
    let c = node_curves(step.mode, step.flags != 0u, step.extra, a.x, v.xyz);
    node_store(step.out, select(vec4f(c, v.w), vec4f(c.x), step.mode == 1u));
}

fn node_op_magic(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let c = node_magic(a.xyz * node_in(start, step, 1u).x, i32(step.mode), node_in(start, step, 2u).x);
    node_store(step.out, vec4f(c, 1.0));
    node_store(step.out + 1u, vec4f((c.x + c.y + c.z) / 3.0));
}

fn node_op_wave(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let f = node_wave(step.mode, a.xyz * node_in(start, step, 1u).x, node_in(start, step, 2u).x, node_in(start, step, 3u).x,
        node_in(start, step, 4u).x, node_in(start, step, 5u).x, node_in(start, step, 6u).x);
    node_store(step.out, vec4f(f, f, f, 1.0));
    node_store(step.out + 1u, vec4f(f));
}

fn node_op_white_noise(start: u32, step: NodeStep, p: NodePoint) {
    let c = white_noise(step.mode, node_in(start, step, 0u).xyz, node_in(start, step, 1u).x);
    node_store(step.out, vec4f(c.w));
    node_store(step.out + 1u, vec4f(c.xyz, 1.0));
}

fn node_op_mapping(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let v = node_mapping(step.mode, a.xyz, node_in(start, step, 1u).xyz, node_in(start, step, 2u).xyz, node_in(start, step, 3u).xyz);
    node_store(step.out, vec4f(v, 0.0));
}

fn node_op_vector_transform(start: u32, step: NodeStep, p: NodePoint) {
    node_store(step.out, vec4f(node_vector_transform(step.mode, node_in(start, step, 0u).xyz, p), 0.0));
}

fn node_op_noise(start: u32, step: NodeStep, p: NodePoint) {
    let n = node_noise(start, step, step.mode, step.flags != 0u);
    node_store(step.out, vec4f(n.w));
    node_store(step.out + 1u, vec4f(n.xyz, 1.0));
}

fn node_op_checker(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let f = node_checker(a.xyz * node_in(start, step, 3u).x);
    node_store(step.out, select(node_in(start, step, 2u), node_in(start, step, 1u), f == 1.0));
    node_store(step.out + 1u, vec4f(f));
}

fn node_op_gradient(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let f = clamp(node_gradient(step.mode, a.xyz), 0.0, 1.0);
    node_store(step.out, vec4f(f, f, f, 1.0));
    node_store(step.out + 1u, vec4f(f));
}

fn node_op_layer_weight(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let w = node_layer_weight(a.x, node_normal(node_in(start, step, 1u).xyz, p), p);
    node_store(step.out, vec4f(w.x));
    node_store(step.out + 1u, vec4f(w.y));
}

fn node_op_fresnel(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u);
    let eta = max(a.x, 1e-5);
    let n = node_normal(node_in(start, step, 1u).xyz, p);
    node_store(step.out, vec4f(node_fresnel(dot(p.incoming, n), select(eta, 1.0 / eta, p.backfacing))));
}

// Sets the material input that Output instruction `step` names.
fn node_op_output(start: u32, step: NodeStep, outputs: ptr<function, NodeOutputs>) {
    let v = node_in(start, step, 0u);
    (*outputs).driven |= 1u << step.mode;
    switch step.mode {
        case 0u: { (*outputs).base_color = v.xyz; }
        case 1u: { (*outputs).roughness = v.x; }
        case 2u: { (*outputs).metallic = v.x; }
        case 3u: { (*outputs).emission = v.xyz; }
        case 4u: { (*outputs).mix_factor = v.x; }
        default: { (*outputs).normal = v.xyz; }
    }
}

// Brick Texture (Cycles' svm_node_tex_brick): a brick's colour is Color1 tinted towards
// Color2 by its hash, the mortar's share blends in Mortar.
fn node_op_brick(start: u32, step: NodeStep, p: NodePoint) {
    let shape = BrickShape(node_in(start, step, 5u).x, node_in(start, step, 6u).x, node_in(start, step, 7u).x,
        node_in(start, step, 8u).x, node_in(start, step, 9u).x, node_word_f(step.extra), i32(step.mode & 0xffu),
        node_word_f(step.extra + 1u), i32(step.mode >> 8u));
    let b = node_brick(node_in(start, step, 0u).xyz * node_in(start, step, 4u).x, shape);
    var color = node_in(start, step, 1u).xyz;
    if b.y != 1.0 {
        color = (1.0 - b.x) * color + b.x * node_in(start, step, 2u).xyz;
    }
    node_store(step.out, vec4f(color * (1.0 - b.y) + node_in(start, step, 3u).xyz * b.y, 1.0));
    node_store(step.out + 1u, vec4f(b.y));
}

// Blackbody (mode 0: the temperature in kelvin) or Wavelength (mode 1: nanometres).
fn node_op_spectrum(start: u32, step: NodeStep, p: NodePoint) {
    let a = node_in(start, step, 0u).x;
    let c = select(blackbody_rec709(a), wavelength_rec709(a), step.mode == 1u);
    node_store(step.out, vec4f(max(c, vec3f(0.0)), 1.0));
}
