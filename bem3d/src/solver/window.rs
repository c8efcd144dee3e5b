//! Compact contacts on a non-periodic grid: the solve restricted to a window (a box of
//! cells) that holds the whole contact, with the operator's own transforms at the window's
//! size ([`GridForms::window`](crate::operator::GridForms::window)), inside an outer loop
//! that grows the window until no cell outside it interpenetrates.
//!
//! A sphere pressed to 1 % contact on a 1024^2 grid touches a disc about 115 cells
//! across; the non-periodic operator's zero-padded transforms run over 2048^2 cells, a
//! window of 192^2 pads to 384^2: an iteration there costs about 1/30 of one on the
//! grid. Between cells of the window the influence coefficients are the grid's own
//! (Love's kernel depends on the offset only), so the window's problem has the same
//! solution as the grid's as soon as that solution carries no pressure outside it.
//! Each round solves on the window with the same preconditioned iteration (to a loose
//! tolerance while the window may still grow, then to half the requested one),
//! scatters the pressure, applies K on the whole grid once and evaluates the solver's
//! criterion there: converged, or the window grows to hold the interpenetrating cells
//! (none: the next round solves to the tolerance). Only cells below the approach can
//! interpenetrate (the kernel is positive): when they are few, their gaps come from
//! direct sums instead, and a round that finds some (or a loose round that finds none)
//! skips the grid's application. The reported solution is checked on the full grid
//! like any other. Spread contacts (rough surfaces: their start covers
//! the grid) skip it at the cost of one start and its bounding box; a window that
//! would exceed [`MAX_FRACTION`] of the grid's cells, or a round that does not
//! converge, gives the attempt up (the next path runs from its own start).

use super::options::{SolverOptions, Target};
use super::rounds::{Part, Round, Tally};
use super::state::{ContactSolver, Gap0};
use crate::operator::GridOperator;
use crate::operator::NonPeriodicHalfSpace;
use crate::solution::{Path, Solution};
use rayon::prelude::*;

/// The start's overlap covers this many times `p / (E* h')` of the domain under force
/// control (half the full solve's [`super::start::FULL_GRID_START_AREA`]). Measured on a
/// sphere (R = 1
/// on the unit square, one thread, 512^2 and 1024^2), solve times at 0.1 %, 1 %, 20 %
/// and 30 % contact with 6 / 3 / 2 here: 1024^2 0.24 / 0.17 / 0.20 s, 0.27 / 0.21 /
/// 0.35 s, 2.9 (no window: the start's box exceeds the limit) / 0.84 / 1.74 s, 3.1 (no
/// window) / 1.98 / 0.92 s; 512^2 within 0.03 s at 0.1-1 %, 0.59 (none) / 0.18 / 0.28 s
/// at 20 %. A start that misses part of the contact costs a loose round on a small
/// window.
const WINDOW_START_AREA: f64 = 3.0;
/// Largest window, as a fraction of the grid's cells: the window's transforms then
/// cost at most 0.7 of the grid's per iteration, and its rounds add about three
/// full-grid applications of K (a sphere at 20 % contact on 1024^2 takes 26 iterations
/// either way).
const MAX_FRACTION: f64 = 0.7;
/// Cells added on each side of the start's bounding box, as a fraction of its width
/// (at least [`MIN_MARGIN`]).
const MARGIN: f64 = 0.125;
const MIN_MARGIN: usize = 2;

/// A box of cells `[x0, x0 + wx) x [y0, y0 + wy)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Window {
    pub(crate) x0: usize,
    pub(crate) y0: usize,
    pub(crate) wx: usize,
    pub(crate) wy: usize,
}

impl Window {
    /// Whether the cell (x, y) lies in the box.
    pub(crate) fn holds(&self, x: usize, y: usize) -> bool {
        (self.x0..self.x0 + self.wx).contains(&x) && (self.y0..self.y0 + self.wy).contains(&y)
    }
}

/// Smallest number >= n of the form 2^a 3^b 5^c (fast transform lengths).
pub(crate) fn smooth(n: usize) -> usize {
    (n.max(1)..)
        .find(|&m| {
            let mut r = m;
            for f in [2, 3, 5] {
                while r % f == 0 {
                    r /= f;
                }
            }
            r == 1
        })
        .unwrap_or(n)
}

