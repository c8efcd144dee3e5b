//! The sweep's numerics on curves sampled on a common grid of reduced forces: log-log
//! interpolation, ensemble means, power-law fits of Eq. (77) over a window, percentile
//! intervals, the studies' one [`Estimate`] (a value with its interval) and the lambda
//! calibration. Curves are `Option` per grid point: `None`
//! outside a realisation's range.

use mrd::rough_contact::fit_line;
use std::f64::consts::PI;

/// Log-log interpolation of a monotone curve (x ascending) at `x`; None outside.
pub fn interp_loglog(xs: &[f64], ys: &[f64], x: f64) -> Option<f64> {
    if xs.len() < 2 || x < xs[0] || x > *xs.last().unwrap() {
        return None;
    }
    let k = xs.partition_point(|&v| v <= x).clamp(1, xs.len() - 1);
    let (x0, x1, y0, y1) = (xs[k - 1].ln(), xs[k].ln(), ys[k - 1].ln(), ys[k].ln());
    let t = if x1 > x0 {
        (x.ln() - x0) / (x1 - x0)
    } else {
        0.0
    };
    Some((y0 + t * (y1 - y0)).exp())
}

/// Ensemble mean of curves given on `fs` (None = outside that realisation's range);
/// a point is kept only where every realisation has a value.
pub fn mean_curve(curves: &[Vec<Option<f64>>], idx: &[usize], nf: usize) -> Vec<Option<f64>> {
    (0..nf)
        .map(|j| {
            let vals: Option<Vec<f64>> = idx.iter().map(|&i| curves[i][j]).collect();
            vals.map(|v| v.iter().sum::<f64>() / v.len() as f64)
        })
        .collect()
}

/// The grid points where `k` has a value inside the window [lo, hi].
///
/// A bootstrap keeps the points of the full sample's curve fixed: a resampled mean
/// leaves out realisations, so it reaches further along f and crosses the window's
/// edges elsewhere; letting each resample pick its own points would make its statistic
/// a different quantity from the estimate, and the interval would not be about it.
pub fn window_points(k: &[Option<f64>], lo: f64, hi: f64) -> Vec<bool> {
    k.iter()
        .map(|v| v.is_some_and(|v| v >= lo && v <= hi))
        .collect()
}

/// alpha, zeta by least squares over the window; None if fewer than 3 points.
pub fn fit_window(fs: &[f64], k: &[Option<f64>], lo: f64, hi: f64) -> Option<(f64, f64)> {
    fit_points(fs, k, &window_points(k, lo, hi))
}

/// alpha, zeta by least squares over the chosen points (those where `k` has a value);
/// None if fewer than 3.
pub fn fit_points(fs: &[f64], k: &[Option<f64>], points: &[bool]) -> Option<(f64, f64)> {
    let (x, y): (Vec<f64>, Vec<f64>) = fs
        .iter()
        .zip(k)
        .zip(points)
        .filter_map(|((&f, &v), &p)| v.filter(|_| p).map(|v| (f.ln(), v.ln())))
        .unzip();
    fit_line(&x, &y).ok().map(|l| (l.b, l.a.exp()))
}

/// lambda minimising the log-space misfit of K1(f sqrt(pi/lambda)) to K3(f) over the
/// points where K3 lies in the window [lo, hi].
pub fn calibrate_lambda(
    fs: &[f64],
    k3: &[Option<f64>],
    k1: &[Option<f64>],
    lo: f64,
    hi: f64,
) -> Option<f64> {
    calibrate_lambda_at(fs, k3, k1, &window_points(k3, lo, hi))
}

/// lambda minimising the log-space misfit of K1(f sqrt(pi/lambda)) to K3(f) over the
/// chosen points (those where K3 has a value); None if fewer than 3.
pub fn calibrate_lambda_at(
    fs: &[f64],
    k3: &[Option<f64>],
    k1: &[Option<f64>],
    points: &[bool],
) -> Option<f64> {
    let (f1, v1): (Vec<f64>, Vec<f64>) = fs
        .iter()
        .zip(k1)
        .filter_map(|(&f, &v)| v.map(|v| (f, v)))
        .unzip();
    let pts: Vec<(f64, f64)> = fs
        .iter()
        .zip(k3)
        .zip(points)
        .filter_map(|((&f, &v), &p)| v.filter(|_| p).map(|v| (f, v)))
        .collect();
    if pts.len() < 3 {
        return None;
    }
    let cost = |ln_lam: f64| -> f64 {
        let s = (PI / ln_lam.exp()).sqrt();
        pts.iter()
            .map(|&(f, v)| match interp_loglog(&f1, &v1, f * s) {
                Some(w) => (v.ln() - w.ln()).powi(2),
                None => 1e3,
            })
            .sum()
    };
    // Golden-section search on ln lambda over [ln 1e-3, ln 1e4] after a coarse scan.
    let (mut a, mut b) = ((1e-3f64).ln(), (1e4f64).ln());
    let scan: Vec<f64> = (0..=200).map(|i| a + (b - a) * i as f64 / 200.0).collect();
    let best = scan.iter().copied().fold((f64::INFINITY, 0.0), |m, x| {
        let c = cost(x);
        if c < m.0 {
            (c, x)
        } else {
            m
        }
    });
    let step = (b - a) / 200.0;
    a = best.1 - step;
    b = best.1 + step;
    let gr = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (c, d) = (b - gr * (b - a), a + gr * (b - a));
        if cost(c) < cost(d) {
            b = d;
        } else {
            a = c;
        }
    }
    Some((0.5 * (a + b)).exp())
}

