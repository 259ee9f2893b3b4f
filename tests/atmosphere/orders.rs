//! Light scattered more than once, order by order, on a grid: J_n, the radiance
//! scattered into a direction by the n-th scattering, and L_n, the radiance of
//! order n arriving from a direction, at altitudes h, view zenith cosines μ (split
//! at the horizon), sun zenith cosines μs and azimuths φ about the zenith between
//! the view and the sun (the field is symmetric in φ). J_n = σs ∫ p L_{n−1} dω on
//! the grid's own directions (phase weights normalised per direction, so that no
//! energy is gained or lost by the quadrature); L_n = ∫ T J_n dt along each
//! grid ray, plus the ground's Lambertian reflection of the order before.
//!
//! Grid: 16 altitudes × 48 view angles × 24 sun angles × 12 azimuths, coarse
//! enough for CI; halving it changes the reference skies by less than its stated error.

use super::model::{BOTTOM, Model, Path, TOP, exact_step, horizon_mu};
use super::reference::parallel;
use super::transmittance::Table;
use glam::DVec3;
use std::f64::consts::PI;

pub const NR: usize = 16;
pub const HALF: usize = 24;
pub const NMU: usize = 2 * HALF;
pub const NMUS: usize = 24;
pub const NPHI: usize = 12;
const STEPS: usize = 64;

pub fn node_h(i: usize) -> f64 {
    TOP * (i as f64 / (NR - 1) as f64).powi(2)
}

/// View zenith cosine of entry j at altitude h, and its quadrature weight in μ.
/// j < HALF: rays that meet the ground, nearest the horizon last; then sky rays.
pub fn node_mu(h: f64, j: usize) -> (f64, f64) {
    let mh = horizon_mu(BOTTOM + h);
    let (k, ground) = if j < HALF { (HALF - 1 - j, true) } else { (j - HALF, false) };
    let v = (k as f64 + 0.5) / HALF as f64;
    if ground {
        (mh - (1.0 + mh) * v * v, 2.0 * (1.0 + mh) * v / HALF as f64)
    } else {
        (mh + (1.0 - mh) * v * v, 2.0 * (1.0 - mh) * v / HALF as f64)
    }
}

pub fn node_mu_s(k: usize) -> f64 {
    let x = -1.0 + 2.0 * k as f64 / (NMUS - 1) as f64;
    x * x.abs()
}

pub fn node_phi(l: usize) -> f64 {
    (l as f64 + 0.5) * PI / NPHI as f64
}

pub fn index(i: usize, j: usize, k: usize, l: usize) -> usize {
    ((i * NMU + j) * NMUS + k) * NPHI + l
}

pub const SIZE: usize = NR * NMU * NMUS * NPHI;

/// Linear interpolation position in 0..n−1, clamped.
fn locate(p: f64, n: usize) -> (usize, f64) {
    let p = p.clamp(0.0, (n - 1) as f64);
    let i = (p as usize).min(n - 2);
    (i, p - i as f64)
}

/// (j, weight) pairs interpolating μ at altitude h, within its side of the horizon.
fn mu_weights(h: f64, mu: f64) -> [(usize, f64); 2] {
    let mh = horizon_mu(BOTTOM + h);
    let (v, base, ground) = if mu < mh {
        (((mh - mu) / (1.0 + mh)).max(0.0).sqrt(), 0, true)
    } else {
        (((mu - mh) / (1.0 - mh)).max(0.0).sqrt(), HALF, false)
    };
    let (k, f) = locate(v * HALF as f64 - 0.5, HALF);
    let j = |k: usize| if ground { base + HALF - 1 - k } else { base + k };
    [(j(k), 1.0 - f), (j(k + 1), f)]
}

/// A field on the grid, interpolated multilinearly.
pub fn sample(field: &[DVec3], h: f64, mu: f64, mu_s: f64, phi: f64) -> DVec3 {
    let (i, fi) = locate((h / TOP).clamp(0.0, 1.0).sqrt() * (NR - 1) as f64, NR);
    let x = mu_s.signum() * mu_s.abs().sqrt();
    let (k, fk) = locate((x + 1.0) / 2.0 * (NMUS - 1) as f64, NMUS);
    let (l, fl) = locate(phi / PI * NPHI as f64 - 0.5, NPHI);
    let mut sum = DVec3::ZERO;
    for (ii, wi) in [(i, 1.0 - fi), (i + 1, fi)] {
        for (j, wj) in mu_weights(node_h(ii), mu) {
            for (kk, wk) in [(k, 1.0 - fk), (k + 1, fk)] {
                for (ll, wl) in [(l, 1.0 - fl), (l + 1, fl)] {
                    let w = wi * wj * wk * wl;
                    if w != 0.0 {
                        sum += field[index(ii, j, kk, ll)] * w;
                    }
                }
            }
        }
    }
    sum
}

/// Solid angle weights and directions of the grid at altitude h, over the whole
/// circle of azimuths: (j, l in 0..2·NPHI, μ, φ, weight).
fn sphere(h: f64) -> Vec<(usize, usize, f64, f64, f64)> {
    let dphi = PI / NPHI as f64;
    let mut out = Vec::with_capacity(NMU * 2 * NPHI);
    for j in 0..NMU {
        let (mu, w) = node_mu(h, j);
        for l in 0..2 * NPHI {
            out.push((j, l, mu, (l as f64 + 0.5) * dphi, w * dphi));
        }
    }
    out
}

fn direction(mu: f64, phi: f64) -> DVec3 {
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), mu)
}

