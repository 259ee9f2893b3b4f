// Shared declarations: GPU structs (mirrored by src/layout.rs), bindings, constants.

//#include "shared_constants.wgsl"

struct Frame {
    camera_position: vec3f,
    // Metres; 0: a pinhole.
    aperture_radius: f32,
    camera_right: vec3f,
    focus_distance: f32,
    camera_up: vec3f,
    width: u32,
    camera_forward: vec3f,
    height: u32,
    // Half the image plane's size and its centre's offset (lens shift), at distance 1
    // along the view (perspective) or in metres (orthographic).
    view_half_extent: vec2f,
    view_shift: vec2f,
    // 1: parallel rays.
    orthographic: u32,
    // 0: a round aperture; else the sides of a regular polygon.
    aperture_blades: u32,
    blade_rotation: f32,
    inv_aperture_ratio: f32,
    sky_color: vec3f,
    max_bounces: u32,
    sample_base: u32,
    samples_per_dispatch: u32,
    seed: u32,
    tlas_root: u32,
    // Unit vector towards the sun's centre.
    sun_direction: vec3f,
    // 1 − cos of the sun's angular radius, computed in f64 on the host: in f32,
    // 1 − cos(0.265°) would keep only two digits.
    sun_one_minus_cos: f32,
    // Disk radiance above any atmosphere.
    sun_radiance: vec3f,
    // Probability that next-event estimation samples the sun rather than an emitter.
    sun_select_probability: f32,
    emitter_count: u32,
    // Sum of the emitters' powers (area × luminance of emission).
    emitter_total_power: f32,
    ris_candidates: u32,
    // Samples whose luminance exceeds this are scaled down to it (0: off). Biased: off by default.
    clamp_luminance: f32,
    // Adaptive sampling: the relative standard error at which a pixel stops, after this many samples.
    noise_threshold: f32,
    adaptive_min_samples: u32,
    // Camera rays start at the plane clip_start along the view and end at clip_end.
    clip_start: f32,
    clip_end: f32,
    // A panoramic camera (`panorama.wgsl`; PANORAMA_NONE: none): Cycles' φ = x·u + y,
    // θ = z·v + w of the equirectangular panorama; the equisolid fisheye's sensor (mm);
    // the fisheyes' field of view (radians) and the equisolid's lens (mm).
    equirectangular_range: vec4f,
    fisheye_sensor: vec2f,
    fisheye_fov: f32,
    fisheye_lens: f32,
    panorama: u32,
    // Film › Transparent Glass: the GGX α up to which glass lets the camera's path keep
    // the background transparent; negative: off (integrator.wgsl).
    transparent_glass: f32,
    // The share of light samples that go to a uniform sky sampled as a light (lights.wgsl).
    sky_light_share: f32,
    // The index of the render's first sample (`--sample-range`): samples draw their random
    // numbers by their index in the whole render, whichever part of it takes them.
    first_sample: u32,
    // How many of `camera_motion` the camera moves through over the shutter (0: it stands
    // still at camera_position, …): motion.wgsl.
    camera_motion_steps: u32,
    camera_motion: array<MotionKey, 17>,
}

// One key of a motion over the shutter (motion.wgsl): a unit quaternion (x, y, z, w), the
// translation and the stretch matrix S as S₀₀, (S₀₁, S₀₂, S₁₀, S₁₁), (S₁₂, S₂₀, S₂₁, S₂₂).
struct MotionKey {
    rotation: vec4f,
    translation: vec3f,
    stretch_xx: f32,
    stretch_a: vec4f,
    stretch_b: vec4f,
}

// A BVH2 node holding both children's boxes, so that one fetch decides where to go.
// count == 0: `link` is the child node's index; count > 0: a leaf of `count`
// primitives starting at `link`. An empty child has count 0 and link EMPTY_LINK.
struct BvhNode {
    a_min: vec3f,
    a_link: u32,
    a_max: vec3f,
    a_count: u32,
    b_min: vec3f,
    b_link: u32,
    b_max: vec3f,
    b_count: u32,
}

// A compressed 8-wide BVH node of a mesh (Ylitie, Karras & Laine 2017; obvhs's
// CwBvhNode): child boxes on a grid origin + q · 2^(e − 127) per axis, q one byte per
// child and plane; see shaders/wide_bvh.wgsl.
struct WideNode {
    origin: vec3f,
    // Bytes 0..3: the biased exponents e of the x, y, z steps; byte 3: imask (bit i: slot i is an inner node).
    exponents_imask: u32,
    // Inner children are contiguous from here, in slot order (relative to the mesh's first node).
    child_base: u32,
    // Leaf triangles are contiguous from here (relative to the mesh's first triangle).
    primitive_base: u32,
    // One byte per slot: 0 empty; inner: 0b001_11000 + slot; leaf: the triangle count
    // in unary in bits 5..8 and its first triangle's offset from primitive_base in bits 0..5.
    child_meta: vec2u,
    // One byte per slot: children 0..4 in .x, 4..8 in .y.
    child_min_x: vec2u,
    child_max_x: vec2u,
    child_min_y: vec2u,
    child_max_y: vec2u,
    child_min_z: vec2u,
    child_max_z: vec2u,
}

