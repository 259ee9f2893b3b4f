//! Reload planning: what changed between two versions of a scene, and so the least
//! work that brings the GPU to the new one.
//!
//! | change | work |
//! |---|---|
//! | camera, sun, sky colour, render settings | new frame constants, accumulation reset |
//! | exposure | none on the GPU's path tracer: the display applies it |
//! | materials | material and emitter tables re-uploaded |
//! | placement (meshes, spheres, instance sets, an instance file's bytes) | top level rebuilt, geometry re-uploaded |
//! | an asset's files | that asset's BVH re-packed, top level rebuilt |
//! | features (sky kind, sun on/off, sampling) | the specialised pipeline for the new set |
//! | shaders (`--dev`) | pipelines rebuilt from `shaders/` on disk |
//!
//! Materials, placement and assets can also change the feature set (glass appears, the
//! last sphere goes); that is found when the geometry is reassembled.

use rt::scene::{LampKinds, RenderSettings, Scene, Sky};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// BLAKE3 of each asset's source files, or why they cannot be read.
pub type AssetPrints = BTreeMap<PathBuf, Result<[u8; 32], String>>;

/// One kind of change, in increasing order of the work it costs.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Change {
    Exposure,
    Camera,
    Sun,
    Sky,
    /// Size, spp, bounces and sampling parameters of `[render]`.
    Settings,
    /// A scene-level switch of the feature set: sky kind, sun on or off, sampling, rough-glass model.
    Features,
    Materials,
    /// Which assets are placed where, with which material; the spheres.
    Placement,
    /// The files of this asset changed.
    Asset(PathBuf),
    /// `shaders/*.wgsl` changed (`--dev`).
    Shaders,
}

impl Change {
    pub fn name(&self) -> &'static str {
        match self {
            Change::Exposure => "exposure",
            Change::Camera => "camera",
            Change::Sun => "sun",
            Change::Sky => "sky",
            Change::Settings => "settings",
            Change::Features => "features",
            Change::Materials => "materials",
            Change::Placement => "placement",
            Change::Asset(_) => "asset",
            Change::Shaders => "shaders",
        }
    }
}

/// The changes from one version of a scene to the next, sorted, without repeats.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Reload {
    pub changes: Vec<Change>,
}

impl Reload {
    pub fn is_empty(&self) -> bool {
        self.changes.is_empty()
    }

    /// "camera", "materials+placement", "none": for logs.
    pub fn kind(&self) -> String {
        let mut names: Vec<&str> = self.changes.iter().map(Change::name).collect();
        names.dedup();
        if names.is_empty() { "none".into() } else { names.join("+") }
    }

    pub fn has(&self, change: &Change) -> bool {
        self.changes.contains(change)
    }

    /// Assets whose BVH must be loaded again.
    pub fn assets(&self) -> impl Iterator<Item = &Path> {
        self.changes.iter().filter_map(|c| match c {
            Change::Asset(path) => Some(path.as_path()),
            _ => None,
        })
    }

    /// Whether the geometry, materials and feature set must be assembled again.
    pub fn reassembles(&self) -> bool {
        self.changes
            .iter()
            .any(|c| matches!(c, Change::Features | Change::Materials | Change::Placement | Change::Asset(_)))
    }

    /// Whether the BVHs and instances on the GPU are replaced (else at most the material table).
    pub fn replaces_geometry(&self) -> bool {
        self.changes.iter().any(|c| matches!(c, Change::Placement | Change::Asset(_)))
    }

    /// Whether the samples taken so far no longer belong to the image.
    pub fn resets_accumulation(&self) -> bool {
        self.changes.iter().any(|c| *c != Change::Exposure)
    }
}

