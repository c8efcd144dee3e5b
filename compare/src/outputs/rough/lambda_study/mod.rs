//! `lambda_study`: lambda(H) of Eq. (76) and alpha(H) of Eq. (77) converged in every
//! numerical parameter: the Hurst sweep's rough punch (see `hurst_sweep`) at a ladder of
//! bandwidths L / lambda_min, with a resolution check (cells per shortest wavelength), a
//! solver-tolerance check and realisations added until lambda's bootstrap interval meets
//! a target.
//!
//! Set-up, with E* = 1 and punch diameter L = 1: a self-affine spectrum C2D ~ q^(-2H-2)
//! from q0 = 2 pi / L (no roll-off) up to the bandwidth B (wave vectors |k| <= B in units
//! of 2 pi / L, so L / lambda_min = B), synthesised on a square of `cells x B` cells a
//! side. Surfaces are nested (`mrd::roughness::nested`): realisation r is one surface
//! whatever B and the grid, its modes shared by every band that holds them, so
//! differences between bandwidths, resolutions and tolerances are paired and carry no
//! sampling noise of the shared modes. MRD lines (C1D = pi q C2D, Eq. 73) are nested
//! the same way, on `points_1d_per_cell x cells x B` points.
//!
//! lambda: Eq. (76) as written, C1D = lambda q C2D at the line's wavenumbers from the
//! same C2D as the surface (`outputs::lambda_meaning`). Each side's curve is reduced by
//! its own rms height (f = F/(E* h L)), and under Eq. (77) lambda only rescales the 1D
//! heights, so the MRD law is K1(f sqrt(pi / l)), K1 the lambda = pi curve reduced by the
//! line's rms and l = pi h1^2 / h3^2 the shift; l minimises the log-space misfit to the
//! 3D ensemble mean over every f where the 3D mean lies in the window k/(E* L) in
//! [window[0], window[1]] (the whole common range, not one point), and lambda is l over
//! the case's rms factor (pi h1^2 / h3^2 per unit lambda on the line and the punch face,
//! from the spectrum: 1.005-1.53 from H = -1 to 3 at bandwidth 128). The adaptive plan
//! tests l (the same relative widths and ratios within a bandwidth). The residual misfit max and rms |Delta ln k| over that range is what MRD with
//! the calibrated lambda gets wrong. Intervals: 95 % bootstrap over realisations (200
//! resamples; paired comparisons resample the realisations the two cases share and use
//! their plain means, the pairing taking the place of the control variates, and fit both
//! cases on the same f points, where both means lie in the window). A resample is fitted
//! on the points of the full sample's mean: a resampled mean leaves realisations out and
//! so reaches further along f, and points chosen afresh would change the quantity.
//!
//! Realisations: every case computes `realisations.min`; a case of the main ladder at or
//! below `calibrate_at` adds batches of `realisations.batch` (up to `realisations.max`)
//! while its lambda interval is wider than the target of its H (`target`: pairs
//! [H_max, relative half-width]). A bandwidth above `calibrate_at` asks only whether
//! lambda moves from there: it starts with 8 realisations and adds 4 at a time (up to
//! `realisations.min`) until the paired ratio's interval lies inside 1 +/- target or
//! wholly outside it. Decisions use complete batches only, so results do not depend on
//! the order of work, threads or interruptions.
//!
//! Files: [`tasks`] (cases, the adaptive plan, the checkpointed work), [`analysis`]
//! (curves, fits, lambda, pairs), [`scatter`] (the scatter between realisations, 3D
//! against MRD: of k at fixed force, and in [`approach`] of F at fixed approach),
//! [`report`] (tables and figures).

pub mod analysis;
mod approach;
mod estimate;
mod kind;
mod report;
mod scatter;
mod schedule;
pub mod tasks;

use crate::checks::bad;
use crate::error::Result;
use crate::experiment::tasks::Realisations;
use serde::Deserialize;

