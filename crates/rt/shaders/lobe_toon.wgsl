// Blender's Toon BSDF as Cycles renders it (`kernel/closure/bsdf_toon.h`), a lobe module
// declared in src/scene/lobe/toon.rs: its parameters are read by `toon_size`,
// `toon_smooth` and `toon_component`, made from that declaration. Light within a cone
// about the normal (Diffuse) or about the view's mirror direction (Glossy) is reflected
// at full intensity up to Size × 90° from the axis, fading linearly to nothing over a
// further Smooth × 90°. Its value (f·cos) is the cone's uniform density times that
// intensity, so a sample drawn uniformly in the cone weighs its intensity. Directions are
// local to the shading normal (z), the viewer above it.

//#include "constants.wgsl"
//#include "directions.wgsl"

// The half angle of full intensity, of the fade after it, and of the cone sampled (at
// most 90°), in radians.
fn toon_angles(m: Material) -> vec3f {
    let full = toon_size(m) * (0.5 * PI);
    let fade = toon_smooth(m) * (0.5 * PI);
    return vec3f(full, fade, min(full + fade, 0.5 * PI));
}

fn toon_intensity(angles: vec3f, angle: f32) -> f32 {
    if angle < angles.x {
        return 1.0;
    }
    if angle < angles.x + angles.y && angles.y != 0.0 {
        return 1.0 - (angle - angles.x) / angles.y;
    }
    return 0.0;
}

fn toon_is_glossy(m: Material) -> bool {
    return toon_component(m) == TOON_COMPONENT_GLOSSY;
}

// The cone's axis: the normal, or the view mirrored about it.
fn toon_axis(ctx: ShadingContext) -> vec3f {
    if toon_is_glossy(ctx.m) {
        return vec3f(-ctx.wo.x, -ctx.wo.y, ctx.wo.z);
    }
    return vec3f(0.0, 0.0, 1.0);
}

// The uniform density of the cone of half angle θ: 1 / (2π (1 − cos θ)), with 1 − cos θ
// as 2 sin²(θ/2), which keeps its digits for narrow cones.
fn toon_cone_pdf(angles: vec3f) -> f32 {
    let s = sin(0.5 * angles.z);
    return 1.0 / (4.0 * PI * s * s);
}

fn toon_pdf(ctx: ShadingContext, wi: vec3f) -> f32 {
    let angles = toon_angles(ctx.m);
    if wi.z < 0.0 || (toon_is_glossy(ctx.m) && wi.z == 0.0) {
        return 0.0;
    }
    let angle = acos(clamp(dot(toon_axis(ctx), wi), 0.0, 1.0));
    return select(0.0, toon_cone_pdf(angles), angle < angles.z);
}

// f·|cos θi| per unit colour.
fn toon_eval(ctx: ShadingContext, wi: vec3f) -> vec3f {
    let pdf = toon_pdf(ctx, wi);
    if pdf == 0.0 {
        return vec3f(0.0);
    }
    let angle = acos(clamp(dot(toon_axis(ctx), wi), 0.0, 1.0));
    return vec3f(pdf * toon_intensity(toon_angles(ctx.m), angle));
}

// A direction uniform in the cone; Cycles drops one below the geometric surface (and,
// for Glossy, below the shading normal).
fn toon_sample(ctx: ShadingContext, u: vec2f) -> BsdfSample {
    let angles = toon_angles(ctx.m);
    let s = sin(0.5 * angles.z);
    let cos_theta = 1.0 - u.x * 2.0 * s * s;
    let sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
    let phi = 2.0 * PI * u.y;
    let wi = tangent_frame(toon_axis(ctx)) * vec3f(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
    let glossy = toon_is_glossy(ctx.m);
    if dot(ctx.n_geometric, wi) <= 0.0 || (glossy && wi.z <= 0.0) {
        return invalid_sample();
    }
    let weight = vec3f(toon_intensity(angles, acos(clamp(cos_theta, -1.0, 1.0))));
    return BsdfSample(wi, weight, toon_cone_pdf(angles), true, false, select(LOBE_DIFFUSE, LOBE_SPECULAR, glossy));
}
