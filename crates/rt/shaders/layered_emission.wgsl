// A Principled material's emission under its sheen and coat. Cycles sets the emission up
// with the weight that those layers leave the ones below them (`svm/closure.h`: the sheen's
// layering weight, then the coat's and its tint's), each seen at the viewer's cosine to its
// own closure's normal: the coat's is the Coat Normal, or the interpolated normal where it is
// unlinked, bent by Bump Map Correction; the sheen's is the Normal input, unbent, leaned
// towards the unbent coat normal by the coat's weight (see sheen.wgsl).
//
// That is the emission a ray finds. A light sample finds another: Cycles evaluates an
// emitter's shader for next-event estimation without room for closures (`surface_shader_eval`
// with PATH_RAY_EMISSION), so there the sheen and the coat allocate nothing and take nothing
// from the emission; only the coat's tint, applied outside its closure, dims it
// (`light_sampled_emission`). The light such an emitter casts on other surfaces is therefore
// mostly undimmed in Cycles (next-event estimation carries most of it), and rt weighs its two
// estimates the same way; the emitter seen directly is dimmed by both layers in either.

//#include "common.wgsl"
//#include "bsdf.wgsl"
//#if normal_maps
//#include "normal_map.wgsl"
//#endif
//#if coat_normal
//#include "coat_normal.wgsl"
//#endif

// The layers' normals (world space, on the viewer's side of the surface: a normal that a map
// turned away from the viewer stays turned away, and its layer sees the viewer at cos θ = 0,
// as Cycles' tables read it).
struct LayerNormals {
    coat: vec3f,
    sheen: vec3f,
}

// The layers' normals at the point that `normal_mapped` and `coat_normal_mapped` were last
// called for, turned to the viewer's side by `side` (±1; they return outward normals):
// `shading` is what the first returned (the base's normal as the glossy lobes take it, the
// interpolated normal without normal maps), `coat` what the second returned (read only where
// coats have normals of their own). The sheen leans from the base's unbent normal (the
// diffuse lobe's) towards the coat's unbent one.
fn mapped_layer_normals(m: Material, shading: vec3f, coat: vec3f, side: f32) -> LayerNormals {
    var base = shading;
    //#if normal_maps
    base = diffuse_mapped_normal();
    //#endif
    var normals = LayerNormals(side * shading, side * base);
    //#if coat_normal
    normals.coat = side * coat;
    normals.sheen = sheen_normal_towards_coat(side * base, side * coat_normal_before_bending(), m.coat);
    //#endif
    return normals;
}

// The emission of material `m` that a light sample towards `wo` finds: `emission` under the
// coat's tint alone (see above), seen along the coat's normal `coat_normal` (on the side of `wo`).
fn light_sampled_emission(m: Material, emission: vec3f, coat_normal: vec3f, wo: vec3f) -> vec3f {
    //#if coat
    if m.coat > 0.0 {
        return emission * coat_tint_seen(m, clamp(dot(coat_normal, wo), 1e-6, 1.0));
    }
    //#endif
    return emission;
}

// The emission `emission` of material `m` that a ray towards `wo` (the viewer) finds, under
// its layers.
fn layered_emission(m: Material, emission: vec3f, normals: LayerNormals, wo: vec3f) -> vec3f {
    var e = emission;
    //#if coat
    e = coated_emission(m, e, dot(normals.coat, wo));
    //#endif
    //#if sheen
    e = sheened_emission(m, e, dot(normals.sheen, wo));
    //#endif
    return e;
}