/// A bootstrap draw of `n` indices into an ensemble of `n` (with replacement).
pub fn resample(rng: &mut rand_chacha::ChaCha8Rng, n: usize) -> Vec<usize> {
    use rand::RngExt;
    (0..n).map(|_| rng.random_range(0..n)).collect()
}

/// A value with its 95 % interval (NaN where undefined): every study's estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    pub value: f64,
    pub lo: f64,
    pub hi: f64,
}

impl Estimate {
    /// Undefined: value and interval NaN.
    pub const NONE: Estimate = Estimate {
        value: f64::NAN,
        lo: f64::NAN,
        hi: f64::NAN,
    };

    /// `value` (NaN where `None`) with the [`interval`] of its bootstrap draws `boot`.
    pub fn of(value: Option<f64>, boot: Vec<f64>) -> Self {
        let (lo, hi) = interval(boot);
        Self {
            value: value.unwrap_or(f64::NAN),
            lo,
            hi,
        }
    }

    /// The estimate and its interval times `factor` (> 0).
    pub fn scaled(self, factor: f64) -> Self {
        Self {
            value: self.value * factor,
            lo: self.lo * factor,
            hi: self.hi * factor,
        }
    }

    /// The interval's larger distance from the value, relative to it.
    pub fn relative_half_width(&self) -> f64 {
        ((self.hi - self.value).max(self.value - self.lo) / self.value).abs()
    }

    /// [value, lo, hi]: a table's three columns.
    pub fn columns(&self) -> [f64; 3] {
        [self.value, self.lo, self.hi]
    }
}

