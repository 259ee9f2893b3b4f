// Where a path goes on from a surface: the local frame of the surface's lobes, a light
// sample towards the emitters (next-event estimation, traced later as a shadow ray) and
// a direction drawn from the BSDF; Russian roulette may end the path.

//#include "path.wgsl"
//#include "path_surface.wgsl"
//#include "ray.wgsl"
//#include "bsdf.wgsl"
//#if nee
//#include "lights.wgsl"
//#endif
//#if smooth_normals
//#include "smooth_shading.wgsl"
//#endif
//#if terminator_offset
//#include "terminator_offset.wgsl"
//#endif
//#if aovs
//#include "aovs.wgsl"
//#endif

// The surface as the path's lobes see it.
struct Scattering {
    ctx: ShadingContext,
    // The normals on the side the path arrived from.
    n_geometric: vec3f,
    n_shading: vec3f,
    // The path arrived from outside (it meets the outward normal head on).
    entering: bool,
}

// The lobes' frame at `at` for the path arriving there.
fn scattering_at(path: ptr<function, Path>, at: ShadingPoint, hit: Hit) -> Scattering {
    let direction = path.direction;
    let m = at.material;
    let entering = dot(at.surface.geometric_normal, direction) < 0.0;
    let n_geometric = select(-at.surface.geometric_normal, at.surface.geometric_normal, entering);
    var n_shading = select(-at.surface.shading_normal, at.surface.shading_normal, entering);
    var mapped = false;
    //#if normal_maps
    let side = select(-1.0, 1.0, entering);
    mapped = m.normal_texture != NO_TEXTURE;
    set_unmapped_normal(side * at.n_unmapped, mapped, side * diffuse_mapped_normal());
    //#endif
    //#if coat_normal
    set_coat_normal(side * at.coat_normal, side * at.n_unmapped, side * coat_normal_before_bending());
    //#endif
    //#if smooth_normals
    var n_interpolated = n_shading;
    //#if normal_maps
    n_interpolated = side * at.n_unmapped;
    //#endif
    n_shading = set_smooth_shading(m, hit, n_interpolated, n_shading, n_geometric, -direction, mapped);
    //#endif
    //#if terminator_offset
    set_terminator_shift(hit);
    //#endif
    //#if anisotropy
    set_surface_tangent(hit, at.surface.position, m.tangent);
    //#endif
    let ctx = shading_context(m, n_shading, n_geometric, -direction, entering);
    return Scattering(ctx, n_geometric, n_shading, entering);
}

//#if nee
// A light sample from `at`, weighted by the path's throughput, for a shadow ray to test.
fn light_sample(path: ptr<function, Path>, at: ShadingPoint, sc: Scattering) -> ShadowRay {
    var rng = path.rng;
    var shadow = direct_light(sc.ctx, at.surface, sc.n_geometric, path.medium_absorption, &rng);
    path.rng = rng;
    shadow.contribution *= path.throughput;
    return shadow;
}
//#endif

// The path's next ray, drawn from the BSDF at `at`, and what the path carries along it;
// the path ends where the BSDF gives no direction.
fn bsdf_scatter(path: ptr<function, Path>, at: ShadingPoint, sc: Scattering) {
    var rng = path.rng;
    var s = bsdf_sample(sc.ctx, &rng);
    path.rng = rng;
    //#if terminator_offset
    // Delta reflections (the other lobes' samples are weighed by `bsdf_eval`).
    if s.pdf == 0.0 && !s.transmitted {
        s.weight *= terminator_shift(dot(s.direction, sc.n_shading));
    }
    //#endif
    //#if aovs
    aov_surface(s, sc.n_shading);
    //#endif
    if !s.valid {
        path.ended = true;
        return;
    }
    attenuate(path, s.weight, EVENT_LOBE + s.lobe);
    path.transparent_background = path.transparent_background && s.transmitted && is_clear_glass(at.material);
    path.bsdf_pdf = s.pdf;
    //#if node_graphs
    path.ray_from = s.lobe + 1u;
    path.ray_singular = s.pdf == 0.0;
    //#endif
    //#if media
    // Crossing into a material adds its medium, leaving subtracts it: nested media add up.
    if s.transmitted {
        let sign = select(-1.0, 1.0, sc.entering);
        path.medium_absorption = max(path.medium_absorption + sign * at.material.absorption, vec3f(0.0));
        path.medium_emission = max(path.medium_emission + sign * at.material.volume_emission, vec3f(0.0));
    }
    //#endif
    russian_roulette(path);
    let n = sc.n_geometric;
    path.origin = offset_ray_origin(at.surface.position, at.surface.position_error, select(-n, n, dot(s.direction, n) > 0.0));
    path.direction = s.direction;
    path.t_max = INFINITY;
}

// Past ROULETTE_START bounces a path goes on with the probability of its throughput's
// largest channel (at most 0.95), and carries the more for it.
fn russian_roulette(path: ptr<function, Path>) {
    if path.bounce <= ROULETTE_START {
        return;
    }
    let throughput = path.throughput;
    let survival = min(max(throughput.x, max(throughput.y, throughput.z)), 0.95);
    var rng = path.rng;
    if rng_next(&rng) >= survival {
        path.ended = true;
    }
    path.rng = rng;
    path.throughput /= survival;
}

// Film › Transparent Glass: glass whose GGX α is at most the frame's threshold (the
// square of Cycles' Roughness Threshold) lets the camera's path keep the background
// transparent.
fn is_clear_glass(m: Material) -> bool {
    return frame.transparent_glass >= 0.0 && m.alpha <= frame.transparent_glass;
}
