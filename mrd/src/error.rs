//! Typed errors of the `mrd` crate.

use thiserror::Error;

/// Everything that can go wrong in the 1D method: invalid physical input, a request
/// outside a profile's tabulated range, or a numerical procedure that did not converge.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MrdError {
    /// A parameter is outside its physical domain (negative modulus, n <= 0, ...).
    #[error("invalid {name} = {}: {reason}", number(*value))]
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
    /// A size the caller chose needs more memory than this process may use.
    #[error(transparent)]
    Memory(#[from] sysmem::MemoryError),
    /// An iterative procedure stopped before reaching its tolerance.
    #[error("{what} did not converge after {iterations} iterations (residual {residual:.3e})")]
    NoConvergence {
        what: &'static str,
        iterations: usize,
        residual: f64,
    },
}

pub type Result<T> = std::result::Result<T, MrdError>;

/// A number as a reader wants it: plain where that is short, scientific otherwise.
fn number(v: f64) -> String {
    if v == 0.0 || (1e-4..1e6).contains(&v.abs()) || !v.is_finite() {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

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

/// Magnitudes a physical parameter may take: any unit system fits, and the products
/// the methods form (forces of order E* d a, energies, spectra of order h^2 L^2) stay
/// finite and normal in double precision.
pub const MAGNITUDE_RANGE: (f64, f64) = (1e-100, 1e100);

/// The index of the first height that is not finite or exceeds [`MAGNITUDE_RANGE`]
/// in magnitude, with the words for a message ("non-finite height" or "height 1e300").
pub fn bad_height(heights: &[f64]) -> Option<(usize, String)> {
    let hi = MAGNITUDE_RANGE.1;
    heights
        .iter()
        .position(|h| !(..=hi).contains(&h.abs()))
        .map(|i| {
            let h = heights[i];
            let what = if h.is_finite() {
                format!("height {h:e} beyond |h| <= {hi:e}")
            } else {
                "non-finite height".to_string()
            };
            (i, what)
        })
}

/// Checks `value` is positive and within [`MAGNITUDE_RANGE`].
/// A row of `n` springs, refused below 2 (the parameter is named `springs`).
pub(crate) fn springs(n: usize) -> Result<usize> {
    if n < 2 {
        return Err(MrdError::InvalidParameter {
            name: "springs",
            value: n as f64,
            reason: "need at least 2 springs",
        });
    }
    Ok(n)
}

pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    let (lo, hi) = MAGNITUDE_RANGE;
    if (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(MrdError::InvalidParameter {
            name,
            value,
            reason: "must be > 0, within 1e-100..1e100",
        })
    }
}

/// Checks `value` is zero or positive within [`MAGNITUDE_RANGE`].
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64> {
    let (lo, hi) = MAGNITUDE_RANGE;
    if value == 0.0 || (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(MrdError::InvalidParameter {
            name,
            value,
            reason: "must be 0 or > 0 within 1e-100..1e100",
        })
    }
}
