//! Energy: with nothing absorbing (no aerosol absorption, no ozone) and a white
//! ground, every bit of sunlight the planet intercepts leaves it again. The
//! power out — the radiance leaving the top of the atmosphere, integrated over its
//! sphere and over outgoing directions, plus the sunbeams that cross the air and
//! miss the ground — must equal the power in, E π R_top². The sky is symmetric
//! about the sun's axis, so the sphere is integrated over the angle from the
//! sub-solar point, the directions over their zenith cosine and azimuth (midpoint
//! rules, the azimuths mirrored).
//!
//! (rt scatters light the first time with the real phase functions and after
//! that isotropically; each scattering conserves energy, so this balance holds
//! for the model. The stronger white-furnace identity — uniform light in, the
//! same radiance everywhere out — does not hold for such a mixture, and is not
//! tested.)

use crate::atmosphere;

use atmosphere::probe::{Kind, Probe, Query, Variant};
use glam::DVec3;
use std::f64::consts::PI;

const BOTTOM: f64 = 6_360_000.0;
const TOP: f64 = 6_460_000.0;
/// Where the outgoing radiance is taken: just above the top of the atmosphere.
const SHELL: f64 = TOP + 1_000.0;
const VARIANTS: [Variant; 6] =
    [Variant::Orders1, Variant::Orders2, Variant::Orders3, Variant::Orders4, Variant::Built, Variant::EarlierRatio];

/// Power out over power in, per variant, with `n` angles from the sub-solar
/// point and 2n/3 × n/3 outgoing directions.
fn balance(probe: &mut Probe, n: usize) -> Vec<DVec3> {
    probe.frame.sun_direction = [0.0, 1.0, 0.0];
    let (n_mu, n_phi) = (2 * n / 3, n / 3);
    let mut queries = Vec::new();
    let mut weights = Vec::new();
    for i in 0..n {
        let theta = (i as f64 + 0.5) * PI / n as f64;
        let normal = DVec3::new(theta.sin(), theta.cos(), 0.0);
        let tangent = DVec3::new(theta.cos(), -theta.sin(), 0.0);
        // The planet's centre lies at y = −R below the world origin.
        let origin = normal * SHELL - DVec3::new(0.0, BOTTOM, 0.0);
        let area = 2.0 * PI * SHELL * SHELL * theta.sin() * PI / n as f64;
        for j in 0..n_mu {
            let mu = (j as f64 + 0.5) / n_mu as f64;
            for k in 0..n_phi {
                let phi = (k as f64 + 0.5) * PI / n_phi as f64;
                let s = (1.0 - mu * mu).sqrt();
                let out = normal * mu + (tangent * phi.cos() + DVec3::Z * phi.sin()) * s;
                let solid_angle = 2.0 * (1.0 / n_mu as f64) * (PI / n_phi as f64);
                for v in VARIANTS {
                    queries.push(
                        Query::new(Kind::Sky, origin.as_vec3().to_array(), (-out).as_vec3().to_array(), 4.0).with(v),
                    );
                }
                weights.push(area * mu * solid_angle);
            }
        }
    }
    let (radiance, _) = probe.run(&queries);
    let mut out = vec![DVec3::ZERO; VARIANTS.len()];
    for (q, (l, _)) in radiance.iter().enumerate() {
        out[q % VARIANTS.len()] += DVec3::from(l.map(f64::from)) * weights[q / VARIANTS.len()];
    }
    // Sunbeams through the air that miss the ground, by impact parameter b:
    // twice the transmittance from their lowest point, horizontally.
    let beams: Vec<Query> = (0..4 * n)
        .map(|i| {
            let b = BOTTOM + (TOP - BOTTOM) * (i as f64 + 0.5) / (4 * n) as f64;
            Query::new(Kind::Transmittance, [(b - BOTTOM) as f32, 0.0, 0.0], [0.0; 3], 0.0)
        })
        .collect();
    let beam: DVec3 = probe
        .run(&beams)
        .0
        .iter()
        .enumerate()
        .map(|(i, (t, _))| {
            let b = BOTTOM + (TOP - BOTTOM) * (i as f64 + 0.5) / (4 * n) as f64;
            let t = DVec3::from(t.map(f64::from));
            t * t * 2.0 * PI * b * (TOP - BOTTOM) / (4 * n) as f64
        })
        .sum();
    // Sun rays beyond the top of the atmosphere pass untouched; only those aimed at it count.
    let power_in = probe.irradiance() * PI * TOP * TOP;
    out.iter().map(|o| (*o + beam * probe.irradiance()) / power_in).collect()
}

#[test]
fn white_planet_returns_all_light() {
    let mut probe = Probe::new("mie_absorption = false\nozone = false\nground_albedo = 1.0", &[]);
    let fine = balance(&mut probe, 72);
    let coarse = balance(&mut probe, 36);
    println!("white planet, power out / power in (r g b):");
    for (v, f) in VARIANTS.iter().zip(&fine) {
        println!("  {v:?}: {:.4} {:.4} {:.4}", f.x, f.y, f.z);
    }
    // The midpoint rules' error, bounded by what halving them changes.
    let quadrature = fine.iter().zip(&coarse).map(|(f, c)| (*f - *c).abs().max_element()).fold(0.0, f64::max);
    println!("  quadrature error below {quadrature:.4}");
    // Each explicit order returns light the one before left in the air; none makes light.
    for k in 1..4 {
        assert!(fine[k].cmpgt(fine[k - 1]).all(), "order {} adds nothing: {} then {}", k + 1, fine[k - 1], fine[k]);
    }
    assert!(fine[3].max_element() <= 1.0 + quadrature, "orders up to 4 return more than came in: {}", fine[3]);
    // The closure's tail from c = L₄/L₃, and from the ratio an order earlier,
    // bracket what orders ≥ 5 really return: the balance lies between them.
    let (built, earlier) = (fine[4], fine[5]);
    let low = built.min(earlier) - DVec3::splat(quadrature);
    let high = built.max(earlier) + DVec3::splat(quadrature);
    assert!(low.cmple(DVec3::ONE).all() && high.cmpge(DVec3::ONE).all(), "1 is not within {low} .. {high}");
}
