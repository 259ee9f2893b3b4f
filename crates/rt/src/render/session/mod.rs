//! The render session: a scene on the GPU (geometry, buffers, pipelines, sky tables),
//! the accumulation its samples go to and the one controller of dispatch sizes.
//! `rt render` steps it to its spp, `rt watch` applies edits to it and steps it frame
//! by frame, `rt bench` steps it under a timer. The watcher decides what to redo; the
//! session does it.

mod update;

pub use update::{GeometryUpdate, SceneUpdate};

use super::accumulation::{Accumulation, Outputs, check_image_size};
use super::dropped::DroppedSamples;
use super::exact::ExactSums;
use super::pacing::{DispatchSizer, Pacing};
use super::progress::ProgressReporter;
use super::{Aovs, Image, RenderRequest, camera, sun};
use crate::bvh::{BuildQuality, SceneGeometry};
use crate::gpu::shader::Program;
use crate::gpu::{GpuContext, GpuTimer, PipelineCache, Pipelines, Readback, STAT_STACK_OVERFLOW, SceneBuffers};
use crate::layout::GpuFrame;
use crate::scene::{FeatureSet, Scene, Sky};
use crate::sky::{AtmosphereTables, EnvironmentMap};
use anyhow::Result;
use std::rc::Rc;
use std::time::{Duration, Instant};

/// What one finished render did.
#[derive(Clone, Debug)]
pub struct RenderReport {
    pub samples_per_pixel: u32,
    /// Wall-clock time of the whole render.
    pub elapsed: Duration,
    /// The dispatches' own time: the GPU's, with a timer that has timestamp queries.
    pub dispatch_time: Duration,
    /// Camera paths per second.
    pub samples_per_second: f64,
    pub dropped: DroppedSamples,
    pub features: FeatureSet,
    /// The most invocations any dispatch spread a pixel's samples over (1: one per pixel).
    pub max_lanes: u32,
}

/// One dispatch: how many samples per pixel it added and how long it took.
#[derive(Clone, Copy, Debug, Default)]
pub struct Step {
    pub samples: u32,
    pub took: Duration,
    /// Invocations each pixel's samples were spread over.
    pub lanes: u32,
}

pub struct Session<'a> {
    ctx: &'a GpuContext,
    scene: Scene,
    geometry: SceneGeometry,
    features: FeatureSet,
    buffers: SceneBuffers,
    pipelines: PipelineCache,
    /// The atmosphere's parameters and tables, when the sky is one.
    sky: Option<AtmosphereTables>,
    /// The environment image, when the sky is one.
    environment: Option<EnvironmentMap>,
    request: RenderRequest,
    acc: Accumulation,
    sizer: DispatchSizer,
    last_step: Step,
    /// Lanes of the dispatch last encoded.
    encoded_lanes: u32,
    readback: Readback,
    /// How many times the samples were dropped: what a copy of the image was taken from.
    restarts: u64,
}

impl<'a> Session<'a> {
    pub fn open(ctx: &'a GpuContext, scene: Scene, quality: BuildQuality) -> Result<Self> {
        let geometry = SceneGeometry::build(&scene, quality)?;
        Self::with_geometry(ctx, scene, geometry)
    }

    /// A session for `scene` placed as `geometry` (which must have been built from it).
    pub fn with_geometry(ctx: &'a GpuContext, scene: Scene, geometry: SceneGeometry) -> Result<Self> {
        Self::with_pipelines(ctx, scene, geometry, PipelineCache::new(ctx))
    }

    /// A session for `scene` placed as `geometry`, keeping the pipelines another session of
    /// the same device built (the frames of an animation).
    pub fn with_pipelines(
        ctx: &'a GpuContext,
        scene: Scene,
        geometry: SceneGeometry,
        mut pipelines: PipelineCache,
    ) -> Result<Self> {
        pipelines.learn_node_code(&geometry);
        let features = FeatureSet::analyse(&scene, &geometry.summary());
        let request = with_alpha_counted(RenderRequest::from_scene(&scene), features);
        let mut acc = Accumulation::new(ctx, &pipelines.accumulation_layout, request.width, request.height)?;
        acc.prepare_outputs(ctx, &pipelines.accumulation_layout, outputs(&request));
        let buffers = SceneBuffers::new(ctx, &geometry, &pipelines.scene_layout)?;
        if matches!(scene.sky, Sky::Atmosphere(_)) && scene.sun.is_none() {
            log::warn!("{}: the atmosphere has no [sun] to light it: only its extinction shows", scene.origin);
        }
        let sky = scene.sky.clone();
        let mut session = Self {
            ctx,
            scene,
            geometry,
            features,
            buffers,
            pipelines,
            sky: None,
            environment: None,
            request,
            acc,
            sizer: DispatchSizer::new(Pacing::RENDER),
            last_step: Step::default(),
            encoded_lanes: 1,
            readback: Readback::new(),
            restarts: 0,
        };
        session.set_sky(&sky)?;
        session.share_light_samples();
        Ok(session)
    }

