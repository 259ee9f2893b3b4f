// Which directions a surface's lobes see and keep. rt's own rule, Mitsuba's, folds a lobe's
// directions that the shading normal puts below the true surface back above it
// (`fold_above`). Surfaces in Cycles' model whose lobes' normals are not the true one
// (smooth-shaded and normal-mapped triangles) follow Cycles instead: each lobe is evaluated
// against its own normal and the geometry decides (a shadow ray below a closed mesh's face
// meets the mesh); `bump_shadowing_term` cuts light on the far side of the interpolated
// normal from a lobe's normal; and a sampled reflection below the true surface, or a
// refraction above it, is dropped.

//#include "common.wgsl"
//#include "directions.wgsl"

//#if cycles_lobe_rules
// Whether the surface follows Cycles' rules: it is smooth-shaded in Cycles' model or
// normal-mapped. (Only scenes with such surfaces compile the rules in: the dead branches
// alone slow a diffuse Cornell box, docs/measured-choices.md.)
fn lobes_follow_cycles() -> bool {
    var cycles = false;
    //#if normal_maps
    cycles = normal_is_mapped;
    //#endif
    //#if smooth_normals
    cycles = cycles || smooth_shaded;
    //#endif
    return cycles;
}

// The interpolated normal (Cycles' `sd->N`) in the shading frame: before a normal map and
// before Bump Map Correction; the true normal on a flat face.
fn interpolated_axis(ctx: ShadingContext) -> vec3f {
    //#if normal_maps
    if normal_is_mapped {
        return transpose(ctx.basis) * unmapped_normal;
    }
    //#endif
    //#if smooth_normals
    if smooth_shaded {
        return transpose(ctx.basis) * smooth_normal;
    }
    //#endif
    return ctx.n_geometric;
}
//#endif

// Whether the specular, metal and glass lobes shade: not on a surface that follows Cycles'
// rules whose shading normal faces away from the viewer (at silhouettes, or a map's normal
// without Bump Map Correction), where Cycles' microfacet closures give nothing (`bsdf_microfacet_eval` and
// `_sample` need cos θ > 0 to their normal) while the diffuse one still shades; rt's frame
// falls back to the true normal there, which would light them (silhouette pixels of sharp
// metals were up to 40% brighter than Cycles'). What they take from the diffuse stays.
fn microfacet_lobes_shade(n_shading: vec3f, wo_world: vec3f) -> bool {
    //#if cycles_lobe_rules
    if lobes_follow_cycles() {
        return dot(n_shading, wo_world) > 1e-4;
    }
    //#endif
    return true;
}

// The diffuse lobe's normal in the shading frame: the shading normal (z), but on a
// normal-mapped surface the map's normal before it was bent (see `set_unmapped_normal`),
// and on a smooth-shaded one the interpolated normal before Bump Map Correction bent it
// (see `set_smooth_shading`).
fn diffuse_axis(ctx: ShadingContext) -> vec3f {
    //#if normal_maps
    if normal_is_mapped {
        return transpose(ctx.basis) * diffuse_normal;
    }
    //#endif
    //#if smooth_normals
    if smooth_shaded {
        return transpose(ctx.basis) * smooth_normal;
    }
    //#endif
    return vec3f(0.0, 0.0, 1.0);
}

// Whether lobes are folded above the surface (`fold_above`): everywhere but on surfaces that
// follow Cycles' rules.
fn folds_below_surface() -> bool {
    var folds = true;
    //#if cycles_lobe_rules
    folds = !lobes_follow_cycles();
    //#endif
    return folds;
}

// Whether the reflection lobes are evaluated at wi: above the true surface, or anywhere
// on a smooth-shaded surface in Cycles' model, where the lobes' own hemispheres cut and
// the geometry decides (a shadow ray below a closed mesh's face meets the mesh).
fn reaches_reflection_lobes(ctx: ShadingContext, wi: vec3f) -> bool {
    //#if smooth_normals
    if smooth_shaded {
        return true;
    }
    //#endif
    return dot(wi, ctx.n_geometric) > 0.0;
}

// Whether a glossy lobe (specular, metal, coat) sees wi: Cycles' `bump_shadowing_term`
// zeroes a glossy closure whose normal a map or Bump Map Correction tilted, for light on the
// far side of the interpolated normal from the closure's.
fn glossy_sees(ctx: ShadingContext, wi: vec3f) -> bool {
    //#if cycles_lobe_rules
    if lobes_follow_cycles() {
        let axis = interpolated_axis(ctx);
        return dot(axis, wi) * axis.z >= 0.0;
    }
    //#endif
    return true;
}

