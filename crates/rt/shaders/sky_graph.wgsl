// `[sky] kind = "graph"`: the World's node graph (src/bvh/world_graph.rs: the last
// material's program), run for a direction that leaves the scene as Cycles runs a World's
// shader (`shader_setup_from_background`): the point is the direction itself (Generated,
// Object, Position), its normals and incoming direction the reverse, on no object, at no
// distance a ray reaches.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "node_program.wgsl"

// The Background's radiance along `direction` (rt's axes) for a ray from `origin` that came
// from `ray_from` (NODE_RAY_*; NODE_RAY_NONE for a light sample) after `depth` bounces,
// `depths` of each kind (NodePoint::ray_depths).
fn graph_sky_radiance(direction: vec3f, origin: vec3f, ray_from: u32, singular: bool, depth: u32, depths: u32) -> vec3f {
    let d = blender_axes(direction);
    var p: NodePoint;
    p.position = d;
    p.object = d;
    p.normal = -d;
    p.object_normal = -d;
    p.true_normal = -d;
    p.incoming = -d;
    p.ray_from = ray_from;
    p.singular = singular;
    p.ray_length = 3.4e38;
    p.ray_depth = f32(depth);
    p.ray_depths = depths;
    p.instance = NODE_NO_OBJECT;
    p.background = true;
    p.ray_origin = origin;
    let out = run_node_program(materials[arrayLength(&materials) - 1u].node_program, p);
    return select(vec3f(0.0), out.emission, (out.driven & 8u) != 0u);
}
