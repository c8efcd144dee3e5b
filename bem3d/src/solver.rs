//! Constrained conjugate gradients for frictionless normal contact
//! (Polonsky & Keer 1999), force- or displacement-controlled.
//!
//! Conventions: `heights` are the rigid surface's topography (peaks up, towards the
//! half-space). With `z = max(h) - h` the gap is `g = u + z - d` for approach d, surface
//! displacement `u = K p` and pressure p >= 0; first contact is at d = 0. Cells outside
//! an optional mask carry no pressure and are not constrained.
//!
//! Convergence criterion (stated exactly): with `h_rms` the rms of the heights about
//! their mean over the domain, the solve stops when
//! `max( sum_i p_i |g_i| / (sum_i p_i h_rms),  max(0, -min_i g_i) / h_rms ) <= tol`
//! over the domain cells: pressure-weighted mean gap (complementarity) and largest
//! interpenetration, both relative to the rms height (the grid diagonal for a flat face).
//! The force (or approach) constraint is enforced exactly at every iteration.

use crate::error::{BemError, Result};
use crate::operator::Compliance;

/// The load prescribed to a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Load {
    /// Total normal force.
    Force(f64),
    /// Mean pressure over the whole grid area lx * ly.
    MeanPressure(f64),
    /// Rigid-body approach d (measured from first contact).
    Approach(f64),
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    pub tolerance: f64,
    pub max_iterations: usize,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 10_000,
        }
    }
}

/// A solved contact state.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Cell pressures (`ny x nx`).
    pub pressure: Vec<f64>,
    /// Gap at cell centres (`ny x nx`); zero in contact.
    pub gap: Vec<f64>,
    /// Rigid-body approach from first contact.
    pub approach: f64,
    /// Total force, sum p * cell area.
    pub force: f64,
    /// Cells carrying pressure.
    pub contact_cells: usize,
    /// Real contact area, contact cells x cell area.
    pub contact_area: f64,
    /// Mean gap over the domain cells.
    pub mean_gap: f64,
    pub iterations: usize,
    /// Criterion value reached (see module docs).
    pub residual: f64,
}

/// Solver for one height map on one operator; buffers are allocated once.
pub struct ContactSolver<K: Compliance> {
    op: K,
    z: Vec<f64>,
    mask: Vec<bool>,
    h_rms: f64,
    u: Vec<f64>,
    g: Vec<f64>,
    t: Vec<f64>,
    r: Vec<f64>,
    active: Vec<bool>,
}

