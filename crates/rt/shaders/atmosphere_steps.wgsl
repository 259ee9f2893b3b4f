// Where a march along a path through the atmosphere takes its steps. The air is
// densest at the path's lowest point (its start when it climbs, the ground when
// it descends onto it, the tangent point in between otherwise), so steps are
// shortest there and grow exponentially away from it, on both sides. The growth
// rate follows the distance over which the path climbs one aerosol scale height,
// which is what the density varies on: ~1 km for a vertical ray, ~120 km for a
// horizontal one.

//#include "atmosphere.wgsl"
//#include "atmosphere_path.wgsl"

struct MarchSteps {
    count: u32,
    // Steps between the path's start and its lowest point; the rest lie after it.
    down_count: u32,
    t_low: f32,
    down_length: f32,
    up_length: f32,
    // Exponent κ of each side's growth: the edges lie at L (e^(κu) − 1) / (e^κ − 1).
    down_growth: f32,
    up_growth: f32,
}

fn step_growth(length: f32, h_low: f32, mu_low: f32) -> f32 {
    let scale = min(atmosphere.mie_scale_height, atmosphere.rayleigh_scale_height);
    let m = abs(mu_low);
    // Solves m s + s² / 2r = H for s, written so that m = 0 and m = 1 both keep their digits.
    let climb = 2.0 * scale / (m + sqrt(m * m + 2.0 * scale / (atmosphere.bottom_radius + h_low)));
    return log(1.0 + length / climb);
}

fn march_steps(ray: PlanetRay, count: u32) -> MarchSteps {
    let t_low = clamp(-ray.r0 * ray.mu, ray.t_start, ray.t_end);
    let down = t_low - ray.t_start;
    let up = ray.t_end - t_low;
    let h_low = altitude_along(ray, t_low);
    let mu_low = zenith_cosine_along(ray, t_low, h_low);
    // Steps shared in proportion to length, each non-empty side getting at least one.
    var down_count = u32(round(f32(count) * down / max(down + up, 1e-30)));
    if down > 0.0 && up > 0.0 {
        down_count = clamp(down_count, 1u, max(count, 2u) - 1u);
    }
    let total = select(count, max(count, 2u), down > 0.0 && up > 0.0);
    return MarchSteps(
        total,
        down_count,
        t_low,
        down,
        up,
        step_growth(down, h_low, mu_low),
        step_growth(up, h_low, mu_low),
    );
}

// (e^(κu) − 1) / (e^κ − 1), which tends to u as κ → 0.
fn grown(u: f32, growth: f32) -> f32 {
    if growth < 1e-3 {
        return u;
    }
    return (exp(growth * u) - 1.0) / (exp(growth) - 1.0);
}

// Distance along the ray of the i-th step edge, i in 0..=count, increasing.
fn step_edge(s: MarchSteps, i: u32) -> f32 {
    if i <= s.down_count {
        if s.down_count == 0u {
            return s.t_low;
        }
        return s.t_low - s.down_length * grown(f32(s.down_count - i) / f32(s.down_count), s.down_growth);
    }
    let up_count = s.count - s.down_count;
    return s.t_low + s.up_length * grown(f32(i - s.down_count) / f32(up_count), s.up_growth);
}
