// Blender's Noise Texture, bit for bit the pattern Cycles makes: Bob Jenkins' lookup3
// hash of the lattice point (Cycles' util/hash.h), Perlin's improved gradient noise with
// the gradients and scale Cycles takes from Open Shading Language (kernel/svm/noise.h),
// the fractal sums of kernel/svm/fractal_noise.h and the distortion and colour offsets of
// kernel/svm/noisetex.h (all Apache-2.0 or BSD-3-Clause, Blender Foundation and Sony
// Pictures Imageworks).

fn hash_rotate(x: u32, k: u32) -> u32 {
    return (x << k) | (x >> (32u - k));
}

// lookup3's `final` mix of (a, b, c); returns c.
fn hash_final(a_in: u32, b_in: u32, c_in: u32) -> u32 {
    var a = a_in;
    var b = b_in;
    var c = c_in;
    c ^= b;
    c -= hash_rotate(b, 14u);
    a ^= c;
    a -= hash_rotate(c, 11u);
    b ^= a;
    b -= hash_rotate(a, 25u);
    c ^= b;
    c -= hash_rotate(b, 16u);
    a ^= c;
    a -= hash_rotate(c, 4u);
    b ^= a;
    b -= hash_rotate(a, 14u);
    c ^= b;
    c -= hash_rotate(b, 24u);
    return c;
}

fn hash_uint2(kx: u32, ky: u32) -> u32 {
    let seed = 0xdeadbeefu + (2u << 2u) + 13u;
    return hash_final(seed + kx, seed + ky, seed);
}

fn hash_uint3(kx: u32, ky: u32, kz: u32) -> u32 {
    let seed = 0xdeadbeefu + (3u << 2u) + 13u;
    return hash_final(seed + kx, seed + ky, seed + kz);
}

// lookup3's `mix` of (a, b, c).
fn hash_mix(a_in: u32, b_in: u32, c_in: u32) -> vec3u {
    var a = a_in;
    var b = b_in;
    var c = c_in;
    a -= c;
    a ^= hash_rotate(c, 4u);
    c += b;
    b -= a;
    b ^= hash_rotate(a, 6u);
    a += c;
    c -= b;
    c ^= hash_rotate(b, 8u);
    b += a;
    a -= c;
    a ^= hash_rotate(c, 16u);
    c += b;
    b -= a;
    b ^= hash_rotate(a, 19u);
    a += c;
    c -= b;
    c ^= hash_rotate(b, 4u);
    b += a;
    return vec3u(a, b, c);
}

fn hash_uint4(kx: u32, ky: u32, kz: u32, kw: u32) -> u32 {
    let seed = 0xdeadbeefu + (4u << 2u) + 13u;
    let m = hash_mix(seed + kx, seed + ky, seed + kz);
    return hash_final(m.x + kw, m.y, m.z);
}

fn hash_to_unit(h: u32) -> f32 {
    return f32(h) * (1.0 / 4294967296.0);
}

fn hash_uint1(kx: u32) -> u32 {
    let seed = 0xdeadbeefu + (1u << 2u) + 13u;
    return hash_final(seed + kx, seed, seed);
}

fn hash_float_to_float(k: f32) -> f32 {
    return hash_to_unit(hash_uint1(bitcast<u32>(k)));
}

fn hash_float4_to_float(k: vec4f) -> f32 {
    let b = bitcast<vec4u>(k);
    return hash_to_unit(hash_uint4(b.x, b.y, b.z, b.w));
}

// The White Noise Texture of `dimensions` (0 to 3: 1D of `w`, 2D of `v.xy`, 3D of `v`, 4D
// of both) as Cycles hashes it (svm/white_noise.h, util/hash.h): the colour, the value in w.
fn white_noise(dimensions: u32, v: vec3f, w: f32) -> vec4f {
    switch dimensions {
        case 0u: {
            let value = hash_float_to_float(w);
            return vec4f(value, hash_float2_to_float(vec2f(w, 1.0)), hash_float2_to_float(vec2f(w, 2.0)), value);
        }
        case 1u: {
            let value = hash_float2_to_float(v.xy);
            return vec4f(value, hash_float3_to_float(vec3f(v.xy, 1.0)), hash_float3_to_float(vec3f(v.xy, 2.0)), value);
        }
        case 3u: {
            let k = vec4f(v, w);
            let value = hash_float4_to_float(k);
            return vec4f(value, hash_float4_to_float(k.zxwy), hash_float4_to_float(k.wzyx), value);
        }
        default: {
            return vec4f(hash_float3_to_float3(v), hash_float3_to_float(v));
        }
    }
}

