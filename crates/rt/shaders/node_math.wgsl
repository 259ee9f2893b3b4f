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
        case 27u: { return vec4f(safe_powf(a.x, b.x), safe_powf(a.y, b.y), safe_powf(a.z, b.z), 0.0); }
        case 28u: { return vec4f(sign(a), 0.0); }
        default: { return vec4f(0.0); }
    }
}

// Cycles' rgb_to_hsv and hsv_to_rgb (util/color.h).
fn rgb_to_hsv(rgb: vec3f) -> vec3f {
    let cmax = max(rgb.x, max(rgb.y, rgb.z));
    let cmin = min(rgb.x, min(rgb.y, rgb.z));
    let cdelta = cmax - cmin;
    let s = select(0.0, cdelta / cmax, cmax != 0.0);
    if s == 0.0 {
        return vec3f(0.0, s, cmax);
    }
    let c = (vec3f(cmax) - rgb) / cdelta;
    var h: f32;
    if rgb.x == cmax {
        h = c.z - c.y;
    } else if rgb.y == cmax {
        h = 2.0 + c.x - c.z;
    } else {
        h = 4.0 + c.y - c.x;
    }
    h /= 6.0;
    return vec3f(select(h, h + 1.0, h < 0.0), s, cmax);
}

fn hsv_to_rgb(hsv: vec3f) -> vec3f {
    let s = hsv.y;
    let v = hsv.z;
    if s == 0.0 {
        return vec3f(v);
    }
    let h = select(hsv.x, 0.0, hsv.x == 1.0) * 6.0;
    let i = floor(h);
    let f = h - i;
    let p = v * (1.0 - s);
    let q = v * (1.0 - s * f);
    let t = v * (1.0 - s * (1.0 - f));
    switch i32(i) {
        case 0: { return vec3f(v, t, p); }
        case 1: { return vec3f(q, v, p); }
        case 2: { return vec3f(p, v, t); }
        case 3: { return vec3f(p, q, v); }
        case 4: { return vec3f(t, p, v); }
        default: { return vec3f(v, p, q); }
    }
}

// Cycles' rgb_to_hsl and hsl_to_rgb (util/color.h).
fn rgb_to_hsl(rgb: vec3f) -> vec3f {
    let cmax = max(rgb.x, max(rgb.y, rgb.z));
    let cmin = min(rgb.x, min(rgb.y, rgb.z));
    let l = min(1.0, (cmax + cmin) / 2.0);
    if cmax == cmin {
        return vec3f(0.0, 0.0, l);
    }
    let cdelta = cmax - cmin;
    let s = select(cdelta / (cmax + cmin), cdelta / (2.0 - cmax - cmin), l > 0.5);
    var h: f32;
    if cmax == rgb.x {
        h = (rgb.y - rgb.z) / cdelta + select(0.0, 6.0, rgb.y < rgb.z);
    } else if cmax == rgb.y {
        h = (rgb.z - rgb.x) / cdelta + 2.0;
    } else {
        h = (rgb.x - rgb.y) / cdelta + 4.0;
    }
    return vec3f(h / 6.0, s, l);
}

fn hsl_to_rgb(hsl: vec3f) -> vec3f {
    let h = hsl.x;
    let n = clamp(vec3f(abs(h * 6.0 - 3.0) - 1.0, 2.0 - abs(h * 6.0 - 2.0), 2.0 - abs(h * 6.0 - 4.0)), vec3f(0.0), vec3f(1.0));
    let chroma = (1.0 - abs(2.0 * hsl.z - 1.0)) * hsl.y;
    return (n - 0.5) * chroma + hsl.z;
}

// Hue, Saturation, Value and Color blends (svm_mix_hue, _sat, _val, _color).
fn node_blend_hsv(blend: u32, t: f32, a: vec3f, b: vec3f) -> vec3f {
    let hsv = rgb_to_hsv(a);
    let hsv2 = rgb_to_hsv(b);
    switch blend {
        case 15u: {
            return select(a, mix(a, hsv_to_rgb(vec3f(hsv2.x, hsv.y, hsv.z)), t), hsv2.y != 0.0);
        }
        case 16u: {
            return select(a, hsv_to_rgb(vec3f(hsv.x, mix(hsv.y, hsv2.y, t), hsv.z)), hsv.y != 0.0);
        }
        case 17u: {
            return hsv_to_rgb(vec3f(hsv.x, hsv.y, mix(hsv.z, hsv2.z, t)));
        }
        default: {
            return select(a, mix(a, hsv_to_rgb(vec3f(hsv2.x, hsv2.y, hsv.z)), t), hsv2.y != 0.0);
        }
    }
}

// Hue/Saturation/Value node: its colour turned in hue, scaled in saturation and value,
// mixed with the input by `fac`, kept non-negative.
fn node_hue_saturation(hue: f32, saturation: f32, value: f32, fac: f32, color: vec3f) -> vec3f {
    var hsv = rgb_to_hsv(color);
    let h = hsv.x + hue + 0.5;
    hsv = vec3f(h - floor(h), clamp(hsv.y * saturation, 0.0, 1.0), hsv.z * value);
    return max(mix(color, hsv_to_rgb(hsv), fac), vec3f(0.0));
}

fn node_gamma(color: vec3f, gamma: f32) -> vec3f {
    if gamma == 0.0 {
        return vec3f(1.0);
    }
    return select(color, pow(color, vec3f(gamma)), color > vec3f(0.0));
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
        case 15u, 16u, 17u, 18u: { return node_blend_hsv(blend, t, a, b); }
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
