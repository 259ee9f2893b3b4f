// The scene has no triangle meshes: the top level holds no instances.
fn trace_instance(instance_index: u32, world_origin: vec3f, world_direction: vec3f, hit: ptr<function, Hit>) {}

fn triangle_surface(hit: Hit) -> Surface {
    return Surface(vec3f(0.0), vec3f(0.0, 1.0, 0.0), vec3f(0.0, 1.0, 0.0), 0u);
}
