// Blender's Math, Vector Math, Mix, Map Range and Clamp nodes, with Cycles' definitions
// of the cases floats leave open (kernel/svm/math_util.h, util/math_base.h): a division
// by zero gives 0, a power of a negative base to a non-integer exponent 0, the log of a
// non-positive number 0. Operations are numbered as in src/asset/node_kinds.rs.

fn safe_divide(a: f32, b: f32) -> f32 {
    return select(0.0, a / b, b != 0.0);
}

fn safe_divide3(a: vec3f, b: vec3f) -> vec3f {
    return vec3f(safe_divide(a.x, b.x), safe_divide(a.y, b.y), safe_divide(a.z, b.z));
}

fn safe_modulo(a: f32, b: f32) -> f32 {
    return select(0.0, a % b, b != 0.0);
}

fn safe_powf(a: f32, b: f32) -> f32 {
    if a < 0.0 && b != f32(i32(b)) {
        return 0.0;
    }
    if b == 0.0 {
        return 1.0;
    }
    if a < 0.0 {
        // An integer exponent: odd ones keep the sign.
        return select(-1.0, 1.0, (-b) % 2.0 == 0.0) * pow(-a, b);
    }
    return select(pow(a, b), 0.0, a == 0.0);
}

fn wrapf(value: f32, maximum: f32, minimum: f32) -> f32 {
    let range = maximum - minimum;
    return select(minimum, value - range * floor((value - minimum) / range), range != 0.0);
}

fn pingpongf(a: f32, b: f32) -> f32 {
    if b == 0.0 {
        return 0.0;
    }
    let t = (a - b) / (b * 2.0);
    return abs((t - floor(t)) * b * 2.0 - b);
}

fn smoothminf(a: f32, b: f32, k: f32) -> f32 {
    if k == 0.0 {
        return min(a, b);
    }
    let h = max(k - abs(a - b), 0.0) / k;
    return min(a, b) - h * h * h * k * (1.0 / 6.0);
}

fn node_math(operation: u32, a: f32, b: f32, c: f32) -> f32 {
    switch operation {
        case 0u: { return a + b; }
        case 1u: { return a - b; }
        case 2u: { return a * b; }
        case 3u: { return safe_divide(a, b); }
        case 4u: { return a * b + c; }
        case 5u: { return safe_powf(a, b); }
        case 6u: { return select(safe_divide(log(a), log(b)), 0.0, a <= 0.0 || b <= 0.0); }
        case 7u: { return sqrt(max(a, 0.0)); }
        case 8u: { return select(0.0, inverseSqrt(a), a > 0.0); }
        case 9u: { return abs(a); }
        case 10u: { return exp(a); }
        case 11u: { return min(a, b); }
        case 12u: { return max(a, b); }
        case 13u: { return select(0.0, 1.0, a < b); }
        case 14u: { return select(0.0, 1.0, a > b); }
        case 15u: { return sign(a); }
        case 16u: { return select(0.0, 1.0, a == b || abs(a - b) <= max(c, 1.1920929e-7)); }
        case 17u: { return smoothminf(a, b, c); }
        case 18u: { return -smoothminf(-a, -b, c); }
        case 19u: { return floor(a + 0.5); }
        case 20u: { return floor(a); }
        case 21u: { return ceil(a); }
        case 22u: { return trunc(a); }
        case 23u: { return a - floor(a); }
        case 24u: { return safe_modulo(a, b); }
        case 25u: { return select(0.0, a - floor(a / b) * b, b != 0.0); }
        case 26u: { return wrapf(a, b, c); }
        case 27u: { return floor(safe_divide(a, b)) * b; }
        case 28u: { return pingpongf(a, b); }
        case 29u: { return sin(a); }
        case 30u: { return cos(a); }
        case 31u: { return tan(a); }
        case 32u: { return asin(clamp(a, -1.0, 1.0)); }
        case 33u: { return acos(clamp(a, -1.0, 1.0)); }
        case 34u: { return atan(a); }
        case 35u: { return atan2(a, b); }
        case 36u: { return sinh(a); }
        case 37u: { return cosh(a); }
        case 38u: { return tanh(a); }
        case 39u: { return a * (PI / 180.0); }
        case 40u: { return a * (180.0 / PI); }
        default: { return 0.0; }
    }
}

