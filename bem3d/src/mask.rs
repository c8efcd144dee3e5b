//! Masks: which cells of the grid may touch.

/// Cells whose centres lie in the disc of radius `radius` centred on the grid (a
/// circular punch face), row-major `ny x nx`, cell centres at `((i + 1/2) hx - lx/2,
/// (j + 1/2) hy - ly/2)`.
pub fn disc(nx: usize, ny: usize, lx: f64, ly: f64, radius: f64) -> Vec<bool> {
    let (hx, hy) = (lx / nx as f64, ly / ny as f64);
    (0..nx * ny)
        .map(|k| {
            let x = ((k % nx) as f64 + 0.5) * hx - 0.5 * lx;
            let y = ((k / nx) as f64 + 0.5) * hy - 0.5 * ly;
            x * x + y * y <= radius * radius
        })
        .collect()
}

/// `f(x, y)` at the cell centres of an `n x n` grid of side `l` centred on the origin,
/// row-major, centres at `((i + 1/2) h - l/2, (j + 1/2) h - l/2)`, `h = l / n` (the
/// convention of [`disc`]): the heights of a body of revolution on the free half-space.
pub fn centred(n: usize, l: f64, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
    let h = l / n as f64;
    (0..n * n)
        .map(|k| {
            let x = ((k % n) as f64 + 0.5) * h - 0.5 * l;
            let y = ((k / n) as f64 + 0.5) * h - 0.5 * l;
            f(x, y)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn disc_area_converges_to_pi_r2() {
        let n = 512;
        let m = super::disc(n, n, 2.0, 2.0, 0.75);
        let area = m.iter().filter(|&&v| v).count() as f64 * (2.0 / n as f64).powi(2);
        assert!((area / (std::f64::consts::PI * 0.5625) - 1.0).abs() < 2e-3);
        // Symmetric under both reflections.
        for j in 0..n {
            for i in 0..n {
                assert_eq!(m[j * n + i], m[j * n + (n - 1 - i)]);
                assert_eq!(m[j * n + i], m[(n - 1 - j) * n + i]);
            }
        }
    }
}
