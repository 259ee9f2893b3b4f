// The scene has no spheres: the top level holds none.
fn test_sphere(index: u32, origin: vec3f, direction: vec3f, hit: ptr<function, Hit>) {}

fn sphere_surface(hit: Hit, origin: vec3f, direction: vec3f) -> Surface {
    return Surface(vec3f(0.0), vec3f(0.0, 1.0, 0.0), vec3f(0.0, 1.0, 0.0), 0u);
}
