//! The two clocks a comparison reads for each renderer: the wall clock (what a user
//! waits for: submission, synchronisation and the renderer's own overheads included) and
//! the device's (the kernels' own time: GPU timestamps for rt, Dr.Jit's kernel history
//! for Mitsuba).

/// Repeated timings of one piece of work that does `count` things (paths, rays).
#[derive(Clone, Debug, Default)]
pub struct Timed {
    pub count: u64,
    /// Seconds, one per run.
    pub wall: Vec<f64>,
    /// Seconds, one per run; empty where the device has no clock.
    pub device: Vec<f64>,
}

fn median(v: &[f64]) -> Option<f64> {
    let mut v: Vec<f64> = v.iter().copied().filter(|t| t.is_finite() && *t > 0.0).collect();
    v.sort_by(f64::total_cmp);
    (!v.is_empty()).then(|| v[v.len() / 2])
}

impl Timed {
    /// Things per second by the wall clock (median run).
    pub fn wall_rate(&self) -> Option<f64> {
        median(&self.wall).map(|t| self.count as f64 / t)
    }

    /// Things per second by the device's clock (median run).
    pub fn device_rate(&self) -> Option<f64> {
        median(&self.device).map(|t| self.count as f64 / t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_take_the_median_run_and_ignore_missing_clocks() {
        let t = Timed { count: 100, wall: vec![2.0, 1.0, 4.0], device: vec![] };
        assert_eq!(t.wall_rate(), Some(50.0));
        assert_eq!(t.device_rate(), None);
        let zero = Timed { count: 100, wall: vec![0.0], device: vec![f64::NAN] };
        assert_eq!((zero.wall_rate(), zero.device_rate()), (None, None));
    }
}
