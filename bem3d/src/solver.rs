//! Constrained conjugate gradients for frictionless normal contact
//! (Polonsky & Keer 1999), force- or displacement-controlled, preconditioned.
//! The measurements behind its strategies and constants: `docs/solver.md`.
//!
//! Where to read what, in the order of a solve ([`ContactSolver::solve`]). The methods
//! of [`ContactSolver`] live in three files (`solver.rs`, `solver/iteration.rs`,
//! `solver/rounds.rs`); the rest are the problem's own (`Problem`: starts, criterion),
//! the parts' (window, candidate set) and the sweeps' free functions:
//!
//! | file | what |
//! |---|---|
//! | `solver/options.rs` | the problem's load ([`Load`]) and the [`SolverOptions`] |
//! | `solver.rs` (here) | the solver's state by job, the heights, the checks, the choice of path, the nested start, the tangent stiffness |
//! | `solver/start.rs` | the problem's starts: overlap, uniform |
//! | `solver/rounds.rs` | compact or small contacts: the one driver of solves on part of the grid, in rounds checked on the grid |
//! | `solver/window.rs`, `solver/restricted.rs` | the two parts: a window, a candidate set |
//! | `solver/iteration.rs` | the iteration: seven named steps per iteration, and the [`Solution`] it reports |
//! | `solver/sweeps.rs` | the cell-by-cell arithmetic of each step (passes A-D) |
//! | `solver/stored.rs` | how the direction vectors t and y_prev are stored (single precision or scaled to 16 bits) |
//! | `solver/fused.rs` | operator applications fused with the sweeps, deterministic sums |
//! | `solver/convergence.rs` | the problem's criterion, certificate and complete-contact floor |
//! | `solver/reference.rs` | the published Polonsky-Keer iteration, for tests and comparisons |
//!
//! The search direction is built from the preconditioned residual `[p > 0] M g`, with M the
//! operator's approximate inverse
//! ([`Preconditioner::precondition`](crate::operator::Preconditioner::precondition): the
//! spectral stiffness E*|k|/2, an FFT-based preconditioner in the spirit of Vollebregt
//! 2014, J. Comput. Phys. 257); it cuts the iterations 3-5x on rough surfaces. M only
//! shapes the directions, so its transforms run in single precision ([`crate::Precision`]);
//! the criterion is always evaluated on K in double precision, so the fixed point is the
//! same. K's transforms also run in single precision while the criterion is above
//! `SINGLE_UNTIL` (1e-4, where the operator has them:
//! [`Operand::ComplianceSingle`](crate::operator::Operand::ComplianceSingle)); then `K p`
//! is recomputed in double precision, again at `REFRESH_AGAIN` (1e-7) and before
//! convergence is reported, while the direction's product `K t` stays in single precision
//! (its rounding shrinks with the step). The direction t and M's output are stored in
//! single precision; K's input, the update and `<q, t>` all read the stored t, so p and
//! `K p` move consistently.
//!
//! Scaled directions: on grids above `LARGE_GRID_CELLS` (2048^2), where memory decides
//! what fits, t and y_prev (M's output, then its projection) are stored as 16-bit
//! integers times one power-of-two scale per row chunk of the sweeps (16 rows), chosen
//! from the chunk's largest new value just before it is written (module `stored`): 13
//! bits or more relative to that value instead of single precision's 24, 4 bytes per
//! cell instead of 8. Both only shape the directions, and everything reads t as stored,
//! so the fixed point and the double-precision criterion are untouched; the
//! iterations stayed within -6 to +2 of single precision's on the benchmark surfaces
//! from 512^2 to 2048^2 at 0.1-20 % contact (`docs/solver.md`). 4096^2 is scaled too
//! although its own peak is set by its nested start: it is the coarse solve of 8192^2
//! nested starts, whose peak rises by about 1 byte per cell without it (`docs/solver.md`).
//! [`Paths::scaled_directions`] forbids or forces them.
//!
//! Each iteration applies K once (to the direction) and M once; `K p` is carried along
//! (see [`ContactSolver::solve`]). The sweeps that produce the transforms' inputs or
//! consume their outputs run inside their row passes
//! ([`Fft2::load_rows`](crate::fft::Fft2::load_rows)); K's column pass also returns
//! `<t, K t>` (Parseval, [`Fft2::transform_columns`](crate::fft::Fft2::transform_columns)),
//! so the projected update runs in K's inverse row pass and `K t` is never stored. While
//! the contact set changes in more cells than point loads can follow, `K p` is recomputed
//! after each update instead ([`Fft2::column_energy`](crate::fft::Fft2::column_energy));
//! which iterations these are is predicted from the last update (a wrong guess costs
//! time, not accuracy). Rows without contact cells are neither transformed nor swept
//! where their values are known to be zero (`rows_on`, `rows_p`, `rows_t`). The
//! measurements behind each of these choices: `docs/solver.md`.
//!
//! The direction is `t = y + beta t` with Polak-Ribiere+'s
//! `beta = max(0, <q, y - y_prev> / <q_prev, y_prev>)` (Gilbert & Nocedal 1992, SIAM J.
//! Optim. 2), q the residual on the contact set: the Fletcher-Reeves (CG) value while
//! the contact set holds, and a near-restart by itself when the set changes enough to
//! spoil conjugacy. Polonsky & Keer instead restart (beta = 0) at every iteration that
//! re-admits a cell, which on rough surfaces degrades their iteration to steepest descent
//! while the contact set forms (iterations about N^0.45 in the cell count N against
//! N^0.22 here; `docs/solver.md`). With M the identity, restarts and the uniform start the
//! iteration is Polonsky & Keer's ([`reference`](mod@reference)).
//!
//! Conventions: `heights` are the rigid surface's topography (peaks up, towards the
//! half-space). With `z = max(h) - h` the gap is `g = u + z - d` for approach d, surface
//! displacement `u = K p` and pressure p >= 0; first contact is at d = 0. Cells outside
//! an optional mask carry no pressure and are not constrained.
//!
//! Convergence criterion (stated exactly): with `h_rms` the rms of the heights about
//! their mean over the domain, the solve stops when
//! `max( sum_i p_i |g_i| / (sum_i p_i h_rms),  max(0, -min_i g_i) / h_rms ) <= tol`
//! over the domain cells: pressure-weighted mean gap (complementarity) and largest
//! interpenetration, both relative to the rms height (the grid diagonal for a flat face).
//! The force (or approach) constraint is enforced exactly at every iteration.
//!
//! What a converged solve guarantees: the solve also requires its certificate
//! [`Solution::certificate`] `c = sum_i p_i (g_i - g_low) / (sum_i p_i h_rms) <= tol`,
//! with `g_low = min(0, min_i g_i)` over the domain (it is at most twice the criterion,
//! so this rarely costs an iteration). Under force control `c F h_rms` bounds the
//! Frank-Wolfe (duality) gap of the energy `E(p) = p.K p / 2 - p.(h + const)` over the
//! pressures `p >= 0` carrying the force `F`: `E(p) - E(p*) <= c F h_rms`, and since E is
//! quadratic, the pressure error in the norm of K, the elastic energy of the difference,
//! `(p - p*).K(p - p*) <= 2 c F h_rms <= 2 tol F h_rms` (sums times the cell area:
//! `F = A sum_i p_i`). Because the criterion looks at the gap of every domain cell, with
//! or without pressure, an iterate with interpenetration beyond `tol h_rms` never
//! passes, whatever the start (a warm start far from the answer included).
//!
//! Complete contact (every domain cell in contact) is a legitimate state. Under force
//! control it is reached in one iteration. There the gap is the small difference of
//! displacements of the load's scale `p_mean sqrt(lx ly) / E*`, and double precision
//! resolves it to some hundred ulps of that scale only (the transforms' rounding): far
//! beyond complete contact (100 E* on the free half-space, 1e6 E* periodic, for a
//! surface of rms height 0.017 L) the criterion then stalls above 1e-10. In complete
//! contact a solve whose criterion has not halved for `STALL_ITERATIONS` (10)
//! iterations therefore stops once it is within the larger of the tolerance and
//! `COMPLETE_CONTACT_FLOOR` (1e3) ulps of that scale over the rms height (a solve that
//! still converges is not cut short); `residual` reports what was reached (above the
//! tolerance only in such solves). A periodic surface without a mask cannot be
//! pressed beyond its complete-contact approach `d_c = max(h) - mean(h)` (the periodic
//! displacement has zero mean, so the mean gap is `d_c - d`): an approach `d >= d_c` is
//! refused as [`BemError::Infeasible`], and the tangent stiffness there is infinite
//! (the force grows without the approach changing).
//!
//! Cold start under force control: the contact set shrinks far more readily than it
//! grows, and a uniform start (every cell in contact) spends most of a low-load solve
//! shedding cells. The start is instead the overlap `(d - z)+` of the heights with a
//! plane whose overlap covers `6 p / (E* h')` of the domain (p the mean pressure, h'
//! the rms slope): about three times the contact area of Persson's small-load estimate
//! `A/A0 ~ 2 p / (E* h')`, capped at the whole domain; uniform when the heights have no
//! slope (about half the iterations of the uniform start at 0.1-1 % contact).
//!
//! Nested start: a cold solve under force control on the full grid, with both sides even
//! and at least `NESTED_MIN` (512) cells and no mask, first solves the same load on the
//! grid coarsened 2 x 2 ([`GridForms::coarse`](crate::operator::GridForms::coarse); heights
//! averaged over each coarse cell's four cells) to `NESTED_TOLERANCE` (1e-3), and starts
//! from that pressure, each coarse cell's value on its four cells, instead of the overlap
//! start (the coarse grid's solver is kept for later solves up to 2048^2 cells and released
//! above, `LARGE_GRID_CELLS`; its own cold start nests again from
//! `COARSE_NESTED_MIN`, 256 cells a side). It saves 10-20 % of the fine iterations
//! from 512^2 up; below, the coarse solve costs more than it saves.
//!
//! Compact contacts on the non-periodic half-space (module `window`): a cold solve whose
//! start (the overlap covering `3 p / (E* h')`, or the overlap at the prescribed approach)
//! fits, with a margin, in a box of at most 0.7 of the grid runs the same iteration on that
//! window, with the operator's own transforms at the window's size
//! ([`GridForms::window`](crate::operator::GridForms::window)), in rounds: solve on the
//! window, apply K on the whole grid once, stop if the criterion holds there, else grow the
//! window to the interpenetrating cells (a sphere at 1 % contact: 5-9x faster).
//!
//! Small contact sets (module `restricted`): otherwise, a cold solve whose start set (the
//! overlap covering `4 p / (E* h')`, or the overlap at the prescribed approach) holds at
//! most `3 sqrt(N)` cells (and 4096) runs the same iteration restricted to a candidate set
//! C, K between its cells a dense matrix from the operator's real-space table
//! ([`RealSpace::restricted`](crate::operator::RealSpace::restricted)), in rounds: solve on
//! C, apply K on the whole grid once, stop if the criterion holds there, else add the
//! interpenetrating cells outside C (rough surfaces at 0.1 % contact: 4-8x faster).
//!
//! Both are the same fixed point as the full iteration, checked on the full grid;
//! [`Solution::path`] says which ran.
//!
//! Every strategy (window, candidate set, stencil, nested start, single precision,
//! scaled directions) can be forbidden or forced in [`SolverOptions::paths`] ([`Paths`],
//! [`Choice`]: forced, it runs without the rules above that judge whether it pays, and a
//! solve where it cannot run fails with [`BemError::PathUnavailable`]); the
//! [`Solution`] reports the path, the start, how many iterations ran in single
//! precision and by the stencil, and whether the directions were scaled. Forbidding or
//! forcing one changes the work, not the fixed point (tested path against path).
//!
//! M on small contact sets by its stencil: while the contact set holds at most
//! `LOCAL_MAX_FRACTION` (2 %) of the grid's cells, the full iteration applies M as a sum
//! over its kernel's values within a few cells of each contact cell ([`crate::stencil`],
//! from the operator's
//! [`Preconditioner::local_stiffness`](crate::operator::Preconditioner::local_stiffness))
//! instead of M's two transforms over the whole grid: y is needed on the contact cells
//! only, and the residual is zero off them. The kernel decays like 1 / r^3, so the
//! truncated M is another preconditioner, not the same one: the iterates differ, the fixed
//! point does not.
//!
//! Warm starts: a previous [`Solution`] is used as the initial iterate only where it
//! pays, i.e. for small load steps: force ratios in [0.9, 1.05] and approach ratios in
//! [1, 1.05] (outside that window a warm start saved nothing or cost up to 15 % more;
//! `docs/solver.md`). Outside the window the solve starts cold.

