//! The atmosphere against an independent double-precision reference
//! (tests/atmosphere/): its tables, and sky images rendered by the real WGSL,
//! per sun elevation and camera altitude, by PSNR; and what the seed's two ideas
//! (the closure for higher orders, exact integration of each step) gain.
//!
//! PSNR = 10 log₁₀(peak² / MSE) over all channels, the peak being the
//! reference's largest value. The reference is good to ~60 dB: refining its grid
//! (20 altitudes, 64 view angles, 18 azimuths, 96 steps) changes its skies by
//! 60–91 dB.

use crate::atmosphere;

use atmosphere::model::{BOTTOM, Model, horizon_mu};
use atmosphere::orders;
use atmosphere::probe::{Kind, Probe, Query, Variant};
use atmosphere::reference::{Reference, parallel};
use glam::DVec3;
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

fn reference() -> &'static Reference {
    static REFERENCE: OnceLock<Reference> = OnceLock::new();
    REFERENCE.get_or_init(|| {
        let start = Instant::now();
        let r = Reference::new(Model::of(&rt::scene::Atmosphere::default()));
        println!("reference: {} scattering orders in {:.1?}", r.orders, start.elapsed());
        r
    })
}

/// The GPU is lavapipe's CPU cores: one test on it at a time keeps timings honest.
fn gpu_turn() -> std::sync::MutexGuard<'static, ()> {
    static TURN: Mutex<()> = Mutex::new(());
    TURN.lock().unwrap_or_else(|e| e.into_inner())
}

const ALTITUDES_M: [f64; 4] = [0.0, 1_000.0, 10_000.0, 50_000.0];
const SUN_ELEVATIONS_DEG: [f64; 6] = [-6.0, 0.0, 2.0, 10.0, 45.0, 90.0];

fn psnr(reference: &[DVec3], measured: &[DVec3]) -> f64 {
    let peak = reference.iter().map(|v| v.max_element()).fold(0.0, f64::max);
    let mse = reference.iter().zip(measured).map(|(r, m)| (*r - *m).length_squared()).sum::<f64>()
        / (3 * reference.len()) as f64;
    10.0 * (peak * peak / mse).log10()
}

fn to_dvec(v: [f32; 3]) -> DVec3 {
    DVec3::from(v.map(f64::from))
}

/// The directions of a sky image: 36 elevations (5° cells, the ground included)
/// by 18 azimuths from the sun (5°, 15°, … 175°: the sky is symmetric about the
/// sun's vertical plane, and no direction lies within 5° of the sun's centre).
fn sky_directions() -> Vec<DVec3> {
    let mut out = Vec::new();
    for e in 0..36 {
        let elevation = (-87.5 + 5.0 * e as f64).to_radians();
        for a in 0..18 {
            let azimuth = (5.0 + 10.0 * a as f64).to_radians();
            out.push(DVec3::new(elevation.cos() * azimuth.cos(), elevation.sin(), elevation.cos() * azimuth.sin()));
        }
    }
    out
}

fn sun_direction(elevation_deg: f64) -> DVec3 {
    let e = elevation_deg.to_radians();
    DVec3::new(e.cos(), e.sin(), 0.0)
}

/// The reference's sky image, in rt's units (the probe's sun irradiance).
fn reference_image(probe: &Probe, altitude: f64, sun_elevation: f64) -> Vec<DVec3> {
    let (dirs, s, e, r) = (sky_directions(), sun_direction(sun_elevation), probe.irradiance(), reference());
    parallel(dirs.len(), |i| r.sky(altitude, dirs[i].y, s.y, dirs[i].dot(s)) * e)
}

/// The GPU's sky image, averaged over `jitters` spread jitters (a converged
/// render), and the time the dispatch took.
fn gpu_image(probe: &mut Probe, altitude: f64, sun: f64, jitters: u32, variant: Variant) -> (Vec<DVec3>, Duration) {
    probe.set_sun(sun);
    let origin = [0.0, altitude as f32, 0.0];
    let queries: Vec<Query> = sky_directions()
        .iter()
        .map(|d| Query::new(Kind::Sky, origin, d.as_vec3().to_array(), jitters as f32).with(variant))
        .collect();
    let (values, took) = probe.run(&queries);
    (values.iter().map(|(a, _)| to_dvec(*a)).collect(), took)
}

