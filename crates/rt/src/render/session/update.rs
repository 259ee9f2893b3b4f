//! Bringing a session to new state (a scene edited, assets re-packed, shaders
//! re-read): everything that can fail happens before anything is replaced.

use super::Session;
use crate::bvh::SceneGeometry;
use crate::gpu::shader::{Program, ShaderFiles};
use crate::scene::{Atmosphere, FeatureSet, RenderSettings, Scene, Sky};
use crate::sky::{AtmosphereTables, EnvironmentMap};
use anyhow::{Result, bail};

/// New state for a session, all applied or none.
pub struct SceneUpdate {
    /// The scene as it now renders.
    pub scene: Scene,
    pub geometry: Option<GeometryUpdate>,
    /// Read the shaders from here from now on.
    pub shaders: Option<ShaderFiles>,
}

pub enum GeometryUpdate {
    /// Assets or their placement changed: every geometry buffer is replaced.
    Replace(SceneGeometry),
    /// Only materials changed: the material and emitter tables are uploaded.
    Materials(SceneGeometry),
}

impl Session<'_> {
    /// Takes new atmosphere parameters: the tables are rebuilt only if they depend on
    /// what changed (the sun may move freely: nothing in them depends on it). Returns
    /// whether they were.
    pub fn set_atmosphere(&mut self, params: &Atmosphere) -> Result<bool> {
        let Some(tables) = self.sky.as_mut() else {
            bail!("{}: the sky is not an atmosphere", self.scene.origin);
        };
        let rebuilt = tables.update(self.ctx, &self.pipelines.sky_layout, params)?;
        self.buffers.sky_bind_group = Some(tables.bind_group.clone());
        self.scene.sky = Sky::Atmosphere(params.clone());
        Ok(rebuilt)
    }

    /// Takes a new sky of any kind: an atmosphere's tables are built or updated,
    /// another kind drops them.
    pub(super) fn set_sky(&mut self, sky: &Sky) -> Result<()> {
        match sky {
            Sky::Atmosphere(params) if self.sky.is_some() => {
                self.set_atmosphere(params)?;
            }
            Sky::Atmosphere(params) => {
                let tables = AtmosphereTables::new(self.ctx, &self.pipelines.sky_layout, params)?;
                self.buffers.sky_bind_group = Some(tables.bind_group.clone());
                self.sky = Some(tables);
                self.environment = None;
            }
            Sky::Environment(params) => {
                // The same image with other constants is not read again.
                match self.environment.as_mut() {
                    Some(map)
                        if map.params().image == params.image && map.params().rotation_deg == params.rotation_deg =>
                    {
                        map.set_constants(self.ctx, params);
                    }
                    _ => self.environment = Some(EnvironmentMap::new(self.ctx, &self.pipelines.sky_layout, params)?),
                }
                self.buffers.sky_bind_group = self.environment.as_ref().map(|m| m.bind_group.clone());
                self.sky = None;
            }
            _ => {
                self.sky = None;
                self.environment = None;
                self.buffers.sky_bind_group = None;
            }
        }
        self.scene.sky = sky.clone();
        Ok(())
    }

    /// Brings the session to `update`. Everything that can fail (shaders, pipelines,
    /// the atmosphere's tables) happens before anything is replaced, so on an error the
    /// last good state keeps rendering. Returns whether the samples so far were dropped.
    pub fn apply(&mut self, update: SceneUpdate) -> Result<bool> {
        let SceneUpdate { scene, geometry, shaders } = update;
        let reshaded = shaders.is_some();
        if let Some(files) = shaders {
            self.pipelines.reload_shaders(self.ctx, files)?;
        }
        let summary = match &geometry {
            Some(GeometryUpdate::Replace(g) | GeometryUpdate::Materials(g)) => {
                self.pipelines.learn_node_code(g);
                g.summary()
            }
            None => self.geometry.summary(),
        };
        let features = FeatureSet::analyse(&scene, &summary);
        self.pipelines.get(self.ctx, Program::Integrator, features)?;
        if scene.sky != self.scene.sky {
            self.set_sky(&scene.sky)?;
        }
        let regeometry = geometry.is_some();
        match geometry {
            Some(GeometryUpdate::Replace(g)) => {
                self.buffers.replace_geometry(self.ctx, &g, &self.pipelines.scene_layout)?;
                self.geometry = g;
            }
            Some(GeometryUpdate::Materials(g)) => {
                self.buffers.replace_materials(self.ctx, &g, &self.pipelines.scene_layout);
                self.geometry = g;
            }
            None => {}
        }
        self.pipelines.keep_node_code(self.geometry.node_code);
        let reset = reshaded || regeometry || features != self.features || !same_image(&scene, &self.scene);
        self.scene = scene;
        self.features = features;
        self.share_light_samples();
        if reset {
            self.reset();
        }
        Ok(reset)
    }
}

impl Session<'_> {
    /// Gives the environment its share of light samples beside the scene's other lights.
    pub(super) fn share_light_samples(&mut self) {
        let others = self.scene.sun.is_some() || !self.scene.lights.is_empty() || !self.geometry.emitters.is_empty();
        if let Some(map) = self.environment.as_mut() {
            map.set_other_lights(self.ctx, others);
        }
    }
}

/// Whether two scenes render the same image (the exposure only changes its display).
fn same_image(a: &Scene, b: &Scene) -> bool {
    let unexposed = |s: &Scene| Scene { render: RenderSettings { exposure: 0.0, ..s.render.clone() }, ..s.clone() };
    unexposed(a) == unexposed(b)
}
