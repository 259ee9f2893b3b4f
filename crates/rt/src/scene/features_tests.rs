//! The feature set's tests: its analysis of materials and its flags' declaration.

use super::*;
use crate::scene::MaterialTextures;

fn features_of(material: Material) -> FeatureSet {
    let scene = crate::scene::default_scene().expect("the built-in scene");
    let geometry = GeometrySummary { triangles: true, materials_in_use: vec![material], ..Default::default() };
    FeatureSet::analyse(&scene, &geometry)
}

/// A coat over a normal map it does not share, or with one of its own, pays for the coat's
/// frame; a coat on the base's own map, a map without a coat or a bare coat do not.
#[test]
fn the_coat_normal_is_on_where_the_coats_normal_differs() {
    let coat = Material { coat: 1.0, ..Default::default() };
    let base_map = MaterialTextures { normal: Some(0), ..Default::default() };
    let on = |m: Material| features_of(m).coat_normal;
    assert!(on(Material { textures: base_map, ..coat.clone() }));
    assert!(on(Material { textures: MaterialTextures { coat_normal: Some(0), ..Default::default() }, ..coat.clone() }));
    let shared = MaterialTextures { coat_normal: Some(0), ..base_map };
    assert!(!on(Material { textures: shared, ..coat.clone() }));
    assert!(!on(Material { textures: base_map, ..Default::default() }));
    assert!(!on(coat));
    let own = features_of(Material {
        coat: 1.0,
        textures: MaterialTextures { coat_normal: Some(0), ..Default::default() },
        ..Default::default()
    });
    assert!(own.normal_maps && own.textures && own.coat, "the coat's map runs the normal-map code: {own}");
}

/// Each need names a flag that `complete` can turn on, and completing any one flag
/// leaves a set that has what it needs.
#[test]
fn every_need_can_be_turned_on() {
    let none = || {
        FeatureSet::with_flags_off(
            SkyFeature::Black,
            Transmission::None,
            LampKinds::default(),
            Sampling::Resampled,
            0,
            0,
        )
    };
    for flag in FLAGS {
        for need in flag.needs {
            let mut set = none();
            set.turn_on(need);
            assert_eq!(set.flag(need), Some(true), "{} needs {need}, which cannot be turned on", flag.name);
        }
        let mut set = none();
        (flag.set)(&mut set, true);
        set.complete();
        assert!(set.consistent() && (flag.get)(&set), "{}: {set}", flag.name);
    }
}

/// The flags' names are the shaders' names: each is found by `flag`, and none is also a
/// derived flag's name.
#[test]
fn every_flag_is_named_once() {
    let all = FeatureSet::all(SkyFeature::Uniform, Sampling::Nee, RoughTransmission::Ggx);
    for flag in FLAGS {
        assert_eq!(all.flag(flag.name), Some((flag.get)(&all)), "{}", flag.name);
        assert_eq!(all.derived_flag(flag.name), None, "{} is declared twice", flag.name);
        assert_eq!(FLAGS.iter().filter(|f| f.name == flag.name).count(), 1);
    }
    assert!(all.consistent() && !all.aovs && all.light_tree && all.coat_normal, "{all}");
    let resampled = FeatureSet::all(SkyFeature::Uniform, Sampling::Resampled, RoughTransmission::Ggx);
    assert!(!resampled.light_tree && resampled.consistent(), "the tree needs next-event estimation");
}

/// An analysed scene is a set whose flags have what they need.
#[test]
fn analysed_sets_are_consistent() {
    let textured = Material {
        coat: 1.0,
        textures: MaterialTextures { coat_normal: Some(0), normal: Some(1), ..Default::default() },
        ..Default::default()
    };
    for material in [Material::default(), textured, Material { anisotropy: 0.5, ..Default::default() }] {
        let set = features_of(material);
        assert!(set.consistent(), "{set}");
    }
}
