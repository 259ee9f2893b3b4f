// The scene's image textures: every texel of every texture, mip levels included, in
// one storage buffer of packed RGBA8 (no binding arrays: lavapipe has none), and a
// table of where each texture lies (`Texture` in common.wgsl). Filtering is bilinear
// within a level and linear between two levels, on the stored values: a colour
// texture's sRGB codes are filtered and then decoded, once, as Cycles does with 8-bit
// images (its mips are averaged in linear light on the host). The level comes from a ray cone's
// footprint (Akenine-Möller et al., Ray Tracing Gems ch. 20): log2 of the cone's width
// over |cos| at the hit, plus the triangle's texture-to-world density.

//#include "common.wgsl"
//#include "hit.wgsl"
//#include "transform.wgsl"
//#include "motion.wgsl"
//#include "rng.wgsl"
//#include "reflectance.wgsl"
//#include "srgb.wgsl"

// TEXTURE_SRGB, TEXTURE_CLOSEST, TEXTURE_WRAP_*, WRAP_* and UV1_* are shared constants
// (src/shared_constants.rs).

struct TexturePoint {
    uv: vec2f,
    // log2 √(texture-space area / world-space area) of the triangle, texture space
    // counted in whole textures: a texture adds log2 √(width·height) to it.
    uv_lod: f32,
    //#if uv_sets
    // The same of the second uv set.
    second_uv: vec2f,
    second_uv_lod: f32,
    //#endif
}

// A triangle's texture coordinates in set 0 or (scenes with uv_sets) set 1.
fn triangle_uvs(triangle: u32, uv_set: u32) -> array<vec2f, 3> {
    //#if uv_sets
    if uv_set == 1u {
        let s = second_uvs[triangle];
        return array<vec2f, 3>(s.uv0, s.uv1, s.uv2);
    }
    //#endif
    let sh = shading[triangle];
    return array<vec2f, 3>(vec2f(sh.u0, sh.v.x), vec2f(sh.u1, sh.v.y), vec2f(sh.u2, sh.v.z));
}

fn triangle_uv(triangle: u32, uv_set: u32, b1: f32, b2: f32) -> vec2f {
    let uv = triangle_uvs(triangle, uv_set);
    return (1.0 - b1 - b2) * uv[0] + b1 * uv[1] + b2 * uv[2];
}

// The set that slot `bit` (UV1_*) of material `m` reads.
fn uv_set_of(m: Material, bit: u32) -> u32 {
    return select(0u, 1u, (m.second_uv_set & bit) != 0u);
}

// log2 √(texture-space area / world-space area) of uvs `uv` on a triangle of world area `world_area`.
fn uv_density_lod(uv: array<vec2f, 3>, world_area: f32) -> f32 {
    let d1 = uv[1] - uv[0];
    let d2 = uv[2] - uv[0];
    return 0.5 * log2(abs(d1.x * d2.y - d1.y * d2.x) / world_area);
}

fn texture_point(hit: Hit) -> TexturePoint {
    var p: TexturePoint;
    if hit.kind != HIT_TRIANGLE {
        return p;
    }
    let tri = triangles[hit.primitive];
    let to_world = affine_inverse(instance_at(hit.instance).world_to_object).m;
    let world_area = length(cross(transform_vector(to_world, tri.v1 - tri.v0), transform_vector(to_world, tri.v2 - tri.v0)));
    p.uv = triangle_uv(hit.primitive, 0u, hit.b1, hit.b2);
    p.uv_lod = uv_density_lod(triangle_uvs(hit.primitive, 0u), world_area);
    //#if uv_sets
    p.second_uv = triangle_uv(hit.primitive, 1u, hit.b1, hit.b2);
    p.second_uv_lod = uv_density_lod(triangle_uvs(hit.primitive, 1u), world_area);
    //#endif
    return p;
}

