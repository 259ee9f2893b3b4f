// Blender's Noise Texture of 1 to 4 dimensions, bit for bit the pattern Cycles makes: the
// fractal sums of kernel/svm/fractal_noise.h over node_perlin.wgsl's noise, and the
// distortion and colour offsets of kernel/svm/noisetex.h (Apache-2.0, Blender Foundation);
// and the Wave and Magic textures, which are made of the same noise and sines.
//
// A point of d dimensions is a vec4f whose first d components are used (1D: x is W).

//#include "node_perlin.wgsl"

// Cycles' random_float_offset … random_float4_offset: the offset in [100, 200] of each used
// component that seeds the noise of component or colour `seed`.
fn noise_offset(seed: f32, dimensions: u32) -> vec4f {
    if dimensions == 1u {
        return vec4f(100.0 + hash_float_to_float(seed) * 100.0, 0.0, 0.0, 0.0);
    }
    var offset = vec4f(0.0);
    for (var i = 0u; i < dimensions; i++) {
        offset[i] = 100.0 + hash_float2_to_float(vec2f(seed, f32(i))) * 100.0;
    }
    return offset;
}

// Blender's Wave Texture (Cycles' svm_wave): `mode` = type (0 bands, 1 rings) | direction
// << 1 | profile (0 sine, 1 saw, 2 triangle) << 4; `co` already scaled.
fn node_wave(mode: u32, co: vec3f, distortion: f32, detail: f32, detail_scale: f32, detail_roughness: f32, phase: f32) -> f32 {
    let p = (co + 0.000001) * 0.999999;
    let direction = (mode >> 1u) & 7u;
    var n: f32;
    if (mode & 1u) == 0u {
        switch direction {
            case 0u: { n = p.x * 20.0; }
            case 1u: { n = p.y * 20.0; }
            case 2u: { n = p.z * 20.0; }
            default: { n = (p.x + p.y + p.z) * 10.0; }
        }
    } else {
        var keep = vec3f(1.0);
        if direction < 3u {
            keep[direction] = 0.0;
        }
        n = length(p * keep) * 20.0;
    }
    n += phase;
    if distortion != 0.0 {
        n += distortion * (noise_select(vec4f(p * detail_scale, 0.0), NoiseSettings(detail, detail_roughness, 2.0, 0.0, 0.0, 0u, true, 3u)) * 2.0 - 1.0);
    }
    switch mode >> 4u {
        case 1u: {
            let t = n / (2.0 * PI);
            return t - floor(t);
        }
        case 2u: {
            let t = n / (2.0 * PI);
            return abs(t - floor(t + 0.5)) * 2.0;
        }
        default: { return 0.5 + 0.5 * sin(n - 0.5 * PI); }
    }
}
struct NoiseSettings {
    detail: f32,
    roughness: f32,
    lacunarity: f32,
    offset: f32,
    gain: f32,
    // NOISE_TYPES' index in src/asset/node_kinds.rs: fBM, Multifractal, Hybrid and Ridged
    // Multifractal, Hetero Terrain.
    kind: u32,
    normalize: bool,
    // 1 to 4.
    dimensions: u32,
}

// A fractal's running sums (kernel/svm/fractal_noise.h names).
struct Fractal {
    p: vec4f,
    fscale: f32,
    amp: f32,
    maxamp: f32,
    sum: f32,
    sum2: f32,
    value: f32,
    pwr: f32,
    weight: f32,
    signal: f32,
}

// The five fractal sums of Cycles' fractal_noise.h in one loop, so that a Noise Texture's
// code holds one noise call, whatever its type and dimensions: octave i of 0 ..= detail,
// then the fractional remainder, each type updating its sums as Cycles' loop does
// (bit for bit: the same operations in the same order).
fn noise_select(p0: vec4f, s: NoiseSettings) -> f32 {
    let n = i32(s.detail);
    let rmd = s.detail - floor(s.detail);
    let ridged = s.kind == 3u;
    let first_pwr = select(1.0, s.roughness, ridged || s.kind == 4u);
    var f = Fractal(p0, 1.0, 1.0, 0.0, 0.0, 0.0, select(0.0, 1.0, s.kind == 1u), first_pwr, 1.0, 0.0);
    let last = select(n, n + 1, rmd != 0.0 && !ridged);
    for (var i = 0; i <= last; i++) {
        if s.kind == 2u && !(f.weight > 0.001) {
            break;
        }
        if ridged && i > 0 {
            f.p *= s.lacunarity;
        }
        let noise = snoise(select(f.p, f.fscale * p0, s.kind == 0u), s.dimensions);
        f = fractal_octave(f, s, noise, i, i > n, rmd);
    }
    switch s.kind {
        case 0u: {
            if rmd != 0.0 {
                if s.normalize {
                    return mix(0.5 * f.sum / f.maxamp + 0.5, 0.5 * f.sum2 / (f.maxamp + f.amp) + 0.5, rmd);
                }
                return mix(f.sum, f.sum2, rmd);
            }
            return select(f.sum, 0.5 * f.sum / f.maxamp + 0.5, s.normalize);
        }
        default: {
            return f.value;
        }
    }
}

