//! When a solve stops: the criterion, the certificate (duality gap) and the floor of
//! complete contact, evaluated on the problem for a pressure and its gap (solver module
//! docs, "Convergence criterion" and "What a converged solve guarantees").

use super::fused::reduce;
use super::state::{chunk_cells, Problem};
use super::sweeps;
use crate::operator::GridOperator;
use rayon::prelude::*;

/// In complete contact the criterion is met to at most this many ulps of the load's
/// displacement scale (module docs, "Complete contact"). Measured (rough maps on 128^2,
/// h_rms 0.017 L): the iteration in double precision stalls at 70-300 ulps of that
/// scale (free half-space at 100 E*, periodic at 1e6 E*).
const COMPLETE_CONTACT_FLOOR: f64 = 1e3;

/// Iterations without halving the criterion after which a solve in complete contact
/// may stop at its floor.
pub(super) const STALL_ITERATIONS: usize = 10;

impl Problem {
    /// The tolerance a solve in complete contact can reach (module docs, "Complete
    /// contact"): the requested one, or [`COMPLETE_CONTACT_FLOOR`] ulps of the
    /// displacement scale of the mean pressure, `p_mean sqrt(lx ly) / E*`, over the rms
    /// height if that is larger. `pressure_sum`: the sum of p over the domain cells.
    pub(super) fn complete_contact_tolerance<K: GridOperator>(
        &self,
        op: &K,
        tolerance: f64,
        pressure_sum: f64,
    ) -> f64 {
        let mean = pressure_sum / self.domain_cells as f64;
        let scale = mean * (op.lx() * op.ly()).sqrt() / op.e_star();
        tolerance.max(COMPLETE_CONTACT_FLOOR * f64::EPSILON * scale / self.h_rms)
    }

    /// The duality (Frank-Wolfe) gap of `p` over the pressures carrying its force,
    /// relative to that force times the rms height: `sum_i p_i (g_i - g_low) / (sum_i
    /// p_i h_rms)` over the domain, `g = w - approach` (`w = K p + z` up to date),
    /// `g_low = min(0, min_j g_j)` (an upper bound of the gap with `min_j g_j`); 0
    /// without pressure. It bounds the energy error of p, hence its error in the norm of
    /// K (module docs). `nx`: the grid's row length.
    pub(super) fn certificate(&self, p: &[f64], w: &[f64], nx: usize, approach: f64) -> f64 {
        let ch = chunk_cells(nx);
        let [pg, ps, low] = reduce(
            (p.par_chunks(ch), w.par_chunks(ch), self.mask.par_chunks(ch)),
            |(p, w, m)| sweeps::certificate_terms(p, w, m, approach),
            Some(2),
        );
        if ps > 0.0 {
            (pg / ps + low.max(0.0)) / self.h_rms
        } else {
            0.0
        }
    }

    /// The convergence criterion (module docs) of `p` with `w = K p + z` up to date
    /// (`nx`: the grid's row length).
    pub(super) fn criterion(&self, p: &[f64], w: &[f64], nx: usize, approach: f64) -> f64 {
        let ch = chunk_cells(nx);
        let [pg, ps, worst] = reduce(
            (p.par_chunks(ch), w.par_chunks(ch), self.mask.par_chunks(ch)),
            |(p, w, m)| sweeps::criterion_terms(p, w, m, approach),
            Some(2),
        );
        let h_rms = self.h_rms;
        (if ps > 0.0 { pg / (ps * h_rms) } else { 0.0 }).max(worst / h_rms)
    }
}
