//! The physical model in f64, planet-centred (f64 keeps micrometres at 6.4e6 m),
//! written from Hillaire's paper (EGSR 2020, table 1) independently of the shaders.

use glam::DVec3;
use std::f64::consts::PI;

pub const BOTTOM: f64 = 6_360_000.0;
pub const TOP: f64 = 100_000.0;

#[derive(Clone, Debug)]
pub struct Model {
    pub rayleigh: DVec3,
    pub rayleigh_height: f64,
    pub mie_scattering: f64,
    pub mie_absorption: f64,
    pub mie_height: f64,
    pub mie_g: f64,
    pub ozone: DVec3,
    pub albedo: DVec3,
}

/// Scattering and extinction coefficients at one altitude.
pub struct Medium {
    pub rayleigh: DVec3,
    pub mie: f64,
    pub extinction: DVec3,
}

impl Model {
    /// The model a scene's `[sky]` keys select.
    pub fn of(a: &rt::scene::Atmosphere) -> Self {
        let t = a.turbidity as f64;
        Self {
            rayleigh: DVec3::new(5.802e-6, 13.558e-6, 33.1e-6) * a.rayleigh_scale as f64,
            rayleigh_height: 8_000.0,
            mie_scattering: 3.996e-6 * t,
            mie_absorption: if a.mie_absorption { 4.40e-6 * t } else { 0.0 },
            mie_height: 1_200.0,
            mie_g: a.mie_g as f64,
            ozone: if a.ozone { DVec3::new(0.650e-6, 1.881e-6, 0.085e-6) } else { DVec3::ZERO },
            albedo: a.ground_albedo.as_dvec3(),
        }
    }

    pub fn medium(&self, h: f64) -> Medium {
        let rayleigh = self.rayleigh * (-h / self.rayleigh_height).exp();
        let aerosols = (-h / self.mie_height).exp();
        let ozone = (1.0 - (h - 25_000.0).abs() / 15_000.0).max(0.0);
        let mie = self.mie_scattering * aerosols;
        let extinction = rayleigh + DVec3::splat(mie + self.mie_absorption * aerosols) + self.ozone * ozone;
        Medium { rayleigh, mie, extinction }
    }

    pub fn rayleigh_phase(&self, nu: f64) -> f64 {
        3.0 / (16.0 * PI) * (1.0 + nu * nu)
    }

    pub fn mie_phase(&self, nu: f64) -> f64 {
        let g = self.mie_g;
        (1.0 - g * g) / (4.0 * PI * (1.0 + g * g - 2.0 * g * nu).powf(1.5))
    }
}

/// Horizon's zenith cosine at radius r: rays below it meet the ground.
pub fn horizon_mu(r: f64) -> f64 {
    -(1.0 - (BOTTOM / r).powi(2)).max(0.0).sqrt()
}

pub fn distance_to_ground(r: f64, mu: f64) -> Option<f64> {
    let discriminant = r * r * (mu * mu - 1.0) + BOTTOM * BOTTOM;
    (mu < 0.0 && discriminant >= 0.0).then(|| (-r * mu - discriminant.sqrt()).max(0.0))
}

/// (entry, exit) of the atmosphere's top along (r, μ); entry 0 from inside.
pub fn top_crossings(r: f64, mu: f64) -> Option<(f64, f64)> {
    let rt = BOTTOM + TOP;
    let discriminant = r * r * (mu * mu - 1.0) + rt * rt;
    if discriminant < 0.0 {
        return None;
    }
    let exit = -r * mu + discriminant.sqrt();
    if r <= rt {
        return Some((0.0, exit));
    }
    let entry = -r * mu - discriminant.sqrt();
    (entry > 0.0).then_some((entry, exit))
}

/// A straight path from radius r0 with zenith cosine μ; the sun at zenith cosine
/// μs there, at cosine ν from the path.
#[derive(Clone, Copy, Debug)]
pub struct Path {
    pub r0: f64,
    pub mu: f64,
    pub mu_s: f64,
    pub nu: f64,
    pub t_start: f64,
    pub t_end: f64,
    pub hits_ground: bool,
}

