// Sampling the BSDF (see bsdf.wgsl): a lobe picked in proportion to its
// probability, then a direction from it. Delta lobes give their one direction.
// For the lobes that have a density: with next-event estimation (`nee`), one
// direction from the picked lobe, weighed against the whole mixture; with the
// seed renderer's scheme (`seed`), resampled importance sampling (Talbot et al.
// 2005): candidates from the BSDF mixture and from the sun's disk, one of them
// chosen in proportion to BSDF × (1 + sun radiance if it points at the sun).

//#include "common.wgsl"
//#include "rng.wgsl"
//#include "directions.wgsl"
//#include "bsdf.wgsl"
//#include "bsdf_eval.wgsl"
//#if glossy
//#include "microfacet.wgsl"
//#endif
//#if glass
//#include "dielectric.wgsl"
//#endif
//#if coat
//#include "microfacet.wgsl"
//#endif
//#if !nee
//#if sun
//#include "sun.wgsl"
//#endif
//#endif

// A direction from one lobe that has a density (before the mixture weighs it).
// Returns a zero vector when the lobe produced nothing.
fn sample_smooth_lobe_direction(ctx: ShadingContext, lobe: u32, rng: ptr<function, Rng>) -> vec3f {
    let u = rng_next2(rng);
    //#if rough_glass_ggx
    if lobe == LOBE_TRANSMISSION {
        return rough_dielectric_sample(ctx, vec3f(u, rng_next(rng)));
    }
    //#endif
    //#if sheen
    if lobe == LOBE_SHEEN {
        return sheen_sample_direction(ctx, u);
    }
    //#endif
    //#if coat
    if lobe == LOBE_COAT {
        // In the coat's frame (see coat_normal.wgsl), returned in the shading frame.
        var wo = ctx.wo;
        //#if coat_normal
        wo = coat_viewer();
        //#endif
        var wi = reflect_local(wo, ggx_sample_visible_normal(wo, vec2f(ctx.m.coat_alpha), u));
        if wi.z <= 0.0 {
            return vec3f(0.0);
        }
        //#if coat_normal
        wi = from_coat_frame(wi);
        //#endif
        return select(vec3f(0.0), select(wi, fold_above(wi, ctx.n_geometric), coat_folds()), sample_clears_surface(ctx, wi, false));
    }
    //#endif
    if lobe == LOBE_DIFFUSE {
        let wi = tangent_frame(diffuse_axis(ctx)) * sample_cosine_hemisphere(u);
        return select(vec3f(0.0), fold_above(wi, ctx.n_geometric), dot(diffuse_axis(ctx), wi) > 0.0 && sample_clears_surface(ctx, wi, false));
    }
    //#if glossy
    let wi = reflect_local(ctx.wo, ggx_sample_visible_normal(ctx.wo, ctx.alpha, u));
    if wi.z <= 0.0 || !sample_clears_surface(ctx, wi, false) {
        return vec3f(0.0);
    }
    return fold_above(wi, ctx.n_geometric);
    //#else
    return vec3f(0.0);
    //#endif
}

// Picks a lobe with `u` in [0, 1); returns its index and rescales u to [0, 1).
fn pick_lobe(ctx: ShadingContext, u: ptr<function, f32>) -> u32 {
    var acc = 0.0;
    for (var lobe = 0u; lobe < 3u; lobe++) {
        let p = ctx.lobe_probability[lobe];
        if *u < acc + p {
            *u = (*u - acc) / p;
            return lobe;
        }
        acc += p;
    }
    *u = clamp((*u - acc) / max(ctx.lobe_probability.w, 1e-20), 0.0, 1.0);
    return LOBE_TRANSMISSION;
}

