// Adaptive sampling: a pixel whose mean luminance is known to a relative standard
// error below the noise threshold takes no more samples (after a minimum count, so
// that its error estimate is not made of a handful of samples).

// Two per pixel: the samples it took (finite or not: pixels differ), and 1 once it
// has stopped. A pixel stops when it and its eight neighbours have converged: a pixel
// whose first samples all happened to land on one side of an edge (the same value, no
// variance) would otherwise stop on a wrong mean, its neighbours still noisy.
@group(1) @binding(4) var<storage, read_write> pixel_samples: array<u32>;

// Relative to no less than this luminance: a black pixel with no variance has converged.
const ADAPTIVE_LUMINANCE_FLOOR: f32 = 1e-4;

fn pixel_converged(acc: vec4f, taken: u32, bad: u32) -> bool {
    let n = f32(taken - (bad & 0xffffffu));
    if taken < frame.adaptive_min_samples || n < 2.0 {
        return false;
    }
    let std_error = sqrt(max(acc.w, 0.0) / ((n - 1.0) * n));
    return std_error <= frame.noise_threshold * max(luminance(acc.rgb), ADAPTIVE_LUMINANCE_FLOOR);
}

fn pixel_converged_at(p: vec2i) -> bool {
    let q = vec2u(clamp(p, vec2i(0), vec2i(i32(frame.width) - 1, i32(frame.height) - 1)));
    let i = q.y * frame.width + q.x;
    return pixel_converged(accumulation[i], pixel_samples[2u * i], non_finite[i]);
}

// Before each dispatch: marks the pixels that stop. It reads the counts and writes the
// marks, so pixels never see a neighbour's value half written.
@compute @workgroup_size(8, 8)
fn adaptive_mask(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let i = id.y * frame.width + id.x;
    if pixel_samples[2u * i + 1u] != 0u {
        return;
    }
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            if !pixel_converged_at(vec2i(id.xy) + vec2i(dx, dy)) {
                return;
            }
        }
    }
    pixel_samples[2u * i + 1u] = 1u;
}
