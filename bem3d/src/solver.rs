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
use rayon::prelude::*;

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
    /// 1.0 on cells that may touch, 0.0 elsewhere (f64: the sweeps are branch-free).
    mask: Vec<f64>,
    h_rms: f64,
    g: Vec<f64>,
    t: Vec<f64>,
    r: Vec<f64>,
    /// 1.0 on the current contact set.
    active: Vec<f64>,
}

/// Sweep chunk: fixed, so that partial sums (and results) do not depend on the thread
/// count.
const CHUNK: usize = 16_384;

/// Sums `N` per-chunk partial results in chunk order (deterministic for any thread
/// count); `max_last` combines the last entry by max instead of sum.
fn reduce<const N: usize, I, F>(iter: I, f: F, max_slot: Option<usize>) -> [f64; N]
where
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item) -> [f64; N] + Sync + Send,
{
    let parts: Vec<[f64; N]> = iter.into_par_iter().map(f).collect();
    let mut acc = [0.0f64; N];
    for p in parts {
        for k in 0..N {
            if Some(k) == max_slot {
                acc[k] = acc[k].max(p[k]);
            } else {
                acc[k] += p[k];
            }
        }
    }
    acc
}

fn reduce2<I, F>(iter: I, f: F) -> [f64; 2]
where
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item) -> [f64; 2] + Sync + Send,
{
    reduce(iter, f, None)
}

fn reduce3<I, F>(iter: I, f: F) -> [f64; 3]
where
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item) -> [f64; 3] + Sync + Send,
{
    reduce(iter, f, None)
}

