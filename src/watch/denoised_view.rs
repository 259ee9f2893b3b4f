//! `rt watch --denoise`: the window shows the running mean denoised by Open Image
//! Denoise once it has a few samples per pixel, denoised again each time the samples
//! double. Denoising runs on a thread of its own: refinement never waits for it, and
//! the last denoised image is shown until the next is ready.

use crate::denoise::Denoiser;
use crate::gpu::GpuContext;
use crate::render::{Aovs, Image, Session};
use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};

/// Samples per pixel before the first denoised frame: fewer give blotches, not a preview.
const FIRST_DENOISE_SAMPLES: u32 = 4;

struct Job {
    image: Image,
    aovs: Aovs,
    generation: u64,
}

struct Done {
    pixels: Vec<[f32; 3]>,
    width: u32,
    height: u32,
    generation: u64,
}

pub struct DenoisedView {
    jobs: Sender<Job>,
    results: Receiver<Result<Done, String>>,
    /// The last denoised image, as the display reads means (RGB and a spare word).
    buffer: Option<(wgpu::Buffer, u32, u32)>,
    /// Toggled by `N`: whether the window shows the denoised image.
    pub shown: bool,
    busy: bool,
    /// Samples per pixel of the image last sent; 0 since the accumulation restarted.
    sent_samples: u32,
    /// Counts restarts of the accumulation: a result of an older one is dropped.
    generation: u64,
    /// The buffer holds an image of the current accumulation.
    valid: bool,
}

impl DenoisedView {
    /// Starts the denoising thread, which owns `denoiser`.
    pub fn new(mut denoiser: Denoiser) -> Self {
        let (jobs, inbox) = channel::<Job>();
        let (outbox, results) = channel();
        std::thread::spawn(move || {
            for job in inbox {
                let done = denoiser.denoise(&job.image, &job.aovs).map(|pixels| Done {
                    pixels,
                    width: job.image.width,
                    height: job.image.height,
                    generation: job.generation,
                });
                if outbox.send(done.map_err(|e| format!("{e:#}"))).is_err() {
                    return;
                }
            }
        });
        Self { jobs, results, buffer: None, shown: true, busy: false, sent_samples: 0, generation: 0, valid: false }
    }

    /// Takes a finished denoise and starts the next when the samples have doubled. An
    /// error (the device failed) is returned once, and the view stops denoising.
    pub fn update(&mut self, ctx: &GpuContext, session: &Session) -> anyhow::Result<()> {
        let samples = session.samples();
        if samples < self.sent_samples {
            self.generation += 1;
            (self.sent_samples, self.valid) = (0, false);
        }
        match self.results.try_recv() {
            Ok(Ok(done)) => {
                self.busy = false;
                if done.generation == self.generation {
                    self.upload(ctx, &done);
                }
            }
            Ok(Err(message)) => {
                self.shown = false;
                anyhow::bail!("denoising: {message}");
            }
            Err(TryRecvError::Empty) => {}
            Err(TryRecvError::Disconnected) => self.busy = true,
        }
        let due = samples >= FIRST_DENOISE_SAMPLES.max(2 * self.sent_samples)
            || (session.converged() && samples > self.sent_samples);
        if self.shown && !self.busy && due {
            let job = Job { image: session.image()?, aovs: session.aovs()?, generation: self.generation };
            self.sent_samples = samples;
            self.busy = self.jobs.send(job).is_ok();
        }
        Ok(())
    }

    fn upload(&mut self, ctx: &GpuContext, done: &Done) {
        let size = done.pixels.len() as u64 * 16;
        if !matches!(&self.buffer, Some((b, w, h)) if b.size() == size && (*w, *h) == (done.width, done.height)) {
            let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("denoised"),
                size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            self.buffer = Some((buffer, done.width, done.height));
        }
        if let Some((buffer, _, _)) = &self.buffer {
            let means: Vec<[f32; 4]> = done.pixels.iter().map(|p| [p[0], p[1], p[2], 0.0]).collect();
            ctx.queue.write_buffer(buffer, 0, bytemuck::cast_slice(&means));
            self.valid = true;
        }
    }

    /// The denoised image to show instead of the running mean, if it is shown and ready
    /// for an image of this size.
    pub fn means(&self, width: u32, height: u32) -> Option<&wgpu::Buffer> {
        match &self.buffer {
            Some((buffer, w, h)) if self.shown && self.valid && (*w, *h) == (width, height) => Some(buffer),
            _ => None,
        }
    }
}
