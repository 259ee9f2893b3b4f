//! When `rt watch --denoise` denoises, and which results it keeps: the first denoise once
//! the running mean has a few samples per pixel, the next each time the samples have
//! doubled, a last one of the converged image; one at a time, and a result of an older
//! accumulation (before a reload, a camera move, a resize) never kept for the new one.
//! No clock and no threads: the window and headless mode tell it what happens.

/// Samples per pixel before the first denoise: fewer give blotches, not a preview.
pub const FIRST_DENOISE_SAMPLES: u32 = 4;

/// Which image a denoise is of: the accumulation ([`rt::render::Session::restarts`])
/// and its samples per pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Stamp {
    pub accumulation: u64,
    pub samples: u32,
}

#[derive(Debug, Default)]
pub struct DenoiseSchedule {
    /// The accumulation refining now.
    accumulation: u64,
    /// Samples per pixel of the last image of it sent to the denoiser (0: none yet).
    sent: u32,
    /// The image being denoised: one at a time, since the denoiser does one at a time.
    in_flight: Option<Stamp>,
    /// The newest denoise kept of the accumulation refining now.
    latest: Option<Stamp>,
    /// The denoiser failed: nothing is denoised any more.
    stopped: bool,
}

impl DenoiseSchedule {
    /// The accumulation refining now: when it is another one, what was kept of the last
    /// is dropped and its samples count again from none.
    pub fn follow(&mut self, accumulation: u64) {
        if accumulation != self.accumulation {
            (self.accumulation, self.sent, self.latest) = (accumulation, 0, None);
        }
    }

    /// Whether to denoise the image now, at `samples` per pixel: when nothing is being
    /// denoised, and the samples reached the first denoise's or doubled since the last,
    /// or the image converged with samples the last denoise did not have.
    pub fn due(&self, samples: u32, converged: bool) -> bool {
        let enough = samples >= FIRST_DENOISE_SAMPLES.max(2 * self.sent) || converged;
        !self.stopped && self.in_flight.is_none() && samples > self.sent && enough
    }

    /// An image of `samples` per pixel of the accumulation refining now went to the
    /// denoiser: its stamp, which comes back with its result.
    pub fn sent(&mut self, samples: u32) -> Stamp {
        let stamp = Stamp { accumulation: self.accumulation, samples };
        (self.sent, self.in_flight) = (samples, Some(stamp));
        stamp
    }

    /// The denoise of `stamp` finished: true if it is of the accumulation refining now
    /// (to show), false if of an older one (to drop).
    pub fn finished(&mut self, stamp: Stamp) -> bool {
        if self.in_flight == Some(stamp) {
            self.in_flight = None;
        }
        let current = stamp.accumulation == self.accumulation;
        if current {
            self.latest = Some(stamp);
        }
        current
    }

    /// The denoiser failed: nothing more is sent, nothing is in flight.
    pub fn stop(&mut self) {
        (self.stopped, self.in_flight) = (true, None);
    }

    pub fn stopped(&self) -> bool {
        self.stopped
    }

    /// Whether an image is being denoised.
    pub fn busy(&self) -> bool {
        self.in_flight.is_some()
    }

    /// The newest denoise kept of the accumulation refining now.
    pub fn latest(&self) -> Option<Stamp> {
        self.latest
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Refines one accumulation to `spp` a sample at a time, each denoise finishing before
    /// the next sample: the samples per pixel of the images denoised.
    fn denoised_samples(schedule: &mut DenoiseSchedule, spp: u32) -> Vec<u32> {
        let mut denoised = Vec::new();
        for samples in 1..=spp {
            if schedule.due(samples, samples == spp) {
                let stamp = schedule.sent(samples);
                assert!(schedule.finished(stamp));
                denoised.push(samples);
            }
        }
        denoised
    }

    #[test]
    fn denoises_at_four_samples_then_each_doubling_then_the_converged_image() {
        let mut schedule = DenoiseSchedule::default();
        assert_eq!(denoised_samples(&mut schedule, 100), [4, 8, 16, 32, 64, 100]);
        assert!(!schedule.due(100, true), "the converged image is denoised once");
        assert_eq!(schedule.latest(), Some(Stamp { accumulation: 0, samples: 100 }));
        // Fewer samples than the first denoise's: only the converged image.
        let mut schedule = DenoiseSchedule::default();
        assert_eq!(denoised_samples(&mut schedule, 2), [2]);
        // Exactly a doubling: no second denoise of the same image.
        let mut schedule = DenoiseSchedule::default();
        assert_eq!(denoised_samples(&mut schedule, 16), [4, 8, 16]);
    }

    #[test]
    fn one_denoise_at_a_time_while_samples_go_on() {
        let mut schedule = DenoiseSchedule::default();
        assert!(schedule.due(5, false));
        let stamp = schedule.sent(5);
        // Refinement goes on; nothing more is sent until the denoise is back.
        for samples in 6..40 {
            assert!(!schedule.due(samples, samples == 39) && schedule.busy(), "{samples} spp");
        }
        assert!(schedule.finished(stamp) && !schedule.busy());
        // The samples doubled meanwhile: the next denoise is due at once.
        assert!(schedule.due(40, false));
        assert_eq!(schedule.sent(40), Stamp { accumulation: 0, samples: 40 });
    }

    #[test]
    fn a_denoise_of_an_older_accumulation_is_dropped() {
        let mut schedule = DenoiseSchedule::default();
        let first = schedule.sent(4);
        assert!(schedule.finished(first));
        let old = schedule.sent(8);
        // A reload restarts the accumulation while the 8-sample image is being denoised.
        schedule.follow(1);
        assert_eq!(schedule.latest(), None, "the last state's denoise is not shown for the new one");
        assert!(!schedule.due(4, false), "one at a time: the old denoise is still running");
        assert!(!schedule.finished(old), "a result of the old state is dropped");
        assert_eq!(schedule.latest(), None);
        // The new state counts its samples from none: its first denoise at 4 samples.
        assert!(!schedule.due(3, false) && schedule.due(4, false));
        let new = schedule.sent(4);
        assert!(schedule.finished(new));
        assert_eq!(schedule.latest(), Some(Stamp { accumulation: 1, samples: 4 }));
        // Following the same accumulation again changes nothing.
        schedule.follow(1);
        assert_eq!(schedule.latest(), Some(new));
    }

    #[test]
    fn a_stopped_schedule_sends_nothing() {
        let mut schedule = DenoiseSchedule::default();
        schedule.sent(4);
        schedule.stop();
        assert!(schedule.stopped() && !schedule.busy());
        assert!(!schedule.due(8, false) && !schedule.due(64, true));
    }
}