/// The cells `[lo, hi]` (inclusive) of a side of `len` cells with a margin, widened to a
/// fast length and shifted to lie inside `0..len`: (start, width).
fn span(lo: usize, hi: usize, len: usize) -> (usize, usize) {
    let margin = ((MARGIN * (hi - lo + 1) as f64).ceil() as usize).max(MIN_MARGIN);
    let (a, b) = (lo.saturating_sub(margin), (hi + margin).min(len - 1));
    let width = smooth(b - a + 1).min(len);
    // Centre the extra cells, then keep the window inside the grid.
    let start = a.saturating_sub((width - (b - a + 1)) / 2).min(len - width);
    (start, width)
}

/// The window path's part: the bounding box of the cells to hold (inclusive: x_lo,
/// x_hi, y_lo, y_hi), the grid's row and column counts, and the window with its solver
/// (kept while the window holds).
pub(super) struct WindowPart {
    bounds: (usize, usize, usize, usize),
    nx: usize,
    ny: usize,
    /// Whether the window is forced (its size limit is then lifted).
    forced: bool,
    win: Window,
    inner: Option<(Window, ContactSolver<NonPeriodicHalfSpace>)>,
}

impl WindowPart {
    /// The start of a windowed solve from a cold start (module docs), holding `target`:
    /// the part, the grid's pressure (scaled to the target force) and whether the first
    /// round solves to the tolerance. Err: why it does not apply (the next path then
    /// runs from its own start, unless the window is forced: then the windows' size
    /// limit is lifted and the reason is the solve's error).
    pub(super) fn start<K: GridOperator>(
        grid: &ContactSolver<K>,
        target: Target,
        opts: &SolverOptions,
    ) -> Result<(Self, Vec<f64>, bool), String> {
        let (op, problem) = (&grid.op, &grid.problem);
        let (n, nx, ny) = (op.cells(), op.nx(), op.ny());
        // Operators without windows stop here (a 1 x 1 probe costs next to nothing).
        if op.window(1, 1).is_none() {
            return Err("the operator has no windows (the non-periodic half-space has)".into());
        }
        let mut p = vec![0.0; n];
        match target {
            Target::Force(f) => problem.cold_start(op, &mut p, f, WINDOW_START_AREA),
            Target::Approach(d) => problem.overlap_start(op, &mut p, d),
        }
        let bounds = bounding_box_where(nx, n, |i| p[i] > 0.0).ok_or("the start holds no cell")?;
        if let Target::Force(f) = target {
            let s: f64 = p.iter().sum::<f64>() * op.cell_area();
            p.par_iter_mut().for_each(|v| *v *= f / s);
        }
        let part = WindowPart {
            bounds,
            nx,
            ny,
            forced: opts.paths.window.forced(),
            win: Window {
                x0: 0,
                y0: 0,
                wx: 0,
                wy: 0,
            },
            inner: None,
        };
        // At a prescribed approach the contact lies inside the start's overlap (K has a
        // positive kernel: no displacement below the surface's level), so the first
        // window holds it and its round solves to the tolerance at once.
        Ok((part, p, target.force().is_none()))
    }
}

impl<K: GridOperator> Part<K> for WindowPart {
    type Op = NonPeriodicHalfSpace;
    const NAME: &'static str = "window";
    const MAX_ROUNDS: usize = 8;

    fn prepare(&mut self, grid: &ContactSolver<K>) -> Result<(), String> {
        let (x0, wx) = span(self.bounds.0, self.bounds.1, self.nx);
        let (y0, wy) = span(self.bounds.2, self.bounds.3, self.ny);
        self.win = Window { x0, y0, wx, wy };
        if !self.forced && (wx * wy) as f64 > MAX_FRACTION * (self.nx * self.ny) as f64 {
            return Err(format!(
                "a window of {wx} x {wy} cells exceeds {MAX_FRACTION} of the grid"
            ));
        }
        if self.inner.as_ref().map(|(w, _)| *w) != Some(self.win) {
            let op = grid
                .op
                .window(wx, wy)
                .ok_or_else(|| format!("the operator has no {wx} x {wy} window"))?;
            self.inner = Some((self.win, on_window(grid, op, self.win)));
        }
        Ok(())
    }

