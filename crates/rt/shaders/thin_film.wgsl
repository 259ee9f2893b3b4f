// Thin-film interference as Cycles 5.0 renders Principled's Thin Film (`kernel/closure/
// bsdf_util.h`, `fresnel_iridescence`; Belcour & Barla 2017, "A Practical Extension to
// Microfacet Theory for the Modeling of Varying Iridescence"): a film of index
// `thin_film_ior` and thickness `thin_film_thickness` (nm) between the air and a lobe's
// dielectric or conductor. The reflectance is the Airy sum over the film's inner
// reflections, its first three orders of path difference integrated against the RGB
// colour matching functions in Fourier space (Cycles' table, see
// `scripts/make_thin_film_table.py`); the two polarisations are summed apart and
// averaged. The specular, metal and glass lobes use it for their Fresnel; their energy
// compensation keeps the film-free average, as Cycles' does.

//#include "constants.wgsl"
//#include "microfacet_tables.wgsl"
//#include "principled.wgsl"

// Films this thin or thinner are not there (Cycles' THINFILM_THICKNESS_CUTOFF).
const THIN_FILM_CUTOFF: f32 = 0.1;
// The sensitivity table: 512 complex values per channel over path differences of 0 to 60 µm.
const TABLE_THIN_FILM: u32 = 16928u;
const THIN_FILM_TABLE_SIZE: u32 = 512u;

fn has_thin_film(m: Material) -> bool {
    return m.thin_film_thickness > THIN_FILM_CUTOFF;
}

// A complex number per channel.
struct Phasor {
    re: vec3f,
    im: vec3f,
}

