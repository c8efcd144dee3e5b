//! Bracketed scalar root finding (Brent's method: inverse quadratic interpolation
//! safeguarded by bisection), used to invert the monotone MRD relations d(a), F(a).

use crate::error::{MrdError, Result};

/// Finds `x` in `[a, b]` with `f(x) = 0`, given `f(a)` and `f(b)` of opposite sign (or
/// zero). Stops when the bracket is below `xtol` (absolute) plus 4 ulp of `x`.
pub fn brent<F: Fn(f64) -> f64>(f: F, mut a: f64, mut b: f64, xtol: f64) -> Result<f64> {
    let mut fa = f(a);
    let mut fb = f(b);
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if fa.signum() == fb.signum() || !fa.is_finite() || !fb.is_finite() {
        return Err(MrdError::NoConvergence {
            what: "root bracket",
            iterations: 0,
            residual: fa.abs().min(fb.abs()),
        });
    }
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + 0.5 * xtol;
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol { d } else { tol * m.signum() };
        fb = f(b);
    }
    Err(MrdError::NoConvergence {
        what: "Brent root finder",
        iterations: 200,
        residual: fb.abs(),
    })
}

/// Finds the smallest `hi >= start` (doubling) with `f(hi) >= target`, for a
/// non-decreasing `f`; fails beyond `limit`.
pub fn bracket_up<F: Fn(f64) -> Result<f64>>(
    f: F,
    target: f64,
    start: f64,
    limit: f64,
) -> Result<f64> {
    let mut hi = start.min(limit);
    for _ in 0..2000 {
        if f(hi)? >= target {
            return Ok(hi);
        }
        if hi >= limit {
            return Err(MrdError::OutOfRange {
                needed: f64::INFINITY,
                limit,
            });
        }
        hi = (hi * 2.0).min(limit);
    }
    Err(MrdError::NoConvergence {
        what: "bracket search",
        iterations: 2000,
        residual: target,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_cube_root() {
        let x = brent(|x| x * x * x - 2.0, 0.0, 2.0, 1e-16).unwrap();
        assert!((x - 2f64.cbrt()).abs() < 1e-15);
    }

    #[test]
    fn rejects_bad_bracket() {
        assert!(brent(|x| x * x + 1.0, -1.0, 1.0, 1e-12).is_err());
    }
}
