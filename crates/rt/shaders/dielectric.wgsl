// The `transmission` lobe: a dielectric interface with exact Fresnel reflectance and
// total internal reflection. Reflection is tinted only towards normal incidence, by
// `specular_tint` (as Cycles' Principled glass); refraction is tinted by `base_color`,
// and refracted radiance is scaled by 1/η² (radiance is not conserved across a change of
// index). See `refraction_tint`.

//#include "constants.wgsl"
//#include "rng.wgsl"
//#include "directions.wgsl"
//#include "bsdf.wgsl"
//#include "microfacet.wgsl"

// The tint of one refraction: with multiscatter GGX Cycles' Principled glass, √base_color
// per crossing (so that a closed object shows base_color); else base_color (Mitsuba's
// `specular_transmittance`).
fn refraction_tint(m: Material) -> vec3f {
    //#if multiscatter
    return sqrt(max(min(m.base_color, vec3f(1.0)), vec3f(0.0)));
    //#else
    return m.base_color;
    //#endif
}

fn refraction_weight(ctx: ShadingContext) -> vec3f {
    return refraction_tint(ctx.m) / (ctx.eta * ctx.eta);
}

// Reflectance of the interface at a microfacet: the exact Fresnel, or the thin film's
// (per channel) mixed with it by the film's weight. Reflection and refraction are chosen
// by its mean.
fn glass_fresnel(ctx: ShadingContext, cos_i: f32) -> vec3f {
    let f = fresnel_dielectric(cos_i, ctx.eta);
    var bare = vec3f(f);
    if any(ctx.m.specular_tint != vec3f(1.0)) {
        bare = specular_tinted_fresnel(f, ctx.m.specular_tint, ctx.m.ior);
    }
    //#if thin_film
    if has_thin_film(ctx.m) {
        return mix(bare, thin_film_glass(ctx.m, cos_i, ctx.eta), ctx.m.thin_film_weight);
    }
    //#endif
    return bare;
}

// Cycles' Principled glass (a generalised Schlick Fresnel that follows the real curve):
// F0 is tinted by Specular Tint, and the real Fresnel's rise from its F0 to 1 (at grazing
// angles and in total internal reflection) is kept, per channel.
fn specular_tinted_fresnel(f: f32, tint: vec3f, ior: f32) -> vec3f {
    let f0_real = fresnel_dielectric_f0(ior);
    let s = saturate((f - f0_real) / (1.0 - f0_real));
    return mix(saturate(f0_real * tint), vec3f(1.0), s);
}

fn mean3(v: vec3f) -> f32 {
    return (v.x + v.y + v.z) / 3.0;
}

// Perfectly smooth interface (α below ALPHA_DELTA), or the seed's cone model.
fn smooth_dielectric_sample(ctx: ShadingContext, u: f32, rng: ptr<function, Rng>) -> BsdfSample {
    let scale = ctx.m.transmission / ctx.lobe_probability.w;
    let fr = glass_fresnel(ctx, ctx.wo.z);
    let f = mean3(fr);
    if u < f {
        let wi = fold_above(vec3f(-ctx.wo.xy, ctx.wo.z), ctx.n_geometric);
        if !sample_clears_surface(ctx, wi, false) {
            return invalid_sample();
        }
        return BsdfSample(wi, scale * fr / f, 0.0, true, false, LOBE_TRANSMISSION);
    }
    var wi = refract_direction(ctx.wo, vec3f(0.0, 0.0, 1.0), ctx.eta);
    //#if rough_glass_cone
    wi = jitter_in_cone(wi, ctx, rng);
    //#endif
    if dot(wi, ctx.n_geometric) >= 0.0 {
        return invalid_sample();
    }
    return BsdfSample(wi, scale * refraction_weight(ctx) * (1.0 - fr) / (1.0 - f), 0.0, true, true, LOBE_TRANSMISSION);
}

//#if rough_glass_cone
// The seed renderer's rough glass: the refracted direction is moved to a
// random direction in a cone around it (half-angle √α·π/2, i.e. roughness·90°),
// and flipped through the surface plane if that took it to the wrong side.
// Cheap, and not a microfacet model: `rt bench` shows what it costs in accuracy.
fn jitter_in_cone(w: vec3f, ctx: ShadingContext, rng: ptr<function, Rng>) -> vec3f {
    let half_angle = sqrt(ctx.m.alpha) * 0.5 * PI;
    let cos_max = cos(half_angle);
    let u = rng_next2(rng);
    let cos_t = 1.0 - u.x * (1.0 - cos_max);
    let sin_t = sqrt(max(0.0, 1.0 - cos_t * cos_t));
    let phi = 2.0 * PI * u.y;
    let jittered = tangent_frame(w) * vec3f(sin_t * cos(phi), sin_t * sin(phi), cos_t);
    return select(jittered, vec3f(jittered.xy, -jittered.z), jittered.z * w.z < 0.0);
}
//#endif