struct Triangle {
    v0: vec3f,
    material: u32,
    v1: vec3f,
    _pad1: u32,
    v2: vec3f,
    _pad2: u32,
}

// Per-vertex shading normals of one triangle (the geometric normal when the mesh has
// none), and texture coordinates: u in the normals' spare words, the three v together.
struct TriangleShading {
    n0: vec3f,
    u0: f32,
    n1: vec3f,
    u1: f32,
    n2: vec3f,
    u2: f32,
    v: vec3f,
    _pad0: u32,
}

struct Instance {
    world_to_object: array<vec4f, 3>,
    node_offset: u32,
    triangle_offset: u32,
    material_base: u32,
    material_override: u32,
}

// An instance's settings that shading reads (see GpuObjectSettings): its Shadow Terminator
// offsets for smooth shading and the terminator shift, and whether the object is a holdout;
// beside the instances, so that traversal's records stay small.
struct ObjectSettings {
    geometry_offset: f32,
    frequency_multiplier: f32,
    holdout: u32,
    _pad0: u32,
}

struct Sphere {
    center: vec3f,
    radius: f32,
    material: u32,
    // |center|² − radius², computed in f64 on the host (see `sphere_c`).
    k: f32,
    _pad0: u32,
    _pad1: u32,
}

// Lobe weights are normalised on the host so that they sum to at most 1.
struct Material {
    base_color: vec3f,
    diffuse: f32,
    emission: vec3f,
    specular: f32,
    absorption: vec3f,
    reflection: f32,
    volume_emission: vec3f,
    transmission: f32,
    ior: f32,
    // GGX α of the specular, reflection and transmission lobes (from roughness or hardness).
    alpha: f32,
    // Luminance of `emission`, for light selection probabilities.
    emission_luminance: f32,
    // Indices into `textures`, or NO_TEXTURE (see texture.wgsl).
    base_color_texture: u32,
    metallic_roughness_texture: u32,
    emission_texture: u32,
    // With `metallic_roughness_texture`: metal = metallic × B, roughness = roughness × G.
    metallic: f32,
    roughness: f32,
    // Opacity = base_alpha × the base colour texture's alpha; below alpha_cutoff
    // (0: opaque) the surface is not there.
    base_alpha: f32,
    // Negative (ALPHA_BLEND): opacity is the probability that the surface is there.
    alpha_cutoff: f32,
    // A tangent-space normal map, or NO_TEXTURE; its x and y are scaled by normal_scale.
    normal_texture: u32,
    normal_scale: f32,
    // The F82 tint of the `reflection` metal; the tint of the diffuse's coating's F0.
    specular_tint: vec3f,
    // Index of the dielectric coating over the diffuse lobe (0: none; then the
    // `specular` lobe is that coating), and its F0 before `specular_tint`.
    coating_eta: f32,
    coating_f0: f32,
    // Roughness of the sheen layer, in [0.001, 1].
    sheen_roughness: f32,
    // The rough lobes' stretch along the surface tangent, and the tangent's turn about
    // the normal (1: a full turn).
    anisotropy: f32,
    anisotropy_rotation: f32,
    // The coat: a dielectric GGX layer of weight `coat` over every other lobe (0: none),
    // and the tint of the light crossing it at normal incidence.
    coat_tint: vec3f,
    coat: f32,
    coat_alpha: f32,
    coat_ior: f32,
    // Bit i: texture slot i reads the second uv set (UV1_* in texture.wgsl).
    second_uv_set: u32,
    // Oren-Nayar roughness of the diffuse lobe (0: Lambertian; see oren_nayar.wgsl).
    diffuse_roughness: f32,
    // The sheen: Cycles' microfiber layer of weight `sheen` and colour `sheen_tint` over
    // every other lobe, the coat included (0: none).
    sheen_tint: vec3f,
    sheen: f32,
    // The thin film on the specular, metal and glass lobes (see thin_film.wgsl): its
    // thickness in nm (at most THIN_FILM_CUTOFF: none) and its index.
    thin_film_thickness: f32,
    thin_film_ior: f32,
    // 1: Cycles' Bump Map Correction of glossy normals on smooth-shaded surfaces (see
    // smooth_shading.wgsl), 0: none.
    bump_map_correction: u32,
    // How much of the film there is (KHR_materials_iridescence's factor): the film's
    // Fresnel and the bare one mixed by it.
    thin_film_weight: f32,
    // The layered lobes' textures, or NO_TEXTURE (`layer_textured` in texture.wgsl): coat
    // R × coat, G × coat roughness, coat tint RGB, sheen R × sheen and G × its roughness,
    // sheen tint RGB, anisotropy R × anisotropy and G + rotation, specular tint RGB.
    coat_texture: u32,
    coat_roughness_texture: u32,
    coat_tint_texture: u32,
    sheen_texture: u32,
    sheen_tint_texture: u32,
    anisotropy_texture: u32,
    specular_tint_texture: u32,
    // The anisotropic lobes' tangent: TANGENT_* in anisotropy.wgsl.
    tangent: u32,
    // More layer textures: diffuse roughness R × diffuse_roughness, and the film's thickness
    // G, from thin_film_minimum at 0 to thin_film_thickness at 1.
    diffuse_roughness_texture: u32,
    thin_film_texture: u32,
    thin_film_minimum: f32,
    // Where the material's node program starts in `node_programs`, or NO_PROGRAM
    // (node_program.wgsl).
    node_program: u32,
    // The transmission texture: R × transmission_factor of the diffuse and its coating
    // turns to glass (the weights above are those of the part that does not transmit);
    // the specular IOR level's: A scales the coating's F0.
    transmission_texture: u32,
    transmission_factor: f32,
    specular_level_texture: u32,
    // 1: the anisotropy texture is glTF's: RG a direction in the tangent frame, B × anisotropy.
    anisotropy_directions: u32,
    // The coat's own normal map (Principled's Coat Normal), its x and y scaled by
    // coat_normal_scale, or NO_TEXTURE: the coat takes the interpolated normal (coat_normal.wgsl).
    coat_normal_texture: u32,
    coat_normal_scale: f32,
    // A Mix Shader's second material, which the node program's mix factor selects at each
    // shading point (node_program.wgsl), or NO_MATERIAL.
    mix_material: u32,
    // The share of the surface that is a Holdout shader (holdout.wgsl).
    holdout: f32,
    // The indices' texture (R the IOR, G the coat's, B the film's), each from its minimum
    // here at 0 to the material's own at 1.
    ior_texture: u32,
    ior_minimum: f32,
    coat_ior_minimum: f32,
    thin_film_ior_minimum: f32,
}