fn phasor_mul(a: Phasor, b: Phasor) -> Phasor {
    return Phasor(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
}

// The Fourier transform of the RGB matching functions at path difference `opd` (nm).
fn thin_film_sensitivity(opd: f32) -> Phasor {
    let x = 2.0 * PI * opd / 60000.0;
    var re = vec3f(0.0);
    var im = vec3f(0.0);
    for (var c = 0u; c < 3u; c++) {
        re[c] = table_1d(TABLE_THIN_FILM + c * THIN_FILM_TABLE_SIZE, THIN_FILM_TABLE_SIZE, x);
        im[c] = table_1d(TABLE_THIN_FILM + (3u + c) * THIN_FILM_TABLE_SIZE, THIN_FILM_TABLE_SIZE, x);
    }
    return Phasor(re, im);
}

// Reflectances of one dielectric interface for s and p polarised light, the signs of their
// amplitudes (the cosine of the phase shift on reflection), and the refracted cosine
// (negative: into the far side); `eta` is the far index over the near one.
struct Polarised {
    r: vec2f,
    cos_phi: vec2f,
    cos_t: f32,
    total: bool,
}

fn fresnel_polarised(cos_i: f32, eta: f32) -> Polarised {
    let eta_cos_t_sq = eta * eta - (1.0 - cos_i * cos_i);
    if eta_cos_t_sq <= 0.0 {
        return Polarised(vec2f(1.0), vec2f(1.0), 0.0, true);
    }
    let c = abs(cos_i);
    let cos_t = -sqrt(eta_cos_t_sq) / eta;
    let r_s = (c + eta * cos_t) / (c - eta * cos_t);
    let r_p = (cos_t + eta * c) / (eta * c - cos_t);
    let cos_phi = vec2f(select(-1.0, 1.0, r_s >= 0.0), select(-1.0, 1.0, r_p >= 0.0));
    return Polarised(vec2f(r_s * r_s, r_p * r_p), cos_phi, cos_t, false);
}

// Equation 10 of Belcour & Barla for one polarisation, truncated after the third order.
fn airy_summation(r12: f32, r23: vec3f, opd: f32, phasor: Phasor) -> vec3f {
    let t121 = 1.0 - r12;
    let r123 = r12 * r23;
    let root = sqrt(r123);
    let rs = t121 * t121 * r23 / (vec3f(1.0) - r123);
    var r = rs + r12;
    var cm = rs - t121;
    var accumulator = phasor;
    for (var m = 1u; m < 4u; m++) {
        cm *= root;
        let s = thin_film_sensitivity(f32(m) * opd);
        r += cm * 2.0 * (accumulator.re * s.re + accumulator.im * s.im);
        accumulator = phasor_mul(accumulator, phasor);
    }
    return r;
}

// The film's index as the Airy sum sees it: below 1 nm it fades into the ambient's (1).
fn film_index(m: Material, film_ior: f32) -> f32 {
    return mix(1.0, film_ior, smoothstep(0.0, 1.0, m.thin_film_thickness));
}

// Reflectance of the film over a dielectric of index `substrate` (relative to the
// ambient), seen at `cos_1` from the ambient side.
fn thin_film_dielectric(m: Material, cos_1: f32, substrate: f32, film_ior: f32) -> vec3f {
    let eta2 = film_index(m, film_ior);
    let top = fresnel_polarised(cos_1, eta2);
    if top.total {
        return vec3f(1.0);
    }
    let bottom = fresnel_polarised(-top.cos_t, substrate / eta2);
    if bottom.total {
        return vec3f(1.0);
    }
    let opd = -2.0 * eta2 * m.thin_film_thickness * top.cos_t;
    let phasor_s = Phasor(vec3f(bottom.cos_phi.x * -top.cos_phi.x), vec3f(0.0));
    let phasor_p = Phasor(vec3f(bottom.cos_phi.y * -top.cos_phi.y), vec3f(0.0));
    let r_s = airy_summation(top.r.x, vec3f(bottom.r.x), opd, phasor_s);
    let r_p = airy_summation(top.r.y, vec3f(bottom.r.y), opd, phasor_p);
    return saturate(0.5 * (r_s + r_p));
}

// Cycles' F0 scaling of a filmed dielectric lobe (`microfacet_fresnel`, generalised
// Schlick): each channel scaled by f0 / F0 of the index, the more the closer it lies to
// that F0 than to 1.
fn thin_film_f0_scaled(f: vec3f, f0: vec3f, eta: f32) -> vec3f {
    let f0_real = fresnel_dielectric_f0(eta);
    if f0_real <= 1e-5 || all(f == vec3f(1.0)) {
        return f;
    }
    let s = saturate((f - vec3f(1.0)) / (f0_real - 1.0));
    return f * mix(vec3f(1.0), f0 / f0_real, s);
}

// The specular layer of a dielectric with a film (the diffuse's coating), at a microfacet.
fn thin_film_coating(m: Material, cos_i: f32) -> vec3f {
    let f = thin_film_dielectric(m, cos_i, m.coating_eta, m.thin_film_ior);
    return thin_film_f0_scaled(f, saturate(m.coating_f0 * m.specular_tint), m.coating_eta);
}

// The glass interface with a film, `eta` the far side's index over the viewer's: from
// inside, the film's index is taken relative to the glass (Cycles divides it by the IOR).
fn thin_film_glass(m: Material, cos_i: f32, eta: f32) -> vec3f {
    let film_ior = select(m.thin_film_ior / m.ior, m.thin_film_ior, eta == m.ior);
    let f = thin_film_dielectric(m, cos_i, eta, film_ior);
    return thin_film_f0_scaled(f, saturate(fresnel_dielectric_f0(m.ior) * m.specular_tint), eta);
}

// The reflectances of a conductor of index n + ik under a film of index `eta1` at `cos_i`
// inside the film, as F82 gives them (one value for both polarisations), with the phase
// shifts of both polarisations (Born & Wolf 14.4.1; Cycles' `fresnel_conductor_polarized`).
struct ConductorReflection {
    r: vec3f,
    phasor_s: Phasor,
    phasor_p: Phasor,
}

fn unit_phasor(re: vec3f, im: vec3f) -> Phasor {
    let mag = sqrt(re * re + im * im);
    let zero = mag == vec3f(0.0);
    return Phasor(select(re / mag, vec3f(1.0), zero), select(im / mag, vec3f(0.0), zero));
}

fn conductor_polarised(cos_i: f32, eta1: f32, n: vec3f, k: vec3f, f82: vec3f) -> ConductorReflection {
    let eta1_sq = eta1 * eta1;
    let n_sq = n * n;
    let k_sq = k * k;
    let two_nk = 2.0 * n * k;
    let t1 = n_sq - k_sq - eta1_sq * (1.0 - cos_i * cos_i);
    let t2 = sqrt(t1 * t1 + two_nk * two_nk);
    let u_sq = max(0.5 * (t2 + t1), vec3f(0.0));
    let v_sq = max(0.5 * (t2 - t1), vec3f(0.0));
    let u = sqrt(u_sq);
    let v = sqrt(v_sq);
    // F82 with n and k relative to the film.
    let nr = n / eta1;
    let kr_sq = k_sq / eta1_sq;
    let f0 = ((nr - 1.0) * (nr - 1.0) + kr_sq) / ((nr + 1.0) * (nr + 1.0) + kr_sq);
    let r = f82_fresnel(cos_i, f0, f82_b_of_value(f0, f82));
    let c = eta1 * cos_i;
    let phasor_s = unit_phasor(-u_sq - v_sq + c * c, -2.0 * c * v);
    let phasor_p = unit_phasor((n_sq + k_sq) * cos_i * (n_sq + k_sq) * cos_i - eta1_sq * (u_sq + v_sq), 2.0 * c * (two_nk * u - (n_sq - k_sq) * v));
    return ConductorReflection(r, phasor_s, phasor_p);
}

// F82's b for a given value at cos = 1/7 (Cycles' `fresnel_f82_B`).
fn f82_b_of_value(f0: vec3f, f82: vec3f) -> vec3f {
    let f = 6.0 / 7.0;
    let f5 = f * f * f * f * f;
    return (7.0 / (f5 * f)) * (mix(f0, vec3f(1.0), f5) - f82);
}

// The F82-tint metal (F0 `f0`, b `b`) under a film, at a microfacet: its n and k estimated
// from F0 and the value at 82° (Gulbrandsen's "Artist Friendly Metallic Fresnel"), as
// Cycles does.
fn thin_film_metal(m: Material, cos_1: f32, f0: vec3f, b: vec3f) -> vec3f {
    let r = min(f0, vec3f(0.999));
    let g = f82_fresnel(1.0 / 7.0, f0, b);
    let sqrt_r = sqrt(r);
    let n = mix((1.0 + sqrt_r) / (1.0 - sqrt_r), (1.0 - r) / (1.0 + r), g);
    let k = sqrt(max((r * (n + 1.0) * (n + 1.0) - (n - 1.0) * (n - 1.0)) / (1.0 - r), vec3f(0.0)));
    let eta2 = film_index(m, m.thin_film_ior);
    let top = fresnel_polarised(cos_1, eta2);
    if top.total {
        return vec3f(1.0);
    }
    let bottom = conductor_polarised(-top.cos_t, eta2, n, k, g);
    let opd = -2.0 * eta2 * m.thin_film_thickness * top.cos_t;
    let r_s = airy_summation(top.r.x, bottom.r, opd, phasor_scale(bottom.phasor_s, -top.cos_phi.x));
    let r_p = airy_summation(top.r.y, bottom.r, opd, phasor_scale(bottom.phasor_p, -top.cos_phi.y));
    return saturate(0.5 * (r_s + r_p));
}

fn phasor_scale(p: Phasor, s: f32) -> Phasor {
    return Phasor(p.re * s, p.im * s);
}
