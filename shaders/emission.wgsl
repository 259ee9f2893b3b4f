// Surface emission is two-sided: an emissive surface glows from both faces.
fn surface_emission(m: Material) -> vec3f {
    return m.emission;
}
