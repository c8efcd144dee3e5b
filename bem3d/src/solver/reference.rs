//! Polonsky & Keer's (1999, Wear 231) constrained conjugate gradients as published: the
//! reference the fast solver ([`super::ContactSolver`]) is tested against, and a plain
//! solver for operators without transforms.
//!
//! One iteration: the gap `g = K p + z - d` on the domain (d, under force control, the
//! mean of `K p + z` over the contact set), the conjugate direction
//! `t = g + delta (G / G_old) t` on the contact set (`G = sum g^2` there; `delta = 0`,
//! a restart, after an iteration that re-admitted a cell), the step
//! `tau = <g, t> / <K t - mean, t>`, the projected update `p <- max(0, p - tau t)`,
//! cells without pressure that interpenetrate re-admitted at `-tau g`, and under force
//! control the pressure rescaled to the force. `K p` is recomputed every iteration; no
//! preconditioner, no restricted solves, all in double precision. The start is uniform
//! (force control) or the overlap `(d - z)+` (approach control). It stops on the fast
//! solver's criterion (module docs of [`super`]).
//!
//! Conventions (heights, approach, mask) are the fast solver's.

use super::{Load, Solution, SolverOptions};
use crate::error::{BemError, Result};
use crate::operator::Compliance;

/// Solves the contact of `heights` on `op` under `load` by the published iteration
/// (module docs); only the cells where `mask` is true (all without a mask) may touch.
/// Checks `opts` and the inputs as [`super::ContactSolver`] does.
pub fn polonsky_keer<K: Compliance>(
    mut op: K,
    heights: &[f64],
    mask: Option<&[bool]>,
    load: Load,
    opts: &SolverOptions,
) -> Result<Solution> {
    opts.validate()?;
    let n = op.cells();
    if heights.len() != n || mask.is_some_and(|m| m.len() != n) {
        return Err(BemError::InvalidInput(format!(
            "heights and mask must have {n} cells"
        )));
    }
    let on: Vec<f64> = (0..n)
        .map(|i| f64::from(u8::from(mask.is_none_or(|m| m[i]))))
        .collect();
    let problem = Problem::new(&op, heights, &on, load)?;
    let mut p = problem.start();
    let mut u = vec![0.0; n];
    let mut kt = vec![0.0; n];
    let mut t = vec![0.0; n];
    let (mut gg_old, mut restart) = (1.0, true);
    let mut last = (0.0, f64::INFINITY);
    for it in 0..=opts.max_iterations {
        op.apply(&p, &mut u);
        let (g, d) = problem.gap(&p, &u);
        let residual = problem.criterion(&p, &g);
        last = (d, residual);
        if residual <= opts.tolerance {
            return Ok(problem.solution(&mut op, p, &g, d, it, residual));
        }
        if it == opts.max_iterations {
            break;
        }
        let gg = direction(&p, &g, &mut t, restart, gg_old);
        gg_old = gg;
        op.apply(&t, &mut kt);
        let tau = problem.step(&p, &g, &t, &kt);
        if !tau.is_finite() {
            return Err(BemError::Breakdown {
                what: "reference solve",
                iterations: it,
                residual,
                reason: "non-finite step",
            });
        }
        restart = update(&mut p, &g, &t, &on, tau);
        problem.rescale(&op, &mut p);
    }
    op.apply(&p, &mut u);
    let (g, _) = problem.gap(&p, &u);
    let sol = problem.solution(&mut op, p, &g, last.0, opts.max_iterations, last.1);
    Err(BemError::NoConvergence {
        what: "reference solve",
        iterations: opts.max_iterations,
        residual: last.1,
        tolerance: opts.tolerance,
        last: Box::new(sol),
    })
}

/// The discrete problem: `z = max(h) - h` over the domain, its rms height, the load.
struct Problem<'a> {
    z: Vec<f64>,
    on: &'a [f64],
    h_rms: f64,
    /// Total force under force control; else the approach.
    force: Option<f64>,
    approach: f64,
    area: f64,
}

impl<'a> Problem<'a> {
    fn new<K: Compliance>(op: &K, h: &[f64], on: &'a [f64], load: Load) -> Result<Self> {
        let n = h.len();
        let cells = on.iter().sum::<f64>();
        if cells == 0.0 {
            return Err(BemError::InvalidInput("the mask holds no cell".into()));
        }
        let top = (0..n)
            .filter(|&i| on[i] > 0.0)
            .map(|i| h[i])
            .fold(f64::NEG_INFINITY, f64::max);
        let mean = (0..n).map(|i| on[i] * h[i]).sum::<f64>() / cells;
        let var = (0..n).map(|i| on[i] * (h[i] - mean).powi(2)).sum::<f64>() / cells;
        // A flat face: the grid diagonal, as the fast solver.
        let h_rms = if var > 0.0 {
            var.sqrt()
        } else {
            op.lx().hypot(op.ly())
        };
        let (force, approach) = match load {
            Load::Force(f) => (Some(f), 0.0),
            Load::MeanPressure(pm) => (Some(pm * op.lx() * op.ly()), 0.0),
            Load::Approach(d) => (None, d),
        };
        Ok(Self {
            z: h.iter().map(|v| top - v).collect(),
            on,
            h_rms,
            force,
            approach,
            area: op.cell_area(),
        })
    }

    /// Uniform pressure carrying the force, or the overlap at the approach.
    fn start(&self) -> Vec<f64> {
        let cells = self.on.iter().sum::<f64>();
        match self.force {
            Some(_) => self.on.to_vec(),
            None => (0..self.z.len())
                .map(|i| self.on[i] * (self.approach - self.z[i]).max(0.0))
                .collect(),
        }
        .into_iter()
        .map(|v| match self.force {
            Some(f) => v * f / (cells * self.area),
            None => v,
        })
        .collect()
    }

