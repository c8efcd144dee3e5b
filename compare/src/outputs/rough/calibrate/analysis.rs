//! Curves on the common reduced-force grid, lambda fitted to the 3D ensemble mean, its
//! bootstrap interval, the misfit left over and the exponents of Eq. (77).

use crate::experiment::fit::{
    calibrate_lambda_at, fit_points, interp_loglog, interval, mean_curve, resample, window_points,
    Estimate,
};
use crate::experiment::rough_punch::BemCurve;
use std::f64::consts::PI;

/// Bootstrap resamples of every interval.
pub const RESAMPLES: usize = 200;

/// k/(E* L) of a 3D curve on the grid `fs`, f = F/(E* h L) with h the curve's own rms
/// height; None outside its range.
pub fn reduce(c: &BemCurve, fs: &[f64]) -> Vec<Option<f64>> {
    let f: Vec<f64> = c.force.iter().map(|v| v / c.rms_height).collect();
    fs.iter()
        .map(|&x| interp_loglog(&f, &c.stiffness, x))
        .collect()
}

/// MRD's k at lambda: K1(f sqrt(pi / l)), l = lambda times the rms factor.
pub fn mrd_at(fs: &[f64], k1: &[Option<f64>], l: f64) -> Vec<Option<f64>> {
    let (f1, v1): (Vec<f64>, Vec<f64>) = fs
        .iter()
        .zip(k1)
        .filter_map(|(&f, &v)| v.map(|v| (f, v)))
        .unzip();
    let s = (PI / l).sqrt();
    fs.iter().map(|&f| interp_loglog(&f1, &v1, f * s)).collect()
}

/// max and rms |ln k3 - ln k1| over the chosen points.
pub fn misfit(k3: &[Option<f64>], k1: &[Option<f64>], points: &[bool]) -> (f64, f64) {
    let d: Vec<f64> = k3
        .iter()
        .zip(k1)
        .zip(points)
        .filter_map(|((a, b), &p)| match (a, b) {
            (Some(a), Some(b)) if p => Some((a.ln() - b.ln()).abs()),
            _ => None,
        })
        .collect();
    if d.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    let max = d.iter().copied().fold(0.0, f64::max);
    (
        max,
        (d.iter().map(|v| v * v).sum::<f64>() / d.len() as f64).sqrt(),
    )
}

/// The calibration of one ensemble.
#[derive(Debug, Clone)]
pub struct Calibration {
    pub realisations: usize,
    pub lambda: Estimate,
    /// The shift of the reduced curves, pi h1^2 / h3^2.
    pub shift: f64,
    pub misfit: (f64, f64),
    pub alpha_3d: Estimate,
    pub alpha_mrd: f64,
    /// lambda fitted on the lower and on the upper half of the range's points.
    pub halves: (f64, f64),
    /// The 3D ensemble mean and its pointwise 95 % interval on the grid.
    pub mean3: Vec<Option<f64>>,
    pub band3: Vec<Option<(f64, f64)>>,
    /// MRD at the calibrated lambda on the grid.
    pub mrd: Vec<Option<f64>>,
    /// The points of the calibration range.
    pub points: Vec<bool>,
}

