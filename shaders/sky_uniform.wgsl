fn sky_radiance(direction: vec3f) -> vec3f {
    return frame.sky_color;
}
