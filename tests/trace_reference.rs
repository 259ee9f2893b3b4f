//! The GPU traversal against a CPU double-precision reference, and watertightness.

use crate::common;

use common::{TestRng, gpu, icosphere_obj, repo, scene_from, temp_dir, trace_ray, write};
use glam::DVec3;
use rt::bvh::BuildQuality;
use rt::layout::{EMPTY_LINK, GpuTraceRay};
use rt::render::Session;

/// Closest hit by brute force in f64 (Möller–Trumbore): (t, triangle index).
fn reference_hit(triangles: &[[DVec3; 3]], o: DVec3, d: DVec3) -> Option<(f64, usize)> {
    let mut best: Option<(f64, usize)> = None;
    for (i, [a, b, c]) in triangles.iter().enumerate() {
        let e1 = *b - *a;
        let e2 = *c - *a;
        let p = d.cross(e2);
        let det = e1.dot(p);
        if det == 0.0 {
            continue;
        }
        let s = o - *a;
        let u = s.dot(p) / det;
        let q = s.cross(e1);
        let v = d.dot(q) / det;
        let t = e2.dot(q) / det;
        if u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && best.is_none_or(|(bt, _)| t < bt) {
            best = Some((t, i));
        }
    }
    best
}

fn world_triangles(renderer: &Session) -> Vec<[DVec3; 3]> {
    let inst = &renderer.geometry().instances[0];
    let m = rt::bvh::object_to_world(inst);
    renderer
        .geometry()
        .triangles
        .iter()
        .map(|t| [t.v0, t.v1, t.v2].map(|v| m.transform_point3(DVec3::from(v.map(f64::from)))))
        .collect()
}

#[test]
fn gpu_traversal_matches_cpu_reference_on_the_bunny() {
    let scene = scene_from(
        "[[mesh]]\nasset = \"assets/bunny/bunny.obj\"\nrotate_deg = [10.0, 35.0, -5.0]\ntranslate = [0.3, -0.2, 0.1]\nscale = 1.7\n",
    );
    let mut renderer = Session::open(gpu(), scene, BuildQuality::Medium).expect("renderer");
    let tris = world_triangles(&renderer);
    let (lo, hi) = (renderer.geometry().bounds_min.as_dvec3(), renderer.geometry().bounds_max.as_dvec3());
    let centre = (lo + hi) / 2.0;
    let mut rng = TestRng(7);
    let rays: Vec<GpuTraceRay> = (0..10_000)
        .map(|_| {
            let o = centre + DVec3::from(rng.unit_vector()) * 3.0;
            let target = lo + (hi - lo) * DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64());
            trace_ray(o, target - o)
        })
        .collect();
    let hits = renderer.trace(&rays).expect("trace");
    let (mut hit_count, mut same_primitive, mut shared_edge, mut max_rel) = (0, 0, 0, 0f64);
    for (r, h) in rays.iter().zip(&hits) {
        assert_eq!(h.overflowed, 0);
        let o = DVec3::from(r.origin.map(f64::from));
        let d = DVec3::from(r.direction.map(f64::from));
        let reference = reference_hit(&tris, o, d);
        match reference {
            None => assert_eq!(h.primitive, EMPTY_LINK, "GPU hit where the reference misses: {r:?}"),
            Some((t, i)) => {
                assert_ne!(h.primitive, EMPTY_LINK, "GPU misses where the reference hits at {t}: {r:?}");
                hit_count += 1;
                let rel = (h.t as f64 - t).abs() / t;
                max_rel = max_rel.max(rel);
                assert!(rel <= 1e-5, "distance {} vs reference {t}", h.t);
                if h.primitive as usize == i {
                    same_primitive += 1;
                } else {
                    // A tie: the ray crosses an edge or vertex the two triangles share.
                    let shares = tris[i].iter().filter(|v| tris[h.primitive as usize].contains(v)).count();
                    assert!(shares >= 1, "GPU hit triangle {} where the reference hits {i}", h.primitive);
                    shared_edge += 1;
                }
            }
        }
    }
    println!(
        "{hit_count} hits of 10000 rays: {same_primitive} same triangle, {shared_edge} ties on shared edges, max relative distance error {max_rel:.2e}"
    );
    assert!(hit_count > 3000, "too few rays hit the bunny to test anything");
}

#[test]
fn no_ray_escapes_a_closed_mesh() {
    let (text, vertices, faces) = icosphere_obj(4);
    let path = temp_dir("watertight").join("icosphere.obj");
    write(&path, &text);
    let scene = scene_from(&format!(
        "[[mesh]]\nasset = {:?}\nrotate_deg = [17.0, 29.0, 41.0]\nscale = 2.0\n",
        path.display().to_string()
    ));
    let mut renderer = Session::open(gpu(), scene, BuildQuality::Medium).expect("renderer");
    let m = renderer.scene().meshes[0].object_to_world.as_dmat4();
    let world = |p: [f64; 3]| m.transform_point3(DVec3::from(p));
    // Targets where rays are likeliest to slip through: vertices, edge midpoints, and edges' thirds.
    let mut targets: Vec<DVec3> = vertices.iter().map(|v| world(*v)).collect();
    for f in &faces {
        for k in 0..3 {
            let (a, b) = (world(vertices[f[k]]), world(vertices[f[(k + 1) % 3]]));
            targets.extend([(a + b) / 2.0, a + (b - a) / 3.0]);
        }
    }
    let mut rng = TestRng(11);
    let mut rays = Vec::with_capacity(1_000_000);
    while rays.len() < 1_000_000 {
        // Origins anywhere well inside (radius 2 after scaling), the centre included.
        let o = if rays.len() % 10 == 0 { DVec3::ZERO } else { DVec3::from(rng.unit_vector()) * 1.5 * rng.next_f64() };
        let target =
            if rays.len() % 4 == 3 { o + DVec3::from(rng.unit_vector()) } else { targets[rays.len() % targets.len()] };
        rays.push(trace_ray(o, target - o));
    }
    let hits = renderer.trace(&rays).expect("trace");
    let escapes = hits.iter().filter(|h| h.primitive == EMPTY_LINK).count();
    let overflows = hits.iter().filter(|h| h.overflowed != 0).count();
    println!("{} rays from inside a closed {}-triangle mesh: {escapes} escapes", rays.len(), faces.len());
    assert_eq!(overflows, 0);
    assert_eq!(escapes, 0, "rays escaped through the closed mesh");
    let _ = std::fs::remove_dir_all(path.parent().unwrap_or(&repo()));
}