use crate::error::{BemError, Result};
use crate::operator::GridOperator;
use crate::set_solve::{SetEnd, SetSolve};
use rayon::prelude::*;

mod convergence;
mod domain;
mod fused;
mod iteration;
mod options;
pub mod reference;
mod restricted;
mod rounds;
mod start;
mod state;
mod stored;
mod sweeps;
pub(crate) mod window;

pub use crate::solution::{Path, Solution};
pub(crate) use options::check_load_magnitude;
use options::Target;
pub use options::{Choice, Interrupt, Load, Paths, SolverOptions, MAX_LOAD, MAX_TOLERANCE};
use state::{chunk_cells, Gap0, Problem, Tuning, Values, Work, ZMap, LARGE_GRID_CELLS};
pub use state::{ContactSolver, SharedHeights};

/// The error of a forced path that cannot run.
fn unavailable(path: &'static str, reason: String) -> BemError {
    BemError::PathUnavailable { path, reason }
}

/// Whether a restricted path's solution ran every forced strategy of the iteration
/// (stencil, single precision, scaled directions); where it did not, the solve goes on
/// to the full grid, which runs them or fails with [`BemError::PathUnavailable`].
fn forced_ran(sol: &Solution, paths: Paths) -> bool {
    let some = |count: usize| sol.iterations == 0 || count > 0;
    (!paths.stencil.forced() || sol.stencil_iterations == sol.iterations)
        && (!paths.single_precision.forced() || some(sol.single_iterations))
        && (!paths.scaled_directions.forced() || sol.scaled_directions)
}

