// The coat's own normal (Principled's Coat Normal): Cycles gives the coat the Coat Normal
// input, or where that is unlinked the interpolated normal `sd->N`, never the Normal
// input's map (`svm/closure.h`), and bends it by Bump Map Correction like the other glossy
// normals; glTF's clearcoat says the same of `clearcoatNormalTexture`. The coat's lobe,
// its albedo (what it leaves the layers under it) and its tint's path length are all
// taken in that normal's frame. Directions stay in the shading frame (bsdf.wgsl's, z = the
// base's normal) everywhere else; the coat turns them into its own.

//#include "directions.wgsl"

// Set by the integrator at each surface (`set_coat_normal`), on the viewer's side, world
// space: the coat's normal, the interpolated normal, and the coat's normal before Bump Map
// Correction bent it (which the sheen's normal leans towards, see sheen.wgsl).
var<private> coat_normal_world: vec3f;
var<private> coat_interpolated_world: vec3f;
var<private> coat_unbent_world: vec3f;
// Set by `coat_frame_setup` with the shading frame: shading frame → coat frame, the viewer
// in the coat's frame (z clamped above 0, as the shading context's), the interpolated
// normal in the shading frame, and whether the coat's frame is not the shading frame.
var<private> coat_rotation: mat3x3f;
var<private> coat_wo: vec3f;
var<private> coat_interpolated: vec3f;
var<private> coat_own_frame: bool;

fn set_coat_normal(n: vec3f, interpolated: vec3f, unbent: vec3f) {
    coat_normal_world = n;
    coat_interpolated_world = interpolated;
    coat_unbent_world = unbent;
}

fn coat_unbent_normal() -> vec3f {
    return coat_unbent_world;
}

// The sheen's normal over a coat of weight `coat` (Cycles', `svm/closure.h`): the base's
// normal `base` leaned towards the coat's unbent normal `coat_normal` by that weight.
fn sheen_normal_towards_coat(base: vec3f, coat_normal: vec3f, coat: f32) -> vec3f {
    if coat <= 0.0 {
        return base;
    }
    return normalize(mix(base, coat_normal, saturate(coat)));
}

// The coat's frame beside the shading frame `basis`; `wo_world` towards the viewer,
// `n_geometric` the true normal on the viewer's side (world space). Returns the viewer's
// cosine to the coat's normal.
fn coat_frame_setup(basis: mat3x3f, wo_world: vec3f, n_geometric: vec3f) -> f32 {
    // A normal that faces away from the viewer cannot shade: the true one instead, as the
    // shading context does.
    var n = coat_normal_world;
    if dot(n, wo_world) <= 1e-4 {
        n = n_geometric;
    }
    coat_own_frame = dot(n, basis[2]) < 1.0 - 1e-6;
    let to_coat = transpose(tangent_frame(n));
    coat_rotation = mat3x3f(vec3f(1.0, 0.0, 0.0), vec3f(0.0, 1.0, 0.0), vec3f(0.0, 0.0, 1.0));
    if coat_own_frame {
        coat_rotation = to_coat * basis;
    }
    let wo = to_coat * wo_world;
    coat_wo = vec3f(wo.xy, max(wo.z, 1e-6));
    coat_interpolated = transpose(basis) * coat_interpolated_world;
    return coat_wo.z;
}

// The viewer in the coat's frame.
fn coat_viewer() -> vec3f {
    return coat_wo;
}

// Whether the coat's frame is not the shading frame.
fn coat_has_own_frame() -> bool {
    return coat_own_frame;
}

// A direction of the shading frame in the coat's, and back.
fn to_coat_frame(w: vec3f) -> vec3f {
    return coat_rotation * w;
}

fn from_coat_frame(w: vec3f) -> vec3f {
    return transpose(coat_rotation) * w;
}

// Cycles' `bump_shadowing_term` of a glossy closure whose normal is not `sd->N`: light on
// the far side of the interpolated surface from the coat's normal does not reach it
// (`wi` in the shading frame, above the coat's normal). Where the coat's normal is the
// interpolated one this cannot cut anything.
fn coat_sees(wi: vec3f) -> bool {
    let nc = from_coat_frame(vec3f(0.0, 0.0, 1.0));
    return dot(coat_interpolated, wi) * dot(coat_interpolated, nc) >= 0.0;
}