// Whether any texture slot of `m` is in use (the normal map's and the layered lobes' included).
fn has_textures(m: Material) -> bool {
    var any = m.base_color_texture != NO_TEXTURE || m.metallic_roughness_texture != NO_TEXTURE
        || m.emission_texture != NO_TEXTURE || m.normal_texture != NO_TEXTURE;
    //#if layer_textures
    any = any || m.coat_texture != NO_TEXTURE || m.coat_roughness_texture != NO_TEXTURE
        || m.coat_tint_texture != NO_TEXTURE || m.sheen_texture != NO_TEXTURE
        || m.sheen_tint_texture != NO_TEXTURE || m.anisotropy_texture != NO_TEXTURE
        || m.specular_tint_texture != NO_TEXTURE || m.diffuse_roughness_texture != NO_TEXTURE
        || m.thin_film_texture != NO_TEXTURE || m.transmission_texture != NO_TEXTURE
        || m.specular_level_texture != NO_TEXTURE || m.ior_texture != NO_TEXTURE;
    //#endif
    //#if coat_normal
    any = any || m.coat_normal_texture != NO_TEXTURE;
    //#endif
    //#if node_graphs
    // A Mix Shader's second material may read textures the first does not.
    any = any || m.mix_material != NO_MATERIAL;
    //#endif
    return any;
}

// Slot `bit` (UV1_*) of `m` at `p`: its coordinates and the level of detail `footprint_lod` adds to.
fn slot_uv(m: Material, bit: u32, p: TexturePoint) -> vec2f {
    //#if uv_sets
    if (m.second_uv_set & bit) != 0u {
        return p.second_uv;
    }
    //#endif
    return p.uv;
}

fn slot_lod(m: Material, bit: u32, p: TexturePoint, footprint_lod: f32) -> f32 {
    //#if uv_sets
    if (m.second_uv_set & bit) != 0u {
        return p.second_uv_lod + footprint_lod;
    }
    //#endif
    return p.uv_lod + footprint_lod;
}

// Brings a coordinate into one period of its wrap mode, so that texel indices stay small.
fn wrap_coordinate(u: f32, mode: u32) -> f32 {
    if mode == WRAP_CLAMP {
        return clamp(u, 0.0, 1.0);
    }
    if mode == WRAP_MIRROR {
        return u - 2.0 * floor(u * 0.5);
    }
    return u - floor(u);
}

fn wrap_texel(i: i32, size: i32, mode: u32) -> i32 {
    if mode == WRAP_CLAMP {
        return clamp(i, 0, size - 1);
    }
    if mode == WRAP_MIRROR {
        let period = 2 * size;
        let j = ((i % period) + period) % period;
        return select(j, period - 1 - j, j >= size);
    }
    return ((i % size) + size) % size;
}

fn fetch_texel(level_offset: u32, width: u32, x: i32, y: i32) -> vec4f {
    return unpack4x8unorm(texels[level_offset + u32(y) * width + u32(x)]);
}

// What a texture's stored (filtered) values mean: colour in linear light, or data.
fn decoded(t: Texture, c: vec4f) -> vec4f {
    if (t.flags & TEXTURE_SRGB) != 0u {
        return vec4f(srgb_to_linear(c.rgb), c.a);
    }
    return c;
}

// Bilinear filtering of the stored values within one mip level (rows from the top; v
// from the bottom).
fn filter_level(t: Texture, level: u32, uv: vec2f) -> vec4f {
    var offset = t.offset;
    var w = t.width;
    var h = t.height;
    for (var l = 0u; l < level; l++) {
        offset += w * h;
        w = max(w / 2u, 1u);
        h = max(h / 2u, 1u);
    }
    let wrap_u = (t.flags >> TEXTURE_WRAP_U_SHIFT) & TEXTURE_WRAP_MASK;
    let wrap_v = (t.flags >> TEXTURE_WRAP_V_SHIFT) & TEXTURE_WRAP_MASK;
    let x = wrap_coordinate(uv.x, wrap_u) * f32(w) - 0.5;
    let y = (1.0 - wrap_coordinate(uv.y, wrap_v)) * f32(h) - 0.5;
    let x0 = floor(x);
    let y0 = floor(y);
    let f = vec2f(x - x0, y - y0);
    let size = vec2i(i32(w), i32(h));
    let xa = wrap_texel(i32(x0), size.x, wrap_u);
    let xb = wrap_texel(i32(x0) + 1, size.x, wrap_u);
    let ya = wrap_texel(i32(y0), size.y, wrap_v);
    let yb = wrap_texel(i32(y0) + 1, size.y, wrap_v);
    let top = mix(fetch_texel(offset, w, xa, ya), fetch_texel(offset, w, xb, ya), f.x);
    let bottom = mix(fetch_texel(offset, w, xa, yb), fetch_texel(offset, w, xb, yb), f.x);
    return mix(top, bottom, f.y);
}