fn bsdf_sample(ctx: ShadingContext, rng: ptr<function, Rng>) -> BsdfSample {
    //#if lobe_modules
    if ctx.m.lobe_module != 0u {
        let u = vec2f(rng_next(rng), rng_next(rng));
        var s = module_lobe_sample(ctx, u);
        s.direction = ctx.basis * s.direction;
        return s;
    }
    //#endif
    //#if sheen
    if ctx.sheen_probability > 0.0 && rng_next(rng) < ctx.sheen_probability {
        var s = sample_smooth_part(ctx, LOBE_SHEEN, rng);
        s.lobe = LOBE_DIFFUSE;
        s.direction = ctx.basis * s.direction;
        return s;
    }
    //#endif
    //#if coat
    if ctx.coat_probability > 0.0 && rng_next(rng) < ctx.coat_probability {
        var s = sample_coat(ctx, rng);
        s.direction = ctx.basis * s.direction;
        return s;
    }
    //#endif
    if all(ctx.lobe_probability == vec4f(0.0)) {
        return invalid_sample();
    }
    var u = rng_next(rng);
    let lobe = pick_lobe(ctx, &u);
    var s: BsdfSample;
    if ctx.smooth_lobe[lobe] > 0.0 {
        s = sample_smooth_part(ctx, lobe, rng);
    } else {
        s = sample_delta_lobe(ctx, lobe, u, rng);
        //#if coat
        s.weight *= ctx.under_coat / (1.0 - ctx.coat_probability);
        //#endif
        s.weight *= under_sheen_delta(ctx);
    }
    s.direction = ctx.basis * s.direction;
    return s;
}

//#if coat
// The coat: a perfect mirror below ALPHA_DELTA, else part of the smooth mixture.
fn sample_coat(ctx: ShadingContext, rng: ptr<function, Rng>) -> BsdfSample {
    if ctx.m.coat_alpha >= ALPHA_DELTA {
        var s = sample_smooth_part(ctx, LOBE_COAT, rng);
        s.lobe = LOBE_SPECULAR;
        return s;
    }
    var wo = ctx.wo;
    //#if coat_normal
    wo = coat_viewer();
    //#endif
    var mirror = vec3f(-wo.xy, wo.z);
    //#if coat_normal
    mirror = from_coat_frame(mirror);
    //#endif
    mirror = select(mirror, fold_above(mirror, ctx.n_geometric), coat_folds());
    if !sample_clears_surface(ctx, mirror, false) {
        return invalid_sample();
    }
    let f = ctx.m.coat * fresnel_dielectric(wo.z, ctx.m.coat_ior);
    return BsdfSample(mirror, vec3f(f / ctx.coat_probability) * under_sheen_delta(ctx), 0.0, true, false, LOBE_SPECULAR);
}
//#endif

// What a delta lobe under the sheen keeps, over the probability of sampling under it.
fn under_sheen_delta(ctx: ShadingContext) -> f32 {
    //#if sheen
    return ctx.under_sheen / (1.0 - ctx.sheen_probability);
    //#else
    return 1.0;
    //#endif
}

// Delta lobes: perfect mirrors and smooth (or cone-jittered) refraction.
fn sample_delta_lobe(ctx: ShadingContext, lobe: u32, u: f32, rng: ptr<function, Rng>) -> BsdfSample {
    let p = ctx.lobe_probability[lobe];
    let mirror = fold_above(vec3f(-ctx.wo.xy, ctx.wo.z), ctx.n_geometric);
    if lobe != LOBE_TRANSMISSION && !sample_clears_surface(ctx, mirror, false) {
        return invalid_sample();
    }
    if lobe == LOBE_SPECULAR {
        return BsdfSample(mirror, ctx.m.specular * specular_fresnel(ctx, ctx.wo.z) / p, 0.0, true, false, lobe);
    }
    if lobe == LOBE_REFLECTION {
        return BsdfSample(mirror, ctx.m.reflection * metal_fresnel(ctx, ctx.wo.z) / p, 0.0, true, false, lobe);
    }
    //#if glass
    return smooth_dielectric_sample(ctx, u, rng);
    //#else
    return invalid_sample();
    //#endif
}

