// Cycles' Principled BSDF (Blender 5.0, `kernel/svm/closure.h`, `kernel/closure/bsdf_microfacet.h`)
// on rt's lobes: the F82-tint metal, the dielectric coating over the diffuse lobe (the
// Principled specular layer: real Fresnel remapped between F0 × tint and 1, the diffuse
// keeping 1 − the coating's albedo), and Cycles' multiple-scattering energy compensation
// of GGX lobes (`microfacet_ggx_preserve_energy`: the single-scattering lobe times
// 1 + Fms (1 − E) / E, Kulla & Conty 2017, with Cycles' tables of E).

//#include "common.wgsl"
//#include "microfacet_tables.wgsl"

// Cycles' `fresnel_dielectric_Fss`: ∫ 2 cos F(cos) dcos of the real Fresnel curve
// (the fit of Kulla & Conty, "Revisiting Physically Based Shading at Imageworks").
fn fresnel_dielectric_average(eta: f32) -> f32 {
    if eta < 1.0 {
        return 0.997118 + eta * (0.1014 - eta * (0.965241 + eta * 0.130607));
    }
    return (eta - 1.0) / (4.08567 + 1.00071 * eta);
}

// F82-tint (Kutz et al., "Novel aspects of the Adobe Standard Material"): Schlick's curve
// from F0 less b·cos·(1 − cos)⁶, b chosen so that the value at cos = 1/7 is Schlick's × tint.
fn f82_b(f0: vec3f, tint: vec3f) -> vec3f {
    let f = 6.0 / 7.0;
    let f5 = f * f * f * f * f;
    return mix(f0, vec3f(1.0), f5) * (7.0 / (f5 * f)) * (vec3f(1.0) - tint);
}

fn f82_fresnel(cos_i: f32, f0: vec3f, b: vec3f) -> vec3f {
    let s = saturate(1.0 - cos_i);
    let s5 = s * s * s * s * s;
    return saturate(mix(f0, vec3f(1.0), s5) - b * cos_i * s5 * s);
}

fn metal_f0(m: Material) -> vec3f {
    return min(m.base_color, vec3f(1.0));
}

// The coating's reflectance at a microfacet: where the real Fresnel of its index lies
// between that index's F0 and 1, carried over to F0 × tint and 1.
fn coating_fresnel(m: Material, cos_i: f32) -> vec3f {
    let s = saturate((fresnel_dielectric(cos_i, m.coating_eta) - m.coating_f0) / (1.0 - m.coating_f0));
    return mix(saturate(m.coating_f0 * m.specular_tint), vec3f(1.0), s);
}

// The coating's average reflectance, for its multiple-scattering colour.
fn coating_average(m: Material) -> vec3f {
    let s = saturate((fresnel_dielectric_average(m.coating_eta) - m.coating_f0) / (1.0 - m.coating_f0));
    return mix(saturate(m.coating_f0 * m.specular_tint), vec3f(1.0), s);
}

// Multiplier of a single-scattering GGX lobe whose albedo without Fresnel is `e`
// (average `e_avg`) and whose average Fresnel is `fss`.
fn energy_compensation(e: f32, e_avg: f32, fss: vec3f) -> vec3f {
    let missing = (1.0 - e) / max(e, 1e-6);
    let fms = fss * e_avg / max(vec3f(1.0) - fss * (1.0 - e_avg), vec3f(1e-6));
    return vec3f(1.0) + fms * missing;
}

// Albedo of GGX reflection without Fresnel.
fn ggx_albedo(alpha: f32, mu: f32) -> f32 {
    return table_2d(TABLE_GGX_E, 32u, 32u, sqrt(alpha), mu);
}

fn reflection_energy(alpha: f32, mu: f32, fss: vec3f) -> vec3f {
    return energy_compensation(ggx_albedo(alpha, mu), table_1d(TABLE_GGX_EAVG, 32u, sqrt(alpha)), fss);
}

