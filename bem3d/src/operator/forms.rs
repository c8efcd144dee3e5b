//! The forms of an operator on other grids that the solver's strategies build: the
//! 2 x 2 coarsened operator of a nested start and the operator of a window, with the
//! operator bound the solvers build on ([`GridOperator`]).

use super::dense::DenseCompliance;
use super::non_periodic::NonPeriodicHalfSpace;
use super::periodic::PeriodicHalfSpace;
use super::space::{halved, HalfSpace};
use super::table::Mirrored;
use super::traits::{Compliance, Preconditioner, RealSpace};

/// The same half-space on another grid: a window of this one, or the grid coarsened
/// 2 x 2 (the window path and the nested start; the defaults: none).
pub trait GridForms: Compliance {
    /// The same half-space on a window of `wx x wy` cells of this grid (same cells and
    /// modulus): between cells of the window K is then the same (up to rounding), for
    /// solves restricted to a window that holds the whole contact; None if the operator
    /// has no such restriction (a periodic one couples the window to its images).
    fn window(&self, wx: usize, wy: usize) -> Option<NonPeriodicHalfSpace> {
        let _ = (wx, wy);
        None
    }
    /// The same half-space on a grid of half the cells per side (each cell the union of
    /// 2 x 2 cells of this grid; same size and modulus), for the solver's nested start;
    /// None if the operator has no such form (the default) or a side is odd.
    fn coarse(&self) -> Option<Self>
    where
        Self: Sized,
    {
        None
    }
}

/// An operator with every form the solvers' strategies use (implemented for every type
/// with the four traits); the solvers take it through
/// [`SolverOperator`](crate::solver::SolverOperator), which adds their compiled entry
/// points.
pub trait GridOperator: Compliance + Preconditioner + RealSpace + GridForms {}

impl<T: Compliance + Preconditioner + RealSpace + GridForms> GridOperator for T {}

impl GridForms for PeriodicHalfSpace {
    fn coarse(&self) -> Option<Self> {
        let hs = halved(&self.hs)?;
        Some(Self::new(hs.nx, hs.ny, hs.lx, hs.ly, hs.e_star))
    }
}

impl GridForms for NonPeriodicHalfSpace {
    fn coarse(&self) -> Option<Self> {
        let hs = halved(&self.hs)?;
        Some(Self::new(hs.nx, hs.ny, hs.lx, hs.ly, hs.e_star))
    }
    /// Love's coefficients of the window's offsets, copied from this grid's table.
    fn window(&self, wx: usize, wy: usize) -> Option<NonPeriodicHalfSpace> {
        let hs = self.hs;
        if wx == 0 || wy == 0 || wx > hs.nx || wy > hs.ny {
            return None;
        }
        let (hx, hy) = (hs.lx / hs.nx as f64, hs.ly / hs.ny as f64);
        let window = HalfSpace {
            nx: wx,
            ny: wy,
            lx: wx as f64 * hx,
            ly: wy as f64 * hy,
            e_star: hs.e_star,
        };
        let table = Mirrored::new(wx, wy, |i, j| self.table.offsets(j)[hs.nx - 1 + i]);
        let precision = self.stiffness.precision();
        Some(NonPeriodicHalfSpace::from_table(window, table, precision))
    }
}

impl GridForms for DenseCompliance {}