/// What changed from `old` to `new`, given their assets' prints and whether the shaders changed.
pub fn plan(old: &Scene, new: &Scene, old_assets: &AssetPrints, new_assets: &AssetPrints, shaders: bool) -> Reload {
    let mut changes = Vec::new();
    if old.camera != new.camera {
        changes.push(Change::Camera);
        if old.camera.depth_of_field.is_some() != new.camera.depth_of_field.is_some()
            || old.camera.motion.is_some() != new.camera.motion.is_some()
        {
            changes.push(Change::Features);
        }
    }
    if old.sun != new.sun {
        changes.push(Change::Sun);
        if old.sun.is_some() != new.sun.is_some() {
            changes.push(Change::Features);
        }
    }
    if old.sky != new.sky {
        changes.push(Change::Sky);
        if std::mem::discriminant(&old.sky) != std::mem::discriminant(&new.sky) {
            changes.push(Change::Features);
        }
        // The world's graph is the material table's last material.
        if [&old.sky, &new.sky].iter().any(|s| matches!(s, Sky::Graph(_))) {
            changes.push(Change::Materials);
        }
    }
    settings(&old.render, &new.render, &mut changes);
    let names = |s: &Scene| s.materials.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    if old.materials != new.materials {
        changes.push(Change::Materials);
        // Instances and spheres refer to scene materials by index.
        if names(old) != names(new) {
            changes.push(Change::Placement);
        }
    }
    if old.meshes != new.meshes
        || old.spheres != new.spheres
        || old.lights != new.lights
        || old.instance_sets != new.instance_sets
    {
        changes.push(Change::Placement);
    }
    if LampKinds::of(&old.lights) != LampKinds::of(&new.lights) {
        changes.push(Change::Features);
    }
    for (path, print) in new_assets {
        if old_assets.get(path) != Some(print) {
            // An edited instance file moves instances: only the top level is rebuilt.
            let instance_file = new.instance_sets.iter().any(|s| s.file == *path);
            changes.push(if instance_file { Change::Placement } else { Change::Asset(path.clone()) });
        }
    }
    if shaders {
        changes.push(Change::Shaders);
    }
    changes.sort();
    changes.dedup();
    Reload { changes }
}

