// Exact sums of a pixel's samples, beside the running means, for `rt render`'s image:
// integer sums do not depend on the order they are added in, so the samples of a render
// split into parts (`--sample-range`) add up, merged, to the very image one render gives
// (src/render/exact.rs reads them). Each value is a 96-bit two's-complement integer in
// units of 2^-32 (three words, least significant first): a sample's value is rounded to
// that grid once, and from then on every sum is exact.
// Per pixel: EXACT_RADIANCE values (red, green, blue, the luminance's square), then with
// AOVs EXACT_AOVS more (albedo, depth where hit, normal, hit count, position, coverage,
// emission, diffuse colour).
//#include "common.wgsl"

@group(1) @binding(6) var<storage, read_write> exact_sums: array<u32>;

const EXACT_WORDS: u32 = 3u;
const EXACT_RADIANCE: u32 = 4u;
const EXACT_AOVS: u32 = 18u;
// A sample adds at most this much to one sum, so that 2^23 samples fit in the 63 bits
// above the fraction.
const EXACT_LARGEST: f32 = 1099511627776.0;

// The first word of the pixel's sum `value` (0: red).
fn exact_index(pixel_index: u32, value: u32) -> u32 {
    //#if aovs
    let values = EXACT_RADIANCE + EXACT_AOVS;
    //#else
    let values = EXACT_RADIANCE;
    //#endif
    return (pixel_index * values + value) * EXACT_WORDS;
}

// `v` on the grid of 2^-32, rounded to nearest (ties away from zero), as three words.
fn exact_words(v: f32) -> vec3u {
    let bits = bitcast<u32>(clamp(v, -EXACT_LARGEST, EXACT_LARGEST));
    let biased = (bits >> 23u) & 0xffu;
    // Zero and subnormals (below 2^-126) round to 0.
    if biased == 0u {
        return vec3u(0u);
    }
    // |v| = m × 2^(biased − 150), that is m × 2^(biased − 118) units of 2^-32.
    let m = (bits & 0x7fffffu) | 0x800000u;
    let shift = i32(biased) - 118;
    var w = vec3u(0u);
    if shift < 0 {
        let r = u32(-shift);
        if r <= 24u {
            w.x = (m + (1u << (r - 1u))) >> r;
        }
    } else {
        let s = u32(shift);
        let low = m << (s % 32u);
        let high = select(0u, m >> ((32u - s % 32u) % 32u), s % 32u != 0u);
        if s < 32u {
            w = vec3u(low, high, 0u);
        } else {
            w = vec3u(0u, low, high);
        }
    }
    if (bits >> 31u) != 0u {
        // Two's complement: invert and add one.
        w = ~w;
        w.x += 1u;
        let c0 = select(0u, 1u, w.x == 0u);
        w.y += c0;
        w.z += select(0u, 1u, c0 == 1u && w.y == 0u);
    }
    return w;
}

// Adds `v` to the pixel's sum that starts at word `at`.
fn exact_add(at: u32, v: f32) {
    let w = exact_words(v);
    let a0 = exact_sums[at];
    let a1 = exact_sums[at + 1u];
    let s0 = a0 + w.x;
    let c0 = select(0u, 1u, s0 < a0);
    let t1 = a1 + w.y;
    let s1 = t1 + c0;
    let c1 = select(0u, 1u, t1 < a1) + select(0u, 1u, s1 < t1);
    exact_sums[at] = s0;
    exact_sums[at + 1u] = s1;
    exact_sums[at + 2u] = exact_sums[at + 2u] + w.z + c1;
}

// A finite sample of (clamped) radiance `l`, of luminance `y`.
fn exact_add_radiance(pixel_index: u32, l: vec3f, y: f32) {
    let at = exact_index(pixel_index, 0u);
    exact_add(at, l.x);
    exact_add(at + EXACT_WORDS, l.y);
    exact_add(at + 2u * EXACT_WORDS, l.z);
    exact_add(at + 3u * EXACT_WORDS, y * y);
}

//#if aovs
// The AOVs of a finished sample (`aov_sums` of aovs.wgsl).
fn exact_add_aovs(pixel_index: u32, values: array<f32, EXACT_AOVS>) {
    var at = exact_index(pixel_index, EXACT_RADIANCE);
    for (var i = 0u; i < EXACT_AOVS; i++) {
        exact_add(at, values[i]);
        at += EXACT_WORDS;
    }
}
//#endif
