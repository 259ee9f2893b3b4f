// The sun: a disk of uniform radiance seen under a small solid angle
// 2π(1 − cos θ), with θ its angular radius.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "directions.wgsl"
//#if sky_atmosphere
//#include "atmosphere_sky.wgsl"
//#endif

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
    return frame.sun_radiance * sun_limb_darkening(direction) * atmosphere_transmittance_to_space(position, direction);
    //#else
    return frame.sun_radiance;
    //#endif
}

//#if sky_atmosphere
// The real sun's disk darkens towards its limb, I ∝ μ^α with μ the cosine on the
// solar surface (Hestroffer & Magnan 1998), redder at the limb; normalised by
// (α + 2) / 2 so that the disk's mean radiance, hence its irradiance, stays
// `frame.sun_radiance`. The plain skies keep a uniform disk.
fn sun_limb_darkening(w: vec3f) -> vec3f {
    let d = w - frame.sun_direction;
    let chord2 = dot(d, d);
    // sin² of the angle from the centre, and of the disk's angular radius.
    let sin2_off = chord2 * (1.0 - 0.25 * chord2);
    let sin2_radius = frame.sun_one_minus_cos * (2.0 - frame.sun_one_minus_cos);
    let mu = sqrt(max(1.0 - sin2_off / sin2_radius, 1e-6));
    let alpha = vec3f(0.397, 0.503, 0.652);
    return pow(vec3f(mu), alpha) * (alpha + 2.0) * 0.5;
}
//#endif