/// Whether starting from `warm` pays for `load` (module docs: small load steps only).
fn warm_pays(warm: &Solution, target: Target) -> bool {
    let (ratio, window) = match target {
        Target::Approach(d) => (d / warm.approach, 1.0..=1.05),
        Target::Force(f) => (f / warm.force, 0.9..=1.05),
    };
    warm.force > 0.0 && warm.approach > 0.0 && window.contains(&ratio)
}

impl<K: GridOperator> ContactSolver<K> {
    /// [`Self::new`] for any operator (its compiled entry, in `compiled.rs`, calls this).
    pub(crate) fn new_generic(op: K, heights: &[f64], mask: Option<Vec<bool>>) -> Result<Self> {
        let heights = Values::Owned(heights.to_vec());
        crate::pool::on_pool(|| Self::new_on_pool(op, heights, mask))
    }

    /// [`Self::new_shared`] for any operator.
    pub(crate) fn new_shared_generic(
        op: K,
        heights: SharedHeights,
        mask: Option<Vec<bool>>,
    ) -> Result<Self> {
        crate::pool::on_pool(|| Self::new_on_pool(op, Values::Shared(heights), mask))
    }

    /// [`Self::set_heights`] for any operator.
    pub(crate) fn set_heights_generic(&mut self, heights: &[f64]) -> Result<()> {
        self.install_heights(Values::Owned(heights.to_vec()))
    }