//#if rough_glass_ggx
// Rough dielectric after Walter et al. 2007, in the form of pbrt-v4's
// DielectricBxDF: the generalised half vector, visible-normal sampling,
// Fresnel at the microfacet. Single scattering: energy is lost at high α.

// The microfacet normal relating wo and wi, facing the viewer; zero if none. In Cycles' model
// a pair that sees the microfacet from behind counts too, with |cos|: `bsdf_microfacet_eval`
// takes every pair as it comes (VNDF sampling never makes one, light sampling meets them),
// which lights rough glass at grazing angles far more than a consistent model would (at
// α = 0.64, cos θ = 0.2 from inside, 0.43 transmitted against 0.12).
fn dielectric_half_vector(ctx: ShadingContext, wi: vec3f) -> vec3f {
    let reflect = wi.z > 0.0;
    let etap = select(ctx.eta, 1.0, reflect);
    let h = wi * etap + ctx.wo;
    if wi.z == 0.0 || dot(h, h) == 0.0 {
        return vec3f(0.0);
    }
    var m = normalize(h);
    m = select(m, -m, m.z < 0.0);
    //#if !multiscatter
    // Microfacets seen from behind contribute nothing.
    if dot(m, wi) * wi.z < 0.0 || dot(m, ctx.wo) < 0.0 {
        return vec3f(0.0);
    }
    //#endif
    return m;
}

fn rough_dielectric_eval(ctx: ShadingContext, wi: vec3f) -> vec3f {
    let reflect = wi.z > 0.0;
    if !glass_sees(ctx, wi) {
        return vec3f(0.0);
    }
    let m = dielectric_half_vector(ctx, wi);
    if m.z == 0.0 {
        return vec3f(0.0);
    }
    let a = ctx.alpha;
    let f = glass_fresnel(ctx, abs(dot(ctx.wo, m)));
    let dg = ggx_d(m, a) * ggx_g2(ctx.wo, wi, a);
    if reflect {
        return dg * f / (4.0 * ctx.wo.z);
    }
    let etap = ctx.eta;
    let denom = dot(wi, m) + dot(ctx.wo, m) / etap;
    let ft = (1.0 - f) * dg * abs(dot(wi, m) * dot(ctx.wo, m) / (ctx.wo.z * denom * denom));
    return ft * refraction_tint(ctx.m) / (etap * etap);
}

fn rough_dielectric_pdf(ctx: ShadingContext, wi: vec3f) -> f32 {
    let reflect = wi.z > 0.0;
    if !glass_sees(ctx, wi) {
        return 0.0;
    }
    let m = dielectric_half_vector(ctx, wi);
    if m.z == 0.0 {
        return 0.0;
    }
    let f = mean3(glass_fresnel(ctx, abs(dot(ctx.wo, m))));
    let visible = ggx_g1(ctx.wo, ctx.alpha) * abs(dot(ctx.wo, m)) * ggx_d(m, ctx.alpha) / ctx.wo.z;
    if reflect {
        return visible / (4.0 * abs(dot(ctx.wo, m))) * f;
    }
    let denom = dot(wi, m) + dot(ctx.wo, m) / ctx.eta;
    return visible * abs(dot(wi, m)) / (denom * denom) * (1.0 - f);
}

fn rough_dielectric_sample(ctx: ShadingContext, u: vec3f) -> vec3f {
    let m = ggx_sample_visible_normal(ctx.wo, ctx.alpha, u.xy);
    let f = mean3(glass_fresnel(ctx, dot(ctx.wo, m)));
    if u.z < f {
        let wi = reflect_local(ctx.wo, m);
        return select(vec3f(0.0), wi, wi.z > 0.0 && sample_clears_surface(ctx, wi, false));
    }
    let wi = refract_direction(ctx.wo, m, ctx.eta);
    return select(vec3f(0.0), wi, wi.z < 0.0 && sample_clears_surface(ctx, wi, true));
}
//#endif
