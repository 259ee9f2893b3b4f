//! Ray tracing in f32 at every scale: no self-intersection, far and huge
//! spheres at the right distance, tiny, huge and degenerate triangles, and a
//! pathological BVH that may overflow its stack but never silently.

use crate::common;

use common::{TestRng, gpu, scene_from, temp_dir, trace_ray, write};
use glam::DVec3;
use rt::bvh::BuildQuality;
use rt::layout::{EMPTY_LINK, GpuTraceRay, SPHERE_BIT};
use rt::render::Session;

fn v(p: [f32; 3]) -> DVec3 {
    DVec3::from(p.map(f64::from))
}

/// Writes triangles (f32 vertices, printed exactly) as an OBJ file and returns a scene placing it.
fn mesh_scene(name: &str, triangles: &[[[f32; 3]; 3]]) -> rt::scene::Scene {
    let mut text = String::new();
    for t in triangles {
        for p in t {
            text.push_str(&format!("v {:e} {:e} {:e}\n", p[0], p[1], p[2]));
        }
    }
    for i in 0..triangles.len() {
        text.push_str(&format!("f {} {} {}\n", 3 * i + 1, 3 * i + 2, 3 * i + 3));
    }
    let path = temp_dir(name).join("mesh.obj");
    write(&path, &text);
    scene_from(&format!("[[mesh]]\nasset = {:?}\n", path.display().to_string()))
}

fn log_uniform(rng: &mut TestRng, lo: f64, hi: f64) -> f64 {
    (lo.ln() + rng.next_f64() * (hi.ln() - lo.ln())).exp()
}

/// Triangles whose size and position share a scale drawn log-uniformly from
/// `lo` to `hi` metres.
fn triangles_at_all_scales(count: usize, lo: f64, hi: f64) -> Vec<[[f32; 3]; 3]> {
    let mut rng = TestRng(17);
    (0..count)
        .map(|_| {
            let s = log_uniform(&mut rng, lo, hi);
            let centre = DVec3::from(rng.unit_vector()) * s * 10.0 * rng.next_f64();
            [0, 1, 2].map(|_| (centre + DVec3::from(rng.unit_vector()) * s).as_vec3().to_array())
        })
        .collect()
}

#[test]
fn spawned_rays_never_rehit_their_own_triangle_from_1e_4_to_1e6_m() {
    const TRIANGLES: usize = 1000;
    const RAYS_EACH: usize = 500;
    let tris = triangles_at_all_scales(TRIANGLES, 1e-4, 1e6);
    let mut renderer = Session::open(gpu(), mesh_scene("reintersect", &tris), BuildQuality::Medium).expect("renderer");
    let mut rng = TestRng(5);
    let mut rays = Vec::with_capacity(TRIANGLES * RAYS_EACH);
    for t in &tris {
        let [a, b, c] = t.map(v);
        let scale = (b - a).length().max((c - a).length());
        for _ in 0..RAYS_EACH {
            let (u, w) = (rng.next_f64(), rng.next_f64());
            let (u, w) = if u + w > 1.0 { (1.0 - u, 1.0 - w) } else { (u, w) };
            let target = a + (b - a) * u + (c - a) * w;
            let o = target + DVec3::from(rng.unit_vector()) * scale * log_uniform(&mut rng, 0.1, 10.0);
            rays.push(trace_ray(o, target - o));
        }
    }
    let mut rehits = [0usize; 2];
    let mut spawned = [0usize; 2];
    for (k, through) in [false, true].into_iter().enumerate() {
        let (first, _, second) = renderer.trace_and_spawn(&rays, through).expect("trace");
        for (f, s) in first.iter().zip(&second) {
            if f.primitive != EMPTY_LINK {
                spawned[k] += 1;
                rehits[k] += usize::from(s.primitive == f.primitive);
            }
        }
    }
    println!(
        "{TRIANGLES} triangles at 1e-4..1e6 m: {} rays spawned back: {} re-hits; {} rays spawned through: {} re-hits",
        spawned[0], rehits[0], spawned[1], rehits[1]
    );
    assert!(spawned.iter().all(|&n| n > TRIANGLES * RAYS_EACH / 2), "too few first hits to test anything");
    assert_eq!(rehits, [0, 0], "spawned rays hit their own surface again");
}

