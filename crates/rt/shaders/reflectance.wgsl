// A dielectric's reflectance at normal incidence and the index it comes from (Cycles'
// `F0_from_ior` and `ior_from_F0`).

// Reflectance of a dielectric of relative index `eta` at normal incidence.
fn fresnel_dielectric_f0(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    return r * r;
}

// The relative index (above 1) whose reflectance at normal incidence is `f0` (below 1).
fn ior_from_f0(f0: f32) -> f32 {
    let r = sqrt(f0);
    return (1.0 + r) / (1.0 - r);
}
