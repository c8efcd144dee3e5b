//! Rust errors as Python exceptions: bad input is a `ValueError` with the same one-line
//! message the CLI prints; an iteration that stops short is a `ConvergenceError` that
//! carries the iterations, the residual reached and (for contact solves) the last
//! iterate.

use pyo3::create_exception;
use pyo3::exceptions::{PyMemoryError, PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    _mrdw,
    ConvergenceError,
    PyRuntimeError,
    "An iteration stopped before its tolerance. Attributes: `what` (which iteration), \
     `iterations`, `residual` (the criterion reached) and `last` (the last iterate as a \
     ContactResult, or None)."
);

/// A `ConvergenceError` with its attributes set.
pub fn convergence(
    py: Python<'_>,
    message: String,
    what: &str,
    iterations: usize,
    residual: f64,
    last: Option<Py<PyAny>>,
) -> PyErr {
    let err = ConvergenceError::new_err(compare::error::readable_numbers(&message));
    let value = err.value(py);
    // Setting attributes on a fresh exception instance cannot fail.
    let _ = value.setattr("what", what);
    let _ = value.setattr("iterations", iterations);
    let _ = value.setattr("residual", residual);
    let _ = value.setattr("last", last);
    err
}

/// A dictionary of named results, or a ValueError when one is not finite: extreme
/// inputs whose results overflow (or cancel to NaN in) double precision.
pub fn finite_dict<'py>(
    py: Python<'py>,
    items: &[(&str, f64)],
) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
    let d = pyo3::types::PyDict::new(py);
    for &(k, v) in items {
        finite(k, v)?;
        d.set_item(k, v)?;
    }
    Ok(d)
}

/// A ValueError naming the first NaN of the argument `name` (its flat index), if any.
pub fn no_nan<'a>(name: &str, values: impl IntoIterator<Item = &'a f64>) -> PyResult<()> {
    match values.into_iter().position(|v| v.is_nan()) {
        Some(i) => Err(value_error(format!("{name}[{i}] = NaN is not a number"))),
        None => Ok(()),
    }
}

/// `v`, or a ValueError naming `what` when it is not finite.
pub fn finite(what: &str, v: f64) -> PyResult<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(value_error(format!(
            "the result {what} = {v} is not representable in double precision for these inputs: rescale the units (lengths, moduli) or check the parameters"
        )))
    }
}

/// A ValueError with the message's extreme numbers in scientific form, as the command
/// line prints them ([`compare::error::readable_numbers`]).
pub fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(compare::error::readable_numbers(&message.into()))
}

/// A size that does not fit this process's memory: `MemoryError` naming the size.
pub fn memory_error(e: sysmem::MemoryError) -> PyErr {
    PyMemoryError::new_err(e.to_string())
}

/// Peak bytes per cell of an adhesive or cohesive contact's steps, the operator included
/// (measured: `compare::checks::cell_bytes`).
pub fn adhesive_bytes(periodic: bool) -> f64 {
    use compare::checks::cell_bytes::{ADHESION, ADHESION_PERIODIC};
    if periodic {
        ADHESION_PERIODIC
    } else {
        ADHESION
    }
}

/// MemoryError unless `bytes_per_cell` on the `(ny, nx)` grid fits the memory available;
/// the message names "`what` ny x nx contact".
pub fn check_grid_memory(
    what: &str,
    (ny, nx): (usize, usize),
    bytes_per_cell: f64,
) -> PyResult<()> {
    sysmem::check_estimate(
        bytes_per_cell * (nx * ny) as f64,
        &format!("{what} {ny} x {nx} contact"),
    )
    .map_err(memory_error)
}

/// Errors of the 1D method.
pub fn mrd_err(py: Python<'_>, e: mrd::MrdError) -> PyErr {
    match e {
        mrd::MrdError::NoConvergence {
            what,
            iterations,
            residual,
        } => convergence(py, e.to_string(), what, iterations, residual, None),
        mrd::MrdError::Memory(m) => memory_error(m),
        other => value_error(other.to_string()),
    }
}

/// Errors of a scene run.
pub fn compare_err(py: Python<'_>, e: compare::CompareError) -> PyErr {
    use compare::CompareError as C;
    let message = e.to_string();
    match e {
        C::Scene(_) => value_error(message),
        C::Mrd {
            source: mrd::MrdError::Memory(_),
            ..
        }
        | C::Bem {
            source: bem3d::BemError::Memory(_),
            ..
        } => PyMemoryError::new_err(message),
        C::Mrd { source, .. } => match source {
            mrd::MrdError::NoConvergence {
                what,
                iterations,
                residual,
            } => convergence(py, message, what, iterations, residual, None),
            _ => value_error(message),
        },
        C::Bem { source, .. } => match source.progress() {
            Some((iterations, residual)) => {
                convergence(py, message, "3D solve", iterations, residual, None)
            }
            None => value_error(message),
        },
        C::Io { .. } => PyOSError::new_err(message),
        _ => PyRuntimeError::new_err(message),
    }
}
