//! Constrained conjugate gradients for frictionless normal contact
//! (Polonsky & Keer 1999), force- or displacement-controlled, preconditioned.
//! The measurements behind its strategies and constants: `docs/solver.md`.
//!
//! The search direction is built from the preconditioned residual `[p > 0] M g`, with M
//! the operator's approximate inverse ([`Compliance::precondition`]: the spectral
//! stiffness E*|k|/2, an FFT-based preconditioner in the spirit of Vollebregt 2014, J.
//! Comput. Phys. 257); it cuts the iterations 3-5x on rough surfaces. M only shapes the
//! directions, so its transforms run in single precision ([`crate::Precision`]); the
//! criterion is always evaluated on K in double precision, so the fixed point is the
//! same. K's transforms also run in single precision while the criterion is above
//! `SINGLE_UNTIL` (1e-4, where the operator has them: [`Operand::ComplianceSingle`]);
//! then `K p` is recomputed in double precision, again at `REFRESH_AGAIN` (1e-7) and
//! before convergence is reported, while the direction's product `K t` stays in single
//! precision (its rounding shrinks with the step). The direction t and M's output are
//! stored in single precision; K's input, the update and `<q, t>` all read the stored t,
//! so p and `K p` move consistently.
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
//! iteration is Polonsky & Keer's ([`reference`]).
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
//! Nested start: a cold solve under force control on the full grid, with both sides
//! even and at least `NESTED_MIN` (512) cells and no mask, first solves the same load
//! on the grid coarsened 2 x 2 ([`Compliance::coarse`]; heights averaged over each
//! coarse cell's four cells) to `NESTED_TOLERANCE` (1e-3), and starts from that
//! pressure, each coarse cell's value on its four cells, instead of the overlap start
//! (the coarse grid's solver is kept for later solves; its own cold start nests again
//! from `COARSE_NESTED_MIN`, 256 cells a side). It saves 10-20 % of the fine iterations
//! from 512^2 up; below, the coarse solve costs more than it saves.
//!
//! Compact contacts on the non-periodic half-space (module `window`): a cold solve
//! whose start (the overlap covering `3 p / (E* h')`, or the overlap at the prescribed
//! approach) fits, with a margin, in a box of at most 0.7 of the grid runs the same
//! iteration on that window, with the operator's own transforms at the window's size
//! ([`Compliance::window`]), in rounds: solve on the window, apply K on the whole grid
//! once, stop if the criterion holds there, else grow the window to the
//! interpenetrating cells (a sphere at 1 % contact: 5-9x faster).
//!
//! Small contact sets (module `restricted`): otherwise, a cold solve whose start set
//! (the overlap covering `4 p / (E* h')`, or the overlap at the prescribed approach)
//! holds at most `3 sqrt(N)` cells (and 4096) runs the same iteration restricted to a
//! candidate set C, K between its cells a dense matrix from the operator's real-space
//! table ([`Compliance::restricted`]), in rounds: solve on C, apply K on the whole grid
//! once, stop if the criterion holds there, else add the interpenetrating cells outside
//! C (rough surfaces at 0.1 % contact: 4-8x faster).
//!
//! Both are the same fixed point as the full iteration, checked on the full grid;
//! [`Solution::restricted`] says when one of them ran.
//!
//! M on small contact sets by its stencil: while the contact set holds at most
//! `LOCAL_MAX_FRACTION` (2 %) of the grid's cells, the full iteration applies M as a
//! sum over its kernel's values within a few cells of each contact cell
//! ([`crate::stencil`], from the operator's [`Compliance::local_stiffness`]) instead
//! of M's two transforms over the whole grid: y is needed on the contact cells only,
//! and the residual is zero off them. The kernel decays like 1 / r^3, so the truncated
//! M is another preconditioner, not the same one: the iterates differ, the fixed point
//! does not.
//!
//! Warm starts: a previous [`Solution`] is used as the initial iterate only where it
//! pays, i.e. for small load steps: force ratios in [0.9, 1.05] and approach ratios in
//! [1, 1.05] (outside that window a warm start saved nothing or cost up to 15 % more;
//! `docs/solver.md`). Outside the window the solve starts cold.

use crate::error::{BemError, Result};
use crate::fft::{copy_in, copy_out, ROWS_PER_CHUNK};
use crate::operator::{Compliance, Operand, Transform};
use rayon::prelude::*;

pub mod reference;
pub use crate::solution::Solution;
mod restricted;
mod sweeps;
mod window;

/// The load prescribed to a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Load {
    /// Total normal force.
    Force(f64),
    /// Mean pressure over the whole grid area lx * ly.
    MeanPressure(f64),
    /// Rigid-body approach d (measured from first contact).
    Approach(f64),
}

#[derive(Debug, Clone)]
pub struct SolverOptions {
    /// Convergence criterion (module docs), in (0, [`MAX_TOLERANCE`]].
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Polled once per iteration: when it is set the solve stops with
    /// [`BemError::Interrupted`] (a caller's Ctrl-C).
    pub interrupt: Option<Interrupt>,
}

/// Largest load a solve accepts, as a mean pressure over E* or an approach over the map's
/// size.
pub const MAX_LOAD: f64 = 1e10;

/// Largest tolerance a solve accepts: beyond it the criterion no longer bounds the
/// answer's error usefully (at 1 the pressures of a rough contact are off by 10 % or
/// more).
pub const MAX_TOLERANCE: f64 = 1e-2;

impl Default for SolverOptions {
    fn default() -> Self {
        Self::new(1e-10, 10_000)
    }
}

impl SolverOptions {
    /// The options of a solve to `tolerance` in at most `max_iterations` iterations.
    pub fn new(tolerance: f64, max_iterations: usize) -> Self {
        Self {
            tolerance,
            max_iterations,
            interrupt: None,
        }
    }

    /// Refuses a tolerance outside (0, [`MAX_TOLERANCE`]] or no iterations; the one
    /// check of the command line and the Python package.
    pub fn validate(&self) -> Result<()> {
        if !(self.tolerance > 0.0 && self.tolerance <= MAX_TOLERANCE) {
            return Err(BemError::InvalidInput(format!(
                "tolerance = {:e} must lie in (0, {MAX_TOLERANCE:e}]",
                self.tolerance
            )));
        }
        if self.max_iterations == 0 {
            return Err(BemError::InvalidInput("max_iterations must be >= 1".into()));
        }
        Ok(())
    }

    /// Whether the caller asked the solve to stop.
    fn interrupted(&self) -> bool {
        self.interrupt.as_ref().is_some_and(Interrupt::is_set)
    }
}

/// A flag a caller sets (from another thread) to stop solves that poll it.
#[derive(Debug, Clone, Default)]
pub struct Interrupt(std::sync::Arc<std::sync::atomic::AtomicBool>);

impl Interrupt {
    pub fn set(&self) {
        self.0.store(true, std::sync::atomic::Ordering::Relaxed);
    }
    pub fn clear(&self) {
        self.0.store(false, std::sync::atomic::Ordering::Relaxed);
    }
    pub fn is_set(&self) -> bool {
        self.0.load(std::sync::atomic::Ordering::Relaxed)
    }
}

