//! Typed errors of the 3D solver.

use thiserror::Error;

#[derive(Debug, Error, Clone)]
pub enum BemError {
    /// Input arrays or parameters are not usable (sizes, non-finite heights, ...).
    #[error("invalid input: {0}")]
    InvalidInput(String),
    /// The solver stopped at its iteration limit; the last iterate is kept so callers can
    /// record it (sweeps) or report it (single runs).
    #[error("contact solver did not converge: {iterations} iterations, residual {residual:.3e} (tolerance {tolerance:.1e})")]
    NoConvergence {
        iterations: usize,
        residual: f64,
        tolerance: f64,
        last: Box<crate::solver::Solution>,
    },
}

pub type Result<T> = std::result::Result<T, BemError>;
