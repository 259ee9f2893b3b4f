// The hashes of Cycles' util/hash.h, bit for bit: Bob Jenkins' lookup3 of integers and of
// floats' bits (Apache-2.0, Blender Foundation), and the White Noise Texture made of them
// (kernel/svm/white_noise.h).

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
