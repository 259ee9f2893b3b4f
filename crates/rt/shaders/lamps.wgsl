// Blender's lamps, as Cycles defines them (intern/cycles/kernel/light/point.h,
// spot.h, area.h, distant.h); the host has turned Blender's watts into the
// radiance each shape emits (src/bvh/lights.rs). As in Cycles, lamps are not
// geometry: they cast no shadow, a path passes through them, and every path ray
// tests each of them. Light sampling picks points by simpler densities than
// Cycles' (uniform over a rectangle's area, say): the estimate is the same, the
// noise differs.

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "rng.wgsl"
//#include "directions.wgsl"
//#if light_tree
//#include "light_tree.wgsl"
//#endif

// Lamp: declared in src/layout.rs (GpuLamp).
//#include "Lamp.struct.wgsl"

// LampInfo: declared in src/layout.rs (GpuLampInfo).
//#include "LampInfo.struct.wgsl"

//#include "lamps.bindings.wgsl"

// 1 − cos of a cone's half-angle from its sin², without cancellation (s < 1).
fn lamp_sin2_to_one_minus_cos(s: f32) -> f32 {
    return s / (1.0 + sqrt(max(1.0 - s, 0.0)));
}

// Uniform over the unit disk.
fn lamp_disk_point(u: vec2f) -> vec2f {
    let r = sqrt(u.x);
    let phi = 2.0 * PI * u.y;
    return vec2f(r * cos(phi), r * sin(phi));
}

// Uniform over the cone about `axis` whose half-angle has 1 − cos = `one_minus_cos`.
fn lamp_cone_direction(axis: vec3f, one_minus_cos: f32, u: vec2f) -> vec3f {
    let omc = u.x * one_minus_cos;
    let sin_t = sqrt(max(0.0, omc * (2.0 - omc)));
    let phi = 2.0 * PI * u.y;
    return tangent_frame(axis) * vec3f(sin_t * cos(phi), sin_t * sin(phi), 1.0 - omc);
}

//#if lamp_spot
// Cycles' smoothstepf: 0 below 0, 1 above 1.
fn lamp_smoothstep(f: f32) -> f32 {
    if f <= 0.0 {
        return 0.0;
    }
    if f >= 1.0 {
        return 1.0;
    }
    return f * f * (3.0 - 2.0 * f);
}

// The spot's cone with its blended edge, for light leaving the lamp along `from_lamp`.
fn spot_attenuation(l: Lamp, from_lamp: vec3f) -> f32 {
    return lamp_smoothstep((dot(from_lamp, l.axis_u) - l.len_u) * l.len_v);
}
//#endif

//#if lamp_round
// Radiance (rgb) that a ray from `o` along unit `w` meets on a point or spot lamp before
// `t_max`, and the solid-angle density (w) with which light sampling picks that direction.
fn round_lamp_hit(l: Lamp, o: vec3f, w: vec3f, t_max: f32) -> vec4f {
    if l.radius <= 0.0 {
        return vec4f(0.0);
    }
    let to_o = o - l.position;
    let d2 = dot(to_o, to_o);
    let r2 = l.radius * l.radius;
    var pdf = 0.0;
    if (l.kind & LAMP_SPHERE) != 0u {
        let b = dot(to_o, w);
        let off_axis = to_o - b * w;
        let discriminant = r2 - dot(off_axis, off_axis);
        if discriminant < 0.0 {
            return vec4f(0.0);
        }
        let root = sqrt(discriminant);
        // From inside, the far side.
        let t = select(-b + root, -b - root, -b - root > 0.0);
        if !(t > 0.0 && t < t_max) {
            return vec4f(0.0);
        }
        // Light sampling leaves a point inside the sphere to BSDF sampling.
        if d2 > r2 {
            pdf = 1.0 / (2.0 * PI * lamp_sin2_to_one_minus_cos(r2 / d2));
        }
    } else {
        // The disk through the centre that faces the ray's origin.
        let d = sqrt(d2);
        let cos_l = -dot(w, to_o) / d;
        if d <= 0.0 || cos_l <= 0.0 {
            return vec4f(0.0);
        }
        let t = d / cos_l;
        let q = o + t * w - l.position;
        if t >= t_max || dot(q, q) > r2 {
            return vec4f(0.0);
        }
        pdf = t * t / (PI * r2 * cos_l);
    }
    var radiance = l.emission;
    //#if lamp_spot
    if (l.kind & LAMP_KIND) == LAMP_SPOT && d2 > r2 {
        radiance *= spot_attenuation(l, -w);
    }
    //#endif
    return vec4f(radiance, pdf);
}
//#endif

