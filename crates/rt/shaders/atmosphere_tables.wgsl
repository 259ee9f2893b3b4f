// The program that builds the atmosphere's tables, run whenever its parameters
// change. Nothing in them depends on the sun's direction or radiance: they are
// functions of the sun's zenith angle at a point, per unit solar irradiance, and
// the march scales them by the sun of the frame.
//
// Passes, in order: build_transmittance, then in atmosphere_scattering.wgsl
// build_second_order, build_third_order, build_fourth_order, build_closure.

//#include "atmosphere.wgsl"
//#include "atmosphere_path.wgsl"
//#include "atmosphere_scattering.wgsl"

@group(0) @binding(0) var<uniform> atmosphere: Atmosphere;
@group(0) @binding(1) var<storage, read_write> atmosphere_luts: array<vec4f>;

// Midpoint rule over the whole ray: its error stays below 1e-4 in optical depth
// even for the thinnest (vertical) rays, whose steps are then 0.4 km against a
// 1.2 km aerosol scale height.
const TRANSMITTANCE_STEPS: u32 = 256u;

// Entry (x, y) of the transmittance table: the inverse of `transmittance_coords`.
@compute @workgroup_size(8, 8)
fn build_transmittance(@builtin(global_invocation_id) id: vec3u) {
    let size = atmosphere.transmittance_size;
    if any(id.xy >= size) {
        return;
    }
    let coords = vec2f(id.xy) / vec2f(size - 1u);
    let top = atmosphere.top_altitude;
    let bottom = atmosphere.bottom_radius;
    let rho_top = sqrt(radius_squared_excess(top));
    let rho = coords.y * rho_top;
    let h = rho * rho / (sqrt(rho * rho + bottom * bottom) + bottom);
    let r = bottom + h;
    let d_min = top - h;
    let d = d_min + coords.x * (rho + rho_top - d_min);
    // The law of cosines in the triangle (centre, origin, exit): R_top² = r² + d² + 2rdμ.
    var mu = 1.0;
    if d > 0.0 {
        mu = clamp(((top - h) * (2.0 * bottom + top + h) - d * d) / (2.0 * r * d), -1.0, 1.0);
    }
    let ray = PlanetRay(h, r, mu, 0.0, 0.0, 0.0, d, false);
    let dt = d / f32(TRANSMITTANCE_STEPS);
    var depth = vec3f(0.0);
    for (var i = 0u; i < TRANSMITTANCE_STEPS; i++) {
        depth += medium_at(altitude_along(ray, (f32(i) + 0.5) * dt)).extinction;
    }
    atmosphere_luts[id.y * size.x + id.x] = vec4f(exp(-depth * dt), 1.0);
}