/// Distance to a sphere along a ray, in f64.
fn sphere_distance(o: DVec3, d: DVec3, c: DVec3, r: f64) -> Option<f64> {
    let f = o - c;
    let b = -f.dot(d);
    let disc = r * r - (f + b * d).length_squared();
    if disc < 0.0 {
        return None;
    }
    let q = b + b.signum() * disc.sqrt();
    let (t0, t1) = ((f.length_squared() - r * r) / q, q);
    [t0.min(t1), t0.max(t1)].into_iter().find(|&t| t > 0.0)
}

#[test]
fn far_and_planet_sized_spheres_are_hit_at_the_right_distance() {
    let scene = scene_from(
        "[[sphere]]\ncenter = [0.0, 1.0, -10000.0]\nradius = 1.0\n\
         [[sphere]]\ncenter = [0.0, -6360000.0, 0.0]\nradius = 6360000.0\n",
    );
    let mut renderer = Session::open(gpu(), scene, BuildQuality::Medium).expect("renderer");
    let mut rng = TestRng(9);
    let eye = DVec3::new(0.0, 1.7, 0.0);
    let small = (DVec3::new(0.0, 1.0, -10000.0), 1.0);
    let planet = (DVec3::new(0.0, -6360000.0, 0.0), 6360000.0);
    let mut rays = Vec::new();
    for _ in 0..5000 {
        // At the small sphere 10 km away, across its whole disk.
        let target = small.0 + DVec3::from(rng.unit_vector()) * 0.999;
        rays.push(trace_ray(eye, target - eye));
        // At the ground from 1.7 m, down to grazing angles 0.1° below the horizon.
        let below = log_uniform(&mut rng, 0.1, 90.0).to_radians();
        let azimuth = rng.next_f64() * std::f64::consts::TAU;
        rays.push(trace_ray(eye, DVec3::new(below.cos() * azimuth.cos(), -below.sin(), below.cos() * azimuth.sin())));
    }
    let hits = renderer.trace(&rays).expect("trace");
    let mut worst = [0f64; 2];
    for (i, (r, h)) in rays.iter().zip(&hits).enumerate() {
        let (c, radius) = if i % 2 == 0 { small } else { planet };
        let o = v(r.origin);
        let d = v(r.direction);
        let expected = sphere_distance(o, d, c, radius).expect("the reference hits");
        assert_eq!(h.primitive, (i % 2) as u32 | SPHERE_BIT, "ray {i} missed");
        let rel = (h.t as f64 - expected).abs() / expected;
        worst[i % 2] = worst[i % 2].max(rel);
    }
    println!("relative distance error: 1 m sphere at 10 km {:.1e}, planet from 1.7 m {:.1e}", worst[0], worst[1]);
    assert!(worst[0] < 1e-6, "1 m sphere at 10 km: {:.2e}", worst[0]);
    assert!(worst[1] < 1e-6, "planet: {:.2e}", worst[1]);

    // Rays spawned from those hits, back and through, never hit their own sphere
    // again where they cannot (the outside of either sphere is convex; through
    // the small one a ray legitimately meets its far side).
    for through in [false, true] {
        let (first, spawned, second) = renderer.trace_and_spawn(&rays, through).expect("trace");
        let mut rehits = 0;
        for (i, ((f, r), s)) in first.iter().zip(&spawned).zip(&second).enumerate() {
            let outward = !through;
            if f.primitive != EMPTY_LINK && outward && s.primitive == f.primitive {
                rehits += 1;
            }
            if through && i % 2 == 1 {
                // Into the planet from 1.7 m above: the origin must be below its surface.
                let (c, radius) = planet;
                assert!((v(r.origin) - c).length() < radius, "ray {i} spawned into the planet starts outside it");
            }
        }
        assert_eq!(rehits, 0, "spawned rays re-hit their sphere");
    }
}

