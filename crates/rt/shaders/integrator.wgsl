// The path-tracing megakernel: each dispatch adds `samples_per_dispatch` samples
// to every pixel's running mean, taken by one invocation per pixel (`render`) or,
// for small images, spread over several (`render_lanes`, then `reduce_lanes`, in
// sample_lanes.wgsl).

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "rng.wgsl"
//#include "ray.wgsl"
//#include "camera.wgsl"
//#include "hit.wgsl"
//#include "traverse.wgsl"
//#include "surface.wgsl"
//#include "sky.wgsl"
//#include "bsdf.wgsl"
//#include "sampling.wgsl"
//#if nee
//#include "lights.wgsl"
//#endif
//#if lamps
//#include "lamps.wgsl"
//#endif
//#if media
//#include "segment.wgsl"
//#endif
//#if sun
//#include "sun.wgsl"
//#endif
//#if sky_atmosphere
//#include "atmosphere_sky.wgsl"
//#endif
//#if textures
//#include "texture.wgsl"
//#endif
//#if node_graphs
//#include "node_program.wgsl"
//#endif
//#if normal_maps
//#include "normal_map.wgsl"
//#endif
//#if smooth_normals
//#include "smooth_shading.wgsl"
//#endif
//#if emission
//#include "layered_emission.wgsl"
//#endif
//#if terminator_offset
//#include "terminator_offset.wgsl"
//#endif
//#if aovs
//#include "aovs.wgsl"
//#endif
//#if holdout
//#include "holdout.wgsl"
//#endif
//#if adaptive
//#include "adaptive.wgsl"
//#endif
//#if exact_sums
//#include "exact_sums.wgsl"
//#endif
//#include "path_steps.wgsl"
//#if sky_graph
//#if node_graphs
//#include "sky_graph.wgsl"
//#endif
//#endif

// The mean of a colour's channels: how much of the pixel a path of this throughput
// stands for (Cycles' `average`, as it counts transparency).
fn channel_mean(c: vec3f) -> f32 {
    return (c.x + c.y + c.z) / 3.0;
}

// Film › Transparent Glass: glass whose GGX α is at most the frame's threshold (the
// square of Cycles' Roughness Threshold) lets the camera's path keep the background
// transparent.
fn is_clear_glass(m: Material) -> bool {
    return frame.transparent_glass >= 0.0 && m.alpha <= frame.transparent_glass;
}

// rgb: the running mean of radiance; w: the running sum of squared deviations
// of luminance (Welford), for the standard error. Means rather than sums: a sum
// of finite samples can overflow.
@group(1) @binding(0) var<storage, read_write> accumulation: array<vec4f>;
// Per pixel: dropped non-finite samples (low 24 bits) and the event that
// produced the first one (top 8 bits).
@group(1) @binding(1) var<storage, read_write> non_finite: array<u32>;

// The first event of this sample that produced a non-finite value (EVENT_*, shared
// constants), recorded per pixel.
var<private> first_bad_event: u32;

// Adds a contribution to the path's radiance, noting the event if the sum stops being finite.
fn gather(radiance: ptr<function, vec3f>, contribution: vec3f, event: u32) {
    *radiance += contribution;
    if first_bad_event == EVENT_NONE && !all_finite(*radiance) {
        first_bad_event = event;
    }
}

// Multiplies the throughput, noting the event if the result is not finite.
fn attenuate(throughput: ptr<function, vec3f>, factor: vec3f, event: u32) {
    *throughput *= factor;
    if first_bad_event == EVENT_NONE && !all_finite(*throughput) {
        first_bad_event = event;
    }
}

// Russian roulette may end a path after ROULETTE_START bounces (src/shared_constants.rs).

// Tested on the bits: compilers may fold `x != x` away under fast-math rules.
fn all_finite(v: vec3f) -> bool {
    let exponent = bitcast<vec3u>(v) & vec3u(0x7f800000u);
    return all(exponent != vec3u(0x7f800000u));
}

