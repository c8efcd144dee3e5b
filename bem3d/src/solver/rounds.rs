//! Solves on part of the grid, in rounds: the one driver of the window path (module
//! `window`) and the candidate-set path (module `restricted`).
//!
//! Each round solves the problem on the part with the solver's iteration (to
//! [`LOOSE`] while the part may still grow, then to half the requested tolerance),
//! puts the part's pressure on the grid, and lets the part judge it there: converged on
//! the whole grid (the solution, checked as any other), grown to cells that
//! interpenetrate outside it, or held (no cell outside it interpenetrates, but the
//! criterion is not met: the next round solves to the tolerance, and a round at the
//! tolerance that still fails gives the attempt up). A part that outgrows its limit,
//! a round that does not converge, or [`Part::MAX_ROUNDS`] rounds give the attempt up
//! too; the solver then runs the next path from its own start.

use super::iteration::{Refresh, Start};
use super::options::{SolverOptions, Target};
use super::state::{ContactSolver, Gap0};
use crate::operator::GridOperator;
use crate::solution::{Path, Solution};

/// Tolerance of the rounds while a part may still grow.
pub(super) const LOOSE: f64 = 1e-4;

/// What a round found on the grid.
pub(super) enum Round {
    /// The criterion holds on the whole grid: the solution.
    Solved(Solution),
    /// The part grew to cells that interpenetrate outside it; the criterion on the grid.
    Grown(f64),
    /// No cell outside the part interpenetrates; the criterion on the grid.
    Held(f64),
}

/// Part of the grid solved in rounds: a window or a candidate set. `K` is the grid's
/// operator.
pub(super) trait Part<K: GridOperator>: Sized {
    /// The operator between the part's cells.
    type Op: GridOperator;
    /// What the part is, in messages ("window", "candidate set").
    const NAME: &'static str;
    /// Rounds before the attempt is given up.
    const MAX_ROUNDS: usize;

    /// Readies the round: the part's solver built anew where the part changed since
    /// the last round. Err: why the part cannot be solved on (too large, no operator
    /// for it).
    fn prepare(&mut self, grid: &ContactSolver<K>) -> Result<(), String>;
    /// The part's solver (None before [`Part::prepare`]).
    fn solver(&mut self) -> Option<&mut ContactSolver<Self::Op>>;
    /// The part's values of a grid field.
    fn gather(&self, p: &[f64]) -> Vec<f64>;
    /// `p` zero on the grid but on the part, which holds `values`.
    fn scatter(&self, p: &mut [f64], values: &[f64]);
    /// The round's pressure `p` (on the grid) judged there; `sol`: the round's solution
    /// on the part, `tight`: whether the round solved to the tolerance. Err: the part
    /// outgrew its limit.
    fn judge(
        &mut self,
        grid: &mut ContactSolver<K>,
        p: &mut Vec<f64>,
        sol: &Solution,
        tally: &Tally,
        tight: bool,
        load: (Target, &SolverOptions),
    ) -> Result<Round, String>;
}

/// Options of a round on part of the grid: [`LOOSE`] while the part may still grow,
/// else half the requested tolerance (the grid's K p differs from the part's by
/// rounding); the iterations left of `opts` after `spent`.
fn round_options(opts: &SolverOptions, tight: bool, spent: usize) -> SolverOptions {
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

/// The iterations of a solve's rounds, summed.
#[derive(Debug, Default)]
pub(super) struct Tally {
    pub(super) iterations: usize,
    pub(super) single: usize,
    pub(super) stencil: usize,
    /// Whether any round stored its directions scaled.
    pub(super) scaled: bool,
}

impl Tally {
    fn add(&mut self, sol: &Solution) {
        self.iterations += sol.iterations;
        self.single += sol.single_iterations;
        self.stencil += sol.stencil_iterations;
        self.scaled |= sol.scaled_directions;
    }
}

impl<K: GridOperator> ContactSolver<K> {
    /// Solves holding `target` on `part` in rounds (module docs), from the grid
    /// pressure `p` (meeting the load); `tight`: whether the first round solves to the
    /// tolerance. Err: why the attempt was given up.
    pub(super) fn solve_in_rounds<P: Part<K>>(
        &mut self,
        mut part: P,
        mut p: Vec<f64>,
        mut tight: bool,
        target: Target,
        opts: &SolverOptions,
    ) -> Result<Solution, String> {
        let mut tally = Tally::default();
        for _ in 0..P::MAX_ROUNDS {
            part.prepare(self)?;
            let start = part.gather(&p);
            let solver = part
                .solver()
                .ok_or_else(|| format!("no {} was built", P::NAME))?;
            let round = round_options(opts, tight, tally.iterations);
            let sol = solver
                .iterate(start, target, &round, Start::default())
                .map_err(|e| format!("a round on the {} failed: {e}", P::NAME))?;
            tally.add(&sol);
            part.scatter(&mut p, &sol.pressure);
            match part.judge(self, &mut p, &sol, &tally, tight, (target, opts))? {
                Round::Solved(sol) => return Ok(sol),
                Round::Held(residual) if tight => {
                    return Err(format!(
                        "a round at the tolerance left the criterion at {residual:.2e} on the grid"
                    ))
                }
                Round::Held(_) => tight = true,
                // Near the answer already: the next rounds solve to the tolerance (a loose
                // solve would stop at once, the few new cells being shallow).
                Round::Grown(residual) => tight |= residual <= LOOSE,
            }
        }
        Err(format!(
            "no {} held the contact in {} rounds",
            P::NAME,
            P::MAX_ROUNDS
        ))
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
        solver.problem.z = Gap0::gathered(z);
        solver.problem.h_rms = h_rms;
        solver
    }

    /// A pressure solved on part of the grid (`tally`: its rounds' iterations in all, by
    /// `path`), on the whole grid: `w = K p + z` there, the approach (under force
    /// control the mean gap over the contact) and the criterion (module docs). The
    /// part's solution if the criterion meets the tolerance (`p` is taken), else the
    /// approach and criterion.
    pub(super) fn on_grid(
        &mut self,
        p: &mut Vec<f64>,
        target: Target,
        (tally, path): (&Tally, Path),
        opts: &SolverOptions,
    ) -> std::result::Result<Solution, (f64, f64)> {
        self.op.apply(p, &mut self.work.w);
        self.work.rows_p.fill(true);
        let base = target.base_approach();
        let [sum_g, nc] = self.pass_a(p, 1.0, Refresh::AddZ, base);
        let approach = match target {
            Target::Force(_) if nc > 0.0 => base + sum_g / nc,
            _ => base,
        };
        let nx = self.op.nx();
        let residual = self.problem.criterion(p, &self.work.w, nx, approach);
        if residual > opts.tolerance
            || self.problem.certificate(p, &self.work.w, nx, approach) > opts.tolerance
        {
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