fn safe_normalize(a: vec3f) -> vec3f {
    let l = length(a);
    return select(a, a / l, l != 0.0);
}

fn node_refract(incident: vec3f, normal: vec3f, eta: f32) -> vec3f {
    let n_dot_i = dot(normal, incident);
    let k = 1.0 - eta * eta * (1.0 - n_dot_i * n_dot_i);
    return select(eta * incident - (eta * n_dot_i + sqrt(k)) * normal, vec3f(0.0), k < 0.0);
}

// Vector Math: the Vector output in xyz, the Value output in w.
fn node_vector_math(operation: u32, a: vec3f, b: vec3f, c: vec3f, scale: f32) -> vec4f {
    switch operation {
        case 0u: { return vec4f(a + b, 0.0); }
        case 1u: { return vec4f(a - b, 0.0); }
        case 2u: { return vec4f(a * b, 0.0); }
        case 3u: { return vec4f(safe_divide3(a, b), 0.0); }
        case 4u: { return vec4f(a * b + c, 0.0); }
        case 5u: { return vec4f(cross(a, b), 0.0); }
        case 6u: {
            let l = dot(b, b);
            return vec4f(select(vec3f(0.0), dot(a, b) / l * b, l != 0.0), 0.0);
        }
        case 7u: {
            let n = normalize(b);
            return vec4f(a - 2.0 * dot(a, n) * n, 0.0);
        }
        case 8u: { return vec4f(node_refract(a, normalize(b), scale), 0.0); }
        case 9u: { return vec4f(select(-a, a, dot(c, b) < 0.0), 0.0); }
        case 10u: { return vec4f(0.0, 0.0, 0.0, dot(a, b)); }
        case 11u: { return vec4f(0.0, 0.0, 0.0, distance(a, b)); }
        case 12u: { return vec4f(0.0, 0.0, 0.0, length(a)); }
        case 13u: { return vec4f(a * scale, 0.0); }
        case 14u: { return vec4f(safe_normalize(a), 0.0); }
        case 15u: { return vec4f(abs(a), 0.0); }
        case 16u: { return vec4f(min(a, b), 0.0); }
        case 17u: { return vec4f(max(a, b), 0.0); }
        case 18u: { return vec4f(floor(a), 0.0); }
        case 19u: { return vec4f(ceil(a), 0.0); }
        case 20u: { return vec4f(a - floor(a), 0.0); }
        case 21u: { return vec4f(safe_modulo(a.x, b.x), safe_modulo(a.y, b.y), safe_modulo(a.z, b.z), 0.0); }
        case 22u: { return vec4f(wrapf(a.x, b.x, c.x), wrapf(a.y, b.y, c.y), wrapf(a.z, b.z, c.z), 0.0); }
        case 23u: { return vec4f(floor(safe_divide3(a, b)) * b, 0.0); }
        case 24u: { return vec4f(sin(a), 0.0); }
        case 25u: { return vec4f(cos(a), 0.0); }
        case 26u: { return vec4f(tan(a), 0.0); }
        default: { return vec4f(0.0); }
    }
}