    fn solver(&mut self) -> Option<&mut ContactSolver<NonPeriodicHalfSpace>> {
        self.inner.as_mut().map(|(_, s)| s)
    }

    fn gather(&self, p: &[f64]) -> Vec<f64> {
        gather(p, self.nx, self.win)
    }

    fn scatter(&self, p: &mut [f64], values: &[f64]) {
        scatter(p, self.nx, self.win, values)
    }

    /// The interpenetrating cells outside the window, and the criterion: by direct sums
    /// where they pay ([`gaps_outside`]), else on the whole grid; the window grows to
    /// hold them and the pressure carried so far.
    fn judge(
        &mut self,
        grid: &mut ContactSolver<K>,
        p: &mut Vec<f64>,
        sol: &Solution,
        tally: &Tally,
        tight: bool,
        (target, opts): (Target, &SolverOptions),
    ) -> Result<Round, String> {
        let (nx, n, win) = (self.nx, p.len(), self.win);
        let (grow, residual) = match gaps_outside(grid, p, win, sol.approach) {
            Some(gaps) if gaps.iter().any(|&(_, g)| g < 0.0) => {
                let worst = gaps.iter().fold(0.0f64, |m, &(_, g)| m.max(-g));
                let cells = gaps.iter().filter(|&&(_, g)| g < 0.0).map(|&(i, _)| i);
                (
                    bounding_box(nx, cells),
                    sol.residual.max(worst / grid.problem.h_rms),
                )
            }
            // None: a loose round goes on to the tight one without the grid's check.
            Some(_) if !tight => (None, sol.residual),
            _ => {
                let (approach, residual) =
                    match grid.on_grid(p, target, (tally, Path::Window), opts) {
                        Ok(sol) => return Ok(Round::Solved(sol)),
                        Err(found) => found,
                    };
                let (w, mask) = (&grid.work.w, &grid.problem.mask);
                let outside = bounding_box_where(nx, n, |i| {
                    mask.holds(i) && w[i] - approach < 0.0 && !win.holds(i % nx, i / nx)
                });
                (outside, residual)
            }
        };
        // Interpenetrating cells outside the window join it.
        let Some(grow) = grow else {
            return Ok(Round::Held(residual));
        };
        // The next window holds those cells and the pressure carried so far (which may
        // lie in this window's margin).
        let held = bounding_box_where(nx, n, |i| p[i] > 0.0).unwrap_or(grow);
        let b = self.bounds;
        self.bounds = (
            b.0.min(grow.0).min(held.0),
            b.1.max(grow.1).max(held.1),
            b.2.min(grow.2).min(held.2),
            b.3.max(grow.3).max(held.3),
        );
        Ok(Round::Grown(residual))
    }
}

/// The gaps `(cell, g)` of the cells outside `win` that may interpenetrate at
/// `approach` with the pressure `p` (held by the window): those below the approach
/// (z < approach; elsewhere g >= z - approach >= 0, Love's kernel being positive), K p
/// there by direct sums. None when the sums would cost more than one product per grid
/// cell (an application of K on the grid costs several times that) or the operator has
/// no real-space table.
fn gaps_outside<K: GridOperator>(
    grid: &ContactSolver<K>,
    p: &[f64],
    win: Window,
    approach: f64,
) -> Option<Vec<(usize, f64)>> {
    let nx = grid.op.nx();
    let (mask, z) = (&grid.problem.mask, &grid.problem.z);
    // Rows in parallel, cells in index order.
    let at: Vec<usize> = (0..p.len() / nx)
        .into_par_iter()
        .flat_map_iter(|y| {
            let below = move |&x: &usize| {
                let i = y * nx + x;
                mask.holds(i) && z.at(i) < approach && !win.holds(x, y)
            };
            (0..nx).filter(below).map(move |x| y * nx + x)
        })
        .collect();
    let loads: Vec<(usize, f64)> = p
        .par_chunks(nx)
        .enumerate()
        .flat_map_iter(|(y, row)| {
            let on = row.iter().enumerate().filter(|(_, &v)| v > 0.0);
            on.map(move |(x, &v)| (y * nx + x, v))
        })
        .collect();
    if at.len().saturating_mul(loads.len()) > p.len() {
        return None;
    }
    let u = grid.op.displacements_at(&at, &loads)?;
    Some(
        at.into_iter()
            .zip(u)
            .map(|(i, u)| (i, u + z.at(i) - approach))
            .collect(),
    )
}