// Cycles' hash_float3_to_float and hash_float3_to_float3.
fn hash_float3_to_float(k: vec3f) -> f32 {
    let b = bitcast<vec3u>(k);
    return hash_to_unit(hash_uint3(b.x, b.y, b.z));
}

fn hash_float3_to_float3(k: vec3f) -> vec3f {
    let b = bitcast<vec3u>(k);
    return vec3f(
        hash_to_unit(hash_uint3(b.x, b.y, b.z)),
        hash_to_unit(hash_uint4(b.x, b.y, b.z, bitcast<u32>(1.0))),
        hash_to_unit(hash_uint4(b.x, b.y, b.z, bitcast<u32>(2.0))),
    );
}

// Cycles' hash_float2_to_float: [0, 1].
fn hash_float2_to_float(k: vec2f) -> f32 {
    return f32(hash_uint2(bitcast<u32>(k.x), bitcast<u32>(k.y))) * (1.0 / 4294967296.0);
}

// The offset in [100, 200] that seeds the noise of component `seed` (noisetex.h).
fn noise_offset3(seed: f32) -> vec3f {
    return 100.0 + 100.0 * vec3f(
        hash_float2_to_float(vec2f(seed, 0.0)),
        hash_float2_to_float(vec2f(seed, 1.0)),
        hash_float2_to_float(vec2f(seed, 2.0)),
    );
}

