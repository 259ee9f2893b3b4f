fn sky_radiance(direction: vec3f) -> vec3f {
    return vec3f(0.0);
}
