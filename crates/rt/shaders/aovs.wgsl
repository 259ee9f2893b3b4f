// Auxiliary images for a denoiser, as Open Image Denoise expects them: the albedo and
// the shading normal of the first surface that is not a perfect mirror or interface
// (those are followed, their tint carried along), and the distance along the camera
// ray to the first surface. Beside them, Cycles' Position and Emission passes: where
// the camera ray met the scene (world space; nothing where it met nothing) and the light
// it saw emitted there. Averaged over the pixel's samples like the radiance.

// Five per pixel: (albedo, mean depth over the samples that hit), (normal, samples that
// hit), (position, the sum of the samples' coverage), (emission, unused), (diffuse colour,
// unused). A sample covers
// its pixel unless a transparent film let it leave the scene or a holdout took it (in
// part: a share of a Holdout shader); the pixel's alpha is that sum over its samples.
//#include "bsdf.wgsl"

@group(1) @binding(3) var<storage, read_write> aov_means: array<vec4f>;
// vec4 per pixel in aov_means and per sample in the lanes' scratch (`render::aovs`'s
// MEANS_PER_PIXEL).
const AOV_VEC4S: u32 = 5u;

struct AovSample {
    albedo: vec3f,
    normal: vec3f,
    // < 0: the camera ray left the scene.
    depth: f32,
    position: vec3f,
    emission: vec3f,
    // Cycles' Diffuse Color: the weight of the diffuse lobe of the first surface met.
    diffuse_color: vec3f,
    // How much of the pixel the sample covers, in [0, 1].
    coverage: f32,
    // The first non-delta surface is still to be found.
    open: bool,
    // The tint of the perfect mirrors and interfaces followed so far.
    weight: vec3f,
}

var<private> aov: AovSample;

fn aov_begin() {
    aov = AovSample(vec3f(0.0), vec3f(0.0), -1.0, vec3f(0.0), vec3f(0.0), vec3f(0.0), 1.0, true, vec3f(1.0));
}

// The camera ray met a surface at distance `t`, at `position`.
fn aov_first_hit(t: f32, position: vec3f) {
    aov.depth = t;
    aov.position = position;
}

// Light the camera ray saw emitted (a surface's emission, a lamp seen directly).
fn aov_emission_seen(light: vec3f) {
    aov.emission += light;
}

// A transparent film's background, seen by the camera's path with `weight` (its
// throughput's average) through what lets it by: that much of the pixel is uncovered.
// Seen by the camera ray itself, the sample also met nothing for the depth.
fn aov_background_seen(weight: f32, camera_ray: bool) {
    aov.coverage -= weight;
    if camera_ray {
        aov.depth = -1.0;
        aov.position = vec3f(0.0);
    }
}

// The first surface the camera's path met (past alpha), shaded by `ctx` and reached with
// `throughput`: the weights of its diffuse closures, as Cycles sums them (the diffuse lobe's,
// base colour × its share × what its coating, coat and sheen let through, and the sheen's
// own, which Cycles counts among the diffuse ones: sheen × tint × its albedo, on top).
fn aov_diffuse_color_seen(ctx: ShadingContext, throughput: vec3f) {
    let diffuse = ctx.m.base_color * (ctx.m.diffuse * ctx.diffuse_kept * ctx.under_sheen) * ctx.under_coat;
    aov.diffuse_color = throughput * (diffuse + ctx.sheen_color);
}

// The camera's path met a holdout: `amount` of the pixel (the held-out share times the
// path's throughput) is left uncovered.
fn aov_held_out(amount: f32) {
    aov.coverage -= amount;
}

// A BSDF sample taken at a surface of shading normal `normal` (facing the viewer):
// a delta lobe's is followed; any other's weight is an estimate of the surface's albedo.
fn aov_surface(s: BsdfSample, normal: vec3f) {
    if !aov.open {
        return;
    }
    if s.valid && s.pdf == 0.0 {
        aov.weight *= s.weight;
        return;
    }
    aov.albedo = aov.weight * select(vec3f(0.0), s.weight, s.valid);
    aov.normal = normal;
    aov.open = false;
}

