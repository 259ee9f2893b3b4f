// Next-event estimation: a light sample towards the sun, an emitter (picked
// in proportion to power: area × luminance of emission) or a lamp, weighed against
// BSDF sampling by the power heuristic (Veach 1997).

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "rng.wgsl"
//#include "ray.wgsl"
//#include "transform.wgsl"
//#include "motion.wgsl"
//#include "directions.wgsl"
//#include "hit.wgsl"
//#include "bsdf.wgsl"
//#include "bsdf_eval.wgsl"
//#include "layered_emission.wgsl"
//#if lamps
//#include "lamps.wgsl"
//#endif
//#if light_tree
//#include "light_tree.wgsl"
//#endif
//#if spheres
//#include "sphere.wgsl"
//#endif
//#if sun
//#include "sun.wgsl"
//#if textures
//#include "texture.wgsl"
//#endif
//#if node_graphs
//#include "node_program.wgsl"
//#endif
//#endif
//#if media
//#include "segment.wgsl"
//#endif
//#if sky_atmosphere
//#include "atmosphere_sky.wgsl"
//#endif
//#if sky_graph
//#if node_graphs
//#include "sky_graph.wgsl"
//#endif
//#endif
//#if sky_environment
//#include "environment.wgsl"
//#endif

struct LightSample {
    direction: vec3f,
    distance: f32,
    radiance: vec3f,
    // Solid-angle density, selection included; for a delta light, the selection probability.
    pdf: f32,
    // A point or a sun of angle 0: no BSDF sample finds it, so no MIS weight.
    delta: bool,
}

fn power_heuristic(a: f32, b: f32) -> f32 {
    let a2 = a * a;
    return a2 / (a2 + b * b);
}

// Probability that a light sample goes to a light other than the environment: the
// other shares are fractions of it.
fn non_environment_share() -> f32 {
    //#if sky_environment
    return 1.0 - environment.light_share;
    //#endif
    //#if sky_uniform_light
    return 1.0 - frame.sky_light_share;
    //#endif
    //#if sky_graph
    return 1.0 - frame.sky_light_share;
    //#endif
    //#if !sky_environment
    //#if !sky_uniform_light
    //#if !sky_graph
    return 1.0;
    //#endif
    //#endif
    //#endif
}

// Probabilities that a light sample goes to the [sun], and to an emitter.
fn sun_share() -> f32 {
    //#if lamps
    return lamp_info.sun_share * non_environment_share();
    //#else
    return frame.sun_select_probability * non_environment_share();
    //#endif
}

fn emitter_share() -> f32 {
    //#if lamps
    return lamp_info.emitter_share * non_environment_share();
    //#else
    return (1.0 - frame.sun_select_probability) * non_environment_share();
    //#endif
}

// 1 − cos of the half-angle under which a sphere is seen from `p`; < 0 from inside.
fn sphere_cone_one_minus_cos(p: vec3f, s: Sphere) -> f32 {
    let to_center = s.center - p;
    let sin2 = s.radius * s.radius / dot(to_center, to_center);
    if sin2 >= 1.0 {
        return -1.0;
    }
    return sin2 / (1.0 + sqrt(1.0 - sin2));
}

// Light sampling never picks a surface that does not emit, nor any in a scene without
// emitters (whose total power is 0: the densities below would be 0/0 there).
fn never_sampled(emission_luminance: f32) -> bool {
    return emission_luminance <= 0.0 || frame.emitter_total_power <= 0.0;
}

// Probability per unit area that light sampling picks a point of an emitter: by power,
// or with the light tree, the probability `tree_selection` of the tree's walk (share
// included) spread over the emitter's `area`.
fn emitter_selection_per_area(emission_luminance: f32, tree_selection: f32, area: f32) -> f32 {
    //#if light_tree
    return tree_selection / area;
    //#else
    if never_sampled(emission_luminance) {
        return 0.0;
    }
    return emitter_share() * emission_luminance / frame.emitter_total_power;
    //#endif
}

// The tree's probability (share included) of the emitter a ray hit; 0 without the tree.
fn tree_selection_of_hit(instance: u32, primitive: u32) -> f32 {
    //#if light_tree
    let index = emitter_index_of(instance, primitive);
    if index != LIGHT_TREE_ABSENT {
        return emitter_share() * light_tree_probability(index);
    }
    //#endif
    return 0.0;
}