/// Four sums; with `third_is_max` the third entry is a maximum.
fn reduce4<I, F>(iter: I, f: F, third_is_max: bool) -> [f64; 4]
where
    I: IntoParallelIterator,
    I::Iter: IndexedParallelIterator,
    F: Fn(I::Item) -> [f64; 4] + Sync + Send,
{
    reduce(iter, f, third_is_max.then_some(2))
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
            h_rms,
            g: vec![0.0; n],
            t: vec![0.0; n],
            r: vec![0.0; n],
            active: vec![0.0; n],
            mask: mask.iter().map(|&m| if m { 1.0 } else { 0.0 }).collect(),
        })
    }

    pub fn operator(&self) -> &K {
        &self.op
    }
    pub fn h_rms(&self) -> f64 {
        self.h_rms
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
        let nm = self.mask.iter().filter(|&&m| m > 0.0).count();
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
                    p[i] = if self.mask[i] > 0.0 {
                        w[i].max(0.0)
                    } else {
                        0.0
                    };
                }
            }
            (None, Load::Approach(d)) => {
                let scale = self.op.e_star() / (self.op.lx() * self.op.ly()).sqrt();
                for i in 0..n {
                    p[i] = if self.mask[i] > 0.0 {
                        (d - self.z[i]).max(0.0) * scale
                    } else {
                        0.0
                    };
                }
            }
            (None, _) => {
                for i in 0..n {
                    p[i] = if self.mask[i] > 0.0 { 1.0 } else { 0.0 };
                }
            }
        }
        if let Some(w) = target_force {
            if w == 0.0 {
                return Ok(self.finish(vec![0.0; n], 0.0, 0, 0.0));
            }
            let s: f64 = p.iter().sum::<f64>() * area;
            if s == 0.0 {
                p.iter_mut().zip(&self.mask).for_each(|(v, &m)| *v = m);
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
        let force_control = target_force.is_some();
        let fixed_approach = match load {
            Load::Approach(d) => d,
            _ => 0.0,
        };
        // Pending factor of the load constraint: p and u = K p are rescaled lazily in
        // pass A (K is linear), saving a sweep.
        let mut scale = 1.0;
        // Shift for the one-pass sum of squares: the previous mean contact gap, close to
        // the current one, so sum (g-c)^2 - n (gbar-c)^2 does not cancel.
        let mut shift = 0.0;
        let h_rms = self.h_rms;
        let e_star = self.op.e_star();
        for it in 0..opts.max_iterations {
            self.op.apply(&p, &mut self.g);
            // Pass A: rescale, raw gap, contact set, sums for its mean and G.
            let [sum_g, sum_g2, nc] = reduce3(
                (
                    p.par_chunks_mut(CHUNK),
                    self.z.par_chunks(CHUNK),
                    self.mask.par_chunks(CHUNK),
                    self.g.par_chunks_mut(CHUNK),
                    self.active.par_chunks_mut(CHUNK),
                ),
                |(p, z, m, g, act)| {
                    let (mut s1, mut s2, mut c) = (0.0, 0.0, 0.0);
                    for i in 0..p.len() {
                        p[i] *= scale;
                        let a = if p[i] > 0.0 { m[i] } else { 0.0 };
                        // g holds u = K p on entry.
                        let gi = m[i] * (scale * g[i] + z[i] - fixed_approach);
                        g[i] = gi;
                        act[i] = a;
                        let gs = gi - shift;
                        s1 += a * gs;
                        s2 += a * gs * gs;
                        c += a;
                    }
                    [s1, s2, c]
                },
            );
            // Force control: the approach is the mean gap over the contact set.
            let mean_shifted = if nc > 0.0 { sum_g / nc } else { 0.0 };
            let gbar = if force_control {
                shift + mean_shifted
            } else {
                0.0
            };
            let approach = fixed_approach + gbar;
            // sum over contact of (g - gbar)^2; for displacement control gbar = 0.
            let big_g = if force_control {
                (sum_g2 - nc * mean_shifted * mean_shifted).max(0.0)
            } else {
                sum_g2 + 2.0 * shift * sum_g + nc * shift * shift
            };
            if force_control {
                shift = gbar;
            }
            let beta = if g_old > 0.0 {
                delta * big_g / g_old
            } else {
                0.0
            };
            // Pass B: shift the gap, residual terms, conjugate direction, <g, t>.
            let [pg, ps, worst, num] = reduce4(
                (
                    p.par_chunks(CHUNK),
                    self.mask.par_chunks(CHUNK),
                    self.active.par_chunks(CHUNK),
                    self.g.par_chunks_mut(CHUNK),
                    self.t.par_chunks_mut(CHUNK),
                ),
                |(p, m, act, g, t)| {
                    let (mut pg, mut ps, mut worst, mut num) = (0.0, 0.0, 0.0f64, 0.0);
                    for i in 0..p.len() {
                        let gi = g[i] - m[i] * gbar;
                        g[i] = gi;
                        pg += p[i] * gi.abs();
                        ps += p[i];
                        worst = worst.max(-gi);
                        let ti = act[i] * (gi + beta * t[i]);
                        t[i] = ti;
                        num += gi * ti;
                    }
                    [pg, ps, worst, num]
                },
                true,
            );
            residual = (if ps > 0.0 { pg / (ps * h_rms) } else { 0.0 }).max(worst / h_rms);
            if residual <= opts.tolerance {
                return Ok(self.finish(p, approach, it, residual));
            }
            g_old = big_g;
            self.op.apply(&self.t, &mut self.r);
            // Pass C: step length (force control: r shifted by its contact mean).
            let [sr, srt, st] = reduce3(
                (
                    self.r.par_chunks(CHUNK),
                    self.t.par_chunks(CHUNK),
                    self.active.par_chunks(CHUNK),
                ),
                |(r, t, act)| {
                    let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
                    for i in 0..r.len() {
                        a += act[i] * r[i];
                        b += r[i] * t[i];
                        c += t[i];
                    }
                    [a, b, c]
                },
            );
            let rbar = if force_control && nc > 0.0 {
                sr / nc
            } else {
                0.0
            };
            let den = srt - rbar * st;
            let tau = if den > 0.0 && num.is_finite() {
                num / den
            } else {
                0.0
            };
            // Pass D: projected update; interpenetrating cells without pressure re-enter
            // the contact set (Polonsky & Keer's overlap correction).
            let step = if tau > 0.0 {
                tau
            } else {
                1.0 / (e_star * nm as f64).max(1e-300)
            };
            let [overlap, total] = reduce2(
                (
                    p.par_chunks_mut(CHUNK),
                    self.t.par_chunks(CHUNK),
                    self.g.par_chunks(CHUNK),
                    self.mask.par_chunks(CHUNK),
                    self.active.par_chunks(CHUNK),
                ),
                |(p, t, g, m, act)| {
                    let (mut o, mut tot) = (0.0, 0.0);
                    for i in 0..p.len() {
                        let enter = if act[i] == 0.0 && g[i] < 0.0 {
                            m[i]
                        } else {
                            0.0
                        };
                        let updated = (p[i] - tau * t[i]).max(0.0);
                        let pi = act[i] * updated + enter * (-step * g[i]);
                        p[i] = pi;
                        o += enter;
                        tot += pi;
                    }
                    [o, tot]
                },
            );
            delta = if overlap > 0.0 { 0.0 } else { 1.0 };
            scale = match target_force {
                Some(w) if total > 0.0 => w / (total * area),
                _ => 1.0,
            };
        }
        // Apply the pending rescale to the last iterate.
        p.iter_mut().for_each(|v| *v *= scale);
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
                self.g[i] = if self.mask[i] > 0.0 {
                    self.z[i] - approach
                } else {
                    0.0
                };
            }
        }
        let contact_cells = p.iter().filter(|&&v| v > 0.0).count();
        let nm = self.mask.iter().filter(|&&m| m > 0.0).count() as f64;
        let mean_gap = (0..n)
            .filter(|&i| self.mask[i] > 0.0)
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
