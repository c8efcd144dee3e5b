//! Typed errors of the 3D solver.

use thiserror::Error;

#[derive(Debug, Error, Clone)]
pub enum BemError {
    /// Input arrays or parameters are not usable (sizes, non-finite heights, ...).
    #[error("invalid input: {0}")]
    InvalidInput(String),
    /// The prescribed load has no solution (e.g. an approach beyond complete contact of
    /// a periodic surface, where the force is unbounded).
    #[error("no solution: {0}")]
    Infeasible(String),
    /// An iteration stopped at its limit; the last iterate of the contact solve is kept
    /// so callers can record it (sweeps) or report it (single runs).
    #[error("{what} did not converge: {iterations} iterations, residual {residual:.3e} (tolerance {tolerance:.1e})")]
    NoConvergence {
        /// Which iteration: "contact solve" or "tangent stiffness".
        what: &'static str,
        iterations: usize,
        residual: f64,
        tolerance: f64,
        last: Box<crate::solution::Solution>,
    },
    /// The caller set the solve's [`crate::solver::Interrupt`].
    #[error("{what} interrupted after {iterations} iterations")]
    Interrupted {
        what: &'static str,
        iterations: usize,
    },
    /// A strategy forced in [`crate::solver::Paths`] could not run (the operator lacks
    /// it, the load or grid does not admit it, or it gave up).
    #[error("the forced {path} path cannot run: {reason}")]
    PathUnavailable { path: &'static str, reason: String },
    /// A grid needs more memory than this process may use.
    #[error(transparent)]
    Memory(#[from] sysmem::MemoryError),
    /// An iteration could not continue: a non-finite or vanishing step. It carries the
    /// residual reached before the breakdown.
    #[error("{what} broke down after {iterations} iterations ({reason}); residual reached {residual:.3e}")]
    Breakdown {
        what: &'static str,
        iterations: usize,
        residual: f64,
        reason: &'static str,
    },
}

impl BemError {
    /// Iterations and residual reached, for the iteration errors.
    pub fn progress(&self) -> Option<(usize, f64)> {
        match self {
            BemError::NoConvergence {
                iterations,
                residual,
                ..
            }
            | BemError::Breakdown {
                iterations,
                residual,
                ..
            } => Some((*iterations, *residual)),
            _ => None,
        }
    }
}

pub type Result<T> = std::result::Result<T, BemError>;
