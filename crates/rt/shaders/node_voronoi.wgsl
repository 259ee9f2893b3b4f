// Blender's Voronoi Texture in 3D, as Cycles computes it (kernel/svm/voronoi.h, Apache-2.0,
// Blender Foundation; smooth F1 and distance to edge after Inigo Quilez, MIT): the same
// feature points from the same hash of the integer cell (Cycles' signed PCG 3D), so the
// same cells, with the fractal octaves of Blender 4.1 on.

//#include "node_noise.wgsl"
//#include "node_math.wgsl"

struct VoronoiParams {
    scale: f32,
    detail: f32,
    roughness: f32,
    lacunarity: f32,
    smoothness: f32,
    exponent: f32,
    randomness: f32,
    max_distance: f32,
    normalize: bool,
    // 0 F1, 1 F2, 2 smooth F1, 3 distance to edge, 4 n-sphere radius.
    feature: u32,
    // 0 Euclidean, 1 Manhattan, 2 Chebychev, 3 Minkowski.
    metric: u32,
    // 1 to 4 (node_voronoi_dimensions.wgsl); this file's code is 3D's.
    dimensions: u32,
}

struct VoronoiOctave {
    distance: f32,
    color: vec3f,
    position: vec3f,
}

fn voronoi_distance(a: vec3f, b: vec3f, p: VoronoiParams) -> f32 {
    let d = abs(a - b);
    switch p.metric {
        case 1u: { return d.x + d.y + d.z; }
        case 2u: { return max(d.x, max(d.y, d.z)); }
        case 3u: {
            let e = pow(d, vec3f(p.exponent));
            return pow(e.x + e.y + e.z, 1.0 / p.exponent);
        }
        default: { return distance(a, b); }
    }
}

// Cycles' hash_pcg3d_i: PCG 3D on signed integers (wrapping, arithmetic shifts), in [0, 1].
fn hash_int3_to_float3(k: vec3i) -> vec3f {
    var v = k * 1664525 + 1013904223;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v = v ^ (v >> vec3u(16u));
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return vec3f(v & vec3i(0x7fffffff)) * (1.0 / 2147483647.0);
}

fn voronoi_cell_hash(cell: vec3f, offset: vec3f) -> vec3f {
    return hash_int3_to_float3(vec3i(cell + offset));
}

fn voronoi_point(cell: vec3f, offset: vec3f, p: VoronoiParams) -> vec3f {
    return offset + voronoi_cell_hash(cell, offset) * p.randomness;
}