    /// [`Self::solve`] for any operator.
    pub(crate) fn solve_generic(
        &mut self,
        load: Load,
        opts: &SolverOptions,
        warm: Option<&Solution>,
    ) -> Result<Solution> {
        crate::pool::on_pool(|| self.solve_on_pool(load, opts, warm))
    }

    /// [`Self::tangent_stiffness`] for any operator.
    pub(crate) fn tangent_stiffness_generic(
        &mut self,
        sol: &Solution,
        opts: &SolverOptions,
    ) -> Result<f64> {
        crate::pool::on_pool(|| self.tangent_stiffness_on_pool(sol, opts))
    }

    fn new_on_pool(op: K, heights: Values, mask: Option<Vec<bool>>) -> Result<Self> {
        let n = op.cells();
        op.half_space().validate()?;
        let mask: Option<Vec<u8>> = match mask {
            None => None,
            Some(m) if m.len() == n && m.iter().any(|&m| m) => {
                Some(m.iter().map(|&m| m as u8).collect())
            }
            Some(_) => {
                return Err(BemError::InvalidInput(
                    "mask must match the grid and contain a cell".into(),
                ))
            }
        };
        // Stiffness of the longest wavelength, E* / sqrt(lx ly) (up to pi): the scale of
        // a re-admitted cell's pressure per unit overlap.
        let overlap_stiffness = op.e_star() / (op.lx() * op.ly()).sqrt();
        let mut solver = Self::with_buffers(op, mask, overlap_stiffness);
        solver.install_heights(heights)?;
        Ok(solver)
    }

