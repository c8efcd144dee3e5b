//! The spectrum's own part of lambda's interval, for a measured map.
//!
//! The map's PSD is an estimate: its lowest annuli hold a few lattice points each, so
//! their C2D scatters by tens of per cent from one map of the same surface to the next,
//! and those annuli carry most of the variance. A parametric bootstrap propagates that:
//! surrogate `s` is a Gaussian random field with the map's estimated spectrum, cut
//! (not periodic) to the map's size and read by the same estimator
//! ([`Measured::surrogate_psd`]); the calibration is repeated with that spectrum on
//! the main sample's first `punches` punches and lines with the same phases
//! ([`tasks::run_surrogate`]), and compared with the calibration of those same punches
//! with the map's spectrum. The ratios r_s = lambda_s / lambda_0 carry the spectrum's
//! uncertainty and what the common phases leave of the punches' sampling; [`analyse`]
//! separates the two, and the spectrum's 95 % half-width in ln lambda is reported beside
//! the punches' and combined with it in quadrature (independent sources).
//!
//! [`Measured::surrogate_psd`]: crate::experiment::measured::Measured::surrogate_psd

use super::analysis::reduce;
use super::tasks::{self, f_grid, surrogate_spectrum, Case, Resample, Spectrum, Task};
use super::Calibrate;
use crate::error::Result;
use crate::experiment::fit::{calibrate_lambda_at, mean_curve, window_points, Estimate};
use crate::experiment::rough_punch::BemCurve;
use std::path::Path;

/// One surrogate's calibration against the map's own on the same punches.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// lambda with the surrogate spectrum (punches and lines).
    pub lambda: f64,
    /// lambda with the map's spectrum on the same punches.
    pub reference: f64,
    /// The punches' sampling variance of ln(lambda / reference) at this number of
    /// punches, from this surrogate alone: (ln r_a - ln r_b)^2 / 4, r_a and r_b the
    /// ratios on the first and second half of the punches (each half's variance is
    /// twice the whole's).
    pub noise: f64,
    /// The surrogate spectrum's mean square height over the map's, at the bandwidth.
    pub mean_square: f64,
    /// The surrogate's 3D solves that did not converge (left out of its curves).
    pub unconverged: usize,
}

/// The spectrum's part of the interval.
#[derive(Debug, Clone)]
pub struct SpectrumPart {
    pub rows: Vec<Row>,
    pub punches: u64,
    /// exp(mean ln r) - 1: how far the surrogates' lambda lies from the map's on
    /// average (the estimator's bias, to the bootstrap's resolution).
    pub bias: f64,
    /// The standard error of ln(1 + bias): sqrt(var ln r / surrogates).
    pub bias_error: f64,
    /// var(ln r) over the surrogates, and the part of it the punches' sampling explains
    /// (the mean of the rows' `noise`): the spectrum's variance is their difference.
    pub variance: (f64, f64),
    /// Whether the spectrum's variance exceeds its standard error (else the surrogates'
    /// spread is mostly the punches' noise, and only `upper` bounds the part).
    pub resolved: bool,
    /// 1.96 sqrt(var ln r): the spectrum's half-width in ln lambda could not exceed it
    /// (the surrogates' whole spread, punches' noise included).
    pub upper: f64,
    /// 1.96 sqrt(var ln r - the punches' part, or 0): the half-width's estimate.
    pub estimate: f64,
    /// The spectrum's interval alone around the calibrated lambda: the estimate where
    /// resolved, else the upper bound.
    pub lambda: Estimate,
    /// The punches' and the spectrum's intervals combined.
    pub total: Estimate,
    /// Every surrogate punch (their solves join the run's tally).
    pub curves: Vec<BemCurve>,
}

impl SpectrumPart {
    /// The bootstrap's bias correction (ln lambda less the surrogates' mean ln ratio),
    /// its interval the total one widened by the correction's own standard error: an
    /// alternative reading, not the calibrated value.
    pub fn bias_corrected(&self) -> Estimate {
        let v = self.total.value;
        let shift = self.bias.ln_1p();
        let corrected = |widen: f64| (v.ln() - shift + widen).exp();
        let (lo, hi) = ((v / self.total.lo).ln(), (self.total.hi / v).ln());
        let widen = 1.96 * self.bias_error;
        Estimate {
            value: corrected(0.0),
            lo: corrected(-lo.hypot(widen)),
            hi: corrected(hi.hypot(widen)),
        }
    }
}