// The texel of the full-size image that `uv` falls in (Blender's Closest interpolation,
// Cycles' `interp_closest`): no filtering, no mip level.
fn closest_texel(t: Texture, uv: vec2f) -> vec4f {
    let wrap_u = (t.flags >> TEXTURE_WRAP_U_SHIFT) & TEXTURE_WRAP_MASK;
    let wrap_v = (t.flags >> TEXTURE_WRAP_V_SHIFT) & TEXTURE_WRAP_MASK;
    let x = floor(wrap_coordinate(uv.x, wrap_u) * f32(t.width));
    let y = floor((1.0 - wrap_coordinate(uv.y, wrap_v)) * f32(t.height));
    let size = vec2i(i32(t.width), i32(t.height));
    return fetch_texel(t.offset, t.width, wrap_texel(i32(x), size.x, wrap_u), wrap_texel(i32(y), size.y, wrap_v));
}

// Where texture `t` reads its image at the uv set's coordinates `uv`: its own uv transform
// (a texture reference's KHR_texture_transform, a Blender Mapping node) applied.
fn texture_uv(t: Texture, uv: vec2f) -> vec2f {
    let p = vec3f(uv, 1.0);
    return vec2f(dot(t.u_row.xyz, p), dot(t.v_row.xyz, p));
}

// One mip level, bilinear (or the closest texel), decoded, at the uv set's coordinates `uv`.
fn sample_level(t: Texture, level: u32, uv: vec2f) -> vec4f {
    if (t.flags & TEXTURE_CLOSEST) != 0u {
        return decoded(t, closest_texel(t, texture_uv(t, uv)));
    }
    return decoded(t, filter_level(t, level, texture_uv(t, uv)));
}

// Texture `index` at the uv set's coordinates `set_uv`, filtered over a footprint of level
// `lod` there (see the top); the transform's scale widens the footprint in the image.
fn sample_texture(index: u32, set_uv: vec2f, lod: f32) -> vec4f {
    let t = textures[index];
    let uv = texture_uv(t, set_uv);
    if (t.flags & TEXTURE_CLOSEST) != 0u {
        return decoded(t, closest_texel(t, uv));
    }
    var lambda = min(lod + t.transform_lod + 0.5 * log2(f32(t.width) * f32(t.height)), f32(t.levels - 1u));
    // Also catches a NaN level, from a triangle whose texture coordinates are all alike.
    if !(lambda > 0.0) {
        lambda = 0.0;
    }
    let fine = u32(lambda);
    let coarse_weight = lambda - f32(fine);
    let a = filter_level(t, fine, uv);
    if coarse_weight <= 0.0 || fine + 1u >= t.levels {
        return decoded(t, a);
    }
    return decoded(t, mix(a, filter_level(t, fine + 1u, uv), coarse_weight));
}

// The material at a point, its textures applied; `footprint_lod` is log2 of the ray
// cone's width over |cos| there.
fn textured_material(material: Material, p: TexturePoint, footprint_lod: f32) -> Material {
    var m = material;
    if m.base_color_texture != NO_TEXTURE {
        let lod = slot_lod(m, UV1_BASE_COLOR, p, footprint_lod);
        m.base_color *= sample_texture(m.base_color_texture, slot_uv(m, UV1_BASE_COLOR, p), lod).rgb;
    }
    if m.metallic_roughness_texture != NO_TEXTURE {
        // glTF's packing: G roughness, B metal. The host's lobe weights are the non-metal part's.
        // Read at the finest level, bilinear, whatever the ray cone (as Cycles reads every
        // image): the shaded result is not linear in roughness, so a mip's mean roughness
        // does not give the mean of the lobes it stands for; and the cone's isotropic level
        // (width over |cos|) blurs far past the pixel across the view at grazing angles:
        // at the silhouette of a sphere striped in metal and diffuse, the mip's half-metal
        // lit the metal's edge with diffuse sunlight, 1.4% (9.6 σ) over Cycles on an 8×8
        // block. The pixel's samples do the averaging, as in Cycles.
        let mr = sample_level(textures[m.metallic_roughness_texture], 0u, slot_uv(m, UV1_METALLIC_ROUGHNESS, p));
        let metal = m.metallic * mr.b;
        let dielectric = 1.0 - metal;
        m.diffuse *= dielectric;
        m.specular *= dielectric;
        m.transmission *= dielectric;
        m.reflection = metal;
        let roughness = m.roughness * mr.g;
        m.alpha = roughness * roughness;
    }
    if m.emission_texture != NO_TEXTURE {
        let lod = slot_lod(m, UV1_EMISSION, p, footprint_lod);
        m.emission *= sample_texture(m.emission_texture, slot_uv(m, UV1_EMISSION, p), lod).rgb;
    }
    //#if layer_textures
    //#if uv_sets
    m = layer_textured(m, p.uv, p.second_uv);
    //#else
    m = layer_textured(m, p.uv, p.uv);
    //#endif
    //#endif
    return m;
}

