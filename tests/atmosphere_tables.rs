//! The atmosphere's tables: built only for an atmosphere, rebuilt only when
//! what they depend on changes, and finite and in range for any parameters the
//! scene file accepts.

use crate::atmosphere;
use crate::common;

use atmosphere::probe::{Kind, Probe, Query};
use common::{gpu, scene_from};
use rt::bvh::BuildQuality;
use rt::render::{RenderRequest, SceneUpdate, Session};
use rt::scene::Sky;

fn render(renderer: &mut Session) -> Vec<[f32; 3]> {
    let mut request = RenderRequest::from_scene(renderer.scene());
    (request.width, request.height, request.spp, request.max_bounces) = (8, 8, 1, 2);
    let (image, report) = renderer.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(report.dropped.is_clean(), "{}", report.dropped);
    image.pixels
}

#[test]
fn no_atmosphere_no_tables() {
    let renderer = Session::open(gpu(), scene_from("[sky]\nkind = \"uniform\"\n"), BuildQuality::Medium)
        .unwrap_or_else(|e| panic!("{e:#}"));
    assert!(renderer.atmosphere().is_none() && renderer.buffers().sky_bind_group.is_none());
}

#[test]
fn tables_are_rebuilt_only_when_they_must() {
    let scene = scene_from(&atmosphere::probe::scene_text(""));
    let mut renderer = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let Sky::Atmosphere(defaults) = renderer.scene().sky.clone() else { panic!("an atmosphere") };
    let before = render(&mut renderer);
    // The sun moves freely: it is in the frame, not in the tables.
    let mut moved = renderer.scene().clone();
    moved.sun.as_mut().expect("a sun").elevation_deg = 40.0;
    let reset = renderer.apply(SceneUpdate { scene: moved, geometry: None, shaders: None }).expect("the sun moves");
    assert!(reset, "a moved sun drops the samples so far");
    assert_ne!(render(&mut renderer), before);
    let mut params = defaults.clone();
    for (what, change, rebuilds) in [
        ("steps", (|p: &mut rt::scene::Atmosphere| p.steps = 8) as fn(&mut rt::scene::Atmosphere), false),
        ("ground altitude", |p| p.ground_altitude_m = 500.0, false),
        ("multiple scattering", |p| p.multiple_scattering = false, false),
        ("turbidity", |p| p.turbidity = 3.0, true),
        ("ground albedo", |p| p.ground_albedo = glam::Vec3::splat(0.6), true),
        ("table size", |p| p.multiple_scattering_lut = [16, 8], true),
    ] {
        let previous = render(&mut renderer);
        change(&mut params);
        let rebuilt = renderer.set_atmosphere(&params).unwrap_or_else(|e| panic!("{e:#}"));
        assert_eq!(rebuilt, rebuilds, "{what}");
        assert_ne!(render(&mut renderer), previous, "{what} changed nothing");
    }
}

#[test]
fn extreme_parameters_stay_finite_and_in_range() {
    for keys in [
        "turbidity = 100.0",
        "turbidity = 0.0\nrayleigh_scale = 0.0",
        "rayleigh_scale = 100.0\nground_albedo = 1.0",
        "mie_g = 0.999\nozone = false",
        "mie_g = -0.999\nmie_absorption = false",
        "ground_albedo = 0.0\nmultiple_scattering = false",
        "transmittance_lut = [4, 4]\nmultiple_scattering_lut = [4, 4]\nsteps = 2",
        "ground_altitude_m = 1000000.0",
    ] {
        let mut probe = Probe::new(keys, &[]);
        let tables = probe.renderer.atmosphere().expect("an atmosphere");
        let layout = tables.layout();
        let entries: Vec<[f32; 4]> = rt::gpu::read_buffer(gpu(), &tables.tables).expect("read back");
        for (i, e) in entries.iter().enumerate() {
            assert!(e.iter().all(|v| v.is_finite() && *v >= 0.0), "{keys}: entry {i} is {e:?}");
            if i < layout.scattering_offset as usize {
                assert!(e[..3].iter().all(|v| *v <= 1.0), "{keys}: transmittance {e:?}");
            }
        }
        for elevation in [-10.0, 0.0, 30.0] {
            probe.set_sun(elevation);
            let queries: Vec<Query> = [-0.5f32, 0.0, 0.2, 1.0]
                .iter()
                .map(|mu| Query::new(Kind::SkyHook, [0.0, 2.0, 0.0], [(1.0 - mu * mu).sqrt(), *mu, 0.0], 0.0))
                .collect();
            for (l, _) in probe.run(&queries).0 {
                assert!(l.iter().all(|v| v.is_finite() && *v >= 0.0), "{keys}, sun {elevation}°: {l:?}");
            }
        }
    }
}