    /// A solver with zeroed buffers for `op`'s cells and no heights yet; `mask`: the
    /// cells that may touch (None: all).
    fn with_buffers(op: K, mask: Option<Vec<u8>>, overlap_stiffness: f64) -> Self {
        let (n, nx, ny) = (op.cells(), op.nx(), op.ny());
        let mask = match mask {
            Some(m) => domain::Domain::given(m),
            // The sweeps' chunks: CHUNK cells or ROWS_PER_CHUNK rows (whole rows).
            None => domain::Domain::all(n, chunk_cells(nx).max(crate::fft::ROWS_PER_CHUNK * nx)),
        };
        Self {
            op,
            problem: Problem {
                z: Gap0::gathered(Vec::new()),
                domain_cells: mask.count(),
                mask,
                h_rms: 0.0,
                z_mean: 0.0,
                slope_rms: 0.0,
                overlap_stiffness,
            },
            work: Work {
                w: vec![0.0; n],
                directions: stored::Directions::zeros(
                    n,
                    crate::fft::ROWS_PER_CHUNK * nx,
                    n > LARGE_GRID_CELLS,
                ),
                changes: vec![Vec::new(); ny.div_ceil(crate::fft::ROWS_PER_CHUNK)],
                active: vec![0; n],
                rows_on: vec![false; ny],
                rows_p: vec![true; ny],
                rows_t: vec![false; ny],
                loads: Vec::new(),
                fallback: [Vec::new(), Vec::new()],
            },
            tuning: Tuning {
                local_max_fraction: iteration::LOCAL_MAX_FRACTION,
                large_grid_cells: LARGE_GRID_CELLS,
                nested_min: start::NESTED_MIN,
            },
            coarse: None,
        }
    }

    /// Checks the heights, records their statistics and z's map, and sets w = z.
    fn install_heights(&mut self, values: Values) -> Result<()> {
        let (n, nx) = (self.op.cells(), self.op.nx());
        let heights = values.as_slice();
        if heights.len() != n {
            return Err(BemError::InvalidInput(format!(
                "height map has {} values but the grid is {} x {nx}",
                heights.len(),
                self.op.ny(),
            )));
        }
        let limit = crate::operator::SCALE_RANGE.1;
        if let Some(i) = heights.iter().position(|h| !(..=limit).contains(&h.abs())) {
            let what = if heights[i].is_finite() {
                format!("height {:e} beyond |h| <= {limit:e}", heights[i])
            } else {
                "non-finite height".to_string()
            };
            return Err(BemError::InvalidInput(format!(
                "{what} at row {}, column {}",
                i / nx,
                i % nx
            )));
        }
        let on = || {
            heights
                .iter()
                .zip(self.problem.mask.iter())
                .filter(|(_, &m)| m > 0)
        };
        let hmax = on().map(|(&h, _)| h).fold(f64::NEG_INFINITY, f64::max);
        let nm = self.problem.domain_cells as f64;
        let mean = on().map(|(&h, _)| h).sum::<f64>() / nm;
        let var = on().map(|(&h, _)| (h - mean).powi(2)).sum::<f64>() / nm;
        // Flat faces (e.g. a flat punch under a mask) have no rms height: the gap is then
        // measured against the grid diagonal.
        self.problem.h_rms = if var > 0.0 {
            var.sqrt()
        } else {
            (self.op.lx() * self.op.lx() + self.op.ly() * self.op.ly()).sqrt()
        };
        self.problem.z_mean = hmax - mean;
        self.problem.slope_rms = self.rms_slope(heights);
        let map = ZMap {
            offset: hmax,
            sign: -1.0,
        };
        self.work
            .w
            .par_iter_mut()
            .zip(heights)
            .for_each(|(w, h)| *w = map.of(*h));
        self.problem.z = Gap0 { values, map };
        self.coarse = None;
        Ok(())
    }

