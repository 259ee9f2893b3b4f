// Evaluating the BSDF (see bsdf.wgsl) at a direction: f·|cos θi| of the lobes
// that have a density, and the density with which `bsdf_sample` produces the direction.

//#include "constants.wgsl"
//#include "bsdf.wgsl"
//#if glossy
//#include "microfacet.wgsl"
//#endif
//#if rough_glass_ggx
//#include "dielectric.wgsl"
//#endif
//#if coat
//#include "microfacet.wgsl"
//#endif
//#if rough_diffuse
//#include "oren_nayar.wgsl"
//#endif
//#if terminator_offset
//#include "terminator_offset.wgsl"
//#endif
//#if lobe_modules
//#include "lobe_modules.wgsl"
//#endif


// f·|cos θi| of one reflection lobe, before folding.
fn reflection_lobe_eval(ctx: ShadingContext, lobe: u32, wi: vec3f) -> vec3f {
    if lobe == LOBE_DIFFUSE {
        let cos_i = dot(diffuse_axis(ctx), wi);
        if cos_i <= 0.0 {
            return vec3f(0.0);
        }
        var f = ctx.m.base_color * (ctx.m.diffuse * ctx.diffuse_kept * cos_i / PI);
        //#if rough_diffuse
        let shape = oren_nayar(ctx.m.diffuse_roughness, ctx.m.base_color, cos_i, dot(diffuse_axis(ctx), ctx.wo), dot(wi, ctx.wo));
        f = ctx.m.base_color * (ctx.m.diffuse * ctx.diffuse_kept * cos_i) * shape;
        //#endif
        //#if normal_maps
        f *= bump_shadowing(ctx, diffuse_axis(ctx), wi);
        //#endif
        //#if terminator_offset
        f *= terminator_shift(cos_i);
        //#endif
        return f;
    }
    if wi.z <= 0.0 || !glossy_sees(ctx, wi) {
        return vec3f(0.0);
    }
    //#if glossy
    let m = normalize(ctx.wo + wi);
    let a = ctx.alpha;
    var microfacet = ggx_d(m, a) * ggx_g2(ctx.wo, wi, a) / (4.0 * ctx.wo.z);
    //#if terminator_offset
    microfacet *= terminator_shift(wi.z);
    //#endif
    if lobe == LOBE_SPECULAR {
        return ctx.m.specular * microfacet * specular_fresnel(ctx, dot(ctx.wo, m)) * ctx.energy_specular;
    }
    return ctx.m.reflection * microfacet * metal_fresnel(ctx, dot(ctx.wo, m)) * ctx.energy_reflection;
    //#else
    return vec3f(0.0);
    //#endif
}

fn reflection_lobe_pdf(ctx: ShadingContext, lobe: u32, wi: vec3f) -> f32 {
    if lobe == LOBE_DIFFUSE {
        return max(dot(diffuse_axis(ctx), wi), 0.0) / PI;
    }
    if wi.z <= 0.0 {
        return 0.0;
    }
    //#if glossy
    let m = normalize(ctx.wo + wi);
    return ggx_visible_pdf(ctx.wo, m, ctx.alpha) / (4.0 * dot(ctx.wo, m));
    //#else
    return 0.0;
    //#endif
}

// f·|cos θi| of all lobes that have a density, at wi (before the material's closure
// weight, which `bsdf_sample` and the light sample apply).
fn bsdf_eval(ctx: ShadingContext, wi: vec3f) -> vec3f {
    //#if lobe_modules
    if ctx.m.lobe_module != 0u {
        return module_lobe_eval(ctx, wi);
    }
    //#endif
    var f = vec3f(0.0);
    if reaches_reflection_lobes(ctx, wi) {
        let mirrored = wi - 2.0 * dot(wi, ctx.n_geometric) * ctx.n_geometric;
        let folded = f32(folds_below_surface());
        for (var lobe = LOBE_DIFFUSE; lobe <= LOBE_REFLECTION; lobe++) {
            if ctx.smooth_lobe[lobe] > 0.0 && ctx.lobe_probability[lobe] > 0.0 {
                f += reflection_lobe_eval(ctx, lobe, wi) + folded * reflection_lobe_eval(ctx, lobe, mirrored);
            }
        }
    }
    //#if rough_glass_ggx
    if ctx.smooth_lobe.w > 0.0 && ctx.lobe_probability.w > 0.0 {
        var glass = ctx.m.transmission * rough_dielectric_eval(ctx, wi) * ctx.energy_transmission;
        //#if terminator_offset
        // Its reflection only: refracted light arrives below the normal.
        glass *= terminator_shift(wi.z);
        //#endif
        f += glass;
    }
    //#endif
    //#if coat
    f = f * ctx.under_coat + coat_eval(ctx, wi);
    //#endif
    //#if sheen
    f = f * ctx.under_sheen + sheen_eval(ctx, wi);
    //#endif
    return f;
}

