//! Typed errors of the `mrd` crate.

use thiserror::Error;

/// Everything that can go wrong in the 1D method: invalid physical input, a request
/// outside a profile's tabulated range, or a numerical procedure that did not converge.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MrdError {
    /// A parameter is outside its physical domain (negative modulus, n <= 0, ...).
    #[error("invalid {name} = {value}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: &'static str,
    },
    /// A tabulated profile is malformed (non-finite value, unsorted radii, ...).
    #[error("invalid profile table: {0}")]
    InvalidTable(String),
    /// The contact would need the profile beyond the radius where it is defined.
    #[error("contact radius {needed:.6e} exceeds the profile's defined range r <= {limit:.6e}")]
    OutOfRange { needed: f64, limit: f64 },
    /// A depth that no contact radius within the profile's range reaches.
    #[error("{}", unreachable_message(*depth, *limit))]
    Unreachable { depth: f64, limit: f64 },
    /// A value outside the range a table covers (no extrapolation).
    #[error("{what} = {value} lies outside the range [{lo}, {hi}] of the {table}")]
    OutsideTable {
        what: &'static str,
        value: f64,
        lo: f64,
        hi: f64,
        table: &'static str,
    },
    /// A quantity the problem needs was not given.
    #[error("missing {name}: {hint}")]
    Missing {
        name: &'static str,
        hint: &'static str,
    },
    /// A data file (height map, table) is malformed; the message names the file.
    #[error("{0}")]
    InvalidData(String),
    /// A load that the contact cannot carry (e.g. a tensile force below pull-off).
    #[error("impossible load: {0}")]
    ImpossibleLoad(String),
    /// An iterative procedure stopped before reaching its tolerance.
    #[error("{what} did not converge after {iterations} iterations (residual {residual:.3e})")]
    NoConvergence {
        what: &'static str,
        iterations: usize,
        residual: f64,
    },
}

pub type Result<T> = std::result::Result<T, MrdError>;

fn unreachable_message(depth: f64, limit: f64) -> String {
    if limit.is_finite() {
        format!(
            "depth {depth:e} needs a contact radius that exceeds the profile's defined range r <= {limit:.6e}"
        )
    } else {
        format!(
            "depth {depth:e} is not reached at any finite contact radius: the profile's 1D image stays below it (check the shape's parameters, e.g. a power law's c and n)"
        )
    }
}

/// Checks `value` is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(MrdError::InvalidParameter {
            name,
            value,
            reason: "must be finite and > 0",
        })
    }
}

/// Checks `value` is finite and non-negative.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(MrdError::InvalidParameter {
            name,
            value,
            reason: "must be finite and >= 0",
        })
    }
}
