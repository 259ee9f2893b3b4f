// What node operations read at a point and compute, beside the textures' own files:
// coordinates, Light Path, ramps and curves, Mapping, Checker, Gradient, Fresnel, Layer
// Weight, Brick, and the noise and Voronoi textures' operands.

//#include "transform.wgsl"
//#include "motion.wgsl"
//#include "texture.wgsl"
//#include "node_step.wgsl"
//#include "node_noise.wgsl"
//#include "node_math.wgsl"
//#include "node_voronoi_dimensions.wgsl"
//#include "node_spectrum.wgsl"
//#if panorama
//#include "panorama.wgsl"
//#endif

// Texture Coordinate (modes 0-3: Generated, Normal, UV, Object) and Geometry (4-8:
// Position, Normal, True Normal, Incoming, Backfacing). Generated's texture space is in
// the instruction's extra words at `extra`.
fn node_coordinate(mode: u32, p: NodePoint, extra: u32) -> vec4f {
    switch mode {
        case 0u: {
            let scale = vec3f(node_word_f(extra), node_word_f(extra + 1u), node_word_f(extra + 2u));
            let offset = vec3f(node_word_f(extra + 3u), node_word_f(extra + 4u), node_word_f(extra + 5u));
            return vec4f(p.object * scale + offset, 0.0);
        }
        case 1u: { return vec4f(p.object_normal, 0.0); }
        case 2u: { return vec4f(p.uv, 0.0, 0.0); }
        case 3u: { return vec4f(p.object, 0.0); }
        case 4u, 5u: { return vec4f(node_camera_coordinates(mode == 5u, node_texture_point(p, mode == 5u)), 0.0); }
        // Reflection: the direction towards the viewer mirrored about the normal.
        case 6u: { return vec4f(2.0 * dot(p.normal, p.incoming) * p.normal - p.incoming, 0.0); }
        case 7u: { return vec4f(p.position, 0.0); }
        case 8u: { return vec4f(p.normal, 0.0); }
        case 9u: { return vec4f(p.true_normal, 0.0); }
        case 10u: { return vec4f(p.incoming, 0.0); }
        case 11u: { return vec4f(select(0.0, 1.0, p.backfacing)); }
        case 25u, 26u, 27u, 28u, 29u: { return node_object_info(mode - 25u, p); }
        // Camera Data: the direction from the camera to the point (in camera space), its
        // depth along the view and its distance.
        case 30u: { return vec4f(normalize(node_camera_coordinates(false, rt_axes(p.position))), 0.0); }
        case 31u: { return vec4f(node_camera_coordinates(false, rt_axes(p.position)).z); }
        case 32u: { return vec4f(length(node_camera_coordinates(false, rt_axes(p.position)))); }
        default: { return vec4f(node_light_path(mode - 12u, p)); }
    }
}

// The point Texture Coordinate's Camera and (with `window`) Window see (rt's axes). In the
// World, as Cycles' camera_world_to_ndc: the direction placed at the camera, but for an
// orthographic camera's Window the origin of a camera ray and the direction itself as a
// point for other rays (Camera Data takes the direction as a point).
fn node_texture_point(p: NodePoint, window: bool) -> vec3f {
    var point = rt_axes(p.position);
    //#if sky_graph
    if p.background {
        if window && frame.orthographic != 0u {
            return select(point, p.ray_origin, p.ray_from == NODE_RAY_CAMERA);
        }
        point += frame.camera_position;
    }
    //#endif
    return point;
}

// Texture Coordinate's Camera (`point` in Cycles' camera space: x right, y up, z along
// the view, metres; a panoramic camera's: x along the view, y left, z up) or, with
// `window`, Window (where the point is on the image, 0 to 1 from the bottom left; z 0; a
// panorama's: where the direction to it falls on its image, as Cycles' camera_world_to_ndc).
fn node_camera_coordinates(window: bool, point: vec3f) -> vec3f {
    let camera = camera_space(point - frame.camera_position);
    //#if panorama
    if frame.panorama != PANORAMA_NONE {
        let panoramic = camera_to_panorama(camera);
        if window {
            return vec3f(panorama_uv(normalize(panoramic)), 0.0);
        }
        return panoramic;
    }
    //#endif
    if !window {
        return camera;
    }
    let plane = select(camera.xy / camera.z, camera.xy, frame.orthographic != 0u);
    return vec3f(0.5 + 0.5 * (plane - frame.view_shift) / frame.view_half_extent, 0.0);
}

