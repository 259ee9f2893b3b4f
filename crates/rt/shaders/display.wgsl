// The viewer's display pass: the running mean of the accumulation, exposed, tone-mapped
// with Khronos PBR Neutral and sRGB-encoded. The same arithmetic as src/render/tonemap.rs,
// so that the window shows what `rt render` writes to a PNG.

struct Display {
    width: u32,
    height: u32,
    samples: u32,
    // 2^EV.
    exposure_scale: f32,
    // 0 when the target's format encodes sRGB itself.
    encode_srgb: u32,
    // 1 while the last reload failed: a red frame around the (last good) image.
    error: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> display: Display;
// Per pixel: the running mean of RGB and the luminance's sum of squared deviations,
// rows from the top (as the integrator writes them).
@group(0) @binding(1) var<storage, read> means: array<vec4f>;

const ERROR_FRAME_PIXELS: u32 = 4u;

@vertex
fn vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
    // One triangle that covers the target.
    let corner = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4f(corner * 2.0 - 1.0, 0.0, 1.0);
}

fn pbr_neutral(color: vec3f) -> vec3f {
    let start_compression = 0.8 - 0.04;
    let desaturation = 0.15;
    let x = min(color.r, min(color.g, color.b));
    let offset = select(0.04, x - 6.25 * x * x, x < 0.08);
    let c = color - offset;
    let peak = max(c.r, max(c.g, c.b));
    if peak < start_compression {
        return c;
    }
    let d = 1.0 - start_compression;
    let new_peak = 1.0 - d * d / (peak + d - start_compression);
    let scaled = c * new_peak / peak;
    let g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    return scaled + (new_peak - scaled) * g;
}

fn srgb_encode(linear: f32) -> f32 {
    let l = clamp(linear, 0.0, 1.0);
    return select(1.055 * pow(l, 1.0 / 2.4) - 0.055, 12.92 * l, l <= 0.0031308);
}

@fragment
fn fragment(@builtin(position) position: vec4f) -> @location(0) vec4f {
    let x = u32(position.x);
    let y = u32(position.y);
    let in_frame = x < ERROR_FRAME_PIXELS || y < ERROR_FRAME_PIXELS
        || x + ERROR_FRAME_PIXELS >= display.width || y + ERROR_FRAME_PIXELS >= display.height;
    if display.error != 0u && in_frame {
        return vec4f(0.9, 0.05, 0.05, 1.0);
    }
    if x >= display.width || y >= display.height || display.samples == 0u {
        return vec4f(0.0, 0.0, 0.0, 1.0);
    }
    let mean = means[y * display.width + x].rgb;
    let mapped = pbr_neutral(max(mean, vec3f(0.0)) * display.exposure_scale);
    if display.encode_srgb == 0u {
        return vec4f(mapped, 1.0);
    }
    return vec4f(srgb_encode(mapped.r), srgb_encode(mapped.g), srgb_encode(mapped.b), 1.0);
}