#[test]
fn sky_images_match_the_reference() {
    reference();
    let _turn = gpu_turn();
    let mut probe = Probe::new("", &[]);
    println!("PSNR of the sky (36x18 directions, 16 jitters each) against the reference, dB:");
    println!("{:>10} {}", "altitude", SUN_ELEVATIONS_DEG.map(|e| format!("{e:>7}°")).join(""));
    let mut worst = f64::INFINITY;
    for altitude in ALTITUDES_M {
        let mut row = format!("{altitude:>8} m");
        for sun in SUN_ELEVATIONS_DEG {
            let (gpu, _) = gpu_image(&mut probe, altitude, sun, 16, Variant::Built);
            let db = psnr(&reference_image(&probe, altitude, sun), &gpu);
            worst = worst.min(db);
            row.push_str(&format!("{db:>8.1}"));
        }
        println!("{row}");
    }
    // 40 dB is the bar (Bruneton's for sunsets); rt clears it by ~8 dB, and
    // losing more than 3 of them is a regression.
    assert!(worst >= 45.0, "worst PSNR {worst:.1} dB");
}

#[test]
fn transmittance_matches_quadrature() {
    let model = Model::of(&rt::scene::Atmosphere::default());
    let _turn = gpu_turn();
    let probe = Probe::new("", &[]);
    println!("transmittance to space against Gauss-Legendre quadrature:");
    for h in [0.0, 1_000.0, 10_000.0, 50_000.0, 99_000.0] {
        // View zenith cosines from just above the horizon up, densest at it.
        let mh = horizon_mu(BOTTOM + h);
        let mus: Vec<f64> = (0..64).map(|i| mh + (1.0 - mh) * ((i as f64 + 0.01) / 63.01).powi(2)).collect();
        let queries: Vec<Query> =
            mus.iter().map(|mu| Query::new(Kind::Transmittance, [h as f32, *mu as f32, 0.0], [0.0; 3], 0.0)).collect();
        let gpu: Vec<DVec3> = probe.run(&queries).0.iter().map(|(t, _)| to_dvec(*t)).collect();
        // The f32 cosine the GPU saw.
        let exact: Vec<DVec3> =
            mus.iter().map(|mu| atmosphere::transmittance::to_space(&model, BOTTOM + h, *mu as f32 as f64)).collect();
        let worst = gpu.iter().zip(&exact).map(|(g, e)| (*g - *e).abs().max_element()).fold(0.0, f64::max);
        let db = psnr(&exact, &gpu);
        println!("  {h:>6} m: PSNR {db:.1} dB, largest error {worst:.2e}");
        assert!(db >= 50.0 && worst < 2e-3, "transmittance at {h} m");
    }
}

#[test]
fn multiple_scattering_table_matches_reference() {
    let r = reference();
    let _turn = gpu_turn();
    let probe = Probe::new("", &[]);
    let nodes: Vec<(usize, usize)> = (0..orders::NR).flat_map(|i| (0..orders::NMUS).map(move |k| (i, k))).collect();
    let plane = |p: f32| {
        let queries: Vec<Query> = nodes
            .iter()
            .map(|&(i, k)| {
                let at = [orders::node_h(i) as f32, orders::node_mu_s(k) as f32, 0.0];
                Query::new(Kind::ScatteringPlane, at, [0.0; 3], p)
            })
            .collect();
        probe.run(&queries).0.iter().map(|(v, _)| to_dvec(*v)).collect::<Vec<_>>()
    };
    // L₂: the isotropic mean of once-scattered light; Ψ: of all scattered light.
    let l2_ref: Vec<DVec3> = nodes.iter().map(|&(i, k)| Reference::mean_at(&r.order_means[0], i, k)).collect();
    let psi_ref: Vec<DVec3> =
        nodes.iter().map(|&(i, k)| r.order_means.iter().map(|m| Reference::mean_at(m, i, k)).sum()).collect();
    let (l2, psi) = (plane(0.0), plane(3.0));
    let mus: Vec<f64> = (0..orders::NMUS).map(orders::node_mu_s).collect();
    let ground: Vec<Query> =
        mus.iter().map(|m| Query::new(Kind::GroundSky, [*m as f32, 0.0, 0.0], [0.0; 3], 0.0)).collect();
    let ground_gpu: Vec<DVec3> = probe.run(&ground).0.iter().map(|(v, _)| to_dvec(*v)).collect();
    let (l2_db, psi_db, ground_db) = (psnr(&l2_ref, &l2), psnr(&psi_ref, &psi), psnr(&r.ground_sky, &ground_gpu));
    println!("multiple scattering table against the reference (16 altitudes x 24 sun angles):");
    println!("  L2 {l2_db:.1} dB, Psi (all orders) {psi_db:.1} dB, the ground's sky irradiance {ground_db:.1} dB");
    assert!(l2_db >= 40.0 && psi_db >= 40.0 && ground_db >= 45.0);
}