// A colour blend of Cycles' svm_mix, with the factor t already clamped or not.
fn node_blend(blend: u32, t: f32, a: vec3f, b: vec3f) -> vec3f {
    let tm = 1.0 - t;
    switch blend {
        case 1u: { return mix(a, min(a, b), t); }
        case 2u: { return a * (tm + t * b); }
        case 3u: {
            let tmp = tm + t * b;
            return select(clamp(1.0 - (1.0 - a) / tmp, vec3f(0.0), vec3f(1.0)), vec3f(0.0), tmp <= vec3f(0.0));
        }
        case 4u: { return mix(a, max(a, b), t); }
        case 5u: { return 1.0 - (tm + t * (1.0 - b)) * (1.0 - a); }
        case 6u: {
            let tmp = 1.0 - t * b;
            let dodged = select(min(a / tmp, vec3f(1.0)), vec3f(1.0), tmp <= vec3f(0.0));
            return select(a, dodged, a != vec3f(0.0));
        }
        case 7u: { return a + t * b; }
        case 8u: {
            let low = a * (tm + 2.0 * t * b);
            let high = 1.0 - (tm + 2.0 * t * (1.0 - b)) * (1.0 - a);
            return select(high, low, a < vec3f(0.5));
        }
        case 9u: {
            let screen = 1.0 - (1.0 - b) * (1.0 - a);
            return tm * a + t * ((1.0 - a) * b * a + a * screen);
        }
        case 10u: { return a + t * (2.0 * b - 1.0); }
        case 11u: { return mix(a, abs(a - b), t); }
        case 12u: { return max(mix(a, a + b - 2.0 * a * b, t), vec3f(0.0)); }
        case 13u: { return a - t * b; }
        case 14u: {
            return select(a, a * tm + t * a / b, b != vec3f(0.0));
        }
        default: { return mix(a, b, t); }
    }
}

// The Mix node (and the legacy MixRGB): `flags` bit 0 clamps the factor, bit 1 the
// result; bits 2-3 the data type (0 float, 1 vector, 2 colour); bit 4 a vector factor.
fn node_mix(blend: u32, flags: u32, factor: vec4f, a: vec4f, b: vec4f) -> vec4f {
    let data_type = (flags >> 2u) & 3u;
    var t = factor;
    if (flags & 1u) != 0u {
        t = clamp(t, vec4f(0.0), vec4f(1.0));
    }
    if data_type == 0u {
        return vec4f(mix(a.x, b.x, t.x));
    }
    if data_type == 1u {
        let per_axis = select(vec3f(t.x), t.xyz, (flags & 16u) != 0u);
        return vec4f(mix(a.xyz, b.xyz, per_axis), 0.0);
    }
    var result = node_blend(blend, t.x, a.xyz, b.xyz);
    if (flags & 2u) != 0u {
        result = clamp(result, vec3f(0.0), vec3f(1.0));
    }
    return vec4f(result, 1.0);
}

fn node_smoothstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    if x < edge0 {
        return 0.0;
    }
    if x >= edge1 {
        return 1.0;
    }
    let t = (x - edge0) / (edge1 - edge0);
    return (3.0 - 2.0 * t) * (t * t);
}

fn node_smootherstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t = clamp(safe_divide(x - edge0, edge1 - edge0), 0.0, 1.0);
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// Clamp in the Range mode: between the two bounds, whichever is lower.
fn clamp_range(value: f32, a: f32, b: f32) -> f32 {
    return select(clamp(value, a, b), clamp(value, b, a), a > b);
}

// Map Range of floats: interpolation 0 linear, 1 stepped, 2 smoothstep, 3 smootherstep;
// `clamp_result` (linear and stepped only, as in Blender) keeps the result in the target range.
fn node_map_range(interpolation: u32, clamp_result: bool, value: f32, from_min: f32, from_max: f32, to_min: f32, to_max: f32, steps: f32) -> f32 {
    if from_max == from_min {
        return 0.0;
    }
    var factor = (value - from_min) / (from_max - from_min);
    if interpolation == 1u {
        factor = select(0.0, floor(factor * (steps + 1.0)) / steps, steps > 0.0);
    } else if interpolation == 2u {
        factor = select(node_smoothstep(from_min, from_max, value), 1.0 - node_smoothstep(from_max, from_min, value), from_min > from_max);
    } else if interpolation == 3u {
        factor = select(node_smootherstep(from_min, from_max, value), 1.0 - node_smootherstep(from_max, from_min, value), from_min > from_max);
    }
    let result = to_min + factor * (to_max - to_min);
    if clamp_result && interpolation <= 1u {
        return clamp_range(result, to_min, to_max);
    }
    return result;
}
