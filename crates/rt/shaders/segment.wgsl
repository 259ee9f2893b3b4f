// Exact integration of radiance along a segment of constant coefficients: the
// solution of dL/ds = −σₑ L + S over length t. Serves absorbing, emitting media
// inside materials, and each step of an atmosphere march.

struct Segment {
    transmittance: vec3f,
    // Radiance the segment adds at its start: S (1 − e^(−σₑ t)) / σₑ, or S t where σₑ = 0.
    radiance: vec3f,
}

fn integrate_segment(extinction: vec3f, source: vec3f, t: f32) -> Segment {
    let clear = extinction <= vec3f(0.0);
    let transmittance = select(exp(-extinction * t), vec3f(1.0), clear);
    let radiance = select(source * (1.0 - transmittance) / extinction, source * t, clear);
    return Segment(transmittance, radiance);
}
