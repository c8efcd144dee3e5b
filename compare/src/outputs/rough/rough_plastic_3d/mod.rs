//! `rough_plastic_3d`: the review's Section 11 question on rough surfaces: does MRD in
//! incremental form reproduce an elastic-perfectly plastic rough contact? A rigid flat
//! punch of diameter L with a self-affine rough face (Section 9's rough punch, Pohrt &
//! Popov) is loaded, unloaded and reloaded on a half-space whose pressure saturates at
//! the hardness H, in 3D (`bem3d::plastic`, the face on a free grid) and by MRD (rough
//! lines with C1D = lambda q C2D on springs capped patch by patch,
//! `mrd::plastic_line`), at plasticity indices psi = E* h'_rms / H from elastic to
//! mostly plastic, side by side:
//!
//! - the loading stiffness k = dF/dd (secants of the force ladder) against the force,
//!   its MRD / 3D ratio against psi, beside the elastic case's;
//! - the unloading stiffness at the peak and the approach recovered on unloading;
//! - lambda refitted at each psi (the lambda whose lines give the 3D loading stiffness),
//!   with its interval, against the elastic case's;
//! - the 3D contact and plastic fractions, and `H A / F` (1 in the fully plastic limit).
//!
//! Units: E* = 1, L = 1; forces reduced as f = F / (E* h L), h the face spectrum's rms
//! height over the square (the lattice sum of its modes), psi with its spectral rms
//! slope h'. The pressure-cap model is that of `plastic_3d` (Tamaas' saturated solver's).

mod report;
mod runs;

