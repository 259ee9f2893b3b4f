// Look-ups in the atmosphere's tables (see atmosphere_tables.wgsl for how they
// are built). Entries sit at the ends of their cells, so that the horizon and
// the zenith are represented exactly, and are interpolated bilinearly.

//#include "atmosphere.wgsl"
//#include "atmosphere_path.wgsl"

fn table_bilinear(offset: u32, size: vec2u, coords: vec2f) -> vec4f {
    let p = clamp(coords, vec2f(0.0), vec2f(1.0)) * vec2f(size - 1u);
    let i = min(vec2u(p), size - 2u);
    let f = p - vec2f(i);
    let row0 = offset + i.y * size.x + i.x;
    let row1 = row0 + size.x;
    let lower = mix(atmosphere_luts[row0], atmosphere_luts[row0 + 1u], f.x);
    let upper = mix(atmosphere_luts[row1], atmosphere_luts[row1 + 1u], f.x);
    return mix(lower, upper, f.y);
}

// Transmittance table: Bruneton's parameterisation (2017), over the rays that
// leave the atmosphere without meeting the ground. x = where the distance d to the
// top lies between its least and greatest value at that altitude, y = ρ / ρ_top
// with ρ = √(r² − R²). It samples the horizon, where transmittance changes
// fastest, far more densely than an angle would.
fn transmittance_coords(h: f32, mu: f32) -> vec2f {
    let top = atmosphere.top_altitude;
    let rho_top = sqrt(radius_squared_excess(top));
    let rho = sqrt(radius_squared_excess(h));
    let d = top_crossings(h, mu).y;
    let d_min = top - h;
    let d_max = rho + rho_top;
    return vec2f((d - d_min) / (d_max - d_min), rho / rho_top);
}

// Transmittance from altitude h along a ray of zenith cosine μ to space; zero
// when the planet is in the way (the earth's shadow), one when the ray misses
// the atmosphere.
fn transmittance_to_space(h_in: f32, mu: f32) -> vec3f {
    let h = max(h_in, 0.0);
    if distance_to_ground(h, mu) >= 0.0 {
        return vec3f(0.0);
    }
    let top = atmosphere.top_altitude;
    if h <= top {
        return table_bilinear(0u, atmosphere.transmittance_size, transmittance_coords(h, mu)).rgb;
    }
    // From above: what the ray meets from where it enters.
    let crossings = top_crossings(h, mu);
    if crossings.y <= 0.0 {
        return vec3f(1.0);
    }
    let mu_entry = clamp(((atmosphere.bottom_radius + h) * mu + crossings.x) / (atmosphere.bottom_radius + top), -1.0, 1.0);
    return table_bilinear(0u, atmosphere.transmittance_size, transmittance_coords(top, mu_entry)).rgb;
}

// Multiple scattering table: x = (1 + sign(μs)√|μs|) / 2, which samples a sun
// near the horizon (where twilight changes fastest) densely; y = √(h / h_top).
fn scattering_coords(h: f32, mu_s: f32) -> vec2f {
    let x = sign(mu_s) * sqrt(abs(mu_s));
    return vec2f(0.5 + 0.5 * x, sqrt(clamp(h / atmosphere.top_altitude, 0.0, 1.0)));
}

// Plane `plane` of the multiple scattering table (atmosphere_scattering.wgsl), bilinearly.
fn scattering_plane(plane: u32, h: f32, mu_s: f32) -> vec3f {
    let size = atmosphere.scattering_size;
    let offset = atmosphere.scattering_offset + plane * size.x * size.y;
    return table_bilinear(offset, size, scattering_coords(h, mu_s)).rgb;
}

// Row `row` of the ground's table, linearly in μs.
fn ground_row(row: u32, mu_s: f32) -> vec3f {
    let width = atmosphere.scattering_size.x;
    let p = scattering_coords(0.0, mu_s).x * f32(width - 1u);
    let i = min(u32(p), width - 2u);
    let at = atmosphere.ground_offset + row * width + i;
    return mix(atmosphere_luts[at], atmosphere_luts[at + 1u], p - f32(i)).rgb;
}

// Ψ: isotropic in-scattered radiance of all orders ≥ 2 per unit scattering
// coefficient and unit solar irradiance, at altitude h and sun zenith cosine μs.
fn multiple_scattering(h: f32, mu_s: f32) -> vec3f {
    return scattering_plane(3u, h, mu_s) * atmosphere.multiple_scattering;
}

// Irradiance of the ground by the sky (its sun excepted) per unit solar irradiance.
fn ground_sky_irradiance(mu_s: f32) -> vec3f {
    return ground_row(0u, mu_s) + ground_row(3u, mu_s) * atmosphere.multiple_scattering;
}
