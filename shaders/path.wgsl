// A path between two of its rays (pbrt's path state): where its next ray starts and
// goes, what it has gathered and what it carries, and what its next vertex must know of
// the last one. The steps of `trace_samples` (integrator.wgsl) read and change it: the
// camera starts a path, its ray meets light on the way and then a surface or nothing
// (path_emission.wgsl), a surface gives the material there (path_surface.wgsl) and
// scatters the path on or ends it (path_scatter.wgsl).

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "rng.wgsl"
//#include "camera.wgsl"
//#if nee
//#include "lights.wgsl"
//#endif
//#if node_graphs
//#include "node_program.wgsl"
//#endif

struct Path {
    rng: Rng,
    origin: vec3f,
    direction: vec3f,
    // The camera ray ends at the far clip plane; the rays after it do not.
    t_max: f32,
    radiance: vec3f,
    throughput: vec3f,
    // Density of the last BSDF sample, for MIS; 0 after the camera and after delta lobes.
    bsdf_pdf: f32,
    // The medium the path travels in: absorption and emission per metre.
    medium_absorption: vec3f,
    medium_emission: vec3f,
    bounce: u32,
    // The camera's path has only passed through what lets the background through (alpha
    // and, with Film › Transparent Glass, clear glass): what it meets may still be a hole
    // (Cycles' PATH_RAY_TRANSPARENT_BACKGROUND).
    transparent_background: bool,
    //#if nee
    // A light sample waiting for its shadow ray, weighted by the throughput it was taken with.
    shadow: ShadowRay,
    //#endif
    // The next ray is the shadow ray (traced before the path's own next ray, if any).
    shadow_pending: bool,
    // No ray follows: the camera sent none, the BSDF gave no direction or Russian
    // roulette ended the path (a pending shadow ray is still traced).
    ended: bool,
    // The sample's identity (its random stream's start: pixel, sample and seed) for the
    // coins of blended surfaces and of Mix Shaders.
    key: u32,
    // The event that first made the path's radiance or throughput non-finite (EVENT_*).
    bad_event: u32,
    //#if textures
    // The ray cone (Ray Tracing Gems ch. 20): its width grows by the pixel's angle per
    // unit of distance; later bounces keep widening it by the path's length, a lower
    // bound on their footprint (a finer level than ideal: noise, never blur).
    cone_width: f32,
    //#endif
    //#if node_graphs
    // What the path's last ray came from, for the Light Path node (NODE_RAY_*).
    ray_from: u32,
    ray_singular: bool,
    //#endif
}

// What produced a non-finite value first, recorded per pixel (src/render/sentinel.rs reads it).
const EVENT_NONE: u32 = 0u;
const EVENT_EMISSION: u32 = 1u;
const EVENT_SKY: u32 = 2u;
const EVENT_LIGHT_SAMPLE: u32 = 3u;
const EVENT_MEDIUM: u32 = 4u;
const EVENT_AIR: u32 = 5u;
// EVENT_LOBE + lobe index (LOBE_* in bsdf.wgsl): the BSDF sample of that lobe.
const EVENT_LOBE: u32 = 6u;

// Sample `sample` of the pixel: its camera ray, nothing gathered yet. A panorama's
// pixel outside its image gets no ray: the path has ended (Cycles' pixel is black).
fn path_from_camera(pixel: vec2u, pixel_index: u32, sample: u32) -> Path {
    var path: Path;
    path.bad_event = EVENT_NONE;
    // (A function is given pointers to whole variables only.)
    var rng = rng_for_sample(pixel_index, sample, frame.seed);
    path.key = rng.state;
    //#if motion
    begin_sample_time(&rng);
    //#endif
    //#if node_graphs
    path.ray_from = NODE_RAY_CAMERA;
    path.ray_singular = false;
    //#endif
    let camera = camera_ray(pixel, &rng);
    path.rng = rng;
    path.origin = camera.origin;
    path.direction = camera.direction;
    path.t_max = camera.t_max;
    path.radiance = vec3f(0.0);
    path.throughput = vec3f(1.0);
    path.bsdf_pdf = 0.0;
    path.medium_absorption = vec3f(0.0);
    path.medium_emission = vec3f(0.0);
    path.bounce = 0u;
    path.transparent_background = true;
    path.ended = false;
    path.shadow_pending = false;
    //#if textures
    path.cone_width = 0.0;
    //#endif
    //#if panorama
    path.ended = no_camera_ray(camera);
    //#endif
    return path;
}

// Adds a contribution to the path's radiance, noting the event if the sum stops being finite.
fn gather(path: ptr<function, Path>, contribution: vec3f, event: u32) {
    path.radiance += contribution;
    if path.bad_event == EVENT_NONE && !all_finite(path.radiance) {
        path.bad_event = event;
    }
}

// Multiplies the path's throughput, noting the event if the result is not finite.
fn attenuate(path: ptr<function, Path>, factor: vec3f, event: u32) {
    path.throughput *= factor;
    if path.bad_event == EVENT_NONE && !all_finite(path.throughput) {
        path.bad_event = event;
    }
}

// Tested on the bits: compilers may fold `x != x` away under fast-math rules.
fn all_finite(v: vec3f) -> bool {
    let exponent = bitcast<vec3u>(v) & vec3u(0x7f800000u);
    return all(exponent != vec3u(0x7f800000u));
}

// The mean of a colour's channels: how much of the pixel a path of this throughput
// stands for (Cycles' `average`, as it counts transparency).
fn channel_mean(c: vec3f) -> f32 {
    return (c.x + c.y + c.z) / 3.0;
}
