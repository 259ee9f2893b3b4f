//! Progressive refinement in frames: each frame adds a few samples per pixel to the
//! running mean, as many as fit the frame budget, so a window stays responsive while
//! the image converges. After a reset the first frame takes one sample, to show the
//! new state as soon as possible.

use super::live::LiveScene;
use crate::render::Accumulation;
use anyhow::Result;
use std::time::{Duration, Instant};

const MAX_SAMPLES_PER_FRAME: u32 = 64;

pub struct Refinement {
    pub acc: Accumulation,
    samples_per_frame: u32,
    /// How long a frame's GPU work should take.
    budget: Duration,
    /// Samples per pixel the image stops at.
    pub target_spp: u32,
    /// Samples per second over the last frame, for the window's title.
    pub samples_per_second: f64,
    pub last_frame: Duration,
}

impl Refinement {
    pub fn new(live: &LiveScene, width: u32, height: u32, target_spp: u32, budget: Duration) -> Self {
        let ctx = live.renderer.ctx;
        Self {
            acc: Accumulation::new(ctx, &live.renderer.pipelines.accumulation_layout, width, height),
            samples_per_frame: 1,
            budget,
            target_spp,
            samples_per_second: 0.0,
            last_frame: Duration::ZERO,
        }
    }

    pub fn converged(&self) -> bool {
        self.acc.samples >= self.target_spp
    }

    /// Drops the samples taken so far (recorded into `encoder`).
    pub fn reset(&mut self, encoder: &mut wgpu::CommandEncoder) {
        self.acc.clear(encoder);
        self.samples_per_frame = 1;
    }

    /// A fresh accumulation at a new size.
    pub fn resize(&mut self, live: &LiveScene, width: u32, height: u32) {
        let ctx = live.renderer.ctx;
        self.acc = Accumulation::new(ctx, &live.renderer.pipelines.accumulation_layout, width, height);
        self.samples_per_frame = 1;
    }

    /// Records this frame's samples into `encoder` (none once converged); returns how many.
    pub fn encode(&mut self, live: &mut LiveScene, seed: u32, encoder: &mut wgpu::CommandEncoder) -> Result<u32> {
        if self.converged() {
            return Ok(0);
        }
        let pipelines = live.pipelines()?;
        let request = live.request(self.acc.width, self.acc.height, seed);
        let frame = live.renderer.frame(&request);
        let n = self.samples_per_frame.min(self.target_spp - self.acc.samples);
        let renderer = &live.renderer;
        self.acc.encode(renderer.ctx, encoder, &pipelines, &renderer.buffers, &frame, n, None);
        Ok(n)
    }

    /// Adapts the samples per frame to the time a frame of `samples` took, from the
    /// submission of its work to its end.
    pub fn frame_done(&mut self, samples: u32, submitted: Instant) {
        let took = submitted.elapsed().max(Duration::from_micros(100));
        self.last_frame = took;
        if samples == 0 {
            return;
        }
        let pixels = self.acc.width as f64 * self.acc.height as f64;
        self.samples_per_second = samples as f64 * pixels / took.as_secs_f64();
        // Grow or shrink towards the budget, by at most 2× a frame, so one slow frame cannot overshoot.
        let ratio = (self.budget.as_secs_f64() / took.as_secs_f64()).clamp(0.5, 2.0);
        self.samples_per_frame = ((samples as f64 * ratio) as u32).clamp(1, MAX_SAMPLES_PER_FRAME);
    }
}
