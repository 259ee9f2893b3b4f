//! A scene kept live on the GPU: the last good version read from disk, the viewer's
//! own camera, sun and exposure on top of it, and reloads that do the least work.
//!
//! A reload is all or nothing: everything that can fail (reading the scene, loading
//! assets, building pipelines) happens before anything on the GPU is replaced, so a
//! bad edit leaves the last good scene rendering.

use super::WatchOptions;
use super::plan::{AssetPrints, Change, Reload, plan};
use super::sources::{asset_prints, watched_files};
use anyhow::{Result, bail};
use rt::bvh::{BuildQuality, LoadedMesh, SceneGeometry, asset_paths, pack::load_or_pack};
use rt::gpu::GpuContext;
use rt::gpu::shader::ShaderFiles;
use rt::render::{GeometryUpdate, RenderFlags, RenderRequest, SceneUpdate, Session};
use rt::scene::{self, Camera, FeatureSet, Scene, Sun};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// What the viewer changed on top of the scene file; a change of the same thing in the
/// file wins over it (the artist moved the camera in Blender: show that).
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    pub camera: Option<Camera>,
    pub sun: Option<Sun>,
    pub exposure: Option<f32>,
}

impl Overrides {
    /// These overrides without those of what the file changed.
    fn without(&self, reload: &Reload) -> Self {
        fn keep<T: Clone>(reload: &Reload, change: Change, value: &Option<T>) -> Option<T> {
            if reload.has(&change) { None } else { value.clone() }
        }
        Self {
            camera: keep(reload, Change::Camera, &self.camera),
            sun: keep(reload, Change::Sun, &self.sun),
            exposure: keep(reload, Change::Exposure, &self.exposure),
        }
    }
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
    pub session: Session<'a>,
    pub scene_path: PathBuf,
    /// The last good scene read from the file, without flags or overrides.
    file_scene: Scene,
    assets: AssetPrints,
    /// The command line's settings on top of the file's `[render]`.
    flags: RenderFlags,
    overrides: Overrides,
    /// The window's size, which wins over the scene's and the flags'.
    window_size: Option<(u32, u32)>,
    quality: BuildQuality,
    /// `shaders/` on disk, with `--dev`.
    shader_dir: Option<PathBuf>,
    reloads: u32,
}

impl<'a> LiveScene<'a> {
    pub fn open(ctx: &'a GpuContext, options: &WatchOptions) -> Result<Self> {
        let file_scene = scene::load(&options.scene)?;
        let assets = asset_prints(&file_scene);
        let mut live_scene = file_scene.clone();
        let request = options.flags.apply(&mut live_scene)?;
        let mut session = Session::open(ctx, live_scene, options.quality)?;
        session.set_request(&request)?;
        let mut live = Self {
            session,
            scene_path: options.scene.clone(),
            file_scene,
            assets,
            flags: options.flags.clone(),
            overrides: Overrides::default(),
            window_size: None,
            quality: options.quality,
            shader_dir: options.shader_dir.clone(),
            reloads: 0,
        };
        if let Some(dir) = &live.shader_dir {
            let update = SceneUpdate {
                scene: live.session.scene().clone(),
                geometry: None,
                shaders: Some(ShaderFiles::Dir(dir.clone())),
            };
            live.session.apply(update)?;
        }
        Ok(live)
    }

    /// Every file whose change may change the image.
    pub fn watched_files(&self) -> Vec<PathBuf> {
        watched_files(&self.scene_path, &self.file_scene, self.shader_dir.as_deref())
    }

    pub fn shader_dir(&self) -> Option<&Path> {
        self.shader_dir.as_deref()
    }

    /// The scene as rendered: the file's, with the flags and the overrides applied.
    pub fn scene(&self) -> &Scene {
        self.session.scene()
    }

    pub fn overrides(&self) -> &Overrides {
        &self.overrides
    }

    /// The file's scene with the flags and `overrides` on top, and the request it makes.
    fn rendered(&self, file: &Scene, overrides: &Overrides) -> Result<(Scene, RenderRequest)> {
        let mut scene = file.clone();
        let mut request = self.flags.apply(&mut scene)?;
        if let Some(camera) = &overrides.camera {
            scene.camera = camera.clone();
        }
        // The sun can be turned, not added: without a sun in the file there is none to turn.
        if let (Some(sun), Some(_)) = (&overrides.sun, &scene.sun) {
            scene.sun = Some(sun.clone());
        }
        if let Some(ev) = overrides.exposure {
            scene.render.exposure = ev;
        }
        if let Some((w, h)) = self.window_size {
            (request.width, request.height) = (w, h);
        }
        Ok((scene, request))
    }

    /// Sets the overrides; the session drops its samples if the camera or sun moved.
    pub fn set_overrides(&mut self, overrides: Overrides) -> Result<()> {
        let (scene, request) = self.rendered(&self.file_scene, &overrides)?;
        self.session.apply(SceneUpdate { scene, geometry: None, shaders: None })?;
        self.session.set_request(&request)?;
        self.overrides = overrides;
        Ok(())
    }

    /// Renders at the window's size from now on.
    pub fn set_window_size(&mut self, width: u32, height: u32) -> Result<()> {
        self.window_size = Some((width, height));
        let (_, request) = self.rendered(&self.file_scene, &self.overrides)?;
        self.session.set_request(&request)?;
        Ok(())
    }

    /// Refines each state to `spp` samples per pixel from now on.
    pub fn set_spp(&mut self, spp: u32) -> Result<()> {
        self.flags.spp = Some(spp);
        let (_, request) = self.rendered(&self.file_scene, &self.overrides)?;
        self.session.set_request(&request)?;
        Ok(())
    }

    /// Reads the scene and its assets again after `changed` files changed, and brings the
    /// GPU to them with the least work. On an error nothing changes.
    pub fn reload(&mut self, changed: &[PathBuf]) -> Result<ReloadReport> {
        let start = Instant::now();
        let shaders_changed =
            self.shader_dir.is_some() && changed.iter().any(|p| p.extension().is_some_and(|e| e == "wgsl"));
        let new_file_scene = scene::load(&self.scene_path)?;
        let new_assets = asset_prints(&new_file_scene);
        let reload = plan(&self.file_scene, &new_file_scene, &self.assets, &new_assets, shaders_changed);
        // The message names the asset's file.
        if let Some(Err(message)) = new_assets.values().find(|print| print.is_err()) {
            bail!("{message}");
        }
        let overrides = self.overrides.without(&reload);
        let (scene, request) = self.rendered(&new_file_scene, &overrides)?;
        self.session.check_image_size(request.width, request.height)?;

        let geometry = if reload.reassembles() {
            let geometry = self.assemble(&new_file_scene, &reload)?;
            Some(if reload.replaces_geometry() {
                GeometryUpdate::Replace(geometry)
            } else {
                GeometryUpdate::Materials(geometry)
            })
        } else {
            None
        };
        let shaders = self.shader_dir.clone().filter(|_| shaders_changed).map(ShaderFiles::Dir);
        let old_features = self.session.features();
        self.session.apply(SceneUpdate { scene, geometry, shaders })?;
        self.session.set_request(&request)?;
        self.overrides = overrides;
        let features = self.session.features();
        (self.file_scene, self.assets) = (new_file_scene, new_assets);
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
            let old = self.session.geometry().meshes.iter().find(|m| m.path == path);
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
}