/// Parameters of a study (an `[[outputs]]` entry of kind `lambda_study`).
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LambdaStudy {
    /// Hurst exponents, each in [-1, 3].
    pub hurst: Vec<f64>,
    /// The main ladder of bandwidths L / lambda_min.
    pub bandwidths: Vec<usize>,
    /// Cells per shortest wavelength on the main ladder.
    #[serde(default = "crate::checks::default_count::<8>")]
    pub cells: usize,
    /// The bandwidth whose lambda is shipped (one of `bandwidths`).
    pub calibrate_at: usize,
    /// Further bandwidths for some H (paired with the main ladder).
    #[serde(default)]
    pub extra: Vec<Extra>,
    /// Other cells per shortest wavelength at one bandwidth, for every H.
    pub resolution: Option<Resolution>,
    /// A second solver tolerance at `calibrate_at` for one H.
    pub tolerance_check: Option<ToleranceCheck>,
    /// The scatter between realisations (Section 9) on the main ladder at one
    /// bandwidth, with at least this many realisations per H there.
    pub scatter: Option<ScatterAt>,
    /// The largest grid's accuracy check: at one H and bandwidth, a few realisations at
    /// twice `cells` and at a second tolerance, paired with that bandwidth's case.
    pub top_check: Option<TopCheck>,
    /// Realisations of the MRD lines: { min, max, batch }: batches while the interval is
    /// wider than its target.
    pub realisations: Realisations,
    /// [H_max, relative half-width] pairs, H_max ascending: the target of lambda's 95 %
    /// interval for H <= H_max.
    #[serde(default = "targets")]
    pub target: Vec<[f64; 2]>,
    /// MRD lines per H and bandwidth.
    pub realisations_1d: u64,
    /// Surfaces per case grid (no solve) for the expectations of the control variates.
    #[serde(default = "crate::checks::default_count_u64::<2000>")]
    pub control_realisations: u64,
    /// Fewer control surfaces on large grids, where each costs a synthesis of the whole
    /// grid: `[side, m]` gives grids of at least `side` cells a side `m` surfaces (their
    /// expectations then carry an error still far below the one of the solved
    /// realisations' mean).
    pub control_realisations_large: Option<[u64; 2]>,
    /// The calibration and fit range in k/(E* L).
    #[serde(default = "window")]
    pub window: [f64; 2],
    /// Approaches per 3D realisation.
    #[serde(default = "crate::checks::default_count::<20>")]
    pub loads: usize,
    /// 3D solver tolerance (bem3d::solver).
    #[serde(default = "tolerance")]
    pub tolerance: f64,
    /// MRD points per 3D cell across.
    #[serde(default = "crate::checks::default_count::<16>")]
    pub points_1d_per_cell: usize,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    pub seed: u64,
}

#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Extra {
    pub bandwidth: usize,
    pub hurst: Vec<f64>,
}

#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Resolution {
    pub bandwidth: usize,
    pub cells: Vec<usize>,
}

#[derive(Debug, Clone, Copy, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TopCheck {
    pub hurst: f64,
    pub bandwidth: usize,
    pub tolerance: f64,
    pub realisations: u64,
}

#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ToleranceCheck {
    pub hurst: f64,
    pub tolerance: f64,
}

#[derive(Debug, Clone, Copy, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ScatterAt {
    pub bandwidth: usize,
    pub realisations: u64,
}

fn tolerance() -> f64 {
    1e-8
}
fn window() -> [f64; 2] {
    [0.02, 0.5]
}
fn targets() -> Vec<[f64; 2]> {
    vec![[1.5, 0.10], [3.0, 0.20]]
}

impl LambdaStudy {
    /// Control surfaces of a case's grid (`control_realisations`, or the large grids'
    /// count).
    pub fn control_count(&self, grid: usize) -> u64 {
        match self.control_realisations_large {
            Some([side, m]) if grid as u64 >= side => m,
            _ => self.control_realisations,
        }
    }

    /// The target relative half-width of lambda's interval at `hurst`.
    pub fn target_at(&self, hurst: f64) -> f64 {
        self.target
            .iter()
            .find(|t| hurst <= t[0])
            .map_or(f64::INFINITY, |t| t[1])
    }

    /// Reduced forces f = F/(E* h L) of the common grid of every curve.
    pub fn f_grid(&self) -> Vec<f64> {
        mrd::friction::log_space(1e-7, 1e2, 91)
    }

    /// Reduced approaches u = (rigid indentation past the mean height) / h of the
    /// scatter of F at fixed approach: -4 to 4 in steps of 1/8.
    pub fn approach_grid(&self) -> Vec<f64> {
        (-32..=32).map(|i| i as f64 / 8.0).collect()
    }

    /// A bandwidth `b` run at `cells` per shortest wavelength; `what` names the keys
    /// that set them, for the messages (`cells` may be derived, as `top_check`'s
    /// doubled cells are).
    fn check_band(&self, b: usize, cells: usize, what: &str) -> Result<()> {
        if !(8..=1024).contains(&b) {
            return bad(format!("bandwidth {b} must lie in 8..=1024"));
        }
        if !(3..=32).contains(&cells) {
            return bad(format!(
                "{what}: {cells} cells per wavelength, outside 3..=32"
            ));
        }
        let g = b * cells;
        if g > 8192 {
            return bad(format!(
                "bandwidth {b} at {cells} cells per wavelength needs a {g}^2 grid: at most 8192"
            ));
        }
        // One 3D task per worker thread at a time.
        crate::checks::check_memory_per_thread(
            (g * g) as f64 * crate::checks::cell_bytes::ROUGH_FREE,
            &format!("bandwidth {b} at {cells} cells ({g}^2)"),
        )
    }
}