    /// The gap on the domain (0 elsewhere) and the approach it is measured from.
    fn gap(&self, p: &[f64], u: &[f64]) -> (Vec<f64>, f64) {
        let n = p.len();
        let d = match self.force {
            Some(_) => {
                let (s, c) = (0..n)
                    .filter(|&i| p[i] > 0.0)
                    .fold((0.0, 0.0), |(s, c), i| (s + u[i] + self.z[i], c + 1.0));
                if c > 0.0 {
                    s / c
                } else {
                    0.0
                }
            }
            None => self.approach,
        };
        let g = (0..n)
            .map(|i| self.on[i] * (u[i] + self.z[i] - d))
            .collect();
        (g, d)
    }

    /// The fast solver's criterion (module docs of [`super`]).
    fn criterion(&self, p: &[f64], g: &[f64]) -> f64 {
        let ps: f64 = p.iter().sum();
        let pg: f64 = p.iter().zip(g).map(|(p, g)| p * g.abs()).sum();
        let worst = g.iter().fold(0.0f64, |m, &v| m.max(-v));
        let mean = if ps > 0.0 { pg / ps } else { 0.0 };
        mean.max(worst) / self.h_rms
    }

    /// `tau = <g, t> / <K t - mean, t>` over the contact set (the mean of K t there under
    /// force control, which keeps the force).
    fn step(&self, p: &[f64], g: &[f64], t: &[f64], kt: &[f64]) -> f64 {
        let set = || (0..p.len()).filter(|&i| p[i] > 0.0);
        let mean = match self.force {
            Some(_) => set().map(|i| kt[i]).sum::<f64>() / set().count().max(1) as f64,
            None => 0.0,
        };
        let num: f64 = set().map(|i| g[i] * t[i]).sum();
        let den: f64 = set().map(|i| (kt[i] - mean) * t[i]).sum();
        num / den
    }

    /// Under force control, p scaled to carry the force exactly.
    fn rescale<K: Compliance>(&self, op: &K, p: &mut [f64]) {
        if let Some(f) = self.force {
            let s = p.iter().sum::<f64>() * op.cell_area();
            if s > 0.0 {
                p.iter_mut().for_each(|v| *v *= f / s);
            }
        }
    }

    fn solution<K: Compliance>(
        &self,
        op: &mut K,
        p: Vec<f64>,
        g: &[f64],
        approach: f64,
        iterations: usize,
        residual: f64,
    ) -> Solution {
        let area = op.cell_area();
        let cells = self.on.iter().sum::<f64>();
        let gap: Vec<f64> = g.iter().map(|v| v.max(0.0)).collect();
        let low = g.iter().fold(0.0f64, |m, &v| m.min(v));
        let ps: f64 = p.iter().sum();
        let pg: f64 = p.iter().zip(g).map(|(p, g)| p * (g - low)).sum();
        let certificate = if ps > 0.0 {
            pg / (ps * self.h_rms)
        } else {
            0.0
        };
        Solution {
            certificate,
            iterations,
            residual,
            ..Solution::full_grid(p, gap, approach, area, cells as usize)
        }
    }
}

/// The conjugate direction on the contact set, `t <- [p > 0] (g + beta t)` with
/// `beta = G / G_old` (0 on a restart); returns G.
fn direction(p: &[f64], g: &[f64], t: &mut [f64], restart: bool, gg_old: f64) -> f64 {
    let gg: f64 = (0..p.len())
        .filter(|&i| p[i] > 0.0)
        .map(|i| g[i] * g[i])
        .sum();
    let beta = if restart { 0.0 } else { gg / gg_old };
    for i in 0..p.len() {
        t[i] = if p[i] > 0.0 { g[i] + beta * t[i] } else { 0.0 };
    }
    gg
}

/// The projected update; returns whether a cell was re-admitted (the next direction
/// restarts).
fn update(p: &mut [f64], g: &[f64], t: &[f64], on: &[f64], tau: f64) -> bool {
    let mut entered = false;
    for i in 0..p.len() {
        if p[i] > 0.0 {
            p[i] = (p[i] - tau * t[i]).max(0.0);
        } else if on[i] > 0.0 && g[i] < 0.0 {
            p[i] = -tau * g[i];
            entered = true;
        }
    }
    entered
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operator::PeriodicHalfSpace;

    /// Bad input and the iteration cap give typed errors (the last iterate kept); the
    /// answer itself is checked against the fast solver in tests/suite/verification.rs.
    #[test]
    fn errors_are_typed() {
        let n = 16;
        let op = || PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
        let h: Vec<f64> = (0..n * n)
            .map(|i| ((i * 7919) % 31) as f64 * 1e-3)
            .collect();
        let load = Load::MeanPressure(1e-2);
        let opts = SolverOptions::new(1e-10, 1000);
        let short = &h[..n];
        assert!(matches!(
            polonsky_keer(op(), short, None, load, &opts),
            Err(BemError::InvalidInput(_))
        ));
        let none = vec![false; n * n];
        assert!(matches!(
            polonsky_keer(op(), &h, Some(&none), load, &opts),
            Err(BemError::InvalidInput(_))
        ));
        match polonsky_keer(op(), &h, None, load, &SolverOptions::new(1e-10, 1)) {
            Err(BemError::NoConvergence { last, .. }) => {
                assert!((last.force - 1e-2).abs() < 1e-15);
            }
            other => panic!("expected NoConvergence, got {other:?}"),
        }
        let sol = polonsky_keer(op(), &h, None, load, &opts).unwrap();
        assert!(sol.residual <= 1e-10 && sol.certificate <= 2e-10);
    }
}
