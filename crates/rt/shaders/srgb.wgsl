// sRGB codes decoded to linear, as Cycles' `color_srgb_to_linear` decodes them (codes
// above 1 follow the same power; below 0, nothing): textures' and environments' codes are
// filtered first and decoded after, as Cycles filters them. `scene::srgb_decode` is the
// host's.

fn srgb_to_linear(c: vec3f) -> vec3f {
    return select(pow((c + 0.055) / 1.055, vec3f(2.4)), max(c, vec3f(0.0)) / 12.92, c <= vec3f(0.04045));
}
