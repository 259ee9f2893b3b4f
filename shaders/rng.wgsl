// Counter-based random numbers: the stream of a sample is a pure function of
// (pixel, sample index, seed), so a render is reproducible whatever the
// number of samples per dispatch.

// PCG-RXS-M-XS hash (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020).
fn pcg_hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

struct Rng {
    state: u32,
}

fn rng_for_sample(pixel: u32, sample: u32, seed: u32) -> Rng {
    return Rng(pcg_hash(pixel ^ pcg_hash(sample ^ pcg_hash(seed))));
}

fn rng_next(rng: ptr<function, Rng>) -> f32 {
    (*rng).state = (*rng).state * 747796405u + 2891336453u;
    let s = (*rng).state;
    let word = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    // 24 bits so that the result is exactly representable and strictly below 1.
    return f32(((word >> 22u) ^ word) >> 8u) * (1.0 / 16777216.0);
}
