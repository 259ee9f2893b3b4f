// Sampling the lobes that have a density. With next-event estimation (`nee`),
// one direction from the picked lobe, weighed against the whole mixture. With
// the seed renderer's scheme (`seed`), resampled importance sampling (Talbot et
// al. 2005): candidates from the BSDF mixture and from the sun's disk, one of
// them chosen in proportion to BSDF × (1 + sun radiance if it points at the sun).

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
    return BsdfSample(wi, bsdf_eval(ctx, wi) / pdf, pdf, true, dot(wi, ctx.n_geometric) < 0.0);
    //#else
    return resample_smooth_part(ctx, rng);
    //#endif
}

//#if !nee
fn resample_smooth_part(ctx: ShadingContext, rng: ptr<function, Rng>) -> BsdfSample {
    let dense = ctx.lobe_probability * ctx.smooth_lobe;
    let p_smooth = dense.x + dense.y + dense.z + dense.w;
    let lobe_choice = ShadingContext(ctx.m, ctx.basis, ctx.wo, ctx.n_geometric, ctx.eta, dense / p_smooth, ctx.smooth_lobe);
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
            x = transpose(ctx.basis) * sample_sun_direction(vec2f(rng_next(rng), rng_next(rng)));
            //#endif
        } else {
            var u = rng_next(rng);
            x = sample_smooth_lobe_direction(ctx, pick_lobe(lobe_choice, &u), rng);
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
    return BsdfSample(chosen, chosen_f * contribution / p_smooth, 0.0, true, dot(chosen, ctx.n_geometric) < 0.0);
}
//#endif