// Octave `i` of the sums with its `noise`, or the `remainder`, weighted by `rmd`.
fn fractal_octave(f_in: Fractal, s: NoiseSettings, noise: f32, i: i32, remainder: bool, rmd: f32) -> Fractal {
    var f = f_in;
    switch s.kind {
        case 0u: {
            if remainder {
                f.sum2 = f.sum + noise * f.amp;
            } else {
                f.sum += noise * f.amp;
                f.maxamp += f.amp;
                f.amp *= s.roughness;
                f.fscale *= s.lacunarity;
            }
        }
        case 1u: {
            if remainder {
                f.value *= rmd * f.pwr * noise + 1.0;
            } else {
                f.value *= f.pwr * noise + 1.0;
                f.pwr *= s.roughness;
                f.p *= s.lacunarity;
            }
        }
        case 2u: {
            if remainder {
                f.value += rmd * min(f.weight, 1.0) * (noise + s.offset) * f.pwr;
            } else {
                f.weight = min(f.weight, 1.0);
                let signal = (noise + s.offset) * f.pwr;
                f.pwr *= s.roughness;
                f.value += f.weight * signal;
                f.weight *= s.gain * signal;
                f.p *= s.lacunarity;
            }
        }
        case 3u: {
            if i == 0 {
                f.signal = s.offset - abs(noise);
                f.signal *= f.signal;
                f.value = f.signal;
            } else {
                let weight = clamp(f.signal * s.gain, 0.0, 1.0);
                f.signal = s.offset - abs(noise);
                f.signal *= f.signal * weight;
                f.value += f.signal * f.pwr;
                f.pwr *= s.roughness;
            }
        }
        default: {
            if i == 0 {
                f.value = s.offset + noise;
            } else if remainder {
                f.value += rmd * (noise + s.offset) * f.pwr * f.value;
            } else {
                f.value += (noise + s.offset) * f.pwr * f.value;
                f.pwr *= s.roughness;
            }
            if !remainder {
                f.p *= s.lacunarity;
            }
        }
    }
    return f;
}

// The Noise Texture's Fac (w) and Color (xyz) at `co`, already scaled: each used component
// distorted by noise seeded 0, 1, …; the colour's green and blue seeded by the next two.
fn noise_texture(co: vec4f, distortion: f32, s: NoiseSettings) -> vec4f {
    let d = s.dimensions;
    var p = co;
    if distortion != 0.0 {
        var shift = vec4f(0.0);
        for (var i = 0u; i < d; i++) {
            shift[i] = snoise(p + noise_offset(f32(i), d), d) * distortion;
        }
        p += shift;
    }
    var colour = vec3f(0.0);
    for (var k = 0u; k < 3u; k++) {
        let offset = select(vec4f(0.0), noise_offset(f32(d + k - 1u), d), k > 0u);
        colour[k] = noise_select(p + offset, s);
    }
    return vec4f(colour, colour.x);
}

// Cycles' Magic Texture (svm_magic.h): `depth` rounds of sines and cosines of the point,
// each scaled by the distortion; the colour is 0.5 minus the last (x, y, z) over twice it.
fn node_magic(p: vec3f, depth: i32, distortion: f32) -> vec3f {
    var x = sin((p.x + p.y + p.z) * 5.0);
    var y = cos((-p.x + p.y - p.z) * 5.0);
    var z = -cos((-p.x - p.y + p.z) * 5.0);
    // Cycles nests each round in the one before; depth > k implies depth > k − 1, so the
    // rounds run in turn.
    if depth > 0 {
        x *= distortion;
        y *= distortion;
        z *= distortion;
        y = -cos(x - y + z) * distortion;
    }
    if depth > 1 {
        x = cos(x - y - z) * distortion;
    }
    if depth > 2 {
        z = sin(-x - y - z) * distortion;
    }
    if depth > 3 {
        x = -cos(-x + y - z) * distortion;
    }
    if depth > 4 {
        y = -sin(-x + y + z) * distortion;
    }
    if depth > 5 {
        y = -cos(-x + y + z) * distortion;
    }
    if depth > 6 {
        x = cos(x + y + z) * distortion;
    }
    if depth > 7 {
        z = sin(x + y - z) * distortion;
    }
    if depth > 8 {
        x = -cos(-x - y + z) * distortion;
    }
    if depth > 9 {
        y = -sin(x - y + z) * distortion;
    }
    if distortion != 0.0 {
        let d = distortion * 2.0;
        x /= d;
        y /= d;
        z /= d;
    }
    return vec3f(0.5 - x, 0.5 - y, 0.5 - z);
}

