// Blender's Voronoi Texture of 1, 2 and 4 dimensions, as Cycles computes it
// (kernel/svm/voronoi.h, Apache-2.0, Blender Foundation; smooth F1 and distance to edge after
// Inigo Quilez, MIT): the same feature points from the same hashes of the cell (lookup3 of
// the cell's float in 1D, Cycles' signed PCG 2D and 4D), so the same cells. A point of d
// dimensions is a vec4f whose first d components are used (the others stay 0), and the
// cells around it are walked in Cycles' order. 3D is node_voronoi.wgsl's own code, apart:
// this general form is slower to compile and to run.

//#include "node_voronoi.wgsl"

struct VoronoiOctave4 {
    distance: f32,
    color: vec3f,
    position: vec4f,
}

// The components a point of `d` dimensions uses.
fn voronoi4_used(d: u32) -> vec4<bool> {
    return vec4<bool>(true, d > 1u, d > 2u, d > 3u);
}

// How far the walk goes from the cell along each axis: `reach` along the used ones.
fn voronoi4_reach(d: u32, reach: i32) -> vec4i {
    return select(vec4i(0), vec4i(reach), voronoi4_used(d));
}

fn voronoi4_distance(a: vec4f, b: vec4f, p: VoronoiParams) -> f32 {
    let d = abs(a - b);
    switch p.metric {
        case 1u: { return d.x + d.y + d.z + d.w; }
        case 2u: { return max(max(d.x, d.y), max(d.z, d.w)); }
        case 3u: {
            let e = select(vec4f(0.0), pow(d, vec4f(p.exponent)), voronoi4_used(p.dimensions));
            return pow(e.x + e.y + e.z + e.w, 1.0 / p.exponent);
        }
        default: { return length(a - b); }
    }
}

// Cycles' hash_pcg2d_i and hash_pcg4d_i (signed, wrapping, arithmetic shifts), in [0, 1];
// hash_int3_to_float3 is PCG 3D's.
fn hash_int2_to_float2(k: vec2i) -> vec2f {
    var v = k * 1664525 + 1013904223;
    v.x += v.y * 1664525;
    v.y += v.x * 1664525;
    v = v ^ (v >> vec2u(16u));
    v.x += v.y * 1664525;
    v.y += v.x * 1664525;
    return vec2f(v & vec2i(0x7fffffff)) * (1.0 / 2147483647.0);
}

fn hash_int4_to_float4(k: vec4i) -> vec4f {
    var v = k * 1664525 + 1013904223;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v = v ^ (v >> vec4u(16u));
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return vec4f(v & vec4i(0x7fffffff)) * (1.0 / 2147483647.0);
}

// Where in cell `c` its feature point lies, in [0, 1] per used component.
fn voronoi4_cell_hash(c: vec4f, d: u32) -> vec4f {
    switch d {
        case 1u: { return vec4f(hash_float_to_float(c.x), 0.0, 0.0, 0.0); }
        case 2u: { return vec4f(hash_int2_to_float2(vec2i(c.xy)), 0.0, 0.0); }
        case 4u: { return hash_int4_to_float4(vec4i(c)); }
        default: { return vec4f(hash_int3_to_float3(vec3i(c.xyz)), 0.0); }
    }
}

// Cell `c`'s colour (hash_float_to_float3, hash_int2/3/4_to_float3).
fn voronoi4_cell_color(c: vec4f, d: u32) -> vec3f {
    switch d {
        case 1u: {
            return vec3f(hash_float_to_float(c.x), hash_float2_to_float(vec2f(c.x, 1.0)), hash_float2_to_float(vec2f(c.x, 2.0)));
        }
        case 2u: { return hash_int3_to_float3(vec3i(vec2i(c.xy), 0)); }
        case 4u: { return hash_int4_to_float4(vec4i(c)).xyz; }
        default: { return hash_int3_to_float3(vec3i(c.xyz)); }
    }
}

fn voronoi4_point(cell: vec4f, offset: vec4f, p: VoronoiParams) -> vec4f {
    return offset + voronoi4_cell_hash(cell + offset, p.dimensions) * p.randomness;
}

