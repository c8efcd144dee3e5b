//! Small contact sets: the solve restricted to a candidate set C of cells, K between them
//! as a dense matrix ([`RealSpace::restricted`](crate::operator::RealSpace::restricted)),
//! inside an outer loop that grows C until no cell outside it interpenetrates.
//!
//! At a contact fraction of 0.1 % a 1024^2 grid has about a thousand cells in contact,
//! and an application of `K_CC` (C: a few thousand cells) costs a fraction of a
//! full-grid convolution. Each round solves the contact problem on C with the same
//! projected conjugate-gradient iteration (unpreconditioned: a dense operator has no
//! spectral form), scatters the pressure to the grid, applies K on the whole grid once
//! (FFT) and evaluates the solver's criterion there: converged, or the cells outside C
//! with negative gap join C (the deepest first, at most doubling C per round: a set
//! much too small carries the load on too few cells, and the overlap it leaves spreads
//! far beyond the contact). Rounds solve to a loose tolerance while C still changes
//! much, then to the requested one. The reported solution is checked on the full grid
//! like any other. The attempt is given up, and the full solve runs from its own start
//! as it did before, when the set outgrows the limit (or half the overlap outside it
//! would), or an inner solve does not converge.
//!
//! The matrix streams from memory at every application once it outgrows the cache
//! (1024^2 at 0.1 %: about 2200 cells, 38 MiB). From `SINGLE_COPY_MIN` (1024) cells on
//! it gets a copy in single precision for the iteration's K t (products and sums in
//! double precision: half the bytes), while K p stays in double precision and is
//! recomputed at the residuals where the full grid's single-precision K is left
//! (solver module docs). A grown set's matrix and copy are built in the last ones'
//! storage (their pages already mapped), and the point-load corrections run row by row
//! in parallel (each row's entries in the loads' order, the same sums as column by
//! column, where the first iterations' few hundred changes cost five applications).
//! Measured on the 1024^2 benchmark surface at 0.1 % contact (cold
//! processes, interleaved, medians of 14-20): 1.16x on two threads and 1.07x on one
//! with the storage and the point loads, 1.29x and 1.15x with the copy too; the same
//! 66 iterations, pressures within 6e-13 of the peak. With the copy forced on smaller
//! sets (256^2 and 512^2 at 0.1 %): the same iterations, pressures within 1.3e-11 and
//! 1.6e-11 of the peak, but 512^2 5-10 % slower (its matrix stays in cache), hence the
//! limit. Below the limit the solutions are the same bit for bit (512^2: 1.02x on two
//! threads, 1.04x on one, with the point loads and the storage).

use super::iteration::{Refresh, Start};
use super::{ContactSolver, Path, Solution, SolverOptions};
use crate::operator::{DenseCompliance, SolverOperator};
use rayon::prelude::*;

/// The restricted start covers this many times `p / (E* h')` of the domain (the full
/// solve's start covers [`super::start::FULL_GRID_START_AREA`] times; a smaller set is
/// cheaper here, and
/// the rounds add what it misses).
const CANDIDATE_START_AREA: f64 = 4.0;
/// Largest candidate set: this many times the square root of the domain's cell count
/// (a dense application then costs at most about 9 domain sweeps) ...
const CELLS_PER_ROOT: f64 = 3.0;
/// ... and at most this many cells (a 128 MiB matrix).
const MAX_CELLS: usize = 4096;
/// Tolerance of the rounds while C (or a window) may still grow.
pub(super) const LOOSE: f64 = 1e-4;
const MAX_ROUNDS: usize = 24;
/// Cells a round may add at least (else: as many as the set holds).
const MIN_GROWTH: usize = 64;

/// Options of a round on part of the grid (a candidate set or a window): [`LOOSE`]
/// while the part may still grow, else half the requested tolerance (the grid's K p
/// differs from the part's by rounding); the iterations left of `opts` after `spent`.
pub(super) fn round_options(opts: &SolverOptions, tight: bool, spent: usize) -> SolverOptions {
    SolverOptions {
        tolerance: if tight {
            0.5 * opts.tolerance
        } else {
            opts.tolerance.max(LOOSE)
        },
        max_iterations: opts.max_iterations.saturating_sub(spent).max(1),
        ..opts.clone()
    }
}

/// The iterations of a restricted solve's rounds, summed.
#[derive(Debug, Default)]
pub(super) struct Tally {
    pub(super) iterations: usize,
    pub(super) single: usize,
    pub(super) stencil: usize,
    /// Whether any round stored its directions scaled.
    pub(super) scaled: bool,
}

