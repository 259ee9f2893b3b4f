//! Models fitted to one setting's measurements, for the equal-time and equal-error
//! views, and the Pareto front of error against time.
//!
//! Error: MSE(spp) = bias² + variance / spp, a Monte Carlo estimator's error (noise
//! falls as 1/√spp; bias does not fall). It is linear in 1/spp, so a weighted least-
//! squares fit over the levels gives both terms. The bias term is kept only when it is
//! at least two standard errors above zero: otherwise noise in the measurements would
//! invent error floors that no amount of samples could get under.
//! The image's mean error is a second, far less noisy, view of bias (a mean over all
//! pixels): |mean bias| ≤ RMS bias, so a mean error three standard errors from zero at
//! the highest level sets a floor under bias² that noise in the fit cannot hide.
//! Time: t(spp) = overhead + per_spp · spp, by ordinary least squares.

/// One measured level of a setting.
#[derive(Clone, Copy, Debug)]
pub struct Level {
    pub spp: f64,
    pub seconds: f64,
    /// Relative MSE (MSE over the reference's mean squared).
    pub mse: f64,
    /// Standard error of `mse`, from the spread over repeats.
    pub mse_std_error: f64,
    /// Relative error of the image's mean, and its standard error.
    pub mean_error: f64,
    pub mean_error_std_error: f64,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// Squared relative bias: the floor of the relative MSE.
    pub bias2: f64,
    /// Relative MSE at 1 spp, less the bias.
    pub variance: f64,
    pub overhead_s: f64,
    pub seconds_per_spp: f64,
    /// Highest measured spp: predictions beyond 4× it are extrapolations.
    pub max_spp: f64,
}

impl Fit {
    /// `None` with fewer than two distinct levels.
    pub fn of(levels: &[Level]) -> Option<Fit> {
        let mut distinct: Vec<f64> = levels.iter().map(|l| l.spp).collect();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        if distinct.len() < 2 {
            return None;
        }
        let top = levels.iter().max_by(|a, b| a.spp.total_cmp(&b.spp)).copied();
        let mean_bias2 = top
            .filter(|l| l.mean_error.abs() > 3.0 * l.mean_error_std_error)
            .map_or(0.0, |l| l.mean_error * l.mean_error);
        let (bias2, variance) = fit_error(levels, mean_bias2);
        let (overhead_s, seconds_per_spp) = fit_time(levels);
        Some(Fit { bias2, variance, overhead_s, seconds_per_spp, max_spp: distinct[distinct.len() - 1] })
    }

    pub fn relative_rmse_at_spp(&self, spp: f64) -> f64 {
        (self.bias2 + self.variance / spp.max(1e-9)).sqrt()
    }

    pub fn seconds_at_spp(&self, spp: f64) -> f64 {
        self.overhead_s + self.seconds_per_spp * spp
    }

    /// Relative RMSE reached in `seconds` (`None` if that buys not even one sample).
    pub fn relative_rmse_at_time(&self, seconds: f64) -> Option<f64> {
        let spp = (seconds - self.overhead_s) / self.seconds_per_spp;
        (spp >= 1.0).then(|| self.relative_rmse_at_spp(spp))
    }

    /// Samples per pixel needed for a relative RMSE of `target` (`None`: the bias is above it).
    pub fn spp_for(&self, target: f64) -> Option<f64> {
        let room = target * target - self.bias2;
        (room > 0.0).then(|| (self.variance / room).max(1.0))
    }

    pub fn seconds_for(&self, target: f64) -> Option<f64> {
        self.spp_for(target).map(|spp| self.seconds_at_spp(spp))
    }

    pub fn relative_bias(&self) -> f64 {
        self.bias2.sqrt()
    }
}