// A direction of rt's world in Cycles' camera space (x right, y up, z along the view).
fn camera_space(d: vec3f) -> vec3f {
    return vec3f(dot(d, frame.camera_right), dot(d, frame.camera_up), dot(d, frame.camera_forward));
}

// Vector Transform (Cycles' svm_node_vector_transform): `v` as a point, vector or normal
// (mode & 3: 0, 1, 2) from one space (mode >> 2 & 3) to another (mode >> 4): 0 world and 1
// object (Blender's axes), 2 Cycles' camera space (x right, y up, z along the view).
// Normals go by the inverse transposes and are normalised; a sphere's object space is the
// world's.
fn node_vector_transform(mode: u32, v: vec3f, p: NodePoint) -> vec3f {
    let space_from = (mode >> 2u) & 3u;
    let space_to = mode >> 4u;
    if space_from == space_to {
        return v;
    }
    return node_from_world(mode & 3u, space_to, node_to_world(mode & 3u, space_from, v, p), p);
}

// `v` of `kind` in space `space_from`, in rt's world (rt's axes).
fn node_to_world(kind: u32, space_from: u32, v: vec3f, p: NodePoint) -> vec3f {
    if space_from == 2u {
        let d = frame.camera_right * v.x + frame.camera_up * v.y + frame.camera_forward * v.z;
        return select(select(frame.camera_position + d, d, kind == 1u), normalize(d), kind == 2u);
    }
    let w = rt_axes(v);
    if space_from == 0u || p.instance == NODE_NO_OBJECT {
        return w;
    }
    let world_to_object = instance_at(p.instance).world_to_object;
    if kind == 2u {
        return normalize(transform_normal_to_world(world_to_object, w));
    }
    let to_world = affine_inverse(world_to_object).m;
    return select(transform_point(to_world, w), transform_vector(to_world, w), kind == 1u);
}

// `w` of `kind` in rt's world, in space `space_to`.
fn node_from_world(kind: u32, space_to: u32, w: vec3f, p: NodePoint) -> vec3f {
    if space_to == 2u {
        let c = camera_space(select(w - frame.camera_position, w, kind != 0u));
        return select(c, normalize(c), kind == 2u);
    }
    if space_to == 0u || p.instance == NODE_NO_OBJECT {
        return blender_axes(w);
    }
    let world_to_object = instance_at(p.instance).world_to_object;
    if kind == 2u {
        return blender_axes(normalize(transform_normal_to_world(affine_inverse(world_to_object).m, w)));
    }
    return blender_axes(select(transform_point(world_to_object, w), transform_vector(world_to_object, w), kind == 1u));
}

// Object Info's Location, Color, Alpha, Random and Object Index (node_kinds' order) of the
// point's object: a sphere's are those of an object at the origin with the defaults.
fn node_object_info(output: u32, p: NodePoint) -> vec4f {
    if p.instance == NODE_NO_OBJECT {
        return select(vec4f(1.0), vec4f(0.0), output == 0u || output >= 3u);
    }
    switch output {
        case 0u: {
            let to_world = affine_inverse(instance_at(p.instance).world_to_object).m;
            return vec4f(blender_axes(vec3f(to_world[0].w, to_world[1].w, to_world[2].w)), 0.0);
        }
        case 1u, 2u: {
            var color = vec4f(1.0);
            //#if object_colors
            // The colours follow the settings (SceneGeometry::object_settings).
            let c = object_settings[arrayLength(&object_settings) / 2u + p.instance];
            color = vec4f(c.geometry_offset, c.frequency_multiplier, bitcast<f32>(c.holdout_and_index), c.random);
            //#endif
            return select(vec4f(color.xyz, 1.0), vec4f(color.w), output == 2u);
        }
        case 3u: { return vec4f(object_settings[p.instance].random); }
        // Object Index: Blender's Pass Index, above the holdout's bit.
        default: { return vec4f(f32(object_settings[p.instance].holdout_and_index >> 1u)); }
    }
}

