// A node program's machine: the program table, its operations, the registers, the point a
// graph is evaluated at, what a program sets, and one instruction (`NodeStep`) with its
// operands. Vectors are in Blender's axes, as a graph expects.

//#include "constants.wgsl"
//#include "common.wgsl"

//#include "node_step.bindings.wgsl"

// The operations, NODE_OP_*, are shared constants (src/shared_constants.rs).
const NODE_REGISTERS: u32 = 32u;
const NODE_MAX_OPERANDS: u32 = 10u;
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
    // singular (a mirror or clear glass), its length, the bounces before it, and those of
    // them that were diffuse, glossy and transmission bounces (NODE_DEPTH_BITS each, from
    // bit 0, NODE_GLOSSY_DEPTH and NODE_TRANSMISSION_DEPTH).
    ray_from: u32,
    singular: bool,
    ray_length: f32,
    ray_depth: f32,
    ray_depths: u32,
    // The instance the point is on (Object Info), or NODE_NO_OBJECT (a sphere).
    instance: u32,
    // Where a Bump reads its height (node_surface_steps): two orthogonal unit directions
    // along the surface (world), what a step of unit length along each moves the object
    // space point and the uv by, and the footprint (the ray cone's width there), which a
    // Bump's Filter Width scales into its step; 0 where there is none (a light sample).
    step_x: vec3f,
    step_y: vec3f,
    object_step_x: vec3f,
    object_step_y: vec3f,
    uv_step_x: vec2f,
    uv_step_y: vec2f,
    footprint: f32,
    //#if attributes
    // The triangle (in the scene's table) and the point's barycentrics of its second and
    // third corners there, and what a Bump's unit steps move them by (attributes).
    triangle: u32,
    barycentrics: vec2f,
    barycentric_step_x: vec2f,
    barycentric_step_y: vec2f,
    //#endif
    //#if sky_graph
    // The World's point: `position` is a direction, seen from the camera (Cycles' P + camera),
    // along a ray from `ray_origin` (rt's axes; an orthographic camera's Window reads it).
    background: bool,
    ray_origin: vec3f,
    //#endif
}

const NODE_NO_OBJECT: u32 = 0xffffffffu;

// What a ray found the point by: from the camera, after a lobe (LOBE_* + 1), or none of
// these (a light sample's point: every Light Path flag off, as Cycles evaluates emission).
const NODE_RAY_CAMERA: u32 = 0u;
const NODE_RAY_NONE: u32 = 255u;
// One bounce of each kind in NodePoint::ray_depths, a field of NODE_DEPTH_BITS each.
const NODE_DEPTH_BITS: u32 = 10u;
const NODE_DIFFUSE_DEPTH: u32 = 1u;
const NODE_GLOSSY_DEPTH: u32 = 1u << NODE_DEPTH_BITS;
const NODE_TRANSMISSION_DEPTH: u32 = 1u << (2u * NODE_DEPTH_BITS);

// What a program sets: `driven` bit i for target i (node_kinds::TARGETS).
const NODE_DRIVES_NORMAL: u32 = 32u;
struct NodeOutputs {
    base_color: vec3f,
    roughness: f32,
    emission: vec3f,
    metallic: f32,
    mix_factor: f32,
    // World, Blender's axes, on the viewer's side.
    normal: vec3f,
    driven: u32,
}

var<private> node_registers: array<vec4f, NODE_REGISTERS>;

fn blender_axes(v: vec3f) -> vec3f {
    return vec3f(v.x, -v.z, v.y);
}

// The inverse of blender_axes.
fn rt_axes(v: vec3f) -> vec3f {
    return vec3f(v.x, v.z, -v.y);
}

fn node_word_f(at: u32) -> f32 {
    return bitcast<f32>(node_programs[at]);
}

fn node_vec4(at: u32) -> vec4f {
    return vec4f(node_word_f(at), node_word_f(at + 1u), node_word_f(at + 2u), node_word_f(at + 3u));
}

// One instruction: decoded from the program table by the interpreter, or written with
// constants into a program shape's specialised code (src/gpu/node_code.rs), where the
// compiler then keeps only its operation's code and its registers in registers.
struct NodeStep {
    op: u32,
    mode: u32,
    flags: u32,
    out: u32,
    // Where its extra words (a ramp's table, a texture space) start in the table.
    extra: u32,
    operands: array<u32, NODE_MAX_OPERANDS>,
}

// Operand `i` of instruction `s`: a register or one of the program's constants.
fn node_in(start: u32, step: NodeStep, i: u32) -> vec4f {
    let operand = step.operands[i];
    if operand >= NODE_CONSTANT {
        return node_vec4(start + node_programs[start] + 4u * (operand - NODE_CONSTANT));
    }
    return node_registers[min(operand, NODE_REGISTERS - 1u)];
}

fn node_store(slot: u32, value: vec4f) {
    node_registers[min(slot, NODE_REGISTERS - 1u)] = value;
}

fn node_outputs_none() -> NodeOutputs {
    return NodeOutputs(vec3f(0.0), 0.0, vec3f(0.0), 0.0, 0.0, vec3f(0.0), 0u);
}
