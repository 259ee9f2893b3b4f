// A shading normal that keeps a glossy lobe's mirror direction above the surface.

// Cycles' `ensure_valid_specular_reflection` (Schüßler et al., "Microfacet-based Normal
// Mapping for Robust Monte Carlo Path Tracing", 2017): a normal that would mirror the
// viewer's direction below the surface is tilted towards the geometric normal `ng` (on
// the viewer's side) until the mirrored direction clears it by min(0.9 cos θ_o, 0.01).
// Blender applies it to the glossy, metal, glass and coat lobes' normals, mapped or
// interpolated, under the material's Bump Map Correction (on by default).
fn valid_for_reflection(n: vec3f, ng: vec3f, wo: vec3f) -> vec3f {
    let r = 2.0 * dot(n, wo) * n - wo;
    let iz = dot(wo, ng);
    let threshold = min(0.9 * iz, 0.01);
    if dot(ng, r) >= threshold {
        return n;
    }
    let tangential = n - dot(n, ng) * ng;
    let tangential_length = length(tangential);
    if !(tangential_length > 0.0) || iz <= 0.0 {
        return n;
    }
    let x = tangential / tangential_length;
    let ix = dot(wo, x);
    let a = ix * ix + iz * iz;
    let b = 2.0 * (a + iz * threshold);
    let c = (threshold + iz) * (threshold + iz);
    let root = sqrt(max(b * b - 4.0 * a * c, 0.0));
    let nz2 = select(0.25 * (b - root) / a, 0.25 * (b + root) / a, ix < 0.0);
    return sqrt(max(1.0 - nz2, 0.0)) * x + sqrt(max(nz2, 0.0)) * ng;
}