use crate::checks::{bad, count_in, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::lambda::LambdaSpec;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::Section;
use mrd::roughness::nested;
use mrd::roughness::synthesis::Grid;
use rayon::prelude::*;
use serde::Deserialize;
use std::f64::consts::{FRAC_1_SQRT_2, PI, SQRT_2};

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoughPlastic3d {
    /// Hurst exponent of the self-affine face (no roll-off), in [0, 1].
    #[serde(default = "default_hurst")]
    hurst: f64,
    /// Bandwidth B: the face's wave vectors 1 <= |k| <= B in units of 2 pi / L.
    #[serde(default = "crate::checks::default_count::<16>")]
    bandwidth: usize,
    /// 3D cells per shortest wavelength, coarse to fine (the grid's side is B times it).
    #[serde(default = "default_cells")]
    cells: Vec<usize>,
    /// Plasticity indices psi = E* h'_rms / H, increasing (the elastic case, psi = 0,
    /// is always run).
    plasticity: Vec<f64>,
    /// Smallest reduced force f = F / (E* h L) of the first loading.
    #[serde(default = "default_f_min")]
    f_min: f64,
    /// Largest reduced force (the peak of the history).
    #[serde(default = "default_f_max")]
    f_max: f64,
    /// Steps of the first loading, log-spaced from f_min to f_max (then the unloading
    /// to 0.9, 0.7, 0.5, 0.3, 0.2, 0.1, 0.05 and 0.02 of the peak and the reloading to
    /// 0.1, 0.3, 0.5, 0.7 and 1).
    #[serde(default = "crate::checks::default_count::<10>")]
    loads: usize,
    /// 3D punches (realisations of the face) per case.
    #[serde(default = "crate::checks::default_count_u64::<8>")]
    realisations_3d: u64,
    /// MRD lines per case.
    #[serde(default = "crate::checks::default_count_u64::<64>")]
    lines: u64,
    /// Springs of an MRD line.
    #[serde(default = "crate::checks::default_count::<2048>")]
    springs: usize,
    /// lambda of Eq. (76) of the MRD lines (the refit scans 0.5 to 2 times it); default
    /// "calibrated", the embedded table.
    #[serde(default = "calibrated")]
    lambda: LambdaSpec,
    /// Relative force tolerance of every step, 3D and MRD.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
    /// Seed of the faces and lines: the same seed gives the same realisations whatever
    /// the thread count.
    #[serde(default)]
    seed: u64,
}

fn default_hurst() -> f64 {
    0.8
}
fn default_cells() -> Vec<usize> {
    vec![4, 8]
}
fn default_f_min() -> f64 {
    1e-3
}
fn default_f_max() -> f64 {
    0.3
}
fn calibrated() -> LambdaSpec {
    LambdaSpec::Named("calibrated".into())
}

/// The history after the first loading, as fractions of the peak force.
const UNLOAD: [f64; 8] = [0.9, 0.7, 0.5, 0.3, 0.2, 0.1, 0.05, 0.02];
const RELOAD: [f64; 5] = [0.1, 0.3, 0.5, 0.7, 1.0];
/// Factors of lambda the refit scans (the lines' heights scale with its square root).
const REFIT: [f64; 5] = [0.5, FRAC_1_SQRT_2, 1.0, SQRT_2, 2.0];
/// rms slope of the face's spectrum (the pressure-cap problem is scale-free: psi and f
/// are what matter; a small slope keeps the half-space's linearisation honest).
const SLOPE: f64 = 0.1;

/// lambda refitted at one psi: (psi, the fit, its interval's ends), None outside the
/// scanned factors.
type Refit = (f64, Option<f64>, Option<f64>, Option<f64>);

/// One step of one punch or line.
#[derive(Debug, Clone, Copy, Default)]
struct Point {
    approach: f64,
    force: f64,
    /// Contact fraction of the face (3D: area over the disc's; MRD: springs in contact
    /// over all) and the plastic share of the contact (3D: cells at H; MRD: springs at
    /// their cap).
    contact: f64,
    plastic: f64,
}

/// What one history gives, the quantities compared.
#[derive(Debug, Clone)]
struct Reading {
    /// ln of the loading secant stiffness per interval of the first loading.
    ln_k: Vec<f64>,
    /// ln of the unloading stiffness at the peak (secant to 0.9 of it).
    ln_k_unload: f64,
    /// ln of the approach recovered from the peak to 0.02 of it.
    ln_recovery: f64,
    /// ln of the approach at the peak (from the first contact).
    ln_peak: f64,
    /// |d at the reloaded peak - d at the peak| / d at the peak.
    retrace: f64,
    points: Vec<Point>,
}

/// Mean and the half-width of its 95 % interval (1.96 s / sqrt(n)).
fn mean_ci(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (m, 1.96 * (var / n).sqrt())
}

impl Output for RoughPlastic3d {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if !(0.0..=1.0).contains(&self.hurst) {
            return bad(format!("hurst = {} must lie in [0, 1]", self.hurst));
        }
        count_in("bandwidth", self.bandwidth as u64, 2..=128)?;
        if self.cells.is_empty() || self.cells.windows(2).any(|w| w[1] <= w[0]) {
            return bad(format!(
                "cells = {:?}: give increasing cells per shortest wavelength",
                self.cells
            ));
        }
        for &c in &self.cells {
            count_in("cells", c as u64, 3..=64)?;
            count_in("bandwidth x cells", (c * self.bandwidth) as u64, 16..=1024)?;
        }
        if self.plasticity.is_empty()
            || self
                .plasticity
                .iter()
                .any(|p| !(p.is_finite() && *p > 0.0 && *p <= 1e3))
            || self.plasticity.windows(2).any(|w| w[1] <= w[0])
        {
            return bad(format!(
                "plasticity = {:?}: give increasing indices psi = E* h'_rms / H in (0, 1000] (the elastic case is always run)",
                self.plasticity
            ));
        }
        if !(self.f_min.is_finite() && self.f_min > 0.0 && self.f_min < self.f_max) {
            return bad(format!(
                "f_min = {}: must be > 0 and below f_max = {}",
                self.f_min, self.f_max
            ));
        }
        // The largest psi's fully plastic face carries H pi L^2 / 4: f_limit = (h' / h)
        // (pi / 4) / psi. The history must stay clear of it.
        let (h, slope) = self.moments()?;
        let psi = self.plasticity.last().copied().unwrap_or(1.0);
        let limit = slope / h * PI / 4.0 / psi;
        if !(self.f_max.is_finite() && self.f_max <= 0.5 * limit) {
            return bad(format!(
                "f_max = {}: must stay below half the fully plastic force of the largest plasticity = {psi}, f = {limit:.4e} (H pi L^2 / 4 over E* h L)",
                self.f_max
            ));
        }
        count_in("loads", self.loads as u64, 3..=200)?;
        count_in("realisations_3d", self.realisations_3d, 2..=100_000)?;
        count_in("lines", self.lines, 2..=1_000_000)?;
        count_in(
            "springs",
            self.springs as u64,
            (4 * self.bandwidth as u64)..=(1 << 20),
        )?;
        LambdaSpec::check_all(std::slice::from_ref(&self.lambda), ctx, &[self.hurst])?;
        crate::checks::check_tolerance(self.tolerance)?;
        if self.tolerance > 1e-2 {
            return bad(format!(
                "tolerance = {} must be <= 0.01 (the plastic steps' relative force tolerance)",
                self.tolerance
            ));
        }
        let g = self.bandwidth * self.cells.last().copied().unwrap_or(0);
        crate::checks::check_memory(
            (g * g) as f64 * crate::checks::cell_bytes::ROUGH_FREE,
            &format!("bandwidth x cells = {g}"),
        )
    }

    fn stages(&self, _ctx: &Context) -> Vec<Stage> {
        vec![Stage::RoughSynthesis, Stage::Plastic3d, Stage::PlasticMrd]
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let (h, slope) = self.moments()?;
        let lambda = self.lambda.build(env.ctx)?.at(self.hurst).ctx("lambda")?;
        let spectrum = self.spectrum()?;
        let c2d = |q: f64| spectrum.c2d(q);
        let forces = self.history();
        // psi = 0: the elastic case, H infinite.
        let cases: Vec<f64> = std::iter::once(0.0)
            .chain(self.plasticity.iter().copied())
            .collect();
        let hardness = |psi: f64| {
            if psi == 0.0 {
                f64::INFINITY
            } else {
                slope / psi
            }
        };
        // 3D: every (case, grid, realisation), in order.
        let faces: Vec<(usize, usize, u64)> = (0..cases.len())
            .flat_map(|c| {
                (0..self.cells.len())
                    .flat_map(move |g| (0..self.realisations_3d).map(move |r| (c, g, r)))
            })
            .collect();
        let three = out.stages_together(&[Stage::RoughSynthesis, Stage::Plastic3d], || {
            faces
                .par_iter()
                .map(|&(c, g, r)| {
                    let n = self.bandwidth * self.cells[g];
                    let z = crate::report::clock::time(Stage::RoughSynthesis, || {
                        nested::surface(&c2d, self.bandwidth, &Grid::square(n, 1.0), self.seed, r)
                    })
                    .ctx("3D face")?;
                    crate::report::clock::time(Stage::Plastic3d, || {
                        self.run_3d(&z, n, hardness(cases[c]), h, &forces)
                    })
                })
                .collect::<Result<Vec<Reading>>>()
        })?;
        // MRD: every (case, lambda factor, line), in order.
        let runs: Vec<(usize, usize, u64)> = (0..cases.len())
            .flat_map(|c| {
                (0..REFIT.len()).flat_map(move |k| (0..self.lines).map(move |r| (c, k, r)))
            })
            .collect();
        let c1d = |q: f64| lambda * q * spectrum.c2d(q);
        let mrd = out.stage(Stage::PlasticMrd, || {
            // Each line once: every case and lambda factor loads the same lines, scaled.
            let lines = (0..self.lines)
                .into_par_iter()
                .map(|r| nested::line(&c1d, self.bandwidth, self.springs, 1.0, self.seed, r))
                .collect::<mrd::Result<Vec<Vec<f64>>>>()
                .ctx("MRD line")?;
            runs.par_iter()
                .map(|&(c, k, r)| {
                    let z: Vec<f64> = lines[r as usize]
                        .iter()
                        .map(|v| v * REFIT[k].sqrt())
                        .collect();
                    self.run_mrd(&z, hardness(cases[c]), h, &forces)
                })
                .collect::<Result<Vec<Reading>>>()
        })?;
        let data = Data {
            cases,
            three,
            mrd,
            grids: self.cells.len(),
            faces: self.realisations_3d as usize,
            lines: self.lines as usize,
            lambda,
            h,
            slope,
            forces,
        };
        self.report(out, &data);
        Ok(())
    }
}

/// What the report reads: the cases (psi, 0 the elastic one), every run of each, and the
/// scales.
struct Data {
    cases: Vec<f64>,
    /// 3D runs by (case, grid, realisation), MRD runs by (case, lambda factor, line).
    three: Vec<Reading>,
    mrd: Vec<Reading>,
    grids: usize,
    faces: usize,
    lines: usize,
    lambda: f64,
    h: f64,
    slope: f64,
    forces: Vec<f64>,
}

impl Data {
    /// The 3D runs of case `c` on grid `g`.
    fn three(&self, c: usize, g: usize) -> &[Reading] {
        let start = (c * self.grids + g) * self.faces;
        &self.three[start..start + self.faces]
    }
    /// The MRD runs of case `c` at lambda factor `k`.
    fn mrd(&self, c: usize, k: usize) -> &[Reading] {
        let start = (c * REFIT.len() + k) * self.lines;
        &self.mrd[start..start + self.lines]
    }
}
