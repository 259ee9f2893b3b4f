//! `rt watch --denoise`'s denoiser on a thread of its own, driven by a
//! [`DenoiseSchedule`]: refinement hands it an image when one is due and looks for the
//! result between frames, never waiting for it. A failure of the denoiser is reported
//! once, and nothing is denoised after it.

use super::denoise_schedule::{DenoiseSchedule, Stamp};
use anyhow::{Result, anyhow};
use rt::denoise::Denoiser;
use rt::render::{Aovs, Image};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, TryRecvError, channel};
use std::time::{Duration, Instant};

/// What denoises: Open Image Denoise, or a stand-in in tests.
pub trait Denoise: Send + 'static {
    /// The denoised radiance of `image`, guided by `aovs`.
    fn denoise(&mut self, image: &Image, aovs: &Aovs) -> Result<Vec<[f32; 3]>>;
}

impl Denoise for Denoiser {
    fn denoise(&mut self, image: &Image, aovs: &Aovs) -> Result<Vec<[f32; 3]>> {
        Denoiser::denoise(self, image, aovs)
    }
}

struct Job {
    image: Image,
    aovs: Aovs,
    stamp: Stamp,
}

/// A finished denoise.
pub struct Denoised {
    pub stamp: Stamp,
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f32; 3]>,
    /// How long the denoiser took, on its thread.
    pub took: Duration,
}

/// What came back from the denoiser.
pub enum Finished {
    /// A denoise of the accumulation refining now.
    Kept(Denoised),
    /// A denoise of an older accumulation, not to be shown.
    Dropped(Stamp),
}

pub struct DenoiseWorker {
    jobs: Sender<Job>,
    results: Receiver<Result<Denoised, String>>,
    schedule: DenoiseSchedule,
}

impl DenoiseWorker {
    /// Starts the denoising thread, which owns `denoiser`.
    pub fn start(mut denoiser: impl Denoise) -> Self {
        let (jobs, inbox) = channel::<Job>();
        let (outbox, results) = channel();
        std::thread::spawn(move || {
            for job in inbox {
                let start = Instant::now();
                let done = denoiser.denoise(&job.image, &job.aovs).map(|pixels| Denoised {
                    stamp: job.stamp,
                    width: job.image.width,
                    height: job.image.height,
                    pixels,
                    took: start.elapsed(),
                });
                if outbox.send(done.map_err(|e| format!("{e:#}"))).is_err() {
                    return;
                }
            }
        });
        Self { jobs, results, schedule: DenoiseSchedule::default() }
    }

    pub fn schedule(&self) -> &DenoiseSchedule {
        &self.schedule
    }

    /// Follows `accumulation` (the session's restarts) and takes a finished denoise if
    /// there is one, without waiting. The denoiser's failure is an error, once.
    pub fn poll(&mut self, accumulation: u64) -> Result<Option<Finished>> {
        self.schedule.follow(accumulation);
        match self.results.try_recv() {
            Ok(result) => self.finish(result),
            Err(TryRecvError::Empty) => Ok(None),
            Err(TryRecvError::Disconnected) => self.finish(Err("the denoising thread ended".into())),
        }
    }

    /// Waits up to `timeout` for the denoise in flight (none: returns at once).
    pub fn wait(&mut self, timeout: Duration) -> Result<Option<Finished>> {
        if !self.schedule.busy() {
            return Ok(None);
        }
        match self.results.recv_timeout(timeout) {
            Ok(result) => self.finish(result),
            Err(RecvTimeoutError::Timeout) => Ok(None),
            Err(RecvTimeoutError::Disconnected) => self.finish(Err("the denoising thread ended".into())),
        }
    }

    fn finish(&mut self, result: Result<Denoised, String>) -> Result<Option<Finished>> {
        if self.schedule.stopped() {
            return Ok(None);
        }
        match result {
            Ok(done) if self.schedule.finished(done.stamp) => Ok(Some(Finished::Kept(done))),
            Ok(done) => Ok(Some(Finished::Dropped(done.stamp))),
            Err(message) => {
                self.schedule.stop();
                // One line in the log, whatever the denoiser said.
                Err(anyhow!("denoising stopped: {}", message.replace('\n', " ")))
            }
        }
    }

    /// Whether an image of `samples` per pixel should be denoised now.
    pub fn due(&self, samples: u32, converged: bool) -> bool {
        self.schedule.due(samples, converged)
    }

