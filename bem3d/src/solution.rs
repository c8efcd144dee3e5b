//! The result of a contact solve, apart from the solver (errors carry the last iterate
//! of an unconverged one).

/// A solved contact state.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Cell pressures (`ny x nx`).
    pub pressure: Vec<f64>,
    /// Gap at cell centres (`ny x nx`); zero in contact.
    pub gap: Vec<f64>,
    /// Rigid-body approach from first contact.
    pub approach: f64,
    /// Total force, sum p * cell area.
    pub force: f64,
    /// Cells carrying pressure.
    pub contact_cells: usize,
    /// Real contact area, contact cells x cell area.
    pub contact_area: f64,
    /// Mean gap over the domain cells.
    pub mean_gap: f64,
    pub iterations: usize,
    /// Criterion value reached (see the solver's module docs).
    pub residual: f64,
    /// Bound of the duality gap relative to force x rms height (the solver's module
    /// docs, "What a converged solve guarantees"): at most the tolerance when the solve
    /// converged.
    pub certificate: f64,
    /// Cells that may touch (the mask's cells, or the whole grid).
    pub domain_cells: usize,
    /// Whether the previous solution given as a warm start was used (the solver's
    /// module docs).
    pub warm_started: bool,
    /// Whether the solve ran restricted to part of the grid (the solver's module docs):
    /// a window around a compact contact (its `iterations` then count iterations on the
    /// window, summed over its rounds) or a small candidate set of cells (a few
    /// thousand at most; `iterations` then count applications of a dense K between
    /// them).
    pub restricted: bool,
}

impl Solution {
    /// Every domain cell in contact.
    pub fn complete_contact(&self) -> bool {
        self.contact_cells == self.domain_cells
    }
}