fn voronoi4_f1_f2(p: VoronoiParams, coord: vec4f, second: bool) -> VoronoiOctave4 {
    let cell = floor(coord);
    let local = coord - cell;
    let r = voronoi4_reach(p.dimensions, 1);
    var d1 = 3.402823466e38;
    var d2 = 3.402823466e38;
    var o1 = vec4f(0.0);
    var o2 = vec4f(0.0);
    var p1 = vec4f(0.0);
    var p2 = vec4f(0.0);
    for (var u = -r.w; u <= r.w; u++) {
        for (var k = -r.z; k <= r.z; k++) {
            for (var j = -r.y; j <= r.y; j++) {
                for (var i = -r.x; i <= r.x; i++) {
                    let offset = vec4f(f32(i), f32(j), f32(k), f32(u));
                    let point = voronoi4_point(cell, offset, p);
                    let d = voronoi4_distance(point, local, p);
                    if d < d1 {
                        d2 = d1;
                        o2 = o1;
                        p2 = p1;
                        d1 = d;
                        o1 = offset;
                        p1 = point;
                    } else if d < d2 {
                        d2 = d;
                        o2 = offset;
                        p2 = point;
                    }
                }
            }
        }
    }
    if second {
        return VoronoiOctave4(d2, voronoi4_cell_color(cell + o2, p.dimensions), p2 + cell);
    }
    return VoronoiOctave4(d1, voronoi4_cell_color(cell + o1, p.dimensions), p1 + cell);
}

fn voronoi4_smooth_f1(p: VoronoiParams, coord: vec4f) -> VoronoiOctave4 {
    let cell = floor(coord);
    let local = coord - cell;
    let r = voronoi4_reach(p.dimensions, 2);
    var smooth_distance = 0.0;
    var smooth_color = vec3f(0.0);
    var smooth_position = vec4f(0.0);
    var h = -1.0;
    for (var u = -r.w; u <= r.w; u++) {
        for (var k = -r.z; k <= r.z; k++) {
            for (var j = -r.y; j <= r.y; j++) {
                for (var i = -r.x; i <= r.x; i++) {
                    let offset = vec4f(f32(i), f32(j), f32(k), f32(u));
                    let point = voronoi4_point(cell, offset, p);
                    let d = voronoi4_distance(point, local, p);
                    h = select(node_smoothstep(0.0, 1.0, 0.5 + 0.5 * (smooth_distance - d) / p.smoothness), 1.0, h == -1.0);
                    var correction = p.smoothness * h * (1.0 - h);
                    smooth_distance = mix(smooth_distance, d, h) - correction;
                    correction /= 1.0 + 3.0 * p.smoothness;
                    smooth_color = mix(smooth_color, voronoi4_cell_color(cell + offset, p.dimensions), vec3f(h)) - correction;
                    smooth_position = mix(smooth_position, point, vec4f(h)) - correction;
                }
            }
        }
    }
    // The unused components of the position stay 0, as Cycles' narrower vectors.
    let used = select(vec4f(0.0), vec4f(1.0), voronoi4_used(p.dimensions));
    return VoronoiOctave4(smooth_distance, smooth_color, (cell + smooth_position) * used);
}

// 1D's distance to the edge: to the midpoints between the cell's point and its neighbours'.
fn voronoi4_distance_to_edge_1d(p: VoronoiParams, coord: f32) -> f32 {
    let cell = floor(coord);
    let local = coord - cell;
    let middle = hash_float_to_float(cell) * p.randomness;
    let left = -1.0 + hash_float_to_float(cell - 1.0) * p.randomness;
    let right = 1.0 + hash_float_to_float(cell + 1.0) * p.randomness;
    return min(abs((middle + left) / 2.0 - local), abs((middle + right) / 2.0 - local));
}

