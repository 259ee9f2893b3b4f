//! `rt watch --headless --denoise`: the window's denoising schedule run between
//! headless dispatches (each denoise logged as `denoise #N spp=S ms=T refined_to=R`,
//! R being the samples refinement had reached when it came back), and the denoise of
//! each converged state, which its frame is written from.

use super::denoise_schedule::Stamp;
use super::denoise_worker::{DenoiseWorker, Denoised, Finished};
use super::reload_log::ReloadLog;
use anyhow::{Result, bail};
use rt::denoise::Denoiser;
use rt::gpu::ms;
use rt::render::Session;
use std::time::Duration;

/// How long a converged state waits for its denoise between looks at the denoiser.
const WAIT: Duration = Duration::from_millis(200);

pub struct HeadlessDenoise {
    worker: DenoiseWorker,
    /// The last denoise kept.
    latest: Option<Denoised>,
}

impl HeadlessDenoise {
    pub fn new(denoiser: Denoiser) -> Self {
        Self { worker: DenoiseWorker::start(denoiser), latest: None }
    }

    /// After a dispatch of state `number`: logs a denoise that came back and sends the
    /// next image when one is due, without waiting for the denoiser.
    pub fn refine(&mut self, session: &Session, number: u32, log: &mut ReloadLog) -> Result<()> {
        let finished = self.worker.poll(session.restarts());
        self.take(finished, session, number, log)?;
        if self.worker.due(session.samples(), session.converged()) {
            self.worker.send(session.image()?, session.aovs()?);
        }
        Ok(())
    }

    /// The denoise of the converged image of state `number`: the denoise running is
    /// waited for, then the converged image denoised unless it was already.
    pub fn converged(&mut self, session: &Session, number: u32, log: &mut ReloadLog) -> Result<Vec<[f32; 3]>> {
        let wanted = Stamp { accumulation: session.restarts(), samples: session.samples() };
        loop {
            if let Some(done) = self.latest.take_if(|d| d.stamp == wanted) {
                return Ok(done.pixels);
            }
            if self.worker.due(wanted.samples, true) {
                self.worker.send(session.image()?, session.aovs()?);
            }
            if !self.worker.schedule().busy() {
                bail!("internal error: no denoise of the converged image ({} spp) is on its way", wanted.samples);
            }
            let finished = self.worker.wait(WAIT);
            self.take(finished, session, number, log)?;
        }
    }

    fn take(
        &mut self,
        finished: Result<Option<Finished>>,
        session: &Session,
        number: u32,
        log: &mut ReloadLog,
    ) -> Result<()> {
        match finished {
            Ok(Some(Finished::Kept(done))) => {
                let (spp, took) = (done.stamp.samples, ms(done.took));
                log.write(&format!("denoise #{number} spp={spp} ms={took:.1} refined_to={}", session.samples()));
                self.latest = Some(done);
            }
            Ok(Some(Finished::Dropped(stamp))) => {
                log.write(&format!("denoise dropped spp={}: the scene changed while it was denoised", stamp.samples))
            }
            Ok(None) => {}
            Err(e) => {
                // Frames asked for denoised are not written raw in their place.
                log.write(&format!("{e:#}; rt watch --headless --denoise stops"));
                return Err(e);
            }
        }
        Ok(())
    }
}
