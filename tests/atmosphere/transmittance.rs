//! Reference transmittance: optical depth by composite Gauss–Legendre quadrature
//! (64 panels of 8 nodes, converged to ~1e-9), and a fine table of it for the
//! reference march, which needs millions of sun transmittances.

use super::model::{BOTTOM, Model, Path, TOP, distance_to_ground, top_crossings};
use glam::DVec3;

const GL8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887),
    (-0.183_434_642_495_65, 0.362_683_783_378_362),
    (0.183_434_642_495_65, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
];
const PANELS: usize = 64;

/// ∫ extinction over [0, d] along (r, μ).
pub fn optical_depth(model: &Model, r: f64, mu: f64, d: f64) -> DVec3 {
    let path = Path { r0: r, mu, mu_s: 0.0, nu: 0.0, t_start: 0.0, t_end: d, hits_ground: false };
    let panel = d / PANELS as f64;
    let mut sum = DVec3::ZERO;
    for p in 0..PANELS {
        let centre = (p as f64 + 0.5) * panel;
        for (x, w) in GL8 {
            sum += model.medium(path.at(centre + 0.5 * panel * x).h).extinction * (0.5 * panel * w);
        }
    }
    sum
}

/// Transmittance to space along (r, μ): zero if the ground is in the way.
pub fn to_space(model: &Model, r: f64, mu: f64) -> DVec3 {
    if distance_to_ground(r, mu).is_some() {
        return DVec3::ZERO;
    }
    match top_crossings(r, mu) {
        None => DVec3::ONE,
        Some((entry, exit)) => {
            let entry_path = Path::new(r, mu, 0.0, 0.0).at(entry);
            (-optical_depth(model, entry_path.r, entry_path.mu, exit - entry)).exp()
        }
    }
}

/// Transmittance to space on a fine grid, in Bruneton's coordinates (smooth
/// there), interpolated bilinearly: 512 × 256 entries.
pub struct Table {
    width: usize,
    height: usize,
    values: Vec<DVec3>,
}

fn rho_top() -> f64 {
    let rt = BOTTOM + TOP;
    (rt * rt - BOTTOM * BOTTOM).sqrt()
}

impl Table {
    pub fn new(model: &Model) -> Self {
        let (width, height) = (512, 256);
        let rows: Vec<Vec<DVec3>> = super::reference::parallel(height, |j| {
            let rho = rho_top() * j as f64 / (height - 1) as f64;
            let r = (rho * rho + BOTTOM * BOTTOM).sqrt();
            (0..width)
                .map(|i| {
                    let d_min = BOTTOM + TOP - r;
                    let d = d_min + (rho + rho_top() - d_min) * i as f64 / (width - 1) as f64;
                    let rt = BOTTOM + TOP;
                    let mu = if d == 0.0 { 1.0 } else { ((rt * rt - r * r - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0) };
                    (-optical_depth(model, r, mu, d)).exp()
                })
                .collect()
        });
        Self { width, height, values: rows.concat() }
    }

    pub fn to_space(&self, r: f64, mu: f64) -> DVec3 {
        if distance_to_ground(r, mu).is_some() {
            return DVec3::ZERO;
        }
        let rt = BOTTOM + TOP;
        let r = r.min(rt);
        let rho = (r * r - BOTTOM * BOTTOM).max(0.0).sqrt();
        let d = -r * mu + (r * r * (mu * mu - 1.0) + rt * rt).max(0.0).sqrt();
        let d_min = rt - r;
        let x = ((d - d_min) / (rho + rho_top() - d_min)).clamp(0.0, 1.0) * (self.width - 1) as f64;
        let y = (rho / rho_top()).clamp(0.0, 1.0) * (self.height - 1) as f64;
        let (i, j) = ((x as usize).min(self.width - 2), (y as usize).min(self.height - 2));
        let (fx, fy) = (x - i as f64, y - j as f64);
        let at = |i: usize, j: usize| self.values[j * self.width + i];
        let lower = at(i, j).lerp(at(i + 1, j), fx);
        let upper = at(i, j + 1).lerp(at(i + 1, j + 1), fx);
        lower.lerp(upper, fy)
    }
}
