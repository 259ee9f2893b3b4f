// A ray's path through the atmosphere, in terms that keep their digits in f32.
// Planet-centred coordinates would not: at 6.4e6 m an f32 is only good to half a
// metre, and the altitude r − R loses even that. Everything here follows from the
// altitude h₀ of the ray's origin and the cosine μ of its zenith angle there, with
// differences of squares written as products: r² − R² = h(2R + h).

//#include "atmosphere.wgsl"

struct PlanetRay {
    h0: f32,
    r0: f32,
    mu: f32,
    // Cosines of the sun's zenith angle at the origin, and of the angle between the ray and the sun.
    mu_s: f32,
    nu: f32,
    // The part of the ray inside the atmosphere; empty (start ≥ end) when it misses it.
    t_start: f32,
    t_end: f32,
    // Whether the ray ends on the ground at t_end.
    hits_ground: bool,
}

// h(2R + h) = r² − R², without cancellation.
fn radius_squared_excess(h: f32) -> f32 {
    return h * (2.0 * atmosphere.bottom_radius + h);
}

// Distance to the ground along (h, μ), or −1 when the ray misses it.
fn distance_to_ground(h: f32, mu: f32) -> f32 {
    let r = atmosphere.bottom_radius + h;
    let discriminant = r * r * mu * mu - radius_squared_excess(h);
    if mu >= 0.0 || discriminant < 0.0 {
        return -1.0;
    }
    // The nearer root, as (r² − R²) / (−rμ + √Δ): no cancellation for grazing rays.
    return radius_squared_excess(h) / (-r * mu + sqrt(discriminant));
}

// Where the ray along (h, μ) crosses the top of the atmosphere: (entry, exit)
// distances, entry 0 from inside; (−1, −1) when it misses it.
fn top_crossings(h: f32, mu: f32) -> vec2f {
    let top = atmosphere.top_altitude;
    let r = atmosphere.bottom_radius + h;
    // R_top² − r², as a product.
    let excess = (top - h) * (2.0 * atmosphere.bottom_radius + top + h);
    let discriminant = r * r * mu * mu + excess;
    if discriminant < 0.0 {
        return vec2f(-1.0);
    }
    let root = sqrt(discriminant);
    if h <= top {
        // −rμ + √Δ, rewritten where the two terms would cancel.
        let exit = select(-r * mu + root, excess / (r * mu + root), mu > 0.0);
        return vec2f(0.0, exit);
    }
    if mu >= 0.0 {
        return vec2f(-1.0);
    }
    return vec2f(-excess / (-r * mu + root), -r * mu + root);
}

fn planet_ray(h0_in: f32, mu: f32, mu_s: f32, nu: f32) -> PlanetRay {
    // Below the ground (scene geometry under y = 0): seen from the ground.
    let h0 = max(h0_in, 0.0);
    var ray = PlanetRay(h0, atmosphere.bottom_radius + h0, mu, mu_s, nu, 0.0, 0.0, false);
    let top = top_crossings(h0, mu);
    if top.y <= 0.0 {
        return ray;
    }
    ray.t_start = top.x;
    ray.t_end = top.y;
    let ground = distance_to_ground(h0, mu);
    if ground >= 0.0 {
        ray.t_end = ground;
        ray.hits_ground = true;
    }
    return ray;
}

// t² + 2r₀μt + h₀(2R + h₀) = r(t)² − R².
fn excess_along(ray: PlanetRay, t: f32) -> f32 {
    return t * t + 2.0 * ray.r0 * ray.mu * t + radius_squared_excess(ray.h0);
}

fn altitude_along(ray: PlanetRay, t: f32) -> f32 {
    let excess = max(excess_along(ray, t), 0.0);
    let r = sqrt(excess + atmosphere.bottom_radius * atmosphere.bottom_radius);
    return excess / (r + atmosphere.bottom_radius);
}

// Cosine of the sun's zenith angle at distance t, where the altitude is h.
fn sun_cosine_along(ray: PlanetRay, t: f32, h: f32) -> f32 {
    return clamp((ray.r0 * ray.mu_s + t * ray.nu) / (atmosphere.bottom_radius + h), -1.0, 1.0);
}

// Cosine of the ray's own zenith angle at distance t, where the altitude is h.
fn zenith_cosine_along(ray: PlanetRay, t: f32, h: f32) -> f32 {
    return clamp((ray.r0 * ray.mu + t) / (atmosphere.bottom_radius + h), -1.0, 1.0);
}
