//! The bootstrap of a coefficient of variation, which the study's scatter and approach
//! parts share (an [`Estimate`] is the experiment layer's).

use crate::experiment::fit::interval;
use crate::experiment::fit::Estimate;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Bootstrap resamples of each CV.
pub(super) const RESAMPLES: usize = 400;

/// s / mean of `v` over the indices `idx` (sample standard deviation).
pub(super) fn cv(v: &[f64], idx: &[usize]) -> f64 {
    let n = idx.len() as f64;
    let m = idx.iter().map(|&i| v[i]).sum::<f64>() / n;
    let var = idx.iter().map(|&i| (v[i] - m).powi(2)).sum::<f64>() / (n - 1.0);
    var.sqrt() / m
}

pub(super) fn cv_estimate(v: &[f64], rng: &mut ChaCha8Rng) -> Estimate {
    let n = v.len();
    let all: Vec<usize> = (0..n).collect();
    let boot = (0..RESAMPLES)
        .map(|_| {
            let idx: Vec<usize> = (0..n).map(|_| rng.random_range(0..n)).collect();
            cv(v, &idx)
        })
        .collect();
    let (lo, hi) = interval(boot);
    Estimate {
        value: cv(v, &all),
        lo,
        hi,
    }
}