//#if emission
// Emission of the surface hit, MIS-weighted against light sampling when the
// bounce that found it could also have been found by next-event estimation.
// `layers`: the normals of the layers over the emission (see layered_emission.wgsl).
fn emission_seen(m: Material, hit: Hit, surface: Surface, layers: LayerNormals, origin: vec3f, direction: vec3f, bsdf_pdf: f32) -> vec3f {
    var weight = 1.0;
    //#if nee
    if bsdf_pdf > 0.0 {
        var light_pdf = 0.0;
        if hit.kind == HIT_SPHERE {
            //#if spheres
            light_pdf = sphere_hit_pdf(origin, hit.primitive, m.emission_luminance);
            //#endif
        } else {
            light_pdf = triangle_hit_pdf(m.emission_luminance, hit, abs(dot(surface.geometric_normal, direction)));
        }
        weight = power_heuristic(bsdf_pdf, light_pdf);
    }
    //#endif
    return layered_emission(m, m.emission, layers, -direction) * weight;
}
//#endif

//#if sun
// The sun's disk seen by a ray that leaves the scene.
fn sun_seen(origin: vec3f, direction: vec3f, bsdf_pdf: f32) -> vec3f {
    if !in_sun_disk(direction) {
        return vec3f(0.0);
    }
    var weight = 1.0;
    //#if nee
    if bsdf_pdf > 0.0 {
        weight = power_heuristic(bsdf_pdf, sun_share() / sun_solid_angle());
    }
    //#endif
    return sun_radiance_at(origin, direction) * weight;
}
//#endif

// The MIS weight of a sky that light sampling picks uniformly over the sphere, seen by a
// ray that leaves the scene after a BSDF sample of density `bsdf_pdf` (0 for the camera's
// rays and delta lobes, which light sampling cannot find).
fn uniform_sky_weight(bsdf_pdf: f32) -> f32 {
    //#if nee
    if bsdf_pdf > 0.0 {
        return power_heuristic(bsdf_pdf, uniform_sky_light_pdf());
    }
    //#endif
    return 1.0;
}

//#if sky_uniform_light
// The uniform sky seen by a ray that leaves the scene, MIS-weighted against light
// sampling after a BSDF sample, as `environment_seen` below.
fn uniform_sky_seen(bsdf_pdf: f32) -> vec3f {
    return frame.sky_color * uniform_sky_weight(bsdf_pdf);
}
//#endif

//#if sky_graph
//#if node_graphs
// The world seen by a ray that leaves the scene, MIS-weighted against light sampling after
// a BSDF sample (the world is light-sampled uniformly over the sphere).
fn graph_sky_seen(origin: vec3f, direction: vec3f, bsdf_pdf: f32, ray_from: u32, singular: bool, depth: u32, depths: u32) -> vec3f {
    return graph_sky_radiance(direction, origin, ray_from, singular, depth, depths) * uniform_sky_weight(bsdf_pdf);
}
//#endif
//#endif

//#if sky_environment
// The environment seen by a ray that leaves the scene, MIS-weighted against light
// sampling after a BSDF sample (the camera's rays and delta lobes have bsdf_pdf 0).
fn environment_seen(direction: vec3f, bsdf_pdf: f32) -> vec3f {
    var weight = 1.0;
    //#if nee
    if bsdf_pdf > 0.0 {
        weight = power_heuristic(bsdf_pdf, environment.light_share * environment_pdf(direction));
    }
    //#endif
    return environment_radiance(direction) * weight;
}
//#endif

// What a finished sample is added to: `render`'s pixel, read before its samples and
// written after them.
var<private> pixel_acc: vec4f;
var<private> pixel_bad: u32;
//#if aovs
var<private> pixel_aovs: AovMeans;
//#endif

// A finished sample `sample_base + k` of radiance `radiance`: into the pixel's running
// mean, or, for `render_lanes`, into slot k of `lane_samples` (its AOVs too, after the
// dispatch's radiance samples).
fn sample_done(pixel_index: u32, sample_base: u32, k: u32, radiance: vec3f, lanes: bool) {
    let sample_index = sample_base + k;
    if lanes {
        let slot = k * frame.width * frame.height + pixel_index;
        lane_samples[slot] = vec4f(radiance, bitcast<f32>(first_bad_event));
        //#if aovs
        aov_lane_store(slot);
        //#endif
        return;
    }
    // (WGSL passes function-space pointers only.)
    var acc = pixel_acc;
    var bad = pixel_bad;
    accumulate(&acc, &bad, radiance, first_bad_event, sample_index);
    pixel_acc = acc;
    pixel_bad = bad;
    //#if aovs
    var aovs = pixel_aovs;
    aov_add(&aovs, sample_index);
    pixel_aovs = aovs;
    //#endif
}