/// Calibrates lambda on the 3D curves `k3` (per realisation) against the MRD mean `k1`
/// over the window (k/(E* L)); `rms_factor` turns the shift into lambda; the bootstrap
/// draws from `rng`. None when fewer than 3 grid points of the 3D mean lie in the window.
pub fn calibrate(
    fs: &[f64],
    k3: &[Vec<Option<f64>>],
    k1: &[Option<f64>],
    window: [f64; 2],
    rms_factor: f64,
    rng: &mut rand_chacha::ChaCha8Rng,
) -> Option<Calibration> {
    let n = k3.len();
    let all: Vec<usize> = (0..n).collect();
    let mean3 = mean_curve(k3, &all, fs.len());
    let points = window_points(&mean3, window[0], window[1]);
    let shift = calibrate_lambda_at(fs, &mean3, k1, &points)?;
    let alpha = fit_points(fs, &mean3, &points)?.0;
    let alpha_mrd = crate::experiment::fit::fit_window(fs, k1, window[0], window[1])?.0;
    let mrd = mrd_at(fs, k1, shift);
    let (mut lams, mut alphas) = (Vec::new(), Vec::new());
    let mut draws: Vec<Vec<Option<f64>>> = Vec::new();
    for _ in 0..RESAMPLES {
        let idx = resample(rng, n);
        let m = mean_curve(k3, &idx, fs.len());
        lams.push(calibrate_lambda_at(fs, &m, k1, &points).map_or(f64::NAN, |l| l / rms_factor));
        alphas.push(fit_points(fs, &m, &points).map_or(f64::NAN, |a| a.0));
        draws.push(m);
    }
    let band3 = (0..fs.len())
        .map(|j| {
            mean3[j]?;
            let (lo, hi) = interval(draws.iter().map(|d| d[j].unwrap_or(f64::NAN)).collect());
            (lo.is_finite() && hi.is_finite()).then_some((lo, hi))
        })
        .collect();
    let ranked: Vec<usize> = (0..fs.len()).filter(|&j| points[j]).collect();
    let half = |keep: &dyn Fn(usize) -> bool| -> f64 {
        let p: Vec<bool> = (0..fs.len())
            .map(|j| points[j] && keep(ranked.iter().position(|&r| r == j).unwrap_or(0)))
            .collect();
        calibrate_lambda_at(fs, &mean3, k1, &p).map_or(f64::NAN, |l| l / rms_factor)
    };
    let m = ranked.len() / 2;
    let estimate = |value: f64, draws: Vec<f64>| {
        let (lo, hi) = interval(draws);
        Estimate { value, lo, hi }
    };
    Some(Calibration {
        realisations: n,
        lambda: estimate(shift / rms_factor, lams),
        shift,
        misfit: misfit(&mean3, &mrd, &points),
        alpha_3d: estimate(alpha, alphas),
        alpha_mrd,
        halves: (half(&|i| i < m), half(&|i| i >= m)),
        mean3,
        band3,
        mrd,
        points,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An ensemble made from the MRD curve itself, shifted by a known factor and scaled
    /// by per-realisation noise: lambda comes back to 1e-6, the misfit is zero, the
    /// interval holds the value and alpha is the curve's slope.
    #[test]
    fn a_shifted_mrd_curve_gives_back_its_lambda() {
        let fs = mrd::friction::log_space(1e-4, 1e2, 121);
        let k1: Vec<Option<f64>> = fs
            .iter()
            .map(|f| Some((0.3 * f.powf(0.6)).min(1.0)))
            .collect();
        let (shift, factor) = (5.0, 1.25);
        let exact = mrd_at(&fs, &k1, shift);
        let k3: Vec<Vec<Option<f64>>> = (0..12)
            .map(|r| {
                let s = 1.0 + 0.02 * ((r as f64) - 5.5) / 5.5;
                exact.iter().map(|v| v.map(|v| v * s)).collect()
            })
            .collect();
        let mut rng = mrd::roughness::synthesis::realisation_rng(1, 2);
        let c = calibrate(&fs, &k3, &k1, [0.02, 0.5], factor, &mut rng).unwrap();
        assert!(
            (c.lambda.value / (shift / factor) - 1.0).abs() < 1e-6,
            "{:?}",
            c.lambda
        );
        assert!(c.lambda.lo < c.lambda.value && c.lambda.value < c.lambda.hi);
        assert!(c.misfit.0 < 1e-6, "{:?}", c.misfit);
        assert!((c.alpha_3d.value - 0.6).abs() < 1e-6 && (c.alpha_mrd - 0.6).abs() < 1e-6);
        assert!((c.halves.0 / c.lambda.value - 1.0).abs() < 1e-6);
    }
}
