//! What the unit tests share.

/// `f(x, y)` on an `n x n` grid over the unit cell, at the cells' corners `(i/n, j/n)`,
/// row-major (index `j * n + i`): a test surface from a formula.
pub(crate) fn on_unit_cell(n: usize, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
    (0..n * n)
        .map(|k| f((k % n) as f64 / n as f64, (k / n) as f64 / n as f64))
        .collect()
}
