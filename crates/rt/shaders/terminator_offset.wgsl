// Blender's Shadow Terminator Shading Offset (Object > Shading), as Cycles applies it
// (`shift_cos_in` in kernel/closure/bsdf.h, after appleseed): every lobe of the object's
// surfaces, smooth-shaded or not, is multiplied where light arrives above the lobe's own
// normal by cos(k θ) / cos θ, with θ the angle to that normal and k the object's frequency
// multiplier 1 / (1 - offset / 2). Light fades out by θ = 90° / k rather than at the horizon,
// which hides the shading normals' terminator on low-poly meshes, and the surface looks
// darker and harder towards it. Densities are left alone (Cycles shifts only the values).

//#include "common.wgsl"
//#include "hit.wgsl"

// The shaded object's frequency multiplier; 1: no shift (spheres, and objects without an offset).
var<private> terminator_frequency: f32 = 1.0;

// Takes the settings of the object that `hit` is on, for the surface about to be shaded.
fn set_terminator_shift(hit: Hit) {
    terminator_frequency = 1.0;
    if hit.kind == HIT_TRIANGLE {
        terminator_frequency = object_settings[hit.instance].frequency_multiplier;
    }
}

// The factor on a lobe's value for light at `cos_i` to the lobe's normal: 1 below it
// (transmission) and without an offset.
fn terminator_shift(cos_i: f32) -> f32 {
    if terminator_frequency <= 1.0 || cos_i <= 0.0 {
        return 1.0;
    }
    let c = min(cos_i, 1.0);
    return max(cos(acos(c) * terminator_frequency), 0.0) / c;
}
