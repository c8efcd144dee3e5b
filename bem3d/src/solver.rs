//! Constrained conjugate gradients for frictionless normal contact
//! (Polonsky & Keer 1999), force- or displacement-controlled, preconditioned.
//! The measurements behind its strategies and constants: `docs/solver.md`.
//!
//! Where to read what, in the order of a solve ([`ContactSolver::solve`]):
//!
//! | file | what |
//! |---|---|
//! | `solver/options.rs` | the problem's load ([`Load`]) and the [`SolverOptions`] |
//! | `solver.rs` (here) | the solver's state, the heights, the checks, the choice of path |
//! | `solver/window.rs`, `solver/restricted.rs` | compact or small contacts: the same iteration on a window or a candidate set, in rounds checked on the grid |
//! | `solver/start.rs` | the initial pressure: overlap, uniform, nested (coarse grid) |
//! | `solver/iteration.rs` | the iteration: seven named steps per iteration |
//! | `solver/sweeps.rs` | the cell-by-cell arithmetic of each step (passes A-D) |
//! | `solver/stored.rs` | how the direction vectors t and y_prev are stored (single precision or scaled to 16 bits) |
//! | `solver/fused.rs` | operator applications fused with the sweeps, deterministic sums |
//! | `solver/convergence.rs` | criterion, certificate, complete-contact floor, the [`Solution`] |
//! | `solver/tangent.rs` | the tangent stiffness dF/dd of a solved contact |
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
use crate::operator::SolverOperator;
use rayon::prelude::*;

mod convergence;
mod domain;
mod fused;
mod iteration;
mod options;
pub mod reference;
mod restricted;
mod start;
mod stored;
mod sweeps;
mod tangent;
mod window;

pub use crate::solution::{Path, Solution};
pub use options::{Choice, Interrupt, Load, Paths, SolverOptions, MAX_LOAD, MAX_TOLERANCE};

/// Solver for one height map on one operator; buffers are allocated once. Its state
/// by job: the operator, the problem (heights, mask and their statistics), the work
/// buffers of the iteration, the tuning knobs, and the coarse solver of nested starts.
pub struct ContactSolver<K: SolverOperator> {
    op: K,
    problem: Problem,
    work: Work,
    tuning: Tuning,
    /// The solver on the grid coarsened 2 x 2, for nested starts (built on first use;
    /// dropped with the heights).
    coarse: Option<Box<ContactSolver<K>>>,
}

/// The problem a solver holds: the heights, the cells that may touch, and the
/// statistics the solve reads.
struct Problem {
    /// The gap at zero approach: the highest height minus the heights.
    z: Vec<f64>,
    /// The cells that may touch, read as 1 or 0 (numbers: the sweeps are branch-free).
    mask: domain::Domain,
    /// Rms of z over the domain (the length scale of the convergence criterion).
    h_rms: f64,
    /// Number of domain cells and the mean of z over them (complete-contact approach of
    /// an unmasked periodic surface).
    domain_cells: usize,
    z_mean: f64,
    /// Rms slope of the heights over the domain (for the cold start under force control).
    slope_rms: f64,
    /// Converts an overlap into a pressure [pressure / length] (see
    /// [`ContactSolver::solve`]).
    overlap_stiffness: f64,
}

/// The work buffers of the iteration (allocated once per solver).
struct Work {
    /// `K p + z`: the gap at zero approach, kept up to date incrementally.
    w: Vec<f64>,
    /// The conjugate direction `t` and Polak-Ribiere+'s `y_prev` (the previous
    /// iteration's projected preconditioned residual; between M's application and the
    /// next direction, this iteration's raw `M q`), in single precision or scaled to 16
    /// bits (module docs, "Scaled directions"); K's input, the update and the sums read
    /// the stored values.
    directions: stored::Directions,
    /// The cells whose projected step departs from `p - tau t` (pass D) and by how much,
    /// one list per row chunk of the sweeps, read for the point-load corrections of
    /// `K p`; empty between iterations.
    changes: Vec<Vec<(usize, f64)>>,
    /// 1 where p > 0 (the contact set), written by pass A: the sweeps that need only
    /// the set read one byte per cell instead of p.
    active: Vec<u8>,
    /// Per row: whether it holds a cell of the contact set (written by pass A; pass B
    /// reads p only there, and M's output is read on the set only, so the other rows are
    /// not computed).
    rows_on: Vec<bool>,
    /// Per row: whether p may be positive there (written by pass D; all rows wherever p
    /// is set otherwise): pass A reads p only in these rows.
    rows_p: Vec<bool>,
    /// Per row: whether t and y_prev may be non-zero there (the contact rows of the last
    /// direction pass): the direction pass skips the rows marked neither here nor in
    /// `rows_on`.
    rows_t: Vec<bool>,
    /// Per-iteration corrections of the projected step (cell, pressure change).
    loads: Vec<(usize, f64)>,
    /// Input and output of fused applications of an operator without a spectral form.
    fallback: [Vec<f64>; 2],
}