// The pixel's samples `sample_base + k` for k = `first` and those `next_sample` gives,
// below the dispatch's count, as paths traced one after another in a single loop. Each
// turn of the loop traces exactly one ray, the path's next ray or a pending shadow ray,
// through the loop's single call of the traversal:
// the traversal code is then in the kernel once, not once per kind of ray. A path that
// ends starts the pixel's next sample in the next turn (path regeneration, Novák et al.
// 2010), so an invocation whose path ended early does not idle until the longest path
// of its subgroup ends: it traces its next sample meanwhile. Samples still finish in
// sample order, so the image does not depend on it.
fn trace_samples(pixel: vec2u, pixel_index: u32, sample_base: u32, first: u32, lanes: bool) {
    if first >= frame.samples_per_dispatch {
        return;
    }
    var k = first;
    var rng: Rng;
    var origin: vec3f;
    var direction: vec3f;
    // The camera ray ends at the far clip plane; the rays after it do not.
    var path_t_max: f32;
    var radiance: vec3f;
    var throughput: vec3f;
    // Density of the last BSDF sample, for MIS; 0 after the camera and after delta lobes.
    var bsdf_pdf: f32;
    // The medium the path travels in: absorption and emission per metre.
    var medium_absorption: vec3f;
    var medium_emission: vec3f;
    var bounce: u32;
    // The camera's path has only passed through what lets the background through (alpha
    // and, with Film › Transparent Glass, clear glass): what it meets may still be a hole
    // (Cycles' PATH_RAY_TRANSPARENT_BACKGROUND).
    var transparent_background: bool;
    // A light sample waiting for its shadow ray, weighted by the throughput it was taken with.
    //#if nee
    var shadow: ShadowRay;
    //#endif
    var shadow_pending: bool;
    var path_ended: bool;
    // Set when the path has ended and its sample is to be added (in `continuing`).
    var sample_finished = false;
    var starting = true;
    // Set by the traversal when a stack was full (it counts that in `stats` itself).
    var stack_overflowed = false;
    //#if textures
    // The ray cone (Ray Tracing Gems ch. 20): its width grows by the pixel's angle per
    // unit of distance; later bounces keep widening it by the path's length, a
    // lower bound on their footprint (a finer level than ideal: noise, never blur).
    // A pixel's angle seen from the camera (view_half_extent is the image plane's half size
    // at distance 1); an orthographic camera's rays do not spread.
    let cone_spread = select(2.0 * frame.view_half_extent.y / f32(frame.height), 0.0, frame.orthographic != 0u);
    //#endif
    var cone_width: f32;
    // The sample's identity (its random stream's start: pixel, sample and seed) for the
    // coins of blended surfaces and of Mix Shaders.
    var path_key: u32;
    // What the path's last ray came from, for the Light Path node (NODE_RAY_*).
    var ray_from: u32;
    var ray_singular: bool;
    // Its bounces of each kind (NodePoint::ray_depths).
    var kind_depths: u32;
    loop {
        if starting {
            starting = false;
            rng = rng_for_sample(pixel_index, frame.first_sample + sample_base + k, frame.seed);
            first_bad_event = EVENT_NONE;
            path_key = rng.state;
            //#if motion
            begin_sample_time(&rng);
            //#endif
            //#if node_graphs
            ray_from = NODE_RAY_CAMERA;
            ray_singular = false;
            kind_depths = 0u;
            //#endif
            let camera = camera_ray(pixel, &rng);
            origin = camera.origin;
            direction = camera.direction;
            path_t_max = camera.t_max;
            radiance = vec3f(0.0);
            throughput = vec3f(1.0);
            bsdf_pdf = 0.0;
            medium_absorption = vec3f(0.0);
            medium_emission = vec3f(0.0);
            bounce = 0u;
            transparent_background = true;
            shadow_pending = false;
            path_ended = false;
            //#if textures
            cone_width = 0.0;
            //#endif
            //#if aovs
            aov_begin();
            //#endif
            //#if panorama
            // Where a panorama sends no ray (outside a fisheye's image), Cycles' pixel is black.
            if no_camera_ray(camera) {
                sample_finished = true;
                continue;
            }
            //#endif
        }
        var ray_origin = origin;
        var ray_direction = direction;
        var ray_t_max = path_t_max;
        //#if nee
        if shadow_pending {
            ray_origin = shadow.origin;
            ray_direction = shadow.direction;
            ray_t_max = shadow.t_max;
        }
        //#endif
        //#if alpha_blend
        set_alpha_ray_key(pcg_hash(path_key ^ pcg_hash(2u * bounce + u32(shadow_pending))));
        //#endif
        // A shadow ray only asks whether anything is in the way.
        let hit = intersect_scene(ray_origin, ray_direction, ray_t_max, shadow_pending, &stack_overflowed);
        //#if nee
        if shadow_pending {
            shadow_pending = false;
            if hit.kind == HIT_NONE {
                gather(&radiance, shadow.contribution, EVENT_LIGHT_SAMPLE);
            }
            sample_finished = path_ended;
            continue;
        }
        //#endif
        light_along_the_ray(&radiance, &throughput, hit, origin, direction, ray_t_max, bsdf_pdf, bounce, medium_absorption, medium_emission);
        if hit.kind == HIT_NONE {
            //#if transparent_film
            // Film › Transparent: the background the camera sees adds nothing, and the
            // sample counts as one that met nothing (the pixel's alpha is the share that met
            // the scene), also when it passed through stochastically transparent surfaces.
            if transparent_background {
                //#if aovs
                aov_background_seen(channel_mean(throughput), bounce == 0u);
                //#endif
                sample_finished = true;
                continue;
            }
            //#endif
            //#if sky_graph
            //#if node_graphs
            gather(&radiance, throughput * graph_sky_seen(origin, direction, bsdf_pdf, ray_from, ray_singular, bounce, kind_depths), EVENT_SKY);
            //#endif
            //#endif
            background_seen(&radiance, throughput, origin, direction, bsdf_pdf);
            sample_finished = true;
            continue;
        }
        //#if sky_atmosphere
        let air = atmosphere_segment(origin, direction, hit.t);
        gather(&radiance, throughput * air.radiance, EVENT_AIR);
        attenuate(&throughput, air.transmittance, EVENT_AIR);
        //#endif
        var surface = surface_at(hit, origin, direction);
        //#if textures
        cone_width += cone_spread * hit.t;
        //#endif
        var m = materials[surface.material];
        let seen = material_seen(&m, hit, surface, direction, cone_width, path_key, bounce, ray_from, ray_singular, kind_depths);
        surface.shading_normal = seen.shading_normal;
        //#if holdout
        let held_out = held_out_share(m, hit, transparent_background);
        if held_out > 0.0 {
            //#if aovs
            if transparent_background {
                aov_held_out(held_out * channel_mean(throughput));
            }
            //#endif
            throughput *= 1.0 - held_out;
            if held_out >= 1.0 {
                sample_finished = true;
                continue;
            }
        }
        //#endif
        //#if emission
        var coat_layer_normal = surface.shading_normal;
        //#if coat_normal
        coat_layer_normal = seen.coat_normal;
        //#endif
        let layer_side = select(-1.0, 1.0, dot(surface.geometric_normal, direction) < 0.0);
        let layers = mapped_layer_normals(m, surface.shading_normal, coat_layer_normal, layer_side);
        let emitted = throughput * emission_seen(m, hit, surface, layers, origin, direction, bsdf_pdf);
        gather(&radiance, emitted, EVENT_EMISSION);
        //#if aovs
        if bounce == 0u {
            aov_emission_seen(emitted);
        }
        //#endif
        //#endif
        if bounce >= frame.max_bounces {
            sample_finished = true;
            continue;
        }
        bounce++;
        // The viewer is outside when the ray meets the outward normal head on.
        let entering = dot(surface.geometric_normal, direction) < 0.0;
        let n_geometric = select(-surface.geometric_normal, surface.geometric_normal, entering);
        let n_shading = shading_normal_at(m, seen, hit, surface, direction, entering, n_geometric);
        let ctx = shading_context(m, n_shading, n_geometric, -direction, entering);
        //#if aovs
        if bounce == 1u {
            aov_diffuse_color_seen(ctx, throughput);
        }
        //#endif
        //#if nee
        shadow = direct_light(ctx, surface, n_geometric, medium_absorption, &rng);
        shadow.contribution *= throughput;
        shadow_pending = any(shadow.contribution != vec3f(0.0));
        //#endif
        var s = bsdf_sample(ctx, &rng);
        //#if closure_weights
        // The BSDF scaled by its material's closure weight (an Add Shader's halves), as the light sample is.
        s.weight *= m.closure_weight;
        //#endif
        //#if terminator_offset
        // Delta reflections (the other lobes' samples are weighed by `bsdf_eval`).
        if s.pdf == 0.0 && !s.transmitted {
            s.weight *= terminator_shift(dot(s.direction, n_shading));
        }
        //#endif
        //#if aovs
        aov_surface(s, n_shading);
        //#endif
        if !s.valid {
            path_ended = true;
        } else {
            attenuate(&throughput, s.weight, EVENT_LOBE + s.lobe);
            transparent_background = transparent_background && s.transmitted && is_clear_glass(m);
            bsdf_pdf = s.pdf;
            //#if node_graphs
            ray_from = s.lobe + 1u;
            ray_singular = s.pdf == 0.0;
            kind_depths += node_depth_step(s.lobe, s.transmitted);
            //#endif
            //#if media
            // Crossing into a material adds its medium, leaving subtracts it: nested media add up.
            if s.transmitted {
                let sign = select(-1.0, 1.0, entering);
                medium_absorption = max(medium_absorption + sign * m.absorption, vec3f(0.0));
                medium_emission = max(medium_emission + sign * m.volume_emission, vec3f(0.0));
            }
            //#endif
            if bounce > ROULETTE_START {
                path_ended = !survives_roulette(&throughput, &rng);
            }
            origin = offset_ray_origin(surface.position, surface.position_error, select(-n_geometric, n_geometric, dot(s.direction, n_geometric) > 0.0));
            direction = s.direction;
            path_t_max = INFINITY;
        }
        // The pending shadow ray, if any, is traced before the path ends.
        sample_finished = path_ended && !shadow_pending;
        continuing {
            if sample_finished {
                sample_finished = false;
                sample_done(pixel_index, sample_base, k, radiance, lanes);
                k = next_sample(k, pixel_index, lanes);
                starting = true;
            }
            break if starting && k >= frame.samples_per_dispatch;
        }
    }
}

