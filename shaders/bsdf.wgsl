// Scattering at a surface: a mixture of lobes weighted by the material (the
// weights are normalised on the host so that a material never reflects more
// than it receives). Directions are local to the shading normal (z), with the
// viewer above (wo.z > 0).
//
// Lobes: Lambertian diffuse; `specular`, an untinted GGX reflection; `reflection`,
// a conductor tinted by `base_color` (see `conductor_fresnel`); `transmission`, a
// dielectric with exact Fresnel and total internal reflection, refraction tinted
// by `base_color`. At α below ALPHA_DELTA a lobe is a perfect (delta) mirror or
// interface.

const ALPHA_DELTA: f32 = 1e-3;

const LOBE_DIFFUSE: u32 = 0u;
const LOBE_SPECULAR: u32 = 1u;
const LOBE_REFLECTION: u32 = 2u;
const LOBE_TRANSMISSION: u32 = 3u;

struct ShadingContext {
    m: Material,
    // Local to world; its z column is the shading normal.
    basis: mat3x3f,
    wo: vec3f,
    // The geometric normal in the local frame, on the viewer's side.
    n_geometric: vec3f,
    // Refractive index beyond the surface over the index on the viewer's side.
    eta: f32,
    // Probability of picking each lobe when sampling (diffuse, specular, reflection, transmission).
    lobe_probability: vec4f,
    // Which lobes have a density (1) rather than being delta (0).
    smooth_lobe: vec4f,
}

struct BsdfSample {
    direction: vec3f,
    // f·|cos|/pdf: what the path throughput is multiplied by.
    weight: vec3f,
    // Solid-angle density of the direction over the whole BSDF; 0 for a delta lobe.
    pdf: f32,
    valid: bool,
    // The direction crosses the surface.
    transmitted: bool,
}

fn invalid_sample() -> BsdfSample {
    return BsdfSample(vec3f(0.0, 0.0, 1.0), vec3f(0.0), 0.0, false, false);
}

// What produced a non-finite value first, recorded per pixel (see `integrator.wgsl`).
const EVENT_NONE: u32 = 0u;
const EVENT_EMISSION: u32 = 1u;
const EVENT_SKY: u32 = 2u;
const EVENT_LIGHT_SAMPLE: u32 = 3u;
const EVENT_MEDIUM: u32 = 4u;
const EVENT_AIR: u32 = 5u;
// EVENT_LOBE + lobe index: the BSDF sample of that lobe.
const EVENT_LOBE: u32 = 6u;

