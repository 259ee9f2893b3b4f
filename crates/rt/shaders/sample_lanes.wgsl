// Small images spread over lanes: several invocations per pixel (`render_lanes`), whose
// samples `reduce_lanes` adds up in sample order. Part of the integrator, included at the
// end of integrator.wgsl: it uses its `frame`, `accumulation`, `non_finite`,
// `trace_samples` and `accumulate`.

// Samples of small images spread over lanes, before `reduce_lanes` adds them up.
@group(1) @binding(2) var<storage, read_write> lane_samples: array<vec4f>;
// Per pixel: the chunks of its samples its lanes have claimed beyond their first (zeroed
// before each dispatch of `render_lanes`).
@group(1) @binding(5) var<storage, read_write> lane_chunks: array<atomic<u32>>;

// How `render_lanes` shares a pixel's samples among its lanes, so that none waits long
// for the others at the end of a dispatch: in chunks of `lane_chunk` samples, lane z
// taking chunk z first, then the next unclaimed chunk from the pixel's counter, until
// they run out or it has taken `lane_budget` chunks. The budget bounds an invocation's
// loop (lavapipe drops the turns past its limit, see src/render/accumulation.rs); as it
// is at least the lanes' fair share, the lanes together always take every chunk.
// Which invocation takes a sample does not change it: the image stays bit for bit.
var<private> lane_count: u32;
var<private> lane_chunk: u32;
var<private> lane_budget: u32;
var<private> lane_chunks_taken: u32;

// Chunks per lane aimed at: many, so that the lanes finish close together (the choice is
// measured in docs/measured-choices.md).
const CHUNKS_PER_LANE: u32 = 32u;

// The sample after `k` of this invocation: `k + 1` within its chunk (or for `render`,
// which takes all), else the first of the next chunk it claims; past the dispatch's
// count when there is none.
fn next_sample(k: u32, pixel_index: u32, lanes: bool) -> u32 {
    let next = k + 1u;
    if !lanes || next % lane_chunk != 0u {
        return next;
    }
    lane_chunks_taken += 1u;
    if lane_chunks_taken >= lane_budget {
        return frame.samples_per_dispatch;
    }
    return (atomicAdd(&lane_chunks[pixel_index], 1u) + lane_count) * lane_chunk;
}

// Small images leave most of a GPU idle with one invocation per pixel: there, each
// pixel's samples are spread over the dispatch's z lanes (shared in chunks, see
// `next_sample`), written to `lane_samples` (radiance, and the event of a non-finite one
// in w) and added up in sample order by `reduce_lanes`, so that the image is the same bit
// for bit as `render`'s; so are the AOVs, whose samples wait beside the radiance's. Under
// adaptive sampling too: both skip stopped pixels and number samples by the pixel's own
// count, which `reduce_lanes` advances.
@compute @workgroup_size(8, 8)
fn render_lanes(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let pixel_index = id.y * frame.width + id.x;
    var sample_base = frame.sample_base;
    //#if adaptive
    // As in `render`: a stopped pixel takes no samples, the others count their own.
    if pixel_samples[2u * pixel_index + 1u] != 0u {
        return;
    }
    sample_base = pixel_samples[2u * pixel_index];
    //#endif
    let samples = frame.samples_per_dispatch;
    lane_count = groups.z;
    lane_chunk = max(1u, samples / (lane_count * CHUNKS_PER_LANE));
    let chunks = (samples + lane_chunk - 1u) / lane_chunk;
    lane_budget = 2u * ((chunks + lane_count - 1u) / lane_count);
    lane_chunks_taken = 0u;
    trace_samples(id.xy, pixel_index, sample_base, id.z * lane_chunk, true);
}

//#if aovs
// The AOVs' running means of the pixel `reduce_lanes` adds up.
var<private> reduced_aovs: AovMeans;
//#endif

// Adds the lanes' sample `index` (`sample`, from `slot`) to the pixel's mean, and its
// AOVs in the same order and by the same sums as `render` adds them; and to the exact
// sums, which only this kernel keeps: a render that asks for them takes its samples
// through the lanes' scratch, one lane or more, so that the integer adds stay out of
// the loop that traces paths.
fn reduce_sample(acc: ptr<function, vec4f>, bad: ptr<function, u32>, sample: vec4f, slot: u32, index: u32) {
    accumulate(acc, bad, sample.xyz, bitcast<u32>(sample.w), index);
    //#if exact_sums
    let pixel_index = slot % (frame.width * frame.height);
    if all_finite(sample.xyz) {
        let c = clamped(sample.xyz);
        exact_add_radiance(pixel_index, c.rgb, c.w);
    }
    //#endif
    //#if aovs
    aov_lane_load(slot);
    var aovs = reduced_aovs;
    aov_add(&aovs, index);
    reduced_aovs = aovs;
    //#if exact_sums
    exact_add_aovs(pixel_index, aov_sums());
    //#endif
    //#endif
}

@compute @workgroup_size(8, 8)
fn reduce_lanes(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let pixel_index = id.y * frame.width + id.x;
    let pixels = frame.width * frame.height;
    var sample_base = frame.sample_base;
    //#if adaptive
    // The stop marks are those `render_lanes` read: `adaptive_mask` ran before both.
    if pixel_samples[2u * pixel_index + 1u] != 0u {
        return;
    }
    sample_base = pixel_samples[2u * pixel_index];
    //#endif
    var acc = accumulation[pixel_index];
    var bad = non_finite[pixel_index];
    //#if aovs
    reduced_aovs = aov_load(pixel_index);
    //#endif
    // Four samples are loaded ahead of their adds: the adds wait on each other, the loads
    // do not, and one invocation per pixel is too few to hide a load's latency otherwise.
    let n = frame.samples_per_dispatch;
    var s = 0u;
    for (; s + 4u <= n; s += 4u) {
        let slot = s * pixels + pixel_index;
        let a = lane_samples[slot];
        let b = lane_samples[slot + pixels];
        let c = lane_samples[slot + 2u * pixels];
        let d = lane_samples[slot + 3u * pixels];
        reduce_sample(&acc, &bad, a, slot, sample_base + s);
        reduce_sample(&acc, &bad, b, slot + pixels, sample_base + s + 1u);
        reduce_sample(&acc, &bad, c, slot + 2u * pixels, sample_base + s + 2u);
        reduce_sample(&acc, &bad, d, slot + 3u * pixels, sample_base + s + 3u);
    }
    for (; s < n; s++) {
        let slot = s * pixels + pixel_index;
        reduce_sample(&acc, &bad, lane_samples[slot], slot, sample_base + s);
    }
    accumulation[pixel_index] = acc;
    non_finite[pixel_index] = bad;
    //#if aovs
    aov_store(pixel_index, reduced_aovs);
    //#endif
    //#if adaptive
    pixel_samples[2u * pixel_index] = sample_base + frame.samples_per_dispatch;
    //#endif
}
