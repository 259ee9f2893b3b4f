// The material where a path hit a surface, as the path sees it: textured at the path's
// ray footprint, its normal mapped, its node graph run (a Mix Shader's factor picking
// one of two materials), and the share of it a holdout takes.

//#include "path.wgsl"
//#include "hit.wgsl"
//#include "surface.wgsl"
//#if textures
//#include "texture.wgsl"
//#endif
//#if node_graphs
//#include "node_program.wgsl"
//#endif
//#if normal_maps
//#include "normal_map.wgsl"
//#endif
//#if holdout
//#include "holdout.wgsl"
//#endif
//#if aovs
//#include "aovs.wgsl"
//#endif

struct ShadingPoint {
    // Its shading normal is the normal map's where the material has one.
    surface: Surface,
    material: Material,
    //#if normal_maps
    // The interpolated normal, before the normal map.
    n_unmapped: vec3f,
    //#endif
    //#if coat_normal
    coat_normal: vec3f,
    //#endif
}

// The surface and material the path's ray hit.
fn shading_point(path: ptr<function, Path>, hit: Hit) -> ShadingPoint {
    var at: ShadingPoint;
    at.surface = surface_at(hit, path.origin, path.direction);
    at.material = materials[at.surface.material];
    //#if textures
    textured_point(path, hit, &at);
    //#endif
    return at;
}

//#if textures
// The textures, normal maps and node graph of the material at `at`.
fn textured_point(path: ptr<function, Path>, hit: Hit, at: ptr<function, ShadingPoint>) {
    let direction = path.direction;
    var m = at.material;
    // A pixel's angle seen from the camera (view_half_extent is the image plane's half size
    // at distance 1); an orthographic camera's rays do not spread.
    let cone_spread = select(2.0 * frame.view_half_extent.y / f32(frame.height), 0.0, frame.orthographic != 0u);
    path.cone_width += cone_spread * hit.t;
    let cos_hit = max(abs(dot(at.surface.geometric_normal, direction)), 1e-4);
    // The uv and its footprint, only where the material reads a texture: it costs a
    // triangle's vertices, its uvs and an instance's inverse transform.
    var texture_at: TexturePoint;
    if has_textures(m) {
        texture_at = texture_point(hit);
    }
    //#if node_graphs
    // A graph reads the interpolated normal, as Cycles' nodes read N, not a normal map's.
    let node_normal = at.surface.shading_normal;
    //#endif
    //#if normal_maps
    let n_unmapped = at.surface.shading_normal;
    at.n_unmapped = n_unmapped;
    at.surface.shading_normal = normal_mapped(m, hit, n_unmapped, at.surface.geometric_normal, -direction, slot_uv(m, UV1_NORMAL, texture_at));
    //#endif
    //#if coat_normal
    at.coat_normal = coat_normal_mapped(m, hit, n_unmapped, at.surface.geometric_normal, -direction, slot_uv(m, UV1_COAT_NORMAL, texture_at));
    //#endif
    m = textured_material(m, texture_at, log2(path.cone_width / cos_hit));
    //#if node_graphs
    if m.node_program != NO_PROGRAM {
        var point = node_point_at(hit, at.surface, node_normal, -direction);
        point.ray_from = path.ray_from;
        point.singular = path.ray_singular;
        point.ray_length = hit.t;
        point.ray_depth = f32(path.bounce);
        let graph = run_node_program(m.node_program, point);
        m = node_graph_applied(m, graph);
        if node_mix_second(m, graph, path.key, path.bounce) {
            m = textured_material(materials[m.mix_material], texture_at, log2(path.cone_width / cos_hit));
            if m.node_program != NO_PROGRAM {
                m = node_graph_material(m, point);
            }
        }
    }
    //#endif
    at.material = m;
}
//#endif

//#if holdout
// Takes the share of the path that a holdout at `at` holds out (a hole in the camera's
// image, black to other rays); true when nothing of the path is left.
fn held_out(path: ptr<function, Path>, at: ShadingPoint, hit: Hit) -> bool {
    let share = held_out_share(at.material, hit, path.transparent_background);
    if !(share > 0.0) {
        return false;
    }
    //#if aovs
    if path.transparent_background {
        aov_held_out(share * channel_mean(path.throughput));
    }
    //#endif
    path.throughput *= 1.0 - share;
    return share >= 1.0;
}
//#endif
