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

//#include "common.wgsl"
//#include "directions.wgsl"
//#include "reflectance.wgsl"
//#if microfacet_tables
//#include "principled.wgsl"
//#endif
//#if sheen
//#include "sheen.wgsl"
//#endif
//#if anisotropy
//#include "anisotropy.wgsl"
//#endif
//#if thin_film
//#include "thin_film.wgsl"
//#endif
//#if coat_normal
//#include "coat_normal.wgsl"
//#endif
//#include "lobe_hemispheres.wgsl"

const ALPHA_DELTA: f32 = 1e-3;

// The lobes, LOBE_*, are shared constants (src/shared_constants.rs).

struct ShadingContext {
    m: Material,
    // Local to world; its z column is the shading normal.
    basis: mat3x3f,
    wo: vec3f,
    // The geometric normal in the local frame, on the viewer's side.
    n_geometric: vec3f,
    // GGX (αx, αy) of the rough lobes along the frame's x and y (see anisotropy.wgsl).
    alpha: vec2f,
    // Refractive index beyond the surface over the index on the viewer's side.
    eta: f32,
    // Probability of picking each lobe when sampling (diffuse, specular, reflection, transmission).
    lobe_probability: vec4f,
    // Which lobes have a density (1) rather than being delta (0).
    smooth_lobe: vec4f,
    // Multiple-scattering energy compensation of the specular, reflection and
    // transmission lobes (see principled.wgsl; 1 in single scattering).
    energy_specular: vec3f,
    energy_reflection: vec3f,
    energy_transmission: vec3f,
    // The part of the diffuse lobe that its dielectric coating lets through (1: no coating).
    diffuse_kept: f32,
    // F82-tint's b of the `reflection` metal (see `metal_fresnel`).
    metal_b: vec3f,
    // The coat: the probability of sampling it, its energy compensation, and what the
    // lobes under it keep (1 without a coat).
    coat_probability: f32,
    coat_energy: vec3f,
    under_coat: vec3f,
    // The sheen (see sheen.wgsl): the probability of sampling it, its colour (sheen × tint ×
    // albedo), its transform (a, b; a = 0: no sheen) and frame's x axis in the shading frame
    // (about the sheen's own normal), and what everything under it keeps (1 without a sheen).
    sheen_probability: f32,
    sheen_color: vec3f,
    sheen_transform: vec2f,
    sheen_side: vec3f,
    under_sheen: f32,
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
    // The lobe that was picked (LOBE_*).
    lobe: u32,
}