// Light Path's outputs in node_kinds' order: Is Camera, Shadow, Diffuse, Glossy, Singular,
// Reflection, Transmission, Volume Scatter Ray, Ray Length, Ray Depth, Diffuse, Glossy and
// Transmission Depth. A lobe's bounce is diffuse (diffuse, sheen) or glossy (the others,
// singular ones too, as in Cycles), transmission for the glass lobe.
fn node_light_path(output: u32, p: NodePoint) -> f32 {
    let bounced = p.ray_from != NODE_RAY_CAMERA && p.ray_from != NODE_RAY_NONE;
    let lobe = p.ray_from - 1u;
    let diffuse = bounced && node_diffuse_lobe(lobe);
    let transmission = bounced && lobe == LOBE_TRANSMISSION;
    var on = false;
    switch output {
        case 0u: { on = p.ray_from == NODE_RAY_CAMERA; }
        case 2u: { on = diffuse; }
        case 3u: { on = bounced && !diffuse; }
        case 4u: { on = bounced && p.singular; }
        case 5u: { on = bounced && !transmission; }
        case 6u: { on = transmission; }
        case 8u: { return p.ray_length; }
        case 9u: { return p.ray_depth; }
        case 10u, 11u, 12u: { return f32(extractBits(p.ray_depths, NODE_DEPTH_BITS * (output - 10u), NODE_DEPTH_BITS)); }
        default: {}
    }
    return select(0.0, 1.0, on);
}

fn node_diffuse_lobe(lobe: u32) -> bool {
    return lobe == LOBE_DIFFUSE || lobe == LOBE_SHEEN;
}

// What a bounce by lobe `lobe` adds to NodePoint::ray_depths, as Cycles' path_state_next
// counts it: a transmission bounce (any lobe), else a diffuse or a glossy reflection.
fn node_depth_step(lobe: u32, transmitted: bool) -> u32 {
    if transmitted {
        return NODE_TRANSMISSION_DEPTH;
    }
    return select(NODE_GLOSSY_DEPTH, NODE_DIFFUSE_DEPTH, node_diffuse_lobe(lobe));
}

// Cycles' ramp lookup in a table of RAMP_TABLE_SIZE RGBA entries at `table`.
fn node_ramp(table: u32, fac: f32, interpolate: bool) -> vec4f {
    let f = clamp(fac, 0.0, 1.0) * f32(RAMP_TABLE_SIZE - 1u);
    let i = u32(clamp(i32(f), 0, i32(RAMP_TABLE_SIZE) - 1));
    let t = f - f32(i);
    let a = node_vec4(table + 4u * i);
    if interpolate && t > 0.0 {
        return (1.0 - t) * a + t * node_vec4(table + 4u * (i + 1u));
    }
    return a;
}

// Cycles' ramp lookup with extrapolation: beyond [0, 1] the table's end slope continues.
fn node_ramp_extended(table: u32, fac: f32, extrapolate: bool) -> vec4f {
    let last = RAMP_TABLE_SIZE - 1u;
    if extrapolate && fac < 0.0 {
        let t0 = node_vec4(table);
        return t0 + (t0 - node_vec4(table + 4u)) * -fac * f32(last);
    }
    if extrapolate && fac > 1.0 {
        let t0 = node_vec4(table + 4u * last);
        return t0 + (t0 - node_vec4(table + 4u * (last - 1u))) * (fac - 1.0) * f32(last);
    }
    return node_ramp(table, fac, true);
}

// RGB and Vector Curves (mode 0: each channel through its curve) and Float Curve (mode 1),
// mixed with the input by `fac`; `extra` holds the curves' range, then their table.
fn node_curves(mode: u32, extrapolate: bool, extra: u32, fac: f32, v: vec3f) -> vec3f {
    let lo = node_word_f(extra);
    let relative = (v - lo) / (node_word_f(extra + 1u) - lo);
    let table = extra + 2u;
    var curved = vec3f(
        node_ramp_extended(table, relative.x, extrapolate).x,
        node_ramp_extended(table, relative.y, extrapolate).y,
        node_ramp_extended(table, relative.z, extrapolate).z,
    );
    if mode == 1u {
        curved = vec3f(node_ramp_extended(table, relative.x, extrapolate).x);
    }
    return mix(v, curved, fac);
}