impl<K: Compliance> ContactSolver<K> {
    /// `heights` (`ny x nx`, peaks up, finite); `mask`: cells that may touch (None: all).
    pub fn new(op: K, heights: &[f64], mask: Option<Vec<bool>>) -> Result<Self> {
        let n = op.cells();
        if heights.len() != n {
            return Err(BemError::InvalidInput(format!(
                "height map has {} values but the grid is {} x {}",
                heights.len(),
                op.ny(),
                op.nx()
            )));
        }
        if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
            return Err(BemError::InvalidInput(format!(
                "non-finite height at row {}, column {}",
                i / op.nx(),
                i % op.nx()
            )));
        }
        if !(op.e_star().is_finite() && op.e_star() > 0.0) {
            return Err(BemError::InvalidInput(format!(
                "E* = {} must be > 0",
                op.e_star()
            )));
        }
        let mask = mask.unwrap_or_else(|| vec![true; n]);
        if mask.len() != n || !mask.iter().any(|&m| m) {
            return Err(BemError::InvalidInput(
                "mask must match the grid and contain a cell".into(),
            ));
        }
        let hmax = heights
            .iter()
            .zip(&mask)
            .filter(|(_, &m)| m)
            .map(|(h, _)| *h)
            .fold(f64::NEG_INFINITY, f64::max);
        let z: Vec<f64> = heights.iter().map(|h| hmax - h).collect();
        let nm = mask.iter().filter(|&&m| m).count() as f64;
        let mean = heights
            .iter()
            .zip(&mask)
            .filter(|(_, &m)| m)
            .map(|(h, _)| h)
            .sum::<f64>()
            / nm;
        let var = heights
            .iter()
            .zip(&mask)
            .filter(|(_, &m)| m)
            .map(|(h, _)| (h - mean).powi(2))
            .sum::<f64>()
            / nm;
        // Flat faces (e.g. a flat punch under a mask) have no rms height: the gap is then
        // measured against the grid diagonal.
        let h_rms = if var > 0.0 {
            var.sqrt()
        } else {
            (op.lx() * op.lx() + op.ly() * op.ly()).sqrt()
        };
        Ok(Self {
            op,
            z,
            mask,
            h_rms,
            u: vec![0.0; n],
            g: vec![0.0; n],
            t: vec![0.0; n],
            r: vec![0.0; n],
            active: vec![false; n],
        })
    }

    pub fn operator(&self) -> &K {
        &self.op
    }
    pub fn h_rms(&self) -> f64 {
        self.h_rms
    }

    fn residual(&self, p: &[f64]) -> f64 {
        let (mut pg, mut ps, mut worst) = (0.0, 0.0, 0.0f64);
        for i in 0..p.len() {
            if self.mask[i] {
                pg += p[i] * self.g[i].abs();
                ps += p[i];
                worst = worst.max(-self.g[i]);
            }
        }
        let comp = if ps > 0.0 {
            pg / (ps * self.h_rms)
        } else {
            0.0
        };
        comp.max(worst / self.h_rms)
    }

    /// Solves for `load`, starting from `warm` pressures if given (e.g. the previous
    /// load step).
    pub fn solve(
        &mut self,
        load: Load,
        opts: &SolverOptions,
        warm: Option<&[f64]>,
    ) -> Result<Solution> {
        let n = self.op.cells();
        let area = self.op.cell_area();
        let nm = self.mask.iter().filter(|&&m| m).count();
        let target_force = match load {
            Load::Force(f) => Some(f),
            Load::MeanPressure(pm) => Some(pm * self.op.lx() * self.op.ly()),
            Load::Approach(_) => None,
        };
        let bad = |v: f64, what: &str| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(BemError::InvalidInput(format!(
                    "{what} = {v} must be finite and >= 0"
                )))
            }
        };
        match load {
            Load::Force(f) | Load::MeanPressure(f) => bad(f, "load")?,
            Load::Approach(d) => bad(d, "approach")?,
        }
        if let Some(w) = warm {
            if w.len() != n {
                return Err(BemError::InvalidInput(
                    "warm start has the wrong size".into(),
                ));
            }
        }
        let mut p = vec![0.0; n];
        match (warm, load) {
            (Some(w), _) => {
                for i in 0..n {
                    p[i] = if self.mask[i] { w[i].max(0.0) } else { 0.0 };
                }
            }
            (None, Load::Approach(d)) => {
                let scale = self.op.e_star() / (self.op.lx() * self.op.ly()).sqrt();
                for i in 0..n {
                    p[i] = if self.mask[i] {
                        (d - self.z[i]).max(0.0) * scale
                    } else {
                        0.0
                    };
                }
            }
            (None, _) => {
                for i in 0..n {
                    p[i] = if self.mask[i] { 1.0 } else { 0.0 };
                }
            }
        }
        if let Some(w) = target_force {
            if w == 0.0 {
                return Ok(self.finish(vec![0.0; n], 0.0, 0, 0.0));
            }
            let s: f64 = p.iter().sum::<f64>() * area;
            if s == 0.0 {
                p.iter_mut()
                    .zip(&self.mask)
                    .for_each(|(v, &m)| *v = if m { 1.0 } else { 0.0 });
            }
            let s: f64 = p.iter().sum::<f64>() * area;
            p.iter_mut().for_each(|v| *v *= w / s);
        } else if let Load::Approach(d) = load {
            if d == 0.0 || p.iter().all(|&v| v == 0.0) {
                // No overlap anywhere: the first contact is at d = 0.
                return Ok(self.finish(vec![0.0; n], d, 0, 0.0));
            }
        }
        let (mut delta, mut g_old) = (0.0, 1.0);
        self.t.iter_mut().for_each(|v| *v = 0.0);
        let mut residual = f64::INFINITY;
        for it in 0..opts.max_iterations {
            self.op.apply(&p, &mut self.u);
            let mut approach = match load {
                Load::Approach(d) => d,
                _ => 0.0,
            };
            for i in 0..n {
                self.g[i] = if self.mask[i] {
                    self.u[i] + self.z[i] - approach
                } else {
                    0.0
                };
            }
            for i in 0..n {
                self.active[i] = self.mask[i] && p[i] > 0.0;
            }
            let active = &self.active;
            let in_contact = |i: usize| active[i];
            let nc = active.iter().filter(|&&a| a).count();
            if target_force.is_some() {
                // Force control: the approach is the mean gap over the contact set.
                let gbar = (0..n)
                    .filter(|&i| in_contact(i))
                    .map(|i| self.g[i])
                    .sum::<f64>()
                    / nc.max(1) as f64;
                approach += gbar;
                for i in 0..n {
                    if self.mask[i] {
                        self.g[i] -= gbar;
                    }
                }
            }
            residual = self.residual(&p);
            if residual <= opts.tolerance {
                return Ok(self.finish(p, approach, it, residual));
            }
            let big_g: f64 = (0..n)
                .filter(|&i| in_contact(i))
                .map(|i| self.g[i] * self.g[i])
                .sum();
            let beta = delta * big_g / g_old;
            for i in 0..n {
                self.t[i] = if in_contact(i) {
                    self.g[i] + beta * self.t[i]
                } else {
                    0.0
                };
            }
            g_old = big_g;
            self.op.apply(&self.t, &mut self.r);
            if target_force.is_some() {
                let rbar = (0..n)
                    .filter(|&i| in_contact(i))
                    .map(|i| self.r[i])
                    .sum::<f64>()
                    / nc.max(1) as f64;
                self.r.iter_mut().for_each(|v| *v -= rbar);
            }
            let num: f64 = (0..n)
                .filter(|&i| in_contact(i))
                .map(|i| self.g[i] * self.t[i])
                .sum();
            let den: f64 = (0..n)
                .filter(|&i| in_contact(i))
                .map(|i| self.r[i] * self.t[i])
                .sum();
            let tau = if den > 0.0 { num / den } else { 0.0 };
            for i in 0..n {
                if in_contact(i) {
                    p[i] = (p[i] - tau * self.t[i]).max(0.0);
                }
            }
            let mut overlap = 0usize;
            // Cells without pressure that interpenetrate re-enter the contact set.
            let step = if tau > 0.0 {
                tau
            } else {
                1.0 / (self.op.e_star() * nm as f64).max(1e-300)
            };
            for i in 0..n {
                if self.mask[i] && !self.active[i] && self.g[i] < 0.0 {
                    p[i] = -step * self.g[i];
                    overlap += 1;
                }
            }
            delta = if overlap > 0 { 0.0 } else { 1.0 };
            if let Some(w) = target_force {
                let s: f64 = p.iter().sum::<f64>() * area;
                if s > 0.0 {
                    p.iter_mut().for_each(|v| *v *= w / s);
                }
            }
        }
        let last = self.finish(p, f64::NAN, opts.max_iterations, residual);
        Err(BemError::NoConvergence {
            iterations: opts.max_iterations,
            residual,
            tolerance: opts.tolerance,
            last: Box::new(last),
        })
    }

    fn finish(&mut self, p: Vec<f64>, approach: f64, iterations: usize, residual: f64) -> Solution {
        let n = p.len();
        let area = self.op.cell_area();
        if iterations == 0 && p.iter().all(|&v| v == 0.0) {
            for i in 0..n {
                self.g[i] = if self.mask[i] {
                    self.z[i] - approach
                } else {
                    0.0
                };
            }
        }
        let contact_cells = p.iter().filter(|&&v| v > 0.0).count();
        let nm = self.mask.iter().filter(|&&m| m).count() as f64;
        let mean_gap = (0..n)
            .filter(|&i| self.mask[i])
            .map(|i| self.g[i].max(0.0))
            .sum::<f64>()
            / nm;
        Solution {
            force: p.iter().sum::<f64>() * area,
            contact_cells,
            contact_area: contact_cells as f64 * area,
            mean_gap,
            gap: self.g.iter().map(|v| v.max(0.0)).collect(),
            pressure: p,
            approach,
            iterations,
            residual,
        }
    }

    /// Tangent normal stiffness dF/dd with the contact set held fixed: solves
    /// `K_CC x = 1` on the contact cells C by conjugate gradients (K_CC is symmetric
    /// positive definite) to relative residual `tol`; k = sum(x) * cell area.
    pub fn tangent_stiffness(&mut self, sol: &Solution, tol: f64) -> Result<f64> {
        let n = self.op.cells();
        let c: Vec<bool> = sol.pressure.iter().map(|&p| p > 0.0).collect();
        let nc = c.iter().filter(|&&v| v).count();
        if nc == 0 {
            return Ok(0.0);
        }
        let mut x = vec![0.0; n];
        let mut res: Vec<f64> = c.iter().map(|&v| if v { 1.0 } else { 0.0 }).collect();
        let mut dir = res.clone();
        let mut q = vec![0.0; n];
        let b_norm = (nc as f64).sqrt();
        let mut rr: f64 = res.iter().map(|v| v * v).sum();
        for it in 0..(10 * nc).max(100) {
            if rr.sqrt() <= tol * b_norm {
                return Ok(x.iter().sum::<f64>() * self.op.cell_area());
            }
            self.op.apply(&dir, &mut q);
            for i in 0..n {
                if !c[i] {
                    q[i] = 0.0;
                }
            }
            let alpha = rr / dir.iter().zip(&q).map(|(a, b)| a * b).sum::<f64>();
            for i in 0..n {
                x[i] += alpha * dir[i];
                res[i] -= alpha * q[i];
            }
            let rr_new: f64 = res.iter().map(|v| v * v).sum();
            let beta = rr_new / rr;
            for i in 0..n {
                dir[i] = res[i] + beta * dir[i];
            }
            rr = rr_new;
            let _ = it;
        }
        Err(BemError::NoConvergence {
            iterations: (10 * nc).max(100),
            residual: rr.sqrt() / b_norm,
            tolerance: tol,
            last: Box::new(sol.clone()),
        })
    }
}
