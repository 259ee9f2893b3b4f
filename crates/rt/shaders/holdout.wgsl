// Blender's holdouts, as Cycles renders them (`integrate_surface_holdout`): a camera path
// that meets a held-out surface before it scatters (but through alpha, or clear glass with
// Film › Transparent Glass) leaves that share of the pixel
// uncovered (its alpha) and black. An object's or collection's Holdout holds out the whole
// object for those paths only: reflections, shadows and light bounced from it stay. A
// Holdout shader (or a Mix Shader's share of one) holds out its share for every path: any
// other ray finds that share absorbed, as Cycles' closure does.

//#include "common.wgsl"
//#include "hit.wgsl"

// The share of the light arriving at `hit` (a surface of material `m`) that is held out,
// for a path that has (`camera_path`) or has not yet scattered but through what lets the
// background through.
fn held_out_share(m: Material, hit: Hit, camera_path: bool) -> f32 {
    if camera_path && hit.kind == HIT_TRIANGLE && (object_settings[hit.instance].holdout_and_index & 1u) != 0u {
        return 1.0;
    }
    return m.holdout;
}