/// 95 % percentile interval of bootstrap draws (nearest rank). A draw that is not
/// finite (its statistic failed) counts against the interval on both sides, as if it
/// lay beyond either end: a bound that such draws could reach is undefined (NaN)
/// rather than taken from the successful draws alone.
pub fn interval(v: Vec<f64>) -> (f64, f64) {
    let n = v.len();
    let mut ok: Vec<f64> = v.into_iter().filter(|x| x.is_finite()).collect();
    let failed = n - ok.len();
    if ok.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    ok.sort_by(f64::total_cmp);
    let rank = |p: f64| ((p * (n - 1) as f64).round() as usize).min(n - 1);
    // Failed draws below the successes for the lower bound, above them for the upper.
    let lo = rank(0.025).checked_sub(failed).map_or(f64::NAN, |i| ok[i]);
    let hi = ok.get(rank(0.975)).copied().unwrap_or(f64::NAN);
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1e-300)
    }

    #[test]
    fn loglog_interpolation_is_exact_on_power_laws_and_none_outside() {
        let xs = [1.0, 10.0, 100.0];
        let ys: Vec<f64> = xs.iter().map(|x: &f64| 3.0 * x.powf(0.7)).collect();
        for x in [1.0, 2.5, 10.0, 31.6, 100.0] {
            let v = interp_loglog(&xs, &ys, x).unwrap();
            assert!(close(v, 3.0 * f64::powf(x, 0.7), 1e-12), "{x}: {v}");
        }
        assert_eq!(interp_loglog(&xs, &ys, 0.99), None);
        assert_eq!(interp_loglog(&xs, &ys, 100.01), None);
        assert_eq!(interp_loglog(&xs[..1], &ys[..1], 1.0), None);
    }

    #[test]
    fn mean_curve_needs_every_realisation() {
        let c = vec![
            vec![Some(1.0), Some(2.0), None],
            vec![Some(3.0), Some(4.0), Some(5.0)],
        ];
        assert_eq!(mean_curve(&c, &[0, 1], 3), vec![Some(2.0), Some(3.0), None]);
        // Resampled indices count with multiplicity (bootstrap).
        assert_eq!(mean_curve(&c, &[1, 1, 0], 3)[0], Some(7.0 / 3.0));
    }

    #[test]
    fn window_fit_recovers_exponent_and_prefactor_inside_the_window_only() {
        let fs: Vec<f64> = (0..30)
            .map(|i| 10f64.powf(-6.0 + 0.25 * i as f64))
            .collect();
        // k = 0.4 f^0.6, saturating (k = 1) above f = 10 outside the window.
        let k: Vec<Option<f64>> = fs
            .iter()
            .map(|&f| Some(if f > 10.0 { 1.0 } else { 0.4 * f.powf(0.6) }))
            .collect();
        let (a, z) = fit_window(&fs, &k, 1e-3, 0.3).unwrap();
        assert!(close(a, 0.6, 1e-12) && close(z, 0.4, 1e-12), "{a} {z}");
        // Fewer than 3 points in the window: no fit.
        assert!(fit_window(&fs, &k, 0.5, 0.6).is_none());
    }

    #[test]
    fn lambda_calibration_inverts_the_height_rescaling() {
        // K1(f) = 0.5 f^0.7; the 3D curve is K1(f sqrt(pi/lambda)) for lambda = 2.3.
        let fs: Vec<f64> = (0..60).map(|i| 10f64.powf(-6.0 + 0.1 * i as f64)).collect();
        let k1: Vec<Option<f64>> = fs.iter().map(|&f| Some(0.5 * f.powf(0.7))).collect();
        let s = (PI / 2.3f64).sqrt();
        let k3: Vec<Option<f64>> = fs.iter().map(|&f| Some(0.5 * (f * s).powf(0.7))).collect();
        let lam = calibrate_lambda(&fs, &k3, &k1, 1e-4, 0.3).unwrap();
        assert!(close(lam, 2.3, 1e-6), "{lam}");
        // lambda = pi leaves the curve unchanged.
        let lam = calibrate_lambda(&fs, &k1, &k1, 1e-4, 0.3).unwrap();
        assert!(close(lam, PI, 1e-6), "{lam}");
    }

    #[test]
    fn percentile_interval_of_a_known_sample() {
        // 0..=1000: 2.5 % and 97.5 % points at 25 and 975 (nearest rank).
        let v: Vec<f64> = (0..=1000).rev().map(f64::from).collect();
        assert_eq!(interval(v), (25.0, 975.0));
        assert!(interval(vec![f64::NAN]).0.is_nan());
    }

    #[test]
    fn failed_draws_widen_the_interval_and_can_leave_it_undefined() {
        // 200 draws 1..=200 and one failure, 201 draws in all: the failure takes the
        // lowest rank for the lower bound (rank 5 -> the 5th success, 5) and the
        // highest for the upper (rank 195 -> the 196th success, 196).
        let mut v: Vec<f64> = (1..=200).map(f64::from).collect();
        v.push(f64::NAN);
        assert_eq!(interval(v), (5.0, 196.0));
        // With more than 2.5 % failed the bounds are not known.
        let mut v: Vec<f64> = (1..=190).map(f64::from).collect();
        v.extend([f64::NAN; 10]);
        let (lo, hi) = interval(v);
        assert!(lo.is_nan() && hi.is_nan(), "{lo} {hi}");
    }

    #[test]
    fn fixed_points_make_calibration_and_fit_ignore_the_window() {
        let fs: Vec<f64> = (0..40).map(|i| 10f64.powf(-4.0 + 0.1 * i as f64)).collect();
        let k1: Vec<Option<f64>> = fs.iter().map(|&f| Some(0.5 * f.powf(0.7))).collect();
        let points = window_points(&k1, 1e-3, 0.05);
        let n = points.iter().filter(|&&p| p).count();
        assert!(n >= 3 && n < fs.len(), "{n}");
        assert_eq!(
            calibrate_lambda_at(&fs, &k1, &k1, &points),
            calibrate_lambda(&fs, &k1, &k1, 1e-3, 0.05)
        );
        assert_eq!(
            fit_points(&fs, &k1, &points),
            fit_window(&fs, &k1, 1e-3, 0.05)
        );
        // A curve moved out of the window keeps the chosen points (and still fits them).
        let k3: Vec<Option<f64>> = k1.iter().map(|v| v.map(|v| 3.0 * v)).collect();
        let (a, z) = fit_points(&fs, &k3, &points).unwrap();
        assert!(close(a, 0.7, 1e-12) && close(z, 1.5, 1e-12), "{a} {z}");
        let lam = calibrate_lambda_at(&fs, &k3, &k1, &points).unwrap();
        // K1(f s) = 3 K1(f): s = 3^(1/0.7), lambda = pi / s^2.
        assert!(close(lam, PI / 3f64.powf(2.0 / 0.7), 1e-6), "{lam}");
    }
}