// Density of reaching an emissive triangle at distance t along `direction` by light sampling.
fn triangle_emitter_pdf(selection_per_area: f32, t: f32, cos_light: f32) -> f32 {
    return selection_per_area * t * t / max(cos_light, 1e-12);
}

fn triangle_hit_pdf(emission_luminance: f32, hit: Hit, cos_light: f32) -> f32 {
    var area = 1.0;
    //#if light_tree
    area = triangle_world_area(hit.instance, hit.primitive);
    //#endif
    let selection = tree_selection_of_hit(hit.instance, hit.primitive);
    return triangle_emitter_pdf(emitter_selection_per_area(emission_luminance, selection, area), hit.t, cos_light);
}

fn sphere_emitter_pdf(p: vec3f, s: Sphere, selection_per_area: f32) -> f32 {
    let omc = sphere_cone_one_minus_cos(p, s);
    if omc <= 0.0 {
        return 0.0;
    }
    return selection_per_area * 4.0 * PI * s.radius * s.radius / (2.0 * PI * omc);
}

fn sphere_hit_pdf(p: vec3f, index: u32, emission_luminance: f32) -> f32 {
    let s = spheres[index];
    let selection = tree_selection_of_hit(0u, index | SPHERE_BIT);
    return sphere_emitter_pdf(p, s, emitter_selection_per_area(emission_luminance, selection, 4.0 * PI * s.radius * s.radius));
}

