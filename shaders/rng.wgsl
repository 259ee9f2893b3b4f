// The random numbers of a sample are a pure function of (pixel, sample index, seed), so a
// render is reproducible whatever the number of samples per dispatch or lanes.
//
// A sample's first SOBOL_DIMENSIONS numbers (the camera's pixel and lens positions, the
// first bounces' light and BSDF samples) are Owen-scrambled Sobol points (Burley, "Practical
// Hash-based Owen Scrambling", JCGT 2020): the numbers come in groups of four, each group a
// 4D Sobol point whose index is the sample index shuffled per pixel and group (a nested
// uniform scramble), each coordinate scrambled by a hash of its own. Over a pixel's samples
// each group is stratified in 4D, and the groups, pixels and seeds are decorrelated. The
// numbers after those come from a PCG stream (Jarzynski & Olano, "Hash Functions for GPU
// Rendering", JCGT 2020).

// Numbers per sample drawn from scrambled Sobol points; the rest from PCG.
const SOBOL_DIMENSIONS: u32 = 16u;

// PCG-RXS-M-XS hash.
fn pcg_hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

struct Rng {
    // The PCG stream, for the numbers after the Sobol ones; its start identifies the sample.
    state: u32,
    // Per pixel and seed: the source of the scrambles.
    scramble: u32,
    sample: u32,
    // How many numbers this sample has drawn.
    dimension: u32,
    // The scrambled Sobol point of the current group of four, made at its first number.
    point: vec4u,
}

fn rng_for_sample(pixel: u32, sample: u32, seed: u32) -> Rng {
    let key = pcg_hash(pixel ^ pcg_hash(seed));
    return Rng(pcg_hash(pixel ^ pcg_hash(sample ^ pcg_hash(seed))), pcg_hash(key ^ 0x9e3779b9u), sample, 0u, vec4u(0u));
}

// A hash-based approximation of a random Owen scramble of reversed bits: Laine and
// Karras' construction with Vegdahl's constants ("Building a Better LK Hash", 2021),
// whose avalanche is far better than the original's.
fn laine_karras_permutation(x_in: u32, seed: u32) -> u32 {
    var x = x_in;
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16u) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

fn nested_uniform_scramble(x: u32, seed: u32) -> u32 {
    return reverseBits(laine_karras_permutation(reverseBits(x), seed));
}