/// Weighted least squares of mse = bias² + variance · x with x = 1/spp, bias² ≥ `min_bias2`.
fn fit_error(levels: &[Level], min_bias2: f64) -> (f64, f64) {
    // Heavy-tailed noise (caustics, fireflies) makes an MSE far less certain than a few
    // repeats suggest: no level counts as known better than to 10 %.
    let weight = |l: &Level| 1.0 / l.mse_std_error.max(l.mse * 0.1).max(1e-30).powi(2);
    let (mut s, mut sx, mut sxx, mut sy, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for l in levels {
        let (w, x, y) = (weight(l), 1.0 / l.spp, l.mse);
        (s, sx, sxx, sy, sxy) = (s + w, sx + w * x, sxx + w * x * x, sy + w * y, sxy + w * x * y);
    }
    // The variance that fits best with bias² held at `b2`.
    let variance_given = |b2: f64| ((sxy - b2 * sx) / sxx).max(0.0);
    let det = s * sxx - sx * sx;
    if det <= 0.0 {
        return (min_bias2, variance_given(min_bias2));
    }
    let bias2 = (sxx * sy - sx * sxy) / det;
    let variance = (s * sxy - sx * sy) / det;
    let bias2_std_error = (sxx / det).sqrt();
    if variance < 0.0 {
        // The error does not fall with samples: all of it is bias.
        return ((sy / s).max(min_bias2), 0.0);
    }
    if bias2 < 2.0 * bias2_std_error || bias2 < min_bias2 {
        // No floor the fit can tell from noise (or a lower one than the mean error shows).
        return (min_bias2, variance_given(min_bias2));
    }
    (bias2, variance)
}

/// Ordinary least squares of seconds = overhead + per_spp · spp, overhead ≥ 0.
fn fit_time(levels: &[Level]) -> (f64, f64) {
    let n = levels.len() as f64;
    let (sx, sy) = (levels.iter().map(|l| l.spp).sum::<f64>(), levels.iter().map(|l| l.seconds).sum::<f64>());
    let sxx: f64 = levels.iter().map(|l| l.spp * l.spp).sum();
    let sxy: f64 = levels.iter().map(|l| l.spp * l.seconds).sum();
    let det = n * sxx - sx * sx;
    let slope = (n * sxy - sx * sy) / det;
    let overhead = (sy - slope * sx) / n;
    if det > 0.0 && overhead >= 0.0 && slope > 0.0 { (overhead, slope) } else { (0.0, (sxy / sxx).max(1e-12)) }
}

/// For each (time, error) point, whether it is on the Pareto front: no other point is
/// at least as fast and at least as accurate, and strictly better in one of the two.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<bool> {
    points.iter().map(|&(t, e)| !points.iter().any(|&(t2, e2)| t2 <= t && e2 <= e && (t2 < t || e2 < e))).collect()
}

/// Slope of log(y) against log(x) by least squares (−½ for RMSE against spp when noise dominates).
pub fn log_log_slope(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> =
        points.iter().filter(|(x, y)| *x > 0.0 && *y > 0.0).map(|(x, y)| (x.ln(), y.ln())).collect();
    let n = pts.len() as f64;
    let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (pts.len() >= 2 && sxx > 0.0).then(|| sxy / sxx)
}

