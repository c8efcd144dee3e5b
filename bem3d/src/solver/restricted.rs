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

use super::options::{SolverOptions, Target};
use super::rounds::{Part, Round, Tally};
use super::state::ContactSolver;
use crate::operator::DenseCompliance;
use crate::operator::GridOperator;
use crate::solution::{Path, Solution};
use rayon::prelude::*;

/// The restricted start covers this many times `p / (E* h')` of the domain (the full
/// solve's start covers [`super::start::FULL_GRID_START_AREA`] times; a smaller set is
/// cheaper here, and the rounds add what it misses).
const CANDIDATE_START_AREA: f64 = 4.0;
/// Largest candidate set: this many times the square root of the domain's cell count
/// (a dense application then costs at most about 9 domain sweeps) ...
const CELLS_PER_ROOT: f64 = 3.0;
/// ... and at most this many cells (a 128 MiB matrix).
const MAX_CELLS: usize = 4096;
/// Cells a round may add at least (else: as many as the set holds).
const MIN_GROWTH: usize = 64;

/// The candidate set C: its cells (ascending), the largest it may grow to, and the
/// solver on it (kept while the set holds).
pub(super) struct CandidateSet {
    cells: Vec<usize>,
    /// Whether each grid cell is in C.
    member: Vec<bool>,
    limit: usize,
    inner: Option<ContactSolver<DenseCompliance>>,
    /// Whether C changed since its solver was built (its matrix's storage then serves
    /// the next one).
    grown: bool,
}

impl CandidateSet {
    /// The start of a restricted solve from a cold start (module docs), holding
    /// `target`: the set and the grid's pressure (scaled to the target force). Err: why
    /// it does not apply (the full iteration then runs from its own start, unless the
    /// candidate set is forced: then its limit is [`MAX_CELLS`] alone).
    pub(super) fn start<K: GridOperator>(
        grid: &ContactSolver<K>,
        target: Target,
        opts: &SolverOptions,
    ) -> Result<(Self, Vec<f64>), String> {
        let limit = if opts.paths.candidate_set.forced() {
            MAX_CELLS
        } else {
            ((CELLS_PER_ROOT * (grid.problem.domain_cells as f64).sqrt()) as usize).min(MAX_CELLS)
        };
        let (p, cells) = candidate_start(grid, target, limit)?;
        let set = CandidateSet {
            cells,
            member: vec![false; grid.op.cells()],
            limit,
            inner: None,
            grown: true,
        };
        Ok((set, p))
    }

    fn too_many(&self, cells: usize) -> String {
        format!("a set of {cells} cells exceeds the limit of {}", self.limit)
    }
}

impl<K: GridOperator> Part<K> for CandidateSet {
    type Op = DenseCompliance;
    const NAME: &'static str = "candidate set";
    const MAX_ROUNDS: usize = 24;

    fn prepare(&mut self, grid: &ContactSolver<K>) -> Result<(), String> {
        if !self.grown {
            return Ok(());
        }
        self.grown = false;
        self.cells.iter().for_each(|&i| self.member[i] = true);
        let (buffer, single) = self
            .inner
            .take()
            .map(|s| s.op.into_storage())
            .unwrap_or_default();
        let matrix = grid
            .op
            .restricted(&self.cells, buffer)
            .ok_or("the operator has no real-space table")?;
        let (hx, hy) = (
            grid.op.lx() / grid.op.nx() as f64,
            grid.op.ly() / grid.op.ny() as f64,
        );
        let e_star = grid.op.e_star();
        let dense =
            DenseCompliance::from_matrix(self.cells.len(), (hx, hy), e_star, matrix, single);
        let z = self.cells.iter().map(|&i| grid.problem.z.at(i)).collect();
        let (h_rms, stiffness) = (grid.problem.h_rms, grid.problem.overlap_stiffness);
        self.inner = Some(ContactSolver::on_part(dense, None, z, h_rms, stiffness));
        Ok(())
    }

    fn solver(&mut self) -> Option<&mut ContactSolver<DenseCompliance>> {
        self.inner.as_mut()
    }

    fn gather(&self, p: &[f64]) -> Vec<f64> {
        self.cells.iter().map(|&i| p[i]).collect()
    }

