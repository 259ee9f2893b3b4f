// Motion blur, as Cycles blurs it: each sample has a time over the open shutter, at
// which every ray of its path sees the scene. The camera keeps its transforms at evenly
// spaced times (`scene::Motion`), each split into a translation, a unit quaternion and a
// stretch matrix; between the two keys about a time the rotation is slerped and the rest
// interpolated linearly (Cycles' `transform_motion_array_interpolate`). A moving instance
// keeps that motion sampled densely on the host, as world-to-object matrices that a ray
// meeting it interpolates linearly: the traversal stays light.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "rng.wgsl"
//#include "transform.wgsl"

// The time of the sample being traced, in [0, 1] over the open shutter (the shutter's
// middle for kernels that trace without samples).
var<private> motion_time: f32 = 0.5;

//#if motion
// A draw of its own for the time, outside the sample's sequence of draws, so that the
// other draws stay as they are: scrambled Sobol, stratified over the pixel's samples.
const TIME_DIMENSION: u32 = 0xffffu;

// Draws the time of the sample that `rng` draws for.
fn begin_sample_time(rng: ptr<function, Rng>) {
    motion_time = sobol_coordinate(sobol_draw_index(rng, TIME_DIMENSION), sobol_coordinate_seed(rng, TIME_DIMENSION));
}

// Where time `t` falls among `count` keys: the key before it and the fraction past it.
fn motion_step(count: u32, t: f32) -> vec2f {
    let last = f32(count - 1u);
    let step = min(floor(t * last), last - 1.0);
    return vec2f(step, t * last - step);
}
//#endif

//#if object_motion
// MotionMatrix: declared in src/layout.rs (GpuMotionMatrix).
//#include "MotionMatrix.struct.wgsl"

//#include "motion.bindings.wgsl"


// Instance motion `motion` (first matrix << 8 | count) at the sample's time: world-to-object rows.
fn instance_motion_now(motion: u32) -> array<vec4f, 3> {
    let at = motion_step(motion & 0xffu, motion_time);
    let first = (motion >> 8u) + u32(at.x);
    let a = motion_matrices[first].world_to_object;
    let b = motion_matrices[first + 1u].world_to_object;
    return array<vec4f, 3>(mix(a[0], b[0], at.y), mix(a[1], b[1], at.y), mix(a[2], b[2], at.y));
}
//#endif

//#if camera_motion
// Cycles' `quat_interpolate` (keys are stored on one side of the sphere).
fn slerp(a: vec4f, b: vec4f, t: f32) -> vec4f {
    let cos_theta = dot(a, b);
    if cos_theta > 0.9995 {
        return normalize(mix(a, b, t));
    }
    let theta = acos(clamp(cos_theta, -1.0, 1.0));
    let perpendicular = normalize(b - a * cos_theta);
    return a * cos(theta * t) + perpendicular * sin(theta * t);
}

// The object-to-world rows between keys `a` and `b`, a fraction `f` of the way: R·S with
// R the slerped rotation and S the interpolated stretch (written out, without arrays
// indexed at run time, to keep the traversal's registers few).
fn motion_between(a: MotionKey, b: MotionKey, f: f32) -> array<vec4f, 3> {
    let q = slerp(a.rotation, b.rotation, f);
    let xx = mix(a.stretch_xx, b.stretch_xx, f);
    let sa = mix(a.stretch_a, b.stretch_a, f);
    let sb = mix(a.stretch_b, b.stretch_b, f);
    let s0 = vec3f(xx, sa.xy);
    let s1 = vec3f(sa.zw, sb.x);
    let s2 = sb.yzw;
    let t = mix(a.translation, b.translation, f);
    let r0 = vec3f(1.0 - 2.0 * (q.y * q.y + q.z * q.z), 2.0 * (q.x * q.y - q.w * q.z), 2.0 * (q.x * q.z + q.w * q.y));
    let r1 = vec3f(2.0 * (q.x * q.y + q.w * q.z), 1.0 - 2.0 * (q.x * q.x + q.z * q.z), 2.0 * (q.y * q.z - q.w * q.x));
    let r2 = vec3f(2.0 * (q.x * q.z - q.w * q.y), 2.0 * (q.y * q.z + q.w * q.x), 1.0 - 2.0 * (q.x * q.x + q.y * q.y));
    return array<vec4f, 3>(
        vec4f(r0.x * s0 + r0.y * s1 + r0.z * s2, t.x),
        vec4f(r1.x * s0 + r1.y * s1 + r1.z * s2, t.y),
        vec4f(r2.x * s0 + r2.y * s1 + r2.z * s2, t.z),
    );
}

// The camera's frame at the sample's time (columns right, up, forward and position).
fn camera_motion_now() -> array<vec4f, 3> {
    let at = motion_step(frame.camera_motion_steps, motion_time);
    let k = u32(at.x);
    return motion_between(frame.camera_motion[k], frame.camera_motion[k + 1u], at.y);
}
//#endif

// Instance `index` as the sample sees it: with its world-to-object matrix at the sample's time.
fn instance_at(index: u32) -> Instance {
    var inst = instances[index];
    //#if object_motion
    if bitcast<u32>(inst.world_to_object[0].x) == MOVING_INSTANCE {
        inst.world_to_object = instance_motion_now(bitcast<u32>(inst.world_to_object[0].y));
    }
    //#endif
    return inst;
}