/// Solver for one height map on one operator; buffers are allocated once.
pub struct ContactSolver<K: Compliance> {
    op: K,
    z: Vec<f64>,
    /// 1 on cells that may touch, 0 elsewhere (numbers: the sweeps are branch-free).
    mask: Vec<u8>,
    h_rms: f64,
    /// Number of domain cells and the mean of z over them (complete-contact approach of
    /// an unmasked periodic surface).
    domain_cells: usize,
    z_mean: f64,
    /// Rms slope of the heights over the domain (for the cold start under force control).
    slope_rms: f64,
    /// Converts an overlap into a pressure [pressure / length] (see [`Self::solve`]).
    overlap_stiffness: f64,
    /// `K p + z`: the gap at zero approach, kept up to date incrementally.
    w: Vec<f64>,
    /// Conjugate direction, stored in single precision (module docs); K's input and the
    /// update read the stored values.
    t: Vec<f32>,
    /// Each cell's departure of the projected step from `p - tau t` (pass D), read for
    /// the point-load corrections of `K p`; zero between iterations (pass D writes only
    /// the changed cells, the iteration clears them once read).
    r: Vec<f64>,
    /// The previous iteration's projected preconditioned residual (Polak-Ribiere's beta);
    /// between M's application and the next direction, this iteration's raw `M q`; in
    /// single precision, as M computes.
    y_prev: Vec<f32>,
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
    /// Largest contact set, as a fraction of the grid's cells, on which M is applied by
    /// its stencil: [`LOCAL_MAX_FRACTION`] (tests set others).
    local_max_fraction: f64,
    /// The solver on the grid coarsened 2 x 2, for nested starts (built on first use;
    /// dropped with the heights).
    coarse: Option<Box<ContactSolver<K>>>,
    /// Whether cold solves under force control may start from the coarse grid's
    /// solution (module docs; on by default).
    nested: bool,
    /// Fewest cells per side for a nested start: [`NESTED_MIN`], or
    /// [`COARSE_NESTED_MIN`] for a coarse grid's solver.
    nested_min: usize,
}

/// Largest contact set, as a fraction of the grid's cells, on which the iteration applies
/// M by its stencil on the contact cells instead of by transforms (module docs).
const LOCAL_MAX_FRACTION: f64 = 0.02;

/// Sweep chunk, in cells (rounded to whole rows): fixed, so that partial sums (and
/// results) do not depend on the thread count.
const CHUNK: usize = 16_384;

/// Cold start under force control: the initial overlap covers this many times
/// `p / (E* h')` of the domain (module docs).
const START_AREA: f64 = 6.0;

/// Nested start (module docs): grids with at least this many cells per side (and
/// even sides) start from their 2 x 2 coarsening's solution.
const NESTED_MIN: usize = 512;

/// A coarse grid's own cold start nests again from this many cells per side: cheap at
/// that size, and on the 512^2 benchmark surface at 1 % contact the fine iterations
/// went from 32 to 28 (1024^2 and 20 % contact: the same iterations as with 512).
const COARSE_NESTED_MIN: usize = 256;

/// Tolerance of the nested start's coarse solve: the fine iteration starts from about
/// the same residual whether the coarse solve stops at 1e-2, 1e-3 or 1e-10 (the coarse
/// grid cannot resolve the fine contact set; measured on the 1024^2 benchmark surface
/// at 1 % contact: 4.0e-2 in each case).
const NESTED_TOLERANCE: f64 = 1e-3;

/// Iteration cap of the nested start's coarse solve (it takes 10-30 on the benchmark
/// surfaces); a coarse solve that does not converge leaves the cold start.
const NESTED_MAX_ITERATIONS: usize = 200;

/// Residual below which the displacement `K p` is recomputed in double precision and
/// from then on carried along with K t in single precision only (module docs); before,
/// K's single-precision transforms ([`Operand::ComplianceSingle`]) serve every
/// application. Measured on the 512^2 benchmark surface at 1 % and 20 % contact: the
/// same iterations with 1e-3, 1e-4 and 1e-5 (1e-5 one more at 20 %), against 9 and 16
/// more with K p never recomputed in double precision before the final check.
const SINGLE_UNTIL: f64 = 1e-4;

/// In complete contact the criterion is met to at most this many ulps of the load's
/// displacement scale (module docs, "Complete contact"). Measured (rough maps on 128^2,
/// h_rms 0.017 L): the iteration in double precision stalls at 70-300 ulps of that
/// scale (free half-space at 100 E*, periodic at 1e6 E*).
const COMPLETE_CONTACT_FLOOR: f64 = 1e3;

/// Iterations without halving the criterion after which a solve in complete contact
/// may stop at its floor.
const STALL_ITERATIONS: usize = 10;

/// Residual below which `K p` is recomputed in double precision once more (module
/// docs): the single-precision K t moves it by rounding of about 1e-6 of the
/// displacement's change since the last recomputation, which scales with the residual
/// then (1e-4: about 1e-10, at the tolerance; 1e-7: about 1e-13).
const REFRESH_AGAIN: f64 = 1e-7;

thread_local! {
    /// A chunk's worth of values for passes that need a buffer only while they run.
    static SCRATCH: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// `f` on this thread's scratch buffer, `len` values long (their contents left from
/// earlier use: `f` writes before it reads).
fn with_scratch<R>(len: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    SCRATCH.with(|s| {
        let mut s = s.borrow_mut();
        if s.len() < len {
            s.resize(len, 0.0);
        }
        f(&mut s[..len])
    })
}

/// Maps each chunk with `f` (in parallel) and sums the `N` partial results with
/// [`sum_parts`].
fn reduce<const N: usize, I, F>(iter: I, f: F, max_slot: Option<usize>) -> [f64; N]
where
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item) -> [f64; N] + Sync + Send,
{
    let parts: Vec<[f64; N]> = iter.into_par_iter().map(f).collect();
    sum_parts(&parts, max_slot)
}

fn combine<const N: usize>(acc: &mut [f64; N], p: &[f64; N], max_slot: Option<usize>) {
    for k in 0..N {
        if Some(k) == max_slot {
            acc[k] = acc[k].max(p[k]);
        } else {
            acc[k] += p[k];
        }
    }
}

/// Sums per-chunk partial results in chunk order (deterministic for any thread count);
/// `max_slot` combines that entry by max instead of sum.
fn sum_parts<const N: usize>(parts: &[[f64; N]], max_slot: Option<usize>) -> [f64; N] {
    let mut acc = [0.0f64; N];
    for p in parts {
        combine(&mut acc, p, max_slot);
    }
    acc
}