/// Local geometry at distance t.
pub struct Point {
    pub r: f64,
    pub h: f64,
    pub mu: f64,
    pub mu_s: f64,
}

impl Path {
    pub fn new(r0: f64, mu: f64, mu_s: f64, nu: f64) -> Self {
        let empty = Self { r0, mu, mu_s, nu, t_start: 0.0, t_end: 0.0, hits_ground: false };
        let Some((t_start, exit)) = top_crossings(r0, mu) else { return empty };
        match distance_to_ground(r0, mu) {
            Some(g) => Self { t_start, t_end: g, hits_ground: true, ..empty },
            None => Self { t_start, t_end: exit, ..empty },
        }
    }

    /// From an altitude, a view zenith cosine, the sun's zenith cosine and the
    /// azimuth φ between the view and the sun about the zenith.
    pub fn from_angles(h: f64, mu: f64, mu_s: f64, phi: f64) -> Self {
        let nu = mu * mu_s + (1.0 - mu * mu).max(0.0).sqrt() * (1.0 - mu_s * mu_s).max(0.0).sqrt() * phi.cos();
        Self::new(BOTTOM + h, mu, mu_s, nu.clamp(-1.0, 1.0))
    }

    pub fn at(&self, t: f64) -> Point {
        let r = (t * t + 2.0 * self.r0 * self.mu * t + self.r0 * self.r0).sqrt();
        let mu = ((self.r0 * self.mu + t) / r).clamp(-1.0, 1.0);
        let mu_s = ((self.r0 * self.mu_s + t * self.nu) / r).clamp(-1.0, 1.0);
        Point { r, h: (r - BOTTOM).max(0.0), mu, mu_s }
    }

    /// Azimuth between the view and the sun about the local zenith at `p`.
    pub fn azimuth_at(&self, p: &Point) -> f64 {
        let s = ((1.0 - p.mu * p.mu) * (1.0 - p.mu_s * p.mu_s)).max(0.0).sqrt();
        if s < 1e-12 {
            return 0.0;
        }
        ((self.nu - p.mu * p.mu_s) / s).clamp(-1.0, 1.0).acos()
    }

    /// `n` steps (midpoint, length) over the part inside the atmosphere, shortest
    /// at its lowest point: edges at L (k/m)² on each side of it.
    pub fn steps(&self, n: usize) -> Vec<(f64, f64)> {
        if self.t_end <= self.t_start {
            return Vec::new();
        }
        let low = (-self.r0 * self.mu).clamp(self.t_start, self.t_end);
        let (down, up) = (low - self.t_start, self.t_end - low);
        let m_down = if down > 0.0 { ((n as f64 * down / (down + up)).round() as usize).max(1) } else { 0 };
        let m_up = if up > 0.0 { (n - m_down.min(n - 1)).max(1) } else { 0 };
        let mut edges = Vec::with_capacity(m_down + m_up + 1);
        for k in (0..=m_down).rev() {
            edges.push(low - down * (k as f64 / m_down.max(1) as f64).powi(2));
        }
        for k in 1..=m_up {
            edges.push(low + up * (k as f64 / m_up as f64).powi(2));
        }
        edges.windows(2).map(|e| (0.5 * (e[0] + e[1]), e[1] - e[0])).filter(|(_, dt)| *dt > 0.0).collect()
    }
}

/// Transmittance and in-scattered radiance over a step of constant coefficients.
pub fn exact_step(extinction: DVec3, source: DVec3, dt: f64) -> (DVec3, DVec3) {
    let t = (-extinction * dt).exp();
    let r = DVec3::from_array(std::array::from_fn(|i| {
        if extinction[i] > 0.0 { source[i] * (1.0 - t[i]) / extinction[i] } else { source[i] * dt }
    }));
    (t, r)
}