// Whether the glass lobe is evaluated at wi, which it reads as a reflection above its normal
// (z) and as a refraction below it: where the true surface agrees; on a surface that follows
// Cycles' rules, where the interpolated normal agrees (`bump_shadowing_term`, which only
// cuts where a map or Bump Map Correction tilted the lobe's normal): Cycles judges an
// evaluated direction by the closure's normal and lets the geometry decide, so light
// reaches a silhouette's glass through directions that the faces would refuse.
fn glass_sees(ctx: ShadingContext, wi: vec3f) -> bool {
    //#if cycles_lobe_rules
    if lobes_follow_cycles() {
        let axis = interpolated_axis(ctx);
        return dot(axis, wi) * axis.z * wi.z >= 0.0;
    }
    //#endif
    return (wi.z > 0.0) == (dot(wi, ctx.n_geometric) > 0.0);
}

// Whether a lobe keeps a direction it sampled, a refraction if `transmitted`: everywhere but
// on a surface that follows Cycles' rules, where Cycles' closures drop a sampled
// reflection below the true surface and a refraction above it (`bsdf_microfacet_sample`,
// `bsdf_diffuse_sample`, `bsdf_sheen_sample`; their evaluation does not, see `glass_sees`
// and `reaches_reflection_lobes`). Followed instead, such a reflection enters a closed mesh
// and light leaks out by the same way: silhouettes of sharp metals without Bump Map
// Correction were up to 48% brighter than Cycles'.
fn sample_clears_surface(ctx: ShadingContext, wi: vec3f, transmitted: bool) -> bool {
    //#if cycles_lobe_rules
    if lobes_follow_cycles() {
        return (dot(wi, ctx.n_geometric) > 0.0) != transmitted;
    }
    //#endif
    return true;
}

// Mirrors a direction that the shading normal put below the true surface back
// above it. Applied to sampling and evaluation alike, it folds the lobe's
// leaking part onto the visible side: the BSDF stays consistent for MIS and a
// white surface keeps all its energy.
fn fold_above(w: vec3f, n_geometric: vec3f) -> vec3f {
    if !folds_below_surface() {
        return w;
    }
    let d = dot(w, n_geometric);
    return select(w, w - 2.0 * d * n_geometric, d < 0.0);
}

//#if normal_maps
// Normal-mapped surfaces are shaded as Cycles shades them: lobes are not folded above
// the surface (see `fold_above`); directions below it are cut instead, and diffuse
// light is shadowed by `bump_shadowing`. Set by the integrator at each surface: the
// interpolated normal before the normal map, on the viewer's side (world space),
// whether a map changed it, and the mapped normal the diffuse lobe uses: as in Cycles,
// the map's own, not the one bent to keep the glossy lobes' reflections above the
// surface (`valid_for_reflection`), which is the shading context's.
var<private> unmapped_normal: vec3f;
var<private> normal_is_mapped: bool;
var<private> diffuse_normal: vec3f;

fn set_unmapped_normal(n: vec3f, mapped: bool, diffuse: vec3f) {
    unmapped_normal = n;
    normal_is_mapped = mapped;
    diffuse_normal = diffuse;
}

// Cycles' shadowing of a diffuse closure (the diffuse lobe, the sheen) whose normal `axis`
// (shading frame) a normal map tilted (Conty Estevez, Lecocq & Stein, "A Microfacet-Based
// Shadowing Function to Solve the Bump Terminator Problem", Ray Tracing Gems ch. 12): the
// closure's normal is read as one facet of a GGX surface whose roughness grows with its tilt
// from the unmapped normal, and light is shadowed as by that surface's masking; light on the
// far side of the unmapped surface from the closure's normal is cut. Blender renders normal
// maps with it (`bump_shadowing_term`), the softening only with Bump Map Correction on.
fn bump_shadowing(ctx: ShadingContext, axis: vec3f, wi: vec3f) -> f32 {
    let n = ctx.basis * axis;
    let cos_d = dot(unmapped_normal, n);
    let cos_i = dot(unmapped_normal, ctx.basis * wi);
    if cos_i * cos_d * dot(axis, wi) < 0.0 {
        return 0.0;
    }
    if ctx.m.bump_map_correction == 0u {
        return 1.0;
    }
    let cd = abs(cos_d);
    let ci = abs(cos_i);
    if cd >= 1.0 || ci >= 1.0 {
        return 1.0;
    }
    if ci < 1e-6 {
        return 0.0;
    }
    let alpha2 = saturate(0.125 * (1.0 / (cd * cd) - 1.0));
    let tan2_i = (1.0 - ci * ci) / (ci * ci);
    return 2.0 / (1.0 + sqrt(1.0 + alpha2 * tan2_i));
}
//#endif

//#if smooth_normals
// Smooth-shaded triangles in Cycles' model (see smooth_shading.wgsl). Set by the
// integrator at each surface: whether it is one (normal-mapped or not), and its
// interpolated normal on the viewer's side (world space), which the diffuse lobe of an
// unmapped one keeps where Bump Map Correction bent the shading context's.
var<private> smooth_shaded: bool;
var<private> smooth_normal: vec3f;

fn set_smooth_normal(on: bool, n: vec3f) {
    smooth_shaded = on;
    smooth_normal = n;
}

fn is_smooth_shaded() -> bool {
    return smooth_shaded;
}

fn interpolated_normal() -> vec3f {
    return smooth_normal;
}
//#endif