#[test]
fn tiny_huge_and_degenerate_triangles() {
    let tiny: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1e-4, 0.0, 0.0], [0.0, 1e-4, 0.0]];
    let huge: [[f32; 3]; 3] = [[-1e6, -1e6, -5.0], [1e6, -1e6, -5.0], [0.0, 1e6, -5.0]];
    let degenerate: [[[f32; 3]; 3]; 3] = [
        [[2.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0]], // repeated vertex
        [[3.0, 0.0, 0.0], [3.0, 1.0, 0.0], [3.0, 2.0, 0.0]], // collinear
        [[4.0, 0.5, 0.0], [4.0, 0.5, 0.0], [4.0, 0.5, 0.0]], // a point
    ];
    let mut tris = vec![tiny, huge];
    tris.extend(degenerate);
    let mut renderer = Session::open(gpu(), mesh_scene("scales", &tris), BuildQuality::Medium).expect("renderer");
    let mut rng = TestRng(3);
    let mut rays = Vec::new();
    for _ in 0..2000 {
        let (u, w) = (rng.next_f64() * 0.5, rng.next_f64() * 0.5);
        rays.push(trace_ray(
            DVec3::new(2e-5, 2e-5, 1.0),
            DVec3::new(u * 1e-4, w * 1e-4, 0.0) - DVec3::new(2e-5, 2e-5, 1.0),
        ));
        let o = DVec3::new(rng.next_f64() * 1e5, rng.next_f64() * 1e5, 100.0);
        rays.push(trace_ray(o, DVec3::new(0.0, 0.0, -1.0)));
        // Straight at the degenerate ones, edge-on and face-on.
        let target = DVec3::new(2.0 + (rng.next_f64() * 3.0).floor(), rng.next_f64() * 2.0, 0.0);
        let from = target + DVec3::from(rng.unit_vector());
        rays.push(trace_ray(from, target - from));
    }
    let hits = renderer.trace(&rays).expect("trace");
    let order = |p: u32| renderer.geometry().triangles[p as usize];
    let mut worst_tiny = 0f64;
    for (i, (r, h)) in rays.iter().zip(&hits).enumerate() {
        assert!(h.t.is_finite() || h.primitive == EMPTY_LINK, "ray {i}: t = {}", h.t);
        if h.primitive == EMPTY_LINK {
            assert_ne!(i % 3, 0, "a ray at the tiny triangle missed");
            assert_ne!(i % 3, 1, "a ray at the huge triangle missed");
            continue;
        }
        let t = order(h.primitive);
        let area = (v(t.v1) - v(t.v0)).cross(v(t.v2) - v(t.v0)).length();
        assert!(area > 0.0, "ray {i} hit a degenerate triangle");
        if i % 3 == 0 {
            let expected = (v(r.origin).z / -v(r.direction).z).abs();
            worst_tiny = worst_tiny.max((h.t as f64 - expected).abs() / expected);
        }
    }
    println!("1e-4 m triangle hit at relative distance error {worst_tiny:.1e}; degenerate triangles never hit");
    assert!(worst_tiny < 1e-6);
    // And a render over them stays finite (the helper asserts a clean sentinel).
    let scene = renderer.scene().clone();
    common::render(scene, 16, 16, 4, 4);
}