// Blender's XYZ Euler rotation (Cycles' euler_to_transform), as rows.
fn euler_rows(e: vec3f) -> mat3x3f {
    let c = cos(e);
    let s = sin(e);
    return mat3x3f(
        vec3f(c.y * c.z, s.y * s.x * c.z - c.x * s.z, s.y * c.x * c.z + s.x * s.z),
        vec3f(c.y * s.z, s.y * s.x * s.z + c.x * c.z, s.y * c.x * s.z - s.x * c.z),
        vec3f(-s.y, c.y * s.x, c.y * c.x),
    );
}

// Mapping: mode 0 point, 1 texture, 2 vector, 3 normal.
fn node_mapping(mode: u32, v: vec3f, location: vec3f, rotation: vec3f, scale: vec3f) -> vec3f {
    let rows = euler_rows(rotation);
    // `m * x` with rows as columns is the transpose's product: the inverse rotation.
    switch mode {
        case 0u: { return v * scale * rows + location; }
        case 1u: { return safe_divide3(rows * (v - location), scale); }
        case 2u: { return v * scale * rows; }
        default: { return safe_normalize(safe_divide3(v, scale) * rows); }
    }
}

fn node_checker(co: vec3f) -> f32 {
    let p = (co + 0.000001) * 0.999999;
    let i = abs(vec3i(floor(p)));
    return select(0.0, 1.0, ((i.x % 2) == (i.y % 2)) == ((i.z % 2) != 0));
}

// Gradient Texture: types in the order of node_kinds' GRADIENT_TYPES.
fn node_gradient(kind: u32, p: vec3f) -> f32 {
    switch kind {
        case 1u: { let r = max(p.x, 0.0); return r * r; }
        case 2u: {
            let r = clamp(p.x, 0.0, 1.0);
            let t = r * r;
            return 3.0 * t - 2.0 * t * r;
        }
        case 3u: { return (p.x + p.y) * 0.5; }
        case 4u: { return max(0.999999 - length(p), 0.0); }
        case 5u: { let r = max(0.999999 - length(p), 0.0); return r * r; }
        case 6u: { return atan2(p.y, p.x) / (2.0 * PI) + 0.5; }
        default: { return p.x; }
    }
}

// Cycles' fresnel_dielectric_cos.
fn node_fresnel(cos_i: f32, eta: f32) -> f32 {
    let c = abs(cos_i);
    var g = eta * eta - 1.0 + c * c;
    if g > 0.0 {
        g = sqrt(g);
        let a = (g - c) / (g + c);
        let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
        return 0.5 * a * a * (1.0 + b * b);
    }
    return 1.0;
}

// A Normal input the graph leaves unlinked reads 0: the point's own normal.
fn node_normal(n: vec3f, p: NodePoint) -> vec3f {
    return select(n, p.normal, all(n == vec3f(0.0)));
}

// Layer Weight's Fresnel (x) and Facing (y).
fn node_layer_weight(blend_in: f32, n: vec3f, p: NodePoint) -> vec2f {
    var eta = max(1.0 - blend_in, 1e-5);
    eta = select(1.0 / eta, eta, p.backfacing);
    let cos_i = dot(p.incoming, n);
    let fresnel = node_fresnel(cos_i, eta);
    var facing = abs(cos_i);
    if blend_in != 0.5 {
        var blend = clamp(blend_in, 0.0, 1.0 - 1e-5);
        blend = select(0.5 / (1.0 - blend), 2.0 * blend, blend < 0.5);
        facing = pow(facing, blend);
    }
    return vec2f(fresnel, 1.0 - facing);
}

