//! What an operator is to the solvers: the compliance `u = K p` and the strategies the
//! solvers may use besides (preconditioner, real-space sums, coarse and window forms).

use super::space::{HalfSpace, Operand, Spectral, Transform};
use crate::stencil::Stencil;

/// An elastic half-space's compliance on a grid: `u = K p`, the grid's sizes, and K's
/// spectral form where it is a convolution (what an operator is; what the solver's
/// strategies need besides is in [`Preconditioner`], [`RealSpace`] and [`GridForms`](super::forms::GridForms)).
pub trait Compliance: Send {
    fn half_space(&self) -> &HalfSpace;
    /// Periodic operators have no defined mean displacement (the k = 0 mode is left to
    /// the load or approach constraint).
    fn is_periodic(&self) -> bool;
    fn nx(&self) -> usize {
        self.half_space().nx
    }
    fn ny(&self) -> usize {
        self.half_space().ny
    }
    fn lx(&self) -> f64 {
        self.half_space().lx
    }
    fn ly(&self) -> f64 {
        self.half_space().ly
    }
    fn e_star(&self) -> f64 {
        self.half_space().e_star
    }
    /// u = K p (both `ny x nx`); `u` is overwritten.
    fn apply(&mut self, p: &[f64], u: &mut [f64]);
    fn cells(&self) -> usize {
        self.nx() * self.ny()
    }
    /// `u = K p` with K's products in single precision where the operator has such a
    /// form without transforms (a dense matrix's copy); the default applies K. The
    /// solver's fused applications of [`Operand::ComplianceSingle`] on an operator
    /// without a spectral form call it.
    fn apply_single(&mut self, p: &[f64], u: &mut [f64]) {
        self.apply(p, u)
    }
    /// Whether [`Operand::ComplianceSingle`] rounds K to single precision (the
    /// single-precision transforms, or [`Self::apply_single`] of a dense copy): the
    /// solver then recomputes `K p` in double precision at set residuals.
    fn rounds_single(&mut self) -> bool {
        matches!(
            self.spectral(Operand::ComplianceSingle),
            Some(Spectral {
                transform: Transform::Single(..),
                ..
            })
        )
    }
    /// The transform and symbol that apply K or M as one convolution, if the operator
    /// is one (the solver then fuses its sweeps into the transform's row passes).
    fn spectral(&mut self, which: Operand) -> Option<Spectral<'_>> {
        let _ = which;
        None
    }
    fn cell_area(&self) -> f64 {
        self.lx() * self.ly() / self.cells() as f64
    }
}

/// An approximate inverse M of K for the solver's search directions (the defaults: the
/// identity, no stencil, which leave the iteration plain Polonsky-Keer).
pub trait Preconditioner: Compliance {
    /// Preconditioner, in place: `g <- M g` with M an approximate inverse of K (a
    /// surface stiffness). The default, the identity, leaves the solver plain
    /// Polonsky-Keer.
    fn precondition(&mut self, g: &mut [f64]) {
        let _ = g;
    }
    /// M's convolution kernel near its centre ([`Stencil`]: the same M as
    /// [`Self::precondition`], truncated), for small contact sets; None if M is no
    /// convolution on this grid (the default) or the grid is smaller than the stencil.
    fn local_stiffness(&mut self) -> Option<&Stencil> {
        None
    }
}

/// K by direct sums over its real-space table: point loads, K between a few cells (the
/// candidate-set path) and at a few cells (the defaults: none, through `apply`).
pub trait RealSpace: Compliance {
    /// `u += K q` for a pressure `q` that is zero except at the listed `(cell, value)`
    /// loads. The default builds `q` and applies `K`.
    fn add_point_loads(&mut self, loads: &[(usize, f64)], u: &mut [f64]) {
        let mut q = vec![0.0; self.cells()];
        for &(c, v) in loads {
            q[c] += v;
        }
        let mut ku = vec![0.0; self.cells()];
        self.apply(&q, &mut ku);
        u.iter_mut().zip(&ku).for_each(|(a, b)| *a += b);
    }
    /// Most loads for which [`Self::add_point_loads`] costs less than [`Compliance::apply`]
    /// (0: never).
    fn point_load_limit(&self) -> usize {
        0
    }
    /// K between the listed cells only, as a dense row-major `n x n` matrix (entry
    /// `(a, b)`: the displacement at `cells[a]` under unit pressure on `cells[b]`), for
    /// solves restricted to a small contact set; None if the operator has no real-space
    /// table. `buffer` is storage to reuse (e.g. the last such matrix, whose pages are
    /// then not mapped afresh; its contents do not matter, may be empty).
    fn restricted(&self, cells: &[usize], buffer: Vec<f64>) -> Option<Vec<f64>> {
        let _ = (cells, buffer);
        None
    }
    /// K of the cell pressures `loads` (cell, pressure) at the listed cells only, by
    /// direct sums over the real-space table (each value sums the loads in list order);
    /// None if the operator has no table. Costs `at.len() * loads.len()` products.
    fn displacements_at(&self, at: &[usize], loads: &[(usize, f64)]) -> Option<Vec<f64>> {
        let _ = (at, loads);
        None
    }
}
