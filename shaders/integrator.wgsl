// The path-tracing megakernel: each dispatch adds `samples_per_dispatch` samples
// to every pixel's running mean, taken by one invocation per pixel (`render`) or,
// for small images, spread over several (`render_lanes`, then `reduce_lanes`, in
// sample_lanes.wgsl).

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "path.wgsl"
//#include "traverse.wgsl"
//#include "path_emission.wgsl"
//#include "path_surface.wgsl"
//#include "path_scatter.wgsl"
//#if adaptive
//#include "adaptive.wgsl"
//#endif
//#if exact_sums
//#include "exact_sums.wgsl"
//#endif

// rgb: the running mean of radiance; w: the running sum of squared deviations
// of luminance (Welford), for the standard error. Means rather than sums: a sum
// of finite samples can overflow.
@group(1) @binding(0) var<storage, read_write> accumulation: array<vec4f>;
// Per pixel: dropped non-finite samples (low 24 bits) and the event that
// produced the first one (top 8 bits).
@group(1) @binding(1) var<storage, read_write> non_finite: array<u32>;

// What a finished sample is added to: `render`'s pixel, read before its samples and
// written after them.
var<private> pixel_acc: vec4f;
var<private> pixel_bad: u32;
//#if aovs
var<private> pixel_aovs: AovMeans;
//#endif

// A finished sample `sample_base + k` of radiance `radiance` (`bad_event`: what first
// made it non-finite, if anything): into the pixel's running mean, or, for
// `render_lanes`, into slot k of `lane_samples` (its AOVs too, after the dispatch's
// radiance samples).
fn sample_done(pixel_index: u32, sample_base: u32, k: u32, radiance: vec3f, bad_event: u32, lanes: bool) {
    let sample_index = sample_base + k;
    if lanes {
        let slot = k * frame.width * frame.height + pixel_index;
        lane_samples[slot] = vec4f(radiance, bitcast<f32>(bad_event));
        //#if aovs
        aov_lane_store(slot);
        //#endif
        return;
    }
    // (WGSL passes function-space pointers only.)
    var acc = pixel_acc;
    var bad = pixel_bad;
    accumulate(&acc, &bad, radiance, bad_event, sample_index);
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
    var path: Path;
    // Set when the path has ended and its sample is to be added (in `continuing`).
    var sample_finished = false;
    var starting = true;
    // Set by the traversal when a stack was full (it counts that in `stats` itself).
    var stack_overflowed = false;
    loop {
        if starting {
            starting = false;
            path = path_from_camera(pixel, pixel_index, frame.first_sample + sample_base + k);
            //#if aovs
            aov_begin();
            //#endif
            //#if panorama
            if path.ended {
                sample_finished = true;
                continue;
            }
            //#endif
        }
        var ray_origin = path.origin;
        var ray_direction = path.direction;
        var ray_t_max = path.t_max;
        //#if nee
        if path.shadow_pending {
            ray_origin = path.shadow.origin;
            ray_direction = path.shadow.direction;
            ray_t_max = path.shadow.t_max;
        }
        //#endif
        //#if alpha_blend
        set_alpha_ray_key(pcg_hash(path.key ^ pcg_hash(2u * path.bounce + u32(path.shadow_pending))));
        //#endif
        // A shadow ray only asks whether anything is in the way.
        let hit = intersect_scene(ray_origin, ray_direction, ray_t_max, path.shadow_pending, &stack_overflowed);
        //#if nee
        if path.shadow_pending {
            path.shadow_pending = false;
            if hit.kind == HIT_NONE {
                gather(&path, path.shadow.contribution, EVENT_LIGHT_SAMPLE);
            }
            sample_finished = path.ended;
            continue;
        }
        //#endif
        light_on_the_way(&path, hit, ray_t_max);
        if hit.kind == HIT_NONE {
            escaped(&path);
            sample_finished = true;
            continue;
        }
        surface_hit(&path, hit);
        // The pending shadow ray, if any, is traced before the path ends.
        sample_finished = path.ended && !path.shadow_pending;
        continuing {
            if sample_finished {
                sample_finished = false;
                sample_done(pixel_index, sample_base, k, path.radiance, path.bad_event, lanes);
                k = next_sample(k, pixel_index, lanes);
                starting = true;
            }
            break if starting && k >= frame.samples_per_dispatch;
        }
    }
}

// The path at the surface its ray hit: a holdout may take all of it, the surface's
// emission is gathered, and unless the path is as long as allowed it scatters on, with
// a light sample for a shadow ray to test.
fn surface_hit(path: ptr<function, Path>, hit: Hit) {
    let at = shading_point(path, hit);
    //#if holdout
    if held_out(path, at, hit) {
        path.ended = true;
        return;
    }
    //#endif
    //#if emission
    surface_emission(path, at, hit);
    //#endif
    if path.bounce >= frame.max_bounces {
        path.ended = true;
        return;
    }
    path.bounce++;
    let sc = scattering_at(path, at, hit);
    //#if aovs
    if path.bounce == 1u {
        aov_diffuse_color_seen(sc.ctx, path.throughput);
    }
    //#endif
    //#if nee
    path.shadow = light_sample(path, at, sc);
    path.shadow_pending = any(path.shadow.contribution != vec3f(0.0));
    //#endif
    bsdf_scatter(path, at, sc);
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