// Noise Texture: mode = type | dimensions' index << 4 (node_kinds' NOISE_TYPES and
// NOISE_DIMENSIONS); the vector and W are scaled, 1D reads W, 2D the vector's x and y.
fn node_noise(start: u32, step: NodeStep, mode: u32, normalize: bool) -> vec4f {
    let scale = node_in(start, step, 2u).x;
    let s = NoiseSettings(
        clamp(node_in(start, step, 3u).x, 0.0, 15.0),
        max(node_in(start, step, 4u).x, 0.0),
        node_in(start, step, 5u).x,
        node_in(start, step, 6u).x,
        node_in(start, step, 7u).x,
        mode & 15u,
        normalize,
        (mode >> 4u) + 1u,
    );
    let v = node_in(start, step, 0u).xyz * scale;
    let w = node_in(start, step, 1u).x * scale;
    var co: vec4f;
    switch s.dimensions {
        case 1u: { co = vec4f(w, 0.0, 0.0, 0.0); }
        case 2u: { co = vec4f(v.xy, 0.0, 0.0); }
        case 4u: { co = vec4f(v, w); }
        default: { co = vec4f(v, 0.0); }
    }
    return noise_texture(co, node_in(start, step, 8u).x, s);
}

// Voronoi Texture's settings: mode = feature | metric << 4 | (dimensions - 1) << 8
// (node_kinds' VORONOI_FEATURES, _METRICS, NOISE_DIMENSIONS); operands Vector, W, Scale,
// Detail, Roughness, Lacunarity, Smoothness, Exponent, Randomness.
fn node_voronoi_params(start: u32, step: NodeStep) -> VoronoiParams {
    return VoronoiParams(
        node_in(start, step, 2u).x,
        node_in(start, step, 3u).x,
        node_in(start, step, 4u).x,
        node_in(start, step, 5u).x,
        node_in(start, step, 6u).x,
        node_in(start, step, 7u).x,
        node_in(start, step, 8u).x,
        0.0,
        step.flags != 0u,
        step.mode & 15u,
        (step.mode >> 4u) & 15u,
        (step.mode >> 8u) + 1u,
    );
}

// A Brick Texture's settings: its sockets' values and its node's properties.
struct BrickShape {
    mortar_size: f32,
    mortar_smooth: f32,
    bias: f32,
    width: f32,
    row_height: f32,
    offset: f32,
    offset_frequency: i32,
    squash: f32,
    squash_frequency: i32,
}

// Cycles' brick_noise: a fast integer hash of a brick's row and number, in [0, 1).
fn brick_noise(seed: u32) -> f32 {
    var n = (seed + 1013u) & 0x7fffffffu;
    n = (n >> 13u) ^ n;
    let nn = (n * (n * n * 60493u + 19990303u) + 1376312589u) & 0x7fffffffu;
    return 0.5 * (f32(nn) / 1073741824.0);
}

// Cycles' svm_brick at `p`: the brick's tint and the mortar's share. Every other row
// (by the frequencies) is offset and squashed; the mortar is where the point is nearer
// than its size to the brick's edge, smoothed by Mortar Smooth.
fn node_brick(p: vec3f, s: BrickShape) -> vec2f {
    let row = i32(floor(p.y / s.row_height));
    var width = s.width;
    var offset = 0.0;
    if s.offset_frequency != 0 && s.squash_frequency != 0 {
        width *= select(s.squash, 1.0, row % s.squash_frequency != 0);
        offset = select(width * s.offset, 0.0, row % s.offset_frequency != 0);
    }
    let brick = i32(floor((p.x + offset) / width));
    let x = (p.x + offset) - width * f32(brick);
    let y = p.y - s.row_height * f32(row);
    let tint = clamp(brick_noise(bitcast<u32>((row << 16u) + (brick & 0xffff))) + s.bias, 0.0, 1.0);
    let edge = min(min(x, y), min(width - x, s.row_height - y));
    if edge >= s.mortar_size {
        return vec2f(tint, 0.0);
    }
    if s.mortar_smooth == 0.0 {
        return vec2f(tint, 1.0);
    }
    // Cycles' smoothstepf, in its own form.
    let f = clamp((1.0 - edge / s.mortar_size) / s.mortar_smooth, 0.0, 1.0);
    return vec2f(tint, 3.0 * f * f - 2.0 * f * f * f);
}