/// The tuning knobs of the strategies (tests set others).
struct Tuning {
    /// Largest contact set, as a fraction of the grid's cells, on which M is applied by
    /// its stencil: [`iteration::LOCAL_MAX_FRACTION`] (tests set others).
    local_max_fraction: f64,
    /// Grids with more cells than this run memory-lean: [`LARGE_GRID_CELLS`] (tests set
    /// others).
    large_grid_cells: usize,
    /// Fewest cells per side for a nested start: [`start::NESTED_MIN`], or
    /// [`start::COARSE_NESTED_MIN`] for a coarse grid's solver.
    nested_min: usize,
}

/// Grids with more cells than this (above 2048^2) trade the speed of repeated solves
/// on one solver for memory: the coarse solver of a nested start is released after the
/// start (its operator and buffers are about a fifth of the fine solve's memory), the
/// solution's gap is written over the solver's w (the next solve maps w's pages again),
/// and a fresh double-precision `K p` after an update is the operator's plain
/// application, not fused with the update (the periodic half-space then holds its
/// spectra in w: no double-precision row buffer). The results are the same either way.
const LARGE_GRID_CELLS: usize = 1 << 22;

/// Sweep chunk, in cells (rounded to whole rows): fixed, so that partial sums (and
/// results) do not depend on the thread count.
const CHUNK: usize = 16_384;

/// Sweep chunk of a grid of row length `nx`: [`CHUNK`] cells rounded to whole rows.
fn chunk_cells(nx: usize) -> usize {
    (CHUNK / nx).max(1) * nx
}

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
fn warm_pays(warm: &Solution, load: Load, target_force: Option<f64>) -> bool {
    let ratio = match (load, target_force) {
        (Load::Approach(d), _) => d / warm.approach,
        (_, Some(f)) => f / warm.force,
        _ => return false,
    };
    let window = match load {
        Load::Approach(_) => 1.0..=1.05,
        _ => 0.9..=1.05,
    };
    warm.force > 0.0 && warm.approach > 0.0 && window.contains(&ratio)
}

impl<K: SolverOperator> ContactSolver<K> {
    /// `heights` (`ny x nx`, peaks up, finite); `mask`: cells that may touch (None: all).
    pub fn new(op: K, heights: &[f64], mask: Option<Vec<bool>>) -> Result<Self> {
        // On the pool, as a solve (its parallel loops start in place).
        crate::pool::on_pool(|| Self::new_on_pool(op, heights, mask))
    }

