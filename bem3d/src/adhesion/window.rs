//! The adhesive solve of a round on a window of the grid: a box of cells that holds the
//! whole contact set and the cells that may join, with the operator's own transforms at
//! the box's size ([`GridForms::window`]).
//!
//! A round's pressure vanishes on every cell that is neither bonded nor pressed, so the
//! solve on a box that holds the bonded and the pressed cells is the solve on the grid: between cells of
//! the box the influence coefficients are the grid's (Love's kernel depends on the
//! offset only), and only the transforms' rounding and the preconditioner (the box's
//! inverse symbol, not the grid's) differ. A round then applies K once on the grid, for
//! the gaps outside the box (a cell penetrating there widens the next round's box),
//! except in a step that retracts the body under approach control: there no gap outside
//! the set can close, and K is applied on the grid once, when the set holds in the box.
//! (The approach's decrease opens every gap outside the set by at least what the set's
//! lift, at most the decrease, closes: the potential of the set's equilibrium pressure
//! is at most its value on the set. A cell that leaves only opens gaps: the potential of
//! a positive load swept onto the set, its balayage, lies below the load's own
//! everywhere. Both hold for the continuous half-space; on the grid, the tests compare
//! whole cycles on the box and on the grid cell by cell.)
//!
//! A sphere's contact covers 10-50 % of the benchmark grid while it unloads: the box's
//! padded transforms cost about that fraction of the grid's. A periodic operator has no
//! window (its cells couple to their images), nor does a set whose box would cover more
//! than [`MAX_FRACTION`] of the grid.

use crate::operator::{GridForms, NonPeriodicHalfSpace};
use crate::solver::window::{bounding_box_where, gather, smooth, Window};

/// Largest window, as a fraction of the grid's cells.
const MAX_FRACTION: f64 = 0.7;
/// Cells added on each side of the set's box, as a fraction of its width (at least
/// one): a growing contact keeps its window for a few steps.
const MARGIN: f64 = 1.0 / 16.0;
/// A kept window is built anew when it has this many times the cells it needs (a
/// shrinking contact: unloading).
const SHRINK: f64 = 1.25;

/// A box of cells of the grid (of row length `nx`) and the operator on it.
pub(super) struct SetWindow {
    pub(super) cells: Window,
    nx: usize,
    pub(super) op: NonPeriodicHalfSpace,
}

/// The window for the cells `on` of the grid of `op`: the kept one, moved over the set,
/// while it holds the set and is not [`SHRINK`] times too large; else a new one, with a
/// [`MARGIN`] around the set's box unless the contact `shrinks` (a retraction). None:
/// no window (periodic operator, no set, or a set spread over the grid).
pub(super) fn place<'a, C: GridForms>(
    op: &C,
    kept: &'a mut Option<SetWindow>,
    on: &[bool],
    shrinks: bool,
) -> Option<&'a mut SetWindow> {
    if op.is_periodic() {
        return None;
    }
    let (nx, ny) = (op.nx(), op.ny());
    let (x_lo, x_hi, y_lo, y_hi) = bounding_box_where(nx, on.len(), |i| on[i])?;
    let (bw, bh) = (x_hi - x_lo + 1, y_hi - y_lo + 1);
    let widen = |b: usize, len: usize| {
        let margin = if shrinks {
            0
        } else {
            ((MARGIN * b as f64).ceil() as usize).max(1)
        };
        smooth(b + 2 * margin).min(len)
    };
    let (wx, wy) = (widen(bw, nx), widen(bh, ny));
    if (wx * wy) as f64 > MAX_FRACTION * (nx * ny) as f64 {
        return None;
    }
    let fits = |w: &SetWindow| {
        let c = w.cells;
        c.wx >= bw && c.wy >= bh && (c.wx * c.wy) as f64 <= SHRINK * (wx * wy) as f64
    };
    if !kept.as_ref().is_some_and(fits) {
        *kept = Some(SetWindow {
            cells: Window {
                x0: 0,
                y0: 0,
                wx,
                wy,
            },
            nx,
            op: op.window(wx, wy)?,
        });
    }
    let w = kept.as_mut()?;
    // Centre the box on the set, inside the grid.
    let c = &mut w.cells;
    c.x0 = x_lo.saturating_sub((c.wx - bw) / 2).min(nx - c.wx);
    c.y0 = y_lo.saturating_sub((c.wy - bh) / 2).min(ny - c.wy);
    Some(w)
}

impl SetWindow {
    /// The window's values of a grid, row-major.
    pub(super) fn gather<T: Copy>(&self, grid: &[T]) -> Vec<T> {
        gather(grid, self.nx, self.cells)
    }

    /// Writes the window's `values` (row-major) into the grid.
    pub(super) fn scatter(&self, grid: &mut [f64], values: &[f64]) {
        let c = self.cells;
        for (r, y) in (c.y0..c.y0 + c.wy).enumerate() {
            let row = y * self.nx + c.x0;
            grid[row..row + c.wx].copy_from_slice(&values[r * c.wx..(r + 1) * c.wx]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_window_holds_the_set_and_stays_inside_the_grid() {
        let op = NonPeriodicHalfSpace::new(64, 48, 1.0, 0.75, 1.0);
        let mut on = vec![false; 64 * 48];
        for (x, y) in [(60, 2), (63, 9), (55, 0)] {
            on[y * 64 + x] = true;
        }
        let mut kept = None;
        let w = place(&op, &mut kept, &on, false).unwrap();
        let c = w.cells;
        assert!(c.x0 <= 55 && c.x0 + c.wx >= 64 && c.y0 == 0 && c.wy >= 10);
        let g: Vec<f64> = (0..64 * 48).map(|i| i as f64).collect();
        let mut back = vec![0.0; 64 * 48];
        w.scatter(&mut back, &w.gather(&g));
        for (i, (&a, &b)) in g.iter().zip(&back).enumerate() {
            let (x, y) = (i % 64, i / 64);
            assert_eq!(b, if c.holds(x, y) { a } else { 0.0 });
        }
        // Spread over the grid: no window; periodic: none.
        assert!(place(&op, &mut kept, &[true; 64 * 48], false).is_none());
        let periodic = crate::operator::PeriodicHalfSpace::new(64, 48, 1.0, 0.75, 1.0);
        assert!(place(&periodic, &mut None, &on, false).is_none());
    }
}