fn noise_fade(t: f32) -> f32 {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

fn negate_if(v: f32, condition: u32) -> f32 {
    return select(v, -v, condition != 0u);
}

fn noise_grad3(hash: u32, x: f32, y: f32, z: f32) -> f32 {
    let h = hash & 15u;
    let u = select(y, x, h < 8u);
    let vt = select(z, x, h == 12u || h == 14u);
    let v = select(vt, y, h < 4u);
    return negate_if(u, h & 1u) + negate_if(v, h & 2u);
}

fn noise_corner(i: vec3i, f: vec3f, corner: vec3i) -> f32 {
    let c = bitcast<vec3u>(i + corner);
    let d = f - vec3f(corner);
    return noise_grad3(hash_uint3(c.x, c.y, c.z), d.x, d.y, d.z);
}

fn perlin_3d(p: vec3f) -> f32 {
    let fl = floor(p);
    let i = vec3i(fl);
    let f = p - fl;
    let u = noise_fade(f.x);
    let v = noise_fade(f.y);
    let w = noise_fade(f.z);
    let x1 = 1.0 - u;
    let y1 = 1.0 - v;
    let z1 = 1.0 - w;
    let v0 = noise_corner(i, f, vec3i(0, 0, 0));
    let v1 = noise_corner(i, f, vec3i(1, 0, 0));
    let v2 = noise_corner(i, f, vec3i(0, 1, 0));
    let v3 = noise_corner(i, f, vec3i(1, 1, 0));
    let v4 = noise_corner(i, f, vec3i(0, 0, 1));
    let v5 = noise_corner(i, f, vec3i(1, 0, 1));
    let v6 = noise_corner(i, f, vec3i(0, 1, 1));
    let v7 = noise_corner(i, f, vec3i(1, 1, 1));
    return z1 * (y1 * (v0 * x1 + v1 * u) + v * (v2 * x1 + v3 * u)) + w * (y1 * (v4 * x1 + v5 * u) + v * (v6 * x1 + v7 * u));
}

// Signed noise in about [-1, 1], repeating every 100000 so that floats keep their precision.
fn snoise_3d(p: vec3f) -> f32 {
    return 0.9820 * perlin_3d(p % vec3f(100000.0));
}

fn noise_fbm(p: vec3f, detail: f32, roughness: f32, lacunarity: f32, normalize: bool) -> f32 {
    var fscale = 1.0;
    var amp = 1.0;
    var maxamp = 0.0;
    var sum = 0.0;
    for (var i = 0; i <= i32(detail); i++) {
        sum += snoise_3d(fscale * p) * amp;
        maxamp += amp;
        amp *= roughness;
        fscale *= lacunarity;
    }
    let rmd = detail - floor(detail);
    if rmd != 0.0 {
        let sum2 = sum + snoise_3d(fscale * p) * amp;
        if normalize {
            return mix(0.5 * sum / maxamp + 0.5, 0.5 * sum2 / (maxamp + amp) + 0.5, rmd);
        }
        return mix(sum, sum2, rmd);
    }
    return select(sum, 0.5 * sum / maxamp + 0.5, normalize);
}

fn noise_multi_fractal(p_in: vec3f, detail: f32, roughness: f32, lacunarity: f32) -> f32 {
    var p = p_in;
    var value = 1.0;
    var pwr = 1.0;
    for (var i = 0; i <= i32(detail); i++) {
        value *= pwr * snoise_3d(p) + 1.0;
        pwr *= roughness;
        p *= lacunarity;
    }
    let rmd = detail - floor(detail);
    if rmd != 0.0 {
        value *= rmd * pwr * snoise_3d(p) + 1.0;
    }
    return value;
}

fn noise_hetero_terrain(p_in: vec3f, detail: f32, roughness: f32, lacunarity: f32, offset: f32) -> f32 {
    var p = p_in;
    var pwr = roughness;
    var value = offset + snoise_3d(p);
    p *= lacunarity;
    for (var i = 1; i <= i32(detail); i++) {
        value += (snoise_3d(p) + offset) * pwr * value;
        pwr *= roughness;
        p *= lacunarity;
    }
    let rmd = detail - floor(detail);
    if rmd != 0.0 {
        value += rmd * (snoise_3d(p) + offset) * pwr * value;
    }
    return value;
}

fn noise_hybrid_multi_fractal(p_in: vec3f, detail: f32, roughness: f32, lacunarity: f32, offset: f32, gain: f32) -> f32 {
    var p = p_in;
    var pwr = 1.0;
    var value = 0.0;
    var weight = 1.0;
    for (var i = 0; weight > 0.001 && i <= i32(detail); i++) {
        weight = min(weight, 1.0);
        let signal = (snoise_3d(p) + offset) * pwr;
        pwr *= roughness;
        value += weight * signal;
        weight *= gain * signal;
        p *= lacunarity;
    }
    let rmd = detail - floor(detail);
    if rmd != 0.0 && weight > 0.001 {
        value += rmd * min(weight, 1.0) * (snoise_3d(p) + offset) * pwr;
    }
    return value;
}

fn noise_ridged_multi_fractal(p_in: vec3f, detail: f32, roughness: f32, lacunarity: f32, offset: f32, gain: f32) -> f32 {
    var p = p_in;
    var pwr = roughness;
    var signal = offset - abs(snoise_3d(p));
    signal *= signal;
    var value = signal;
    for (var i = 1; i <= i32(detail); i++) {
        p *= lacunarity;
        let weight = clamp(signal * gain, 0.0, 1.0);
        signal = offset - abs(snoise_3d(p));
        signal *= signal * weight;
        value += signal * pwr;
        pwr *= roughness;
    }
    return value;
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
        n += distortion * (noise_fbm(p * detail_scale, detail, detail_roughness, 2.0, true) * 2.0 - 1.0);
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
    // NOISE_TYPES' index in src/asset/node_kinds.rs.
    kind: u32,
    normalize: bool,
}

fn noise_select(p: vec3f, s: NoiseSettings) -> f32 {
    switch s.kind {
        case 1u: {
            return noise_multi_fractal(p, s.detail, s.roughness, s.lacunarity);
        }
        case 2u: {
            return noise_hybrid_multi_fractal(p, s.detail, s.roughness, s.lacunarity, s.offset, s.gain);
        }
        case 3u: {
            return noise_ridged_multi_fractal(p, s.detail, s.roughness, s.lacunarity, s.offset, s.gain);
        }
        case 4u: {
            return noise_hetero_terrain(p, s.detail, s.roughness, s.lacunarity, s.offset);
        }
        default: {
            return noise_fbm(p, s.detail, s.roughness, s.lacunarity, s.normalize);
        }
    }
}

// The Noise Texture's Fac (w) and Color (xyz) at `co`, already scaled.
fn noise_texture_3d(co: vec3f, distortion: f32, s: NoiseSettings) -> vec4f {
    var p = co;
    if distortion != 0.0 {
        p += distortion * vec3f(
            snoise_3d(p + noise_offset3(0.0)),
            snoise_3d(p + noise_offset3(1.0)),
            snoise_3d(p + noise_offset3(2.0)),
        );
    }
    let value = noise_select(p, s);
    return vec4f(value, noise_select(p + noise_offset3(3.0), s), noise_select(p + noise_offset3(4.0), s), value);
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

