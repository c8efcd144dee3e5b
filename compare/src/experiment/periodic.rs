//! Periodic self-affine patches for the 3D studies of rough contact on the periodic
//! half-space: C2D ~ q^(-2H-2) from the period L = 1 down to the shortest wavelength
//! L / `bandwidth`, nested synthesis (a finer grid samples the same surface), and the
//! patch's rms slope h' (the same for every realisation: the modes' amplitudes are fixed,
//! their phases random), the scale of the reduced pressure p / (E* h').

use crate::checks::{bad, check_memory_per_thread, count_in, MAX_REALISATIONS};
use crate::error::{Context as _, Result};
use bem3d::{ContactSolver, Load, PeriodicHalfSpace, Solution, SolverOptions};
use mrd::roughness::synthesis::Grid;
use mrd::roughness::{nested, SelfAffine};
use rayon::prelude::*;
use std::f64::consts::PI;

/// One realisation: heights (`n x n`, row-major) and the rms slope of the band.
pub struct Patch {
    pub heights: Vec<f64>,
    pub rms_slope: f64,
}

/// Realisation `r` of the patch of Hurst exponent `hurst` on `n x n` cells.
pub fn patch(hurst: f64, bandwidth: usize, n: usize, seed: u64, r: u64) -> Result<Patch> {
    let q0 = 2.0 * PI;
    let sa = SelfAffine::new(hurst, q0, q0, q0 * (bandwidth as f64 + 2.0)).ctx("spectrum")?;
    let c2d = |q: f64| sa.c2d(q);
    let heights =
        nested::surface(&c2d, bandwidth, &Grid::square(n, 1.0), seed, r).ctx("3D surface")?;
    Ok(Patch {
        heights,
        rms_slope: rms_slope(c2d, bandwidth),
    })
}

/// One realisation of a ladder ready to solve: the grid's side `n`, the patch, its
/// periodic normal solver and the options of its solves.
pub struct Realisation {
    pub n: usize,
    pub patch: Patch,
    pub solver: ContactSolver<PeriodicHalfSpace>,
    pub opts: SolverOptions,
}

impl Realisation {
    /// The normal solve at total force `force` (warm-started from `warm` when given) and
    /// its tangent stiffness dF/dd.
    pub fn normal_at(&mut self, force: f64, warm: Option<&Solution>) -> Result<(Solution, f64)> {
        let sol = self
            .solver
            .solve(Load::Force(force), &self.opts, warm)
            .ctx("3D normal solve")?;
        let kn = self
            .solver
            .tangent_stiffness(&sol, &self.opts)
            .ctx("3D normal stiffness")?;
        Ok((sol, kn))
    }
}

/// The ensembles of a study on periodic patches: Hurst exponents, the substrates'
/// Poisson's ratios, the band, a ladder of cells per shortest wavelength (the same
/// surfaces on each grid) and the realisations of each.
pub struct Ladder<'a> {
    pub hurst: &'a [f64],
    pub poisson: &'a [f64],
    pub bandwidth: usize,
    pub cells: &'a [usize],
    pub realisations: u64,
    /// The seed of the surfaces (realisation r is the same surface on every grid).
    pub seed: u64,
}

/// One ensemble of a ladder: (Hurst exponent, cells per shortest wavelength, the runs
/// of its realisations in order).
pub type Ensemble<R> = (f64, usize, Vec<R>);

