// The random numbers of a sample are a pure function of (pixel, sample index, seed), so a
// render is reproducible whatever the number of samples per dispatch or lanes.
//
// A sample's first SOBOL_DIMENSIONS draws (the camera's pixel and lens positions, the first
// bounces' light picks, light and BSDF samples) are Owen-scrambled Sobol points (Burley,
// "Practical Hash-based Owen Scrambling", JCGT 2020), padded: each draw is a 1D or 2D point
// of its own, whose index is the sample index shuffled per pixel and draw (a nested uniform
// scramble), each coordinate scrambled by a hash of its own. Over a pixel's samples every 2D
// draw is stratified like a (0,2)-sequence, and draws, pixels and seeds are decorrelated.
// The draws after those come from a PCG stream (Jarzynski & Olano, "Hash Functions for GPU
// Rendering", JCGT 2020). Each draw computes its point on its own, from a few integer
// operations and no table, so a path keeps no sampler state beyond four words.

// Draws per sample from scrambled Sobol points; the rest from PCG.
const SOBOL_DIMENSIONS: u32 = 16u;

// PCG-RXS-M-XS hash.
fn pcg_hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

struct Rng {
    // The PCG stream, for the draws after the Sobol ones; its start identifies the sample.
    state: u32,
    // Per pixel and seed: the source of the scrambles.
    scramble: u32,
    sample: u32,
    // How many draws this sample has made.
    dimension: u32,
}

fn rng_for_sample(pixel: u32, sample: u32, seed: u32) -> Rng {
    let key = pcg_hash(pixel ^ pcg_hash(seed));
    return Rng(pcg_hash(pixel ^ pcg_hash(sample ^ pcg_hash(seed))), pcg_hash(key ^ 0x9e3779b9u), sample, 0u);
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

// Sobol's second dimension (primitive polynomial x + 1) of `index`, bit-reversed: its
// generator matrix is Pascal's triangle mod 2, whose row j has bit k where k's bits are a
// subset of j's (Lucas), so bit k of the result is the parity of the index's bits j ⊇ k: a
// superset-sum transform, one shift per bit of a bit position.
fn sobol_pascal_reversed(index: u32) -> u32 {
    var z = index;
    z ^= (z >> 1u) & 0x55555555u;
    z ^= (z >> 2u) & 0x33333333u;
    z ^= (z >> 4u) & 0x0f0f0f0fu;
    z ^= (z >> 8u) & 0x00ff00ffu;
    z ^= (z >> 16u) & 0x0000ffffu;
    return z;
}

// The draw's index: the sample index shuffled by a nested uniform scramble of its own, and
// the draw's seeds. Coordinates are scrambled in reversed-bit order (the LK hash owes its
// nesting to that) and reversed once at the end.
fn sobol_draw_index(rng: ptr<function, Rng>, d: u32) -> u32 {
    let seed = pcg_hash((*rng).scramble ^ (d * 0x68bc21ebu));
    return reverseBits(laine_karras_permutation(reverseBits((*rng).sample), seed));
}

// A coordinate scrambled in reversed-bit order, then a random XOR (a digital shift, which
// keeps the points' stratification): the scramble decorrelates, and the shift makes each
// point exactly uniform whatever the hash's flaws, so every sample is unbiased.
fn sobol_coordinate(reversed: u32, seed: u32) -> f32 {
    return to_unit(reverseBits(laine_karras_permutation(reversed, seed)) ^ pcg_hash(seed ^ 0x5bd1e995u));
}

// The stream's next number: the hash of its state (which steps the state as the
// stream does and permutes the result), then the step.
fn pcg_next(rng: ptr<function, Rng>) -> f32 {
    let bits = pcg_hash((*rng).state);
    (*rng).state = (*rng).state * 747796405u + 2891336453u;
    return to_unit(bits);
}

// The seed of draw `d`'s coordinates (of the first; the second's is derived from it).
fn sobol_coordinate_seed(rng: ptr<function, Rng>, d: u32) -> u32 {
    return pcg_hash((*rng).scramble + d * 0x02e5be93u);
}

// One number: for the first draws a scrambled van der Corput point (1D-stratified).
fn rng_next(rng: ptr<function, Rng>) -> f32 {
    let d = (*rng).dimension;
    (*rng).dimension = d + 1u;
    if d < SOBOL_DIMENSIONS {
        return sobol_coordinate(sobol_draw_index(rng, d), sobol_coordinate_seed(rng, d));
    }
    return pcg_next(rng);
}

// Two numbers drawn together (a position on a lamp, a direction, a pixel offset): for the
// first draws Sobol's first two dimensions, stratified in 2D.
fn rng_next2(rng: ptr<function, Rng>) -> vec2f {
    let d = (*rng).dimension;
    (*rng).dimension = d + 1u;
    if d < SOBOL_DIMENSIONS {
        let index = sobol_draw_index(rng, d);
        let seed = sobol_coordinate_seed(rng, d);
        return vec2f(sobol_coordinate(index, seed), sobol_coordinate(sobol_pascal_reversed(index), pcg_hash(seed ^ 1u)));
    }
    let x = pcg_next(rng);
    return vec2f(x, pcg_next(rng));
}

fn to_unit(bits: u32) -> f32 {
    // 24 bits so that the result is exactly representable and strictly below 1.
    return f32(bits >> 8u) * (1.0 / 16777216.0);
}
