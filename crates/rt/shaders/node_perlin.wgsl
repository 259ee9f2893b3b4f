// Perlin's improved gradient noise of 1 to 4 dimensions as Cycles computes it
// (kernel/svm/noise.h, after Open Shading Language; BSD-3-Clause, Sony Pictures Imageworks
// and Blender Foundation): the lattice points hashed by lookup3, OSL's gradients and the
// scales that bring each dimension's noise to about [-1, 1].

//#include "node_hash.wgsl"

fn noise_fade(t: f32) -> f32 {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

fn negate_if(v: f32, condition: u32) -> f32 {
    return select(v, -v, condition != 0u);
}

fn perlin_1d(x: f32) -> f32 {
    let fl = floor(x);
    let i = bitcast<u32>(i32(fl));
    let f = x - fl;
    let g0 = negate_if(f32(1u + (hash_uint1(i) & 7u)), hash_uint1(i) & 8u) * f;
    let g1 = negate_if(f32(1u + (hash_uint1(i + 1u) & 7u)), hash_uint1(i + 1u) & 8u) * (f - 1.0);
    return g0 + noise_fade(f) * (g1 - g0);
}

fn noise_grad2(hash: u32, x: f32, y: f32) -> f32 {
    let h = hash & 7u;
    let u = select(y, x, h < 4u);
    let v = 2.0 * select(x, y, h < 4u);
    return negate_if(u, h & 1u) + negate_if(v, h & 2u);
}

fn noise_corner2(i: vec2i, f: vec2f, corner: vec2i) -> f32 {
    let c = bitcast<vec2u>(i + corner);
    let d = f - vec2f(corner);
    return noise_grad2(hash_uint2(c.x, c.y), d.x, d.y);
}

fn perlin_2d(p: vec2f) -> f32 {
    let fl = floor(p);
    let i = vec2i(fl);
    let f = p - fl;
    let u = noise_fade(f.x);
    let v = noise_fade(f.y);
    let x1 = 1.0 - u;
    let v0 = noise_corner2(i, f, vec2i(0, 0));
    let v1 = noise_corner2(i, f, vec2i(1, 0));
    let v2 = noise_corner2(i, f, vec2i(0, 1));
    let v3 = noise_corner2(i, f, vec2i(1, 1));
    return (1.0 - v) * (v0 * x1 + v1 * u) + v * (v2 * x1 + v3 * u);
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

// Cycles' tri_mix of a cube's eight corner values `a` (x fastest) and `b`.
fn noise_tri_mix(a: vec4f, b: vec4f, u: f32, v: f32, w: f32) -> f32 {
    let x1 = 1.0 - u;
    let y1 = 1.0 - v;
    let z1 = 1.0 - w;
    return z1 * (y1 * (a.x * x1 + a.y * u) + v * (a.z * x1 + a.w * u)) + w * (y1 * (b.x * x1 + b.y * u) + v * (b.z * x1 + b.w * u));
}

fn perlin_3d(p: vec3f) -> f32 {
    let fl = floor(p);
    let i = vec3i(fl);
    let f = p - fl;
    let near = vec4f(
        noise_corner(i, f, vec3i(0, 0, 0)),
        noise_corner(i, f, vec3i(1, 0, 0)),
        noise_corner(i, f, vec3i(0, 1, 0)),
        noise_corner(i, f, vec3i(1, 1, 0)),
    );
    let far = vec4f(
        noise_corner(i, f, vec3i(0, 0, 1)),
        noise_corner(i, f, vec3i(1, 0, 1)),
        noise_corner(i, f, vec3i(0, 1, 1)),
        noise_corner(i, f, vec3i(1, 1, 1)),
    );
    return noise_tri_mix(near, far, noise_fade(f.x), noise_fade(f.y), noise_fade(f.z));
}

fn noise_grad4(hash: u32, d: vec4f) -> f32 {
    let h = hash & 31u;
    let u = select(d.y, d.x, h < 24u);
    let v = select(d.z, d.y, h < 16u);
    let s = select(d.w, d.z, h < 8u);
    return negate_if(u, h & 1u) + negate_if(v, h & 2u) + negate_if(s, h & 4u);
}

fn noise_corner4(i: vec4i, f: vec4f, corner: vec4i) -> f32 {
    let c = bitcast<vec4u>(i + corner);
    return noise_grad4(hash_uint4(c.x, c.y, c.z, c.w), f - vec4f(corner));
}

// The eight corners of the cube at w = `w` (0 or 1) of the lattice cell at `i`, tri-mixed.
fn perlin_4d_cube(i: vec4i, f: vec4f, w: i32) -> f32 {
    let near = vec4f(
        noise_corner4(i, f, vec4i(0, 0, 0, w)),
        noise_corner4(i, f, vec4i(1, 0, 0, w)),
        noise_corner4(i, f, vec4i(0, 1, 0, w)),
        noise_corner4(i, f, vec4i(1, 1, 0, w)),
    );
    let far = vec4f(
        noise_corner4(i, f, vec4i(0, 0, 1, w)),
        noise_corner4(i, f, vec4i(1, 0, 1, w)),
        noise_corner4(i, f, vec4i(0, 1, 1, w)),
        noise_corner4(i, f, vec4i(1, 1, 1, w)),
    );
    return noise_tri_mix(near, far, noise_fade(f.x), noise_fade(f.y), noise_fade(f.z));
}

fn perlin_4d(p: vec4f) -> f32 {
    let fl = floor(p);
    let i = vec4i(fl);
    let f = p - fl;
    let a = perlin_4d_cube(i, f, 0);
    let b = perlin_4d_cube(i, f, 1);
    return a + noise_fade(f.w) * (b - a);
}

// Signed noise of the first `dimensions` (1 to 4) components of `p`, in about [-1, 1]
// (Cycles' snoise_1d … snoise_4d): repeating every 100000 so that floats keep their
// precision, shifted by half a cell where a component is a million or more.
fn snoise(p_in: vec4f, dimensions: u32) -> f32 {
    let p = p_in % vec4f(100000.0) + select(vec4f(0.0), vec4f(0.5), abs(p_in) >= vec4f(1000000.0));
    switch dimensions {
        case 1u: {
            return 0.2500 * perlin_1d(p.x);
        }
        case 2u: {
            return 0.6616 * perlin_2d(p.xy);
        }
        case 4u: {
            return 0.8344 * perlin_4d(p);
        }
        default: {
            return 0.9820 * perlin_3d(p.xyz);
        }
    }
}