//#if !light_tree
// First emitter whose cumulative probability exceeds u.
fn find_emitter(u: f32) -> u32 {
    var lo = 0u;
    var hi = frame.emitter_count - 1u;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        if emitters[mid].cdf > u {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

fn sample_emitter(p: vec3f, rng: ptr<function, Rng>) -> LightSample {
    return sample_emitter_at(emitters[find_emitter(rng_next(rng))], 0.0, p, rng);
}
//#endif

// The distance to an emitter's sampled point at `t`, brought forward off its surface by
// twice the point's rounding `error` across it (arriving at `cos_light`): a shadow ray aimed
// there then ends before the surface, however grazing its arrival, rather than meeting it
// first and counting the light as blocked (pbrt-v4 moves both ends of a shadow ray so).
fn lifted_off_the_light(t: f32, error: f32, cos_light: f32) -> f32 {
    return max(t - 2.0 * error / max(cos_light, 1e-3), 0.5 * t);
}

// A light sample towards emitter `e`, picked with probability `tree_selection` by the
// light tree (unused without it); its distance ends just before the emitter's surface
// (`lifted_off_the_light`).
fn sample_emitter_at(e: Emitter, tree_selection: f32, p: vec3f, rng: ptr<function, Rng>) -> LightSample {
    let u = rng_next2(rng);
    if (e.primitive & SPHERE_BIT) != 0u {
        //#if spheres
        return sample_sphere_emitter(e, tree_selection, p, u);
        //#endif
    }
    //#if triangles
    return sample_triangle_emitter(e, tree_selection, p, u);
    //#else
    return LightSample(vec3f(0.0, 1.0, 0.0), 0.0, vec3f(0.0), 0.0, false);
    //#endif
}

//#if spheres
// A direction to emitting sphere `e` from `p`, uniform in the cone it fills (`u`).
fn sample_sphere_emitter(e: Emitter, tree_selection: f32, p: vec3f, u: vec2f) -> LightSample {
    let none = LightSample(vec3f(0.0, 1.0, 0.0), 0.0, vec3f(0.0), 0.0, false);
    let s = spheres[e.primitive & ~SPHERE_BIT];
    let omc = sphere_cone_one_minus_cos(p, s);
    if omc <= 0.0 {
        return none;
    }
    let one_minus_cos = u.x * omc;
    let sin_t = sqrt(max(0.0, one_minus_cos * (2.0 - one_minus_cos)));
    let phi = 2.0 * PI * u.y;
    let axis = normalize(s.center - p);
    let d = tangent_frame(axis) * vec3f(sin_t * cos(phi), sin_t * sin(phi), 1.0 - one_minus_cos);
    let t = intersect_sphere(p, d, s.center, s.radius, s.k, INFINITY);
    if t == INFINITY {
        return none;
    }
    let m = materials[s.material];
    let selection = emitter_selection_per_area(m.emission_luminance, tree_selection, 4.0 * PI * s.radius * s.radius);
    // The radial normal on the viewer's side: a sphere seen from inside emits too.
    let radial = normalize(p + t * d - s.center);
    let towards = select(radial, -radial, dot(radial, d) > 0.0);
    let emission = light_sampled_emission(m, m.emission, towards, -d);
    let error = gamma(7.0) * (dot(abs(radial), abs(s.center)) + s.radius);
    let before = lifted_off_the_light(t, error, abs(dot(radial, d)));
    return LightSample(d, before, emission, sphere_emitter_pdf(p, s, selection), false);
}
//#endif

//#if triangles
// A point of emitting triangle `e`, uniform in its area (`u`), seen from `p`.
fn sample_triangle_emitter(e: Emitter, tree_selection: f32, p: vec3f, u: vec2f) -> LightSample {
    let inst = instance_at(e.instance);
    let tri = triangles[e.primitive];
    let to_world = affine_inverse(inst.world_to_object).m;
    let v0 = transform_point(to_world, tri.v0);
    let v1 = transform_point(to_world, tri.v1);
    let v2 = transform_point(to_world, tri.v2);
    let su = sqrt(u.x);
    let q = (1.0 - su) * v0 + su * (1.0 - u.y) * v1 + su * u.y * v2;
    let to_light = q - p;
    let t = length(to_light);
    if t <= 0.0 {
        return LightSample(vec3f(0.0, 1.0, 0.0), 0.0, vec3f(0.0), 0.0, false);
    }
    let d = to_light / t;
    let normal = cross(v1 - v0, v2 - v0);
    let n = normalize(normal);
    var material = inst.material_override;
    if material == NO_MATERIAL {
        material = inst.material_base + tri.material;
    }
    var m = materials[material];
    var emission = m.emission;
    //#if textures
    emission = textured_emission(m, e.primitive, su * (1.0 - u.y), su * u.y);
    //#endif
    //#if node_graphs
    if m.node_program != NO_PROGRAM {
        let sh = shading[e.primitive];
        let b1 = su * (1.0 - u.y);
        let b2 = su * u.y;
        let n_object = (1.0 - b1 - b2) * sh.n0 + b1 * sh.n1 + b2 * sh.n2;
        let n_shading = normalize(transform_normal_to_world(inst.world_to_object, n_object));
        var lit = m;
        lit.emission = emission;
        let graph = run_node_program(m.node_program, node_point_on_triangle(e.instance, inst, e.primitive, b1, b2, q, n_shading, -d));
        // Of a Mix Shader, only its first shader emits (the exporter puts it first): the
        // light is its share of the point.
        emission = node_graph_applied(lit, graph).emission * node_first_share(m, graph);
    }
    //#endif
    //#if coat
    //#if layer_textures
    m = layer_textured_at(m, e.primitive, su * (1.0 - u.y), su * u.y);
    //#endif
    if m.coat > 0.0 {
        emission = emission_under_coat(m, emission, e, inst, n, su, u.y, t, d);
    }
    //#endif
    let selection = emitter_selection_per_area(m.emission_luminance, tree_selection, 0.5 * length(normal));
    let cos_light = abs(dot(n, d));
    let error = gamma(7.0) * dot(abs(n), abs((1.0 - su) * v0) + abs(su * (1.0 - u.y) * v1) + abs(su * u.y * v2));
    let before = lifted_off_the_light(t, error, cos_light);
    return LightSample(d, before, emission, triangle_emitter_pdf(selection, t, cos_light), false);
}
//#endif

//#if coat
//#if triangles
// `emission` of the triangle's point (`su`, `v`: its sample) seen through the coat of
// `m` from direction `d` at distance `t`; `n` is the triangle's true normal.
fn emission_under_coat(m: Material, emission: vec3f, e: Emitter, inst: Instance, n: vec3f, su: f32, v: f32, t: f32, d: vec3f) -> vec3f {
    // The coat's tint is seen along its normal as at a hit on this point (`emission_seen`).
    let sh = shading[e.primitive];
    let n_object = (1.0 - su) * sh.n0 + su * (1.0 - v) * sh.n1 + su * v * sh.n2;
    let n_shading = normalize(transform_normal_to_world(inst.world_to_object, n_object));
    // The coat's normal: its own map's, or where it shares the base's, that map's.
    var coat = n_shading;
    // The true normal, on the interpolated one's side (a mirroring instance flips the winding's).
    let n_true = select(-n, n, dot(n, n_shading) >= 0.0);
    //#if normal_maps
    let b1 = su * (1.0 - v);
    let b2 = su * v;
    let at = Hit(t, HIT_TRIANGLE, e.primitive, e.instance, b1, b2);
    //#if coat_normal
    coat = coat_normal_mapped(m, at, n_shading, n_true, -d, triangle_uv(e.primitive, uv_set_of(m, UV1_COAT_NORMAL), b1, b2));
    //#else
    coat = normal_mapped(m, at, n_shading, n_true, -d, triangle_uv(e.primitive, uv_set_of(m, UV1_NORMAL), b1, b2));
    //#endif
    //#endif
    // Turned to the side of the point lit, as the true normal is (see layered_emission.wgsl).
    let side = select(-1.0, 1.0, dot(n_true, d) < 0.0);
    return light_sampled_emission(m, emission, side * coat, -d);
}
//#endif
//#endif

// The density of a light sample of a sky sampled uniformly over the sphere, which takes
// `sky_light_share` of the light samples.
fn uniform_sky_light_pdf() -> f32 {
    return frame.sky_light_share / (4.0 * PI);
}

// A direction uniformly over the unit sphere, from two uniform numbers.
fn uniform_sphere_direction(u: vec2f) -> vec3f {
    let z = 1.0 - 2.0 * u.x;
    let r = sqrt(max(0.0, 1.0 - z * z));
    let phi = 2.0 * PI * u.y;
    return vec3f(r * cos(phi), r * sin(phi), z);
}

fn sample_light(p: vec3f, rng: ptr<function, Rng>) -> LightSample {
    let none = LightSample(vec3f(0.0, 1.0, 0.0), 0.0, vec3f(0.0), 0.0, false);
    //#if sky_environment
    if rng_next(rng) < environment.light_share {
        let e = sample_environment(rng);
        return LightSample(e.direction, INFINITY, e.radiance, e.pdf * environment.light_share, false);
    }
    //#endif
    //#if sky_uniform_light
    // Uniformly over the sphere: a constant sky has no brighter part to aim for.
    if rng_next(rng) < frame.sky_light_share {
        let d = uniform_sphere_direction(rng_next2(rng));
        return LightSample(d, INFINITY, frame.sky_color, uniform_sky_light_pdf(), false);
    }
    //#endif
    //#if sky_graph
    // The world's graph, uniformly over the sphere, evaluated as a light sample sees it.
    if rng_next(rng) < frame.sky_light_share {
        let d = uniform_sphere_direction(rng_next2(rng));
        var radiance = vec3f(0.0);
        //#if node_graphs
        radiance = graph_sky_radiance(d, vec3f(0.0), NODE_RAY_NONE, false, 0u, 0u);
        //#endif
        return LightSample(d, INFINITY, radiance, uniform_sky_light_pdf(), false);
    }
    //#endif
    // Below, the choice among the other lights (their shares without the environment's part).
    //#if lamps
    let u = rng_next(rng);
    let sun_picked = u < lamp_info.sun_share;
    if u >= lamp_info.sun_share + lamp_info.emitter_share {
        if lamp_info.count == 0u {
            return none;
        }
        return sample_lamp(p, rng);
    }
    //#else
    var sun_picked = false;
    //#if sun
    sun_picked = rng_next(rng) < frame.sun_select_probability;
    //#endif
    //#endif
    //#if sun
    if sun_picked {
        let d = sample_sun_direction(rng_next2(rng));
        return LightSample(d, INFINITY, sun_radiance_at(p, d), sun_share() / sun_solid_angle(), false);
    }
    //#endif
    //#if light_tree
    return sample_light_tree(p, rng);
    //#else
    if frame.emitter_count == 0u {
        return none;
    }
    return sample_emitter(p, rng);
    //#endif
}

//#if light_tree
// A light sample towards the emitter or lamp that a walk down the light tree picks.
fn sample_light_tree(p: vec3f, rng: ptr<function, Rng>) -> LightSample {
    let none = LightSample(vec3f(0.0, 1.0, 0.0), 0.0, vec3f(0.0), 0.0, false);
    let pick = light_tree_pick(rng);
    if !(pick.probability > 0.0) {
        return none;
    }
    let selection = emitter_share() * pick.probability;
    //#if lamps
    if (pick.light & LIGHT_TREE_LAMP) != 0u {
        let i = pick.light & ~LIGHT_TREE_LAMP;
        var s = sample_lamp_shape(lamps[i], p, rng_next2(rng));
        // The lamps' own table may pick it too.
        s.pdf *= selection + lamp_probability(i);
        return s;
    }
    //#endif
    return sample_emitter_at(emitters[pick.light], selection, p, rng);
}
//#endif

// A light sample's contribution and the shadow ray that decides it.
struct ShadowRay {
    origin: vec3f,
    t_max: f32,
    direction: vec3f,
    // Unoccluded, the sample adds this (BSDF, MIS weight and the medium's transmittance included).
    contribution: vec3f,
}

// Light arriving directly at the surface point from one light sample, through
// the BSDF, weighted for MIS, if nothing blocks the returned shadow ray. The ray
// is traced by the caller once the shading context is no longer needed, so that
// little is live during its traversal. `medium_absorption` is that of the
// medium the point lies in.
fn direct_light(ctx: ShadingContext, surface: Surface, n_geometric: vec3f, medium_absorption: vec3f, rng: ptr<function, Rng>) -> ShadowRay {
    let none = ShadowRay(vec3f(0.0), 0.0, vec3f(0.0, 1.0, 0.0), vec3f(0.0));
    let p = surface.position;
    //#if light_tree
    light_tree_set_point(p, n_geometric);
    //#endif
    let light = sample_light(p, rng);
    if !(light.pdf > 0.0) || all(light.radiance == vec3f(0.0)) {
        return none;
    }
    let wi = transpose(ctx.basis) * light.direction;
    let f = bsdf_eval(ctx, wi);
    if all(f == vec3f(0.0)) {
        return none;
    }
    var start = p;
    //#if smooth_normals
    start = shadow_ray_lift(p, n_geometric, light.direction);
    //#endif
    let origin = offset_ray_origin(start, surface.position_error, select(-n_geometric, n_geometric, dot(light.direction, n_geometric) > 0.0));
    // Aimed from the moved origin itself at the light's point (lifted off its surface, see
    // `lifted_off_the_light`), and stopping short of it: a ray parallel to the line from `p`
    // meets the light's own surface before its point, by the move over the sine of the angle
    // it arrives at (at 1.5° and 1 µm, 0.04 mm: a ceiling 1 cm above a lamp's back lost all
    // its light).
    var direction = light.direction;
    var t_max = INFINITY;
    if light.distance < INFINITY {
        let to_light = p + light.direction * light.distance - origin;
        let distance = length(to_light);
        direction = to_light / distance;
        t_max = distance * (1.0 - 1e-4);
    }
    var transmittance = vec3f(1.0);
    //#if media
    transmittance = integrate_segment(medium_absorption, vec3f(0.0), light.distance).transmittance;
    //#endif
    //#if sky_atmosphere
    // The air on the way to an emitter, as a path that hits it sees it (the sun's is in its radiance).
    if light.distance < INFINITY {
        transmittance *= atmosphere_transmittance_along(origin, light.direction, light.distance);
    }
    //#endif
    var weight = select(power_heuristic(light.pdf, bsdf_pdf(ctx, wi)), 1.0, light.delta);
    //#if closure_weights
    weight *= ctx.m.closure_weight;
    //#endif
    return ShadowRay(origin, t_max, direction, f * light.radiance * transmittance * (weight / light.pdf));
}