// The 4D Sobol point of `index`: the bit reversal, then the direction numbers of Joe and
// Kuo's primitive polynomials x + 1, x² + x + 1 and x³ + x + 1 (initial numbers 1; 1, 3;
// 1, 3, 1) of each set bit XORed together. Written out bit by bit rather than looped:
// lavapipe ends an invocation after 65,535 turns of its loops, which long paths of many
// samples reach.
fn sobol4(index: u32) -> vec4u {
    var x = vec3u(0u);
    x ^= select(vec3u(0u), vec3u(0x80000000u, 0x80000000u, 0x80000000u), (index & 0x1u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xc0000000u, 0xc0000000u, 0xc0000000u), (index & 0x2u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xa0000000u, 0x60000000u, 0x20000000u), (index & 0x4u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xf0000000u, 0x90000000u, 0x50000000u), (index & 0x8u) != 0u);
    x ^= select(vec3u(0u), vec3u(0x88000000u, 0xe8000000u, 0xf8000000u), (index & 0x10u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xcc000000u, 0x5c000000u, 0x74000000u), (index & 0x20u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xaa000000u, 0x8e000000u, 0xa2000000u), (index & 0x40u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xff000000u, 0xc5000000u, 0x93000000u), (index & 0x80u) != 0u);
    x ^= select(vec3u(0u), vec3u(0x80800000u, 0x68800000u, 0xd8800000u), (index & 0x100u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xc0c00000u, 0x9cc00000u, 0x25400000u), (index & 0x200u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xa0a00000u, 0xee600000u, 0x59e00000u), (index & 0x400u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xf0f00000u, 0x55900000u, 0xe6d00000u), (index & 0x800u) != 0u);
    x ^= select(vec3u(0u), vec3u(0x88880000u, 0x80680000u, 0x78080000u), (index & 0x1000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xcccc0000u, 0xc09c0000u, 0xb40c0000u), (index & 0x2000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xaaaa0000u, 0x60ee0000u, 0x82020000u), (index & 0x4000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xffff0000u, 0x90550000u, 0xc3050000u), (index & 0x8000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0x80008000u, 0xe8808000u, 0x208f8000u), (index & 0x10000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xc000c000u, 0x5cc0c000u, 0x51474000u), (index & 0x20000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xa000a000u, 0x8e606000u, 0xfbea2000u), (index & 0x40000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xf000f000u, 0xc5909000u, 0x75d93000u), (index & 0x80000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0x88008800u, 0x6868e800u, 0xa0858800u), (index & 0x100000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xcc00cc00u, 0x9c9c5c00u, 0x914e5400u), (index & 0x200000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xaa00aa00u, 0xeeee8e00u, 0xdbe79e00u), (index & 0x400000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xff00ff00u, 0x5555c500u, 0x25db6d00u), (index & 0x800000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0x80808080u, 0x8000e880u, 0x58800080u), (index & 0x1000000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xc0c0c0c0u, 0xc0005cc0u, 0xe54000c0u), (index & 0x2000000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xa0a0a0a0u, 0x60008e60u, 0x79e00020u), (index & 0x4000000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xf0f0f0f0u, 0x9000c590u, 0xb6d00050u), (index & 0x8000000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0x88888888u, 0xe8006868u, 0x800800f8u), (index & 0x10000000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xccccccccu, 0x5c009c9cu, 0xc00c0074u), (index & 0x20000000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xaaaaaaaau, 0x8e00eeeeu, 0x200200a2u), (index & 0x40000000u) != 0u);
    x ^= select(vec3u(0u), vec3u(0xffffffffu, 0xc5005555u, 0x50050093u), (index & 0x80000000u) != 0u);
    return vec4u(reverseBits(index), x);
}

fn to_unit(bits: u32) -> f32 {
    // 24 bits so that the result is exactly representable and strictly below 1.
    return f32(bits >> 8u) * (1.0 / 16777216.0);
}

fn rng_next(rng: ptr<function, Rng>) -> f32 {
    let d = (*rng).dimension;
    (*rng).dimension = d + 1u;
    if d < SOBOL_DIMENSIONS {
        if (d & 3u) == 0u {
            let group = d >> 2u;
            let index = nested_uniform_scramble((*rng).sample, pcg_hash((*rng).scramble ^ (group * 0x68bc21ebu)));
            let point = sobol4(index);
            let seeds = pcg_hash((*rng).scramble + d * 0x02e5be93u);
            let seed = vec4u(seeds, pcg_hash(seeds ^ 1u), pcg_hash(seeds ^ 2u), pcg_hash(seeds ^ 3u));
            // The scramble decorrelates; a random XOR (a digital shift, which keeps the
            // points' stratification) on top makes each point exactly uniform, whatever
            // the hash's flaws: every sample is unbiased.
            let shift = vec4u(pcg_hash(seed.x), pcg_hash(seed.y), pcg_hash(seed.z), pcg_hash(seed.w));
            (*rng).point = vec4u(
                nested_uniform_scramble(point.x, seed.x),
                nested_uniform_scramble(point.y, seed.y),
                nested_uniform_scramble(point.z, seed.z),
                nested_uniform_scramble(point.w, seed.w),
            ) ^ shift;
        }
        return to_unit((*rng).point[d & 3u]);
    }
    (*rng).state = (*rng).state * 747796405u + 2891336453u;
    let s = (*rng).state;
    let word = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return to_unit((word >> 22u) ^ word);
}
