//! When a solve stops and what it reports: the certificate (duality gap), the floor of
//! complete contact, and the [`Solution`] collected from p and the gap (solver module
//! docs, "Convergence criterion" and "What a converged solve guarantees").

use super::fused::reduce;
use super::{sweeps, ContactSolver, Path, Solution};
use crate::operator::SolverOperator;
use rayon::prelude::*;

/// In complete contact the criterion is met to at most this many ulps of the load's
/// displacement scale (module docs, "Complete contact"). Measured (rough maps on 128^2,
/// h_rms 0.017 L): the iteration in double precision stalls at 70-300 ulps of that
/// scale (free half-space at 100 E*, periodic at 1e6 E*).
const COMPLETE_CONTACT_FLOOR: f64 = 1e3;

/// Iterations without halving the criterion after which a solve in complete contact
/// may stop at its floor.
pub(super) const STALL_ITERATIONS: usize = 10;

impl<K: SolverOperator> ContactSolver<K> {
    /// The solution without contact: w = z (no pressure), approach `d`.
    pub(super) fn finish_unloaded(&mut self, d: f64) -> Solution {
        self.work.w.copy_from_slice(&self.problem.z);
        let n = self.op.cells();
        self.finish(vec![0.0; n], d, 0, 0.0)
    }

    /// The tolerance a solve in complete contact can reach (module docs, "Complete
    /// contact"): the requested one, or [`COMPLETE_CONTACT_FLOOR`] ulps of the
    /// displacement scale of the mean pressure, `p_mean sqrt(lx ly) / E*`, over the rms
    /// height if that is larger. `pressure_sum`: the sum of p over the domain cells.
    pub(super) fn complete_contact_tolerance(&self, tolerance: f64, pressure_sum: f64) -> f64 {
        let mean = pressure_sum / self.problem.domain_cells as f64;
        let scale = mean * (self.op.lx() * self.op.ly()).sqrt() / self.op.e_star();
        tolerance.max(COMPLETE_CONTACT_FLOOR * f64::EPSILON * scale / self.problem.h_rms)
    }

    /// The duality (Frank-Wolfe) gap of `p` over the pressures carrying its force,
    /// relative to that force times the rms height: `sum_i p_i (g_i - g_low) / (sum_i
    /// p_i h_rms)` over the domain, `g = w - approach` (`w = K p + z` up to date),
    /// `g_low = min(0, min_j g_j)` (an upper bound of the gap with `min_j g_j`); 0
    /// without pressure. It bounds the energy error of p, hence its error in the norm of
    /// K (module docs).
    pub(super) fn certificate(&self, p: &[f64], approach: f64) -> f64 {
        let ch = self.chunk();
        let [pg, ps, low] = reduce(
            (
                p.par_chunks(ch),
                self.work.w.par_chunks(ch),
                self.problem.mask.par_chunks(ch),
            ),
            |(p, w, m)| sweeps::certificate_terms(p, w, m, approach),
            Some(2),
        );
        if ps > 0.0 {
            (pg / ps + low.max(0.0)) / self.problem.h_rms
        } else {
            0.0
        }
    }

    /// Collects the solution from p and w = K p + z.
    pub(super) fn finish(
        &mut self,
        p: Vec<f64>,
        approach: f64,
        iterations: usize,
        residual: f64,
    ) -> Solution {
        let area = self.op.cell_area();
        let d = if approach.is_finite() { approach } else { 0.0 };
        let contact_cells = p.iter().filter(|&&v| v > 0.0).count();
        let certificate = self.certificate(&p, d);
        let gap_of = |w: f64, m: u8| if m > 0 { (w - d).max(0.0) } else { 0.0 };
        let gap: Vec<f64> = if p.len() > self.tuning.large_grid_cells {
            // Written over w (a solve recomputes w from its start), the solver's w
            // replaced by zeroed pages that cost no memory until the next solve writes
            // them: the same values without a third grid alive.
            let mut gap = std::mem::replace(&mut self.work.w, vec![0.0; p.len()]);
            gap.par_iter_mut()
                .zip(self.problem.mask.par_iter())
                .for_each(|(w, &m)| *w = gap_of(*w, m));
            gap
        } else {
            let w = self.work.w.par_iter().zip(self.problem.mask.par_iter());
            w.map(|(&w, &m)| gap_of(w, m)).collect()
        };
        Solution {
            certificate,
            force: p.iter().sum::<f64>() * area,
            contact_cells,
            contact_area: contact_cells as f64 * area,
            mean_gap: gap.iter().sum::<f64>() / self.problem.domain_cells as f64,
            gap,
            pressure: p,
            approach,
            iterations,
            residual,
            domain_cells: self.problem.domain_cells,
            warm_started: false,
            path: Path::FullGrid,
            nested_start: false,
            single_iterations: 0,
            stencil_iterations: 0,
            scaled_directions: false,
        }
    }

    /// The convergence criterion (module docs) of `p` with `w = K p + z` up to date.
    pub(super) fn criterion(&self, p: &[f64], approach: f64) -> f64 {
        let ch = self.chunk();
        let [pg, ps, worst] = reduce(
            (
                p.par_chunks(ch),
                self.work.w.par_chunks(ch),
                self.problem.mask.par_chunks(ch),
            ),
            |(p, w, m)| sweeps::criterion_terms(p, w, m, approach),
            Some(2),
        );
        let h_rms = self.problem.h_rms;
        (if ps > 0.0 { pg / (ps * h_rms) } else { 0.0 }).max(worst / h_rms)
    }
}