// As `round_lamp_hit`, for any lamp; sun lamps only for rays that left the scene.
fn lamp_hit(l: Lamp, o: vec3f, w: vec3f, t_max: f32, escaped: bool) -> vec4f {
    let kind = l.kind & LAMP_KIND;
    //#if lamp_sun
    if kind == LAMP_SUN {
        // The chord |w − s|² = 2(1 − cos) keeps its digits for tiny angles.
        let chord = w - l.position;
        if !escaped || l.radius <= 0.0 || dot(chord, chord) > 2.0 * l.radius {
            return vec4f(0.0);
        }
        return vec4f(l.emission, 1.0 / (2.0 * PI * l.radius));
    }
    //#endif
    //#if lamp_area
    if kind == LAMP_AREA {
        // One-sided: only the side the normal points to emits.
        let cos_l = -dot(w, l.normal);
        if cos_l <= 0.0 {
            return vec4f(0.0);
        }
        let t = dot(o - l.position, l.normal) / cos_l;
        if !(t > 0.0 && t < t_max) {
            return vec4f(0.0);
        }
        let q = o + t * w - l.position;
        let x = dot(q, l.axis_u) / l.len_u;
        let y = dot(q, l.axis_v) / l.len_v;
        var area = l.len_u * l.len_v;
        if (l.kind & LAMP_ELLIPSE) != 0u {
            if x * x + y * y > 0.25 {
                return vec4f(0.0);
            }
            area *= 0.25 * PI;
        } else if abs(x) > 0.5 || abs(y) > 0.5 {
            return vec4f(0.0);
        }
        return vec4f(l.emission, t * t / (area * cos_l));
    }
    //#endif
    //#if lamp_round
    return round_lamp_hit(l, o, w, t_max);
    //#else
    return vec4f(0.0);
    //#endif
}

// Light of every lamp a path ray meets before `t_max` (of sun lamps when it leaves the
// scene), weighted for MIS against light sampling after a BSDF sample of density
// `bsdf_pdf` (0: nothing to weigh against). Camera rays see only lamps visible to them.
fn lamps_seen(origin: vec3f, direction: vec3f, t_max: f32, escaped: bool, bsdf_pdf: f32, camera_ray: bool) -> vec3f {
    var total = vec3f(0.0);
    for (var i = 0u; i < lamp_info.count; i++) {
        let l = lamps[i];
        if camera_ray && (l.kind & LAMP_CAMERA) == 0u {
            continue;
        }
        let seen = lamp_hit(l, origin, direction, t_max, escaped);
        if all(seen.rgb == vec3f(0.0)) {
            continue;
        }
        var weight = 1.0;
        //#if nee
        if bsdf_pdf > 0.0 && seen.w > 0.0 {
            weight = power_heuristic(bsdf_pdf, seen.w * lamp_selection(i));
        }
        //#endif
        total += seen.rgb * weight;
    }
    return total;
}

//#if nee
// Probability that light sampling picks lamp i.
fn lamp_probability(i: u32) -> f32 {
    var below = 0.0;
    if i > 0u {
        below = lamps[i - 1u].cdf;
    }
    return lamp_info.lamp_share * non_environment_share() * (lamps[i].cdf - below);
}

// Probability that light sampling picks lamp i, by the lamps' table or the light tree.
fn lamp_selection(i: u32) -> f32 {
    var p = lamp_probability(i);
    //#if light_tree
    p += emitter_share() * light_tree_probability(frame.emitter_count + i);
    //#endif
    return p;
}