    /// Hands `image` (of the accumulation last polled) and its AOVs to the denoiser.
    pub fn send(&mut self, image: Image, aovs: Aovs) {
        let stamp = self.schedule.sent(image.samples);
        // A thread that is gone is reported by the next poll or wait.
        let _ = self.jobs.send(Job { image, aovs, stamp });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::mpsc::SyncSender;

    /// A denoiser that halves the image, each denoise waiting for the test to let it
    /// finish (or fail): the test decides how long the denoiser takes.
    struct Gated(Receiver<Result<(), String>>);

    impl Denoise for Gated {
        fn denoise(&mut self, image: &Image, _: &Aovs) -> Result<Vec<[f32; 3]>> {
            self.0.recv()?.map_err(|e| anyhow!(e))?;
            Ok(image.pixels.iter().map(|p| p.map(|c| 0.5 * c)).collect())
        }
    }

    fn gated() -> (DenoiseWorker, SyncSender<Result<(), String>>) {
        let (gate, opens) = std::sync::mpsc::sync_channel(8);
        (DenoiseWorker::start(Gated(opens)), gate)
    }

    fn frame(samples: u32, value: f32) -> (Image, Aovs) {
        let n = 4;
        let image = Image {
            width: 2,
            height: 2,
            samples,
            pixels: vec![[value; 3]; n],
            std_error: vec![0.0; n],
            sample_counts: vec![samples; n],
            alpha: None,
        };
        let aovs = Aovs {
            width: 2,
            height: 2,
            albedo: vec![[0.5; 3]; n],
            normal: vec![[0.0, 0.0, 1.0]; n],
            depth: vec![1.0; n],
            ..Default::default()
        };
        (image, aovs)
    }

    /// Polls until something comes back (the denoiser's thread takes its time).
    fn next(worker: &mut DenoiseWorker, accumulation: u64) -> Result<Finished> {
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            if let Some(finished) = worker.poll(accumulation)? {
                return Ok(finished);
            }
            assert!(Instant::now() < deadline, "nothing came back from the denoiser");
            std::thread::sleep(Duration::from_millis(1));
        }
    }

    #[test]
    fn polling_never_waits_for_the_denoiser() {
        let (mut worker, gate) = gated();
        let (image, aovs) = frame(4, 2.0);
        worker.send(image, aovs);
        // The denoiser holds on; a frame's poll returns at once, and nothing more is sent.
        for samples in 5..200 {
            let start = Instant::now();
            assert!(worker.poll(0).unwrap_or_else(|e| panic!("{e:#}")).is_none());
            assert!(start.elapsed() < Duration::from_millis(50), "a poll took {:?}", start.elapsed());
            assert!(!worker.due(samples, false), "{samples} spp: a second denoise while one runs");
        }
        gate.send(Ok(())).expect("gate");
        match next(&mut worker, 0).unwrap_or_else(|e| panic!("{e:#}")) {
            Finished::Kept(done) => {
                assert_eq!(done.stamp, Stamp { accumulation: 0, samples: 4 });
                assert_eq!((done.width, done.height, done.pixels), (2, 2, vec![[1.0; 3]; 4]));
            }
            Finished::Dropped(stamp) => panic!("the denoise of the current accumulation was dropped: {stamp:?}"),
        }
        assert!(worker.due(199, false), "the samples doubled while it ran: the next is due");
    }

    #[test]
    fn a_result_of_the_last_state_is_dropped_and_the_new_one_denoised() {
        let (mut worker, gate) = gated();
        let (image, aovs) = frame(8, 2.0);
        worker.send(image, aovs);
        // A reload: the session restarted while the old state's image is denoised.
        assert!(worker.poll(1).unwrap_or_else(|e| panic!("{e:#}")).is_none());
        assert!(worker.schedule().latest().is_none());
        gate.send(Ok(())).expect("gate");
        match next(&mut worker, 1).unwrap_or_else(|e| panic!("{e:#}")) {
            Finished::Dropped(stamp) => assert_eq!(stamp, Stamp { accumulation: 0, samples: 8 }),
            Finished::Kept(done) => panic!("a denoise of the last state was kept: {:?}", done.stamp),
        }
        assert!(worker.schedule().latest().is_none() && worker.due(4, false));
        let (image, aovs) = frame(4, 6.0);
        worker.send(image, aovs);
        gate.send(Ok(())).expect("gate");
        match worker.wait(Duration::from_secs(10)).unwrap_or_else(|e| panic!("{e:#}")) {
            Some(Finished::Kept(done)) => {
                assert_eq!(done.stamp, Stamp { accumulation: 1, samples: 4 });
                assert_eq!(done.pixels, vec![[3.0; 3]; 4], "the new state's image");
            }
            _ => panic!("no denoise of the new state"),
        }
    }

    #[test]
    fn a_failed_denoiser_is_one_error_then_silence() {
        let (mut worker, gate) = gated();
        let (image, aovs) = frame(4, 1.0);
        worker.send(image, aovs);
        gate.send(Err("device lost\n(CUDA error 999)".into())).expect("gate");
        let error = match next(&mut worker, 0) {
            Err(e) => format!("{e:#}"),
            Ok(_) => panic!("a failed denoise came back as a result"),
        };
        assert_eq!(error, "denoising stopped: device lost (CUDA error 999)", "one line, naming the cause");
        for samples in [8, 16, 64] {
            assert!(!worker.due(samples, samples == 64), "{samples} spp: denoised after the failure");
            assert!(worker.poll(0).unwrap_or_else(|e| panic!("{e:#}")).is_none(), "the error came twice");
        }
        assert!(worker.wait(Duration::from_millis(10)).unwrap_or_else(|e| panic!("{e:#}")).is_none());
    }

    #[test]
    fn a_denoiser_thread_that_dies_is_a_failure() {
        struct Panics;
        impl Denoise for Panics {
            fn denoise(&mut self, _: &Image, _: &Aovs) -> Result<Vec<[f32; 3]>> {
                panic!("the denoiser's thread panicked on purpose")
            }
        }
        let mut worker = DenoiseWorker::start(Panics);
        let (image, aovs) = frame(4, 1.0);
        worker.send(image, aovs);
        let error = match next(&mut worker, 0) {
            Err(e) => format!("{e:#}"),
            Ok(_) => panic!("a result from a dead thread"),
        };
        assert!(error.contains("the denoising thread ended"), "{error}");
        assert!(!worker.due(8, false));
    }
}