// Object-space vertex tangents (xyz) and bitangent signs (w) of one triangle; zero
// where its mesh has none.
struct TriangleTangents {
    t0: vec4f,
    t1: vec4f,
    t2: vec4f,
}

// The second uv set at a triangle's vertices (scenes whose textures read it only).
struct TriangleUvs {
    uv0: vec2f,
    uv1: vec2f,
    uv2: vec2f,
}

// One texture of the texture store: its texels start at `offset` in `texels`, levels
// finest first. flags: bit 0 sRGB; bits 1-2 wrap of u, bits 3-4 wrap of v.
struct Texture {
    offset: u32,
    width: u32,
    height: u32,
    levels: u32,
    flags: u32,
    // ½ log2 |det| of the uv transform, added to the level of detail.
    transform_lod: f32,
    _pad0: u32,
    _pad1: u32,
    // The uv transform's rows (xyz): the image is read at (dot(u_row.xyz, (u, v, 1)), dot(v_row.xyz, ...)).
    u_row: vec4f,
    v_row: vec4f,
}

// An emissive triangle (of one instance) or sphere, for next-event estimation.
struct Emitter {
    // Triangle index, or sphere index | SPHERE_BIT.
    primitive: u32,
    instance: u32,
    // Cumulative selection probability up to and including this emitter.
    cdf: f32,
    _pad0: u32,
}

// Counters in the statistics buffer.
const STAT_STACK_OVERFLOW: u32 = 0u;

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<storage, read> nodes: array<BvhNode>;
@group(0) @binding(2) var<storage, read> triangles: array<Triangle>;
@group(0) @binding(3) var<storage, read> shading: array<TriangleShading>;
@group(0) @binding(4) var<storage, read> instances: array<Instance>;
@group(0) @binding(5) var<storage, read> tlas_primitives: array<u32>;
@group(0) @binding(6) var<storage, read> spheres: array<Sphere>;
@group(0) @binding(7) var<storage, read> materials: array<Material>;
@group(0) @binding(8) var<storage, read_write> stats: array<atomic<u32>>;
@group(0) @binding(9) var<storage, read> emitters: array<Emitter>;
@group(0) @binding(12) var<storage, read> wide_nodes: array<WideNode>;
//#if textures
@group(0) @binding(13) var<storage, read> textures: array<Texture>;
// RGBA8 texels, red in the low byte.
@group(0) @binding(14) var<storage, read> texels: array<u32>;
//#endif
//#if tangent_frames
@group(0) @binding(17) var<storage, read> tangent_frames: array<TriangleTangents>;
//#endif
//#if uv_sets
@group(0) @binding(19) var<storage, read> second_uvs: array<TriangleUvs>;
//#endif
//#if object_settings
@group(0) @binding(20) var<storage, read> object_settings: array<ObjectSettings>;
//#endif
