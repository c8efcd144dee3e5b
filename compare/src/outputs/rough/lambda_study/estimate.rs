//! A value with its 95 % interval, and the bootstrap of a coefficient of variation: the
//! estimates that the study's analysis, scatter and approach parts share.

use crate::experiment::fit::interval;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// A value with its 95 % interval (NaN where undefined).
#[derive(Debug, Clone, Copy)]
pub struct Estimate {
    pub value: f64,
    pub lo: f64,
    pub hi: f64,
}

impl Estimate {
    pub(super) const NONE: Estimate = Estimate {
        value: f64::NAN,
        lo: f64::NAN,
        hi: f64::NAN,
    };

    pub(super) fn of(value: Option<f64>, boot: Vec<f64>) -> Self {
        let (lo, hi) = interval(boot);
        Self {
            value: value.unwrap_or(f64::NAN),
            lo,
            hi,
        }
    }

    /// The estimate and its interval times `factor` (> 0).
    pub(super) fn scaled(self, factor: f64) -> Self {
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
}

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