/// First half of a fused application of K or M
/// ([`Fft2::load_rows`](crate::fft::Fft2::load_rows)): `load(item, values)` produces
/// the input a chunk of [`ROWS_PER_CHUNK`] rows at a time from the caller's items.
/// Operators without a spectral form collect the input in `fallback` instead (same
/// chunks, same sums).
fn load_fused<K, I, F, const A: usize>(
    op: &mut K,
    which: Operand,
    fallback: &mut [Vec<f64>; 2],
    items: I,
    load: F,
) -> Vec<[f64; A]>
where
    K: Compliance,
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item, &mut [f64]) -> [f64; A] + Sync,
{
    let (n, chunk) = (op.cells(), ROWS_PER_CHUNK * op.nx());
    if let Some(s) = op.spectral(which) {
        return match s.transform {
            Transform::Double(fft, _) => fft.load_rows(s.dims, items, load),
            Transform::Single(fft, _) => fft.load_rows(s.dims, items, load),
        };
    }
    fallback[0].resize(n, 0.0);
    fallback[0]
        .par_chunks_mut(chunk)
        .zip(items)
        .map(|(values, item)| load(item, values))
        .collect()
}

/// Second half of a fused application: the operator applied to the loaded input, handed
/// to `store(item, values)` a chunk at a time
/// ([`Fft2::finish_rows`](crate::fft::Fft2::finish_rows)).
fn finish_fused<K, I, F, const B: usize>(
    op: &mut K,
    which: Operand,
    fallback: &mut [Vec<f64>; 2],
    items: I,
    store: F,
    wanted: Option<&[bool]>,
) -> Vec<[f64; B]>
where
    K: Compliance,
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item, &[f64]) -> [f64; B] + Sync,
{
    apply_fused(op, which, fallback, false);
    store_fused(op, which, fallback, items, store, wanted)
}

/// The second half's first step: the operator applied to the loaded input x (the
/// transforms' column pass,
/// [`Fft2::convolve_columns`](crate::fft::Fft2::convolve_columns); an operator without
/// a spectral form applies itself into `fallback`). With `energy` (K only), returns
/// `<x, K x>` (Parseval,
/// [`Fft2::transform_columns`](crate::fft::Fft2::transform_columns); the fallback sums
/// in a fixed order) for a caller that needs it before the rows, else 0; the rows
/// follow with [`store_fused`].
fn apply_fused<K: Compliance>(
    op: &mut K,
    which: Operand,
    fallback: &mut [Vec<f64>; 2],
    energy: bool,
) -> f64 {
    debug_assert!(!energy || which != Operand::Preconditioner);
    if let Some(s) = op.spectral(which) {
        return match (s.transform, energy) {
            (Transform::Double(fft, symbol), true) => fft.transform_columns(symbol),
            (Transform::Single(fft, symbol), true) => fft.transform_columns(symbol),
            (Transform::Double(fft, symbol), false) => {
                fft.convolve_columns(symbol);
                0.0
            }
            (Transform::Single(fft, symbol), false) => {
                fft.convolve_columns(symbol);
                0.0
            }
        };
    }
    let n = op.cells();
    let [input, output] = fallback;
    match which {
        Operand::Compliance => {
            output.resize(n, 0.0);
            op.apply(input, output);
        }
        Operand::ComplianceSingle => {
            output.resize(n, 0.0);
            op.apply_single(input, output);
        }
        Operand::Preconditioner => {
            op.precondition(input);
            std::mem::swap(input, output);
        }
    }
    if energy {
        input.iter().zip(output.iter()).map(|(a, b)| a * b).sum()
    } else {
        0.0
    }
}

/// `<x, K x>` of the loaded input x alone, as [`apply_fused`] with `energy` returns it
/// (bit for bit, [`Fft2::column_energy`](crate::fft::Fft2::column_energy)), without K x:
/// no rows follow.
fn energy_fused<K: Compliance>(op: &mut K, which: Operand, fallback: &mut [Vec<f64>; 2]) -> f64 {
    debug_assert!(which != Operand::Preconditioner);
    if let Some(s) = op.spectral(which) {
        return match s.transform {
            Transform::Double(fft, symbol) => fft.column_energy(symbol),
            Transform::Single(fft, symbol) => fft.column_energy(symbol),
        };
    }
    apply_fused(op, which, fallback, true)
}

