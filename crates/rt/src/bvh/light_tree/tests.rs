use super::*;

fn point(p: Vec3, phi: f32, i: u32) -> TreeLight {
    let bounds =
        LightBounds { min: p, max: p, phi, normals: DirectionCone::ENTIRE_SPHERE, cos_theta_e: 0.0, two_sided: false };
    TreeLight { bounds, link: i, trail_index: i }
}

/// Lights on a jittered grid with powers that vary over three orders of magnitude.
fn grid(n: u32) -> Vec<TreeLight> {
    (0..n)
        .map(|i| {
            let (x, z) = ((i % 37) as f32, (i / 37) as f32);
            let jitter = ((i as f32 * 12.9898).sin() * 43758.547).fract();
            point(Vec3::new(x + 0.3 * jitter, 2.0, z), 10f32.powf(3.0 * jitter), i)
        })
        .collect()
}

/// The leaf that `trail` leads to from the root.
fn follow(tree: &LightTree, mut trail: u32) -> &GpuLightTreeNode {
    let mut index = 0;
    loop {
        let node = &tree.nodes[index];
        if node.flags & LIGHT_TREE_LEAF != 0 {
            return node;
        }
        index = if trail & 1 == 0 { index + 1 } else { node.link as usize };
        trail >>= 1;
    }
}

/// Each inner node bounds its children and carries their summed power; returns the depth.
fn check_subtree(tree: &LightTree, index: usize) -> (GpuLightTreeNode, u32) {
    let node = tree.nodes[index];
    if node.flags & LIGHT_TREE_LEAF != 0 {
        return (node, 0);
    }
    let (a, da) = check_subtree(tree, index + 1);
    let (b, db) = check_subtree(tree, node.link as usize);
    for child in [a, b] {
        for k in 0..3 {
            assert!(node.bounds_min[k] <= child.bounds_min[k] && node.bounds_max[k] >= child.bounds_max[k]);
        }
    }
    let sum = a.power + b.power;
    assert!((node.power - sum).abs() <= 1e-5 * sum, "power {} of children summing to {sum}", node.power);
    (node, 1 + da.max(db))
}

#[test]
fn every_trail_leads_to_its_light() {
    let mut lights = grid(1500);
    lights[7].bounds.phi = 0.0;
    let tree = LightTree::build(&lights, lights.len()).expect("tree");
    assert_eq!(tree.nodes.len(), 2 * 1499 - 1);
    for l in &lights {
        let trail = tree.trails[l.trail_index as usize];
        if l.bounds.phi == 0.0 {
            assert_eq!(trail, LIGHT_TREE_ABSENT, "a dark light is left out");
            continue;
        }
        assert_eq!(follow(&tree, trail).link, l.link);
    }
    let (_, depth) = check_subtree(&tree, 0);
    // The cost-driven splits keep it shallow: a balanced tree over 1499 leaves has 11 levels.
    assert!(depth <= 22, "depth {depth}");
}

#[test]
fn lights_in_one_place_still_fit_their_trails() {
    // No split separates them: the median keeps the depth at log2 n.
    let lights: Vec<TreeLight> = (0..5000).map(|i| point(Vec3::ONE, 1.0, i)).collect();
    let tree = LightTree::build(&lights, lights.len()).expect("tree");
    assert_eq!(check_subtree(&tree, 0).1, 13);
    for l in &lights {
        assert_eq!(follow(&tree, tree.trails[l.trail_index as usize]).link, l.link);
    }
}

#[test]
fn a_deep_split_falls_back_to_the_median() {
    // Powers that halve from light to light make the cheapest split peel off one light at
    // a time: without the depth limit the tree would be 60 levels deep.
    let lights: Vec<TreeLight> =
        (0..60).map(|i| point(Vec3::new(2f32.powi(i as i32 / 4), 0.0, 0.0), 0.5f32.powi(i as i32), i)).collect();
    let tree = LightTree::build(&lights, lights.len()).expect("tree");
    assert!(check_subtree(&tree, 0).1 <= MAX_DEPTH);
    for l in &lights {
        assert_eq!(follow(&tree, tree.trails[l.trail_index as usize]).link, l.link);
    }
}

#[test]
fn without_lights_one_dark_leaf() {
    let tree = LightTree::build(&[], 3).expect("tree");
    assert_eq!(tree.nodes.len(), 1);
    assert_eq!((tree.nodes[0].flags, tree.nodes[0].power), (LIGHT_TREE_LEAF, 0.0));
    assert_eq!(tree.trails, vec![LIGHT_TREE_ABSENT; 3]);
}

#[test]
fn cone_union_holds_both_cones() {
    let cone = |w: Vec3, deg: f32| DirectionCone { w: w.normalize(), cos_theta: deg.to_radians().cos() };
    let pairs = [
        (cone(Vec3::Y, 10.0), cone(Vec3::X, 20.0)),
        (cone(Vec3::Y, 5.0), cone(Vec3::new(0.1, 1.0, 0.0), 1.0)),
        (cone(Vec3::Z, 0.0), cone(Vec3::new(0.0, 1.0, 1.0), 0.0)),
        (cone(Vec3::Z, 80.0), cone(-Vec3::Z, 80.0)),
    ];
    for (a, b) in pairs {
        let u = DirectionCone::union(a, b);
        for c in [a, b] {
            // The cone's axis and its rim, tilted every way.
            let angle = c.cos_theta.clamp(-1.0, 1.0).acos();
            let side = c.w.any_orthonormal_vector();
            for k in 0..16 {
                let around = glam::Quat::from_axis_angle(c.w, k as f32 * PI / 8.0) * side;
                let rim = glam::Quat::from_axis_angle(around, angle) * c.w;
                for d in [c.w, rim] {
                    assert!(d.dot(u.w) >= u.cos_theta - 1e-5, "{d} is outside {u:?}, the union of {a:?} and {b:?}");
                }
            }
        }
    }
}

#[test]
fn subtrees_built_on_threads_join_into_one_tree() {
    let lights = grid(40_000);
    let tree = LightTree::build(&lights, lights.len()).expect("tree");
    assert_eq!(tree.nodes.len(), 2 * lights.len() - 1);
    for l in &lights {
        assert_eq!(follow(&tree, tree.trails[l.trail_index as usize]).link, l.link);
    }
    let (root, _) = check_subtree(&tree, 0);
    let total: f32 = lights.iter().map(|l| l.bounds.phi).sum();
    assert!((root.power - total).abs() <= 1e-4 * total);
}