/// Reads the surrogates' checkpoints and calibrates each; `k3` the main sample's reduced
/// curves (the first `punches` are used), `k1` and `rms_factor` the map spectrum's MRD
/// mean and factor, `lambda` the calibration's estimate (its punches' interval).
///
/// ln r_s = ln(lambda_s / lambda_0) scatters by the spectrum's uncertainty plus what the
/// common phases leave of the punches' sampling (a punch dominated by one low mode
/// answers a change of that annulus more than the others): var(ln r) = s2_spectrum +
/// s2_punches. s2_punches is estimated within each surrogate from its two halves of
/// punches, pooled over the surrogates, and subtracted (random-effects decomposition).
/// The punches' part is about 0.1 / punches on the maps tried (docs/results.md), so the
/// spectrum's part is resolved only with tens of punches per surrogate; unresolved, it
/// is taken at its upper bound.
pub fn analyse(
    spec: &Calibrate,
    case: &Case,
    work: &Path,
    k3: &[Vec<Option<f64>>],
    k1: &[Option<f64>],
    rms_factor: f64,
    lambda: &Estimate,
) -> Result<Option<SpectrumPart>> {
    let Some(u) = spec.spectrum_resamples() else {
        return Ok(None);
    };
    let fs = f_grid();
    let n0 = spec.spectrum_punches() as usize;
    let reference_curves = &k3[..n0.min(k3.len())];
    // lambda of the punches `idx` of `k3` against `k1`, on the window points of the
    // full set's mean (as the main bootstrap keeps its points).
    let fit = |k3: &[Vec<Option<f64>>], idx: &[usize], k1: &[Option<f64>], factor: f64| {
        let all: Vec<usize> = (0..k3.len()).collect();
        let points = window_points(
            &mean_curve(k3, &all, fs.len()),
            spec.window[0],
            spec.window[1],
        );
        let mean = mean_curve(k3, idx, fs.len());
        calibrate_lambda_at(&fs, &mean, k1, &points).map_or(f64::NAN, |l| l / factor)
    };
    let all: Vec<usize> = (0..reference_curves.len()).collect();
    let reference = fit(reference_curves, &all, k1, rms_factor);
    let ms = |s: &Spectrum| -> f64 {
        mrd::roughness::nested::surface_mean_square(&|q| s.c2d(q), case.band as f64, 1.0, true)
    };
    let ms_map = ms(&case.spectrum);
    let mut rows = Vec::new();
    let mut curves = Vec::new();
    for s in 0..u.resamples {
        let task = Task::Spectrum {
            s,
            punches: n0 as u64,
        };
        let r: Resample = tasks::load(work, task)?;
        let k3s: Vec<Vec<Option<f64>>> = r.punches.iter().map(|c| reduce(c, &fs)).collect();
        let k1s: Vec<Option<f64>> = r.k1.iter().map(|&v| Some(v)).collect();
        // The two halves of the punches: independent samples of the same spectrum's
        // ratio, so their difference is the punches' noise alone.
        let h = k3s.len() / 2;
        let half = |idx: Vec<usize>| {
            (fit(&k3s, &idx, &k1s, r.rms_factor) / fit(reference_curves, &idx, k1, rms_factor)).ln()
        };
        let d = half((0..h).collect()) - half((h..2 * h).collect());
        rows.push(Row {
            lambda: fit(&k3s, &all, &k1s, r.rms_factor),
            reference,
            noise: d * d / 4.0,
            mean_square: ms(&surrogate_spectrum(&r.psd, case)?) / ms_map,
            unconverged: r.punches.iter().map(|c| c.unconverged).sum(),
        });
        curves.extend(r.punches);
    }
    let logs: Vec<f64> = rows
        .iter()
        .map(|r| (r.lambda / r.reference).ln())
        .filter(|v| v.is_finite())
        .collect();
    let noises: Vec<f64> = rows
        .iter()
        .map(|r| r.noise)
        .filter(|v| v.is_finite())
        .collect();
    let split = Split::of(&logs, &noises);
    // Unresolved, the part is taken at its bound: the interval may be too wide, never
    // too narrow.
    let b = if split.resolved {
        split.estimate
    } else {
        split.upper
    };
    let v = lambda.value;
    let (lo, hi) = ((v / lambda.lo).ln(), (lambda.hi / v).ln());
    Ok(Some(SpectrumPart {
        punches: n0 as u64,
        bias: split.mean.exp() - 1.0,
        bias_error: (split.spread / logs.len() as f64).sqrt(),
        variance: (split.spread, split.noise),
        resolved: split.resolved,
        upper: split.upper,
        estimate: split.estimate,
        lambda: Estimate {
            value: v,
            lo: v * (-b).exp(),
            hi: v * b.exp(),
        },
        total: Estimate {
            value: v,
            lo: v * (-(lo * lo + b * b).sqrt()).exp(),
            hi: v * (hi * hi + b * b).sqrt().exp(),
        },
        rows,
        curves,
    }))
}

/// The random-effects split of the surrogates' spread (module docs): ln r_s (`logs`)
/// scatters by the spectrum's variance plus the punches' noise, whose estimate per
/// surrogate (`noises`, from its two halves of punches) is pooled and subtracted.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Split {
    /// The mean of ln r.
    mean: f64,
    /// var(ln r) over the surrogates, and the mean of their noise estimates.
    spread: f64,
    noise: f64,
    /// The standard error of `spread - noise` (S - 1 and S degrees of freedom for the
    /// two; the two are independent: a surrogate's whole-sample ratio and the difference
    /// of its halves are).
    error: f64,
    /// `spread - noise > error`: the spectrum's part stands out of the noise.
    resolved: bool,
    /// 1.96 sqrt(spread - noise, or 0) and 1.96 sqrt(spread): the spectrum's 95 %
    /// half-width in ln lambda and its bound.
    estimate: f64,
    upper: f64,
}