// A rough dielectric interface: reflection and refraction together (`eta`: the far side's
// index over the viewer's), tinted by `tint` on refraction.
fn dielectric_energy(alpha: f32, mu: f32, eta: f32, tint: vec3f) -> vec3f {
    let rough = sqrt(alpha);
    var e_table = TABLE_GLASS_E;
    var avg_table = TABLE_GLASS_EAVG;
    var index = eta;
    if eta < 1.0 {
        index = 1.0 / eta;
        e_table = TABLE_GLASS_INV_E;
        avg_table = TABLE_GLASS_INV_EAVG;
    }
    let z = microfacet_table_z(index);
    let e = table_3d(e_table, 16u, rough, mu, z);
    return energy_compensation(e, table_2d(avg_table, 16u, 16u, rough, z), tint);
}

// Principled's coat seen from `mu`: its energy compensation, what the lobes and the emission
// under it keep (1 − coat × its albedo, times the tint along the refracted view: Cycles'
// `closure_layering_weight` and Beer's law), and its albedo (for sampling).
struct CoatLayer {
    energy: vec3f,
    under: vec3f,
    albedo: f32,
}

fn coat_layer(m: Material, mu: f32) -> CoatLayer {
    let f0 = fresnel_dielectric_f0(m.coat_ior);
    let estimate = mix(f0, 1.0, coating_fresnel_s(sqrt(m.coat_alpha), mu, m.coat_ior));
    var energy = vec3f(1.0);
    var darkening = 1.0;
    //#if multiscatter
    if m.coat_alpha >= ALPHA_DELTA {
        energy = reflection_energy(m.coat_alpha, mu, vec3f(fresnel_dielectric_average(m.coat_ior)));
        darkening = energy.x * ggx_albedo(m.coat_alpha, mu);
    }
    //#endif
    let tint = coat_tint_seen(m, mu);
    return CoatLayer(energy, saturate(1.0 - m.coat * estimate * darkening) * tint, m.coat * estimate);
}

// The coat's tint along a path at cosine `mu` to its normal, refracted into it: Beer's law
// over the coat's thickness, its colour at normal incidence (`svm/closure.h`).
fn coat_tint_seen(m: Material, mu: f32) -> vec3f {
    let cos_t = sqrt(max(1e-6, 1.0 - (1.0 - mu * mu) / (m.coat_ior * m.coat_ior)));
    return mix(vec3f(1.0), pow(max(m.coat_tint, vec3f(1e-8)), vec3f(1.0 / cos_t)), m.coat);
}

fn coat_setup(ctx: ptr<function, ShadingContext>, mu: f32) -> f32 {
    let layer = coat_layer((*ctx).m, mu);
    (*ctx).coat_energy = layer.energy;
    (*ctx).under_coat = layer.under;
    return layer.albedo;
}

// Emission under the coat, leaving at cosine `mu` to the coat's normal: Cycles sets up a
// Principled's emission with the weight that its coat leaves the lower layers (`svm/closure.h`).
fn coated_emission(m: Material, emission: vec3f, mu: f32) -> vec3f {
    if m.coat <= 0.0 {
        return emission;
    }
    return emission * coat_layer(m, clamp(mu, 1e-6, 1.0)).under;
}

// How much of the diffuse lobe the coating lets through, seen from `mu`: 1 − the largest
// channel of its albedo (Cycles' `closure_layering_weight` of `bsdf_microfacet_estimate_albedo`).
// The estimate assumes a lobe that keeps its energy; `darkening` is what multiple-scattering
// Fresnel takes off that (1 in single scattering).
fn coating_transmittance(m: Material, mu: f32, darkening: vec3f) -> f32 {
    let s = coating_fresnel_s(sqrt(m.alpha), mu, m.coating_eta);
    let albedo = mix(saturate(m.coating_f0 * m.specular_tint), vec3f(1.0), s) * darkening;
    return saturate(1.0 - max(max(albedo.x, albedo.y), albedo.z));
}
