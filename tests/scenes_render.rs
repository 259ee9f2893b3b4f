//! Every scene in `scenes/` renders, small, with finite pixels; the default scene too.

use crate::common;

use common::{render, repo};

#[test]
fn every_scene_renders_finite() {
    let scenes = common::scene_files();
    // The scenes README and the gallery show must be among those rendered here.
    for name in [
        "cornell_box",
        "cornell_glass",
        "courtyard",
        "dragon_clay",
        "dragon_mirror_spheres",
        "far_spheres",
        "flight",
        "furnace",
        "lamps",
        "many_lights",
        "showcase",
        "specular_pillars",
        "sunset",
    ] {
        assert!(scenes.iter().any(|p| p.file_stem().is_some_and(|s| s == name)), "scenes/{name}.toml is missing");
    }
    for path in scenes {
        let scene = rt::scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let image = render(scene, 48, 32, 2, 4);
        let bad = image.pixels.iter().flatten().filter(|v| !v.is_finite() || **v < 0.0).count();
        assert_eq!(bad, 0, "{}: non-finite or negative values", path.display());
        let mean: f32 = image.pixels.iter().flatten().sum::<f32>() / (image.pixels.len() * 3) as f32;
        assert!(mean > 0.0, "{}: the image is black", path.display());
    }
}

#[test]
fn built_in_default_scene_matches_the_file() {
    let builtin = rt::scene::default_scene().unwrap_or_else(|e| panic!("{e}"));
    let file = rt::scene::load(&repo().join("scenes/cornell_box.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(builtin.materials, file.materials);
    assert_eq!(builtin.camera, file.camera);
    let a = render(builtin, 32, 32, 4, 3);
    let b = render(file, 32, 32, 4, 3);
    // Same geometry and seed: the same image, bit for bit.
    assert_eq!(a.pixels, b.pixels);
}

#[test]
fn same_seed_same_image_whatever_the_dispatch_split() {
    let scene = rt::scene::load(&repo().join("scenes/cornell_box.toml")).unwrap_or_else(|e| panic!("{e}"));
    let one = render(scene.clone(), 24, 24, 5, 3);
    let again = render(scene, 24, 24, 5, 3);
    assert_eq!(one.pixels, again.pixels);
}

#[test]
fn dragon_mirror_spheres_is_the_seed_shot() {
    let scene = rt::scene::load(&repo().join("scenes/dragon_mirror_spheres.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.spheres.len(), 30);
    assert!(scene.spheres.iter().all(|s| s.material.as_deref() == Some("mirror") && (2.0..=4.0).contains(&s.radius)));
    let dragon = &scene.meshes[0];
    assert!(dragon.asset.ends_with("assets/dragon") && dragon.material.as_deref() == Some("blue_glass"));
    let (_, glass) = &scene.materials[scene.material_index("blue_glass").expect("blue_glass")];
    assert_eq!((glass.transmission, glass.ior, glass.roughness), (1.0, 1.3, 0.03));
    assert_eq!((glass.emission, glass.absorption), ([0.01, 0.03, 0.05], [0.02, 0.02, 0.015]));
}

#[test]
fn showcase_places_every_exported_asset() {
    let scene = rt::scene::load(&repo().join("scenes/showcase.toml")).unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<_> = scene.meshes.iter().filter_map(|m| m.asset.file_name()?.to_str()).collect();
    assert_eq!(names, ["dragon", "ground", "stanford_bunny", "suzanne", "teapot"]);
    for m in &scene.meshes {
        rt::asset::load_mesh(&m.asset).unwrap_or_else(|e| panic!("{e}"));
    }
}