fn voronoi4_distance_to_edge(p: VoronoiParams, coord: vec4f) -> f32 {
    if p.dimensions == 1u {
        return voronoi4_distance_to_edge_1d(p, coord.x);
    }
    let cell = floor(coord);
    let local = coord - cell;
    let r = voronoi4_reach(p.dimensions, 1);
    var to_closest = vec4f(0.0);
    var nearest = 3.402823466e38;
    for (var u = -r.w; u <= r.w; u++) {
        for (var k = -r.z; k <= r.z; k++) {
            for (var j = -r.y; j <= r.y; j++) {
                for (var i = -r.x; i <= r.x; i++) {
                    let to_point = voronoi4_point(cell, vec4f(f32(i), f32(j), f32(k), f32(u)), p) - local;
                    let d = dot(to_point, to_point);
                    if d < nearest {
                        nearest = d;
                        to_closest = to_point;
                    }
                }
            }
        }
    }
    var edge = 3.402823466e38;
    for (var u = -r.w; u <= r.w; u++) {
        for (var k = -r.z; k <= r.z; k++) {
            for (var j = -r.y; j <= r.y; j++) {
                for (var i = -r.x; i <= r.x; i++) {
                    let to_point = voronoi4_point(cell, vec4f(f32(i), f32(j), f32(k), f32(u)), p) - local;
                    let across = to_point - to_closest;
                    if dot(across, across) > 0.0001 {
                        edge = min(edge, dot((to_closest + to_point) / 2.0, normalize(across)));
                    }
                }
            }
        }
    }
    return edge;
}

fn voronoi4_n_sphere_radius(p: VoronoiParams, coord: vec4f) -> f32 {
    let cell = floor(coord);
    let local = coord - cell;
    let r = voronoi4_reach(p.dimensions, 1);
    var closest = vec4f(0.0);
    var closest_offset = vec4f(0.0);
    var nearest = 3.402823466e38;
    for (var u = -r.w; u <= r.w; u++) {
        for (var k = -r.z; k <= r.z; k++) {
            for (var j = -r.y; j <= r.y; j++) {
                for (var i = -r.x; i <= r.x; i++) {
                    let offset = vec4f(f32(i), f32(j), f32(k), f32(u));
                    let point = voronoi4_point(cell, offset, p);
                    let d = distance(point, local);
                    if d < nearest {
                        nearest = d;
                        closest = point;
                        closest_offset = offset;
                    }
                }
            }
        }
    }
    nearest = 3.402823466e38;
    var next = vec4f(0.0);
    for (var u = -r.w; u <= r.w; u++) {
        for (var k = -r.z; k <= r.z; k++) {
            for (var j = -r.y; j <= r.y; j++) {
                for (var i = -r.x; i <= r.x; i++) {
                    if i == 0 && j == 0 && k == 0 && u == 0 {
                        continue;
                    }
                    let point = voronoi4_point(cell, vec4f(f32(i), f32(j), f32(k), f32(u)) + closest_offset, p);
                    let d = distance(closest, point);
                    if d < nearest {
                        nearest = d;
                        next = point;
                    }
                }
            }
        }
    }
    return distance(next, closest) / 2.0;
}

fn voronoi4_octave(p: VoronoiParams, coord: vec4f) -> VoronoiOctave4 {
    if p.feature == 2u && p.smoothness != 0.0 {
        return voronoi4_smooth_f1(p, coord);
    }
    return voronoi4_f1_f2(p, coord, p.feature == 1u);
}

// The octaves summed as fBM noise sums them, positions blended (fractal_voronoi_x_fx).
fn fractal_voronoi4(p: VoronoiParams, coord: vec4f) -> VoronoiOctave4 {
    var amplitude = 1.0;
    var max_amplitude = 0.0;
    var scale = 1.0;
    var out = VoronoiOctave4(0.0, vec3f(0.0), vec4f(0.0));
    let zero_input = p.detail == 0.0 || p.roughness == 0.0;
    for (var i = 0; f32(i) <= ceil(p.detail); i++) {
        let octave = voronoi4_octave(p, coord * scale);
        if zero_input {
            max_amplitude = 1.0;
            out = octave;
            break;
        }
        if f32(i) <= p.detail {
            max_amplitude += amplitude;
            out.distance += octave.distance * amplitude;
            out.color += octave.color * amplitude;
            out.position = mix(out.position, octave.position / scale, vec4f(amplitude));
            scale *= p.lacunarity;
            amplitude *= p.roughness;
        } else {
            let remainder = p.detail - floor(p.detail);
            if remainder != 0.0 {
                max_amplitude = mix(max_amplitude, max_amplitude + amplitude, remainder);
                out.distance = mix(out.distance, out.distance + octave.distance * amplitude, remainder);
                out.color = mix(out.color, out.color + octave.color * amplitude, vec3f(remainder));
                out.position = mix(out.position, mix(out.position, octave.position / scale, vec4f(amplitude)), vec4f(remainder));
            }
        }
    }
    if p.normalize {
        out.distance /= max_amplitude * p.max_distance;
        out.color /= max_amplitude;
    }
    out.position = select(vec4f(0.0), out.position / p.scale, p.scale != 0.0);
    return out;
}

