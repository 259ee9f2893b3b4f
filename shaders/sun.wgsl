// The sun: a disk of uniform radiance seen under a small solid angle
// 2π(1 − cos θ), with θ its angular radius.

fn sun_solid_angle() -> f32 {
    return 2.0 * PI * frame.sun_one_minus_cos;
}

// Tested on the chord |w − s|² = 2(1 − cos), which keeps its digits for tiny angles.
fn in_sun_disk(w: vec3f) -> bool {
    let d = w - frame.sun_direction;
    return dot(d, d) <= 2.0 * frame.sun_one_minus_cos;
}

fn sun_direction_pdf(w: vec3f) -> f32 {
    return select(0.0, 1.0 / sun_solid_angle(), in_sun_disk(w));
}

// Uniform over the disk's cone.
fn sample_sun_direction(u: vec2f) -> vec3f {
    let one_minus_cos = u.x * frame.sun_one_minus_cos;
    let cos_t = 1.0 - one_minus_cos;
    let sin_t = sqrt(max(0.0, one_minus_cos * (2.0 - one_minus_cos)));
    let phi = 2.0 * PI * u.y;
    return tangent_frame(frame.sun_direction) * vec3f(sin_t * cos(phi), sin_t * sin(phi), cos_t);
}

// Radiance of the disk reaching `position` along a ray towards it.
fn sun_radiance_at(position: vec3f, direction: vec3f) -> vec3f {
    //#if sky_atmosphere
    return frame.sun_radiance * atmosphere_transmittance_to_space(position, direction);
    //#else
    return frame.sun_radiance;
    //#endif
}
