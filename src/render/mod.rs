//! Headless rendering: from a scene to an image, progressively, on the GPU.

mod camera;
mod image_out;
mod progressive;
mod sentinel;
mod sun;
pub mod tonemap;
mod trace;

pub use camera::set_camera;
pub use image_out::{ImageFormat, check_output, image_format, write_image, write_png};
pub use progressive::{Accumulation, MAX_SAMPLES_PER_DISPATCH};
pub use sentinel::{NonFiniteCause, Sentinel};
pub use sun::{default_sun_radiance, sun_direction, sun_one_minus_cos};
pub use trace::TraceBuffers;

use crate::bvh::{BuildQuality, SceneGeometry};
use crate::gpu::layout::GpuFrame;
use crate::gpu::shader::Program;
use crate::gpu::{GpuContext, PipelineCache, SceneBuffers};
use crate::scene::{FeatureSet, Scene, Sky};
use crate::sky::AtmosphereTables;
use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use std::time::{Duration, Instant};

/// Mean radiance per pixel (linear, rows from the top), with the standard
/// error of each pixel's luminance.
#[derive(Clone, Debug)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub samples: u32,
    pub pixels: Vec<[f32; 3]>,
    pub std_error: Vec<f32>,
}

/// What `rt render` was asked for; the scene's `[render]` gives the defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderRequest {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub max_bounces: u32,
    pub seed: u32,
    /// Candidates per resampled direction in `seed` sampling.
    pub ris_candidates: u32,
    /// Scale samples down to this luminance (biased; `None`: off).
    pub clamp: Option<f32>,
    /// Run this feature set's pipeline instead of the scene's own (it must include it).
    pub features: Option<FeatureSet>,
    /// Samples per pixel in each GPU dispatch; `None`: as many as keep a dispatch near 80 ms.
    pub samples_per_dispatch: Option<u32>,
    pub progress: bool,
}

impl RenderRequest {
    pub fn from_scene(scene: &Scene) -> Self {
        let r = &scene.render;
        Self {
            width: r.width,
            height: r.height,
            spp: r.spp,
            max_bounces: r.max_bounces,
            seed: 0,
            ris_candidates: r.ris_candidates,
            clamp: None,
            features: None,
            samples_per_dispatch: None,
            progress: false,
        }
    }
}

#[derive(Clone, Debug)]
pub struct RenderReport {
    pub samples_per_pixel: u32,
    pub elapsed: Duration,
    /// Camera paths per second.
    pub samples_per_second: f64,
    pub sentinel: Sentinel,
    pub features: FeatureSet,
}

/// A scene on the GPU, ready to render any number of times.
pub struct Renderer<'a> {
    pub ctx: &'a GpuContext,
    pub scene: Scene,
    pub geometry: SceneGeometry,
    pub buffers: SceneBuffers,
    pub pipelines: PipelineCache,
    /// The atmosphere's parameters and tables, when the sky is one.
    pub sky: Option<AtmosphereTables>,
}

impl<'a> Renderer<'a> {
    pub fn new(ctx: &'a GpuContext, scene: Scene, quality: BuildQuality) -> Result<Self> {
        let geometry = SceneGeometry::build(&scene, quality)?;
        Self::with_geometry(ctx, scene, geometry)
    }

    /// A renderer for `scene` placed as `geometry` (which must have been built from it).
    pub fn with_geometry(ctx: &'a GpuContext, scene: Scene, geometry: SceneGeometry) -> Result<Self> {
        let pipelines = PipelineCache::new(ctx);
        let buffers = SceneBuffers::new(ctx, &geometry, &pipelines.scene_layout)?;
        if matches!(scene.sky, Sky::Atmosphere(_)) && scene.sun.is_none() {
            log::warn!("{}: the atmosphere has no [sun] to light it: only its extinction shows", scene.origin);
        }
        let sky = scene.sky.clone();
        let mut renderer = Self { ctx, scene, geometry, buffers, pipelines, sky: None };
        renderer.set_sky(&sky)?;
        Ok(renderer)
    }

