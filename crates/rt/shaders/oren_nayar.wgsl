// Cycles' rough diffuse (Blender 4.3+, `kernel/closure/bsdf_oren_nayar.h`), the Principled's
// Diffuse Roughness and the Diffuse BSDF's Roughness: Fujii's improved Oren-Nayar
// (https://mimosa-pudica.net/improved-oren-nayar.html) with the energy-preserving
// multiple-scattering term of OpenPBR's EON (Portsmouth, Kutz & Hill 2024). Cycles samples it
// as a Lambertian (cosine-weighted), so only the evaluation differs from one.

//#include "constants.wgsl"

// Below this roughness Cycles sets up a Lambertian closure (`CLOSURE_WEIGHT_CUTOFF`).
const OREN_NAYAR_CUTOFF: f32 = 1e-5;

// Cycles' `bsdf_oren_nayar_G`: the single-scattering albedo at `cos_theta` is A π + B G.
fn oren_nayar_g(cos_theta: f32) -> f32 {
    if cos_theta < 1e-6 {
        // tan θ misbehaves near grazing: the Taylor expansion there.
        return (0.5 * PI - 2.0 / 3.0) - cos_theta;
    }
    let sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
    let theta = acos(min(cos_theta, 1.0));
    return sin_theta * (theta - 2.0 / 3.0 - sin_theta * cos_theta)
        + 2.0 / 3.0 * (sin_theta / cos_theta) * (1.0 - sin_theta * sin_theta * sin_theta);
}

// The lobe's f / base colour (Lambert's 1/π) for roughness `sigma`, the cosines of the light
// (`cos_i`) and the view (`cos_o`) to the diffuse normal and between each other (`cos_io`).
// `albedo` is the base colour, which Cycles also feeds to the multiple-scattering term.
fn oren_nayar(sigma: f32, albedo: vec3f, cos_i: f32, cos_o: f32, cos_io: f32) -> vec3f {
    if sigma < OREN_NAYAR_CUTOFF {
        return vec3f(1.0 / PI);
    }
    let s = saturate(sigma);
    let a = 1.0 / (PI + s * (0.5 * PI - 2.0 / 3.0));
    let b = s * a;
    let nl = max(cos_i, 0.0);
    let nv = max(cos_o, 0.0);
    var t = cos_io - nl * nv;
    if t > 0.0 {
        t /= max(nl, nv) + 1.17549435e-38;
    }
    let e_avg = a * PI + ((2.0 * PI - 5.6) / 3.0) * b;
    let rho = saturate(albedo);
    let e_ms = rho * rho * (e_avg / (1.0 - e_avg)) / (PI * (vec3f(1.0) - rho * (1.0 - e_avg)));
    let e_i = a * PI + b * oren_nayar_g(nl);
    let e_o = a * PI + b * oren_nayar_g(nv);
    return vec3f(a + b * t) + e_ms * ((1.0 - e_o) * (1.0 - e_i));
}
