//! How many samples per pixel the next dispatch takes: as many as keep it near a
//! target time. `rt render` aims far below the ~2 s after which drivers reset a GPU
//! that does not answer; `rt watch` aims at its frame time, so the window stays
//! responsive. After a reset the first dispatch takes one sample, to show the new
//! state as soon as possible.

use super::MAX_SAMPLES_PER_DISPATCH;
use std::time::Duration;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pacing {
    /// How long one dispatch should take.
    pub target: Duration,
    /// Samples per pixel in one dispatch at most.
    pub max_samples: u32,
}

impl Pacing {
    /// Long enough to keep the GPU busy, far below a driver's watchdog.
    pub const RENDER: Pacing = Pacing { target: Duration::from_millis(80), max_samples: MAX_SAMPLES_PER_DISPATCH };
}

/// The one controller of dispatch sizes.
#[derive(Clone, Debug)]
pub struct DispatchSizer {
    pacing: Pacing,
    next: u32,
    /// Set by `fix`: every dispatch takes this many, whatever it takes.
    fixed: Option<u32>,
}

impl DispatchSizer {
    pub fn new(pacing: Pacing) -> Self {
        Self { pacing, next: 1, fixed: None }
    }

    pub fn set_pacing(&mut self, pacing: Pacing) {
        self.pacing = pacing;
        self.next = self.next.clamp(1, pacing.max_samples);
    }

    /// Every dispatch takes `n` samples per pixel (`None`: follow the times again).
    pub fn fix(&mut self, n: Option<u32>) {
        self.fixed = n.map(|n| n.clamp(1, MAX_SAMPLES_PER_DISPATCH));
    }

    /// Starts again from one sample, as after a reset.
    pub fn restart(&mut self) {
        self.next = 1;
    }

    /// The size of the next dispatch when `remaining` samples per pixel are still wanted.
    pub fn next(&self, remaining: u32) -> u32 {
        self.fixed.unwrap_or(self.next).min(remaining).max(1)
    }

    /// Takes the time a dispatch of `samples` took; the next one grows or shrinks
    /// towards the target, by at most 2× a step, so one slow dispatch cannot overshoot.
    pub fn observe(&mut self, samples: u32, took: Duration) {
        if self.fixed.is_some() || samples == 0 {
            return;
        }
        let took = took.max(Duration::from_micros(100));
        let ratio = (self.pacing.target.as_secs_f64() / took.as_secs_f64()).clamp(0.5, 2.0);
        self.next = ((samples as f64 * ratio) as u32).clamp(1, self.pacing.max_samples);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grows_towards_the_target_at_most_twice_a_step() {
        let mut s = DispatchSizer::new(Pacing::RENDER);
        assert_eq!(s.next(100), 1);
        s.observe(1, Duration::from_millis(1));
        assert_eq!(s.next(100), 2);
        s.observe(2, Duration::from_millis(40));
        assert_eq!(s.next(100), 4);
        s.observe(4, Duration::from_millis(800));
        assert_eq!(s.next(100), 2);
        assert_eq!(s.next(1), 1, "never more than remain");
    }

    #[test]
    fn fixed_sizes_ignore_times_and_restarts_begin_at_one() {
        let mut s = DispatchSizer::new(Pacing::RENDER);
        s.fix(Some(16));
        s.observe(16, Duration::from_secs(5));
        assert_eq!(s.next(100), 16);
        s.fix(None);
        s.observe(1, Duration::from_millis(1));
        s.restart();
        assert_eq!(s.next(100), 1);
    }
}
