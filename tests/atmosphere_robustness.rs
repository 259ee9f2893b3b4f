//! The atmosphere stays finite and in range everywhere, and its hard cases stay
//! right: rays tangent to the planet, the sun at and below the horizon, cameras
//! at, above and below the atmosphere's ends, segments of any length.

use crate::atmosphere;

use atmosphere::probe::{Kind, Probe, Query};
use glam::DVec3;

const BOTTOM: f64 = 6_360_000.0;

fn to_dvec(v: [f32; 3]) -> DVec3 {
    DVec3::from(v.map(f64::from))
}

/// Zenith cosine of the horizon from altitude h.
fn horizon(h: f64) -> f64 {
    -(h * (2.0 * BOTTOM + h)).sqrt() / (BOTTOM + h)
}

/// A direction of zenith cosine μ at azimuth φ from the sun (which lies towards +X).
fn direction(mu: f64, phi: f64) -> [f32; 3] {
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    [(s * phi.cos()) as f32, mu as f32, (s * phi.sin()) as f32]
}

#[test]
fn finite_and_in_range_for_every_sun_and_altitude() {
    let mut probe = Probe::new("", &[]);
    let altitudes = [0.0, 1e-6, 1e-3, 1.5, 1_000.0, 10_000.0, 50_000.0, 99_999.99, 100_000.0, 100_000.01, 120_000.0];
    let mut queries = Vec::new();
    for h in altitudes {
        let origin = [0.0, h as f32, 0.0];
        let mh = horizon(h);
        let mut mus = vec![-1.0, -0.5, -0.1, 0.0, 1e-6, -1e-6, 0.1, 0.5, 1.0];
        // Rays grazing the planet, on both sides of tangent.
        for d in [0.0, 1e-7, 1e-5, 1e-3] {
            mus.extend([mh + d, mh - d]);
        }
        for mu in mus {
            for phi in [0.0f64, 1.0, std::f64::consts::PI] {
                let d = direction(mu.clamp(-1.0, 1.0), phi);
                queries.push(Query::new(Kind::SkyHook, origin, d, 0.0));
                queries.push(Query::new(Kind::TransmittanceHook, origin, d, 0.0));
                queries.push(Query::new(Kind::SunDisk, origin, d, 0.0));
                for t in [1e-3, 1.0, 1e3, 1e5, 1e7] {
                    queries.push(Query::new(Kind::Segment, origin, d, t));
                }
            }
        }
    }
    let mut elevations: Vec<f64> = (-18..=18).map(|e| e as f64 * 5.0).collect();
    elevations.extend([-0.265, -0.001, 0.001, 0.265, -3.2, -7.2]);
    for elevation in elevations {
        probe.set_sun(elevation);
        for (q, (a, b)) in queries.iter().zip(probe.run(&queries).0) {
            let (a, b) = (to_dvec(a), to_dvec(b));
            let what =
                format!("sun {elevation}°, kind {}, at {:?} along {:?} ({})", q.kind, q.origin, q.direction, q.param);
            assert!(a.is_finite() && b.is_finite(), "{what}: {a} {b}");
            assert!(a.cmpge(DVec3::ZERO).all() && b.cmpge(DVec3::ZERO).all(), "{what}: negative {a} {b}");
            if q.kind == Kind::TransmittanceHook as u32 {
                assert!(a.cmple(DVec3::ONE).all(), "{what}: transmittance {a}");
            }
            if q.kind == Kind::Segment as u32 {
                assert!(b.cmple(DVec3::ONE).all(), "{what}: transmittance {b}");
            }
        }
    }
}

/// The geometric horizon from 1.5 m lies 0.0393° below the horizontal: a ray
/// 0.038° down clears the planet, one 0.041° down meets it (the planet's radius
/// in f32 carries only half-metres, so this needs r² − R² written as h(2R + h)).
#[test]
fn the_horizon_from_eye_height_is_in_the_right_place() {
    let probe = Probe::new("", &[]);
    let origin = [0.0, 1.5, 0.0];
    let ray = |deg: f64| Query::new(Kind::TransmittanceHook, origin, direction(-deg.to_radians().sin(), 0.0), 0.0);
    let (t, _) = probe.run(&[ray(0.038), ray(0.041)]);
    assert!(t[0].0[0] > 0.0, "0.038° below the horizontal is sky: {:?}", t[0]);
    assert_eq!(t[1].0, [0.0; 3], "0.041° below the horizontal is ground");
}