    pub fn ctx(&self) -> &'a GpuContext {
        self.ctx
    }

    /// The scene as it renders.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    pub fn geometry(&self) -> &SceneGeometry {
        &self.geometry
    }

    /// The effects the scene needs: the pipeline that runs unless a request names another.
    pub fn features(&self) -> FeatureSet {
        self.features
    }

    pub fn atmosphere(&self) -> Option<&AtmosphereTables> {
        self.sky.as_ref()
    }

    pub fn buffers(&self) -> &SceneBuffers {
        &self.buffers
    }

    pub fn pipeline_cache(&self) -> &PipelineCache {
        &self.pipelines
    }

    /// The pipelines built so far, for the next session of the same device.
    pub fn into_pipelines(self) -> PipelineCache {
        self.pipelines
    }

    pub(super) fn pipelines_mut(&mut self) -> &mut PipelineCache {
        &mut self.pipelines
    }

    pub fn request(&self) -> &RenderRequest {
        &self.request
    }

    pub fn accumulation(&self) -> &Accumulation {
        &self.acc
    }

    /// Samples per pixel taken since the last reset.
    pub fn samples(&self) -> u32 {
        self.acc.samples
    }

    /// How many times the accumulation started afresh: an image read back with the same
    /// count belongs to the accumulation still refining, one with a lower count to an
    /// older state (another camera, scene or size), whatever their samples.
    pub fn restarts(&self) -> u64 {
        self.restarts
    }

    pub fn converged(&self) -> bool {
        self.acc.samples >= self.request.spp
    }

    /// The last dispatch.
    pub fn last_step(&self) -> Step {
        self.last_step
    }

    /// How long dispatches should take: `rt watch` aims at its frame time.
    pub fn set_pacing(&mut self, pacing: Pacing) {
        self.sizer.set_pacing(pacing);
    }

    /// Renders `request` from now on. Returns whether the samples taken so far were
    /// dropped (anything but the spp and the dispatch sizes changed). An image larger
    /// than the GPU can hold is refused and nothing changes.
    pub fn set_request(&mut self, request: &RenderRequest) -> Result<bool> {
        let request = &with_alpha_counted(request.clone(), self.features);
        let resized = (request.width, request.height) != (self.acc.width, self.acc.height);
        if resized {
            self.acc = Accumulation::new(self.ctx, &self.pipelines.accumulation_layout, request.width, request.height)?;
        }
        self.acc.prepare_outputs(self.ctx, &self.pipelines.accumulation_layout, outputs(request));
        let reset = resized || !self.request.same_image(request);
        self.sizer.fix(request.samples_per_dispatch);
        self.request = request.clone();
        if reset {
            self.reset();
        }
        Ok(reset)
    }

    /// Refuses an image size the GPU cannot hold, before anything changes.
    pub fn check_image_size(&self, width: u32, height: u32) -> Result<()> {
        check_image_size(self.ctx, width, height)
    }

    /// Drops the samples taken so far; the next dispatch takes one sample, to show the
    /// new state as soon as possible.
    pub fn reset(&mut self) {
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        self.acc.clear(&mut encoder);
        self.ctx.queue.submit([encoder.finish()]);
        self.sizer.restart();
        self.restarts += 1;
    }

    /// The feature set the pipeline runs: the scene's (or the request's) with the
    /// outputs and sampling strategy the request asks for, and the scene's film.
    pub fn pipeline_features(&self) -> FeatureSet {
        let features = self.request.features.unwrap_or(self.features);
        FeatureSet {
            aovs: self.request.aovs,
            adaptive: self.request.adaptive(),
            exact_sums: self.acc.keeps_exact_sums(),
            transparent_film: self.features.transparent_film,
            holdout: features.holdout || self.features.holdout,
            ..features
        }
    }

    fn integrator(&mut self) -> Result<Rc<Pipelines>> {
        let features = self.pipeline_features();
        self.pipelines.get(self.ctx, Program::Integrator, features)
    }

    /// The frame constants of the current request, before per-dispatch fields.
    pub fn frame(&self) -> GpuFrame {
        let request = &self.request;
        let mut frame = GpuFrame {
            max_bounces: request.max_bounces,
            seed: request.seed,
            tlas_root: self.geometry.tlas_root,
            ..Default::default()
        };
        camera::set_camera(&mut frame, &self.scene.camera, request.width, request.height);
        // A sky sampled uniformly as a light shares the light samples with the other lights.
        let other_lights =
            !self.geometry.emitters.is_empty() || self.scene.sun.is_some() || !self.scene.lights.is_empty();
        match &self.scene.sky {
            Sky::Uniform { color, sample_as_light } => {
                frame.sky_color = color.to_array();
                let emits = *sample_as_light && color.max_element() > 0.0;
                frame.sky_light_share = crate::sky::light_share(emits, other_lights);
            }
            Sky::Graph(world) => frame.sky_light_share = crate::sky::light_share(world.sample_as_light, other_lights),
            _ => {}
        }
        sun::set_sun(&mut frame, self.scene.sun.as_ref(), !self.geometry.emitters.is_empty());
        frame.emitter_count = self.geometry.emitters.len() as u32;
        frame.emitter_total_power = self.geometry.emitter_total_power;
        frame.ris_candidates = request.ris_candidates;
        frame.clamp_luminance = request.clamp.unwrap_or(0.0);
        frame.noise_threshold = request.noise_threshold;
        frame.adaptive_min_samples = request.adaptive_min_samples;
        frame.transparent_glass = self.scene.render.transparent_glass_alpha();
        frame.first_sample = request.first_sample;
        frame
    }

    /// Records the next dispatch into `encoder` (none once converged) and returns its
    /// samples per pixel; the caller submits it and reports its time to [`Self::observe`].
    pub fn encode_step(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites>,
    ) -> Result<u32> {
        if self.converged() {
            return Ok(0);
        }
        let pipelines = self.integrator()?;
        let remaining = self.request.spp - self.acc.samples;
        let n = self.sizer.next(remaining);
        let mut lanes = self.acc.lanes(n, self.request.sample_lanes);
        if lanes > 1 {
            self.acc.prepare_lanes(self.ctx, &self.pipelines.accumulation_layout, self.request.aovs);
        }
        let n = n.min(self.acc.max_samples(lanes, self.request.aovs));
        if n <= 1 {
            // One sample per pixel needs no lanes (and an image too large for the
            // scratch gets none).
            lanes = 1;
        }
        let n = n.max(1);
        let frame = GpuFrame { samples_per_dispatch: n, ..self.frame() };
        self.acc.encode(self.ctx, encoder, &pipelines, &self.buffers, &frame, lanes, timestamp_writes);
        self.encoded_lanes = lanes;
        Ok(n)
    }

    /// How long a dispatch of `samples` took: the next one's size follows it.
    pub fn observe(&mut self, samples: u32, took: Duration) {
        self.sizer.observe(samples, took);
        self.last_step = Step { samples, took, lanes: self.encoded_lanes };
    }

    /// One dispatch towards the request's spp, waited for. Its time is the GPU's with a
    /// timer that has timestamp queries, else the wall-clock time until it finished.
    pub fn step(&mut self, timer: Option<&GpuTimer>) -> Result<Step> {
        let start = Instant::now();
        let (samples, took) = match timer {
            Some(timer) => {
                let ctx = self.ctx;
                let mut samples = Ok(0);
                let took = timer.time(ctx, |e, w| samples = self.encode_step(e, w))?;
                (samples?, took)
            }
            None => {
                let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
                let samples = self.encode_step(&mut encoder, None)?;
                self.ctx.queue.submit([encoder.finish()]);
                self.ctx.wait()?;
                (samples, start.elapsed())
            }
        };
        // Sizes follow the wall clock: it is what a watchdog and a window see.
        self.sizer.observe(samples, start.elapsed());
        self.last_step = Step { samples, took, lanes: self.encoded_lanes };
        Ok(self.last_step)
    }

    /// Renders `request` from no samples to its spp, showing its progress as it asks.
    pub fn render(&mut self, request: &RenderRequest, timer: Option<&GpuTimer>) -> Result<(Image, RenderReport)> {
        self.render_with(request, timer, None, |_| Ok(()))
    }

    /// [`Self::render`], stopping at `time_limit` (after at least one sample) with the
    /// samples taken so far, and calling `after_step` after each dispatch (to show or
    /// save the image so far).
    pub fn render_with(
        &mut self,
        request: &RenderRequest,
        timer: Option<&GpuTimer>,
        time_limit: Option<Duration>,
        mut after_step: impl FnMut(&Self) -> Result<()>,
    ) -> Result<(Image, RenderReport)> {
        self.set_request(request)?;
        self.reset();
        self.buffers.take_stats(self.ctx)?;
        let mut progress = ProgressReporter::new(request.progress, request.spp);
        let start = Instant::now();
        let pixels = request.width as f64 * request.height as f64;
        let mut dispatch_time = Duration::ZERO;
        let mut max_lanes = 1;
        while !self.converged() {
            let step = self.step(timer)?;
            dispatch_time += step.took;
            max_lanes = max_lanes.max(step.lanes);
            let rate = self.acc.samples as f64 * pixels / start.elapsed().as_secs_f64();
            progress.update(self.acc.samples, start.elapsed(), rate);
            after_step(self)?;
            if time_limit.is_some_and(|limit| start.elapsed() >= limit) {
                break;
            }
        }
        progress.finish();
        let elapsed = start.elapsed();
        let report = RenderReport {
            samples_per_pixel: self.acc.samples,
            elapsed,
            dispatch_time,
            samples_per_second: self.acc.samples as f64 * pixels / elapsed.as_secs_f64(),
            dropped: self.dropped()?,
            features: self.pipeline_features(),
            max_lanes,
        };
        Ok((self.image()?, report))
    }

    /// The mean radiance per pixel so far, with each pixel's standard error, and with a
    /// transparent film or holdouts (and AOVs, which count what the samples cover) its alpha.
    pub fn image(&self) -> Result<Image> {
        if let Some(sums) = self.exact_sums()? {
            return Ok(sums.image(self.acc.samples, self.features.has_alpha()));
        }
        let mut image = self.acc.image(self.ctx, &self.readback, self.request.adaptive())?;
        if self.features.has_alpha() && self.request.aovs {
            let means = self.acc.aov_means(self.ctx, &self.readback)?;
            image.alpha = Some(Aovs::coverage(&means, &image.sample_counts));
        }
        Ok(image)
    }

    /// The AOVs so far; an error unless the request asked for them.
    pub fn aovs(&self) -> Result<Aovs> {
        if !self.request.aovs {
            anyhow::bail!("the render did not ask for AOVs");
        }
        if let Some(aovs) = self.exact_sums()?.and_then(|sums| sums.aovs()) {
            return Ok(aovs);
        }
        let means = self.acc.aov_means(self.ctx, &self.readback)?;
        Ok(Aovs::from_means(self.acc.width, self.acc.height, &means))
    }

    /// The exact sums of the samples so far, where the request asked for them.
    pub fn exact_sums(&self) -> Result<Option<ExactSums>> {
        if !self.acc.keeps_exact_sums() {
            return Ok(None);
        }
        let words = self.acc.exact_words(self.ctx, &self.readback)?;
        let taken = self.acc.taken(self.ctx, &self.readback, self.request.adaptive())?;
        let dropped = self.acc.non_finite(self.ctx, &self.readback)?.iter().map(|(n, _)| *n).collect();
        let (width, height) = (self.acc.width, self.acc.height);
        Ok(Some(ExactSums::from_words(width, height, self.request.aovs, &words, taken, dropped)))
    }

    /// What was dropped since the last reset; the stack-overflow counter starts again.
    pub fn dropped(&mut self) -> Result<DroppedSamples> {
        let stats = self.buffers.take_stats(self.ctx)?;
        let per_pixel = self.acc.non_finite(self.ctx, &self.readback)?;
        Ok(DroppedSamples::from_pixels(&per_pixel, stats[STAT_STACK_OVERFLOW]))
    }
}

/// The outputs beside the means that `request` needs.
fn outputs(request: &RenderRequest) -> Outputs {
    Outputs { aovs: request.aovs, adaptive: request.adaptive(), exact_sums: request.exact_sums }
}

/// `request`, counting the AOVs where the scene's image has an alpha (a transparent film,
/// holdouts): they count what each sample covers.
fn with_alpha_counted(request: RenderRequest, features: FeatureSet) -> RenderRequest {
    RenderRequest { aovs: request.aovs || features.has_alpha(), ..request }
}