impl Ladder<'_> {
    /// Checks the keys (ranges named as the scene spells them) and the memory of one
    /// finest grid per thread at `bytes_per_cell` (the study's entry of
    /// [`crate::checks::cell_bytes`]). Returns the finest grid's side.
    pub fn check(&self, bytes_per_cell: f64) -> Result<usize> {
        if self.hurst.is_empty() || self.poisson.is_empty() {
            return bad("hurst and poisson need at least one entry each");
        }
        if let Some(h) = self.hurst.iter().find(|h| !(0.0..=1.0).contains(*h)) {
            return bad(format!("hurst = {h} must lie in [0, 1]"));
        }
        if let Some(nu) = self.poisson.iter().find(|n| !(0.0..=0.5).contains(*n)) {
            return bad(format!("poisson = {nu} must lie in [0, 0.5]"));
        }
        count_in("bandwidth", self.bandwidth as u64, 2..=512)?;
        if self.cells.is_empty() || self.cells.windows(2).any(|w| w[1] <= w[0]) {
            return bad(format!(
                "cells = {:?}: give increasing cells per shortest wavelength",
                self.cells
            ));
        }
        for &c in self.cells {
            count_in("cells", c as u64, 2..=256)?;
            count_in("cells x bandwidth", (c * self.bandwidth) as u64, 8..=4096)?;
        }
        count_in("realisations", self.realisations, 2..=MAX_REALISATIONS)?;
        let n = self.cells.last().copied().unwrap_or(2) * self.bandwidth;
        check_memory_per_thread(
            (n * n) as f64 * bytes_per_cell,
            &format!("3D grids of {n}^2 cells, one per thread"),
        )?;
        Ok(n)
    }

    /// Realisation `r` of Hurst exponent `hurst` at `cells` per shortest wavelength on a
    /// substrate of modulus `e_star`, solved to `tolerance`.
    pub fn realise(
        &self,
        hurst: f64,
        cells: usize,
        r: u64,
        e_star: f64,
        tolerance: f64,
    ) -> Result<Realisation> {
        let n = cells * self.bandwidth;
        let patch = patch(hurst, self.bandwidth, n, self.seed, r)?;
        let op = PeriodicHalfSpace::new(n, n, 1.0, 1.0, e_star);
        let solver = ContactSolver::new(op, &patch.heights, None).ctx("3D solver set-up")?;
        Ok(Realisation {
            n,
            patch,
            solver,
            opts: super::solve_options(tolerance, n),
        })
    }

    /// `run(hurst, cells, realisation)` over every ensemble, realisations in parallel
    /// (collected in order: the same results for any thread count).
    pub fn run<R: Send>(
        &self,
        run: impl Fn(f64, usize, u64) -> Result<R> + Sync,
    ) -> Result<Vec<Ensemble<R>>> {
        let mut all = Vec::new();
        for &h in self.hurst {
            for &cells in self.cells {
                let ens = (0..self.realisations)
                    .into_par_iter()
                    .map(|r| run(h, cells, r))
                    .collect::<Result<Vec<_>>>()?;
                all.push((h, cells, ens));
            }
        }
        Ok(all)
    }
}

/// The rms slope of the nested surfaces of `c2d` cut at `band`: the sum over the wave
/// vectors 0 < |k| <= band of (2 pi / L)^2 C2D(q) q^2, L = 1.
fn rms_slope(c2d: impl Fn(f64) -> f64, band: usize) -> f64 {
    let b = band as i64;
    let dq = 2.0 * PI;
    let mut sum = 0.0;
    for i in -b..=b {
        for j in -b..=b {
            let k2 = (i * i + j * j) as f64;
            if k2 > 0.0 && k2 <= (b * b) as f64 {
                let q = dq * k2.sqrt();
                sum += dq * dq * c2d(q) * q * q;
            }
        }
    }
    sum.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rms_slope_is_the_sampled_surfaces() {
        // Forward differences underestimate the slope of the finest modes; at 16 cells
        // per shortest wavelength the sampled slope is within 2 % of the band's.
        let p = patch(0.5, 8, 128, 3, 0).unwrap();
        let n = 128;
        let h = 1.0 / n as f64;
        let mut s = 0.0;
        for j in 0..n {
            for i in 0..n {
                let c = j * n + i;
                let gx = (p.heights[j * n + (i + 1) % n] - p.heights[c]) / h;
                let gy = (p.heights[((j + 1) % n) * n + i] - p.heights[c]) / h;
                s += gx * gx + gy * gy;
            }
        }
        let sampled = (s / (n * n) as f64).sqrt();
        assert!(
            (sampled / p.rms_slope - 1.0).abs() < 0.02,
            "{sampled} {}",
            p.rms_slope
        );
    }
}