    fn scatter(&self, p: &mut [f64], values: &[f64]) {
        p.par_iter_mut().for_each(|v| *v = 0.0);
        self.cells.iter().zip(values).for_each(|(&i, &v)| p[i] = v);
    }

    /// Converged on the grid, or the interpenetrating cells outside C join it: the
    /// deepest first, at most doubling C (module docs).
    fn judge(
        &mut self,
        grid: &mut ContactSolver<K>,
        p: &mut Vec<f64>,
        _: &Solution,
        tally: &Tally,
        _: bool,
        (target, opts): (Target, &SolverOptions),
    ) -> Result<Round, String> {
        let (approach, residual) = match grid.on_grid(p, target, (tally, Path::CandidateSet), opts)
        {
            Ok(sol) => return Ok(Round::Solved(sol)),
            Err(found) => found,
        };
        let (w, mask, member) = (&grid.work.w, &grid.problem.mask, &self.member);
        let mut entering: Vec<(f64, usize)> = (0..grid.op.cells())
            .into_par_iter()
            .filter(|&i| mask.holds(i) && !member[i] && w[i] - approach < 0.0)
            .map(|i| (w[i] - approach, i))
            .collect();
        // A set much too small carries the load on too few cells: the approach
        // overshoots and the overlap spreads far beyond the contact (for a sphere the
        // overlap at the right approach covers twice the contact already). Give up when
        // even half the overlap would not fit; else the deepest cells join first, at
        // most doubling the set per round.
        if self.cells.len() + entering.len() / 2 > self.limit {
            return Err(self.too_many(self.cells.len() + entering.len() / 2));
        }
        let room = self.cells.len().max(MIN_GROWTH);
        if entering.len() > room {
            entering.select_nth_unstable_by(room, |a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            entering.truncate(room);
        }
        if entering.is_empty() {
            return Ok(Round::Held(residual));
        }
        self.cells.extend(entering.iter().map(|&(_, i)| i));
        self.cells.sort_unstable();
        self.grown = true;
        if self.cells.len() > self.limit {
            return Err(self.too_many(self.cells.len()));
        }
        Ok(Round::Grown(residual))
    }
}

/// The candidate set's start: the pressure (scaled to the target force) and its
/// cells, or why it does not fit in `limit` cells or the operator has no real-space
/// table.
fn candidate_start<K: GridOperator>(
    grid: &ContactSolver<K>,
    target: Target,
    limit: usize,
) -> Result<(Vec<f64>, Vec<usize>), String> {
    let (op, problem) = (&grid.op, &grid.problem);
    let n = op.cells();
    let too_many = |cells: usize| format!("a set of {cells} cells exceeds the limit of {limit}");
    // The start set's size first (a uniform start covers the domain).
    let estimate = match target {
        Target::Force(f) => {
            let fraction = problem.start_fraction(op, f, CANDIDATE_START_AREA);
            if fraction.is_finite() && fraction < 1.0 {
                (fraction * problem.domain_cells as f64).ceil() as usize
            } else {
                problem.domain_cells
            }
        }
        Target::Approach(d) => {
            let (mask, z) = (&problem.mask, &problem.z);
            (0..n)
                .into_par_iter()
                .filter(|&i| mask.holds(i) && z.at(i) < d)
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
    match target {
        Target::Force(f) => problem.cold_start(op, &mut p, f, CANDIDATE_START_AREA),
        Target::Approach(d) => problem.overlap_start(op, &mut p, d),
    }
    // In parallel, in cell order (as the window path's scans).
    let cells: Vec<usize> = (0..n).into_par_iter().filter(|&i| p[i] > 0.0).collect();
    if cells.is_empty() {
        return Err("the start set is empty".into());
    }
    if cells.len() > limit {
        return Err(too_many(cells.len()));
    }
    if op.restricted(&[], Vec::new()).is_none() {
        return Err("the operator has no real-space table".into());
    }
    if let Target::Force(f) = target {
        let s: f64 = p.iter().sum::<f64>() * op.cell_area();
        p.par_iter_mut().for_each(|v| *v *= f / s);
    }
    Ok((p, cells))
}
