fn surface_emission(m: Material) -> vec3f {
    return vec3f(0.0);
}