// First lamp whose cumulative probability exceeds u.
fn find_lamp(u: f32) -> u32 {
    var lo = 0u;
    var hi = lamp_info.count - 1u;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        if lamps[mid].cdf > u {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

//#if lamp_round
fn sample_round_lamp(l: Lamp, p: vec3f, u: vec2f) -> LightSample {
    let none = LightSample(vec3f(0.0, 1.0, 0.0), 0.0, vec3f(0.0), 0.0, false);
    let to_p = p - l.position;
    let d2 = dot(to_p, to_p);
    let r2 = l.radius * l.radius;
    let d = sqrt(d2);
    if d <= 0.0 {
        return none;
    }
    let lamp_n = to_p / d;
    var s: LightSample;
    if l.radius <= 0.0 {
        // A point: `emission` is its intensity.
        s = LightSample(-lamp_n, d, l.emission / d2, 1.0, true);
    } else if (l.kind & LAMP_SPHERE) != 0u {
        if d2 <= r2 {
            return none;
        }
        let omc = lamp_sin2_to_one_minus_cos(r2 / d2);
        let w = lamp_cone_direction(-lamp_n, omc, u);
        // Law of cosines: the near side of the sphere along w.
        let cos_t = -dot(w, lamp_n);
        let t = d * cos_t - sqrt(max(r2 - d2 + d2 * cos_t * cos_t, 0.0));
        s = LightSample(w, t, l.emission, 1.0 / (2.0 * PI * omc), false);
    } else {
        // A disk facing the shaded point (Blender's soft falloff), sampled by area.
        let q = l.position + tangent_frame(lamp_n) * vec3f(l.radius * lamp_disk_point(u), 0.0);
        let to_q = q - p;
        let t = length(to_q);
        let w = to_q / t;
        let cos_l = -dot(w, lamp_n);
        if !(t > 0.0) || cos_l <= 0.0 {
            return none;
        }
        s = LightSample(w, t, l.emission, t * t / (PI * r2 * cos_l), false);
    }
    //#if lamp_spot
    if (l.kind & LAMP_KIND) == LAMP_SPOT && d2 > r2 {
        s.radiance *= spot_attenuation(l, -s.direction);
    }
    //#endif
    return s;
}
//#endif

// A direction towards lamp `l` from `p`, with its solid-angle density (selection not included).
fn sample_lamp_shape(l: Lamp, p: vec3f, u: vec2f) -> LightSample {
    let none = LightSample(vec3f(0.0, 1.0, 0.0), 0.0, vec3f(0.0), 0.0, false);
    let kind = l.kind & LAMP_KIND;
    //#if lamp_sun
    if kind == LAMP_SUN {
        if l.radius <= 0.0 {
            // A delta direction: `emission` is the irradiance on a plane facing it.
            return LightSample(l.position, INFINITY, l.emission, 1.0, true);
        }
        let w = lamp_cone_direction(l.position, l.radius, u);
        return LightSample(w, INFINITY, l.emission, 1.0 / (2.0 * PI * l.radius), false);
    }
    //#endif
    //#if lamp_area
    if kind == LAMP_AREA {
        if dot(p - l.position, l.normal) <= 0.0 {
            return none;
        }
        var offset = u - 0.5;
        var area = l.len_u * l.len_v;
        if (l.kind & LAMP_ELLIPSE) != 0u {
            offset = 0.5 * lamp_disk_point(u);
            area *= 0.25 * PI;
        }
        let q = l.position + offset.x * l.len_u * l.axis_u + offset.y * l.len_v * l.axis_v;
        let to_q = q - p;
        let t = length(to_q);
        let w = to_q / t;
        let cos_l = -dot(w, l.normal);
        if !(t > 0.0) || cos_l <= 0.0 {
            return none;
        }
        return LightSample(w, t, l.emission, t * t / (area * cos_l), false);
    }
    //#endif
    //#if lamp_round
    return sample_round_lamp(l, p, u);
    //#else
    return none;
    //#endif
}

// A light sample towards one lamp, picked in proportion to its power; the density
// includes the selection.
fn sample_lamp(p: vec3f, rng: ptr<function, Rng>) -> LightSample {
    let i = find_lamp(rng_next(rng));
    let u = rng_next2(rng);
    var s = sample_lamp_shape(lamps[i], p, u);
    s.pdf *= lamp_selection(i);
    return s;
}
//#endif
