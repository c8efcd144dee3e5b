//! Passes over the cells in chunks of [`CHUNK`] on the pool's threads, whose partial
//! results are combined in chunk order: sums and maxima that do not depend on the number
//! of threads. The families' passes are built from these.

use rayon::prelude::*;

/// Cells per chunk of a pass (small in the unit tests, so that their grids split).
pub(crate) const CHUNK: usize = if cfg!(test) { 128 } else { 8192 };

/// `max(a, b)` as a select (vectorizes); a NaN `b` leaves `a`.
#[inline(always)]
pub(crate) fn max(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

/// `sum a b`.
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let parts: Vec<f64> = a
        .par_chunks(CHUNK)
        .zip(b.par_chunks(CHUNK))
        .map(|(a, b)| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>())
        .collect();
    parts.into_iter().sum()
}