/// J_n from L_{n−1}: per altitude, normalised phase matrices folded over the
/// symmetric azimuths, applied for each sun angle.
pub fn scatter(model: &Model, previous: &[DVec3]) -> Vec<DVec3> {
    let planes: Vec<Vec<DVec3>> = parallel(NR, |i| {
        let h = node_h(i);
        let medium = model.medium(h);
        let dirs = sphere(h);
        let n = NMU * NPHI;
        let mut rayleigh = vec![0.0; n * n];
        let mut mie = vec![0.0; n * n];
        for j in 0..NMU {
            for l in 0..NPHI {
                let view = direction(node_mu(h, j).0, node_phi(l));
                let row = (j * NPHI + l) * n;
                let (mut sum_r, mut sum_m) = (0.0, 0.0);
                for &(jj, ll, mu, phi, w) in &dirs {
                    let cos = view.dot(direction(mu, phi)).clamp(-1.0, 1.0);
                    let folded = jj * NPHI + if ll < NPHI { ll } else { 2 * NPHI - 1 - ll };
                    let (pr, pm) = (model.rayleigh_phase(cos) * w, model.mie_phase(cos) * w);
                    rayleigh[row + folded] += pr;
                    mie[row + folded] += pm;
                    (sum_r, sum_m) = (sum_r + pr, sum_m + pm);
                }
                for c in 0..n {
                    rayleigh[row + c] /= sum_r;
                    mie[row + c] /= sum_m;
                }
            }
        }
        let mut plane = vec![DVec3::ZERO; NMU * NMUS * NPHI];
        for k in 0..NMUS {
            let incoming: Vec<DVec3> = (0..n).map(|c| previous[index(i, c / NPHI, k, c % NPHI)]).collect();
            for r in 0..n {
                let (mut sr, mut sm) = (DVec3::ZERO, DVec3::ZERO);
                for c in 0..n {
                    sr += incoming[c] * rayleigh[r * n + c];
                    sm += incoming[c] * mie[r * n + c];
                }
                plane[(r / NPHI * NMUS + k) * NPHI + r % NPHI] = medium.rayleigh * sr + sm * medium.mie;
            }
        }
        plane
    });
    planes.concat()
}

/// Irradiance of the ground by a field, per sun angle: ∫ L μ dω over the sky.
pub fn ground_irradiance(field: &[DVec3]) -> Vec<DVec3> {
    let dirs = sphere(0.0);
    (0..NMUS)
        .map(|k| {
            dirs.iter()
                .filter(|d| d.2 > 0.0)
                .map(|&(j, l, mu, _, w)| field[index(0, j, k, if l < NPHI { l } else { 2 * NPHI - 1 - l })] * mu * w)
                .sum()
        })
        .collect()
}

/// Interpolates a per-sun-angle ground table.
pub fn sample_ground(table: &[DVec3], mu_s: f64) -> DVec3 {
    let x = mu_s.signum() * mu_s.abs().sqrt();
    let (k, f) = locate((x + 1.0) / 2.0 * (NMUS - 1) as f64, NMUS);
    table[k].lerp(table[k + 1], f)
}

/// L along every grid ray: ∫ T J dt with `source` giving J at a point, plus the
/// ground's reflection of irradiance `ground(μs)` (without the albedo/π).
pub fn gather(
    model: &Model,
    source: &(dyn Fn(&Path, f64) -> DVec3 + Sync),
    ground: &(dyn Fn(f64) -> DVec3 + Sync),
) -> Vec<DVec3> {
    let planes: Vec<Vec<DVec3>> = parallel(NR * NMU, |ij| {
        let (i, j) = (ij / NMU, ij % NMU);
        let h = node_h(i);
        let mu = node_mu(h, j).0;
        let mut out = Vec::with_capacity(NMUS * NPHI);
        for k in 0..NMUS {
            for l in 0..NPHI {
                let path = Path::from_angles(h, mu, node_mu_s(k), node_phi(l));
                out.push(integrate(model, &path, STEPS, source, ground));
            }
        }
        out
    });
    planes.concat()
}

/// Radiance along one path from its sources and its ground.
pub fn integrate(
    model: &Model,
    path: &Path,
    steps: usize,
    source: &(dyn Fn(&Path, f64) -> DVec3 + Sync),
    ground: &(dyn Fn(f64) -> DVec3 + Sync),
) -> DVec3 {
    let mut transmittance = DVec3::ONE;
    let mut radiance = DVec3::ZERO;
    for (t, dt) in path.steps(steps) {
        let medium = model.medium(path.at(t).h);
        let (tr, l) = exact_step(medium.extinction, source(path, t), dt);
        radiance += transmittance * l;
        transmittance *= tr;
    }
    if path.hits_ground {
        radiance += transmittance * model.albedo / PI * ground(path.at(path.t_end).mu_s);
    }
    radiance
}

/// Once-scattered sun light at distance t along a path, per unit irradiance.
pub fn single_source<'a>(model: &'a Model, sun: &'a Table) -> impl Fn(&Path, f64) -> DVec3 + Sync + 'a {
    move |path: &Path, t: f64| {
        let p = path.at(t);
        let m = model.medium(p.h);
        (m.rayleigh * model.rayleigh_phase(path.nu) + DVec3::splat(m.mie * model.mie_phase(path.nu)))
            * sun.to_space(p.r, p.mu_s)
    }
}

/// A tabulated J at distance t along a path.
pub fn table_source(field: &[DVec3]) -> impl Fn(&Path, f64) -> DVec3 + Sync + '_ {
    move |path: &Path, t: f64| {
        let p = path.at(t);
        sample(field, p.h, p.mu, p.mu_s, path.azimuth_at(&p))
    }
}