/// A solver for the problem on a window: `op` its half-space, the grid's heights and
/// mask there, and the criterion's and the re-admission's scales of the whole domain.
fn on_window<K: GridOperator>(
    grid: &ContactSolver<K>,
    op: NonPeriodicHalfSpace,
    win: Window,
) -> ContactSolver<NonPeriodicHalfSpace> {
    let nx = grid.op.nx();
    let problem = &grid.problem;
    let mask = problem.mask.cells().map(|m| gather(m, nx, win));
    let z = gather_z(&problem.z, nx, win);
    ContactSolver::on_part(op, mask, z, problem.h_rms, problem.overlap_stiffness)
}

/// The values of a window of a grid of row length `nx`, row-major.
pub(crate) fn gather<T: Copy>(grid: &[T], nx: usize, win: Window) -> Vec<T> {
    (win.y0..win.y0 + win.wy)
        .flat_map(|y| {
            grid[y * nx + win.x0..y * nx + win.x0 + win.wx]
                .iter()
                .copied()
        })
        .collect()
}

/// z over a window of a grid of row length `nx`, row-major.
fn gather_z(z: &Gap0, nx: usize, win: Window) -> Vec<f64> {
    let map = z.map;
    gather(z.values(), nx, win)
        .into_iter()
        .map(|v| map.of(v))
        .collect()
}

/// `p` zero but in the window, which holds `values` (row-major, the window's width).
fn scatter(p: &mut [f64], nx: usize, win: Window, values: &[f64]) {
    p.par_chunks_mut(nx).enumerate().for_each(|(y, row)| {
        row.fill(0.0);
        if (win.y0..win.y0 + win.wy).contains(&y) {
            let r = y - win.y0;
            row[win.x0..win.x0 + win.wx].copy_from_slice(&values[r * win.wx..(r + 1) * win.wx]);
        }
    });
}

/// [`bounding_box`] of the cells `i < n` of a grid of row length `nx` for which
/// `on(i)`, rows in parallel.
pub(crate) fn bounding_box_where(
    nx: usize,
    n: usize,
    on: impl Fn(usize) -> bool + Sync,
) -> Option<(usize, usize, usize, usize)> {
    (0..n / nx)
        .into_par_iter()
        .filter_map(|y| {
            let row = y * nx..(y + 1) * nx;
            let first = row.clone().find(|&i| on(i))?;
            let last = row.rev().find(|&i| on(i))?;
            Some((first - y * nx, last - y * nx, y, y))
        })
        .reduce_with(|a, b| (a.0.min(b.0), a.1.max(b.1), a.2.min(b.2), a.3.max(b.3)))
}

/// Inclusive bounding box `(x_lo, x_hi, y_lo, y_hi)` of cells of a grid of row length
/// `nx` (None: no cells).
fn bounding_box(
    nx: usize,
    cells: impl Iterator<Item = usize>,
) -> Option<(usize, usize, usize, usize)> {
    cells.fold(None, |b, i| {
        let (x, y) = (i % nx, i / nx);
        Some(match b {
            None => (x, x, y, y),
            Some((a, b, c, d)) => (a.min(x), b.max(x), c.min(y), d.max(y)),
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_lengths_and_spans_stay_inside_the_grid() {
        assert_eq!(smooth(1), 1);
        assert_eq!(smooth(7), 8);
        assert_eq!(smooth(97), 100);
        assert_eq!(smooth(121), 125);
        // Margin 2 on each side of 3 cells: 7, widened to 8.
        assert_eq!(span(10, 12, 100), (8, 8));
        // Clipped at the grid's edges (5 cells), or shifted inwards (7 -> 8).
        assert_eq!(span(0, 2, 100), (0, 5));
        assert_eq!(span(95, 99, 100), (92, 8));
        // Never wider than the grid.
        assert_eq!(span(0, 99, 100), (0, 100));
        assert_eq!(span(1, 95, 97), (0, 97));
    }
}