fn voronoi_f1_f2(p: VoronoiParams, coord: vec3f, second: bool) -> VoronoiOctave {
    let cell = floor(coord);
    let local = coord - cell;
    var d1 = 3.402823466e38;
    var d2 = 3.402823466e38;
    var o1 = vec3f(0.0);
    var o2 = vec3f(0.0);
    var p1 = vec3f(0.0);
    var p2 = vec3f(0.0);
    for (var k = -1; k <= 1; k++) {
        for (var j = -1; j <= 1; j++) {
            for (var i = -1; i <= 1; i++) {
                let offset = vec3f(f32(i), f32(j), f32(k));
                let point = voronoi_point(cell, offset, p);
                let d = voronoi_distance(point, local, p);
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
    if second {
        return VoronoiOctave(d2, voronoi_cell_hash(cell, o2), p2 + cell);
    }
    return VoronoiOctave(d1, voronoi_cell_hash(cell, o1), p1 + cell);
}

fn voronoi_smooth_f1(p: VoronoiParams, coord: vec3f) -> VoronoiOctave {
    let cell = floor(coord);
    let local = coord - cell;
    var smooth_distance = 0.0;
    var smooth_color = vec3f(0.0);
    var smooth_position = vec3f(0.0);
    var h = -1.0;
    for (var k = -2; k <= 2; k++) {
        for (var j = -2; j <= 2; j++) {
            for (var i = -2; i <= 2; i++) {
                let offset = vec3f(f32(i), f32(j), f32(k));
                let point = voronoi_point(cell, offset, p);
                let d = voronoi_distance(point, local, p);
                h = select(node_smoothstep(0.0, 1.0, 0.5 + 0.5 * (smooth_distance - d) / p.smoothness), 1.0, h == -1.0);
                var correction = p.smoothness * h * (1.0 - h);
                smooth_distance = mix(smooth_distance, d, h) - correction;
                correction /= 1.0 + 3.0 * p.smoothness;
                smooth_color = mix(smooth_color, voronoi_cell_hash(cell, offset), vec3f(h)) - correction;
                smooth_position = mix(smooth_position, point, vec3f(h)) - correction;
            }
        }
    }
    return VoronoiOctave(smooth_distance, smooth_color, cell + smooth_position);
}

fn voronoi_distance_to_edge(p: VoronoiParams, coord: vec3f) -> f32 {
    let cell = floor(coord);
    let local = coord - cell;
    var to_closest = vec3f(0.0);
    var nearest = 3.402823466e38;
    for (var k = -1; k <= 1; k++) {
        for (var j = -1; j <= 1; j++) {
            for (var i = -1; i <= 1; i++) {
                let to_point = voronoi_point(cell, vec3f(f32(i), f32(j), f32(k)), p) - local;
                let d = dot(to_point, to_point);
                if d < nearest {
                    nearest = d;
                    to_closest = to_point;
                }
            }
        }
    }
    var edge = 3.402823466e38;
    for (var k = -1; k <= 1; k++) {
        for (var j = -1; j <= 1; j++) {
            for (var i = -1; i <= 1; i++) {
                let to_point = voronoi_point(cell, vec3f(f32(i), f32(j), f32(k)), p) - local;
                let across = to_point - to_closest;
                if dot(across, across) > 0.0001 {
                    edge = min(edge, dot((to_closest + to_point) / 2.0, normalize(across)));
                }
            }
        }
    }
    return edge;
}

fn voronoi_n_sphere_radius(p: VoronoiParams, coord: vec3f) -> f32 {
    let cell = floor(coord);
    let local = coord - cell;
    var closest = vec3f(0.0);
    var closest_offset = vec3f(0.0);
    var nearest = 3.402823466e38;
    for (var k = -1; k <= 1; k++) {
        for (var j = -1; j <= 1; j++) {
            for (var i = -1; i <= 1; i++) {
                let offset = vec3f(f32(i), f32(j), f32(k));
                let point = voronoi_point(cell, offset, p);
                let d = distance(point, local);
                if d < nearest {
                    nearest = d;
                    closest = point;
                    closest_offset = offset;
                }
            }
        }
    }
    nearest = 3.402823466e38;
    var next = vec3f(0.0);
    for (var k = -1; k <= 1; k++) {
        for (var j = -1; j <= 1; j++) {
            for (var i = -1; i <= 1; i++) {
                if i == 0 && j == 0 && k == 0 {
                    continue;
                }
                let point = voronoi_point(cell, vec3f(f32(i), f32(j), f32(k)) + closest_offset, p);
                let d = distance(closest, point);
                if d < nearest {
                    nearest = d;
                    next = point;
                }
            }
        }
    }
    return distance(next, closest) / 2.0;
}

fn voronoi_octave(p: VoronoiParams, coord: vec3f) -> VoronoiOctave {
    if p.feature == 2u && p.smoothness != 0.0 {
        return voronoi_smooth_f1(p, coord);
    }
    return voronoi_f1_f2(p, coord, p.feature == 1u);
}

// The octaves summed as fBM noise sums them, positions blended (fractal_voronoi_x_fx).
fn fractal_voronoi(p: VoronoiParams, coord: vec3f) -> VoronoiOctave {
    var amplitude = 1.0;
    var max_amplitude = 0.0;
    var scale = 1.0;
    var out = VoronoiOctave(0.0, vec3f(0.0), vec3f(0.0));
    let zero_input = p.detail == 0.0 || p.roughness == 0.0;
    for (var i = 0; f32(i) <= ceil(p.detail); i++) {
        let octave = voronoi_octave(p, coord * scale);
        if zero_input {
            max_amplitude = 1.0;
            out = octave;
            break;
        }
        if f32(i) <= p.detail {
            max_amplitude += amplitude;
            out.distance += octave.distance * amplitude;
            out.color += octave.color * amplitude;
            out.position = mix(out.position, octave.position / scale, vec3f(amplitude));
            scale *= p.lacunarity;
            amplitude *= p.roughness;
        } else {
            let remainder = p.detail - floor(p.detail);
            if remainder != 0.0 {
                max_amplitude = mix(max_amplitude, max_amplitude + amplitude, remainder);
                out.distance = mix(out.distance, out.distance + octave.distance * amplitude, remainder);
                out.color = mix(out.color, out.color + octave.color * amplitude, vec3f(remainder));
                out.position = mix(out.position, mix(out.position, octave.position / scale, vec3f(amplitude)), vec3f(remainder));
            }
        }
    }
    if p.normalize {
        out.distance /= max_amplitude * p.max_distance;
        out.color /= max_amplitude;
    }
    out.position = safe_divide3(out.position, vec3f(p.scale));
    return out;
}

fn fractal_voronoi_distance_to_edge(p: VoronoiParams, coord: vec3f) -> f32 {
    var amplitude = 1.0;
    var max_amplitude = p.max_distance;
    var scale = 1.0;
    var d = 8.0;
    let zero_input = p.detail == 0.0 || p.roughness == 0.0;
    for (var i = 0; f32(i) <= ceil(p.detail); i++) {
        let octave = voronoi_distance_to_edge(p, coord * scale);
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

// The Voronoi Texture at `coord` (not yet scaled): its Distance, Color, Position and Radius.
struct VoronoiResult {
    distance: f32,
    color: vec3f,
    position: vec3f,
    w: f32,
    radius: f32,
}

fn voronoi_texture(coord_in: vec3f, params: VoronoiParams) -> VoronoiResult {
    var p = params;
    p.detail = clamp(p.detail, 0.0, 15.0);
    p.roughness = clamp(p.roughness, 0.0, 1.0);
    p.randomness = clamp(p.randomness, 0.0, 1.0);
    p.smoothness = clamp(p.smoothness / 2.0, 0.0, 0.5);
    let coord = coord_in * p.scale;
    let reach = 0.5 + 0.5 * p.randomness;
    if p.feature == 3u {
        p.max_distance = reach;
        return VoronoiResult(fractal_voronoi_distance_to_edge(p, coord), vec3f(0.0), vec3f(0.0), 0.0, 0.0);
    }
    if p.feature == 4u {
        return VoronoiResult(0.0, vec3f(0.0), vec3f(0.0), 0.0, voronoi_n_sphere_radius(p, coord));
    }
    p.max_distance = voronoi_distance(vec3f(0.0), vec3f(reach), p) * select(1.0, 2.0, p.feature == 1u);
    let out = fractal_voronoi(p, coord);
    return VoronoiResult(out.distance, out.color, out.position, 0.0, 0.0);
}
