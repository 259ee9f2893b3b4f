// The Bump node (Cycles' svm_node_set_bump, Mikkelsen's "Bump Mapping Unparameterized
// Surfaces on the GPU"): the height is read at the point and a step away along two
// directions of the surface, and the normal tilted by its surface gradient. Cycles steps
// along the ray differentials of P times the node's Filter Width; rt steps along two
// orthogonal directions of the triangle's plane by the ray cone's width times it. Both span
// the same plane, and the surface gradient over the determinant is the same for any pair of
// steps spanning it, so the normal is Cycles' wherever the height is smooth at the step's
// scale; where it is finer (detail below a tenth of a pixel) both filter it alike.

//#include "directions.wgsl"
//#include "node_inputs.wgsl"

// The steps along triangle `triangle` (of instance `inst`, at barycentrics (b1, b2), its
// world normal `true_normal`) that a Bump reads its height at: two orthogonal unit
// directions of its plane (world, Blender's axes) and what each moves the object-space
// point and the uv by, through the barycentrics that move the point so.
fn node_surface_steps(p: ptr<function, NodePoint>, inst: Instance, triangle: u32, b1: f32, b2: f32, true_normal: vec3f) {
    let frame = tangent_frame(true_normal);
    let tri = triangles[triangle];
    let e1 = tri.v1 - tri.v0;
    let e2 = tri.v2 - tri.v0;
    let a = dot(e1, e1);
    let b = dot(e1, e2);
    let c = dot(e2, e2);
    let det = a * c - b * b;
    for (var axis = 0u; axis < 2u; axis++) {
        let world = frame[axis];
        // The direction in object space lies in the triangle's plane there: the barycentrics
        // (d1, d2) with d1 e1 + d2 e2 equal to it.
        let object = transform_vector(inst.world_to_object, world);
        let r1 = dot(e1, object);
        let r2 = dot(e2, object);
        let d = select(vec2f(0.0), vec2f(c * r1 - b * r2, a * r2 - b * r1) / det, det > 0.0);
        let uv = triangle_uv(triangle, 0u, b1 + d.x, b2 + d.y) - (*p).uv;
        if axis == 0u {
            (*p).step_x = blender_axes(world);
            (*p).object_step_x = blender_axes(object);
            (*p).uv_step_x = uv;
            //#if attributes
            (*p).barycentric_step_x = d;
            //#endif
        } else {
            (*p).step_y = blender_axes(world);
            (*p).object_step_y = blender_axes(object);
            (*p).uv_step_y = uv;
            //#if attributes
            (*p).barycentric_step_y = d;
            //#endif
        }
    }
}

// The same on a sphere, whose object space is the world's and which has no uv.
fn node_sphere_steps(p: ptr<function, NodePoint>, normal: vec3f) {
    let frame = tangent_frame(normal);
    (*p).step_x = blender_axes(frame[0]);
    (*p).step_y = blender_axes(frame[1]);
    (*p).object_step_x = (*p).step_x;
    (*p).object_step_y = (*p).step_y;
}

// How far a Bump of filter width `width` steps at `p`: its share of the footprint, and no
// less than f32 can tell apart at the point's distance from the origin (a light sample or
// an orthographic camera's ray has no cone).
fn node_bump_step(p: NodePoint, width: f32) -> f32 {
    let far = max(max(abs(p.position.x), abs(p.position.y)), max(abs(p.position.z), 1e-2));
    return max(width * p.footprint, 1e-4 * far);
}

// `p` moved one step of a Bump of filter width `width` along axis `axis` (1: x, 2: y).
fn node_point_stepped(p: NodePoint, axis: u32, width: f32) -> NodePoint {
    let s = node_bump_step(p, width);
    var q = p;
    if axis == 1u {
        q.position += s * p.step_x;
        q.object += s * p.object_step_x;
        q.uv += s * p.uv_step_x;
        //#if attributes
        q.barycentrics += s * p.barycentric_step_x;
        //#endif
    } else {
        q.position += s * p.step_y;
        q.object += s * p.object_step_y;
        q.uv += s * p.uv_step_y;
        //#if attributes
        q.barycentrics += s * p.barycentric_step_y;
        //#endif
    }
    return q;
}

// The normal of a Bump at `p` of heights `h` (at the point, a step along x, along y), its
// step `width`'s, `strength`, `distance` (negative: inverted) and normal `n_in`.
fn node_bump(p: NodePoint, h: vec3f, width: f32, strength_in: f32, distance: f32, n_in: vec3f) -> vec3f {
    let s = node_bump_step(p, width);
    // Cycles' tangents from the normal, per unit step: Rx = dPdy × N, Ry = N × dPdx.
    let rx = cross(p.step_y, n_in);
    let ry = cross(n_in, p.step_x);
    let det = dot(p.step_x, rx);
    let surface_gradient = ((h.y - h.x) / s) * rx + ((h.z - h.x) / s) * ry;
    let sign_det = select(1.0, -1.0, det < 0.0);
    let tilted = abs(det) * n_in - distance * sign_det * surface_gradient;
    let length_squared = dot(tilted, tilted);
    if !(length_squared > 0.0) {
        return n_in;
    }
    let strength = max(strength_in, 0.0);
    return normalize(strength * tilted * inverseSqrt(length_squared) + (1.0 - strength) * n_in);
}
