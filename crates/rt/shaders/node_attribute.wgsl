// Attribute and Color Attribute (Cycles' svm_node_attr and svm_node_vertex_color): a
// mesh's named attribute at the point, its values at the triangle's corners interpolated
// by the barycentrics, as Cycles' triangle_attribute does.

//#include "common.wgsl"
//#include "node_step.wgsl"

//#if attributes
//#include "TriangleAttribute.struct.wgsl"
//#endif
//#include "node_attribute.bindings.wgsl"

// The attribute's values at `p` (a colour's linear RGBA, a vector's xyz, a value in x),
// or zero where there are none (a sphere, a mesh with fewer attributes).
fn node_attribute_at(p: NodePoint, slot: u32) -> vec4f {
    //#if attributes
    let stride = arrayLength(&attributes) / max(arrayLength(&triangles), 1u);
    if p.instance == NODE_NO_OBJECT || slot >= stride {
        return vec4f(0.0);
    }
    let t = attributes[p.triangle * stride + slot];
    let b = p.barycentrics;
    return (1.0 - b.x - b.y) * t.a0 + b.x * t.a1 + b.y * t.a2;
    //#else
    return vec4f(0.0);
    //#endif
}

// Output `read` (0 the colour or vector, 1 Fac, 2 Alpha) of data of kind `data` (0 a
// value, 1 two, 2 three, 3 a colour's four), as Cycles' svm_node_attr_store reads each.
fn node_attribute_output(read: u32, data: u32, a: vec4f) -> vec4f {
    var v = a.xyz;
    var fac = (a.x + a.y + a.z) / 3.0;
    switch data {
        case 0u: { v = vec3f(a.x); fac = a.x; }
        case 1u: { v = vec3f(a.xy, 0.0); fac = a.x; }
        default: {}
    }
    switch read {
        case 0u: { return vec4f(v, 0.0); }
        case 1u: { return vec4f(fac); }
        default: { return vec4f(select(1.0, a.w, data == 3u)); }
    }
}
