// GGX microfacet distribution (Trowbridge–Reitz; Walter et al., "Microfacet
// Models for Refraction through Rough Surfaces", EGSR 2007) with Smith
// masking–shadowing: height-correlated 1/(1 + Λ(wo) + Λ(wi)) with multiscatter GGX
// (as Cycles), else Walter's separable G1(wo)·G1(wi) (as Mitsuba 3, so that rt can
// be validated against it); sampled by its distribution of
// visible normals (Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 2018).
// Directions are in a local frame whose z axis is the shading normal; α is (αx, αy),
// the roughness along the frame's x and y axes (anisotropic GGX, as Cycles'; equal for
// an isotropic lobe).

//#include "constants.wgsl"

fn ggx_d(m: vec3f, alpha: vec2f) -> f32 {
    let s = m.xy / alpha;
    let d = dot(s, s) + m.z * m.z;
    return 1.0 / (PI * alpha.x * alpha.y * d * d);
}

fn ggx_lambda(w: vec3f, alpha: vec2f) -> f32 {
    let c2 = w.z * w.z;
    if c2 <= 0.0 {
        return INFINITY;
    }
    let s = w.xy * alpha;
    return 0.5 * (sqrt(1.0 + dot(s, s) / c2) - 1.0);
}

fn ggx_g1(w: vec3f, alpha: vec2f) -> f32 {
    return 1.0 / (1.0 + ggx_lambda(w, alpha));
}

fn ggx_g2(wo: vec3f, wi: vec3f, alpha: vec2f) -> f32 {
    //#if multiscatter
    return 1.0 / (1.0 + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
    //#else
    return ggx_g1(wo, alpha) * ggx_g1(wi, alpha);
    //#endif
}

// Density of visible normal m seen from wo (wo.z > 0).
fn ggx_visible_pdf(wo: vec3f, m: vec3f, alpha: vec2f) -> f32 {
    return ggx_g1(wo, alpha) * max(0.0, dot(wo, m)) * ggx_d(m, alpha) / wo.z;
}

fn ggx_sample_visible_normal(wo: vec3f, alpha: vec2f, u: vec2f) -> vec3f {
    let vh = normalize(vec3f(alpha * wo.xy, wo.z));
    let len2 = vh.x * vh.x + vh.y * vh.y;
    var t1 = vec3f(1.0, 0.0, 0.0);
    if len2 > 0.0 {
        t1 = vec3f(-vh.y, vh.x, 0.0) / sqrt(len2);
    }
    let t2 = cross(vh, t1);
    let r = sqrt(u.x);
    let phi = 2.0 * PI * u.y;
    let p1 = r * cos(phi);
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * r * sin(phi);
    let nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3f(alpha * nh.xy, max(1e-7, nh.z)));
}

// Refraction of wo (pointing away from the surface, on the side of m) through
// the interface with normal m; `eta` as above. Returns a zero vector on total internal reflection.
fn refract_direction(wo: vec3f, m: vec3f, eta: f32) -> vec3f {
    let cos_i = dot(wo, m);
    let sin2_t = max(0.0, 1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return vec3f(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return -wo / eta + (cos_i / eta - cos_t) * m;
}
