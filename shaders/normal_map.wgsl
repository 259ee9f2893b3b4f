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
    if m.normal_texture == NO_TEXTURE || hit.kind != HIT_TRIANGLE {
        return shading_normal;
    }
    let frame = tangent_frames[hit.primitive];
    let b0 = 1.0 - hit.b1 - hit.b2;
    let t = b0 * frame.t0 + hit.b1 * frame.t1 + hit.b2 * frame.t2;
    if dot(t.xyz, t.xyz) == 0.0 {
        return shading_normal;
    }
    let sh = shading[hit.primitive];
    // Normalised: a mesh without normals stores its face normal unnormalised.
    let n = normalize(b0 * sh.n0 + hit.b1 * sh.n1 + hit.b2 * sh.n2);
    let bitangent = select(-1.0, 1.0, t.w >= 0.0) * cross(n, t.xyz);
    let c = sample_level(textures[m.normal_texture], 0u, uv).rgb * 2.0 - 1.0;
    let mapped = (c.x * m.normal_scale) * t.xyz + (c.y * m.normal_scale) * bitangent + c.z * n;
    let world = transform_normal_to_world(instances[hit.instance].world_to_object, mapped);
    let length_squared = dot(world, world);
    // A texel of (0.5, 0.5, 0.5) or a NaN points nowhere: keep the interpolated normal.
    if !(length_squared > 0.0) {
        return shading_normal;
    }
    unbent_mapped_normal = world * inverseSqrt(length_squared);
    // Bent on the viewer's side, then turned back outward.
    let side = select(-1.0, 1.0, dot(geometric_normal, wo) >= 0.0);
    return side * valid_for_reflection(side * unbent_mapped_normal, side * geometric_normal, wo);
}
