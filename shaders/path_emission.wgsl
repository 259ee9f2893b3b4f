// What a path's ray sees of what emits: a lamp or a medium along the ray, the sky, an
// environment and the sun when it leaves the scene, a surface's emission when it hits
// one. Each is weighted against light sampling (MIS, power heuristic) when the BSDF
// sample that found it could also have been drawn by next-event estimation.

//#include "path.wgsl"
//#include "hit.wgsl"
//#include "path_surface.wgsl"
//#include "sky.wgsl"
//#include "sampling.wgsl"
//#if nee
//#include "lights.wgsl"
//#endif
//#if lamps
//#include "lamps.wgsl"
//#endif
//#if media
//#include "segment.wgsl"
//#endif
//#if sun
//#include "sun.wgsl"
//#endif
//#if sky_atmosphere
//#include "atmosphere_sky.wgsl"
//#endif
//#if emission
//#include "layered_emission.wgsl"
//#endif
//#if aovs
//#include "aovs.wgsl"
//#endif

//#if emission
// Emission of the surface hit, MIS-weighted against light sampling when the
// bounce that found it could also have been found by next-event estimation.
// `layers`: the normals of the layers over the emission (see layered_emission.wgsl).
fn emission_seen(m: Material, hit: Hit, surface: Surface, layers: LayerNormals, origin: vec3f, direction: vec3f, bsdf_pdf: f32) -> vec3f {
    var weight = 1.0;
    //#if nee
    if bsdf_pdf > 0.0 {
        var light_pdf = 0.0;
        if hit.kind == HIT_SPHERE {
            //#if spheres
            light_pdf = sphere_hit_pdf(origin, hit.primitive, m.emission_luminance);
            //#endif
        } else {
            light_pdf = triangle_hit_pdf(m.emission_luminance, hit, abs(dot(surface.geometric_normal, direction)));
        }
        weight = power_heuristic(bsdf_pdf, light_pdf);
    }
    //#endif
    return layered_emission(m, m.emission, layers, -direction) * weight;
}
//#endif

//#if sun
// The sun's disk seen by a ray that leaves the scene.
fn sun_seen(origin: vec3f, direction: vec3f, bsdf_pdf: f32) -> vec3f {
    if !in_sun_disk(direction) {
        return vec3f(0.0);
    }
    var weight = 1.0;
    //#if nee
    if bsdf_pdf > 0.0 {
        weight = power_heuristic(bsdf_pdf, sun_share() / sun_solid_angle());
    }
    //#endif
    return sun_radiance_at(origin, direction) * weight;
}
//#endif

//#if sky_uniform_light
// The uniform sky seen by a ray that leaves the scene, MIS-weighted against light
// sampling after a BSDF sample, as `environment_seen` below.
fn uniform_sky_seen(bsdf_pdf: f32) -> vec3f {
    var weight = 1.0;
    //#if nee
    if bsdf_pdf > 0.0 {
        weight = power_heuristic(bsdf_pdf, frame.sky_light_share / (4.0 * PI));
    }
    //#endif
    return frame.sky_color * weight;
}
//#endif

//#if sky_environment
// The environment seen by a ray that leaves the scene, MIS-weighted against light
// sampling after a BSDF sample (the camera's rays and delta lobes have bsdf_pdf 0).
fn environment_seen(direction: vec3f, bsdf_pdf: f32) -> vec3f {
    var weight = 1.0;
    //#if nee
    if bsdf_pdf > 0.0 {
        weight = power_heuristic(bsdf_pdf, environment.light_share * environment_pdf(direction));
    }
    //#endif
    return environment_radiance(direction) * weight;
}
//#endif

// What the path's ray meets before what it hits (`t_max`: where the ray ends): the
// lamp objects, which are not in the BVH, the medium it crosses and, when it hits a
// surface, the air.
fn light_on_the_way(path: ptr<function, Path>, hit: Hit, t_max: f32) {
    //#if lamps
    // (Seen through a medium, lamps skip its absorption.)
    let lamp_light = lamps_seen(path.origin, path.direction, min(hit.t, t_max), hit.kind == HIT_NONE, path.bsdf_pdf, path.bounce == 0u);
    gather(path, path.throughput * lamp_light, EVENT_EMISSION);
    //#if aovs
    if path.bounce == 0u {
        aov_emission_seen(lamp_light);
    }
    //#endif
    //#endif
    //#if media
    let segment = integrate_segment(path.medium_absorption, path.medium_emission, hit.t);
    gather(path, path.throughput * segment.radiance, EVENT_MEDIUM);
    attenuate(path, segment.transmittance, EVENT_MEDIUM);
    //#endif
    //#if aovs
    if path.bounce == 0u && hit.kind != HIT_NONE {
        aov_first_hit(hit.t, path.origin + path.direction * hit.t);
    }
    //#endif
    //#if sky_atmosphere
    if hit.kind != HIT_NONE {
        let air = atmosphere_segment(path.origin, path.direction, hit.t);
        gather(path, path.throughput * air.radiance, EVENT_AIR);
        attenuate(path, air.transmittance, EVENT_AIR);
    }
    //#endif
}

// The background the path's ray meets when it leaves the scene, which ends it.
fn escaped(path: ptr<function, Path>) {
    //#if transparent_film
    // Film › Transparent: the background the camera sees adds nothing, and the sample
    // counts as one that met nothing (the pixel's alpha is the share that met the
    // scene), also when it passed through stochastically transparent surfaces.
    if path.transparent_background {
        //#if aovs
        aov_background_seen(channel_mean(path.throughput), path.bounce == 0u);
        //#endif
        return;
    }
    //#endif
    //#if sky_environment
    gather(path, path.throughput * environment_seen(path.direction, path.bsdf_pdf), EVENT_SKY);
    //#endif
    //#if sky_uniform_light
    gather(path, path.throughput * uniform_sky_seen(path.bsdf_pdf), EVENT_SKY);
    //#endif
    //#if !sky_environment
    //#if !sky_uniform_light
    gather(path, path.throughput * sky_radiance(path.origin, path.direction), EVENT_SKY);
    //#endif
    //#endif
    //#if sun
    gather(path, path.throughput * sun_seen(path.origin, path.direction, path.bsdf_pdf), EVENT_SKY);
    //#endif
}

//#if emission
// The emission of the surface the path hit, under the layers over it (`at`: the
// material and normals there).
fn surface_emission(path: ptr<function, Path>, at: ShadingPoint, hit: Hit) {
    let surface = at.surface;
    var coat_layer_normal = surface.shading_normal;
    //#if coat_normal
    coat_layer_normal = at.coat_normal;
    //#endif
    let layer_side = select(-1.0, 1.0, dot(surface.geometric_normal, path.direction) < 0.0);
    let layers = mapped_layer_normals(at.material, surface.shading_normal, coat_layer_normal, layer_side);
    let emitted = path.throughput * emission_seen(at.material, hit, surface, layers, path.origin, path.direction, path.bsdf_pdf);
    gather(path, emitted, EVENT_EMISSION);
    //#if aovs
    if path.bounce == 0u {
        aov_emission_seen(emitted);
    }
    //#endif
}
//#endif
