//! The tangent normal stiffness dF/dd of a solved contact, its contact set held fixed.

use super::{ContactSolver, Solution, SolverOptions};
use crate::error::{BemError, Result};
use crate::operator::SolverOperator;
use crate::set_solve::{SetEnd, SetSolve};

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
        let mut solve = SetSolve {
            what: WHAT,
            op: &mut self.op,
            tolerance: opts.tolerance,
            max_iterations: opts.max_iterations,
            interrupted: &|| opts.interrupted(),
        };
        match solve.run(&c, &c)? {
            SetEnd::Converged { x, .. } => Ok(x.iter().sum::<f64>() * self.op.cell_area()),
            SetEnd::Limit {
                iterations,
                residual,
            } => Err(BemError::NoConvergence {
                what: WHAT,
                iterations,
                residual,
                tolerance: opts.tolerance,
                last: Box::new(sol.clone()),
            }),
        }
    }
}