    /// Takes new atmosphere parameters: the tables are rebuilt only if they
    /// depend on what changed (the sun may move freely: nothing in them depends
    /// on it). Returns whether they were.
    pub fn set_atmosphere(&mut self, params: &crate::scene::Atmosphere) -> Result<bool> {
        let Some(tables) = self.sky.as_mut() else {
            anyhow::bail!("{}: the sky is not an atmosphere", self.scene.origin);
        };
        let rebuilt = tables.update(self.ctx, &self.pipelines.sky_layout, params)?;
        self.buffers.sky_bind_group = Some(tables.bind_group.clone());
        self.scene.sky = Sky::Atmosphere(params.clone());
        Ok(rebuilt)
    }

    /// Takes a new sky of any kind: an atmosphere's tables are built or updated,
    /// another kind drops them. The frame constants follow `self.scene.sky`.
    pub fn set_sky(&mut self, sky: &Sky) -> Result<()> {
        match sky {
            Sky::Atmosphere(params) if self.sky.is_some() => {
                self.set_atmosphere(params)?;
            }
            Sky::Atmosphere(params) => {
                let tables = AtmosphereTables::new(self.ctx, &self.pipelines.sky_layout, params)?;
                self.buffers.sky_bind_group = Some(tables.bind_group.clone());
                self.sky = Some(tables);
            }
            _ => {
                self.sky = None;
                self.buffers.sky_bind_group = None;
            }
        }
        self.scene.sky = sky.clone();
        Ok(())
    }

    /// The frame constants of a request, before per-dispatch fields.
    pub fn frame(&self, request: &RenderRequest) -> GpuFrame {
        let mut frame = GpuFrame {
            max_bounces: request.max_bounces,
            seed: request.seed,
            tlas_root: self.geometry.tlas_root,
            ..Default::default()
        };
        set_camera(&mut frame, &self.scene.camera, request.width, request.height);
        if let Sky::Uniform { color } = self.scene.sky {
            frame.sky_color = color.to_array();
        }
        sun::set_sun(&mut frame, self.scene.sun.as_ref(), !self.geometry.emitters.is_empty());
        frame.emitter_count = self.geometry.emitters.len() as u32;
        frame.emitter_total_power = self.geometry.emitter_total_power;
        frame.ris_candidates = request.ris_candidates;
        frame.clamp_luminance = request.clamp.unwrap_or(0.0);
        frame
    }

    pub fn render(&mut self, request: &RenderRequest) -> Result<(Image, RenderReport)> {
        let features = request.features.unwrap_or(self.geometry.features);
        let pipelines = self.pipelines.get(self.ctx, Program::Integrator, features)?;
        let frame = self.frame(request);
        let mut acc = Accumulation::new(self.ctx, &self.pipelines.accumulation_layout, request.width, request.height);
        if let Some(n) = request.samples_per_dispatch {
            acc.fix_samples_per_dispatch(n);
        }
        self.buffers.take_stats(self.ctx)?;
        let bar = if request.progress { ProgressBar::new(request.spp as u64) } else { ProgressBar::hidden() };
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} spp  {msg}  ETA {eta}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        let start = Instant::now();
        let pixels = request.width as f64 * request.height as f64;
        while acc.samples < request.spp {
            acc.dispatch(self.ctx, &pipelines, &self.buffers, &frame, request.spp - acc.samples)?;
            let rate = acc.samples as f64 * pixels / start.elapsed().as_secs_f64();
            bar.set_position(acc.samples as u64);
            bar.set_message(format!("{} samples/s", human(rate)));
        }
        bar.finish_and_clear();
        let elapsed = start.elapsed();
        let stats = self.buffers.take_stats(self.ctx)?;
        let image = acc.image(self.ctx)?;
        let report = RenderReport {
            samples_per_pixel: acc.samples,
            elapsed,
            samples_per_second: acc.samples as f64 * pixels / elapsed.as_secs_f64(),
            sentinel: Sentinel::from_pixels(&acc.non_finite(self.ctx)?, stats[crate::gpu::STAT_STACK_OVERFLOW]),
            features,
        };
        Ok((image, report))
    }
}

/// 12.3 M, 4.56 G: rates at a glance.
pub fn human(v: f64) -> String {
    let (scale, unit) = match v {
        v if v >= 1e9 => (1e9, " G"),
        v if v >= 1e6 => (1e6, " M"),
        v if v >= 1e3 => (1e3, " k"),
        _ => (1.0, " "),
    };
    format!("{:.3}{unit}", v / scale).replace("  ", " ")
}