/// A ray a hair below the horizontal (its lowest point micrometres ahead) sees
/// the sky the horizontal ray sees: the march's step growth tends to linear as
/// a side of the path shrinks to nothing, where e^κu − 1 over e^κ − 1 is 0/0
/// (harmless on lavapipe, whose fast-math division does not make it NaN).
#[test]
fn a_hair_below_the_horizontal_is_the_horizon() {
    let mut probe = Probe::new("", &[]);
    probe.set_sun(5.0);
    for h in [1_000.0f32, 10_000.0] {
        let q = |mu: f64| Query::new(Kind::Sky, [0.0, h, 0.0], direction(mu, 2.0), 8.0);
        let (l, _) = probe.run(&[q(0.0), q(-1e-10), q(-1e-9)]);
        let horizontal = to_dvec(l[0].0);
        for (a, _) in &l[1..] {
            let below = to_dvec(*a);
            assert!(((below - horizontal) / horizontal).abs().max_element() < 1e-3, "{h} m: {below} vs {horizontal}");
        }
    }
}

/// A camera above the atmosphere sees what a camera where its ray enters the air sees.
#[test]
fn from_space_the_sky_starts_at_the_top_of_the_atmosphere() {
    let mut probe = Probe::new("", &[]);
    probe.set_sun(20.0);
    let top = 100_000.0f64;
    for (h, mu) in [(120_000.0f64, -0.3f64), (400_000.0, -0.5), (120_000.0, -0.15)] {
        let d = DVec3::new((1.0 - mu * mu).sqrt(), mu, 0.0);
        // Where the ray meets the top: |c + t d| = R + top with c the origin from the centre.
        let c = DVec3::new(0.0, BOTTOM + h, 0.0);
        let (b, rt) = (c.dot(d), BOTTOM + top);
        let t = -b - (b * b - c.length_squared() + rt * rt).sqrt();
        let entry = DVec3::new(0.0, h, 0.0) + d * (t + 1.0);
        let q = |o: DVec3| Query::new(Kind::Sky, o.as_vec3().to_array(), d.as_vec3().to_array(), 16.0);
        let (l, _) = probe.run(&[q(DVec3::new(0.0, h, 0.0)), q(entry)]);
        let (far, near) = (to_dvec(l[0].0), to_dvec(l[1].0));
        assert!(far.length() > 0.0 && ((far - near).length() / near.length()) < 2e-3, "{far} vs {near}");
    }
}

/// Scene geometry below y = 0 is seen as if from the ground.
#[test]
fn below_the_ground_is_as_on_the_ground() {
    let mut probe = Probe::new("", &[]);
    probe.set_sun(30.0);
    let d = direction(0.3, 1.0);
    let (l, _) = probe.run(&[
        Query::new(Kind::Sky, [0.0, -25.0, 0.0], d, 8.0),
        Query::new(Kind::Sky, [0.0, 0.0, 0.0], d, 8.0),
        Query::new(Kind::Segment, [0.0, -25.0, 0.0], d, 500.0),
    ]);
    assert_eq!(l[0].0, l[1].0);
    assert!(to_dvec(l[2].1).cmple(DVec3::ONE).all() && to_dvec(l[2].0).is_finite());
}

/// The earth's shadow: the sun 1° below the horizon is hidden at the ground and
/// seen from 10 km (whose horizon dips 3.2°), reddened.
#[test]
fn the_sun_sets_later_for_a_plane() {
    let mut probe = Probe::new("", &[]);
    probe.set_sun(-1.0);
    let towards_sun = probe.frame.sun_direction;
    let (t, _) = probe.run(&[
        Query::new(Kind::TransmittanceHook, [0.0, 0.0, 0.0], towards_sun, 0.0),
        Query::new(Kind::TransmittanceHook, [0.0, 10_000.0, 0.0], towards_sun, 0.0),
    ]);
    assert_eq!(t[0].0, [0.0; 3]);
    let plane = to_dvec(t[1].0);
    assert!(plane.x > 0.05 && plane.x > 2.0 * plane.z, "the setting sun from 10 km: {plane}");
}