impl Split {
    /// Undefined (NaN, reported as such) below three surrogates.
    fn of(logs: &[f64], noises: &[f64]) -> Self {
        let logs = if logs.len() < 3 { &[][..] } else { logs };
        let noise = noises.iter().sum::<f64>() / noises.len() as f64;
        let spread = variance(logs);
        let n = logs.len() as f64;
        let error = ((spread * (2.0 / (n - 1.0)).sqrt()).powi(2)
            + (noise * (2.0 / noises.len() as f64).sqrt()).powi(2))
        .sqrt();
        Self {
            mean: logs.iter().sum::<f64>() / n,
            spread,
            noise,
            error,
            resolved: spread - noise > error,
            estimate: 1.96 * (spread - noise).max(0.0).sqrt(),
            upper: 1.96 * spread.sqrt(),
        }
    }
}

/// The sample variance (NaN below two values).
fn variance(v: &[f64]) -> f64 {
    if v.len() < 2 {
        return f64::NAN;
    }
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Synthetic surrogates with a known spectrum variance `s2` and punches' noise `n2`
    /// (of the whole sample; each half has twice it): ln r_s = a_s + (e_a + e_b) / 2 and
    /// the noise estimate (e_a - e_b)^2 / 4, a_s ~ N(0, s2), e ~ N(0, 2 n2). Returns the
    /// splits of `trials` experiments of `surrogates` each.
    fn experiments(s2: f64, n2: f64, surrogates: usize, trials: usize) -> Vec<Split> {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        // Box-Muller: a standard normal from two uniforms.
        let mut normal = move || -> f64 {
            let (u, v): (f64, f64) = (rng.random(), rng.random());
            (-2.0 * (1.0 - u).ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
        };
        (0..trials)
            .map(|_| {
                let (mut logs, mut noises) = (vec![], vec![]);
                for _ in 0..surrogates {
                    let a = s2.sqrt() * normal();
                    let (ea, eb) = ((2.0 * n2).sqrt() * normal(), (2.0 * n2).sqrt() * normal());
                    logs.push(a + (ea + eb) / 2.0);
                    noises.push((ea - eb).powi(2) / 4.0);
                }
                Split::of(&logs, &noises)
            })
            .collect()
    }

    fn mean_sd(v: impl Iterator<Item = f64>) -> (f64, f64) {
        let v: Vec<f64> = v.collect();
        let m = v.iter().sum::<f64>() / v.len() as f64;
        (m, variance(&v).sqrt())
    }

    /// The split recovers a known spectrum variance: over 4000 experiments of 12
    /// surrogates (the default) with the punches' noise of 32 punches (0.1 / 32),
    /// `spread - noise` averages the true s2 within 4 of its standard errors (measured
    /// within 0.1 of one, for s2 equal to, a quarter of and zero times the noise), and
    /// its stated standard error matches its observed scatter within 15 % (measured
    /// 4 % high); with no spectrum part, the part is called resolved in at most 20 % of
    /// the experiments (measured 14 %: a one-sided one-standard-error test). How often
    /// a real part is found at 12 surrogates: 53 % of the experiments where it equals
    /// the noise, 24 % at a quarter of it.
    #[test]
    fn the_split_recovers_a_known_spectrum_variance() {
        let n2 = 0.1 / 32.0;
        for s2 in [n2, 0.25 * n2, 0.0] {
            let runs = experiments(s2, n2, 12, 4000);
            let (m, sd) = mean_sd(runs.iter().map(|r| r.spread - r.noise));
            let se = sd / (runs.len() as f64).sqrt();
            assert!((m - s2).abs() < 4.0 * se, "s2 {s2}: mean {m} +/- {se}");
            // The stated error at the true variances, against the observed scatter.
            let (stated, _) = mean_sd(runs.iter().map(|r| r.error));
            assert!(
                (stated / sd - 1.0).abs() < 0.15,
                "s2 {s2}: error {stated} against {sd}"
            );
            if s2 == 0.0 {
                let called = runs.iter().filter(|r| r.resolved).count() as f64;
                assert!(called / (runs.len() as f64) < 0.2, "resolved in {called}");
            }
        }
        // Well above the noise and with many surrogates, it is resolved every time.
        let runs = experiments(10.0 * n2, n2, 64, 200);
        assert!(runs.iter().all(|r| r.resolved));
        // Below three surrogates: undefined.
        let few = Split::of(&[0.1, 0.2], &[0.01, 0.01]);
        assert!(few.spread.is_nan() && !few.resolved);
    }
}