/// The second half's second step (after [`apply_fused`]): the result handed to
/// `store(item, values)` a chunk at a time.
fn store_fused<K, I, F, const B: usize>(
    op: &mut K,
    which: Operand,
    fallback: &mut [Vec<f64>; 2],
    items: I,
    store: F,
    wanted: Option<&[bool]>,
) -> Vec<[f64; B]>
where
    K: Compliance,
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item, &[f64]) -> [f64; B] + Sync,
{
    let chunk = ROWS_PER_CHUNK * op.nx();
    if let Some(s) = op.spectral(which) {
        return match s.transform {
            Transform::Double(fft, _) => fft.store_some_rows(items, store, wanted),
            Transform::Single(fft, _) => fft.store_some_rows(items, store, wanted),
        };
    }
    fallback[1]
        .par_chunks(chunk)
        .zip(items)
        .map(|(values, item)| store(item, values))
        .collect()
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

/// What pass A adds to `w` before use: point-load corrections (none: w is current), or
/// `z` (when `w` was just recomputed as `K p`).
enum Refresh<'a> {
    Loads(&'a [(usize, f64)]),
    AddZ,
}

impl<K: Compliance> ContactSolver<K> {
    /// `heights` (`ny x nx`, peaks up, finite); `mask`: cells that may touch (None: all).
    pub fn new(op: K, heights: &[f64], mask: Option<Vec<bool>>) -> Result<Self> {
        // On the pool, as a solve (its parallel loops start in place).
        crate::pool::on_pool(|| Self::new_on_pool(op, heights, mask))
    }

    fn new_on_pool(op: K, heights: &[f64], mask: Option<Vec<bool>>) -> Result<Self> {
        let n = op.cells();
        op.half_space().validate()?;
        let mask: Vec<u8> = match mask {
            None => vec![1; n],
            Some(m) if m.len() == n && m.iter().any(|&m| m) => m.iter().map(|&m| m as u8).collect(),
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

    /// A solver with zeroed buffers for `op`'s cells and no heights yet.
    fn with_buffers(op: K, mask: Vec<u8>, overlap_stiffness: f64) -> Self {
        let (n, ny) = (op.cells(), op.ny());
        Self {
            overlap_stiffness,
            op,
            w: vec![0.0; n],
            z: vec![0.0; n],
            h_rms: 0.0,
            domain_cells: mask.iter().filter(|&&m| m > 0).count(),
            z_mean: 0.0,
            slope_rms: 0.0,
            t: vec![0.0; n],
            r: vec![0.0; n],
            y_prev: vec![0.0; n],
            active: vec![0; n],
            rows_on: vec![false; ny],
            rows_p: vec![true; ny],
            rows_t: vec![false; ny],
            loads: Vec::new(),
            fallback: [Vec::new(), Vec::new()],
            local_max_fraction: LOCAL_MAX_FRACTION,
            mask,
            coarse: None,
            nested: true,
            nested_min: NESTED_MIN,
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
        let on = || heights.iter().zip(&self.mask).filter(|(_, &m)| m > 0);
        let hmax = on().map(|(&h, _)| h).fold(f64::NEG_INFINITY, f64::max);
        let nm = self.domain_cells as f64;
        let mean = on().map(|(&h, _)| h).sum::<f64>() / nm;
        let var = on().map(|(&h, _)| (h - mean).powi(2)).sum::<f64>() / nm;
        // Flat faces (e.g. a flat punch under a mask) have no rms height: the gap is then
        // measured against the grid diagonal.
        self.h_rms = if var > 0.0 {
            var.sqrt()
        } else {
            (self.op.lx() * self.op.lx() + self.op.ly() * self.op.ly()).sqrt()
        };
        self.z_mean = hmax - mean;
        self.slope_rms = self.rms_slope(heights);
        self.z
            .par_iter_mut()
            .zip(self.w.par_iter_mut())
            .zip(heights)
            .for_each(|((z, w), h)| {
                *z = hmax - h;
                *w = *z;
            });
        self.coarse = None;
        Ok(())
    }

    /// Turns the nested start (module docs) on or off for the following solves.
    pub fn set_nested_start(&mut self, on: bool) {
        self.nested = on;
    }

    /// Rms slope sqrt(<(dh/dx)^2> + <(dh/dy)^2>), each mean over the pairs of adjacent
    /// domain cells (across the boundary too on a periodic operator).
    fn rms_slope(&self, h: &[f64]) -> f64 {
        let (nx, ny) = (self.op.nx(), self.op.ny());
        let wrap = self.op.is_periodic();
        let (dx, dy) = (self.op.lx() / nx as f64, self.op.ly() / ny as f64);
        let mask = &self.mask;
        // Sum of squared slopes and count over the pairs (a, b) of domain cells.
        let add = |(sum, pairs): &mut (f64, usize), a: usize, b: usize, step: f64| {
            if mask[a] > 0 && mask[b] > 0 {
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
    pub fn h_rms(&self) -> f64 {
        self.h_rms
    }

    /// Cells per sweep chunk: whole rows, about [`CHUNK`] cells.
    fn chunk(&self) -> usize {
        let nx = self.op.nx();
        (CHUNK / nx).max(1) * nx
    }

    /// Pass A: brings `w` up to date (`refresh`, then the pending force rescale of p
    /// and K p), marks the contact set (p > 0) in `active` and its rows in `rows_on`, and
    /// sums `w - offset` and the cell count over it. p is read in the rows `rows_p`
    /// marks only.
    fn pass_a(&mut self, p: &mut [f64], scale: f64, refresh: Refresh, offset: f64) -> [f64; 2] {
        let (nx, ch) = (self.op.nx(), self.chunk());
        let (loads, add_z) = match refresh {
            Refresh::Loads(l) => (l, 0.0),
            Refresh::AddZ => (&[][..], 1.0),
        };
        if !loads.is_empty() {
            self.op.add_point_loads(loads, &mut self.w);
        }
        // w = K p + z before, scale K p + z after (with add_z: w = K p before).
        let zf = 1.0 - scale * (1.0 - add_z);
        reduce(
            (
                p.par_chunks_mut(ch),
                self.z.par_chunks(ch),
                self.w.par_chunks_mut(ch),
                self.active.par_chunks_mut(ch),
                self.rows_p.par_chunks(ch / nx),
                self.rows_on.par_chunks_mut(ch / nx),
            ),
            |(p, z, w, act, with_p, on)| {
                sweeps::rescale(p, z, w, act, (with_p, on, nx), (scale, zf), offset)
            },
            None,
        )
    }

    /// The second half of a fresh `K p` (in `k_op`'s precision) whose input is loaded:
    /// K p into `w` (pass A then adds z).
    fn finish_into_w(&mut self, k_op: Operand) {
        let fc = ROWS_PER_CHUNK * self.op.nx();
        finish_fused(
            &mut self.op,
            k_op,
            &mut self.fallback,
            self.w.par_chunks_mut(fc),
            copy_out,
            None,
        );
    }

    /// Reads the changes pass D wrote to `r` in the chunks whose sums (`parts`, per
    /// chunk: total, changed cells, ...) count any, appending them to `loads` when
    /// given, and sets them back to zero (r is zero between passes).
    fn take_changes(&mut self, parts: &[[f64; 3]], mut loads: Option<&mut Vec<(usize, f64)>>) {
        let fc = ROWS_PER_CHUNK * self.op.nx();
        for (b, part) in parts.iter().enumerate() {
            if part[1] == 0.0 {
                continue;
            }
            let start = b * fc;
            let end = (start + fc).min(self.r.len());
            for (i, r) in self.r[start..end].iter_mut().enumerate() {
                if *r != 0.0 {
                    if let Some(l) = loads.as_deref_mut() {
                        l.push((start + i, *r));
                    }
                    *r = 0.0;
                }
            }
        }
    }

    /// Solves for `load`, starting from a previous solution `warm` where that pays (see
    /// the module docs; [`Solution::warm_started`] says whether it was used). A cold
    /// solve of a compact contact runs on a window first, one with a small start set
    /// restricted to a candidate set (module docs, [`Solution::restricted`]); if the
    /// window or the set outgrows its limit or a round does not converge, the attempt is
    /// dropped and the next path (last: the full iteration below) runs from its own
    /// start with `max_iterations` of its own (an attempt spends at most
    /// `max_iterations` iterations, over at most 8 rounds for a window and 24 for a
    /// set).
    ///
    /// Each iteration applies K once, to the conjugate direction t: `K p` moves by
    /// `-tau K t` and, where the projection clips a cell or re-admits an interpenetrating
    /// one, by K of those few point changes (a direct real-space sum below the
    /// operator's [`Compliance::point_load_limit`], a fresh `K p` above it). Before the
    /// solver reports convergence, `K p` is recomputed from scratch and the criterion
    /// re-evaluated, so rounding in the updates cannot pass for a solution.
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
        let n = self.op.cells();
        let area = self.op.cell_area();
        let nm = self.domain_cells;
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
            if self.op.is_periodic() && nm == n && d >= self.z_mean {
                return Err(BemError::Infeasible(format!(
                    "approach {d:e} reaches complete contact of a periodic surface \
                     (at max(h) - mean(h) = {:e} the force is unbounded); prescribe a \
                     force or mean pressure instead",
                    self.z_mean
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
        let warm = warm.filter(|w| warm_pays(w, load, target_force));
        let fixed_approach = match load {
            Load::Approach(d) => d,
            _ => 0.0,
        };
        let loaded = target_force.unwrap_or(fixed_approach) > 0.0;
        if warm.is_none() && loaded {
            if let Some(sol) = self.solve_windowed(target_force, fixed_approach, opts) {
                return Ok(sol);
            }
            if let Some(sol) = self.solve_restricted(target_force, fixed_approach, opts) {
                return Ok(sol);
            }
        }
        let mut p = vec![0.0; n];
        match (warm, load) {
            (Some(w), _) => p
                .par_iter_mut()
                .zip(&self.mask)
                .zip(&w.pressure)
                .for_each(|((p, &m), w)| *p = m as f64 * w.max(0.0)),
            (None, Load::Approach(d)) => self.overlap_start(&mut p, d),
            (None, _) => {
                let force = target_force.unwrap_or(0.0);
                if !(force > 0.0 && self.nested_start(&mut p, force, opts)) {
                    self.cold_start(&mut p, force, START_AREA);
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
            let s: f64 = p.iter().sum::<f64>() * area;
            p.par_iter_mut().for_each(|v| *v *= w / s);
        } else if let Load::Approach(d) = load {
            if d == 0.0 || p.iter().all(|&v| v == 0.0) {
                // No overlap anywhere: the first contact is at d = 0.
                return Ok(self.finish_unloaded(d));
            }
        }
        self.iterate(p, target_force, fixed_approach, opts, warm.is_some())
    }

    /// The projected, preconditioned conjugate-gradient iteration from the pressure `p`
    /// (on the domain, meeting the load), under force control (`target_force`) or at
    /// the approach `fixed_approach`.
    fn iterate(
        &mut self,
        mut p: Vec<f64>,
        target_force: Option<f64>,
        fixed_approach: f64,
        opts: &SolverOptions,
        warm_started: bool,
    ) -> Result<Solution> {
        let area = self.op.cell_area();
        let nm = self.domain_cells;
        let force_control = target_force.is_some();
        // <q, y> of the previous iteration (0: no direction yet).
        let mut gy_old = 0.0;
        // t and y_prev start at zero (y_prev is read before it is written; with beta = 0
        // its values do not matter). Written here, in parallel, each page of a fresh
        // buffer gets its own frame now: a page of `vec![0.0; n]` first read maps the
        // shared zero page, and its first write then copies it and flushes the other
        // threads' TLBs (measured: ~4 % of a two-thread solve at 1024^2).
        self.t
            .par_iter_mut()
            .zip(self.y_prev.par_iter_mut())
            .for_each(|(t, y)| {
                *t = 0.0;
                *y = 0.0;
            });
        self.rows_t.fill(false);
        self.rows_p.fill(true);
        // Sum of t over the contact set of the coming iteration (pass D).
        let mut t_on_set = 0.0;
        // K p carried along in single precision while the residual is above
        // SINGLE_UNTIL, where the operator rounds K so (its transforms; a dense
        // matrix's copy, whose K t alone is rounded, K p fresh in double precision).
        let mut single = self.op.rounds_single();
        let mut residual;
        // Residual below which K p is recomputed in double precision once more (-inf:
        // no more).
        let mut refresh_below = f64::NEG_INFINITY;
        // Pending factor of the load constraint: p and K p are rescaled lazily in pass A
        // (K is linear), saving a sweep.
        let mut scale = 1.0;
        let h_rms = self.h_rms;
        let limit = self.op.point_load_limit();
        // w = K p: pass A adds z.
        self.op.apply(&p, &mut self.w);
        let mut refresh_z = true;
        // Whether w holds K p + z recomputed from scratch (not updated).
        let mut exact = true;
        // Complete contact's floor (module docs): the criterion's best value so far (to a
        // factor 2) and the iterations since.
        let mut stall = (f64::INFINITY, 0usize);
        let mut loads = std::mem::take(&mut self.loads);
        let mut it = 0;
        let mut approach;
        // Cells the last update changed against p - tau t (a cold start changes many).
        let mut changed_last = if warm_started { 0.0 } else { f64::INFINITY };
        // Whether K is a transform whose inverse half an iteration can skip (module
        // docs); an operator applied as a whole would be applied twice.
        let skips = self.op.spectral(Operand::Compliance).is_some();
        loop {
            let refresh = if refresh_z {
                Refresh::AddZ
            } else {
                Refresh::Loads(&loads)
            };
            let [sum_g, nc] = self.pass_a(&mut p, scale, refresh, fixed_approach);
            refresh_z = false;
            loads.clear();
            scale = 1.0;
            // Force control: the approach is the mean gap over the contact set.
            let gbar = if force_control && nc > 0.0 {
                sum_g / nc
            } else {
                0.0
            };
            approach = fixed_approach + gbar;
            // Pass B, fused into M's row pass: the gap `g = w - approach` on the domain,
            // the criterion's terms (sum p |g|, sum p, max -g) and the residual
            // `q = [p > 0] g`, with its sum, as M's input.
            let (nx, fc) = (self.op.nx(), ROWS_PER_CHUNK * self.op.nx());
            // M by its stencil on a small contact set (module docs) instead of its
            // transforms (the same chunks, the same sums).
            let local = nc <= self.local_max_fraction * self.op.cells() as f64
                && self.op.local_stiffness().is_some();
            let residual_of =
                |(p, w, m, on), q: &mut [f64]| sweeps::residual(p, w, m, q, (on, nx), approach);
            let chunks = (
                p.par_chunks(fc),
                self.w.par_chunks(fc),
                self.mask.par_chunks(fc),
                self.rows_on.par_chunks(ROWS_PER_CHUNK),
            );
            let parts = if local {
                // The stencil reads q from the gap and the contact set: the chunk's q
                // goes to a scratch buffer.
                chunks
                    .into_par_iter()
                    .map(|item| with_scratch(item.0.len(), |q| residual_of(item, q)))
                    .collect()
            } else {
                load_fused(
                    &mut self.op,
                    Operand::Preconditioner,
                    &mut self.fallback,
                    chunks,
                    residual_of,
                )
            };
            let [pg, ps, worst, sum_q] = sum_parts(&parts, Some(2));
            residual = (if ps > 0.0 { pg / (ps * h_rms) } else { 0.0 }).max(worst / h_rms);
            if !residual.is_finite() {
                return Err(BemError::Breakdown {
                    what: "contact solve",
                    iterations: it,
                    residual,
                    reason: "non-finite residual",
                });
            }
            if single && residual <= SINGLE_UNTIL || residual <= refresh_below {
                // K p in double precision from here on, from a fresh one (the direction
                // is kept), and once more below REFRESH_AGAIN.
                refresh_below = if single && residual > REFRESH_AGAIN {
                    REFRESH_AGAIN
                } else {
                    f64::NEG_INFINITY
                };
                single = false;
                self.op.apply(&p, &mut self.w);
                refresh_z = true;
                exact = true;
                continue;
            }
            if residual < 0.5 * stall.0 {
                stall = (residual, 0);
            } else {
                stall.1 += 1;
            }
            let tolerance = if nc as usize == self.domain_cells && stall.1 >= STALL_ITERATIONS {
                self.complete_contact_tolerance(opts.tolerance, ps)
            } else {
                opts.tolerance
            };
            if residual <= tolerance {
                if !exact {
                    // Confirm on a fresh K p (the direction is kept).
                    self.op.apply(&p, &mut self.w);
                    refresh_z = true;
                    exact = true;
                    continue;
                }
                // Converged when the duality gap is within the tolerance too (module
                // docs); it is at most twice the criterion, so this rarely iterates on.
                if self.certificate(&p, approach) <= tolerance {
                    self.loads = loads;
                    let mut sol = self.finish(p, approach, it, residual);
                    sol.warm_started = warm_started;
                    return Ok(sol);
                }
            }
            if it == opts.max_iterations {
                break;
            }
            if opts.interrupted() {
                return Err(BemError::Interrupted {
                    what: "contact solve",
                    iterations: it,
                });
            }
            it += 1;
            // Preconditioned residual y = M q, with the sums of the projected
            // y = [p > 0] (M q - ybar), ybar its contact mean under force control (the
            // direction keeps the total force); y replaces y_prev once read.
            let chunks = (
                self.active.par_chunks(fc),
                self.w.par_chunks(fc),
                self.y_prev.par_chunks_mut(fc),
                self.rows_on.par_chunks(ROWS_PER_CHUNK),
            );
            let sums_of = |(act, w, y_prev, on), y: &[f64]| {
                sweeps::preconditioned(act, w, y_prev, y, (on, nx), approach)
            };
            // (The stencil is made only once a set is small.)
            let stencil = if local {
                self.op.local_stiffness()
            } else {
                None
            };
            let parts: Vec<[f64; 3]> = match stencil {
                Some(stencil) => {
                    // y = M q on the contact cells of each chunk's rows (in a scratch
                    // buffer), then its sums.
                    let grid = (&self.active[..], &self.w[..], approach);
                    chunks
                        .into_par_iter()
                        .enumerate()
                        .map(|(b, item)| {
                            let len = item.0.len();
                            with_scratch(len, |y| {
                                stencil.apply_rows(grid, y, item.3, b * ROWS_PER_CHUNK);
                                sums_of(item, y)
                            })
                        })
                        .collect()
                }
                _ => finish_fused(
                    &mut self.op,
                    Operand::Preconditioner,
                    &mut self.fallback,
                    chunks,
                    sums_of,
                    Some(&self.rows_on),
                ),
            };
            let [sum_y, qy, qy_prev] = sum_parts(&parts, None);
            let ybar = if force_control && nc > 0.0 {
                sum_y / nc
            } else {
                0.0
            };
            // <q, y>: the preconditioned residual norm (p > 0 implies the mask).
            let gy = qy - ybar * sum_q;
            // Polak-Ribiere+ (module docs): <q, y - y_prev> / <q_prev, y_prev>, >= 0.
            let beta = if gy_old > 0.0 {
                ((gy - qy_prev) / gy_old).max(0.0)
            } else {
                0.0
            };
            gy_old = gy;
            // Conjugate direction t = y + beta t, with <q, t>, as K's input; the
            // projected y is kept. Under force control the old t is first projected too
            // (its mean over the contact set removed), so that t sums to zero there.
            let tbar = if force_control && nc > 0.0 {
                t_on_set / nc
            } else {
                0.0
            };
            let dir = sweeps::Direction {
                ybar,
                tbar,
                beta,
                approach,
            };
            // A fresh K p in the precision it is carried in; K t in single precision to
            // the end, where the operator has it (module docs).
            let kp_op = if single {
                Operand::ComplianceSingle
            } else {
                Operand::Compliance
            };
            let kt_op = Operand::ComplianceSingle;
            let parts = load_fused(
                &mut self.op,
                kt_op,
                &mut self.fallback,
                (
                    self.active.par_chunks(fc),
                    self.w.par_chunks(fc),
                    self.t.par_chunks_mut(fc),
                    self.y_prev.par_chunks_mut(fc),
                    self.rows_on.par_chunks(ROWS_PER_CHUNK),
                    self.rows_t.par_chunks(ROWS_PER_CHUNK),
                ),
                |(act, w, t, y_prev, on, was), out| {
                    sweeps::direction(act, w, t, y_prev, out, (on, was, nx), dir)
                },
            );
            self.rows_t.copy_from_slice(&self.rows_on);
            let [num] = sum_parts(&parts, None);
            // K t, its rows fused with pass D below: the step length needs <t, K t> over
            // the whole grid first, which K's column pass gives (Parseval). Under force
            // control t sums to zero on the contact set, so the step needs no shift of
            // K t by a contact mean.
            // While the contact set still changes in more cells than point loads can
            // follow, K p is recomputed after the update anyway: K t is then needed for
            // its energy only (predicted from the last iteration's changes, module docs).
            let fresh = skips && changed_last > (2 * limit) as f64;
            let tkt = if fresh {
                energy_fused(&mut self.op, kt_op, &mut self.fallback)
            } else {
                apply_fused(&mut self.op, kt_op, &mut self.fallback, true)
            };
            let tau = if tkt > 0.0 && num.is_finite() {
                num / tkt
            } else {
                0.0
            };
            // Pass D: projected update; interpenetrating cells without pressure re-enter
            // the contact set (Polonsky & Keer's overlap correction). w follows p along
            // t exactly; the cells where the projection departs from p - tau t are
            // collected (up to the limit) for pass A.
            // Re-admitted cells get -step g: the step times the stiffness of the longest
            // wavelength (a small, scale-consistent pressure the next iterations adjust;
            // measured on the benchmark surfaces: the preconditioner's diagonal or the
            // inverse self-compliance as the scale cost 5-9 % more iterations). With unit
            // E* and size this is Polonsky & Keer's -tau g.
            let step = self.overlap_stiffness * if tau > 0.0 { tau } else { 1.0 / nm as f64 };
            // Per chunk: total pressure, changed cells, t summed over the new contact
            // set; without a fresh K p, the change p_new - (p - tau t) goes to r.
            let upd = sweeps::Update {
                tau,
                approach,
                step,
            };
            let parts = if fresh {
                // The update as the input of a fresh K p, in K's precision.
                let parts = load_fused(
                    &mut self.op,
                    kp_op,
                    &mut self.fallback,
                    (
                        p.par_chunks_mut(fc),
                        self.t.par_chunks(fc),
                        self.w.par_chunks(fc),
                        self.mask.par_chunks(fc),
                        self.rows_p.par_chunks_mut(ROWS_PER_CHUNK),
                    ),
                    |(p, t, w, m, with_p), values| {
                        sweeps::advance(p, t, w, m, values, (with_p, nx), upd)
                    },
                );
                self.finish_into_w(kp_op);
                refresh_z = true;
                exact = !single;
                parts
            } else {
                let parts = store_fused(
                    &mut self.op,
                    kt_op,
                    &mut self.fallback,
                    (
                        p.par_chunks_mut(fc),
                        self.t.par_chunks(fc),
                        self.r.par_chunks_mut(fc),
                        self.w.par_chunks_mut(fc),
                        self.mask.par_chunks(fc),
                        self.rows_p.par_chunks_mut(ROWS_PER_CHUNK),
                    ),
                    |(p, t, r, w, m, with_p), kt| {
                        sweeps::update(p, t, r, (w, kt), m, (with_p, nx), upd)
                    },
                    None,
                );
                let changed = sum_parts(&parts, None)[1];
                let too_many = changed > limit as f64;
                // The changes as point loads (unless too many), and r zero again.
                self.take_changes(&parts, (!too_many).then_some(&mut loads));
                if too_many {
                    // A fresh K p (in K's precision).
                    if single {
                        load_fused(
                            &mut self.op,
                            kp_op,
                            &mut self.fallback,
                            p.par_chunks(fc),
                            copy_in,
                        );
                        self.finish_into_w(kp_op);
                    } else {
                        self.op.apply(&p, &mut self.w);
                    }
                    refresh_z = true;
                    exact = !single;
                } else {
                    exact = false;
                }
                parts
            };
            let [total, changed, t_set] = sum_parts(&parts, None);
            t_on_set = t_set;
            changed_last = changed;
            scale = match target_force {
                Some(w) if total > 0.0 => w / (total * area),
                _ => 1.0,
            };
        }
        // Not converged: report the last iterate, on a fresh K p.
        p.iter_mut().for_each(|v| *v *= scale);
        self.op.apply(&p, &mut self.w);
        let [sum_g, nc] = self.pass_a(&mut p, 1.0, Refresh::AddZ, fixed_approach);
        if force_control && nc > 0.0 {
            approach = sum_g / nc;
        }
        self.loads = loads;
        let mut last = self.finish(p, approach, opts.max_iterations, residual);
        last.warm_started = warm_started;
        Err(BemError::NoConvergence {
            what: "contact solve",
            iterations: opts.max_iterations,
            residual,
            tolerance: opts.tolerance,
            last: Box::new(last),
        })
    }

    /// Cold start under force control (module docs): p = (d - z)+ on the domain, d the
    /// height quantile whose overlap covers `start_area p / (E* h')` of it ([`START_AREA`]
    /// for the full iteration); the rescale to the force follows. Uniform pressure when
    /// the heights have no slope.
    fn cold_start(&self, p: &mut [f64], force: f64, start_area: f64) {
        let nm = self.domain_cells;
        let fraction = self.start_fraction(force, start_area);
        if nm >= 2 && fraction.is_finite() && fraction < 1.0 {
            let k = ((fraction * nm as f64).ceil() as usize).clamp(1, nm - 1);
            let d = self.kth_height(k);
            p.par_iter_mut()
                .zip(&self.mask)
                .zip(&self.z)
                .for_each(|((v, &m), z)| *v = m as f64 * (d - z).max(0.0));
        }
        if p.iter().all(|&v| v == 0.0) {
            self.uniform_start(p);
        }
    }

    /// The k-th smallest (from 0) of z over the domain cells, as a sort would give it
    /// (bit for bit): a histogram of the values, made in parallel, finds the bin that
    /// holds rank k (bins are monotone in z), and the selection runs among that bin's
    /// values only (a serial selection over a 1024^2 grid's copy costs about 20 ms).
    fn kth_height(&self, k: usize) -> f64 {
        const BINS: usize = 4096;
        let ch = self.chunk();
        // The domain's heights, a chunk at a time in parallel.
        let domain = || {
            let chunks = self.z.par_chunks(ch).zip(self.mask.par_chunks(ch));
            chunks.map(|(z, m)| z.iter().zip(m).filter(|(_, &m)| m > 0).map(|(&v, _)| v))
        };
        let wide = (f64::INFINITY, f64::NEG_INFINITY);
        let (lo, hi) = domain()
            .map(|vals| vals.fold(wide, |(a, b), v| (a.min(v), b.max(v))))
            .reduce(|| wide, |a, b| (a.0.min(b.0), a.1.max(b.1)));
        let scale = (BINS - 1) as f64 / (hi - lo);
        let bin = |v: f64| match scale.is_finite() {
            true => ((v - lo) * scale) as usize,
            false => 0,
        };
        let counts = domain()
            .map(|vals| {
                let mut c = vec![0usize; BINS];
                vals.for_each(|v| c[bin(v)] += 1);
                c
            })
            .reduce(
                || vec![0usize; BINS],
                |mut a, b| {
                    a.iter_mut().zip(&b).for_each(|(x, y)| *x += y);
                    a
                },
            );
        // The bin of rank k and the ranks below it.
        let (mut target, mut before) = (BINS - 1, 0);
        for (b, &c) in counts.iter().enumerate() {
            if before + c > k {
                target = b;
                break;
            }
            before += c;
        }
        let mut vals: Vec<f64> = domain()
            .flat_map_iter(|vals| vals.filter(move |&v| bin(v) == target))
            .collect();
        *vals.select_nth_unstable_by(k - before, f64::total_cmp).1
    }

    /// Uniform pressure (one per domain cell; the load's rescale follows).
    fn uniform_start(&self, p: &mut [f64]) {
        p.par_iter_mut()
            .zip(&self.mask)
            .for_each(|(v, &m)| *v = m as f64);
    }

    /// Nested start under force control (module docs): the load solved to
    /// [`NESTED_TOLERANCE`] on the grid coarsened 2 x 2 (heights averaged over each
    /// coarse cell's four cells), each coarse cell's pressure given to its four cells.
    /// False, with p untouched, where it does not apply: nesting off, a side below
    /// [`NESTED_MIN`] ([`COARSE_NESTED_MIN`] on a coarse grid) or odd, a mask, an
    /// operator without a coarse form, or a coarse solve that fails (the cold start
    /// then runs as without it).
    fn nested_start(&mut self, p: &mut [f64], force: f64, opts: &SolverOptions) -> bool {
        let (nx, ny) = (self.op.nx(), self.op.ny());
        if !self.nested
            || nx < self.nested_min
            || ny < self.nested_min
            || self.domain_cells != self.op.cells()
        {
            return false;
        }
        if self.coarse.is_none() {
            self.coarse = self.coarse_solver().map(Box::new);
        }
        let Some(coarse) = self.coarse.as_deref_mut() else {
            return false;
        };
        let loose = SolverOptions {
            tolerance: NESTED_TOLERANCE.max(opts.tolerance),
            max_iterations: opts.max_iterations.min(NESTED_MAX_ITERATIONS),
            ..opts.clone()
        };
        let Ok(sol) = coarse.solve_on_pool(Load::Force(force), &loose, None) else {
            return false;
        };
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
        true
    }

    /// The solver on this grid coarsened 2 x 2 (heights averaged over each coarse
    /// cell's four cells), nesting again from [`COARSE_NESTED_MIN`]; None if the
    /// operator has no coarse form.
    fn coarse_solver(&self) -> Option<ContactSolver<K>> {
        let op = self.op.coarse()?;
        let (nx, cx) = (self.op.nx(), op.nx());
        let z = &self.z;
        let heights: Vec<f64> = (0..op.cells())
            .into_par_iter()
            .map(|k| {
                let i = 2 * (k / cx) * nx + 2 * (k % cx);
                -0.25 * (z[i] + z[i + 1] + z[i + nx] + z[i + nx + 1])
            })
            .collect();
        let mut s = ContactSolver::new(op, &heights, None).ok()?;
        s.nested_min = COARSE_NESTED_MIN;
        Some(s)
    }

    /// The fraction of the domain the cold start's overlap covers (may be >= 1 or not
    /// finite: then the start is uniform).
    fn start_fraction(&self, force: f64, start_area: f64) -> f64 {
        let mean_pressure = force / (self.domain_cells as f64 * self.op.cell_area());
        start_area * mean_pressure / (self.op.e_star() * self.slope_rms)
    }

    /// Start at the approach `d`: the overlap `(d - z)+` times the stiffness of the
    /// longest wavelength.
    fn overlap_start(&self, p: &mut [f64], d: f64) {
        let scale = self.op.e_star() / (self.op.lx() * self.op.ly()).sqrt();
        p.par_iter_mut()
            .zip(&self.mask)
            .zip(&self.z)
            .for_each(|((v, &m), z)| *v = m as f64 * (d - z).max(0.0) * scale);
    }

    /// The solution without contact: w = z (no pressure), approach `d`.
    fn finish_unloaded(&mut self, d: f64) -> Solution {
        self.w.copy_from_slice(&self.z);
        let n = self.op.cells();
        self.finish(vec![0.0; n], d, 0, 0.0)
    }

    /// The tolerance a solve in complete contact can reach (module docs, "Complete
    /// contact"): the requested one, or [`COMPLETE_CONTACT_FLOOR`] ulps of the
    /// displacement scale of the mean pressure, `p_mean sqrt(lx ly) / E*`, over the rms
    /// height if that is larger. `pressure_sum`: the sum of p over the domain cells.
    fn complete_contact_tolerance(&self, tolerance: f64, pressure_sum: f64) -> f64 {
        let mean = pressure_sum / self.domain_cells as f64;
        let scale = mean * (self.op.lx() * self.op.ly()).sqrt() / self.op.e_star();
        tolerance.max(COMPLETE_CONTACT_FLOOR * f64::EPSILON * scale / self.h_rms)
    }

    /// The duality (Frank-Wolfe) gap of `p` over the pressures carrying its force,
    /// relative to that force times the rms height: `sum_i p_i (g_i - g_low) / (sum_i
    /// p_i h_rms)` over the domain, `g = w - approach` (`w = K p + z` up to date),
    /// `g_low = min(0, min_j g_j)` (an upper bound of the gap with `min_j g_j`); 0
    /// without pressure. It bounds the energy error of p, hence its error in the norm of
    /// K (module docs).
    fn certificate(&self, p: &[f64], approach: f64) -> f64 {
        let ch = self.chunk();
        let [pg, ps, low] = reduce(
            (
                p.par_chunks(ch),
                self.w.par_chunks(ch),
                self.mask.par_chunks(ch),
            ),
            |(p, w, m)| sweeps::certificate_terms(p, w, m, approach),
            Some(2),
        );
        if ps > 0.0 {
            (pg / ps + low.max(0.0)) / self.h_rms
        } else {
            0.0
        }
    }

    /// Collects the solution from p and w = K p + z.
    fn finish(&mut self, p: Vec<f64>, approach: f64, iterations: usize, residual: f64) -> Solution {
        let area = self.op.cell_area();
        let d = if approach.is_finite() { approach } else { 0.0 };
        let gap: Vec<f64> = self
            .w
            .par_iter()
            .zip(&self.mask)
            .map(|(w, &m)| if m > 0 { (w - d).max(0.0) } else { 0.0 })
            .collect();
        let contact_cells = p.iter().filter(|&&v| v > 0.0).count();
        let certificate = self.certificate(&p, d);
        Solution {
            certificate,
            force: p.iter().sum::<f64>() * area,
            contact_cells,
            contact_area: contact_cells as f64 * area,
            mean_gap: gap.iter().sum::<f64>() / self.domain_cells as f64,
            gap,
            pressure: p,
            approach,
            iterations,
            residual,
            domain_cells: self.domain_cells,
            warm_started: false,
            restricted: false,
        }
    }

    /// Tangent normal stiffness dF/dd with the contact set held fixed: solves
    /// `K_CC x = 1` on the contact cells C by conjugate gradients (K_CC is symmetric
    /// positive definite; preconditioned by the operator's M restricted to C) to
    /// relative residual `opts.tolerance` within `opts.max_iterations`;
    /// k = sum(x) * cell area.
    ///
    /// No contact: k = 0. Complete contact of an unmasked periodic surface: k = +inf
    /// (K_CC is then K itself, whose mean mode is free: the force grows at a fixed
    /// approach). A non-finite or vanishing step is a [`BemError::Breakdown`].
    pub fn tangent_stiffness(&mut self, sol: &Solution, opts: &SolverOptions) -> Result<f64> {
        crate::pool::on_pool(|| self.tangent_stiffness_on_pool(sol, opts))
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
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let mut x = vec![0.0; n];
        let mut res = c.clone();
        let mut zr = res.clone();
        self.op.precondition(&mut zr);
        zr.iter_mut().zip(&c).for_each(|(v, m)| *v *= m);
        let mut dir = zr.clone();
        let mut q = vec![0.0; n];
        let b_norm = (nc as f64).sqrt();
        let mut rz = dot(&res, &zr);
        let mut residual = 1.0;
        for it in 0..=opts.max_iterations {
            residual = dot(&res, &res).sqrt() / b_norm;
            if !residual.is_finite() {
                return Err(BemError::Breakdown {
                    what: WHAT,
                    iterations: it,
                    residual,
                    reason: "non-finite residual",
                });
            }
            if residual <= opts.tolerance {
                return Ok(x.iter().sum::<f64>() * self.op.cell_area());
            }
            if it == opts.max_iterations {
                break;
            }
            if opts.interrupted() {
                return Err(BemError::Interrupted {
                    what: WHAT,
                    iterations: it,
                });
            }
            self.op.apply(&dir, &mut q);
            q.iter_mut().zip(&c).for_each(|(v, m)| *v *= m);
            let curvature = dot(&dir, &q);
            if !(curvature > 0.0 && curvature.is_finite() && rz > 0.0) {
                return Err(BemError::Breakdown {
                    what: WHAT,
                    iterations: it,
                    residual,
                    reason: "vanishing or non-finite step",
                });
            }
            let alpha = rz / curvature;
            for i in 0..n {
                x[i] += alpha * dir[i];
                res[i] -= alpha * q[i];
            }
            zr.copy_from_slice(&res);
            self.op.precondition(&mut zr);
            zr.iter_mut().zip(&c).for_each(|(v, m)| *v *= m);
            let rz_new = dot(&res, &zr);
            let beta = rz_new / rz;
            for i in 0..n {
                dir[i] = zr[i] + beta * dir[i];
            }
            rz = rz_new;
        }
        Err(BemError::NoConvergence {
            what: WHAT,
            iterations: opts.max_iterations,
            residual,
            tolerance: opts.tolerance,
            last: Box::new(sol.clone()),
        })
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
                    .filter(|&i| s.mask[i] > 0)
                    .map(|i| s.z[i])
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
            (s.slope_rms - want).abs() < 1e-12 * want,
            "{} {want}",
            s.slope_rms
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
            (s.slope_rms - want).abs() < 1e-12 * want,
            "{} {want}",
            s.slope_rms
        );
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
        fn run<K: Compliance>(op: K, h: &[f64], fraction: f64, threads: usize) -> Solution {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut s = ContactSolver::new(op, h, None).unwrap();
                s.local_max_fraction = fraction;
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
                !by_stencil.restricted && !by_transforms.restricted,
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
