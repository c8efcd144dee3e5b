//! The bootstrap of a coefficient of variation, its figures and its agreement tally,
//! which the study's scatter and approach parts share (an [`Estimate`] is the
//! experiment layer's).

use super::tasks::Case;
use crate::experiment::fit::interval;
use crate::experiment::fit::Estimate;
use crate::report::{Figure, Series, Style};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// The table columns of a 3D CV and MRD's, each with its 95 % interval.
pub(super) const CV_COLUMNS: &[&str] = &[
    "cv_3d [1]",
    "cv_3d_lo95 [1]",
    "cv_3d_hi95 [1]",
    "cv_mrd [1]",
    "cv_mrd_lo95 [1]",
    "cv_mrd_hi95 [1]",
];

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

/// The CV figures of a scatter part: one panel for H <= 0.5 and one above, so that no
/// band hides another; per H the 3D CVs with their intervals (crosses and bars) and
/// MRD's line.
pub(super) struct CvPanels {
    figures: [Figure; 2],
    log_y: bool,
}

impl CvPanels {
    /// `title(what)` names a panel from its range of H.
    pub(super) fn new(
        stem: &str,
        title: impl Fn(&str) -> String,
        x_label: &str,
        y_label: &str,
        log_y: bool,
    ) -> Self {
        let panel = |name: &str, what: &str| {
            let mut f = Figure::new(&format!("{stem}_{name}"), &title(what), x_label, y_label);
            f.log_x = true;
            f.log_y = log_y;
            f
        };
        Self {
            figures: [panel("low_h", "H <= 0.5"), panel("high_h", "H > 0.5")],
            log_y,
        }
    }

    /// The series of case `i` (its colour): `three` at 3D's abscissae, `mrd` at MRD's.
    /// On a logarithmic CV axis a point (a bar) is drawn where its value (its lower
    /// end) is positive.
    pub(super) fn add(
        &mut self,
        i: usize,
        case: &Case,
        realisations: usize,
        three: &[(f64, Estimate)],
        mrd: Vec<(f64, f64)>,
    ) {
        let log_y = self.log_y;
        let fig = &mut self.figures[(case.hurst > 0.5) as usize];
        let drawn = |v: f64| !log_y || v > 0.0;
        fig.series.push(
            Series::new(
                format!(
                    "3D, H = {} (B {}, n = {realisations})",
                    case.hurst, case.band
                ),
                three
                    .iter()
                    .filter(|p| drawn(p.1.value))
                    .map(|p| (p.0, p.1.value))
                    .collect(),
                Style::Crosses,
            )
            .with_bars(
                three
                    .iter()
                    .filter(|p| drawn(p.1.lo))
                    .map(|p| (p.0, p.1.lo, p.1.hi))
                    .collect(),
            )
            .colored(i),
        );
        fig.series
            .push(Series::new(format!("MRD, H = {}", case.hurst), mrd, Style::Line).colored(i));
    }

    /// The panels that have series.
    pub(super) fn into_figures(self) -> impl Iterator<Item = Figure> {
        self.figures.into_iter().filter(|f| !f.series.is_empty())
    }
}

/// MRD's CV against 3D's at the points of the calibration window: the largest
/// |CV_MRD / CV_3D - 1| and how many of the intervals overlap.
#[derive(Default)]
pub(super) struct Agreement {
    pub(super) worst: f64,
    pub(super) overlap: usize,
    pub(super) count: usize,
}

impl Agreement {
    /// One point, 3D's `three` (CV > 0) against MRD's `mrd`.
    pub(super) fn add(&mut self, three: &Estimate, mrd: &Estimate) {
        self.worst = self.worst.max((mrd.value / three.value - 1.0).abs());
        self.overlap += (three.lo <= mrd.hi && mrd.lo <= three.hi) as usize;
        self.count += 1;
    }

    /// "k of n" intervals overlap.
    pub(super) fn overlaps(&self) -> String {
        format!("{} of {}", self.overlap, self.count)
    }
}