/// Deep night stays dark: far below the horizon the sky is darker than in twilight.
#[test]
fn night_is_darker_than_twilight() {
    let mut probe = Probe::new("", &[]);
    let zenith = [Query::new(Kind::Sky, [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], 8.0)];
    let mut previous = f64::INFINITY;
    for elevation in [-6.0, -12.0, -18.0, -30.0, -60.0, -90.0] {
        probe.set_sun(elevation);
        let l = to_dvec(probe.run(&zenith).0[0].0);
        println!("sun {elevation}°: zenith {l}");
        assert!(l.is_finite() && l.max_element() <= previous, "sun {elevation}°: {l}");
        previous = l.max_element();
    }
    assert!(previous < 1e-6, "with the sun at the nadir the sky is {previous}");
}

/// Aerial perspective is the sky's first stretch: what a segment adds, plus what
/// lies beyond it seen through it, is the sky along the whole ray.
#[test]
fn a_segment_and_the_sky_beyond_it_make_the_sky() {
    let mut probe = Probe::new("", &[]);
    probe.set_sun(10.0);
    for (h, mu, t) in
        [(2.0f64, 0.0f64, 3_000.0f64), (2.0, 0.02, 30_000.0), (500.0, 0.3, 2_000.0), (10_000.0, -0.2, 20_000.0)]
    {
        let d = DVec3::new((1.0 - mu * mu).sqrt() * 0.6, mu, (1.0 - mu * mu).sqrt() * 0.8);
        let o = DVec3::new(0.0, h, 0.0);
        let end = o + d * t;
        let dir = d.as_vec3().to_array();
        // Many segment samples: the segment's jitter is a hash of the ray.
        let segments: Vec<Query> = (0..64)
            .map(|k| Query::new(Kind::Segment, (o + d * (k as f64 * 1e-3)).as_vec3().to_array(), dir, t as f32))
            .collect();
        let (s, _) = probe.run(&segments);
        let radiance = s.iter().map(|(a, _)| to_dvec(*a)).sum::<DVec3>() / 64.0;
        let transmittance = s.iter().map(|(_, b)| to_dvec(*b)).sum::<DVec3>() / 64.0;
        let (sky, _) = probe.run(&[
            Query::new(Kind::Sky, o.as_vec3().to_array(), dir, 16.0),
            Query::new(Kind::Sky, end.as_vec3().to_array(), dir, 16.0),
        ]);
        let whole = to_dvec(sky[0].0);
        let split = radiance + transmittance * to_dvec(sky[1].0);
        let error = ((split - whole) / whole).abs().max_element();
        println!("h {h} m, mu {mu}, t {t} m: whole {whole:.5}, split {split:.5}, error {error:.4}");
        assert!(error < 0.01, "{error}");
    }
}

/// Limb darkening darkens and reddens the disk's edge and keeps its mean
/// radiance, hence the sun's irradiance.
#[test]
fn limb_darkening_keeps_the_irradiance() {
    let mut probe = Probe::new("", &[]);
    probe.set_sun(60.0);
    let s = to_dvec(probe.frame.sun_direction);
    let radius = (1.0 - probe.frame.sun_one_minus_cos as f64).acos();
    let (u, v) = (s.cross(DVec3::Z).normalize(), s.cross(s.cross(DVec3::Z)).normalize());
    // The disk by rings of equal area, each at 16 azimuths.
    let (rings, spokes) = (64, 16);
    let mut queries = Vec::new();
    for i in 0..rings {
        let r = radius * ((i as f64 + 0.5) / rings as f64).sqrt();
        for j in 0..spokes {
            let a = j as f64 * std::f64::consts::TAU / spokes as f64;
            let d = s * r.cos() + (u * a.cos() + v * a.sin()) * r.sin();
            queries.push(Query::new(Kind::SunDisk, [0.0; 3], d.as_vec3().to_array(), 0.0));
        }
    }
    queries.push(Query::new(Kind::TransmittanceHook, [0.0; 3], s.as_vec3().to_array(), 0.0));
    let (l, _) = probe.run(&queries);
    let through = to_dvec(l[queries.len() - 1].0) * probe.frame.sun_radiance[0] as f64;
    let disk = &l[..queries.len() - 1];
    let mean = disk.iter().map(|(a, _)| to_dvec(*a)).sum::<DVec3>() / disk.len() as f64;
    let (centre, limb) = (to_dvec(disk[0].0), to_dvec(disk[disk.len() - 1].0));
    println!("disk mean / (radiance x transmittance) = {}", mean / through);
    assert!(((mean / through) - DVec3::ONE).abs().max_element() < 2e-3, "{}", mean / through);
    assert!(limb.x < centre.x && limb.z / centre.z < limb.x / centre.x, "centre {centre}, limb {limb}");
}
