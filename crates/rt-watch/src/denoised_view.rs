//! `rt watch --denoise`'s window: the running mean denoised by Open Image Denoise on the
//! schedule of [`super::denoise_schedule`], on a thread of its own
//! ([`super::denoise_worker`]): refinement never waits for it, and the last denoised image
//! of the accumulation refining now is shown until the next is ready.

use super::denoise_worker::{DenoiseWorker, Denoised, Finished};
use rt::denoise::Denoiser;
use rt::gpu::GpuContext;
use rt::render::Session;

pub struct DenoisedView {
    worker: DenoiseWorker,
    /// The last denoised image kept, as the display reads means (RGB and a spare word).
    buffer: Option<(wgpu::Buffer, u32, u32)>,
    /// Toggled by `N`: whether the window shows the denoised image.
    pub shown: bool,
}

impl DenoisedView {
    pub fn new(denoiser: Denoiser) -> Self {
        Self { worker: DenoiseWorker::start(denoiser), buffer: None, shown: true }
    }

    /// Takes a finished denoise and starts the next when one is due; to be called once
    /// the frame's samples are on the GPU, so that the image sent has the samples it says.
    /// The denoiser's failure is an error, once: the view is then to be dropped.
    pub fn update(&mut self, ctx: &GpuContext, session: &Session) -> anyhow::Result<()> {
        if let Some(Finished::Kept(done)) = self.worker.poll(session.restarts())? {
            self.upload(ctx, &done);
        }
        if self.shown && self.worker.due(session.samples(), session.converged()) {
            self.worker.send(session.image()?, session.aovs()?);
        }
        Ok(())
    }

    /// Whether a denoise is running or due: the window keeps drawing to show it.
    pub fn pending(&self, session: &Session) -> bool {
        let schedule = self.worker.schedule();
        self.shown && (schedule.busy() || schedule.due(session.samples(), session.converged()))
    }

    /// Whether the image shown is the denoise of the session's image as it is now (a
    /// converged state's frame waits for it).
    pub fn up_to_date(&self, session: &Session) -> bool {
        let latest = self.worker.schedule().latest();
        self.means(session).is_some() && latest.is_some_and(|s| s.samples == session.samples())
    }

    fn upload(&mut self, ctx: &GpuContext, done: &Denoised) {
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
        }
    }

    /// The denoised image to show instead of the running mean: when it is shown, and
    /// there is one of the session's accumulation (not of the state before a reload or
    /// a camera move, even before the next update) at its size.
    pub fn means(&self, session: &Session) -> Option<&wgpu::Buffer> {
        let acc = session.accumulation();
        let current = self.worker.schedule().latest().is_some_and(|s| s.accumulation == session.restarts());
        match &self.buffer {
            Some((buffer, w, h)) if self.shown && current && (*w, *h) == (acc.width, acc.height) => Some(buffer),
            _ => None,
        }
    }
}