fn fractal_voronoi4_distance_to_edge(p: VoronoiParams, coord: vec4f) -> f32 {
    var amplitude = 1.0;
    var max_amplitude = p.max_distance;
    var scale = 1.0;
    var d = 8.0;
    let zero_input = p.detail == 0.0 || p.roughness == 0.0;
    for (var i = 0; f32(i) <= ceil(p.detail); i++) {
        let octave = voronoi4_distance_to_edge(p, coord * scale);
        if zero_input {
            d = octave;
            break;
        }
        if f32(i) <= p.detail {
            max_amplitude = mix(max_amplitude, p.max_distance / scale, amplitude);
            d = mix(d, min(d, octave / scale), amplitude);
            scale *= p.lacunarity;
            amplitude *= p.roughness;
        } else {
            let remainder = p.detail - floor(p.detail);
            if remainder != 0.0 {
                let lerp_amplitude = mix(max_amplitude, p.max_distance / scale, amplitude);
                max_amplitude = mix(max_amplitude, lerp_amplitude, remainder);
                let lerp_distance = mix(d, min(d, octave / scale), amplitude);
                d = mix(d, min(d, lerp_distance), remainder);
            }
        }
    }
    return select(d, d / max_amplitude, p.normalize);
}

// The Voronoi Texture of 1, 2 or 4 dimensions at `v` and `w` (not yet scaled).
fn voronoi_texture_of_dimensions(v: vec3f, w: f32, params: VoronoiParams) -> VoronoiResult {
    var p = params;
    p.detail = clamp(p.detail, 0.0, 15.0);
    p.roughness = clamp(p.roughness, 0.0, 1.0);
    p.randomness = clamp(p.randomness, 0.0, 1.0);
    p.smoothness = clamp(p.smoothness / 2.0, 0.0, 0.5);
    var coord: vec4f;
    switch p.dimensions {
        case 1u: {
            coord = vec4f(w, 0.0, 0.0, 0.0);
            // 1D measures |a - b|, which Manhattan's sum of one component is.
            p.metric = 1u;
        }
        case 2u: { coord = vec4f(v.xy, 0.0, 0.0); }
        case 4u: { coord = vec4f(v, w); }
        default: { coord = vec4f(v, 0.0); }
    }
    coord *= p.scale;
    let reach = 0.5 + 0.5 * p.randomness;
    if p.feature == 3u {
        p.max_distance = reach;
        return VoronoiResult(fractal_voronoi4_distance_to_edge(p, coord), vec3f(0.0), vec3f(0.0), 0.0, 0.0);
    }
    if p.feature == 4u {
        return VoronoiResult(0.0, vec3f(0.0), vec3f(0.0), 0.0, voronoi4_n_sphere_radius(p, coord));
    }
    let corner = select(vec4f(0.0), vec4f(reach), voronoi4_used(p.dimensions));
    p.max_distance = voronoi4_distance(vec4f(0.0), corner, p) * select(1.0, 2.0, p.feature == 1u);
    let out = fractal_voronoi4(p, coord);
    // Cycles' position of a 1D point is (0, 0, 0, w), of a 2D one (x, y, 0, 0).
    if p.dimensions == 1u {
        return VoronoiResult(out.distance, out.color, vec3f(0.0), out.position.x, 0.0);
    }
    return VoronoiResult(out.distance, out.color, out.position.xyz, out.position.w, 0.0);
}
