// Radiance arriving from the sky along a ray that leaves the scene, the sun's disk excepted.

//#include "common.wgsl"
//#if sky_atmosphere
//#include "atmosphere_sky.wgsl"
//#endif
//#if sky_environment
//#include "environment.wgsl"
//#endif

fn sky_radiance(origin: vec3f, direction: vec3f) -> vec3f {
    //#if sky_uniform
    return frame.sky_color;
    //#endif
    //#if sky_atmosphere
    return atmosphere_sky_radiance(origin, direction);
    //#endif
    //#if sky_environment
    return environment_radiance(direction);
    //#endif
    //#if sky_black
    return vec3f(0.0);
    //#endif
    // The world's graph is run where the path leaves the scene (graph_sky_seen).
    //#if sky_graph
    return vec3f(0.0);
    //#endif
}
