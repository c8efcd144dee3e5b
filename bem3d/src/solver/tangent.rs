//! The tangent normal stiffness dF/dd of a solved contact, its contact set held fixed.

use super::{ContactSolver, Solution, SolverOptions};
use crate::error::{BemError, Result};
use crate::operator::SolverOperator;

impl<K: SolverOperator> ContactSolver<K> {
    /// Tangent normal stiffness dF/dd with the contact set held fixed: solves
    /// `K_CC x = 1` on the contact cells C by conjugate gradients (K_CC is symmetric
    /// positive definite; preconditioned by the operator's M restricted to C) to
    /// relative residual `opts.tolerance` within `opts.max_iterations`;
    /// k = sum(x) * cell area.
    ///
    /// No contact: k = 0. Complete contact of an unmasked periodic surface: k = +inf
    /// (K_CC is then K itself, whose mean mode is free: the force grows at a fixed
    /// approach). A non-finite or vanishing step is a [`BemError::Breakdown`].
    pub fn tangent_stiffness(&mut self, sol: &Solution, opts: &SolverOptions) -> Result<f64> {
        crate::pool::on_pool(|| self.tangent_stiffness_on_pool(sol, opts))
    }

    fn tangent_stiffness_on_pool(&mut self, sol: &Solution, opts: &SolverOptions) -> Result<f64> {
        const WHAT: &str = "tangent stiffness";
        let n = self.op.cells();
        if sol.pressure.len() != n {
            return Err(BemError::InvalidInput(format!(
                "solution has {} cells but the grid has {n}",
                sol.pressure.len()
            )));
        }
        let c: Vec<f64> = sol
            .pressure
            .iter()
            .map(|&p| if p > 0.0 { 1.0 } else { 0.0 })
            .collect();
        let nc = c.iter().sum::<f64>() as usize;
        if nc == 0 {
            return Ok(0.0);
        }
        if self.op.is_periodic() && nc == n {
            return Ok(f64::INFINITY);
        }
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let mut x = vec![0.0; n];
        let mut res = c.clone();
        let mut zr = res.clone();
        self.op.precondition(&mut zr);
        zr.iter_mut().zip(&c).for_each(|(v, m)| *v *= m);
        let mut dir = zr.clone();
        let mut q = vec![0.0; n];
        let b_norm = (nc as f64).sqrt();
        let mut rz = dot(&res, &zr);
        let mut residual = 1.0;
        for it in 0..=opts.max_iterations {
            residual = dot(&res, &res).sqrt() / b_norm;
            if !residual.is_finite() {
                return Err(BemError::Breakdown {
                    what: WHAT,
                    iterations: it,
                    residual,
                    reason: "non-finite residual",
                });
            }
            if residual <= opts.tolerance {
                return Ok(x.iter().sum::<f64>() * self.op.cell_area());
            }
            if it == opts.max_iterations {
                break;
            }
            if opts.interrupted() {
                return Err(BemError::Interrupted {
                    what: WHAT,
                    iterations: it,
                });
            }
            self.op.apply(&dir, &mut q);
            q.iter_mut().zip(&c).for_each(|(v, m)| *v *= m);
            let curvature = dot(&dir, &q);
            if !(curvature > 0.0 && curvature.is_finite() && rz > 0.0) {
                return Err(BemError::Breakdown {
                    what: WHAT,
                    iterations: it,
                    residual,
                    reason: "vanishing or non-finite step",
                });
            }
            let alpha = rz / curvature;
            for i in 0..n {
                x[i] += alpha * dir[i];
                res[i] -= alpha * q[i];
            }
            zr.copy_from_slice(&res);
            self.op.precondition(&mut zr);
            zr.iter_mut().zip(&c).for_each(|(v, m)| *v *= m);
            let rz_new = dot(&res, &zr);
            let beta = rz_new / rz;
            for i in 0..n {
                dir[i] = zr[i] + beta * dir[i];
            }
            rz = rz_new;
        }
        Err(BemError::NoConvergence {
            what: WHAT,
            iterations: opts.max_iterations,
            residual,
            tolerance: opts.tolerance,
            last: Box::new(sol.clone()),
        })
    }
}