// A sample that ends the path: nothing could be sampled (its lobe is not looked at).
fn invalid_sample() -> BsdfSample {
    return BsdfSample(vec3f(0.0, 0.0, 1.0), vec3f(0.0), 0.0, false, false, LOBE_DIFFUSE);
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

// Fresnel reflectance of the `reflection` lobe: Cycles' F82-tint metal with
// multiscatter GGX, else `conductor_fresnel` (as Mitsuba 3's conductor); under a film,
// the film's mixed with it by the film's weight (KHR_materials_iridescence's factor).
fn metal_fresnel(ctx: ShadingContext, cos_i: f32) -> vec3f {
    //#if multiscatter
    let bare = f82_fresnel(cos_i, metal_f0(ctx.m), ctx.metal_b);
    //#else
    let bare = conductor_fresnel(ctx.m.base_color, cos_i);
    //#endif
    //#if thin_film
    if has_thin_film(ctx.m) {
        let f0 = metal_f0(ctx.m);
        let film = thin_film_metal(ctx.m, cos_i, f0, f82_b(f0, min(ctx.m.specular_tint, vec3f(1.0))));
        return mix(bare, film, ctx.m.thin_film_weight);
    }
    //#endif
    return bare;
}

// Reflectance of the `specular` lobe: the diffuse's dielectric coating, or `specular_tint`
// (a lobe without Fresnel: Cycles' Glossy BSDF of that colour) for a material without one.
fn specular_fresnel(ctx: ShadingContext, cos_i: f32) -> vec3f {
    //#if coating
    if ctx.m.coating_eta > 0.0 {
        //#if thin_film
        if has_thin_film(ctx.m) {
            return mix(coating_fresnel(ctx.m, cos_i), thin_film_coating(ctx.m, cos_i), ctx.m.thin_film_weight);
        }
        //#endif
        return coating_fresnel(ctx.m, cos_i);
    }
    //#endif
    return ctx.m.specular_tint;
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
    var basis = tangent_frame(n);
    var alpha = vec2f(m.alpha);
    //#if anisotropy
    if m.anisotropy > 0.0 {
        basis = anisotropic_frame(n, m.anisotropy_rotation);
        alpha = anisotropic_alpha(m.alpha, m.anisotropy);
    }
    //#endif
    let to_local = transpose(basis);
    let wo = to_local * wo_world;
    let eta = select(1.0 / m.ior, m.ior, entering);
    let rough = m.alpha >= ALPHA_DELTA;
    var smooth_lobe = vec4f(1.0, f32(rough), f32(rough), 0.0);
    //#if rough_glass_ggx
    smooth_lobe.w = f32(rough);
    //#endif
    let mu = max(wo.z, 1e-6);
    // Where the microfacet lobes do not shade, Cycles still reads its albedo tables for what
    // they take from the layers below, at cos θ clamped to 0.
    let shades = microfacet_lobes_shade(n_shading, wo_world);
    let table_mu = select(1e-6, mu, shades);
    var ctx = ShadingContext(m, basis, vec3f(wo.xy, mu), to_local * n_geometric, alpha, eta, vec4f(0.0), smooth_lobe, vec3f(1.0), vec3f(1.0), vec3f(1.0), 1.0, vec3f(0.0), 0.0, vec3f(1.0), vec3f(1.0), 0.0, vec3f(0.0), vec2f(0.0), vec3f(1.0, 0.0, 0.0), 1.0);
    var specular_albedo = luminance(m.specular_tint);
    //#if multiscatter
    microfacet_energies(&ctx, rough, table_mu);
    //#endif
    //#if coating
    if m.coating_eta > 0.0 {
        specular_albedo = coating_setup(&ctx, rough, table_mu);
    }
    //#endif
    var p = vec4f(m.diffuse * ctx.diffuse_kept * luminance(m.base_color), m.specular * specular_albedo, m.reflection * luminance(m.base_color), m.transmission);
    if !shades {
        p = vec4f(p.x, 0.0, 0.0, 0.0);
    }
    let total = p.x + p.y + p.z + p.w;
    ctx.lobe_probability = select(vec4f(0.0), p / total, total > 0.0);
    layer_probabilities(&ctx, total, table_mu, shades, wo_world, n_geometric);
    return ctx;
}

//#if multiscatter
// The multiscatter lobes' energies at the view's cos θ (`table_mu`): Cycles' albedo tables.
fn microfacet_energies(ctx: ptr<function, ShadingContext>, rough: bool, table_mu: f32) {
    let m = (*ctx).m;
    (*ctx).metal_b = f82_b(metal_f0(m), min(m.specular_tint, vec3f(1.0)));
    if rough {
        // Without a coating, Cycles' constant Fresnel of a Glossy BSDF: its colour.
        var specular_fss = m.specular_tint;
        //#if coating
        if m.coating_eta > 0.0 {
            specular_fss = coating_average(m);
        }
        //#endif
        (*ctx).energy_specular = reflection_energy(m.alpha, table_mu, specular_fss);
        let metal_fss = mix(metal_f0(m), vec3f(1.0), 1.0 / 21.0) - (*ctx).metal_b / 126.0;
        (*ctx).energy_reflection = reflection_energy(m.alpha, table_mu, metal_fss);
        (*ctx).energy_transmission = dielectric_energy(m.alpha, table_mu, (*ctx).eta, sqrt(saturate(m.base_color)));
    }
}
//#endif

//#if coating
// What a dielectric coating keeps of the diffuse lobe under it (`diffuse_kept`), and the
// coating's albedo, which it returns: the specular lobe's sampling weight.
fn coating_setup(ctx: ptr<function, ShadingContext>, rough: bool, table_mu: f32) -> f32 {
    let m = (*ctx).m;
    var darkening = vec3f(1.0);
    //#if multiscatter
    if rough {
        darkening = (*ctx).energy_specular * ggx_albedo(m.alpha, table_mu);
    }
    //#endif
    (*ctx).diffuse_kept = coating_transmittance(m, table_mu, darkening);
    var specular_albedo = luminance(mix(saturate(m.coating_f0 * m.specular_tint), vec3f(1.0), coating_fresnel_s(sqrt(m.alpha), table_mu, m.coating_eta)));
    //#if thin_film
    if has_thin_film(m) {
        // Cycles has no albedo table for a film: its estimate is the film's Fresnel at
        // mu; a partial film (glTF's factor) mixes the estimates with and without it.
        let film = thin_film_coating(m, table_mu);
        let albedo = film * darkening;
        let kept = saturate(1.0 - max(max(albedo.x, albedo.y), albedo.z));
        (*ctx).diffuse_kept = mix((*ctx).diffuse_kept, kept, m.thin_film_weight);
        specular_albedo = mix(specular_albedo, luminance(film), m.thin_film_weight);
    }
    //#endif
    return specular_albedo;
}
//#endif

// The coat's and the sheen's sampling probabilities against the lobes below them, whose
// albedo is `total`.
fn layer_probabilities(ctx: ptr<function, ShadingContext>, total: f32, table_mu: f32, shades: bool, wo_world: vec3f, n_geometric: vec3f) {
    let m = (*ctx).m;
    // The albedo of what lies under the sheen, for its sampling probability.
    var below = total;
    //#if coat
    if m.coat > 0.0 {
        var coat_mu = table_mu;
        //#if coat_normal
        coat_mu = coat_frame_setup((*ctx).basis, wo_world, n_geometric);
        //#endif
        let coat_albedo = coat_setup(ctx, coat_mu);
        let rest = total * luminance((*ctx).under_coat);
        (*ctx).coat_probability = select(1.0, coat_albedo / (coat_albedo + rest), coat_albedo + rest > 0.0);
        below = coat_albedo + rest;
        if !shades {
            // The coat is a microfacet lobe too; what it takes from the layers below stays.
            (*ctx).m.coat = 0.0;
            (*ctx).coat_probability = 0.0;
            below = rest;
        }
    }
    //#endif
    //#if sheen
    if m.sheen > 0.0 {
        let sheen_albedo = sheen_setup(ctx, m.coat);
        let rest = below * (*ctx).under_sheen;
        (*ctx).sheen_probability = select(0.0, sheen_albedo / (sheen_albedo + rest), sheen_albedo > 0.0);
    }
    //#endif
}

fn reflect_local(wo: vec3f, m: vec3f) -> vec3f {
    return 2.0 * dot(wo, m) * m - wo;
}