// An orthonormal basis around n (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
fn tangent_frame(n: vec3f) -> mat3x3f {
    let s = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    let t = vec3f(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    let bt = vec3f(b, s + n.y * n.y * a, -n.y);
    return mat3x3f(t, bt, n);
}

fn sample_cosine_hemisphere(u: vec2f) -> vec3f {
    let r = sqrt(u.x);
    let phi = 2.0 * PI * u.y;
    return vec3f(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
}

// Unpolarised Fresnel reflectance of a dielectric interface; `eta` is the
// index on the far side over the index on the near side, `cos_i` > 0.
fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let sin2_t = max(0.0, 1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = sqrt(1.0 - sin2_t);
    let r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (r_parallel * r_parallel + r_perpendicular * r_perpendicular);
}

// Fresnel reflectance of the `reflection` lobe's conductor, per channel: the
// exact Fresnel of a non-absorbing interface whose reflectance at normal
// incidence is `f0` (index η = (1 + √f0)/(1 − √f0)), rising to 1 at grazing.
// Mitsuba's `conductor` with that η and k = 0 is the same function.
fn conductor_fresnel(f0: vec3f, cos_i: f32) -> vec3f {
    let r = sqrt(clamp(f0, vec3f(0.0), vec3f(0.999999)));
    let eta = (1.0 + r) / (1.0 - r);
    return vec3f(fresnel_dielectric(cos_i, eta.x), fresnel_dielectric(cos_i, eta.y), fresnel_dielectric(cos_i, eta.z));
}

fn luminance(c: vec3f) -> f32 {
    return dot(c, vec3f(0.2126, 0.7152, 0.0722));
}

// `n_shading` and `n_geometric` face the viewer; `entering` says that the viewer
// is outside the surface (so refraction leads inside).
fn shading_context(m: Material, n_shading: vec3f, n_geometric: vec3f, wo_world: vec3f, entering: bool) -> ShadingContext {
    // A shading normal that faces away from the viewer cannot shade: fall back to the true one.
    var n = n_shading;
    if dot(n, wo_world) <= 1e-4 {
        n = n_geometric;
    }
    let basis = tangent_frame(n);
    let to_local = transpose(basis);
    let wo = to_local * wo_world;
    let eta = select(1.0 / m.ior, m.ior, entering);
    let rough = m.alpha >= ALPHA_DELTA;
    var smooth_lobe = vec4f(1.0, f32(rough), f32(rough), 0.0);
    //#if rough_glass_ggx
    smooth_lobe.w = f32(rough);
    //#endif
    let p = vec4f(m.diffuse * luminance(m.base_color), m.specular, m.reflection * luminance(m.base_color), m.transmission);
    let total = p.x + p.y + p.z + p.w;
    let probability = select(vec4f(0.0), p / total, total > 0.0);
    return ShadingContext(m, basis, vec3f(wo.xy, max(wo.z, 1e-6)), to_local * n_geometric, eta, probability, smooth_lobe);
}

// Mirrors a direction that the shading normal put below the true surface back
// above it. Applied to sampling and evaluation alike, it folds the lobe's
// leaking part onto the visible side: the BSDF stays consistent for MIS and a
// white surface keeps all its energy.
fn fold_above(w: vec3f, n_geometric: vec3f) -> vec3f {
    let d = dot(w, n_geometric);
    return select(w, w - 2.0 * d * n_geometric, d < 0.0);
}

fn reflect_local(wo: vec3f, m: vec3f) -> vec3f {
    return 2.0 * dot(wo, m) * m - wo;
}

// f·|cos θi| of one reflection lobe, before folding.
fn reflection_lobe_eval(ctx: ShadingContext, lobe: u32, wi: vec3f) -> vec3f {
    if wi.z <= 0.0 {
        return vec3f(0.0);
    }
    if lobe == LOBE_DIFFUSE {
        return ctx.m.base_color * (ctx.m.diffuse * wi.z / PI);
    }
    //#if glossy
    let m = normalize(ctx.wo + wi);
    let a = ctx.m.alpha;
    let microfacet = ggx_d(m, a) * ggx_g2(ctx.wo, wi, a) / (4.0 * ctx.wo.z);
    if lobe == LOBE_SPECULAR {
        return vec3f(ctx.m.specular * microfacet);
    }
    return ctx.m.reflection * microfacet * conductor_fresnel(ctx.m.base_color, dot(ctx.wo, m));
    //#else
    return vec3f(0.0);
    //#endif
}

fn reflection_lobe_pdf(ctx: ShadingContext, lobe: u32, wi: vec3f) -> f32 {
    if wi.z <= 0.0 {
        return 0.0;
    }
    if lobe == LOBE_DIFFUSE {
        return wi.z / PI;
    }
    //#if glossy
    let m = normalize(ctx.wo + wi);
    return ggx_visible_pdf(ctx.wo, m, ctx.m.alpha) / (4.0 * dot(ctx.wo, m));
    //#else
    return 0.0;
    //#endif
}

// f·|cos θi| of all lobes that have a density, at wi.
fn bsdf_eval(ctx: ShadingContext, wi: vec3f) -> vec3f {
    var f = vec3f(0.0);
    if dot(wi, ctx.n_geometric) > 0.0 {
        let mirrored = wi - 2.0 * dot(wi, ctx.n_geometric) * ctx.n_geometric;
        for (var lobe = LOBE_DIFFUSE; lobe <= LOBE_REFLECTION; lobe++) {
            if ctx.smooth_lobe[lobe] > 0.0 && ctx.lobe_probability[lobe] > 0.0 {
                f += reflection_lobe_eval(ctx, lobe, wi) + reflection_lobe_eval(ctx, lobe, mirrored);
            }
        }
    }
    //#if rough_glass_ggx
    if ctx.smooth_lobe.w > 0.0 && ctx.lobe_probability.w > 0.0 {
        f += ctx.m.transmission * rough_dielectric_eval(ctx, wi);
    }
    //#endif
    return f;
}

// Density with which `bsdf_sample` produces wi (delta lobes aside).
fn bsdf_pdf(ctx: ShadingContext, wi: vec3f) -> f32 {
    var pdf = 0.0;
    if dot(wi, ctx.n_geometric) > 0.0 {
        let mirrored = wi - 2.0 * dot(wi, ctx.n_geometric) * ctx.n_geometric;
        for (var lobe = LOBE_DIFFUSE; lobe <= LOBE_REFLECTION; lobe++) {
            if ctx.smooth_lobe[lobe] > 0.0 {
                pdf += ctx.lobe_probability[lobe] * (reflection_lobe_pdf(ctx, lobe, wi) + reflection_lobe_pdf(ctx, lobe, mirrored));
            }
        }
    }
    //#if rough_glass_ggx
    if ctx.smooth_lobe.w > 0.0 {
        pdf += ctx.lobe_probability.w * rough_dielectric_pdf(ctx, wi);
    }
    //#endif
    return pdf;
}

// A direction from one lobe that has a density (before the mixture weighs it).
// Returns a zero vector when the lobe produced nothing.
fn sample_smooth_lobe_direction(ctx: ShadingContext, lobe: u32, rng: ptr<function, Rng>) -> vec3f {
    let u = vec2f(rng_next(rng), rng_next(rng));
    //#if rough_glass_ggx
    if lobe == LOBE_TRANSMISSION {
        return rough_dielectric_sample(ctx, vec3f(u, rng_next(rng)));
    }
    //#endif
    var wi = sample_cosine_hemisphere(u);
    //#if glossy
    if lobe != LOBE_DIFFUSE {
        wi = reflect_local(ctx.wo, ggx_sample_visible_normal(ctx.wo, ctx.m.alpha, u));
    }
    //#endif
    if wi.z <= 0.0 {
        return vec3f(0.0);
    }
    return fold_above(wi, ctx.n_geometric);
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

// The lobe picked by the last `bsdf_sample`, for the non-finite sentinel.
var<private> sampled_lobe: u32;

fn bsdf_sample(ctx: ShadingContext, rng: ptr<function, Rng>) -> BsdfSample {
    if all(ctx.lobe_probability == vec4f(0.0)) {
        return invalid_sample();
    }
    var u = rng_next(rng);
    let lobe = pick_lobe(ctx, &u);
    sampled_lobe = lobe;
    var s: BsdfSample;
    if ctx.smooth_lobe[lobe] > 0.0 {
        s = sample_smooth_part(ctx, lobe, rng);
    } else {
        s = sample_delta_lobe(ctx, lobe, u, rng);
    }
    s.direction = ctx.basis * s.direction;
    return s;
}

// Delta lobes: perfect mirrors and smooth (or cone-jittered) refraction.
fn sample_delta_lobe(ctx: ShadingContext, lobe: u32, u: f32, rng: ptr<function, Rng>) -> BsdfSample {
    let p = ctx.lobe_probability[lobe];
    let mirror = fold_above(vec3f(-ctx.wo.xy, ctx.wo.z), ctx.n_geometric);
    if lobe == LOBE_SPECULAR {
        return BsdfSample(mirror, vec3f(ctx.m.specular / p), 0.0, true, false);
    }
    if lobe == LOBE_REFLECTION {
        return BsdfSample(mirror, ctx.m.reflection * conductor_fresnel(ctx.m.base_color, ctx.wo.z) / p, 0.0, true, false);
    }
    //#if glass
    return smooth_dielectric_sample(ctx, u, rng);
    //#else
    return invalid_sample();
    //#endif
}