/// Sky images for the gains: a low and a high sun, from the ground and from 10 km.
const GAIN_CASES: [(f64, f64); 4] = [(0.0, 2.0), (0.0, 45.0), (10_000.0, -6.0), (10_000.0, 10.0)];

/// Worst and mean PSNR over the gain cases, and the fastest of three timings of
/// all their directions (16 jitters each).
fn score(probe: &mut Probe, references: &[Vec<DVec3>], variant: Variant) -> (f64, f64, Duration) {
    let mut dbs = Vec::new();
    let mut time = Duration::ZERO;
    for (&(altitude, sun), reference) in GAIN_CASES.iter().zip(references) {
        let mut fastest = Duration::MAX;
        let mut image = Vec::new();
        for _ in 0..3 {
            let (values, took) = gpu_image(probe, altitude, sun, 16, variant);
            (image, fastest) = (values, fastest.min(took));
        }
        time += fastest;
        dbs.push(psnr(reference, &image));
    }
    (dbs.iter().copied().fold(f64::INFINITY, f64::min), dbs.iter().sum::<f64>() / dbs.len() as f64, time)
}

/// Point sampling: each step adds its source at the sample point times its
/// length, attenuated to the step's middle, instead of the exact solution.
const POINT_SAMPLING: (&str, &str) = (
    "let radiance = select(source * (1.0 - transmittance) / extinction, source * t, clear);",
    "let radiance = source * t * exp(-extinction * (0.5 * t));",
);

#[test]
fn closure_and_exact_integration_gains() {
    reference();
    let _turn = gpu_turn();
    let mut exact = Probe::new("", &[]);
    let mut point = Probe::new("", &[POINT_SAMPLING]);
    let references: Vec<Vec<DVec3>> = GAIN_CASES.iter().map(|&(h, sun)| reference_image(&exact, h, sun)).collect();
    let queries = sky_directions().len() * GAIN_CASES.len() * 16;
    println!(
        "exact per-step integration against point sampling (PSNR worst / mean over {GAIN_CASES:?}, GPU time of {queries} rays):"
    );
    let mut rows = Vec::new();
    for steps in [4u32, 8, 16, 32, 64] {
        let mut row = Vec::new();
        for probe in [&mut exact, &mut point] {
            probe.set_steps(steps);
            row.push(score(probe, &references, Variant::Built));
        }
        println!(
            "  {steps:>2} steps: exact {:.1} / {:.1} dB in {:.0} ms, point {:.1} / {:.1} dB in {:.0} ms",
            row[0].0,
            row[0].1,
            row[0].2.as_secs_f64() * 1e3,
            row[1].0,
            row[1].1,
            row[1].2.as_secs_f64() * 1e3
        );
        rows.push(row);
    }
    exact.set_steps(32);
    println!("light scattered more than once, at 32 steps:");
    let mut closures = Vec::new();
    for (name, variant) in [
        ("single scattering only", Variant::Orders1),
        ("second order, no closure", Variant::Orders2),
        ("seed's L2/(1-c), c = L3/L2", Variant::SecondOrderClosure),
        ("L2 + L3 + L4/(1-c), c = L4/L3 (rt)", Variant::Built),
    ] {
        let (worst, mean, time) = score(&mut exact, &references, variant);
        println!("  {name:<36} {worst:.1} / {mean:.1} dB in {:.0} ms", time.as_secs_f64() * 1e3);
        closures.push(mean);
    }
    // Exact steps are better at every count up to 32; each closure step helps.
    for row in &rows[..4] {
        assert!(row[0].1 > row[1].1, "exact integration lost to point sampling");
    }
    assert!(closures.windows(2).all(|w| w[1] > w[0]), "{closures:?}");
}
