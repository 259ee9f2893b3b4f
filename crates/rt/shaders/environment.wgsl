// `[sky] kind = "environment"`: an equirectangular image around the scene, looked up
// as Cycles' Environment Texture (Linear interpolation) reads it, and light-sampled
// from a piecewise-constant distribution over its texels (src/sky/environment.rs
// builds it): a row from the marginal, a column from that row's conditional.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "rng.wgsl"
//#include "srgb.wgsl"

// Environment: declared in src/layout.rs (GpuEnvironment).
//#include "Environment.struct.wgsl"

@group(2) @binding(0) var<uniform> environment: Environment;
// width × height texels: rgb, and in w the row's cumulative probability up to the
// texel; then the rows' cumulative probabilities, four to an entry.
@group(2) @binding(1) var<storage, read> environment_data: array<vec4f>;

// The direction in the image's frame (Blender's axes, Z up), rotated by the Mapping node.
fn environment_to_image(d: vec3f) -> vec3f {
    return vec3f(dot(environment.to_image_x, d), dot(environment.to_image_y, d), dot(environment.to_image_z, d));
}

// Cycles' direction_to_equirectangular: u = 0.5 − atan2(y, x) / 2π (the image's centre
// faces +X); returned as (u, t) with t = θ / π from the top row (+Z) down.
fn environment_uv(d: vec3f) -> vec2f {
    let b = environment_to_image(d);
    return vec2f(0.5 - atan2(b.y, b.x) / (2.0 * PI), acos(clamp(b.z / length(b), -1.0, 1.0)) / PI);
}

fn environment_direction(uv: vec2f) -> vec3f {
    let phi = (0.5 - uv.x) * 2.0 * PI;
    let theta = uv.y * PI;
    let b = vec3f(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
    return b.x * environment.to_image_x + b.y * environment.to_image_y + b.z * environment.to_image_z;
}

fn environment_texel(x: u32, y: u32) -> vec3f {
    return environment_data[y * environment.width + x].rgb;
}

// Bilinear between texel centres, wrapping around in u and clamped at the poles.
fn environment_radiance(d: vec3f) -> vec3f {
    let uv = environment_uv(d);
    let w = environment.width;
    let h = environment.height;
    let p = uv * vec2f(f32(w), f32(h)) - 0.5;
    let base = floor(p);
    let f = p - base;
    let x0 = u32(i32(base.x) + i32(w)) % w;
    let x1 = (x0 + 1u) % w;
    let y0 = u32(clamp(i32(base.y), 0, i32(h) - 1));
    let y1 = u32(clamp(i32(base.y) + 1, 0, i32(h) - 1));
    // a + (b − a) f rather than mix(): exact where neighbouring texels are equal.
    let t00 = environment_texel(x0, y0);
    let t01 = environment_texel(x0, y1);
    let top = t00 + (environment_texel(x1, y0) - t00) * f.x;
    let bottom = t01 + (environment_texel(x1, y1) - t01) * f.x;
    var radiance = top + (bottom - top) * f.y;
    if environment.srgb != 0u {
        radiance = srgb_to_linear(radiance);
    }
    return radiance * environment.strength;
}

// Cumulative probability of rows 0..=y.
fn environment_marginal(y: u32) -> f32 {
    return environment_data[environment.width * environment.height + y / 4u][y % 4u];
}

// Cumulative probability of columns 0..=x in row y.
fn environment_conditional(x: u32, y: u32) -> f32 {
    return environment_data[y * environment.width + x].w;
}

// Solid-angle density of a light sample in direction d.
fn environment_pdf(d: vec3f) -> f32 {
    if environment.importance == 0u {
        return 1.0 / (4.0 * PI);
    }
    let uv = environment_uv(d);
    let w = environment.width;
    let h = environment.height;
    let x = min(u32(uv.x * f32(w)), w - 1u);
    let y = min(u32(uv.y * f32(h)), h - 1u);
    var row = environment_marginal(y);
    if y > 0u {
        row -= environment_marginal(y - 1u);
    }
    var column = environment_conditional(x, y);
    if x > 0u {
        column -= environment_conditional(x - 1u, y);
    }
    let sin_theta = sin(uv.y * PI);
    if sin_theta <= 0.0 {
        return 0.0;
    }
    return max(row * column, 0.0) * f32(w) * f32(h) / (2.0 * PI * PI * sin_theta);
}

// The first row whose cumulative probability exceeds u, and the fraction of the way through it.
fn environment_pick_row(u: f32) -> vec2f {
    var lo = 0u;
    var hi = environment.height - 1u;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        if environment_marginal(mid) > u {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    var below = 0.0;
    if lo > 0u {
        below = environment_marginal(lo - 1u);
    }
    let width = environment_marginal(lo) - below;
    return vec2f(f32(lo), clamp((u - below) / max(width, 1e-30), 0.0, 0.999999));
}

fn environment_pick_column(y: u32, u: f32) -> vec2f {
    var lo = 0u;
    var hi = environment.width - 1u;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        if environment_conditional(mid, y) > u {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    var below = 0.0;
    if lo > 0u {
        below = environment_conditional(lo - 1u, y);
    }
    let width = environment_conditional(lo, y) - below;
    return vec2f(f32(lo), clamp((u - below) / max(width, 1e-30), 0.0, 0.999999));
}

// A direction towards the environment, with its radiance and density (selection excluded).
struct EnvironmentSample {
    direction: vec3f,
    radiance: vec3f,
    pdf: f32,
}

fn sample_environment(rng: ptr<function, Rng>) -> EnvironmentSample {
    let u = rng_next2(rng);
    var d: vec3f;
    if environment.importance == 0u {
        let z = 1.0 - 2.0 * u.x;
        let r = sqrt(max(0.0, 1.0 - z * z));
        let phi = 2.0 * PI * u.y;
        d = vec3f(r * cos(phi), r * sin(phi), z);
    } else {
        let row = environment_pick_row(u.y);
        let column = environment_pick_column(u32(row.x), u.x);
        let uv = vec2f((column.x + column.y) / f32(environment.width), (row.x + row.y) / f32(environment.height));
        d = environment_direction(uv);
    }
    return EnvironmentSample(d, environment_radiance(d), environment_pdf(d));
}