//#if layer_textures
// Texture `index` of slot `bit` (UV1_*) of `m` at `uv` (of the first set) or `second_uv`, at
// its finest level, whatever the ray cone: these parameters shade non-linearly (a rotation,
// a roughness, an amount of stretch), so a filtered (averaged) texel would shade otherwise
// than the texels it averages. The pixel's samples do the averaging, as in Cycles, which
// reads them without mip levels; as normal maps are read.
fn layer_texel(m: Material, index: u32, bit: u32, uv: vec2f, second_uv: vec2f) -> vec4f {
    return sample_level(textures[index], 0u, select(uv, second_uv, (m.second_uv_set & bit) != 0u));
}

// The coat, sheen, anisotropy, specular tint, diffuse roughness, film thickness, transmission
// and specular level textures
// applied at the texture coordinates `uv` and `second_uv` (the second set's, or anything
// without `uv_sets`): texels times the factors (Principled's sockets fed by an image; glTF's
// clearcoat textures), the film's thickness between its minimum and maximum (glTF's
// iridescence thickness texture).
fn layer_textured(material: Material, uv: vec2f, second_uv: vec2f) -> Material {
    var m = material;
    if m.coat_texture != NO_TEXTURE {
        m.coat *= layer_texel(m, m.coat_texture, UV1_COAT, uv, second_uv).r;
    }
    if m.coat_roughness_texture != NO_TEXTURE {
        // α is the square of the (perceptual) roughness that the texel scales.
        let g = layer_texel(m, m.coat_roughness_texture, UV1_COAT_ROUGHNESS, uv, second_uv).g;
        m.coat_alpha *= g * g;
    }
    if m.coat_tint_texture != NO_TEXTURE {
        m.coat_tint *= layer_texel(m, m.coat_tint_texture, UV1_COAT_TINT, uv, second_uv).rgb;
    }
    if m.sheen_texture != NO_TEXTURE {
        let t = layer_texel(m, m.sheen_texture, UV1_SHEEN, uv, second_uv);
        m.sheen *= t.r;
        m.sheen_roughness = clamp(m.sheen_roughness * t.g, 1e-3, 1.0);
    }
    if m.sheen_tint_texture != NO_TEXTURE {
        m.sheen_tint *= layer_texel(m, m.sheen_tint_texture, UV1_SHEEN_TINT, uv, second_uv).rgb;
    }
    if m.anisotropy_texture != NO_TEXTURE {
        let t = layer_texel(m, m.anisotropy_texture, UV1_ANISOTROPY, uv, second_uv);
        if m.anisotropy_directions != 0u {
            // Filtered as directions, then turned into a rotation (as Blender's import of
            // glTF's texture does, with an arc tangent node after the image).
            let d = t.rg * 2.0 - 1.0;
            m.anisotropy *= t.b;
            if dot(d, d) > 0.0 {
                m.anisotropy_rotation += atan2(d.y, d.x) / (2.0 * PI);
            }
        } else {
            m.anisotropy *= t.r;
            m.anisotropy_rotation += t.g;
        }
    }
    if m.specular_tint_texture != NO_TEXTURE {
        m.specular_tint *= layer_texel(m, m.specular_tint_texture, UV1_SPECULAR_TINT, uv, second_uv).rgb;
    }
    if m.diffuse_roughness_texture != NO_TEXTURE {
        m.diffuse_roughness *= layer_texel(m, m.diffuse_roughness_texture, UV1_DIFFUSE_ROUGHNESS, uv, second_uv).r;
    }
    if m.thin_film_texture != NO_TEXTURE {
        let g = layer_texel(m, m.thin_film_texture, UV1_THIN_FILM, uv, second_uv).g;
        m.thin_film_thickness = mix(m.thin_film_minimum, m.thin_film_thickness, g);
    }
    if m.transmission_texture != NO_TEXTURE {
        // Principled's Transmission Weight mixes the glass in for the diffuse and the
        // dielectric layer over it, the part that is not metal (which the weights hold).
        let t = m.transmission_factor * layer_texel(m, m.transmission_texture, UV1_TRANSMISSION, uv, second_uv).r;
        m.transmission = m.diffuse * t;
        m.diffuse *= 1.0 - t;
        m.specular *= 1.0 - t;
    }
    if m.ior_texture != NO_TEXTURE {
        // Principled's IOR, Coat IOR and Thin Film IOR, each between its value at 0 and the
        // material's own at 1. The dielectric layer's F0 keeps its IOR Level's scale of the
        // new index's F0 (before the level's own texture below).
        let t = layer_texel(m, m.ior_texture, UV1_IOR, uv, second_uv);
        let f0 = fresnel_dielectric_f0(m.ior);
        m.ior = mix(m.ior_minimum, m.ior, t.r);
        if m.coating_eta > 0.0 && f0 > 0.0 {
            m.coating_f0 = min(m.coating_f0 / f0 * fresnel_dielectric_f0(m.ior), 0.9999);
            m.coating_eta = ior_from_f0(m.coating_f0);
        }
        m.coat_ior = mix(m.coat_ior_minimum, m.coat_ior, t.g);
        m.thin_film_ior = mix(m.thin_film_ior_minimum, m.thin_film_ior, t.b);
    }
    if m.specular_level_texture != NO_TEXTURE && m.coating_eta > 0.0 {
        // Cycles' IOR Level scales the layer's F0 (2 × level × F0 of the IOR), and the
        // layer's index is the one of that F0.
        let level = layer_texel(m, m.specular_level_texture, UV1_SPECULAR_LEVEL, uv, second_uv).a;
        m.coating_f0 = min(m.coating_f0 * level, 0.9999);
        m.coating_eta = ior_from_f0(m.coating_f0);
    }
    return m;
}

