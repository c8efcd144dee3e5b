//! The Hurst sweep (Section 9, Fig. 6): the same rough contact in 3D (bem3d, circular
//! rough punch) and in 1D (MRD rough lines), for Hurst exponents from -1 to 3.
//!
//! Set-up, with E* = 1 and punch diameter L = 1: a self-affine surface without
//! long-wavelength cut-off (C2D ~ q^(-2H-2) from q0 = 2 pi/L to q1 = ratio x pi/dx3,
//! ratio 0.25 by default so the shortest wavelength spans 8 cells, Eq. 70) is
//! synthesised on a `grid x grid` square of side L; the inscribed disc is the punch face
//! (mask). It is pressed, displacement-controlled and warm-started, from 1e-3 of the
//! full-contact approach to full contact, and the tangent stiffness k = dF/dd is
//! computed at each approach with the contact set fixed. The 1D line of length L, with
//! `C1D = pi q C2D` (Eq. 73) over the same band, is loaded on a fixed grid of reduced
//! forces. Both give k/(E* L) against f = F/(E* h L) (Eq. 77), h the rms height of the
//! punch face or of the line.
//!
//! Fit window (documented, plotted): ensemble-mean k/(E* L) in [3/grid, 0.3], i.e. from
//! a few cells in contact to well below saturation (k -> E* L); alpha and zeta by least
//! squares in log space, 95 % intervals by a bootstrap over realisations (200 resamples).
//!
//! lambda(H), Eq. (76) as written (C1D = lambda q C2D on the same C2D,
//! `outputs::lambda_meaning`): under Eq. (77) lambda only rescales the 1D heights, so
//! the 1D law in terms of the 3D surface's h is K1(f sqrt(pi / l)) with the shift
//! l = pi h1^2 / h3^2; l is the least-squares fit in log space of that curve to the 3D
//! one over the 3D fit window, and lambda is l over the rms factor of the spectrum on
//! the line and the punch face.
//!
//! Every task (one 3D realisation, or the whole 1D ensemble of one H) is checkpointed
//! atomically to `<out>.work/<key>/`; a killed run resumes from there, shards
//! (`--shard K/N`) compute disjoint task subsets, and results do not depend on thread
//! count, shard split or interruption.
//!
//! Files: [`tasks`] (the checkpointed work), [`fit`] (curves, fits, intervals, lambda),
//! [`aggregate`] (per-H results from the checkpoints), [`figures`].

mod aggregate;
mod figures;
mod kind;
pub mod tasks;

use serde::Deserialize;

/// Parameters of one sweep (an `[[outputs]]` entry of kind `hurst_sweep`).
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct HurstSweep {
    /// Hurst exponents, each in [-1, 3].
    pub hurst: Vec<f64>,
    /// 3D grid side (cells across the punch diameter).
    pub grid: usize,
    /// Extra, coarser grids for the convergence study of alpha (optional).
    #[serde(default)]
    pub convergence_grids: Vec<usize>,
    /// Upper cut-off q1 as a fraction of the 3D grid's Nyquist wavenumber pi/dx. The
    /// default 0.25 resolves the shortest wavelength with 8 cells; at 0.5 (4 cells) the
    /// 3D alpha for H < 0 is biased low (64^2, H = -0.5: 0.55 against MRD's 0.74; at 0.25
    /// both give 0.62).
    #[serde(default = "quarter")]
    pub upper_cutoff_ratio: f64,
    /// Rough surfaces solved in 3D (independent realisations of the spectrum).
    pub realisations_3d: u64,
    /// MRD rough lines (independent realisations, C1D = lambda q C2D) behind each MRD
    /// curve.
    pub realisations_1d: u64,
    /// 1D points per 3D cell across (N1 = factor x grid).
    #[serde(default = "crate::checks::default_count::<16>")]
    pub points_1d_factor: usize,
    /// Number of approaches per 3D realisation.
    #[serde(default = "crate::checks::default_count::<20>")]
    pub loads: usize,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    pub seed: u64,
    /// 3D solver tolerance (see bem3d::solver).
    #[serde(default = "tol")]
    pub tolerance: f64,
}

fn quarter() -> f64 {
    0.25
}
fn tol() -> f64 {
    1e-8
}

impl HurstSweep {
    /// The 3D grids: the main one first, then the convergence grids.
    fn grids(&self) -> Vec<usize> {
        let mut g = vec![self.grid];
        g.extend(
            self.convergence_grids
                .iter()
                .copied()
                .filter(|&x| x != self.grid),
        );
        g
    }

    /// Reduced forces at which the 1D lines are loaded and all curves are compared.
    fn f_grid(&self) -> Vec<f64> {
        mrd::friction::log_space(1e-7, 1e2, 91)
    }

    /// The fit window in k/(E* L): a few cells in contact to well below saturation.
    fn window(&self, grid: usize) -> (f64, f64) {
        (3.0 / grid as f64, 0.3)
    }
}
