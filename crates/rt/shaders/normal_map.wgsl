// Tangent-space normal maps (glTF `normalTexture`; Blender's Normal Map node in tangent
// space). A texel's RGB is a direction 2·RGB − 1 in the frame of the vertex tangent,
// the bitangent and the shading normal, as MikkTSpace defines it: tangent and normal
// interpolated across the triangle, bitangent = sign · normal × tangent, the mapped
// normal normalised only after the sum (so a map baked by any MikkTSpace tool
// reproduces its source). The frame is built in object space, as Cycles does, and the
// result is carried to the world as a normal: that is right under any instance
// transform, mirrors included.

//#include "common.wgsl"
//#include "hit.wgsl"
//#include "transform.wgsl"
//#include "motion.wgsl"
//#include "texture.wgsl"
//#include "valid_reflection.wgsl"

// The mapped normal of the last `normal_mapped` call before `valid_for_reflection` bent
// it (outward, world space): Cycles' Principled BSDF gives its diffuse lobe this one and
// only its glossy, metal and glass lobes the bent one (`maybe_ensure_valid_specular_reflection`
// in svm/closure.h).
var<private> unbent_mapped_normal: vec3f;

fn diffuse_mapped_normal() -> vec3f {
    return unbent_mapped_normal;
}

// The shading normal (outward, world space) at a hit, perturbed by the material's
// normal map, read at `uv` of the set it reads, whose tangents the triangle carries (see
// the cache's tangent section); unchanged where there is none, or no tangent to orient it by. The map is
// read at its finest level, whatever the ray cone: shading is not linear in the normal,
// and an averaged (shorter, flatter) normal would shade bumps away where many texels
// share a pixel. The pixel's samples do the averaging, as in Cycles.
// `wo` points to the viewer, `geometric_normal` is the surface's outward one.
fn normal_mapped(m: Material, hit: Hit, shading_normal: vec3f, geometric_normal: vec3f, wo: vec3f, uv: vec2f) -> vec3f {
    unbent_mapped_normal = shading_normal;
    let mapped = map_normal(m.normal_texture, m.normal_scale, hit, uv);
    if all(mapped == vec3f(0.0)) {
        return shading_normal;
    }
    return mapped_normal_bent(mapped, geometric_normal, wo);
}

// `mapped` (outward, world, unit: a map's or a Bump node's) kept for the diffuse lobe and
// returned bent as Cycles bends the specular lobes' normal (see `unbent_mapped_normal`).
fn mapped_normal_bent(mapped: vec3f, geometric_normal: vec3f, wo: vec3f) -> vec3f {
    unbent_mapped_normal = mapped;
    // Bent on the viewer's side, then turned back outward.
    let side = select(-1.0, 1.0, dot(geometric_normal, wo) >= 0.0);
    return side * valid_for_reflection(side * mapped, side * geometric_normal, wo);
}

// The normal (outward, world space, unit) that map `texture`, its x and y scaled by
// `scale`, gives at `hit`, read at `uv`; zero where it gives none: no map, not a
// triangle, no tangent to orient it by, or a texel that points nowhere.
fn map_normal(texture: u32, scale: f32, hit: Hit, uv: vec2f) -> vec3f {
    if texture == NO_TEXTURE || hit.kind != HIT_TRIANGLE {
        return vec3f(0.0);
    }
    let frame = tangent_frames[hit.primitive];
    let b0 = 1.0 - hit.b1 - hit.b2;
    let t = b0 * frame.t0 + hit.b1 * frame.t1 + hit.b2 * frame.t2;
    if dot(t.xyz, t.xyz) == 0.0 {
        return vec3f(0.0);
    }
    let sh = shading[hit.primitive];
    // Normalised: a mesh without normals stores its face normal unnormalised.
    let n = normalize(b0 * sh.n0 + hit.b1 * sh.n1 + hit.b2 * sh.n2);
    let bitangent = select(-1.0, 1.0, t.w >= 0.0) * cross(n, t.xyz);
    let c = sample_level(textures[texture], 0u, uv).rgb * 2.0 - 1.0;
    let mapped = (c.x * scale) * t.xyz + (c.y * scale) * bitangent + c.z * n;
    let world = transform_normal_to_world(instance_at(hit.instance).world_to_object, mapped);
    let length_squared = dot(world, world);
    // A texel of (0.5, 0.5, 0.5) or a NaN points nowhere: keep the interpolated normal.
    if !(length_squared > 0.0) {
        return vec3f(0.0);
    }
    return world * inverseSqrt(length_squared);
}

//#if coat_normal
// The coat's normal of the last `coat_normal_mapped` call before Bump Map Correction bent it
// (outward, world space).
var<private> unbent_coat_normal: vec3f;

fn coat_normal_before_bending() -> vec3f {
    return unbent_coat_normal;
}

// The coat's normal (outward, world space; see coat_normal.wgsl): its own map's, read at
// `uv`, or the interpolated `shading_normal` (never the base's map), bent by Bump Map
// Correction as Cycles bends it (`maybe_ensure_valid_specular_reflection`, which leaves a
// normal that already mirrors the view above the surface, a flat face's among them, as it is).
fn coat_normal_mapped(m: Material, hit: Hit, shading_normal: vec3f, geometric_normal: vec3f, wo: vec3f, uv: vec2f) -> vec3f {
    var n = map_normal(m.coat_normal_texture, m.coat_normal_scale, hit, uv);
    // An interpolated normal is bent in Cycles' model only (see smooth_shading.wgsl).
    var bent = any(n != vec3f(0.0));
    if !bent {
        n = shading_normal;
        //#if smooth_normals
        bent = true;
        //#endif
    }
    unbent_coat_normal = n;
    if !bent || m.bump_map_correction == 0u {
        return n;
    }
    let side = select(-1.0, 1.0, dot(geometric_normal, wo) >= 0.0);
    return side * valid_for_reflection(side * n, side * geometric_normal, wo);
}
//#endif