// `layer_textured` at barycentrics (b1, b2) of a triangle: for a light sample (the coat and
// sheen over an emitter dim it).
fn layer_textured_at(m: Material, triangle: u32, b1: f32, b2: f32) -> Material {
    let uv = triangle_uv(triangle, 0u, b1, b2);
    //#if uv_sets
    return layer_textured(m, uv, triangle_uv(triangle, 1u, b1, b2));
    //#else
    return layer_textured(m, uv, uv);
    //#endif
}
//#endif

// The emission of an emissive triangle at barycentrics (b1, b2), at the finest level
// (a light sample has no footprint).
fn textured_emission(m: Material, triangle: u32, b1: f32, b2: f32) -> vec3f {
    if m.emission_texture == NO_TEXTURE {
        return m.emission;
    }
    let uv = triangle_uv(triangle, uv_set_of(m, UV1_EMISSION), b1, b2);
    return m.emission * sample_level(textures[m.emission_texture], 0u, uv).rgb;
}

//#if alpha_mask
// Whether a candidate hit on a triangle is there at all: where the opacity (base
// alpha × the base colour texture's alpha) is below the material's cutoff, every ray,
// shadow rays included, passes through. At the finest level, so that the cut's shape
// does not change with distance.
fn opaque_at(inst: Instance, triangle: u32, b1: f32, b2: f32) -> bool {
    var material = inst.material_override;
    if material == NO_MATERIAL {
        material = inst.material_base + triangles[triangle].material;
    }
    let m = materials[material];
    if m.alpha_cutoff == 0.0 {
        return true;
    }
    var alpha = m.base_alpha;
    if m.base_color_texture != NO_TEXTURE {
        let uv = triangle_uv(triangle, uv_set_of(m, UV1_BASE_COLOR), b1, b2);
        alpha *= sample_level(textures[m.base_color_texture], 0u, uv).a;
    }
    //#if alpha_blend
    if m.alpha_cutoff < 0.0 {
        return alpha_coin(triangle) < alpha;
    }
    //#endif
    return alpha >= m.alpha_cutoff;
}
//#endif

//#if alpha_blend
// Stochastic transparency (glTF BLEND): a blended surface is there for a ray with
// probability equal to its opacity, so that the converged image is the opacity-weighted
// mix of the surface and what lies behind it, in shadows too. The coin is a hash of the
// ray (`alpha_ray_key`: pixel, sample, bounce and kind of ray, set by the integrator)
// and the triangle, not a draw from the path's random stream: the traversal may test
// one triangle more than once (in several leaves), and must get the same answer.
var<private> alpha_ray_key: u32;

fn set_alpha_ray_key(key: u32) {
    alpha_ray_key = key;
}

fn alpha_coin(triangle: u32) -> f32 {
    return f32(pcg_hash(alpha_ray_key ^ pcg_hash(triangle)) >> 8u) * (1.0 / 16777216.0);
}
//#endif
