// Scattering at a surface. Lobes are weighted by the material and normalised so
// that a material never reflects more than it receives.

struct BsdfSample {
    direction: vec3f,
    // f·cos/pdf: the factor the path throughput is multiplied by.
    weight: vec3f,
    valid: bool,
}

// An orthonormal basis around n (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
fn tangent_frame(n: vec3f) -> mat3x3f {
    let s = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    let t = vec3f(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    let bt = vec3f(b, s + n.y * n.y * a, -n.y);
    return mat3x3f(t, bt, n);
}

fn lobe_weight_sum(m: Material) -> f32 {
    return max(m.diffuse + m.specular + m.reflection + m.transmission, 1.0);
}

fn sample_cosine_hemisphere(u: vec2f) -> vec3f {
    let r = sqrt(u.x);
    let phi = 2.0 * PI * u.y;
    return vec3f(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
}

// `n_shading` and `n_geometric` both face the side the ray arrived from.
fn sample_bsdf(m: Material, n_shading: vec3f, n_geometric: vec3f, rng: ptr<function, Rng>) -> BsdfSample {
    let albedo = m.base_color * (m.diffuse / lobe_weight_sum(m));
    let u = vec2f(rng_next(rng), rng_next(rng));
    var direction = tangent_frame(n_shading) * sample_cosine_hemisphere(u);
    // An interpolated shading normal can send a reflected ray under the true
    // surface, where it would leak through. Ending the path there loses energy
    // (a white furnace turns grey); mirroring the ray about the true surface
    // keeps every sample's weight, so reflectance stays exactly the albedo.
    let below = dot(direction, n_geometric);
    if below <= 0.0 {
        direction = normalize(direction - 2.0 * below * n_geometric);
    }
    return BsdfSample(direction, albedo, any(albedo > vec3f(0.0)));
}