#[test]
fn nested_coincident_triangles_never_give_a_silently_wrong_hit() {
    // Thousands of triangles sharing a corner and a plane, each slightly
    // smaller than the last: a BVH over them nests deeply.
    let tris: Vec<[[f32; 3]; 3]> = (0..4000)
        .map(|k| {
            let s = 0.999f32.powi(k);
            let z = k as f32 * 1e-7;
            [[0.0, 0.0, z], [s, 0.0, z], [0.0, s, z]]
        })
        .collect();
    let mut renderer = Session::open(gpu(), mesh_scene("nested", &tris), BuildQuality::Medium).expect("renderer");
    let depth = renderer.geometry().meshes[0].bvh.stats.depth;
    let mut rng = TestRng(21);
    let rays: Vec<GpuTraceRay> = (0..20000)
        .map(|_| {
            let target = DVec3::new(rng.next_f64() * 0.5, rng.next_f64() * 0.5, 0.0);
            let o = target + DVec3::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5, 1.0);
            trace_ray(o, target - o)
        })
        .collect();
    let hits = renderer.trace(&rays).expect("trace");
    let world: Vec<[DVec3; 3]> = renderer.geometry().triangles.iter().map(|t| [v(t.v0), v(t.v1), v(t.v2)]).collect();
    let (mut overflowed, mut wrong) = (0, 0);
    for (r, h) in rays.iter().zip(&hits) {
        let (o, d) = (v(r.origin), v(r.direction));
        // The closest hit by brute force: all triangles are in planes z = const.
        let best = world
            .iter()
            .filter(|[a, b, c]| {
                let t = (a.z - o.z) / d.z;
                let p = o + d * t;
                t > 0.0 && p.x >= a.x.min(b.x).min(c.x) && p.y >= 0.0 && p.x + p.y <= b.x.max(c.y)
            })
            .map(|[a, ..]| (a.z - o.z) / d.z)
            .fold(f64::INFINITY, f64::min);
        let correct = (h.t as f64 - best).abs() <= 1e-5 * best.max(1.0);
        if h.overflowed != 0 {
            overflowed += 1;
        } else if !correct {
            wrong += 1;
        }
    }
    println!(
        "nested triangles: BVH depth {depth}, {overflowed} of {} rays flagged as overflowed, {wrong} wrong and unflagged",
        rays.len()
    );
    assert_eq!(wrong, 0, "a ray returned a wrong hit without flagging a stack overflow");
}

/// Many coincident or nested boxes once made the top level (and a mesh's tree) a chain as
/// deep as there were boxes, built in quadratic time: 10,000 coincident spheres gave depth
/// 9,993 in 2 s, 40,000 never finished. Now every tree is at most 30 levels deep (the GPU's
/// stack holds 32), and coincident spheres render as the one sphere they look like.
#[test]
fn coincident_and_nested_entries_build_shallow_trees_and_render_as_one() {
    let sphere = "[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\n";
    let camera = "[camera]\nposition = [0.0, 0.0, 4.0]\nlook_at = [0.0, 0.0, 0.0]\n";
    let coincident = scene_from(&format!("{camera}{}", sphere.repeat(20_000)));
    let nested: String = (0..20_000)
        .map(|i| format!("[[sphere]]\ncenter = [{}, 0.0, 0.0]\nradius = {}\n", i as f32 * 1e-5, 1.0 + i as f32 * 1e-3))
        .collect();
    for (what, scene) in [("coincident", &coincident), ("nested", &scene_from(&format!("{camera}{nested}")))] {
        let geometry = rt::bvh::SceneGeometry::build_in_memory(scene, BuildQuality::Medium).expect("geometry");
        println!("{what}: top level {:?}", geometry.tlas_stats);
        assert!(geometry.tlas_stats.depth <= 30, "{what}: top level {:?}", geometry.tlas_stats);
    }
    let same = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let mesh = rt::bvh::SceneGeometry::build_in_memory(
        &mesh_scene("coincident-triangles", &vec![same; 20_000]),
        BuildQuality::Medium,
    )
    .expect("geometry");
    println!("20,000 coincident triangles: {:?}", mesh.meshes[0].bvh.stats);
    assert!(mesh.meshes[0].bvh.stats.depth <= 30, "{:?}", mesh.meshes[0].bvh.stats);

    let one = common::render(scene_from(&format!("{camera}{sphere}")), 32, 32, 2, 2);
    let many = common::render(coincident, 32, 32, 2, 2);
    let worst = one
        .pixels
        .iter()
        .zip(&many.pixels)
        .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs()))
        .fold(0.0, f32::max);
    assert!(worst <= 1e-6 * one.pixels.iter().flatten().fold(1.0f32, |m, &c| m.max(c)), "worst difference {worst}");
}