    fn new_on_pool(op: K, heights: &[f64], mask: Option<Vec<bool>>) -> Result<Self> {
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
        solver.set_heights(heights)?;
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
                z: vec![0.0; n],
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

    /// Replaces the height map (same grid and mask), keeping the operator and buffers.
    pub fn set_heights(&mut self, heights: &[f64]) -> Result<()> {
        let (n, nx) = (self.op.cells(), self.op.nx());
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
        self.problem
            .z
            .par_iter_mut()
            .zip(self.work.w.par_iter_mut())
            .zip(heights)
            .for_each(|((z, w), h)| {
                *z = hmax - h;
                *w = *z;
            });
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

    /// Solves for `load`, starting from a previous solution `warm` where that pays (see
    /// the module docs; [`Solution::warm_started`] says whether it was used). A cold
    /// solve of a compact contact runs on a window first, one with a small start set
    /// restricted to a candidate set (module docs, [`Solution::path`]); if the
    /// window or the set outgrows its limit or a round does not converge, the attempt is
    /// dropped and the next path (last: the full iteration below) runs from its own
    /// start with `max_iterations` of its own (an attempt spends at most
    /// `max_iterations` iterations, over at most 8 rounds for a window and 24 for a
    /// set).
    ///
    /// Each iteration applies K once, to the conjugate direction t: `K p` moves by
    /// `-tau K t` and, where the projection clips a cell or re-admits an interpenetrating
    /// one, by K of those few point changes (a direct real-space sum below the operator's
    /// [`RealSpace::point_load_limit`](crate::operator::RealSpace::point_load_limit), a
    /// fresh `K p` above it). Before the solver reports convergence, `K p` is recomputed
    /// from scratch and the criterion re-evaluated, so rounding in the updates cannot pass
    /// for a solution.
    pub fn solve(
        &mut self,
        load: Load,
        opts: &SolverOptions,
        warm: Option<&Solution>,
    ) -> Result<Solution> {
        crate::pool::on_pool(|| self.solve_on_pool(load, opts, warm))
    }

    fn solve_on_pool(
        &mut self,
        load: Load,
        opts: &SolverOptions,
        warm: Option<&Solution>,
    ) -> Result<Solution> {
        let target_force = self.check(load, opts, warm)?;
        self.check_forced(opts)?;
        let paths = opts.paths;
        // A forced start (window, candidate set, nested) overrides a warm one.
        let forced_start =
            paths.window.forced() || paths.candidate_set.forced() || paths.nested_start.forced();
        let warm = warm.filter(|w| !forced_start && warm_pays(w, load, target_force));
        let fixed_approach = match load {
            Load::Approach(d) => d,
            _ => 0.0,
        };
        // The paths in order (module docs): a window, a candidate set, the full grid.
        let loaded = target_force.unwrap_or(fixed_approach) > 0.0;
        // A nested start is a start of the full grid: forced, it leaves the restricted
        // paths out (and cannot be forced with one of them).
        let restricted_allowed = !paths.nested_start.forced();
        if warm.is_none() && loaded && restricted_allowed {
            if paths.window.allowed() {
                match self.solve_windowed(target_force, fixed_approach, opts) {
                    Ok(sol) if paths.window.forced() || forced_ran(&sol, paths) => return Ok(sol),
                    Err(reason) if paths.window.forced() => {
                        return Err(unavailable("window", reason))
                    }
                    _ => {}
                }
            }
            if paths.candidate_set.allowed() {
                match self.solve_restricted(target_force, fixed_approach, opts) {
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
        match (warm, load) {
            (Some(w), _) => p
                .par_iter_mut()
                .zip(self.problem.mask.par_iter())
                .zip(&w.pressure)
                .for_each(|((p, &m), w)| *p = m as f64 * w.max(0.0)),
            (None, Load::Approach(_)) if paths.nested_start.forced() => {
                return Err(unavailable(
                    "nested_start",
                    "it needs force control (the load is an approach)".into(),
                ))
            }
            (None, Load::Approach(d)) => self.overlap_start(&mut p, d),
            (None, _) => {
                let force = target_force.unwrap_or(0.0);
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
                    self.cold_start(&mut p, force, start::FULL_GRID_START_AREA);
                }
            }
        }
        if let Some(w) = target_force {
            if w == 0.0 {
                return Ok(self.finish_unloaded(0.0));
            }
            if p.iter().all(|&v| v == 0.0) {
                // A warm start with no pressure on this domain: start from uniform.
                self.uniform_start(&mut p);
            }
            let s: f64 = p.iter().sum::<f64>() * self.op.cell_area();
            p.par_iter_mut().for_each(|v| *v *= w / s);
        } else if let Load::Approach(d) = load {
            if d == 0.0 || p.iter().all(|&v| v == 0.0) {
                // No overlap anywhere: the first contact is at d = 0.
                return Ok(self.finish_unloaded(d));
            }
        }
        let start = iteration::Start {
            warm: warm.is_some(),
            nested,
        };
        self.iterate(p, target_force, fixed_approach, opts, start)
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
    /// force (None under a prescribed approach).
    fn check(
        &self,
        load: Load,
        opts: &SolverOptions,
        warm: Option<&Solution>,
    ) -> Result<Option<f64>> {
        let n = self.op.cells();
        let target_force = match load {
            Load::Force(f) => Some(f),
            Load::MeanPressure(pm) => Some(pm * self.op.lx() * self.op.ly()),
            Load::Approach(_) => None,
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
        // Linear elasticity and double precision both end long before a mean pressure
        // of MAX_LOAD E* or an approach of MAX_LOAD times the map's size.
        let (e, size) = (self.op.e_star(), self.op.lx().max(self.op.ly()));
        match (load, target_force) {
            (_, Some(f)) if !(..=MAX_LOAD * e).contains(&(f / (self.op.lx() * self.op.ly()))) => {
                return Err(BemError::InvalidInput(format!(
                    "load: a force of {f:e} is a mean pressure of {:e}, more than {MAX_LOAD:e} E* = {:e}",
                    f / (self.op.lx() * self.op.ly()),
                    MAX_LOAD * e
                )))
            }
            (Load::Approach(d), _) if d > MAX_LOAD * size => {
                return Err(BemError::InvalidInput(format!(
                    "approach = {d:e} is more than {MAX_LOAD:e} times the map's size {size:e}"
                )))
            }
            _ => {}
        }
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
        Ok(target_force)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operator::{NonPeriodicHalfSpace, PeriodicHalfSpace};

    /// An iterate the criterion alone accepts and the certificate refuses: every
    /// pressure cell open by `tol h_rms` (complementarity at the tolerance) and a cell
    /// without pressure interpenetrating by `tol h_rms` (interpenetration at the
    /// tolerance): criterion tol, duality gap 2 tol.
    #[test]
    fn the_certificate_refuses_what_the_criterion_alone_accepts() {
        let tol = 1e-6;
        let p = [1.0, 2.0, 0.0, 0.0];
        let w = [tol, tol, -tol, 1.0];
        let mask = [1u8; 4];
        let [pg, ps, worst] = sweeps::criterion_terms(&p, &w, &mask, 0.0);
        let criterion = (pg / ps).max(worst);
        let [pg, ps, low] = sweeps::certificate_terms(&p, &w, &mask, 0.0);
        let certificate = pg / ps + low.max(0.0);
        assert!(criterion <= tol * (1.0 + 1e-12), "criterion {criterion:e}");
        assert!(
            (certificate - 2.0 * tol).abs() < 1e-18,
            "certificate {certificate:e}"
        );
    }

    /// The cold start's order statistic against a sort of the domain's heights, every
    /// rank: many ties (heights on 7 levels), both signs of zero, a constant map, a
    /// mask, and a grid of several chunks; a wrong bin or rank offset shows as a
    /// different value.
    #[test]
    fn kth_height_matches_a_sort() {
        type Height = fn(usize) -> f64;
        let cases: [(usize, usize, Height); 5] = [
            (16, 12, |k| ((k * 7919) % 613) as f64 * 0.37 - 50.0),
            (16, 12, |k| ((k * 31) % 7) as f64),
            (8, 8, |k| if k % 2 == 0 { 0.0 } else { -0.0 }),
            (8, 8, |_| 2.5),
            (512, 40, |k| ((k * 2654435761) % 100_003) as f64 * 1e-3),
        ];
        for (nx, ny, height) in cases {
            let h: Vec<f64> = (0..nx * ny).map(height).collect();
            for masked in [false, true] {
                let mask = masked.then(|| (0..nx * ny).map(|k| k % 3 != 0).collect::<Vec<_>>());
                let op = PeriodicHalfSpace::new(nx, ny, 1.0, 1.0, 1.0);
                let s = ContactSolver::new(op, &h, mask).unwrap();
                let mut zs: Vec<f64> = (0..nx * ny)
                    .filter(|&i| s.problem.mask.holds(i))
                    .map(|i| s.problem.z[i])
                    .collect();
                zs.sort_by(f64::total_cmp);
                let step = (zs.len() / 200).max(1);
                for k in (0..zs.len()).step_by(step).chain([zs.len() - 1]) {
                    let got = s.kth_height(k);
                    assert_eq!(got.to_bits(), zs[k].to_bits(), "{nx}x{ny} rank {k}");
                }
            }
        }
    }

    /// The rms slope against closed forms: a periodic sine (every pair, the wrap-around
    /// one included) and a parabola whose right half the mask leaves out (only pairs of
    /// domain cells count).
    #[test]
    fn rms_slope_matches_closed_forms() {
        let (nx, ny, l) = (16, 6, 2.0);
        let dx = l / nx as f64;
        let sine: Vec<f64> = (0..nx * ny)
            .map(|k| (2.0 * std::f64::consts::PI * (k % nx) as f64 / nx as f64).sin())
            .collect();
        let s = ContactSolver::new(PeriodicHalfSpace::new(nx, ny, l, l, 1.0), &sine, None).unwrap();
        // (h[i+1] - h[i])^2 = 4 sin^2(pi/nx) cos^2(2 pi (i + 1/2)/nx): mean 2 sin^2(pi/nx).
        let want = 2f64.sqrt() * (std::f64::consts::PI / nx as f64).sin() / dx;
        assert!(
            (s.problem.slope_rms - want).abs() < 1e-12 * want,
            "{} {want}",
            s.problem.slope_rms
        );

        let parabola: Vec<f64> = (0..nx * ny)
            .map(|k| ((k % nx) as f64 * dx).powi(2))
            .collect();
        let mask: Vec<bool> = (0..nx * ny).map(|k| k % nx < nx / 2).collect();
        let op = NonPeriodicHalfSpace::new(nx, ny, l, l, 1.0);
        let s = ContactSolver::new(op, &parabola, Some(mask)).unwrap();
        // Pairs i, i + 1 < nx/2 along x: slope (2 i + 1) dx, mean square
        // dx^2 (4 m^2 - 1) / 3 over m = nx/2 - 1 pairs; along y the slope is zero.
        let m = (nx / 2 - 1) as f64;
        let want = dx * ((4.0 * m * m - 1.0) / 3.0).sqrt();
        assert!(
            (s.problem.slope_rms - want).abs() < 1e-12 * want,
            "{} {want}",
            s.problem.slope_rms
        );
    }

    /// The memory-lean handling of large grids (coarse solver released after a nested
    /// start, the gap written over w, the update apart from a fresh double-precision
    /// K p, the operator's symbols computed and its double-precision spectra held in w)
    /// against the default on a grid where both run: the same bits through cold,
    /// repeated and warm solves, under force and approach, and K's row buffer stays
    /// sized for single precision.
    #[test]
    fn lean_large_grid_handling_changes_no_bit() {
        let n = 512;
        let h: Vec<f64> = (0..n * n)
            .map(|k| {
                let (x, y) = ((k % n) as f64 / n as f64, (k / n) as f64 / n as f64);
                let phase = |a: f64, b: f64, c: f64| {
                    (2.0 * std::f64::consts::PI * (a * x + b * y) + c).cos()
                };
                0.01 * (phase(1.0, 2.0, 0.3)
                    + 0.5 * phase(5.0, -3.0, 1.0)
                    + 0.2 * phase(-11.0, 17.0, 2.0))
            })
            .collect();
        // Without the single-precision phase, every fresh K p is in double precision
        // (the early ones, while the contact set changes, too), and K t's double-precision
        // transform grows K's row buffer to its own size.
        for single_precision in [Choice::Allow, Choice::Forbid] {
            lean_against_default(n, &h, single_precision);
        }
    }

    fn lean_against_default(n: usize, h: &[f64], single_precision: Choice) {
        let opts = SolverOptions {
            tolerance: 1e-10,
            // The same iterates with and without the lean layout: directions in single
            // precision on both (scaled ones: their own test).
            paths: Paths {
                single_precision,
                scaled_directions: Choice::Forbid,
                ..Default::default()
            },
            ..Default::default()
        };
        let run = |large: usize| {
            let op = PeriodicHalfSpace::with_symbols(n, n, (1.0, 1.0), 1.0, large == 0);
            let mut s = ContactSolver::new(op, h, None).unwrap();
            s.tuning.large_grid_cells = large;
            let first = s.solve(Load::MeanPressure(2e-3), &opts, None).unwrap();
            let kept = s.coarse.is_some();
            let again = s.solve(Load::MeanPressure(2e-3), &opts, None).unwrap();
            let warm = s
                .solve(Load::MeanPressure(3e-3), &opts, Some(&again))
                .unwrap();
            let approach = s.solve(Load::Approach(warm.approach), &opts, None).unwrap();
            // Single-precision spectra: 8 bytes per complex value, n/2 + 1 per row.
            let single = 8 * n * (n / 2 + 1);
            let lean = large == 0 && single_precision == Choice::Allow;
            assert_eq!(s.op.row_buffer_bytes() == single, lean, "row buffer");
            (kept, [first, again, warm, approach])
        };
        let (kept, default) = run(LARGE_GRID_CELLS);
        let (kept_lean, lean) = run(0);
        assert!(
            kept && !kept_lean,
            "coarse solver kept: {kept}, {kept_lean}"
        );
        assert!(default[0].nested_start && lean[0].nested_start);
        for (a, b) in default.iter().zip(&lean) {
            assert!(a.gap.iter().any(|&g| g > 0.0) && a.contact_cells > 0);
            assert_eq!(
                (a.iterations, a.approach.to_bits()),
                (b.iterations, b.approach.to_bits())
            );
            let same =
                |x: &[f64], y: &[f64]| x.iter().zip(y).all(|(u, v)| u.to_bits() == v.to_bits());
            assert!(same(&a.pressure, &b.pressure) && same(&a.gap, &b.gap));
        }
    }

    /// M by its stencil (small contact sets) against M by its transforms: the same
    /// solution at a tight tolerance, not the same iterates (the stencil path ran),
    /// and the same bits on one and three threads. Periodic and free, square and not,
    /// a few per cent of contact, the stencil forced (every contact set counts as
    /// small) or off.
    #[test]
    fn stencil_and_transforms_reach_the_same_solution() {
        let rough = |nx: usize, ny: usize| -> Vec<f64> {
            (0..nx * ny)
                .map(|k| {
                    let (x, y) = ((k % nx) as f64 / nx as f64, (k / nx) as f64 / ny as f64);
                    (1..=6)
                        .map(|m| {
                            let (a, b) = ((m * 5 % 7) as f64, (m * 3 % 5) as f64 - 2.0);
                            let phase = 2.0 * std::f64::consts::PI * (a * x + b * y) + m as f64;
                            phase.cos() / m as f64
                        })
                        .sum::<f64>()
                        * 0.01
                })
                .collect()
        };
        fn run<K: SolverOperator>(op: K, h: &[f64], fraction: f64, threads: usize) -> Solution {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut s = ContactSolver::new(op, h, None).unwrap();
                s.tuning.local_max_fraction = fraction;
                let opts = SolverOptions {
                    tolerance: 1e-12,
                    max_iterations: 5_000,
                    ..Default::default()
                };
                s.solve(Load::MeanPressure(6e-3), &opts, None).unwrap()
            })
        }
        for (nx, ny, periodic) in [(64, 64, true), (48, 40, false), (40, 56, true)] {
            let h = rough(nx, ny);
            let solve = |fraction: f64, threads: usize| {
                if periodic {
                    run(
                        PeriodicHalfSpace::new(nx, ny, 1.0, 1.0, 1.0),
                        &h,
                        fraction,
                        threads,
                    )
                } else {
                    run(
                        NonPeriodicHalfSpace::new(nx, ny, 1.0, 1.0, 1.0),
                        &h,
                        fraction,
                        threads,
                    )
                }
            };
            let (by_transforms, by_stencil) = (solve(0.0, 2), solve(1.0, 2));
            let share = by_stencil.contact_cells as f64 / (nx * ny) as f64;
            assert!((0.01..0.3).contains(&share), "{nx}x{ny}: contact {share}");
            assert!(
                !by_stencil.restricted() && !by_transforms.restricted(),
                "{nx}x{ny}: {share}"
            );
            let peak = by_transforms.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
            let worst = by_transforms
                .pressure
                .iter()
                .zip(&by_stencil.pressure)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(worst <= 1e-9 * peak, "{nx}x{ny}: {worst:e} of {peak:e}");
            assert_ne!(
                by_transforms.pressure, by_stencil.pressure,
                "{nx}x{ny}: the stencil path did not run"
            );
            let one = solve(1.0, 1);
            let three = solve(1.0, 3);
            assert!(one
                .pressure
                .iter()
                .zip(&three.pressure)
                .all(|(a, b)| a.to_bits() == b.to_bits()));
            assert!(one
                .pressure
                .iter()
                .zip(&by_stencil.pressure)
                .all(|(a, b)| a.to_bits() == b.to_bits()));
        }
    }
}
