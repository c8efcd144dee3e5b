//! Tanh-sinh (double-exponential) quadrature.
//!
//! Chosen because the MRD integrals (rule of Hess, Eq. 11; Abel transform, Eq. 26;
//! inverse transform) have integrable algebraic or logarithmic end-point singularities,
//! for which tanh-sinh keeps its near-exponential convergence. Interior kinks must be
//! passed as break points so that each panel is smooth inside.

use crate::error::{MrdError, Result};
use std::f64::consts::FRAC_PI_2;

/// Relative tolerance used by the crate's semi-analytic paths.
pub const DEFAULT_TOL: f64 = 1e-13;
const MAX_LEVEL: usize = 9;
// Wide enough that end-point tails of x^{-1/2} singularities (~ 2 sqrt(delta)) vanish.
const T_MAX: f64 = 4.5;

/// Integrates `f` over `[a, b]` to relative tolerance `tol` (absolute when the integral
/// is near zero). `f` may be singular (integrably) at either end point (best at `a`,
/// where nodes are exact offsets from `a`); it is never
/// evaluated exactly at an end point.
pub fn tanh_sinh<F: Fn(f64) -> f64>(f: F, a: f64, b: f64, tol: f64) -> Result<f64> {
    if b.partial_cmp(&a) != Some(std::cmp::Ordering::Greater) {
        return Ok(0.0);
    }
    let h = 0.5 * (b - a);
    // Node at parameter t: x = c +/- h*tanh(u), u = pi/2 sinh t. Distances to the end
    // points are formed as h*(1 - tanh u) = 2h/(1 + e^{2u}) to avoid cancellation.
    let eval = |t: f64| -> f64 {
        let u = FRAC_PI_2 * t.sinh();
        let w = FRAC_PI_2 * t.cosh() / (u.cosh() * u.cosh());
        if w == 0.0 {
            return 0.0;
        }
        let delta = 2.0 * h / (1.0 + (2.0 * u.abs()).exp());
        if delta == 0.0 {
            return 0.0;
        }
        let x = if u >= 0.0 { b - delta } else { a + delta };
        if x <= a || x >= b {
            return 0.0;
        }
        let v = f(x);
        // A node within rounding distance of an end point may land on a singularity of
        // f (e.g. an interior break point of the profile); its share of the integral is
        // O(sqrt(ulp)) for integrable singularities, so it is dropped.
        let near_end = (x - a).min(b - x) <= 64.0 * f64::EPSILON * a.abs().max(b.abs());
        if !v.is_finite() && near_end {
            return 0.0;
        }
        w * v
    };
    let abs_eval = |t: f64| eval(t).abs();
    // Adds the nodes +/- k step, k = 1, 1 + stride, ... up to T_MAX, to the sums.
    let add_nodes = |step: f64, stride: usize, sums: &mut (f64, f64)| {
        let mut k = 1;
        while (k as f64) * step <= T_MAX {
            let t = k as f64 * step;
            sums.0 += eval(t) + eval(-t);
            sums.1 += abs_eval(t) + abs_eval(-t);
            k += stride;
        }
    };
    let mut step = 1.0;
    let mut sums = (eval(0.0), abs_eval(0.0));
    add_nodes(step, 1, &mut sums);
    let mut estimate = h * step * sums.0;
    let mut residual = f64::INFINITY;
    for _level in 1..=MAX_LEVEL {
        step *= 0.5;
        // Only the new (odd) nodes are added at each halving.
        add_nodes(step, 2, &mut sums);
        let next = h * step * sums.0;
        residual = (next - estimate).abs();
        estimate = next;
        if !estimate.is_finite() {
            break;
        }
        // Converged, or down to the rounding noise of the sum itself.
        let noise = 1e3 * f64::EPSILON * h * step * sums.1;
        if residual <= tol * estimate.abs().max(f64::MIN_POSITIVE) || residual <= noise {
            return Ok(estimate);
        }
    }
    Err(MrdError::NoConvergence {
        what: "tanh-sinh quadrature",
        iterations: MAX_LEVEL,
        residual: residual / estimate.abs().max(f64::MIN_POSITIVE),
    })
}

/// Integrates over `[a, b]` split at the interior `breaks` (sorted or not; points outside
/// `(a, b)` are ignored).
pub fn tanh_sinh_split<F: Fn(f64) -> f64>(
    f: F,
    a: f64,
    b: f64,
    breaks: &[f64],
    tol: f64,
) -> Result<f64> {
    let mut pts: Vec<f64> = breaks.iter().copied().filter(|&p| p > a && p < b).collect();
    pts.sort_by(f64::total_cmp);
    pts.dedup();
    let mut lo = a;
    let mut total = 0.0;
    for hi in pts.into_iter().chain(std::iter::once(b)) {
        total += tanh_sinh(&f, lo, hi, tol)?;
        lo = hi;
    }
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_and_endpoint_singularities() {
        let i = tanh_sinh(|x| x * x, 0.0, 2.0, 1e-14).unwrap();
        assert!((i - 8.0 / 3.0).abs() < 1e-14);
        // 1/sqrt(x) on [0,1] = 2
        let i = tanh_sinh(|x| 1.0 / x.sqrt(), 0.0, 1.0, 1e-14).unwrap();
        assert!((i - 2.0).abs() < 1e-13, "{i}");
        // ln x on [0,1] = -1
        let i = tanh_sinh(|x: f64| x.ln(), 0.0, 1.0, 1e-14).unwrap();
        assert!((i + 1.0).abs() < 1e-13, "{i}");
    }

    #[test]
    fn divergent_integral_is_reported() {
        assert!(tanh_sinh(|x| 1.0 / x, 0.0, 1.0, 1e-13).is_err());
    }

    #[test]
    fn split_handles_kinks() {
        let f = |x: f64| (x - 0.3).abs();
        let exact = 0.3f64 * 0.3 / 2.0 + 0.7 * 0.7 / 2.0;
        let i = tanh_sinh_split(f, 0.0, 1.0, &[0.3], 1e-14).unwrap();
        assert!((i - exact).abs() < 1e-14);
    }
}