    /// Rms slope sqrt(<(dh/dx)^2> + <(dh/dy)^2>), each mean over the pairs of adjacent
    /// domain cells (across the boundary too on a periodic operator).
    fn rms_slope(&self, h: &[f64]) -> f64 {
        let (nx, ny) = (self.op.nx(), self.op.ny());
        let wrap = self.op.is_periodic();
        let (dx, dy) = (self.op.lx() / nx as f64, self.op.ly() / ny as f64);
        let mask = &self.problem.mask;
        // Sum of squared slopes and count over the pairs (a, b) of domain cells.
        let add = |(sum, pairs): &mut (f64, usize), a: usize, b: usize, step: f64| {
            if mask.holds(a) && mask.holds(b) {
                *sum += ((h[b] - h[a]) / step).powi(2);
                *pairs += 1;
            }
        };
        // Along x, row by row: each cell and its right neighbour, the last column and
        // the first where periodic.
        let mut x = (0.0, 0usize);
        for row in (0..ny).map(|j| j * nx) {
            for a in row..row + nx - 1 {
                add(&mut x, a, a + 1, dx);
            }
            if wrap && nx > 1 {
                add(&mut x, row + nx - 1, row, dx);
            }
        }
        // Along y: each row and the next, the last and the first where periodic.
        let mut y = (0.0, 0usize);
        for j in 0..ny {
            let next = match j + 1 {
                k if k < ny => k,
                _ if wrap && ny > 1 => 0,
                _ => continue,
            };
            for i in 0..nx {
                add(&mut y, j * nx + i, next * nx + i, dy);
            }
        }
        let mut mean_square = 0.0;
        for (sum, pairs) in [x, y] {
            if pairs > 0 {
                mean_square += sum / pairs as f64;
            }
        }
        mean_square.sqrt()
    }

    pub fn operator(&self) -> &K {
        &self.op
    }
    /// `u = K p` on the solver's operator (`u` overwritten).
    pub fn displacement(&mut self, p: &[f64], u: &mut [f64]) {
        crate::pool::on_pool(|| self.op.apply(p, u))
    }
    pub fn h_rms(&self) -> f64 {
        self.problem.h_rms
    }

    /// Cells per sweep chunk: whole rows, about [`CHUNK`] cells.
    fn chunk(&self) -> usize {
        chunk_cells(self.op.nx())
    }

    fn solve_on_pool(
        &mut self,
        load: Load,
        opts: &SolverOptions,
        warm: Option<&Solution>,
    ) -> Result<Solution> {
        let target = self.check(load, opts, warm)?;
        self.check_forced(opts)?;
        let paths = opts.paths;
        // A forced start (window, candidate set, nested) overrides a warm one.
        let forced_start =
            paths.window.forced() || paths.candidate_set.forced() || paths.nested_start.forced();
        let warm = warm.filter(|w| !forced_start && warm_pays(w, target));
        // The paths in order (module docs): a window, a candidate set, the full grid.
        let loaded = match target {
            Target::Force(v) | Target::Approach(v) => v > 0.0,
        };
        // A nested start is a start of the full grid: forced, it leaves the restricted
        // paths out (and cannot be forced with one of them).
        let restricted_allowed = !paths.nested_start.forced();
        if warm.is_none() && loaded && restricted_allowed {
            if paths.window.allowed() {
                let windowed =
                    window::WindowPart::start(self, target, opts).and_then(|(part, p, tight)| {
                        self.solve_in_rounds(part, p, tight, target, opts)
                    });
                match windowed {
                    Ok(sol) if paths.window.forced() || forced_ran(&sol, paths) => return Ok(sol),
                    Err(reason) if paths.window.forced() => {
                        return Err(unavailable("window", reason))
                    }
                    _ => {}
                }
            }
            if paths.candidate_set.allowed() {
                let restricted = restricted::CandidateSet::start(self, target, opts)
                    .and_then(|(part, p)| self.solve_in_rounds(part, p, false, target, opts));
                match restricted {
                    Ok(sol) if paths.candidate_set.forced() || forced_ran(&sol, paths) => {
                        return Ok(sol)
                    }
                    Err(reason) if paths.candidate_set.forced() => {
                        return Err(unavailable("candidate_set", reason))
                    }
                    _ => {}
                }
            }
        }
        let n = self.op.cells();
        let mut p = vec![0.0; n];
        let mut nested = false;
        match (warm, target) {
            (Some(w), _) => p
                .par_iter_mut()
                .zip(self.problem.mask.par_iter())
                .zip(&w.pressure)
                .for_each(|((p, &m), w)| *p = m as f64 * w.max(0.0)),
            (None, Target::Approach(_)) if paths.nested_start.forced() => {
                return Err(unavailable(
                    "nested_start",
                    "it needs force control (the load is an approach)".into(),
                ))
            }
            (None, Target::Approach(d)) => self.problem.overlap_start(&self.op, &mut p, d),
            (None, Target::Force(force)) => {
                if force > 0.0 {
                    match self.nested_start(&mut p, force, opts) {
                        Ok(()) => nested = true,
                        Err(reason) if paths.nested_start.forced() => {
                            return Err(unavailable("nested_start", reason))
                        }
                        Err(_) => {}
                    }
                }
                if !nested {
                    let area = start::FULL_GRID_START_AREA;
                    self.problem.cold_start(&self.op, &mut p, force, area);
                }
            }
        }
        match target {
            Target::Force(w) => {
                if w == 0.0 {
                    return Ok(self.finish_unloaded(0.0));
                }
                if p.iter().all(|&v| v == 0.0) {
                    // A warm start with no pressure on this domain: start from uniform.
                    self.problem.uniform_start(&mut p);
                }
                let s: f64 = p.iter().sum::<f64>() * self.op.cell_area();
                p.par_iter_mut().for_each(|v| *v *= w / s);
            }
            Target::Approach(d) => {
                if d == 0.0 || p.iter().all(|&v| v == 0.0) {
                    // No overlap anywhere: the first contact is at d = 0.
                    return Ok(self.finish_unloaded(d));
                }
            }
        }
        let start = iteration::Start {
            warm: warm.is_some(),
            nested,
        };
        self.iterate(p, target, opts, start)
    }

