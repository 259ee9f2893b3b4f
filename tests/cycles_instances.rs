//! rt against Cycles on scenes built from instances in Blender
//! (`tests/cycles/make_instance_refs.py` builds, exports and renders them): nested
//! collection instances with a material override, a geometry-nodes scatter and a hair
//! particle system, and objects sharing one mesh with other materials in some slots
//! (material sets of one asset). The global mean must agree within 4 σ and every 8×8 block within
//! 5 σ, σ estimated from rt's own noise at the sample counts used.

use crate::common;

use common::measured::render_measured;
use common::reference::{self, Noiseless};
use common::repo;

/// Samples per pixel of the committed references (`make_instance_refs.py --spp`).
const REFERENCE_SPP: f64 = 8192.0;
const SPP: u32 = 256;
/// Cycles renders with 16 bounces of each kind.
const MAX_BOUNCES: u32 = 16;

/// rt's render of `instances_{name}` against Cycles'.
fn check(name: &str) {
    let folder = repo().join(format!("tests/cycles/scenes/instances_{name}"));
    let scene = rt::scene::load(&folder.join("scene.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert!(!scene.instance_sets.is_empty(), "{name}: the export wrote no [[instances]]");
    let instances: usize = scene
        .instance_sets
        .iter()
        .map(|s| rt::asset::rtinst::read(&s.file).unwrap_or_else(|e| panic!("{e}")).records.len())
        .sum();
    let (ours, _) = render_measured(scene, |r| (r.spp, r.max_bounces) = (SPP, MAX_BOUNCES));
    // Blocks with no noise in rt (sky seen directly) must match to rounding: Cycles' f32
    // sums of 8192 samples leave it a few parts in 10⁴ (measured: up to 1.9e-4).
    let file = repo().join(format!("tests/cycles/instances_{name}.exr"));
    let comparison = reference::compare_measured(&ours, &file, REFERENCE_SPP, Noiseless::Relative(5e-4));
    comparison.check(&format!("instances_{name} ({instances} instances)"), "Cycles");
}

#[test]
fn nested_collection_instances_with_a_material_override_match_cycles() {
    check("collections");
}

#[test]
fn geometry_nodes_scatter_and_hair_particles_match_cycles() {
    // "pile" runs nodes that output only instances: its cones are placed, it is not a mesh.
    let folder = repo().join("tests/cycles/scenes/instances_scatter");
    assert!(!folder.join("assets/pile").exists(), "an object with only instances was exported as a mesh");
    let cones =
        rt::asset::rtinst::read(&folder.join("scene_instances/cone.rtinst")).unwrap_or_else(|e| panic!("{e}")).records;
    assert!(cones.len() > 40, "{} cones: the pile's instances are missing (the lawn's hair has 40)", cones.len());
    check("scatter");
}

#[test]
fn objects_showing_one_mesh_with_other_materials_share_one_asset_and_match_cycles() {
    // Three objects of one two-slot mesh (own materials, a red top, an emissive body),
    // instanced thrice: one asset, whose instance file has two material sets.
    let folder = repo().join("tests/cycles/scenes/instances_overrides");
    let assets: Vec<_> =
        std::fs::read_dir(folder.join("assets")).expect("assets").flatten().map(|e| e.file_name()).collect();
    assert_eq!(assets.len(), 2, "{assets:?}: expected the floor and one slab folder");
    let file = rt::asset::rtinst::read(&folder.join("scene_instances/slab.rtinst")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((file.records.len(), file.material_sets.len(), file.material_sets.slot_count()), (9, 2, 2));
    check("overrides");
}

#[test]
fn object_info_of_instances_and_objects_matches_cycles() {
    // Each scattered pebble has its own Random (from the depsgraph's random_id), each
    // tinted cube its Object Color; the instance files carry them.
    let folder = repo().join("tests/cycles/scenes/instances_object_info");
    let pebbles =
        rt::asset::rtinst::read(&folder.join("scene_instances/pebble.rtinst")).unwrap_or_else(|e| panic!("{e}"));
    let mut randoms: Vec<f32> = pebbles.info.iter().map(|i| i.random).collect();
    randoms.dedup();
    assert_eq!(randoms.len(), pebbles.records.len(), "the pebbles' Random values are not each their own");
    check("object_info");
}
