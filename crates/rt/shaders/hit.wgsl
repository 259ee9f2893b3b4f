// What a ray finds: the primitive it hits (from traversal), and the local
// geometry there, whatever the primitive (from `surface_at`).

const HIT_NONE: u32 = 0u;
const HIT_TRIANGLE: u32 = 1u;
const HIT_SPHERE: u32 = 2u;

struct Hit {
    t: f32,
    kind: u32,
    // Triangle index (into `triangles`) or sphere index.
    primitive: u32,
    instance: u32,
    b1: f32,
    b2: f32,
}

struct Surface {
    position: vec3f,
    // Bound on the absolute error of each component of `position`.
    position_error: vec3f,
    // Outward normals: the winding's for triangles, radial for spheres.
    geometric_normal: vec3f,
    shading_normal: vec3f,
    material: u32,
}
