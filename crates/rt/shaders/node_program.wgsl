// Materials' shader node graphs, run at each shading point: the interpreter of the node
// programs that src/asset/node_graph.rs compiles (its header says how a program is laid
// out), the point a graph reads, and how its outputs set the material. A scene whose
// programs have few shapes runs code specialised to them instead of the interpreter
// (src/gpu/node_code.rs); either way editing a node's value rewrites the program table,
// never the pipeline.

//#include "node_ops.wgsl"

// The instruction at word `at`, as the table holds it.
fn node_step_at(at: u32) -> NodeStep {
    let word = node_programs[at];
    var step = NodeStep(word & 0xffu, (word >> 8u) & 0xffffu, word >> 24u, node_programs[at + 1u], 0u, array<u32, NODE_MAX_OPERANDS>());
    let operands = min(node_programs[at + 2u], NODE_MAX_OPERANDS);
    for (var i = 0u; i < operands; i++) {
        step.operands[i] = node_programs[at + 3u + i];
    }
    step.extra = at + 4u + node_programs[at + 2u];
    return step;
}

//#if !node_code
// Runs the program that starts at word `start` at point `p`, instruction by instruction.
// A scene whose programs have few shapes runs specialised code instead (`node_code`).
fn run_node_program(start: u32, p: NodePoint) -> NodeOutputs {
    var outputs = node_outputs_none();
    var at = start + 1u;
    for (var n = 0u; n < NODE_MAX_INSTRUCTIONS; n++) {
        if (node_programs[at] & 0xffu) == NODE_OP_END {
            break;
        }
        let step = node_step_at(at);
        if step.op == NODE_OP_OUTPUT {
            node_op_output(start, step, &outputs);
        } else {
            node_instruction(start, step, p);
        }
        at = step.extra + node_programs[step.extra - 1u];
    }
    return outputs;
}
//#endif

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

// The share of a Mix Shader's point that is its first material (1 for a material that
// mixes nothing): what a light sample of it weighs its emission by, where a ray that
// meets it tosses `node_mix_second`'s coin.
fn node_first_share(m: Material, out: NodeOutputs) -> f32 {
    if m.mix_material == NO_MATERIAL || (out.driven & 16u) == 0u {
        return 1.0;
    }
    return 1.0 - clamp(out.mix_factor, 0.0, 1.0);
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
fn node_point_on_triangle(instance: u32, inst: Instance, triangle: u32, b1: f32, b2: f32, position: vec3f, normal: vec3f, incoming: vec3f) -> NodePoint {
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
    p.instance = instance;
    //#if attributes
    p.triangle = triangle;
    p.barycentrics = vec2f(b1, b2);
    //#endif
    node_surface_steps(&p, inst, triangle, b1, b2, true_normal);
    return p;
}

// A hit's point: on a triangle, or on a sphere (whose object space is the world's).
fn node_point_at(hit: Hit, surface: Surface, normal: vec3f, incoming: vec3f) -> NodePoint {
    if hit.kind == HIT_TRIANGLE {
        return node_point_on_triangle(hit.instance, instance_at(hit.instance), hit.primitive, hit.b1, hit.b2, surface.position, normal, incoming);
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
    p.instance = NODE_NO_OBJECT;
    node_sphere_steps(&p, surface.geometric_normal);
    return p;
}
