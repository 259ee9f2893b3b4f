// The steps of a path's turn at a surface or past the scene, as `trace_samples`
// (integrator.wgsl) takes them: what the ray meets on its way, what the background
// gives a ray that leaves, the material seen at a hit, the normal it is shaded with,
// and Russian roulette. The loop itself keeps the path's state and its control flow, and
// calls the emission's `emission_seen` itself: one function more around it cost the
// Cornell box's pipeline 39 % on NVIDIA GPUs (docs/performance.md).

// What the path meets on its way to `hit` (at most `t_max` away): each lamp it passes,
// which is not in the BVH (seen through a medium, it skips its absorption), and the
// medium it travels in; and the first hit's AOVs.
fn light_along_the_ray(radiance: ptr<function, vec3f>, throughput: ptr<function, vec3f>, hit: Hit, origin: vec3f, direction: vec3f, t_max: f32, bsdf_pdf: f32, bounce: u32, medium_absorption: vec3f, medium_emission: vec3f) {
    //#if lamps
    let lamp_light = lamps_seen(origin, direction, min(hit.t, t_max), hit.kind == HIT_NONE, bsdf_pdf, bounce == 0u);
    gather(radiance, *throughput * lamp_light, EVENT_EMISSION);
    //#if aovs
    if bounce == 0u {
        aov_emission_seen(lamp_light);
    }
    //#endif
    //#endif
    //#if media
    let segment = integrate_segment(medium_absorption, medium_emission, hit.t);
    gather(radiance, *throughput * segment.radiance, EVENT_MEDIUM);
    attenuate(throughput, segment.transmittance, EVENT_MEDIUM);
    //#endif
    //#if aovs
    if bounce == 0u && hit.kind != HIT_NONE {
        aov_first_hit(hit.t, origin + direction * hit.t);
    }
    //#endif
}

// What a ray that leaves the scene sees: the sky or the environment, and the sun.
fn background_seen(radiance: ptr<function, vec3f>, throughput: vec3f, origin: vec3f, direction: vec3f, bsdf_pdf: f32) {
    //#if sky_environment
    gather(radiance, throughput * environment_seen(direction, bsdf_pdf), EVENT_SKY);
    //#endif
    //#if sky_uniform_light
    gather(radiance, throughput * uniform_sky_seen(bsdf_pdf), EVENT_SKY);
    //#endif
    //#if !sky_environment
    //#if !sky_uniform_light
    gather(radiance, throughput * sky_radiance(origin, direction), EVENT_SKY);
    //#endif
    //#endif
    //#if sun
    gather(radiance, throughput * sun_seen(origin, direction, bsdf_pdf), EVENT_SKY);
    //#endif
}

// The normals a hit's maps give: the shading normal, the one before the normal map and
// the coat's.
struct SeenNormals {
    shading_normal: vec3f,
    n_unmapped: vec3f,
    coat_normal: vec3f,
    // Whether a node graph set the normal (a Bump node's), which is then shaded as a map's.
    graph_normal: bool,
}

