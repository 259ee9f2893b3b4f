// Principled's sheen as Cycles renders it (Blender 4.0 on): the microfiber sheen of Zeltner,
// Burley & Chiang ("Practical Multiple-Scattering Sheen Using Linearly Transformed
// Cosines", 2022). Its lobe is a cosine lobe under a linear transform whose two parameters
// (a on the diagonal, b the shear of x by z, in a frame whose x axis is the viewer's side)
// and whose albedo come from Cycles' fit table, read at (cos θ of the viewer, roughness).
// As in Cycles' Principled BSDF it is the outermost layer: its colour is
// sheen × tint × albedo, and everything under it (the coat included) keeps
// 1 − the largest channel of that (`closure_layering_weight`). Its normal is Cycles': the
// Normal input mixed towards the Coat Normal by the coat's weight, both before Bump Map
// Correction (`sheen_axis`), never the glossy lobes' normal that is bent to keep reflections
// above the surface. Cycles counts the sheen among its diffuse closures, so where its normal is
// not the interpolated one it is shadowed as the diffuse lobe is (`bump_shadowing`).

//#include "constants.wgsl"
//#include "directions.wgsl"
//#include "microfacet_tables.wgsl"
//#if terminator_offset
//#include "terminator_offset.wgsl"
//#endif

// Cycles' `table_sheen_ltc` (src/gpu/sheen_ltc.bin), after the microfacet tables:
// [3 planes: a, b, albedo][32 roughness][32 mu].
const TABLE_SHEEN_LTC: u32 = 13856u;
const SHEEN_PLANE: u32 = 1024u;

// The sheen's normal in the shading frame, set by `sheen_setup`.
var<private> sheen_normal: vec3f;

// Cycles' sheen normal (`svm/closure.h`): the base's unbent normal (`diffuse_axis`) mixed
// towards the coat's unbent normal by the coat's weight `coat` (the material's, before the
// shading context turns a coat that cannot shade off).
fn sheen_axis(ctx: ShadingContext, coat: f32) -> vec3f {
    var n = diffuse_axis(ctx);
    //#if coat_normal
    n = sheen_normal_towards_coat(n, transpose(ctx.basis) * coat_unbent_normal(), coat);
    //#endif
    return n;
}


// Reads the layer's transform and albedo for the viewer, at cos θ to the sheen's normal;
// returns the luminance of its albedo (for sampling). A fit without a lobe there (a tiny a
// at the smoothest roughness) reflects nothing. `coat` is the material's coat weight.
fn sheen_setup(ctx: ptr<function, ShadingContext>, coat: f32) -> f32 {
    let m = (*ctx).m;
    let n = sheen_axis(*ctx, coat);
    sheen_normal = n;
    let wo = (*ctx).wo;
    let mu = clamp(dot(n, wo), 1e-6, 1.0);
    let a = table_2d(TABLE_SHEEN_LTC, 32u, 32u, mu, m.sheen_roughness);
    let b = table_2d(TABLE_SHEEN_LTC + SHEEN_PLANE, 32u, 32u, mu, m.sheen_roughness);
    let albedo = sheen_table_albedo(m, mu, a);
    if albedo <= 0.0 {
        return 0.0;
    }
    (*ctx).sheen_transform = vec2f(a, b);
    // The frame's x axis: the viewer's direction projected on the surface (any one at normal incidence).
    let side = wo - dot(wo, n) * n;
    let len = length(side);
    (*ctx).sheen_side = select(tangent_frame(n)[0], side / len, len > 1e-7);
    let color = m.sheen * m.sheen_tint * albedo;
    (*ctx).sheen_color = color;
    (*ctx).under_sheen = saturate(1.0 - max(max(color.x, color.y), color.z));
    return luminance(color);
}

// The table's albedo of the layer seen from `mu`, given its transform's `a` there: 0 where
// the fit has no lobe.
fn sheen_table_albedo(m: Material, mu: f32, a: f32) -> f32 {
    let albedo = table_2d(TABLE_SHEEN_LTC + 2u * SHEEN_PLANE, 32u, 32u, mu, m.sheen_roughness);
    return select(albedo, 0.0, a < 1e-4 || albedo <= 0.0);
}

