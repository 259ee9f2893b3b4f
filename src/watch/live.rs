//! A scene kept live on the GPU: the last good version read from disk, the viewer's
//! own camera, sun and exposure on top of it, and reloads that do the least work.
//!
//! A reload is all or nothing: everything that can fail (reading the scene, loading
//! assets, building pipelines) happens before anything on the GPU is replaced, so a
//! bad edit leaves the last good scene rendering.

use super::plan::{AssetPrints, Change, Reload, plan};
use super::sources::{asset_prints, watched_files};
use crate::bvh::{BuildQuality, LoadedMesh, SceneGeometry, asset_paths, pack::load_or_pack};
use crate::gpu::shader::{Program, ShaderFiles};
use crate::gpu::{GpuContext, Pipelines};
use crate::render::{RenderRequest, Renderer};
use crate::scene::{self, Camera, FeatureSet, Scene, Sun};
use anyhow::{Result, bail};
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::time::{Duration, Instant};

/// What the viewer changed on top of the scene file; a change of the same thing in the
/// file wins over it (the artist moved the camera in Blender: show that).
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    pub camera: Option<Camera>,
    pub sun: Option<Sun>,
    pub exposure: Option<f32>,
}

/// What one successful reload did.
#[derive(Clone, Debug)]
pub struct ReloadReport {
    /// 1 for the first reload after opening.
    pub number: u32,
    pub reload: Reload,
    pub elapsed: Duration,
    /// The new feature set, when it differs from the old one (another pipeline runs).
    pub new_features: Option<FeatureSet>,
}

pub struct LiveScene<'a> {
    pub renderer: Renderer<'a>,
    pub scene_path: PathBuf,
    /// The last good scene read from the file, without overrides.
    file_scene: Scene,
    assets: AssetPrints,
    overrides: Overrides,
    quality: BuildQuality,
    /// `shaders/` on disk, with `--dev`.
    shader_dir: Option<PathBuf>,
    reloads: u32,
}

impl<'a> LiveScene<'a> {
    pub fn open(
        ctx: &'a GpuContext,
        scene_path: &Path,
        quality: BuildQuality,
        shader_dir: Option<PathBuf>,
    ) -> Result<Self> {
        let scene = scene::load(scene_path)?;
        let assets = asset_prints(&scene);
        let mut renderer = Renderer::new(ctx, scene.clone(), quality)?;
        if let Some(dir) = &shader_dir {
            renderer.pipelines.reload_shaders(ctx, ShaderFiles::Dir(dir.clone()))?;
        }
        Ok(Self {
            renderer,
            scene_path: scene_path.to_path_buf(),
            file_scene: scene,
            assets,
            overrides: Overrides::default(),
            quality,
            shader_dir,
            reloads: 0,
        })
    }

    /// Every file whose change may change the image.
    pub fn watched_files(&self) -> Vec<PathBuf> {
        watched_files(&self.scene_path, &self.file_scene, self.shader_dir.as_deref())
    }

    pub fn shader_dir(&self) -> Option<&Path> {
        self.shader_dir.as_deref()
    }

    /// The path tracer's pipelines for the current feature set.
    pub fn pipelines(&mut self) -> Result<Rc<Pipelines>> {
        let features = self.renderer.geometry.features;
        self.renderer.pipelines.get(self.renderer.ctx, Program::Integrator, features)
    }

    /// A request for the current scene at `width`×`height`.
    pub fn request(&self, width: u32, height: u32, seed: u32) -> RenderRequest {
        let mut request = RenderRequest::from_scene(&self.renderer.scene);
        (request.width, request.height, request.seed) = (width, height, seed);
        request
    }

    /// The scene as rendered: the file's, with the overrides applied.
    pub fn scene(&self) -> &Scene {
        &self.renderer.scene
    }

    pub fn overrides(&self) -> &Overrides {
        &self.overrides
    }

    /// Sets the overrides; the caller resets the accumulation if the camera or sun moved.
    pub fn set_overrides(&mut self, overrides: Overrides) {
        self.overrides = overrides;
        self.renderer.scene = self.with_overrides(&self.file_scene);
    }