struct AovMeans {
    a: vec4f,
    b: vec4f,
    position: vec4f,
    emission: vec4f,
    diffuse_color: vec4f,
}

fn aov_load(pixel_index: u32) -> AovMeans {
    let at = AOV_VEC4S * pixel_index;
    return AovMeans(aov_means[at], aov_means[at + 1u], aov_means[at + 2u], aov_means[at + 3u], aov_means[at + 4u]);
}

fn aov_store(pixel_index: u32, m: AovMeans) {
    let at = AOV_VEC4S * pixel_index;
    aov_means[at] = m.a;
    aov_means[at + 1u] = m.b;
    aov_means[at + 2u] = m.position;
    aov_means[at + 3u] = m.emission;
    aov_means[at + 4u] = m.diffuse_color;
}

// Adds the sample just traced, the pixel's sample `sample_index` (from 0).
fn aov_add(m: ptr<function, AovMeans>, sample_index: u32) {
    let n = f32(sample_index + 1u);
    let albedo = (*m).a.rgb + (aov.albedo - (*m).a.rgb) / n;
    let normal = (*m).b.xyz + (aov.normal - (*m).b.xyz) / n;
    let position = (*m).position.xyz + (aov.position - (*m).position.xyz) / n;
    let emission = (*m).emission.xyz + (aov.emission - (*m).emission.xyz) / n;
    let diffuse_color = (*m).diffuse_color.xyz + (aov.diffuse_color - (*m).diffuse_color.xyz) / n;
    var depth = (*m).a.w;
    var hits = (*m).b.w;
    if aov.depth >= 0.0 {
        hits += 1.0;
        depth += (aov.depth - depth) / hits;
    }
    let coverage = (*m).position.w + aov.coverage;
    *m = AovMeans(vec4f(albedo, depth), vec4f(normal, hits), vec4f(position, coverage), vec4f(emission, 0.0), vec4f(diffuse_color, 0.0));
}

// The sample's values as its exact sums add them (exact_sums.wgsl): albedo, depth where
// hit, normal, hit count, position, coverage, emission, diffuse colour.
fn aov_sums() -> array<f32, 18> {
    let hit = aov.depth >= 0.0;
    return array<f32, 18>(
        aov.albedo.x, aov.albedo.y, aov.albedo.z, select(0.0, aov.depth, hit),
        aov.normal.x, aov.normal.y, aov.normal.z, select(0.0, 1.0, hit),
        aov.position.x, aov.position.y, aov.position.z, aov.coverage,
        aov.emission.x, aov.emission.y, aov.emission.z,
        aov.diffuse_color.x, aov.diffuse_color.y, aov.diffuse_color.z,
    );
}

// Under lanes (`render_lanes`), a finished sample's AOVs wait in the lanes' scratch for
// `reduce_lanes`, five vec4 per sample after the dispatch's radiance samples: (albedo,
// depth), (normal, unused), (position, coverage), (emission, unused), (diffuse colour, unused). Stored and reloaded
// as they are, so that the means are the same bit for bit as when `render` adds them at
// once.
fn aov_lane_index(slot: u32) -> u32 {
    return frame.samples_per_dispatch * frame.width * frame.height + AOV_VEC4S * slot;
}

fn aov_lane_store(slot: u32) {
    let at = aov_lane_index(slot);
    lane_samples[at] = vec4f(aov.albedo, aov.depth);
    lane_samples[at + 1u] = vec4f(aov.normal, 0.0);
    lane_samples[at + 2u] = vec4f(aov.position, aov.coverage);
    lane_samples[at + 3u] = vec4f(aov.emission, 0.0);
    lane_samples[at + 4u] = vec4f(aov.diffuse_color, 0.0);
}

// Makes the sample in `slot` the one `aov_add` adds.
fn aov_lane_load(slot: u32) {
    let at = aov_lane_index(slot);
    let a = lane_samples[at];
    let b = lane_samples[at + 1u];
    let position = lane_samples[at + 2u];
    let emission = lane_samples[at + 3u].xyz;
    let diffuse_color = lane_samples[at + 4u].xyz;
    aov = AovSample(a.xyz, b.xyz, a.w, position.xyz, emission, diffuse_color, position.w, false, vec3f(1.0));
}