/// Samples per pixel at which 1 − SSIM falls to `target`, from measured (spp, 1 − SSIM)
/// points: interpolated log–log between the two levels it falls between, below the lowest
/// or beyond the highest level along the nearest segment's slope (no fewer than 1 spp).
/// SSIM has no one power law: under heavy noise its contrast term saturates and 1 − SSIM
/// falls nearer 1/√spp, under light noise as 1/spp; the last measured slope is the
/// shallower one, so a prediction beyond the levels errs towards more samples. `None`
/// where the last segment does not fall (more samples did not help), and beyond the
/// highest level where it falls more slowly than 1/√spp: noise alone falls at least that
/// fast, so a flatter slope is a floor (pixels that stopped sampling, a denoiser's bias)
/// that more samples do not get under, not a rate to extrapolate.
pub fn spp_for_dssim(points: &[(f64, f64)], target: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> =
        points.iter().filter(|(x, y)| *x > 0.0 && *y > 0.0).map(|(x, y)| (x.ln(), y.ln())).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts.dedup_by(|a, b| a.0 == b.0);
    if target <= 0.0 {
        return None;
    }
    let goal = target.ln();
    if pts.len() < 2 {
        return None;
    }
    let along = |(x0, y0): (f64, f64), (x1, y1): (f64, f64)| -> Option<f64> {
        let slope = (y1 - y0) / (x1 - x0);
        (slope < 0.0).then(|| (x0 + (goal - y0) / slope).exp().max(1.0))
    };
    if goal >= pts[0].1 {
        return along(pts[0], pts[1]);
    }
    match pts.windows(2).find(|w| w[0].1 > goal && goal >= w[1].1) {
        Some(w) => along(w[0], w[1]),
        None => {
            let (a, b) = (pts[pts.len() - 2], pts[pts.len() - 1]);
            ((b.1 - a.1) / (b.0 - a.0) <= -0.5).then(|| along(a, b)).flatten()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dssim_is_interpolated_between_levels_and_extrapolated_along_the_last_slope() {
        // 1 − SSIM = 1/spp exactly: every target is hit exactly, inside or beyond the levels.
        let pts = [(4.0, 0.25), (16.0, 0.0625), (64.0, 1.0 / 64.0)];
        for (target, spp) in [(0.1, 10.0), (0.01, 100.0), (0.5, 2.0), (0.0625, 16.0)] {
            let got = spp_for_dssim(&pts, target).expect("reachable");
            assert!((got - spp).abs() < 1e-9 * spp, "{target}: {got}");
        }
        assert_eq!(spp_for_dssim(&pts, 2.0), Some(1.0), "no fewer than one sample");
        // A slope that steepens from −½ to −1: beyond the levels the last one counts.
        let pts = [(4.0, 0.5), (16.0, 0.25), (64.0, 0.0625)];
        assert!((spp_for_dssim(&pts, 0.03125).expect("reachable") - 128.0).abs() < 1e-9);
        // More samples that did not help predict nothing.
        assert_eq!(spp_for_dssim(&[(4.0, 0.2), (16.0, 0.1), (64.0, 0.1)], 0.01), None);
        // Nor do ones that barely helped: a floor is not extrapolated to astronomical spp.
        assert_eq!(spp_for_dssim(&[(16.0, 0.04), (64.0, 0.035), (256.0, 0.0349)], 0.01), None);
        // Falling as 1/√spp is still noise, and extrapolated.
        let got = spp_for_dssim(&[(16.0, 0.04), (64.0, 0.02)], 0.01).expect("reachable");
        assert!((got - 256.0).abs() < 1e-6, "{got}");
        assert_eq!(spp_for_dssim(&[(4.0, 0.2)], 0.01), None);
    }

    fn level(spp: f64, mse: f64) -> Level {
        Level {
            spp,
            seconds: 0.001 + 0.002 * spp,
            mse,
            mse_std_error: mse * 0.02,
            mean_error: 0.0,
            mean_error_std_error: 0.01,
        }
    }

    #[test]
    fn pure_noise_has_no_floor_and_time_is_linear() {
        let fit = Fit::of(&[level(4.0, 0.25), level(16.0, 0.0625), level(64.0, 0.015625)]).expect("fit");
        assert_eq!(fit.bias2, 0.0);
        assert!((fit.variance - 1.0).abs() < 1e-9, "{fit:?}");
        assert!((fit.seconds_per_spp - 0.002).abs() < 1e-12 && (fit.overhead_s - 0.001).abs() < 1e-12);
        let spp = fit.spp_for(0.01).expect("reachable");
        assert!((spp - 10_000.0).abs() < 1e-6);
        assert!((fit.relative_rmse_at_time(fit.seconds_at_spp(100.0)).expect("time") - 0.1).abs() < 1e-9);
    }

    #[test]
    fn a_floor_makes_small_targets_unreachable() {
        let b2 = 0.01;
        let fit = Fit::of(&[level(4.0, b2 + 0.25), level(16.0, b2 + 0.0625), level(64.0, b2 + 0.015625)]).expect("fit");
        assert!((fit.bias2 - b2).abs() < 1e-6, "{fit:?}");
        assert_eq!(fit.spp_for(0.05), None);
        assert!(fit.spp_for(0.2).is_some());
    }

    #[test]
    fn a_clear_mean_error_is_a_floor_even_when_noise_hides_it_in_the_mse() {
        let mut levels = [level(4.0, 0.25), level(16.0, 0.0625), level(64.0, 0.015625)];
        levels[2].mean_error = -0.05;
        let fit = Fit::of(&levels).expect("fit");
        assert!((fit.relative_bias() - 0.05).abs() < 1e-9, "{fit:?}");
        assert_eq!(fit.spp_for(0.01), None);
        levels[2].mean_error = -0.02;
        assert_eq!(Fit::of(&levels).expect("fit").bias2, 0.0, "within 3 standard errors of zero");
    }

    #[test]
    fn front_and_slope() {
        assert_eq!(pareto_front(&[(1.0, 1.0), (2.0, 0.5), (2.0, 2.0), (3.0, 0.5)]), [true, true, false, false]);
        let slope = log_log_slope(&[(1.0, 1.0), (4.0, 0.5), (16.0, 0.25)]).expect("slope");
        assert!((slope + 0.5).abs() < 1e-12);
    }
}