// Density with which `bsdf_sample` produces wi (delta lobes aside).
fn bsdf_pdf(ctx: ShadingContext, wi: vec3f) -> f32 {
    //#if lobe_modules
    if ctx.m.lobe_module != 0u {
        return module_lobe_pdf(ctx, wi);
    }
    //#endif
    var pdf = 0.0;
    if reaches_reflection_lobes(ctx, wi) {
        let mirrored = wi - 2.0 * dot(wi, ctx.n_geometric) * ctx.n_geometric;
        let folded = f32(folds_below_surface());
        for (var lobe = LOBE_DIFFUSE; lobe <= LOBE_REFLECTION; lobe++) {
            if ctx.smooth_lobe[lobe] > 0.0 {
                pdf += ctx.lobe_probability[lobe] * (reflection_lobe_pdf(ctx, lobe, wi) + folded * reflection_lobe_pdf(ctx, lobe, mirrored));
            }
        }
    }
    //#if rough_glass_ggx
    if ctx.smooth_lobe.w > 0.0 {
        pdf += ctx.lobe_probability.w * rough_dielectric_pdf(ctx, wi);
    }
    //#endif
    //#if coat
    pdf = mix(pdf, coat_pdf(ctx, wi), ctx.coat_probability);
    //#endif
    //#if sheen
    pdf = mix(pdf, sheen_pdf(ctx, wi), ctx.sheen_probability);
    //#endif
    return pdf;
}

//#if coat
fn rough_coat(ctx: ShadingContext) -> bool {
    return ctx.m.coat > 0.0 && ctx.m.coat_alpha >= ALPHA_DELTA;
}

// f·|cos θi| of the rough coat (folded, where lobes are, like the other reflection lobes).
fn coat_eval(ctx: ShadingContext, wi: vec3f) -> vec3f {
    if !rough_coat(ctx) || !reaches_reflection_lobes(ctx, wi) {
        return vec3f(0.0);
    }
    let mirrored = wi - 2.0 * dot(wi, ctx.n_geometric) * ctx.n_geometric;
    let folded = f32(coat_folds());
    return (coat_lobe_eval(ctx, wi) + folded * coat_lobe_eval(ctx, mirrored)) * ctx.m.coat * ctx.coat_energy;
}

// Whether the coat's lobe is folded above the surface: as the other lobes are, but never
// where the coat has a frame of its own (see coat_normal.wgsl; Cycles folds nothing).
fn coat_folds() -> bool {
    var folds = folds_below_surface();
    //#if coat_normal
    folds = folds && !coat_has_own_frame();
    //#endif
    return folds;
}

// `wi` in the shading frame; the lobe is evaluated in the coat's.
fn coat_lobe_eval(ctx: ShadingContext, wi_shading: vec3f) -> f32 {
    var wi = wi_shading;
    var wo = ctx.wo;
    //#if coat_normal
    if !coat_sees(wi_shading) {
        return 0.0;
    }
    wi = to_coat_frame(wi_shading);
    wo = coat_viewer();
    //#endif
    if wi.z <= 0.0 || !glossy_sees(ctx, wi_shading) {
        return 0.0;
    }
    let m = normalize(wo + wi);
    let a = vec2f(ctx.m.coat_alpha);
    var f = ggx_d(m, a) * ggx_g2(wo, wi, a) / (4.0 * wo.z) * fresnel_dielectric(dot(wo, m), ctx.m.coat_ior);
    //#if terminator_offset
    f *= terminator_shift(wi.z);
    //#endif
    return f;
}

fn coat_pdf(ctx: ShadingContext, wi: vec3f) -> f32 {
    if !rough_coat(ctx) || !reaches_reflection_lobes(ctx, wi) {
        return 0.0;
    }
    let mirrored = wi - 2.0 * dot(wi, ctx.n_geometric) * ctx.n_geometric;
    return coat_lobe_pdf(ctx, wi) + f32(coat_folds()) * coat_lobe_pdf(ctx, mirrored);
}

fn coat_lobe_pdf(ctx: ShadingContext, wi_shading: vec3f) -> f32 {
    var wi = wi_shading;
    var wo = ctx.wo;
    //#if coat_normal
    wi = to_coat_frame(wi_shading);
    wo = coat_viewer();
    //#endif
    if wi.z <= 0.0 {
        return 0.0;
    }
    let m = normalize(wo + wi);
    return ggx_visible_pdf(wo, m, vec2f(ctx.m.coat_alpha)) / (4.0 * dot(wo, m));
}
//#endif