// The material seen at `hit` by a ray along `direction` whose cone is `cone_width` wide
// there: `m`, the material the surface names, made what its textures and node graph make
// it, and the normals its maps give. `path_key`, `bounce`, `ray_from`, `ray_singular` and
// `kind_depths` are what a node graph's coins and Light Path node read.
fn material_seen(m: ptr<function, Material>, hit: Hit, surface: Surface, direction: vec3f, cone_width: f32, path_key: u32, bounce: u32, ray_from: u32, ray_singular: bool, kind_depths: u32) -> SeenNormals {
    var seen = SeenNormals(surface.shading_normal, surface.shading_normal, surface.shading_normal, false);
    //#if textures
    let cos_hit = max(abs(dot(surface.geometric_normal, direction)), 1e-4);
    // The uv and its footprint, only where the material reads a texture: it costs a
    // triangle's vertices, its uvs and an instance's inverse transform.
    var texture_at: TexturePoint;
    if has_textures(*m) {
        texture_at = texture_point(hit);
    }
    //#if normal_maps
    seen.shading_normal = normal_mapped(*m, hit, seen.n_unmapped, surface.geometric_normal, -direction, slot_uv(*m, UV1_NORMAL, texture_at));
    //#endif
    //#if coat_normal
    seen.coat_normal = coat_normal_mapped(*m, hit, seen.n_unmapped, surface.geometric_normal, -direction, slot_uv(*m, UV1_COAT_NORMAL, texture_at));
    //#endif
    *m = textured_material(*m, texture_at, log2(cone_width / cos_hit));
    //#if node_graphs
    if (*m).node_program != NO_PROGRAM {
        // A graph reads the interpolated normal, as Cycles' nodes read N, not a normal map's.
        var point = node_point_at(hit, surface, seen.n_unmapped, -direction);
        point.ray_from = ray_from;
        point.singular = ray_singular;
        point.ray_length = hit.t;
        point.ray_depth = f32(bounce);
        point.ray_depths = kind_depths;
        point.footprint = cone_width;
        let graph = run_node_program((*m).node_program, point);
        *m = node_graph_applied(*m, graph);
        //#if normal_maps
        if (graph.driven & NODE_DRIVES_NORMAL) != 0u {
            // The graph's normal is on the viewer's side, as Cycles' N.
            let outward = select(1.0, -1.0, point.backfacing) * rt_axes(graph.normal);
            seen.shading_normal = mapped_normal_bent(outward, surface.geometric_normal, -direction);
            seen.graph_normal = true;
        }
        //#endif
        if node_mix_second(*m, graph, path_key, bounce) {
            *m = textured_material(materials[(*m).mix_material], texture_at, log2(cone_width / cos_hit));
            if (*m).node_program != NO_PROGRAM {
                *m = node_graph_material(*m, point);
            }
        }
    }
    //#endif
    //#endif
    return seen;
}

// The normal the hit is shaded with, on the viewer's side (`entering`), and the state the
// lobes read beside it: the normal before its map, the coat's, Cycles' smooth-shading
// correction, the terminator shift and the anisotropic tangent.
fn shading_normal_at(m: Material, seen: SeenNormals, hit: Hit, surface: Surface, direction: vec3f, entering: bool, n_geometric: vec3f) -> vec3f {
    var n_shading = select(-surface.shading_normal, surface.shading_normal, entering);
    var mapped = false;
    //#if normal_maps
    let side = select(-1.0, 1.0, entering);
    mapped = m.normal_texture != NO_TEXTURE || seen.graph_normal;
    set_unmapped_normal(side * seen.n_unmapped, mapped, side * diffuse_mapped_normal());
    //#endif
    //#if coat_normal
    set_coat_normal(side * seen.coat_normal, side * seen.n_unmapped, side * coat_normal_before_bending());
    //#endif
    //#if smooth_normals
    var n_interpolated = n_shading;
    //#if normal_maps
    n_interpolated = side * seen.n_unmapped;
    //#endif
    n_shading = set_smooth_shading(m, hit, n_interpolated, n_shading, n_geometric, -direction, mapped);
    //#endif
    //#if terminator_offset
    set_terminator_shift(hit);
    //#endif
    //#if anisotropy
    set_surface_tangent(hit, surface.position, m.tangent);
    //#endif
    return n_shading;
}

// Russian roulette: the path survives with probability its throughput's largest channel
// (at most 0.95), and a survivor's throughput is divided by it.
fn survives_roulette(throughput: ptr<function, vec3f>, rng: ptr<function, Rng>) -> bool {
    let t = *throughput;
    let survival = min(max(t.x, max(t.y, t.z)), 0.95);
    let survives = rng_next(rng) < survival;
    *throughput /= survival;
    return survives;
}
