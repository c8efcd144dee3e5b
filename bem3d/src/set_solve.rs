//! A linear solve on a set of cells: `A_CC x = b_C` by preconditioned conjugate
//! gradients, for a symmetric positive definite compliance `A` restricted to the cells
//! C (the rows and columns of C; `x` vanishes off C). The normal tangent stiffness
//! (`K_CC x = 1`) and the tangential stick stiffness (Cerruti's tensor on C) are both
//! this solve with another operator; the preconditioner is the operator's inverse
//! symbol restricted to C.

use crate::error::{BemError, Result};

/// The operator of a set solve and its preconditioner, over all cells (the solve
/// restricts them to the set).
pub(crate) trait SetOperator {
    /// `out = A v`.
    fn apply(&mut self, v: &[f64], out: &mut [f64]);
    /// `r = M r` (an approximate inverse of A, symmetric positive definite).
    fn precondition(&mut self, r: &mut [f64]);
}

impl<K: crate::operator::GridOperator> SetOperator for K {
    fn apply(&mut self, v: &[f64], out: &mut [f64]) {
        crate::operator::Compliance::apply(self, v, out);
    }
    fn precondition(&mut self, r: &mut [f64]) {
        crate::operator::Preconditioner::precondition(self, r);
    }
}

/// What a set solve needs of its caller: the operator and the stop.
pub(crate) struct SetSolve<'a> {
    /// Names the iteration in errors ("tangent stiffness", ...).
    pub what: &'static str,
    pub op: &'a mut dyn SetOperator,
    /// Relative residual `|b - A x|_C / |b|_C` at which the solve stops.
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Polled once per iteration: the caller asked the solve to stop.
    pub interrupted: &'a dyn Fn() -> bool,
}

/// The end of a set solve that did not fail: converged, or stopped at its iteration
/// limit with its last iterate.
pub(crate) enum SetEnd {
    Converged { x: Vec<f64>, iterations: usize },
    Limit { iterations: usize, residual: f64 },
}

impl SetSolve<'_> {
    /// Solves `A_CC x = b_C` with `set` 1 on C and 0 elsewhere, from x = 0. Breakdown
    /// (a non-finite residual or a direction without curvature) and interruption are
    /// errors; the iteration limit is [`SetEnd::Limit`], which the caller reports.
    pub fn run(&mut self, set: &[f64], b: &[f64]) -> Result<SetEnd> {
        let n = set.len();
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let mut x = vec![0.0; n];
        let mut res: Vec<f64> = b.iter().zip(set).map(|(v, m)| v * m).collect();
        let mut zr = res.clone();
        self.op.precondition(&mut zr);
        zr.iter_mut().zip(set).for_each(|(v, m)| *v *= m);
        let mut dir = zr.clone();
        let mut q = vec![0.0; n];
        let b_norm = dot(&res, &res).sqrt();
        let mut rz = dot(&res, &zr);
        let mut residual = 1.0;
        for it in 0..=self.max_iterations {
            residual = dot(&res, &res).sqrt() / b_norm;
            if !residual.is_finite() {
                return Err(self.breakdown(it, residual, "non-finite residual"));
            }
            if residual <= self.tolerance {
                return Ok(SetEnd::Converged { x, iterations: it });
            }
            if it == self.max_iterations {
                break;
            }
            if (self.interrupted)() {
                return Err(BemError::Interrupted {
                    what: self.what,
                    iterations: it,
                });
            }
            self.op.apply(&dir, &mut q);
            q.iter_mut().zip(set).for_each(|(v, m)| *v *= m);
            let curvature = dot(&dir, &q);
            if !(curvature > 0.0 && curvature.is_finite() && rz > 0.0) {
                return Err(self.breakdown(it, residual, "vanishing or non-finite step"));
            }
            let alpha = rz / curvature;
            for i in 0..n {
                x[i] += alpha * dir[i];
                res[i] -= alpha * q[i];
            }
            zr.copy_from_slice(&res);
            self.op.precondition(&mut zr);
            zr.iter_mut().zip(set).for_each(|(v, m)| *v *= m);
            let rz_new = dot(&res, &zr);
            let beta = rz_new / rz;
            for i in 0..n {
                dir[i] = zr[i] + beta * dir[i];
            }
            rz = rz_new;
        }
        Ok(SetEnd::Limit {
            iterations: self.max_iterations,
            residual,
        })
    }

    fn breakdown(&self, iterations: usize, residual: f64, reason: &'static str) -> BemError {
        BemError::Breakdown {
            what: self.what,
            iterations,
            residual,
            reason,
        }
    }
}