impl Tally {
    pub(super) fn add(&mut self, sol: &Solution) {
        self.iterations += sol.iterations;
        self.single += sol.single_iterations;
        self.stencil += sol.stencil_iterations;
        self.scaled |= sol.scaled_directions;
    }
}

impl<K: SolverOperator> ContactSolver<K> {
    /// Restricted solve from a cold start (module docs), under force control
    /// (`target_force` > 0) or at the approach `fixed_approach` > 0. Err: why it does
    /// not apply or was given up (the full iteration then runs from its own start,
    /// unless the candidate set is forced: then its limit is [`MAX_CELLS`] alone and the
    /// reason is the solve's error).
    pub(super) fn solve_restricted(
        &mut self,
        target_force: Option<f64>,
        fixed_approach: f64,
        opts: &SolverOptions,
    ) -> Result<Solution, String> {
        let n = self.op.cells();
        let limit = if opts.paths.candidate_set.forced() {
            MAX_CELLS
        } else {
            ((CELLS_PER_ROOT * (self.problem.domain_cells as f64).sqrt()) as usize).min(MAX_CELLS)
        };
        let too_many =
            |cells: usize| format!("a set of {cells} cells exceeds the limit of {limit}");
        let (mut p, mut cells) = self.candidate_start(target_force, fixed_approach, limit)?;
        let (hx, hy) = (
            self.op.lx() / self.op.nx() as f64,
            self.op.ly() / self.op.ny() as f64,
        );
        let mut member = vec![false; n];
        let mut tally = Tally::default();
        let mut tight = false;
        // The solver on the current set (kept while the set holds), and whether the set
        // changed since it was built (its matrix's storage then serves the next one).
        let mut inner: Option<ContactSolver<DenseCompliance>> = None;
        let mut grown = true;
        for _ in 0..MAX_ROUNDS {
            if grown {
                grown = false;
                cells.iter().for_each(|&i| member[i] = true);
                let (buffer, single) = inner
                    .take()
                    .map(|s| s.op.into_storage())
                    .unwrap_or_default();
                let matrix = self
                    .op
                    .restricted(&cells, buffer)
                    .ok_or("the operator has no real-space table")?;
                let e_star = self.op.e_star();
                let dense =
                    DenseCompliance::from_matrix(cells.len(), (hx, hy), e_star, matrix, single);
                let z = cells.iter().map(|&i| self.problem.z[i]).collect();
                let (h_rms, stiffness) = (self.problem.h_rms, self.problem.overlap_stiffness);
                inner = Some(ContactSolver::on_part(dense, None, z, h_rms, stiffness));
            }
            let Some(solver) = inner.as_mut() else {
                return Err("no candidate set was built".into());
            };
            let inner_opts = round_options(opts, tight, tally.iterations);
            let start = cells.iter().map(|&i| p[i]).collect();
            let sol = match solver.iterate(
                start,
                target_force,
                fixed_approach,
                &inner_opts,
                Start::default(),
            ) {
                Ok(sol) => sol,
                // The full iteration takes over (and reports its own failure, if any).
                Err(e) => return Err(format!("a round on the candidate set failed: {e}")),
            };
            tally.add(&sol);
            p.par_iter_mut().for_each(|v| *v = 0.0);
            cells
                .iter()
                .zip(&sol.pressure)
                .for_each(|(&i, &v)| p[i] = v);
            let (approach, residual) = match self.on_grid(
                &mut p,
                target_force,
                fixed_approach,
                (&tally, Path::CandidateSet),
                opts,
            ) {
                Ok(sol) => return Ok(sol),
                Err(found) => found,
            };
            let (w, mask) = (&self.work.w, &self.problem.mask);
            let mut entering: Vec<(f64, usize)> = (0..n)
                .into_par_iter()
                .filter(|&i| mask.holds(i) && !member[i] && w[i] - approach < 0.0)
                .map(|i| (w[i] - approach, i))
                .collect();
            // A set much too small carries the load on too few cells: the approach
            // overshoots and the overlap spreads far beyond the contact (for a sphere
            // the overlap at the right approach covers twice the contact already).
            // Give up when even half the overlap would not fit; else the deepest cells
            // join first, at most doubling the set per round.
            if cells.len() + entering.len() / 2 > limit {
                return Err(too_many(cells.len() + entering.len() / 2));
            }
            let room = cells.len().max(MIN_GROWTH);
            if entering.len() > room {
                entering
                    .select_nth_unstable_by(room, |a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                entering.truncate(room);
            }
            if entering.is_empty() {
                if tight {
                    return Err(format!(
                        "a round at the tolerance left the criterion at {residual:.2e} on the grid"
                    ));
                }
                tight = true;
                continue;
            }
            cells.extend(entering.iter().map(|&(_, i)| i));
            cells.sort_unstable();
            grown = true;
            if cells.len() > limit {
                return Err(too_many(cells.len()));
            }
            // Near the answer already: the next rounds solve to the tolerance (a loose
            // solve would stop at once, the few new cells being shallow).
            tight |= residual <= LOOSE;
        }
        Err(format!(
            "no candidate set held the contact in {MAX_ROUNDS} rounds"
        ))
    }

    /// The candidate set's start: the pressure (scaled to the target force) and its
    /// cells, or why it does not fit in `limit` cells or the operator has no
    /// real-space table.
    fn candidate_start(
        &self,
        target_force: Option<f64>,
        fixed_approach: f64,
        limit: usize,
    ) -> Result<(Vec<f64>, Vec<usize>), String> {
        let n = self.op.cells();
        let too_many =
            |cells: usize| format!("a set of {cells} cells exceeds the limit of {limit}");
        // The start set's size first (a uniform start covers the domain).
        let estimate = match target_force {
            Some(f) => {
                let fraction = self.start_fraction(f, CANDIDATE_START_AREA);
                if fraction.is_finite() && fraction < 1.0 {
                    (fraction * self.problem.domain_cells as f64).ceil() as usize
                } else {
                    self.problem.domain_cells
                }
            }
            None => {
                let (mask, z) = (&self.problem.mask, &self.problem.z);
                (0..n)
                    .into_par_iter()
                    .filter(|&i| mask.holds(i) && z[i] < fixed_approach)
                    .count()
            }
        };
        if estimate == 0 {
            return Err("the start set is empty".into());
        }
        if estimate > limit {
            return Err(too_many(estimate));
        }
        let mut p = vec![0.0; n];
        match target_force {
            Some(f) => self.cold_start(&mut p, f, CANDIDATE_START_AREA),
            None => self.overlap_start(&mut p, fixed_approach),
        }
        // In parallel, in cell order (as the window path's scans).
        let cells: Vec<usize> = (0..n).into_par_iter().filter(|&i| p[i] > 0.0).collect();
        if cells.is_empty() {
            return Err("the start set is empty".into());
        }
        if cells.len() > limit {
            return Err(too_many(cells.len()));
        }
        if self.op.restricted(&[], Vec::new()).is_none() {
            return Err("the operator has no real-space table".into());
        }
        if let Some(f) = target_force {
            let s: f64 = p.iter().sum::<f64>() * self.op.cell_area();
            p.par_iter_mut().for_each(|v| *v *= f / s);
        }
        Ok((p, cells))
    }

    /// A solver for the problem restricted to part of the grid: `op` between its cells,
    /// their mask (None: all) and `z`, and the criterion's and the re-admission's scales
    /// of the whole domain.
    pub(super) fn on_part(
        op: K,
        mask: Option<Vec<u8>>,
        z: Vec<f64>,
        h_rms: f64,
        overlap_stiffness: f64,
    ) -> Self {
        let mut solver = Self::with_buffers(op, mask, overlap_stiffness);
        solver.work.w.copy_from_slice(&z);
        solver.problem.z = z;
        solver.problem.h_rms = h_rms;
        solver
    }

    /// A pressure solved on part of the grid (`tally`: its rounds' iterations in all, by
    /// `path`), on the whole
    /// grid: `w = K p + z` there, the approach (under force control the mean gap over
    /// the contact) and the criterion (module docs). The restricted solution if the
    /// criterion meets the tolerance (`p` is taken), else the approach and criterion.
    pub(super) fn on_grid(
        &mut self,
        p: &mut Vec<f64>,
        target_force: Option<f64>,
        fixed_approach: f64,
        (tally, path): (&Tally, Path),
        opts: &SolverOptions,
    ) -> std::result::Result<Solution, (f64, f64)> {
        self.op.apply(p, &mut self.work.w);
        self.work.rows_p.fill(true);
        let [sum_g, nc] = self.pass_a(p, 1.0, Refresh::AddZ, fixed_approach);
        let approach = match target_force {
            Some(_) if nc > 0.0 => fixed_approach + sum_g / nc,
            _ => fixed_approach,
        };
        let residual = self.criterion(p, approach);
        if residual > opts.tolerance || self.certificate(p, approach) > opts.tolerance {
            return Err((approach, residual));
        }
        let mut sol = self.finish(std::mem::take(p), approach, tally.iterations, residual);
        sol.path = path;
        sol.single_iterations = tally.single;
        sol.stencil_iterations = tally.stencil;
        sol.scaled_directions = tally.scaled;
        Ok(sol)
    }
}