// Emission under the sheen, leaving at cosine `mu` to the sheen's normal: Cycles sets up a
// Principled's emission with the weight that its sheen leaves the lower layers
// (`svm/closure.h`), 1 − the largest channel of the sheen's colour there.
fn sheened_emission(m: Material, emission: vec3f, mu: f32) -> vec3f {
    if m.sheen <= 0.0 {
        return emission;
    }
    let c = clamp(mu, 1e-6, 1.0);
    let color = m.sheen * m.sheen_tint * sheen_table_albedo(m, c, table_2d(TABLE_SHEEN_LTC, 32u, 32u, c, m.sheen_roughness));
    return emission * saturate(1.0 - max(max(color.x, color.y), color.z));
}

fn has_sheen(ctx: ShadingContext) -> bool {
    return ctx.sheen_transform.x > 0.0;
}

// The lobe's density at wi (local to the shading frame), which is also its f·cos θi / colour.
fn sheen_lobe(ctx: ShadingContext, wi: vec3f) -> f32 {
    let n = sheen_normal;
    let z = dot(n, wi);
    if z <= 0.0 {
        return 0.0;
    }
    let t = ctx.sheen_side;
    let x = dot(t, wi);
    let y = dot(cross(n, t), wi);
    let a = ctx.sheen_transform.x;
    let b = ctx.sheen_transform.y;
    // |M⁻¹ wi|² with M⁻¹ = [[a, 0, b], [0, a, 0], [0, 0, 1]] in the sheen's frame (t, n × t, n);
    // the density is the cosine lobe's at M⁻¹ wi / |M⁻¹ wi| times the Jacobian a² / |M⁻¹ wi|³.
    let len2 = (a * x + b * z) * (a * x + b * z) + (a * y) * (a * y) + z * z;
    return z / PI * (a / len2) * (a / len2);
}

// f·|cos θi| of the sheen layer (folded like the other reflection lobes).
fn sheen_eval(ctx: ShadingContext, wi: vec3f) -> vec3f {
    if !has_sheen(ctx) || !reaches_reflection_lobes(ctx, wi) {
        return vec3f(0.0);
    }
    let mirrored = wi - 2.0 * dot(wi, ctx.n_geometric) * ctx.n_geometric;
    var f = sheen_lobe(ctx, wi);
    var f_mirrored = sheen_lobe(ctx, mirrored);
    //#if terminator_offset
    f *= terminator_shift(dot(sheen_normal, wi));
    f_mirrored *= terminator_shift(dot(sheen_normal, mirrored));
    //#endif
    var color = ctx.sheen_color * (f + f32(folds_below_surface()) * f_mirrored);
    //#if normal_maps
    color *= bump_shadowing(ctx, sheen_normal, wi);
    //#endif
    return color;
}

fn sheen_pdf(ctx: ShadingContext, wi: vec3f) -> f32 {
    if !has_sheen(ctx) || !reaches_reflection_lobes(ctx, wi) {
        return 0.0;
    }
    //#if normal_maps
    // Cycles' `bsdf_eval` gives no density where the shadowing cuts the direction.
    if bump_shadowing(ctx, sheen_normal, wi) == 0.0 {
        return 0.0;
    }
    //#endif
    let mirrored = wi - 2.0 * dot(wi, ctx.n_geometric) * ctx.n_geometric;
    return sheen_lobe(ctx, wi) + f32(folds_below_surface()) * sheen_lobe(ctx, mirrored);
}

// A direction from the lobe: a cosine-distributed one, transformed by M.
fn sheen_sample_direction(ctx: ShadingContext, u: vec2f) -> vec3f {
    let c = sample_cosine_hemisphere(u);
    let a = ctx.sheen_transform.x;
    let b = ctx.sheen_transform.y;
    let l = normalize(vec3f((c.x - c.z * b) / a, c.y / a, c.z));
    let n = sheen_normal;
    let t = ctx.sheen_side;
    let wi = l.x * t + l.y * cross(n, t) + l.z * n;
    if dot(n, wi) <= 0.0 || !sample_clears_surface(ctx, wi, false) {
        return vec3f(0.0);
    }
    return fold_above(wi, ctx.n_geometric);
}