// Adds sample `sample_index` of a pixel, of radiance `radiance`, to its running mean
// `acc`; a non-finite sample is dropped and counted in `bad` with the event `event`
// that first made it so. One sample at a time, in sample order, so that the result
// does not depend on how samples are split into dispatches or lanes.
fn accumulate(acc: ptr<function, vec4f>, bad: ptr<function, u32>, radiance: vec3f, event: u32, sample_index: u32) {
    // A non-finite sample would poison the pixel for good: drop it, count it, keep its cause.
    if !all_finite(radiance) {
        if (*bad & 0xffffffu) == 0u {
            *bad = event << 24u;
        }
        *bad = (*bad & 0xff000000u) | min((*bad & 0xffffffu) + 1u, 0xffffffu);
        return;
    }
    let c = clamped(radiance);
    let l = c.rgb;
    let y = c.w;
    let n = f32(sample_index + 1u - (*bad & 0xffffffu));
    let y_before = luminance((*acc).rgb);
    let mean = (*acc).rgb + (l - (*acc).rgb) / n;
    *acc = vec4f(mean, (*acc).w + (y - y_before) * (y - luminance(mean)));
}

// A finite sample's radiance scaled down to the clamp's luminance if it is over it, and
// its luminance after.
fn clamped(radiance: vec3f) -> vec4f {
    let y = luminance(radiance);
    if frame.clamp_luminance > 0.0 && y > frame.clamp_luminance {
        return vec4f(radiance * (frame.clamp_luminance / y), frame.clamp_luminance);
    }
    return vec4f(radiance, y);
}

// One invocation per pixel, taking the dispatch's samples one after another.
@compute @workgroup_size(8, 8)
fn render(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let pixel_index = id.y * frame.width + id.x;
    var sample_base = frame.sample_base;
    //#if adaptive
    // Pixels stop at different counts: each keeps its own.
    sample_base = pixel_samples[2u * pixel_index];
    if pixel_samples[2u * pixel_index + 1u] != 0u {
        return;
    }
    //#endif
    pixel_acc = accumulation[pixel_index];
    pixel_bad = non_finite[pixel_index];
    //#if aovs
    pixel_aovs = aov_load(pixel_index);
    //#endif
    trace_samples(id.xy, pixel_index, sample_base, 0u, false);
    accumulation[pixel_index] = pixel_acc;
    non_finite[pixel_index] = pixel_bad;
    //#if aovs
    aov_store(pixel_index, pixel_aovs);
    //#endif
    //#if adaptive
    pixel_samples[2u * pixel_index] = sample_base + frame.samples_per_dispatch;
    //#endif
}

//#include "sample_lanes.wgsl"