    fn with_overrides(&self, file: &Scene) -> Scene {
        let mut scene = file.clone();
        if let Some(camera) = &self.overrides.camera {
            scene.camera = camera.clone();
        }
        // The sun can be turned, not added: without a sun in the file there is none to turn.
        if let (Some(sun), Some(_)) = (&self.overrides.sun, &scene.sun) {
            scene.sun = Some(sun.clone());
        }
        if let Some(ev) = self.overrides.exposure {
            scene.render.exposure = ev;
        }
        scene
    }

    /// Reads the scene and its assets again after `changed` files changed, and brings the
    /// GPU to them with the least work. On an error nothing changes.
    pub fn reload(&mut self, changed: &[PathBuf]) -> Result<ReloadReport> {
        let start = Instant::now();
        let ctx = self.renderer.ctx;
        let shaders_changed =
            self.shader_dir.is_some() && changed.iter().any(|p| p.extension().is_some_and(|e| e == "wgsl"));
        let new_scene = scene::load(&self.scene_path)?;
        let new_assets = asset_prints(&new_scene);
        let reload = plan(&self.file_scene, &new_scene, &self.assets, &new_assets, shaders_changed);
        // The message names the asset's file.
        if let Some(Err(message)) = new_assets.values().find(|print| print.is_err()) {
            bail!("{message}");
        }

        let geometry = if reload.reassembles() { Some(self.assemble(&new_scene, &reload)?) } else { None };
        if let Some(dir) = self.shader_dir.as_ref().filter(|_| shaders_changed) {
            self.renderer.pipelines.reload_shaders(ctx, ShaderFiles::Dir(dir.clone()))?;
        }
        let features = geometry.as_ref().map_or(self.renderer.geometry.features, |g| g.features);
        self.renderer.pipelines.get(ctx, Program::Integrator, features)?;
        if reload.has(&Change::Sky) {
            // Before anything else changes: building an atmosphere's tables can fail.
            self.renderer.set_sky(&new_scene.sky)?;
        }

        let old_features = self.renderer.geometry.features;
        let layout = &self.renderer.pipelines.scene_layout;
        if let Some(geometry) = geometry {
            if reload.replaces_geometry() {
                self.renderer.buffers.replace_geometry(ctx, &geometry, layout)?;
            } else {
                self.renderer.buffers.replace_materials(ctx, &geometry, layout);
            }
            self.renderer.geometry = geometry;
        }
        self.forget_overrides(&reload);
        self.renderer.scene = self.with_overrides(&new_scene);
        (self.file_scene, self.assets) = (new_scene, new_assets);
        self.reloads += 1;
        Ok(ReloadReport {
            number: self.reloads,
            reload,
            elapsed: start.elapsed(),
            new_features: (features != old_features).then_some(features),
        })
    }

    /// The geometry of `scene`: the BVHs of changed assets loaded again (re-packed, since
    /// their cache is stale), the others reused.
    fn assemble(&self, scene: &Scene, reload: &Reload) -> Result<SceneGeometry> {
        let changed: Vec<&Path> = reload.assets().collect();
        let mut meshes: Vec<LoadedMesh> = Vec::new();
        for path in asset_paths(scene) {
            let old = self.renderer.geometry.meshes.iter().find(|m| m.path == path);
            match old {
                Some(mesh) if !changed.contains(&path.as_path()) => meshes.push(mesh.clone()),
                _ => {
                    let mesh = load_or_pack(&path, self.quality)?;
                    log::info!("{}: {} triangles, {:?}", path.display(), mesh.triangle_count, mesh.provenance);
                    meshes.push(mesh);
                }
            }
        }
        SceneGeometry::assemble(scene, meshes)
    }

    /// Drops the overrides of what the file changed.
    fn forget_overrides(&mut self, reload: &Reload) {
        if reload.has(&Change::Camera) {
            self.overrides.camera = None;
        }
        if reload.has(&Change::Sun) {
            self.overrides.sun = None;
        }
        if reload.has(&Change::Exposure) {
            self.overrides.exposure = None;
        }
    }
}
