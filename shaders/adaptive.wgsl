// Adaptive sampling: a pixel whose mean luminance is known to a relative standard
// error below the noise threshold takes no more samples (after a minimum count, so
// that its error estimate is not made of a handful of samples).

// Samples taken per pixel (finite or not): with adaptive sampling, pixels differ.
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