    /// Nested start under force control (module docs): the load solved to
    /// [`start::NESTED_TOLERANCE`] on the grid coarsened 2 x 2 (heights averaged over each
    /// coarse cell's four cells), each coarse cell's pressure given to its four cells.
    /// Err, with p untouched, where it does not apply (the reason): nesting forbidden, a
    /// side below [`start::NESTED_MIN`] ([`start::COARSE_NESTED_MIN`] on a coarse grid; 2 when
    /// forced) or odd, a mask, an operator without a coarse form, or a coarse solve that
    /// fails (the cold start then runs as without it, unless nesting is forced).
    fn nested_start(
        &mut self,
        p: &mut [f64],
        force: f64,
        opts: &SolverOptions,
    ) -> std::result::Result<(), String> {
        let (nx, ny) = (self.op.nx(), self.op.ny());
        let min = if opts.paths.nested_start.forced() {
            2
        } else {
            self.tuning.nested_min
        };
        if !opts.paths.nested_start.allowed() {
            return Err("forbidden".into());
        }
        if nx < min || ny < min || nx % 2 == 1 || ny % 2 == 1 {
            return Err(format!(
                "the grid is {nx} x {ny} (both sides must be even and at least {min})"
            ));
        }
        if self.problem.domain_cells != self.op.cells() {
            return Err("a mask restricts the domain".into());
        }
        if self.coarse.is_none() {
            self.coarse = self.coarse_solver().map(Box::new);
        }
        let Some(coarse) = self.coarse.as_deref_mut() else {
            return Err("the operator has no coarse form".into());
        };
        // The coarse grid nests by its own rule.
        let loose = SolverOptions {
            tolerance: start::NESTED_TOLERANCE.max(opts.tolerance),
            max_iterations: opts.max_iterations.min(start::NESTED_MAX_ITERATIONS),
            paths: Paths {
                nested_start: Choice::Allow,
                ..opts.paths
            },
            ..opts.clone()
        };
        let sol = coarse
            .solve_on_pool(Load::Force(force), &loose, None)
            .map_err(|e| format!("the coarse solve failed: {e}"))?;
        // Each coarse cell's value on its 2 x 2 cells (both sides are even), row pairs
        // in parallel.
        let cx = nx / 2;
        p.par_chunks_mut(2 * nx)
            .zip(sol.pressure.par_chunks(cx))
            .for_each(|(rows, coarse)| {
                for row in rows.chunks_mut(nx) {
                    for (pair, &v) in row.chunks_exact_mut(2).zip(coarse) {
                        pair.fill(v);
                    }
                }
            });
        if self.op.cells() > self.tuning.large_grid_cells {
            self.coarse = None;
        }
        Ok(())
    }