fn settings(old: &RenderSettings, new: &RenderSettings, changes: &mut Vec<Change>) {
    if old.exposure != new.exposure {
        changes.push(Change::Exposure);
    }
    let frame = |r: &RenderSettings| (r.width, r.height, r.spp, r.max_bounces, r.ris_candidates);
    if frame(old) != frame(new) {
        changes.push(Change::Settings);
    }
    if (old.sampling, old.rough_transmission, old.microfacet) != (new.sampling, new.rough_transmission, new.microfacet)
    {
        changes.extend([Change::Settings, Change::Features]);
    }
    if old.light_sampler != new.light_sampler {
        // The lamps' table and the shares of light samples follow the sampler.
        changes.extend([Change::Settings, Change::Features, Change::Placement]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use rt::scene::{Sampling, Sky};

    const SCENE: &str = r#"
        [camera]
        position = [0.0, 1.0, 4.0]
        look_at = [0.0, 1.0, 0.0]
        [sky]
        kind = "uniform"
        color = [0.5, 0.5, 0.5]
        [sun]
        elevation_deg = 30.0
        azimuth_deg = 10.0
        [materials.red]
        base_color = [0.8, 0.1, 0.1]
        [materials.white]
        [[mesh]]
        asset = "box.obj"
        material = "red"
        [[sphere]]
        center = [0.0, 1.0, 0.0]
        radius = 0.5
        material = "white"
    "#;

    fn scene() -> Scene {
        rt::scene::parse(SCENE, "scene.toml", Path::new("/s")).unwrap_or_else(|e| panic!("{e}"))
    }

    fn prints(hash: u8) -> AssetPrints {
        [(PathBuf::from("/s/box.obj"), Ok([hash; 32]))].into()
    }

    fn edited(edit: impl FnOnce(&mut Scene)) -> Scene {
        let mut s = scene();
        edit(&mut s);
        s
    }

    /// The plan from the test scene to `edit` of it, with unchanged assets.
    fn kind_after(edit: impl FnOnce(&mut Scene)) -> Reload {
        plan(&scene(), &edited(edit), &prints(1), &prints(1), false)
    }

    #[test]
    fn the_same_scene_needs_nothing() {
        let reload = kind_after(|_| {});
        assert!(reload.is_empty());
        assert_eq!(reload.kind(), "none");
        assert!(!reload.resets_accumulation());
    }

    #[test]
    fn a_camera_move_only_resets_accumulation() {
        let reload = kind_after(|s| s.camera.position.x += 1.0);
        assert_eq!(reload.changes, [Change::Camera]);
        assert!(reload.resets_accumulation() && !reload.reassembles());
    }

    #[test]
    fn sun_angles_are_frame_constants_but_a_sun_that_comes_or_goes_is_a_feature() {
        let reload = kind_after(|s| s.sun.as_mut().expect("sun").elevation_deg = 5.0);
        assert_eq!(reload.changes, [Change::Sun]);
        let reload = kind_after(|s| s.sun = None);
        assert_eq!(reload.changes, [Change::Sun, Change::Features]);
        assert!(reload.reassembles() && !reload.replaces_geometry());
        let back = plan(&edited(|s| s.sun = None), &scene(), &prints(1), &prints(1), false);
        assert_eq!(back.kind(), "sun+features");
    }

    #[test]
    fn a_new_light_sampler_reassembles_the_lights() {
        let reload = kind_after(|s| s.render.light_sampler = rt::scene::LightSampler::Tree);
        assert_eq!(reload.changes, [Change::Settings, Change::Features, Change::Placement]);
        assert!(reload.reassembles());
    }

    #[test]
    fn exposure_does_not_touch_the_samples() {
        let reload = kind_after(|s| s.render.exposure = 1.5);
        assert_eq!(reload.changes, [Change::Exposure]);
        assert!(!reload.resets_accumulation() && !reload.reassembles());
    }

    #[test]
    fn sky_colour_is_a_constant_and_sky_kind_a_feature() {
        assert_eq!(
            kind_after(|s| s.sky = Sky::Uniform { color: Vec3::ONE, sample_as_light: false }).changes,
            [Change::Sky]
        );
        assert_eq!(kind_after(|s| s.sky = Sky::Black).changes, [Change::Sky, Change::Features]);
    }

    /// The world's graph lives in the material table: another graph re-uploads it.
    #[test]
    fn a_world_graph_is_a_material() {
        let graph = |name: &str| Sky::Graph(rt::scene::WorldGraph { graph: name.into(), sample_as_light: true });
        assert_eq!(kind_after(|s| s.sky = graph("a.json")).changes, [Change::Sky, Change::Features, Change::Materials]);
        let old = edited(|s| s.sky = graph("a.json"));
        let reload = plan(&old, &edited(|s| s.sky = graph("b.json")), &prints(1), &prints(1), false);
        assert_eq!(reload.changes, [Change::Sky, Change::Materials]);
        assert!(reload.reassembles());
    }

    #[test]
    fn settings_and_sampling() {
        assert_eq!(kind_after(|s| s.render.max_bounces = 3).changes, [Change::Settings]);
        let reload = kind_after(|s| s.render.sampling = Sampling::Resampled);
        assert_eq!(reload.changes, [Change::Settings, Change::Features]);
    }

    #[test]
    fn a_material_colour_re_uploads_the_material_table_only() {
        let reload = kind_after(|s| s.materials[0].1.base_color = [0.1, 0.8, 0.1]);
        assert_eq!(reload.changes, [Change::Materials]);
        assert!(reload.reassembles() && !reload.replaces_geometry());
    }

    #[test]
    fn a_new_material_shifts_indices_so_placement_is_rebuilt() {
        let reload = kind_after(|s| s.materials.insert(0, ("blue".into(), Default::default())));
        assert_eq!(reload.kind(), "materials+placement");
        assert!(reload.replaces_geometry());
    }

    #[test]
    fn moving_a_mesh_or_a_sphere_is_placement() {
        let reload = kind_after(|s| s.meshes[0].object_to_world *= glam::Mat4::from_scale(Vec3::splat(2.0)));
        assert_eq!(reload.changes, [Change::Placement]);
        assert_eq!(kind_after(|s| s.spheres[0].radius = 0.7).changes, [Change::Placement]);
        assert_eq!(kind_after(|s| s.meshes[0].material = None).changes, [Change::Placement]);
        // An object's Shadow Terminator settings are its instance's; the features follow the geometry.
        let shifted = kind_after(|s| s.meshes[0].shadow_terminator.shading_offset = 0.5);
        assert_eq!(shifted.changes, [Change::Placement]);
        assert_eq!(kind_after(|s| s.meshes[0].holdout = true).changes, [Change::Placement]);
    }

    #[test]
    fn editing_a_lamp_is_placement_and_a_new_kind_a_feature() {
        let point = "[[light]]\ntype = \"point\"\nposition = [0.0, 2.0, 0.0]\n";
        let with_lamp = rt::scene::parse(point, "s.toml", Path::new("/s")).expect("a lamp");
        let mut brighter = with_lamp.clone();
        brighter.lights[0].power *= 2.0;
        assert_eq!(
            plan(&with_lamp, &brighter, &AssetPrints::new(), &AssetPrints::new(), false).changes,
            [Change::Placement]
        );
        let none = rt::scene::parse("", "s.toml", Path::new("/s")).expect("no lamp");
        let added = plan(&none, &with_lamp, &AssetPrints::new(), &AssetPrints::new(), false);
        assert_eq!(added.changes, [Change::Features, Change::Placement]);
    }

    #[test]
    fn an_asset_whose_files_changed_is_repacked_alone() {
        let old = scene();
        let reload = plan(&old, &old, &prints(1), &prints(2), false);
        assert_eq!(reload.changes, [Change::Asset(PathBuf::from("/s/box.obj"))]);
        assert_eq!(reload.kind(), "asset");
        assert_eq!(reload.assets().collect::<Vec<_>>(), [Path::new("/s/box.obj")]);
        assert!(reload.replaces_geometry());
        // A broken asset that is fixed is reloaded, even with the bytes it had before it broke.
        let broken: AssetPrints = [(PathBuf::from("/s/box.obj"), Err("truncated".into()))].into();
        assert_eq!(plan(&old, &old, &broken, &prints(1), false).kind(), "asset");
    }

    #[test]
    fn a_newly_placed_asset_is_loaded() {
        let old = scene();
        let mut new = old.clone();
        new.meshes.push(rt::scene::MeshInstance {
            asset: PathBuf::from("/s/other.obj"),
            material: None,
            object_to_world: glam::Mat4::IDENTITY,
            shadow_terminator: Default::default(),
            holdout: false,
            info: Default::default(),
            motion: None,
        });
        let mut new_prints = prints(1);
        new_prints.insert(PathBuf::from("/s/other.obj"), Ok([7; 32]));
        let reload = plan(&old, &new, &prints(1), &new_prints, false);
        assert_eq!(reload.changes, [Change::Placement, Change::Asset(PathBuf::from("/s/other.obj"))]);
    }

    #[test]
    fn turning_depth_of_field_on_changes_the_features() {
        let dof = rt::scene::DepthOfField {
            fstop: 2.8,
            focus_distance: 3.0,
            blades: 0,
            blade_rotation_deg: 0.0,
            aperture_ratio: 1.0,
        };
        let reload = kind_after(|s| s.camera.depth_of_field = Some(dof));
        assert_eq!(reload.changes, [Change::Camera, Change::Features]);
    }

    #[test]
    fn an_edited_instance_file_is_placement_not_an_asset() {
        let mut old = scene();
        old.instance_sets.push(rt::scene::InstanceSet {
            asset: PathBuf::from("/s/box.obj"),
            file: PathBuf::from("/s/boxes.rtinst"),
            materials: vec![],
            shadow_terminator: Default::default(),
            holdout: false,
            info: Default::default(),
        });
        let with_file = |hash: u8| {
            let mut p = prints(1);
            p.insert(PathBuf::from("/s/boxes.rtinst"), Ok([hash; 32]));
            p
        };
        let reload = plan(&old, &old, &with_file(1), &with_file(2), false);
        assert_eq!(reload.changes, [Change::Placement]);
        assert!(reload.replaces_geometry() && reload.assets().next().is_none());
    }

    #[test]
    fn several_changes_at_once_and_shaders() {
        let old = scene();
        let mut new = old.clone();
        new.camera.projection = rt::scene::Projection::FovY { degrees: 50.0 };
        new.materials[1].1.emission = [1.0; 3];
        let reload = plan(&old, &new, &prints(1), &prints(1), true);
        assert_eq!(reload.changes, [Change::Camera, Change::Materials, Change::Shaders]);
        assert_eq!(reload.kind(), "camera+materials+shaders");
    }
}
