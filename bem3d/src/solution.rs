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
    /// The path that produced the solution (the solver's module docs): the full grid,
    /// a window around a compact contact (`iterations` then count iterations on the
    /// window, summed over its rounds) or a small candidate set of cells (a few thousand
    /// at most; `iterations` then count applications of a dense K between them).
    pub path: Path,
    /// Whether the full-grid iteration started from the solution on the grid coarsened
    /// 2 x 2 (the solver's nested start).
    pub nested_start: bool,
    /// Of `iterations`, those with `K p` carried in single precision (the first phase of
    /// the solver's precision schedule; 0 where it is forbidden or the operator has no
    /// single-precision form).
    pub single_iterations: usize,
    /// Of `iterations`, those that applied the preconditioner by its stencil on the
    /// contact cells instead of by transforms.
    pub stencil_iterations: usize,
    /// Whether the iteration (on the grid, or in a restricted path's rounds) stored its
    /// direction vectors as 16-bit integers scaled per row chunk instead of single
    /// precision (the solver's module docs, "Scaled directions").
    pub scaled_directions: bool,
}

/// Which of the solver's paths produced a [`Solution`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Path {
    /// The iteration on the whole grid.
    FullGrid,
    /// The iteration on a window around a compact contact, in rounds checked on the grid.
    Window,
    /// The iteration on a candidate set of cells, in rounds checked on the grid.
    CandidateSet,
}

impl Path {
    /// The path's name in reports: `full grid`, `window` or `candidate set`.
    pub fn name(self) -> &'static str {
        match self {
            Path::FullGrid => "full grid",
            Path::Window => "window",
            Path::CandidateSet => "candidate set",
        }
    }
}

impl Solution {
    /// The full grid's solution of `pressure` and `gap` (cells of `cell_area`): force,
    /// contact and mean gap over the `domain_cells` follow; the caller sets
    /// `iterations`, `residual` and `certificate` (zero here).
    pub(crate) fn full_grid(
        pressure: Vec<f64>,
        gap: Vec<f64>,
        approach: f64,
        cell_area: f64,
        domain_cells: usize,
    ) -> Self {
        let contact_cells = pressure.iter().filter(|&&v| v > 0.0).count();
        Solution {
            force: pressure.iter().sum::<f64>() * cell_area,
            contact_cells,
            contact_area: contact_cells as f64 * cell_area,
            mean_gap: gap.iter().sum::<f64>() / domain_cells as f64,
            gap,
            pressure,
            approach,
            iterations: 0,
            residual: 0.0,
            certificate: 0.0,
            domain_cells,
            warm_started: false,
            path: Path::FullGrid,
            nested_start: false,
            single_iterations: 0,
            stencil_iterations: 0,
            scaled_directions: false,
        }
    }

    /// Whether the solve ran on part of the grid (a window or a candidate set).
    pub fn restricted(&self) -> bool {
        self.path != Path::FullGrid
    }

    /// Every domain cell in contact.
    pub fn complete_contact(&self) -> bool {
        self.contact_cells == self.domain_cells
    }
}