    /// The solver on this grid coarsened 2 x 2 (heights averaged over each coarse
    /// cell's four cells), nesting again from [`start::COARSE_NESTED_MIN`]; None if the
    /// operator has no coarse form.
    fn coarse_solver(&self) -> Option<ContactSolver<K>> {
        let op = self.op.coarse()?;
        let (nx, cx) = (self.op.nx(), op.nx());
        let z = &self.problem.z;
        let heights: Vec<f64> = (0..op.cells())
            .into_par_iter()
            .map(|k| {
                let i = 2 * (k / cx) * nx + 2 * (k % cx);
                -0.25 * (z.at(i) + z.at(i + 1) + z.at(i + nx) + z.at(i + nx + 1))
            })
            .collect();
        let mut s = ContactSolver::new_generic(op, &heights, None).ok()?;
        s.tuning.nested_min = start::COARSE_NESTED_MIN;
        Some(s)
    }

    fn tangent_stiffness_on_pool(&mut self, sol: &Solution, opts: &SolverOptions) -> Result<f64> {
        const WHAT: &str = "tangent stiffness";
        let n = self.op.cells();
        if sol.pressure.len() != n {
            return Err(BemError::InvalidInput(format!(
                "solution has {} cells but the grid has {n}",
                sol.pressure.len()
            )));
        }
        let c: Vec<f64> = sol
            .pressure
            .iter()
            .map(|&p| if p > 0.0 { 1.0 } else { 0.0 })
            .collect();
        let nc = c.iter().sum::<f64>() as usize;
        if nc == 0 {
            return Ok(0.0);
        }
        if self.op.is_periodic() && nc == n {
            return Ok(f64::INFINITY);
        }
        let mut solve = SetSolve {
            what: WHAT,
            op: &mut self.op,
            tolerance: opts.tolerance,
            max_iterations: opts.max_iterations,
            interrupted: &|| opts.interrupted(),
        };
        match solve.run(&c, &c)? {
            SetEnd::Converged { x, .. } => Ok(x.iter().sum::<f64>() * self.op.cell_area()),
            SetEnd::Limit {
                iterations,
                residual,
            } => Err(BemError::NoConvergence {
                what: WHAT,
                iterations,
                residual,
                tolerance: opts.tolerance,
                last: Box::new(sol.clone()),
            }),
        }
    }
    /// Refuses a forced stencil or single precision the operator does not have.
    fn check_forced(&mut self, opts: &SolverOptions) -> Result<()> {
        if opts.paths.stencil.forced() && self.op.local_stiffness().is_none() {
            return Err(unavailable(
                "stencil",
                "the operator has no stencil of its preconditioner".into(),
            ));
        }
        if opts.paths.single_precision.forced() && !self.op.rounds_single() {
            return Err(unavailable(
                "single_precision",
                "the operator has no single-precision form".into(),
            ));
        }
        Ok(())
    }

    /// Refuses a load, options or warm start this solver cannot take (negative,
    /// non-finite or beyond [`MAX_LOAD`]; an approach at or beyond complete contact of
    /// an unmasked periodic surface; a warm start of another grid); returns the target
    /// or approach the solve holds.
    fn check(&self, load: Load, opts: &SolverOptions, warm: Option<&Solution>) -> Result<Target> {
        let n = self.op.cells();
        let target = match load {
            Load::Force(f) => Target::Force(f),
            Load::MeanPressure(pm) => Target::Force(pm * self.op.lx() * self.op.ly()),
            Load::Approach(d) => Target::Approach(d),
        };
        let bad = |v: f64, what: &str| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(BemError::InvalidInput(format!(
                    "{what} = {v} must be finite and >= 0"
                )))
            }
        };
        match load {
            Load::Force(f) | Load::MeanPressure(f) => bad(f, "load")?,
            Load::Approach(d) => bad(d, "approach")?,
        }
        check_load_magnitude(load, self.op.e_star(), (self.op.lx(), self.op.ly()))?;
        opts.validate()?;
        if let Load::Approach(d) = load {
            if self.op.is_periodic() && self.problem.domain_cells == n && d >= self.problem.z_mean {
                return Err(BemError::Infeasible(format!(
                    "approach {d:e} reaches complete contact of a periodic surface \
                     (at max(h) - mean(h) = {:e} the force is unbounded); prescribe a \
                     force or mean pressure instead",
                    self.problem.z_mean
                )));
            }
        }
        if let Some(w) = warm {
            if w.pressure.len() != n {
                return Err(BemError::InvalidInput(format!(
                    "warm start has {} cells but the grid has {n}",
                    w.pressure.len()
                )));
            }
        }
        Ok(target)
    }
}

#[cfg(test)]
mod tests;
