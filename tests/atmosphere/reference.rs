//! The reference sky: single scattering integrated exactly (2000 steps per ray,
//! sun transmittance from the fine table), higher orders summed from the grid of
//! `orders` until an order adds less than 1e-4 of the total, and the ground lit
//! by the sun and by every order of the sky. Everything per unit solar irradiance.

use super::model::{BOTTOM, Model, Path};
use super::orders::{self, gather, ground_irradiance, integrate, sample_ground, scatter, single_source, table_source};
use super::transmittance::Table;
use glam::DVec3;
use std::f64::consts::PI;

const FINE_STEPS: usize = 2000;
const MAX_ORDER: usize = 40;

/// Runs `f(0..n)` on the machine's cores, in order.
pub fn parallel<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get()).min(n.max(1));
    let mut slots: Vec<Option<T>> = (0..n).map(|_| None).collect();
    std::thread::scope(|scope| {
        let chunks: Vec<_> = slots.chunks_mut(n.div_ceil(threads)).enumerate().collect();
        let size = n.div_ceil(threads);
        for (c, chunk) in chunks {
            let f = &f;
            scope.spawn(move || {
                for (k, slot) in chunk.iter_mut().enumerate() {
                    *slot = Some(f(c * size + k));
                }
            });
        }
    });
    slots.into_iter().map(|s| s.expect("every slot filled")).collect()
}

pub struct Reference {
    pub model: Model,
    pub sun: Table,
    /// Σ_{n≥2} J_n on the grid.
    pub multiple: Vec<DVec3>,
    /// L₁ and Σ_{n≥1} L_n on the grid.
    pub first: Vec<DVec3>,
    pub scattered: Vec<DVec3>,
    /// Σ_{n≥1} ground irradiance by the sky, per grid sun angle.
    pub ground_sky: Vec<DVec3>,
    /// Isotropic means of L_n (`isotropic_mean`), n = 1, 2, …, per grid (altitude, sun angle).
    pub order_means: Vec<Vec<DVec3>>,
    pub orders: usize,
}

/// Isotropic means of a field at every grid (altitude, sun angle).
fn means(field: &[DVec3]) -> Vec<DVec3> {
    (0..orders::NR * orders::NMUS)
        .map(|ik| Reference::isotropic_mean(field, ik / orders::NMUS, ik % orders::NMUS))
        .collect()
}

fn luminance(v: DVec3) -> f64 {
    0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z
}

impl Reference {
    pub fn new(model: Model) -> Self {
        let sun = Table::new(&model);
        let direct = |mu_s: f64| DVec3::splat(mu_s.max(0.0)) * sun.to_space(BOTTOM, mu_s);
        let first = gather(&model, &single_source(&model, &sun), &direct);
        let mut previous_ground = ground_irradiance(&first);
        let mut ground_sky = previous_ground.clone();
        let mut scattered = first.clone();
        let mut multiple = vec![DVec3::ZERO; orders::SIZE];
        let mut previous = first.clone();
        let mut order_means = vec![means(&first)];
        let mut order = 1;
        while order < MAX_ORDER {
            order += 1;
            let j = scatter(&model, &previous);
            let ground = previous_ground.clone();
            let l = gather(&model, &table_source(&j), &|mu_s| sample_ground(&ground, mu_s));
            let added: f64 = l.iter().map(|v| luminance(*v)).sum();
            let total: f64 = scattered.iter().map(|v| luminance(*v)).sum();
            for (m, v) in multiple.iter_mut().zip(&j) {
                *m += *v;
            }
            for (s, v) in scattered.iter_mut().zip(&l) {
                *s += *v;
            }
            order_means.push(means(&l));
            previous_ground = ground_irradiance(&l);
            for (g, v) in ground_sky.iter_mut().zip(&previous_ground) {
                *g += *v;
            }
            previous = l;
            if added < 1e-3 * total {
                break;
            }
        }
        Self { model, sun, multiple, first, scattered, ground_sky, order_means, orders: order }
    }

    /// Radiance per unit solar irradiance reaching altitude h0 along view zenith
    /// cosine μ, the sun at zenith cosine μs and cosine ν from the view; the sun's
    /// disk excluded.
    pub fn sky(&self, h0: f64, mu: f64, mu_s: f64, nu: f64) -> DVec3 {
        let path = Path::new(BOTTOM + h0, mu, mu_s, nu);
        let single = single_source(&self.model, &self.sun);
        let multiple = table_source(&self.multiple);
        let source = |p: &Path, t: f64| single(p, t) + multiple(p, t);
        let ground = |mu_s: f64| {
            DVec3::splat(mu_s.max(0.0)) * self.sun.to_space(BOTTOM, mu_s) + sample_ground(&self.ground_sky, mu_s)
        };
        integrate(&self.model, &path, FINE_STEPS, &source, &ground)
    }

    /// The isotropic mean at grid altitude i and sun angle k in a `means` table.
    pub fn mean_at(means: &[DVec3], i: usize, k: usize) -> DVec3 {
        means[i * orders::NMUS + k]
    }

    /// (1/4π) ∫ field dω at grid altitude i and sun angle k: the isotropic mean
    /// that the GPU's multiple scattering table approximates.
    pub fn isotropic_mean(field: &[DVec3], i: usize, k: usize) -> DVec3 {
        let h = orders::node_h(i);
        let dphi = PI / orders::NPHI as f64;
        let mut sum = DVec3::ZERO;
        for j in 0..orders::NMU {
            let w = orders::node_mu(h, j).1;
            for l in 0..orders::NPHI {
                sum += field[orders::index(i, j, k, l)] * (2.0 * w * dphi);
            }
        }
        sum / (4.0 * PI)
    }
}
