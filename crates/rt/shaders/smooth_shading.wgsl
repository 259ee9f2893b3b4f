// Smooth-shaded triangles as Cycles shades them (scenes in Cycles' material model,
// `microfacet = "multiscatter"`, with interpolated normals). Cycles does not fold a lobe's
// directions that the interpolated normal puts below the true surface back above it (rt's
// `fold_above`, Mitsuba's way): it evaluates the lobes against their own normals and lets
// the geometry decide, and it starts shadow rays near the shadow terminator from the
// smooth surface that the normals describe rather than from the flat face
// (`shadow_ray_offset` in kernel/light/sample.h): on a coarse sphere, a face turned away
// from the sun whose normals still face it is lit, as the smooth sphere would be. With the
// material's Bump Map Correction (on by default) the glossy, metal, glass and coat lobes
// take a normal tilted just enough to mirror the view above the surface
// (`valid_for_reflection`), and light below the interpolated normal does not reach them.

//#include "common.wgsl"
//#include "hit.wgsl"
//#include "transform.wgsl"
//#include "motion.wgsl"
//#include "valid_reflection.wgsl"

// The triangle hit being shaded, for `shadow_ray_origin`.
var<private> smooth_hit: Hit;

// Marks the surface about to be shaded (see `set_smooth_normal` in lobe_hemispheres.wgsl)
// and returns the shading normal its lobes take: `n_interpolated` (before any normal map),
// `n_shading` and `n_geometric` on the viewer's side, `wo` towards the viewer. A normal-mapped
// triangle counts as smooth where its interpolated normal is (its shadow rays start from the
// smooth surface as Cycles' do); normal_map.wgsl has already bent its shading normal.
fn set_smooth_shading(m: Material, hit: Hit, n_interpolated: vec3f, n_shading: vec3f, n_geometric: vec3f, wo: vec3f, normal_mapped: bool) -> vec3f {
    smooth_hit = hit;
    let smoothed = hit.kind == HIT_TRIANGLE && dot(n_interpolated, n_geometric) < 1.0 - 1e-6;
    set_smooth_normal(smoothed, n_interpolated);
    if smoothed && !normal_mapped && m.bump_map_correction != 0u {
        return valid_for_reflection(n_shading, n_geometric, wo);
    }
    return n_shading;
}

// Where a shadow ray towards `l` starts on a smooth-shaded triangle: `p` lifted towards the
// smooth surface, by as much as the direction is close to the face's or the normals'
// horizon (Cycles' `shadow_ray_offset`); `n_geometric` is on the viewer's side.
fn shadow_ray_lift(p: vec3f, n_geometric: vec3f, l: vec3f) -> vec3f {
    if !is_smooth_shaded() {
        return p;
    }
    var nl = dot(interpolated_normal(), l);
    let ng = select(n_geometric, -n_geometric, nl < 0.0);
    nl = abs(nl);
    let ngl = dot(ng, l);
    // The object's Shadow Terminator Geometry Offset: shadow rays within about this cosine
    // of the terminator start from the smooth surface (0: none do).
    let cutoff = object_settings[smooth_hit.instance].geometry_offset;
    if cutoff <= 0.0 {
        return p;
    }
    let amount = select(saturate(1.0 - ngl / cutoff), saturate(2.0 - (ngl + nl) / cutoff), nl < cutoff);
    if amount <= 0.0 {
        return p;
    }
    return p + smooth_surface_offset(ng) * amount;
}

// Hanika's parabolic estimate of the smooth surface over the flat face at the hit
// ("Hacking the Shadow Terminator", Ray Tracing Gems II ch. 4), bounded by the vertices'
// tangent planes, as Cycles' `shadow_ray_smooth_surface_offset` computes it in object
// space; returned in world space. `ng`: the geometric normal on the side of the light.
fn smooth_surface_offset(ng: vec3f) -> vec3f {
    let tri = triangles[smooth_hit.primitive];
    let sh = shading[smooth_hit.primitive];
    let v = array<vec3f, 3>(tri.v0, tri.v1, tri.v2);
    let n = array<vec3f, 3>(normalize(sh.n0), normalize(sh.n1), normalize(sh.n2));
    let u = 1.0 - smooth_hit.b1 - smooth_hit.b2;
    let w1 = smooth_hit.b1;
    let w2 = smooth_hit.b2;
    let p = v[0] * u + v[1] * w1 + v[2] * w2;
    let n_object = n[0] * u + n[1] * w1 + n[2] * w2;
    let to_world = affine_inverse(instance_at(smooth_hit.instance).world_to_object).m;
    let n_world = transform_vector(to_world, n_object);
    let a = dot(n[2] - n[0], v[0] - v[2]);
    let b = dot(n[2] - n[1], v[1] - v[2]);
    let c = dot(n[1] - n[0], v[1] - v[0]);
    var h = a * u * (u - 1.0) + (a + b + c) * u * w1 + b * w1 * (w1 - 1.0);
    if dot(n_world, ng) > 0.0 {
        // The local linear envelope: no higher than the vertices' tangent planes allow.
        let e0 = max(max(dot(v[1] - v[0], n[0]), dot(v[2] - v[0], n[0])), 0.0);
        let e1 = max(max(dot(v[0] - v[1], n[1]), dot(v[2] - v[1], n[1])), 0.0);
        let e2 = max(max(dot(v[0] - v[2], n[2]), dot(v[1] - v[2], n[2])), 0.0);
        let h0 = max(dot(v[0] - p, n[0]) + e0, 0.0);
        let h1 = max(dot(v[1] - p, n[1]) + e1, 0.0);
        let h2 = max(dot(v[2] - p, n[2]) + e2, 0.0);
        h = max(min(min(h0, h1), h2), h * 0.5);
    } else {
        let e0 = max(max(dot(v[0] - v[1], n[0]), dot(v[0] - v[2], n[0])), 0.0);
        let e1 = max(max(dot(v[1] - v[0], n[1]), dot(v[1] - v[2], n[1])), 0.0);
        let e2 = max(max(dot(v[2] - v[0], n[2]), dot(v[2] - v[1], n[2])), 0.0);
        let h0 = max(dot(p - v[0], n[0]) + e0, 0.0);
        let h1 = max(dot(p - v[1], n[1]) + e1, 0.0);
        let h2 = max(dot(p - v[2], n[2]) + e2, 0.0);
        h = min(-min(min(h0, h1), h2), h * 0.5);
    }
    return n_world * h;
}