fn sample_smooth_part(ctx: ShadingContext, lobe: u32, rng: ptr<function, Rng>) -> BsdfSample {
    //#if nee
    let wi = sample_smooth_lobe_direction(ctx, lobe, rng);
    if all(wi == vec3f(0.0)) {
        return invalid_sample();
    }
    let pdf = bsdf_pdf(ctx, wi);
    if pdf <= 0.0 {
        return invalid_sample();
    }
    return BsdfSample(wi, bsdf_eval(ctx, wi) / pdf, pdf, true, dot(wi, ctx.n_geometric) < 0.0, lobe);
    //#else
    return resample_smooth_part(ctx, lobe, rng);
    //#endif
}

//#if !nee
// The whole smooth part is resampled; `lobe`, the one `bsdf_sample` picked, only labels the sample.
fn resample_smooth_part(ctx: ShadingContext, lobe: u32, rng: ptr<function, Rng>) -> BsdfSample {
    let dense = ctx.lobe_probability * ctx.smooth_lobe;
    let p_dense = dense.x + dense.y + dense.z + dense.w;
    var lobe_choice = ctx;
    lobe_choice.lobe_probability = dense / max(p_dense, 1e-20);
    // How likely `bsdf_sample` reached the smooth part, by the coat or by another lobe.
    var p_coat = 0.0;
    var p_smooth = p_dense;
    //#if coat
    p_coat = ctx.coat_probability * f32(ctx.m.coat_alpha >= ALPHA_DELTA);
    p_smooth = p_dense * (1.0 - ctx.coat_probability) + p_coat;
    //#endif
    // The sheen, sampled before the rest, is all smooth.
    var p_sheen = 0.0;
    //#if sheen
    p_sheen = ctx.sheen_probability;
    p_smooth = p_sheen + (1.0 - p_sheen) * p_smooth;
    p_coat *= 1.0 - p_sheen;
    //#endif
    var sun_share = 0.0;
    //#if sun
    sun_share = 0.5;
    //#endif
    var weight_sum = 0.0;
    var chosen = vec3f(0.0);
    var chosen_f = vec3f(0.0);
    var chosen_target = 0.0;
    for (var i = 0u; i < frame.ris_candidates; i++) {
        var x: vec3f;
        if rng_next(rng) < sun_share {
            //#if sun
            x = transpose(ctx.basis) * sample_sun_direction(rng_next2(rng));
            //#endif
        } else {
            var u = rng_next(rng);
            var candidate_lobe = LOBE_SHEEN;
            if u * p_smooth >= p_sheen {
                candidate_lobe = LOBE_COAT;
            }
            if u * p_smooth >= p_sheen + p_coat {
                u = (u * p_smooth - p_sheen - p_coat) / (p_smooth - p_sheen - p_coat);
                candidate_lobe = pick_lobe(lobe_choice, &u);
            }
            x = sample_smooth_lobe_direction(ctx, candidate_lobe, rng);
        }
        if all(x == vec3f(0.0)) {
            continue;
        }
        let f = bsdf_eval(ctx, x);
        // Density of the candidate under the mixture it was drawn from.
        var q = (1.0 - sun_share) * bsdf_pdf(ctx, x) / p_smooth;
        var target_value = luminance(f);
        //#if sun
        let world = ctx.basis * x;
        q += sun_share * sun_direction_pdf(world);
        if in_sun_disk(world) {
            target_value *= 1.0 + luminance(frame.sun_radiance);
        }
        //#endif
        if q <= 0.0 || target_value <= 0.0 {
            continue;
        }
        let w = target_value / q;
        weight_sum += w;
        if rng_next(rng) * weight_sum < w {
            chosen = x;
            chosen_f = f;
            chosen_target = target_value;
        }
    }
    if weight_sum <= 0.0 {
        return invalid_sample();
    }
    // Unbiased contribution weight of the chosen candidate; the smooth part was picked with p_smooth.
    let contribution = weight_sum / (f32(frame.ris_candidates) * chosen_target);
    return BsdfSample(chosen, chosen_f * contribution / p_smooth, 0.0, true, dot(chosen, ctx.n_geometric) < 0.0, lobe);
}
//#endif
