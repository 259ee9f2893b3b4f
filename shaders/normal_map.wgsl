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

// The shading normal (outward, world space) at a hit, perturbed by the material's
// normal map; unchanged where there is none, or no tangent to orient it by.
fn normal_mapped(m: Material, hit: Hit, shading_normal: vec3f, p: TexturePoint, lod: f32) -> vec3f {
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
    let c = sample_texture(m.normal_texture, p.uv, lod).rgb * 2.0 - 1.0;
    let mapped = (c.x * m.normal_scale) * t.xyz + (c.y * m.normal_scale) * bitangent + c.z * n;
    let world = transform_normal_to_world(instances[hit.instance].world_to_object, mapped);
    let length_squared = dot(world, world);
    // A texel of (0.5, 0.5, 0.5) or a NaN points nowhere: keep the interpolated normal.
    if !(length_squared > 0.0) {
        return shading_normal;
    }
    return world * inverseSqrt(length_squared);
}
