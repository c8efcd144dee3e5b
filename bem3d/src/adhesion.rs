//! Adhesive normal contact in the Griffith (JKR) limit: a rigid body on an elastic
//! half-space, with the local, mesh-dependent detachment criterion of Pohrt & Popov
//! (Facta Universitatis 13, 2015), the 3D counterpart of the review's Eq. 33.
//!
//! **Model.** Adhesion has zero range: surfaces attract only where they touch. A cell
//! joins the contact when the body penetrates it (gap `g < 0`) and, once in contact,
//! carries any pressure, compressive or tensile, until its tension exceeds the critical
//! stress `sigma_c`; then it detaches. `sigma_c` is set by the energy balance of one
//! cell: a cell of area `A` under a uniform tension `sigma` stores the elastic energy
//! `sigma^2 A c / 2`, with `c` its mean surface displacement per unit pressure
//! ([`cell_compliance`]); detaching releases it and costs `w A`, so
//! `sigma_c = sqrt(2 w / c)`. For a square cell of side `h`, `c = 0.946402 h / E*` and
//! `sigma_c = sqrt(w E* / (0.473201 h))`, Pohrt & Popov's value.
//! The criterion depends on the mesh by construction: the crack tip's stress
//! singularity is sampled by one cell, and the resulting force-approach curve converges
//! to JKR's as the cells shrink (the tests measure the order). Loading is path
//! dependent: cells join only on touching, so a loading branch runs (nearly) without
//! adhesion while the unloading branch holds the contact until its rim detaches, as in
//! MRD's rule of Hess.
//!
//! **Conventions** are the normal solver's ([`crate::solver`]): `heights` are the rigid
//! surface's topography (peaks up); with `z = max(h) - h` the gap is `g = u + z - d`
//! for approach `d` and surface displacement `u = K p`, pressure positive in
//! compression. `d` may be negative (retraction past first contact).
//!
//! **Iteration.** For a contact set `C`, the pressures on `C` solve `u + z = d` on `C`
//! (`p = 0` outside): a preconditioned conjugate gradient on `K` restricted to `C`, with
//! the force `sum p A = F` as a projection when the force is prescribed (`d` is then
//! the multiplier, the mean of `u + z` on `C`). Then cells of `C` in tension beyond
//! `sigma_c` leave, and cells outside with `g < 0` join; the rounds repeat from the
//! last pressures until no cell moves. Each round is a linear, symmetric positive
//! definite solve, stopped when `max_C |u + z - d| <= tolerance * l` with
//! `l = max(rms of z, max_C |u|, |d|, min(w / sigma_c, L))` (L the map's larger side:
//! an adhesive length beyond it would not set the size of the displacements' errors);
//! the set update is exact. On a
//! free half-space a round solves on the smallest box of cells that holds `C` (module
//! `window`), at the box's transform size; `K` is applied on the grid, for the gaps
//! outside the box, once the set holds in it. The
//! problem is not convex (the energy of detachment is not), so the result is an
//! equilibrium reached from the previous state (the physical one along a quasi-static
//! history), not a global minimum. A step reports the cells that joined and detached,
//! and whether the body separated; a set that keeps changing after [`MAX_ROUNDS`]
//! rounds, or a solve that stalls, is an error carrying the residual reached.

use crate::error::{BemError, Result};
use crate::kit::chunks::dot;
use crate::kit::surface::{rigid_surface, RigidSurface};
use crate::operator::{GridForms, Preconditioner};
use crate::solver::window::Window;
use crate::solver::{Interrupt, Load};

pub(crate) mod passes;
mod window;

/// Rounds of set updates in one step (a jump-out detaches the contact ring by ring:
/// one round per ring).
pub const MAX_ROUNDS: usize = 20_000;
/// Conjugate-gradient iterations of one round.
const MAX_ITERATIONS: usize = 10_000;

/// The mean surface displacement of a uniformly loaded `hx x hy` cell per unit
/// pressure, times E* [length]: `I / (pi hx hy)` with `I` the integral of `1/r` over
/// pairs of points of the rectangle, in closed form
/// `I = 2/3 (hx^3 + hy^3 - r^3) + 2 hx hy^2 asinh(hx/hy) + 2 hx^2 hy asinh(hy/hx)`,
/// `r = sqrt(hx^2 + hy^2)` (checked against quadrature of Love's displacement in the
/// tests).
pub fn cell_compliance(hx: f64, hy: f64) -> f64 {
    let r = hx.hypot(hy);
    let i = 2.0 / 3.0 * (hx.powi(3) + hy.powi(3) - r.powi(3))
        + 2.0 * hx * hy * hy * (hx / hy).asinh()
        + 2.0 * hx * hx * hy * (hy / hx).asinh();
    i / (std::f64::consts::PI * hx * hy)
}

/// The critical tension of a cell (module docs): `sqrt(2 w E* / cell_compliance)`.
pub fn critical_stress(e_star: f64, work: f64, hx: f64, hy: f64) -> f64 {
    (2.0 * work * e_star / cell_compliance(hx, hy)).sqrt()
}

/// The state reached by one load step.
#[derive(Debug, Clone)]
pub struct AdhesiveStep {
    /// Approach `d` from first contact [length] (the multiplier under force control;
    /// after a separation under force control, the last approach in contact).
    pub approach: f64,
    /// Total normal force `sum p A` [force], negative in tension.
    pub force: f64,
    pub contact_cells: usize,
    /// Contact cells times the cell area [length^2].
    pub contact_area: f64,
    /// Cells that joined (touched) and detached during the step.
    pub joined: usize,
    pub detached: usize,
    /// The largest tension of a contact cell over the critical stress (`<= 1`; 0 with
    /// no cell in tension).
    pub tension: f64,
    /// Set-update rounds and conjugate-gradient iterations summed over them.
    pub rounds: usize,
    pub iterations: usize,
    /// The last round's criterion value (module docs).
    pub residual: f64,
    /// No cell is in contact at the end of the step.
    pub separated: bool,
}

/// The state of an [`AdhesiveContact`] after a step ([`AdhesiveContact::snapshot`]).
#[derive(Debug, Clone)]
pub struct AdhesiveSnapshot {
    contact: Vec<bool>,
    p: Vec<f64>,
    u: Vec<f64>,
    approach: f64,
}

/// A rigid surface in adhesive contact with an elastic half-space, loaded along a
/// history (module docs). Shares the normal solver's operators.
pub struct AdhesiveContact<C: Preconditioner + GridForms> {
    op: C,
    /// `max(h) - h` [length].
    z: Vec<f64>,
    /// Cells that may touch.
    domain: Vec<bool>,
    critical: f64,
    work: f64,
    /// Length scale floor of the criterion: the rms of z, or `w / sigma_c` up to the
    /// map's larger side.
    scale: f64,
    contact: Vec<bool>,
    p: Vec<f64>,
    /// `K p` [length].
    u: Vec<f64>,
    approach: f64,
    /// The window of the last solves on a set, kept while it fits the set.
    window: Option<window::SetWindow>,
    /// Set by the caller (from another thread) to stop the iteration.
    interrupt: Option<Interrupt>,
}

/// Work vectors of the conjugate gradient.
struct Work {
    r: Vec<f64>,
    y: Vec<f64>,
    t: Vec<f64>,
    kt: Vec<f64>,
}

impl<C: Preconditioner + GridForms> AdhesiveContact<C> {
    /// [`Self::new`] for any operator (its compiled entry, in `compiled.rs`, calls this).
    pub(crate) fn new_generic(
        op: C,
        heights: &[f64],
        mask: Option<&[bool]>,
        work: f64,
    ) -> Result<Self> {
        if !(work.is_finite() && work > 0.0) {
            return Err(BemError::InvalidInput(format!(
                "work of adhesion w = {work} must be finite and > 0 (without adhesion use the normal solver)"
            )));
        }
        let RigidSurface { z, domain, rms, .. } = rigid_surface(&op, heights, mask)?;
        let n = z.len();
        let (hx, hy) = (op.lx() / op.nx() as f64, op.ly() / op.ny() as f64);
        let critical = critical_stress(op.e_star(), work, hx, hy);
        if !(critical.is_finite() && critical > 0.0) {
            return Err(BemError::InvalidInput(format!(
                "the critical stress sqrt(2 w E* / c) = {critical} is not a positive number (w = {work}, E* = {}, cells {hx} x {hy})",
                op.e_star()
            )));
        }
        let side = op.lx().max(op.ly());
        Ok(Self {
            // `w / sigma_c` grows as sqrt(w) while the displacements stay set by the
            // geometry: beyond the map's size it would loosen every solve's stop.
            scale: rms.max((work / critical).min(side)),
            op,
            z,
            domain,
            critical,
            work,
            contact: vec![false; n],
            p: vec![0.0; n],
            u: vec![0.0; n],
            approach: 0.0,
            window: None,
            interrupt: None,
        })
    }

    /// Stops the iteration of a step with [`BemError::Interrupted`] once `flag` is set
    /// (from another thread), polled once per iteration. The state is then the
    /// unfinished step's: build a new contact to go on.
    pub fn interrupt_on(&mut self, flag: Interrupt) {
        self.interrupt = Some(flag);
    }

    /// The critical tension of a cell [pressure].
    pub fn critical_stress(&self) -> f64 {
        self.critical
    }

    /// The work of adhesion [energy / length^2].
    pub fn work(&self) -> f64 {
        self.work
    }

    /// Cell pressures of the last step (`ny x nx`, negative in tension).
    pub fn pressure(&self) -> &[f64] {
        &self.p
    }

    /// Which cells are in contact after the last step.
    pub fn contact(&self) -> &[bool] {
        &self.contact
    }

    /// Gap `u + z - d` of the last step at every cell (`ny x nx`).
    pub fn gap(&self) -> Vec<f64> {
        (0..self.z.len())
            .map(|i| self.u[i] + self.z[i] - self.approach)
            .collect()
    }

    /// The state after the last step (contact set, pressures, displacements, approach),
    /// to come back to with [`Self::restore`]: a time integrator's trial step.
    pub fn snapshot(&self) -> AdhesiveSnapshot {
        AdhesiveSnapshot {
            contact: self.contact.clone(),
            p: self.p.clone(),
            u: self.u.clone(),
            approach: self.approach,
        }
    }

    /// Returns to a state taken by [`Self::snapshot`] of this contact. The solve window
    /// (a cache of the box around the contact set) is dropped: the next step starts from
    /// the same state and reaches the same equilibrium to its tolerance, and the same
    /// sequence of steps and restores gives the same numbers bit for bit.
    pub fn restore(&mut self, s: AdhesiveSnapshot) -> Result<()> {
        if s.p.len() != self.p.len() {
            return Err(BemError::InvalidInput(
                "restore: the snapshot is of another contact (its grid differs)".into(),
            ));
        }
        self.contact = s.contact;
        self.p = s.p;
        self.u = s.u;
        self.approach = s.approach;
        self.window = None;
        Ok(())
    }

    /// [`Self::step`] for any operator (its compiled entry, in `compiled.rs`, calls this).
    pub(crate) fn step_generic(&mut self, load: Load, tolerance: f64) -> Result<AdhesiveStep> {
        if !(tolerance > 0.0 && tolerance <= 0.01) {
            return Err(BemError::InvalidInput(format!(
                "tolerance {tolerance} must lie in (0, 0.01]"
            )));
        }
        let area = self.op.lx() * self.op.ly();
        let target = match load {
            Load::Approach(d) if d.is_finite() => {
                if self.op.is_periodic() {
                    return Err(BemError::InvalidInput(
                        "an approach on a periodic half-space leaves the mean displacement open: prescribe the force (Load::Force or Load::MeanPressure)".into(),
                    ));
                }
                Target::Approach(d)
            }
            Load::Force(f) if f.is_finite() => Target::Force(f),
            Load::MeanPressure(p) if p.is_finite() => Target::Force(p * area),
            other => {
                return Err(BemError::InvalidInput(format!(
                    "load {other:?} must be finite"
                )))
            }
        };
        let op = &self.op;
        crate::solver::check_load_magnitude(load, op.e_star(), (op.lx(), op.ly()))?;
        crate::pool::on_pool(|| self.settle(target, tolerance))
    }

    /// The rounds of one step (module docs).
    fn settle(&mut self, target: Target, tolerance: f64) -> Result<AdhesiveStep> {
        let n = self.z.len();
        let mut work = Work {
            r: vec![0.0; n],
            y: vec![0.0; n],
            t: vec![0.0; n],
            kt: vec![0.0; n],
        };
        let (mut joined, mut detached, mut iterations) = (0, 0, 0);
        let mut residual = 0.0;
        // A retraction opens every gap outside the set (module `window`): the rounds may
        // leave them for the end of the step.
        let retracting = matches!(target, Target::Approach(d) if d <= self.approach);
        for round in 1..=MAX_ROUNDS {
            if !self.contact.iter().any(|c| *c) {
                self.p.iter_mut().for_each(|p| *p = 0.0);
                self.u.iter_mut().for_each(|u| *u = 0.0);
                match target {
                    Target::Approach(d) => self.approach = d,
                    // No contact carries a tension or no force: the body stays apart.
                    Target::Force(f) if f <= 0.0 => {
                        return Ok(self.report(round, joined, detached, iterations, 0.0));
                    }
                    // A compressive force: the highest cells touch first.
                    Target::Force(_) => {
                        self.approach = 0.0;
                        let added = self.join_highest();
                        joined += added;
                        continue;
                    }
                }
            } else {
                let (it, res, box_only) =
                    self.solve_on_set(target, tolerance, retracting, &mut work)?;
                iterations += it;
                residual = res;
                if let Some(b) = box_only {
                    // `u` is current in the box only: the gaps outside it wait until the
                    // set holds in the box, then come from K p on the grid.
                    let (left, came) = self.update_set(Some(&b));
                    detached += left;
                    joined += came;
                    if left > 0 || came > 0 {
                        continue;
                    }
                    self.op.apply(&self.p, &mut self.u);
                }
            }
            let (left, came) = self.update_set(None);
            detached += left;
            joined += came;
            if left == 0 && came == 0 {
                return Ok(self.report(round, joined, detached, iterations, residual));
            }
        }
        // The last round's detachments left `u` stale: the state stays consistent.
        self.op.apply(&self.p, &mut self.u);
        Err(BemError::Breakdown {
            what: "adhesive contact",
            iterations,
            residual,
            reason: "the contact set kept changing within the round limit",
        })
    }

    /// Puts the domain's highest cells (`z = 0`) in contact; returns how many.
    fn join_highest(&mut self) -> usize {
        let mut count = 0;
        for i in 0..self.z.len() {
            if self.domain[i] && self.z[i] == 0.0 && !self.contact[i] {
                self.contact[i] = true;
                count += 1;
            }
        }
        count
    }

    /// Cells in tension beyond the critical stress leave, cells that penetrate join (in
    /// `only` if given: where `u` is current); returns (left, joined).
    fn update_set(&mut self, only: Option<&Window>) -> (usize, usize) {
        let (mut left, mut came) = (0, 0);
        let d = self.approach;
        let (nx, n) = (self.op.nx(), self.z.len());
        // Runs of cells (first, length): the box's rows, or the whole grid.
        let runs: Vec<(usize, usize)> = match only {
            Some(b) => (b.y0..b.y0 + b.wy).map(|y| (y * nx + b.x0, b.wx)).collect(),
            None => vec![(0, n)],
        };
        for i in runs.into_iter().flat_map(|(first, len)| first..first + len) {
            if self.contact[i] {
                if self.p[i] < -self.critical {
                    self.contact[i] = false;
                    self.p[i] = 0.0;
                    left += 1;
                }
            } else if self.domain[i] && self.u[i] + self.z[i] - d < 0.0 {
                self.contact[i] = true;
                came += 1;
            }
        }
        // Where cells left, `u` is stale until the next round, which recomputes `K p`
        // before it reads `u` (or zeroes both when no cell is left in contact).
        (left, came)
    }

    fn report(
        &self,
        rounds: usize,
        joined: usize,
        detached: usize,
        iterations: usize,
        residual: f64,
    ) -> AdhesiveStep {
        let cell = self.op.cell_area();
        let cells = self.contact.iter().filter(|c| **c).count();
        let tension = (0..self.p.len())
            .filter(|&i| self.contact[i])
            .map(|i| -self.p[i] / self.critical)
            .fold(0.0f64, f64::max);
        AdhesiveStep {
            approach: self.approach,
            force: sum(&self.p) * cell,
            contact_cells: cells,
            contact_area: cells as f64 * cell,
            joined,
            detached,
            tension,
            rounds,
            iterations,
            residual,
            separated: cells == 0,
        }
    }

    /// Pressures on the contact set for the target (module docs), on the smallest window
    /// of the grid that holds the set where the operator has one (module `window`), else
    /// on the grid. Returns the iterations, the criterion reached and, if `box_only`, the
    /// window, if one was used: `u = K p` is then current in the window only (else on the
    /// grid).
    fn solve_on_set(
        &mut self,
        target: Target,
        tolerance: f64,
        box_only: bool,
        w: &mut Work,
    ) -> Result<(usize, f64, Option<Window>)> {
        let on = &self.contact;
        let Some(win) = window::place(&self.op, &mut self.window, on, box_only) else {
            let set = OnSet {
                on,
                z: &self.z,
                p: &mut self.p,
                u: &mut self.u,
                scale: self.scale,
                approach: &mut self.approach,
                interrupt: self.interrupt.as_ref(),
            };
            let (it, res) = solve_set(&mut self.op, set, target, tolerance, w)?;
            return Ok((it, res, None));
        };
        let (z, mut p) = (win.gather(&self.z), win.gather(&self.p));
        let mut u = vec![0.0; p.len()];
        let set = OnSet {
            on: &win.gather(on),
            z: &z,
            p: &mut p,
            u: &mut u,
            scale: self.scale,
            approach: &mut self.approach,
            interrupt: self.interrupt.as_ref(),
        };
        let solved = solve_set(&mut win.op, set, target, tolerance, w);
        // The set lies in the window: p vanishes outside it, and K p in it is the grid's.
        win.scatter(&mut self.p, &p);
        let cells = win.cells;
        if box_only && solved.is_ok() {
            win.scatter(&mut self.u, &u);
        } else {
            self.op.apply(&self.p, &mut self.u);
        }
        let (it, res) = solved?;
        Ok((it, res, box_only.then_some(cells)))
    }
}

/// A contact set's solve: the set, `z` and the pressures and displacements it moves (all
/// of one grid or window), the criterion's length floor, the approach it sets and the
/// caller's stop flag.
struct OnSet<'a> {
    on: &'a [bool],
    z: &'a [f64],
    p: &'a mut [f64],
    u: &'a mut [f64],
    scale: f64,
    approach: &'a mut f64,
    interrupt: Option<&'a Interrupt>,
}

/// Pressures on the set for the target (module docs): a preconditioned conjugate
/// gradient on `op`, projected on `sum p = F / A` under force control. Returns the
/// iterations and the criterion reached.
fn solve_set<O: Preconditioner>(
    op: &mut O,
    s: OnSet,
    target: Target,
    tolerance: f64,
    w: &mut Work,
) -> Result<(usize, f64)> {
    let n = s.z.len();
    let on = s.on;
    let (r, y, t, kt) = (&mut w.r[..n], &mut w.y[..n], &mut w.t[..n], &mut w.kt[..n]);
    let count = on.iter().filter(|c| **c).count() as f64;
    let cell = op.cell_area();
    if let Target::Force(f) = target {
        // Start on the constraint: shift the pressures uniformly over the set.
        let miss = (f / cell - sum(s.p)) / count;
        for i in 0..n {
            if on[i] {
                s.p[i] += miss;
            }
        }
    }
    op.apply(s.p, s.u);
    let mean_free = matches!(target, Target::Force(_));
    let mut rho_old = 0.0;
    // The step of the last iteration, made at the start of the next (fused with the
    // residual under approach control).
    let mut pending: Option<f64> = None;
    for it in 0..MAX_ITERATIONS {
        // Recompute K p now and then against the drift of the updates.
        let refresh = it % 50 == 0;
        let mut step = None;
        if let Some(alpha) = pending.take() {
            if mean_free || refresh {
                passes::advance(s.p, s.u, alpha, t, kt);
                if refresh {
                    op.apply(s.p, s.u);
                }
            } else {
                step = Some((alpha, &t[..], &kt[..]));
            }
        }
        // Residual on the set: d - (u + z), d the target or the set's mean.
        let d = match target {
            Target::Approach(d) => d,
            Target::Force(_) => masked_sum(on, |i| s.u[i] + s.z[i]) / count,
        };
        *s.approach = d;
        let (worst, largest) = passes::residual(on, s.z, s.p, s.u, step, d, r, y);
        let residual = worst / s.scale.max(largest).max(d.abs());
        if residual <= tolerance {
            return Ok((it, residual));
        }
        if s.interrupt.is_some_and(Interrupt::is_set) {
            return Err(BemError::Interrupted {
                what: "adhesive contact",
                iterations: it,
            });
        }
        // Preconditioned residual on the set (about its mean under force control).
        op.precondition(y);
        let (ry, sy, sr) = passes::products(on, r, y);
        let mean = if mean_free { sy / count } else { 0.0 };
        let rho = ry - mean * sr;
        let beta = if it == 0 || rho_old == 0.0 {
            0.0
        } else {
            rho / rho_old
        };
        rho_old = rho;
        passes::direction(on, y, mean, beta, t);
        op.apply(t, kt);
        let curvature = dot(t, kt);
        if !(curvature > 0.0 && rho.is_finite()) {
            return Err(BemError::Breakdown {
                what: "adhesive contact",
                iterations: it,
                residual,
                reason: "a direction without curvature",
            });
        }
        pending = Some(rho / curvature);
    }
    Err(BemError::Breakdown {
        what: "adhesive contact",
        iterations: MAX_ITERATIONS,
        residual: f64::NAN,
        reason: "the solve on a contact set did not converge within the iteration limit",
    })
}

#[derive(Debug, Clone, Copy)]
enum Target {
    Approach(f64),
    Force(f64),
}

fn sum(v: &[f64]) -> f64 {
    v.iter().sum()
}

fn masked_sum(on: &[bool], f: impl Fn(usize) -> f64) -> f64 {
    (0..on.len()).filter(|&i| on[i]).map(f).sum()
}

#[cfg(test)]
/// An adhesive solve at a vanishing work of adhesion against the normal solver's at
/// the same approach `d` on `op`: pressures within 1e-6 of the peak, force within 1e-7,
/// the same contact cells.
pub(crate) fn is_the_normal_solve<K: crate::SolverOperator>(
    op: K,
    heights: &[f64],
    d: f64,
    pressure: &[f64],
    force: f64,
    contact_cells: usize,
) {
    let normal = crate::ContactSolver::new(op, heights, None)
        .unwrap()
        .solve(
            Load::Approach(d),
            &crate::SolverOptions::new(1e-12, 10_000),
            None,
        )
        .unwrap();
    let peak = normal.pressure.iter().cloned().fold(0.0, f64::max);
    let worst = pressure
        .iter()
        .zip(&normal.pressure)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        worst < 1e-6 * peak,
        "largest difference {worst:e}, peak {peak:e}"
    );
    assert!(
        (force / normal.force - 1.0).abs() < 1e-7,
        "{force} {}",
        normal.force
    );
    assert_eq!(contact_cells, normal.contact_cells);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::love::love_coefficient;
    use crate::operator::NonPeriodicHalfSpace;
    use std::f64::consts::PI;

    /// JKR (Johnson, Kendall & Roberts 1971) for a sphere of radius `r`, parametric in
    /// the contact radius: (approach, force).
    fn jkr(e: f64, r: f64, w: f64, a: f64) -> (f64, f64) {
        let d = a * a / r - (2.0 * PI * a * w / e).sqrt();
        let f = 4.0 * e * a.powi(3) / (3.0 * r) - (8.0 * PI * w * e * a.powi(3)).sqrt();
        (d, f)
    }

    #[test]
    fn cell_compliance_is_the_mean_of_loves_displacement() {
        for (hx, hy) in [(1.0, 1.0), (2.0, 1.0), (0.3, 1.7)] {
            let m = 600;
            let mut total = 0.0;
            for i in 0..m {
                for j in 0..m {
                    let x = ((i as f64 + 0.5) / m as f64 - 0.5) * hx;
                    let y = ((j as f64 + 0.5) / m as f64 - 0.5) * hy;
                    total += love_coefficient(x, y, 0.5 * hx, 0.5 * hy);
                }
            }
            let mean = total / (m * m) as f64 / PI;
            let c = cell_compliance(hx, hy);
            let err = (mean / c - 1.0).abs();
            assert!(
                err < 2e-5,
                "{hx} x {hy}: quadrature {mean} closed form {c} ({err:e})"
            );
        }
        // Pohrt & Popov's factor for a square cell: c / 2 = 0.47320 h / E*.
        assert!((cell_compliance(1.0, 1.0) / 2.0 - 0.473201).abs() < 1e-6);
    }

    /// An approach-controlled cycle of a body of revolution `z(r)` (E* = 1) on an
    /// `n x n` grid of side `l`, optionally masked to a disc of radius `rim`: loading in
    /// `steps` to `d_max`, unloading by the same steps until separation. Returns the
    /// unloading branch as (d, F, contact radius).
    fn cycle(
        n: usize,
        l: f64,
        w: f64,
        profile: impl Fn(f64) -> f64,
        rim: Option<f64>,
        d_max: f64,
        steps: usize,
    ) -> Vec<(f64, f64, f64)> {
        let at = crate::mask::centred(n, l, f64::hypot);
        let heights: Vec<f64> = at.iter().map(|r| -profile(*r)).collect();
        let mask: Option<Vec<bool>> = rim.map(|a| at.iter().map(|r| *r < a).collect());
        let op = NonPeriodicHalfSpace::new(n, n, l, l, 1.0);
        let mut c = AdhesiveContact::new(op, &heights, mask.as_deref(), w).unwrap();
        // Approaches from the apex: the highest cell centre sits below it by the same
        // fraction of a cell at every resolution.
        let apex = (0..n * n)
            .filter(|&k| mask.as_ref().is_none_or(|m| m[k]))
            .map(|k| heights[k])
            .fold(f64::NEG_INFINITY, f64::max);
        let dd = d_max / steps as f64;
        for k in 1..=steps {
            c.step(Load::Approach(dd * k as f64 + apex), 1e-8).unwrap();
        }
        let mut branch = Vec::new();
        for k in 0.. {
            let d = d_max - dd * k as f64;
            let s = c.step(Load::Approach(d + apex), 1e-8).unwrap();
            branch.push((d, s.force, (s.contact_area / PI).sqrt()));
            if s.separated {
                break;
            }
        }
        branch
    }

    /// A JKR sphere (R = 1, w = 0.002) on `n`^2 cells over 3 zero-load radii a0:
    /// (heights, apex, a0, side).
    fn jkr_sphere(n: usize) -> (Vec<f64>, f64, f64, f64) {
        let a0 = (4.5 * PI * 0.002f64).cbrt();
        let l = 3.0 * a0;
        let heights = crate::mask::centred(n, l, |x, y| -(x * x + y * y) / 2.0);
        let apex = heights.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        (heights, apex, a0, l)
    }

    /// The rounds on the box that holds the contact (module `window`) against the same
    /// cycle on the grid (Love's dense matrix: no window): the same contact cells at
    /// every step of a JKR sphere's loading and unloading, forces within 1e-6 of the
    /// peak (the two solves differ by rounding and by their preconditioners).
    #[test]
    fn a_round_on_the_box_is_the_round_on_the_grid() {
        let (n, w, r) = (40, 0.002, 1.0);
        let (heights, apex, a0, l) = jkr_sphere(n);
        let boxed = NonPeriodicHalfSpace::new(n, n, l, l, 1.0);
        let grid = crate::operator::DenseCompliance::love(n, n, l, l, 1.0);
        let mut a = AdhesiveContact::new(boxed, &heights, None, w).unwrap();
        let mut b = AdhesiveContact::new(grid, &heights, None, w).unwrap();
        let dd = (1.2 * a0).powi(2) / r / 30.0;
        // Loading in 30 steps, unloading by the same steps until the body separates.
        let history = (1..=30).chain((-30..30).rev()).map(|k| k as f64 * dd);
        let (mut peak, mut worst, mut boxed_rounds) = (0.0f64, 0.0f64, 0);
        for d in history {
            let sa = a.step(Load::Approach(d + apex), 1e-10).unwrap();
            let sb = b.step(Load::Approach(d + apex), 1e-10).unwrap();
            assert_eq!(sa.contact_cells, sb.contact_cells, "d = {d}");
            assert_eq!(a.contact(), b.contact());
            peak = peak.max(sa.force.abs());
            worst = worst.max((sa.force - sb.force).abs());
            boxed_rounds += a.window.is_some() as usize;
            if sa.separated {
                break;
            }
        }
        assert!(worst < 1e-6 * peak, "{worst} of {peak}");
        assert!(boxed_rounds > 20, "the box served {boxed_rounds} steps");
    }

    /// The rounds' passes sum their chunks in order: a JKR sphere's loading and
    /// unloading on 1 and 3 threads gives the same contact cells, pressures and forces,
    /// bit for bit (the unit tests' chunks are 128 cells: the 48^2 box splits).
    #[test]
    fn a_cycle_is_the_same_whatever_the_threads() {
        let (n, w) = (48, 0.002);
        let (heights, apex, a0, l) = jkr_sphere(n);
        let dd = (1.2 * a0).powi(2) / 20.0;
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build();
            pool.expect("a thread pool").install(|| {
                let op = NonPeriodicHalfSpace::new(n, n, l, l, 1.0);
                let mut c = AdhesiveContact::new(op, &heights, None, w).unwrap();
                let mut trace = Vec::new();
                for k in (1..=20).chain((-20..20).rev()) {
                    let s = c.step(Load::Approach(k as f64 * dd + apex), 1e-10).unwrap();
                    let p: Vec<u64> = c.pressure().iter().map(|v| v.to_bits()).collect();
                    trace.push((s.force.to_bits(), s.contact_cells, p));
                    if s.separated {
                        break;
                    }
                }
                trace
            })
        };
        let one = run(1);
        assert!(
            one.len() > 30 && one.iter().any(|s| s.1 > 128),
            "{}",
            one.len()
        );
        assert!(one == run(3));
    }

    /// Observed order of a ladder that halves the cell size.
    fn order(errs: &[f64]) -> f64 {
        (errs[errs.len() - 2] / errs[errs.len() - 1]).log2()
    }

    /// JKR's pull-off force (force control, the minimum of the approach-controlled
    /// branch) 3/2 pi R w, and the approach at which the contact jumps out under
    /// approach control (JKR's turning point of d(a)); measured errors of the force 0.30,
    /// 0.098, 0.059 at 8, 16 and 32 cells per zero-load radius a0 (with finer approach
    /// steps 0.029 and 0.013 at 64 and 128: first order).
    #[test]
    fn sphere_pull_off_converges_to_jkr() {
        let (w, r) = (0.002, 1.0);
        let fc = 1.5 * PI * r * w;
        let a0 = (4.5 * PI * w * r * r).cbrt();
        let d_max = (1.3 * a0).powi(2);
        let steps = 100;
        let turn = (PI * w * r * r / 8.0).cbrt();
        let d_jump = jkr(1.0, r, w, turn).0;
        let (mut errs, mut jumps) = (Vec::new(), Vec::new());
        for n in [32usize, 64, 128] {
            let branch = cycle(n, 4.0 * a0, w, |x| x * x / (2.0 * r), None, d_max, steps);
            let min_f = branch.iter().map(|b| b.1).fold(f64::INFINITY, f64::min);
            errs.push((min_f / -fc - 1.0).abs());
            let last = branch[branch.len() - 2].0;
            jumps.push((last / d_jump - 1.0).abs());
        }
        // Over the ladder: first order (the last pair alone: 0.74).
        let overall = (errs[0] / errs[2]).log2() / 2.0;
        assert!(errs[0] > errs[1] && errs[1] > errs[2], "{errs:?}");
        assert!(errs[2] < 0.07 && overall > 0.9, "{errs:?}");
        // The jump-out approach: 23 %, 11 %, 4.4 % (an approach step is 6 % of it).
        assert!(
            jumps[0] > jumps[1] && jumps[1] > jumps[2] && jumps[2] < 0.07,
            "{jumps:?}"
        );
    }

    /// Kendall's flat punch: F = -sqrt(8 pi a^3 E* w) (the review's Eq. 34), with a the
    /// radius of the mask's area; measured 3.6 %, 1.4 %, 0.16 % at 8, 16, 32 cells per
    /// radius.
    #[test]
    fn flat_punch_pull_off_converges_to_kendall() {
        let (w, rim, l) = (0.002, 0.25, 1.0);
        let mut errs = Vec::new();
        for n in [32usize, 64, 128] {
            let h = l / n as f64;
            let cells = crate::mask::centred(n, l, f64::hypot)
                .iter()
                .filter(|r| **r < rim)
                .count();
            let a = (cells as f64 * h * h / PI).sqrt();
            let kendall = (8.0 * PI * a.powi(3) * w).sqrt();
            let branch = cycle(n, l, w, |_| 0.0, Some(rim), 0.01, 100);
            let min_f = branch.iter().map(|b| b.1).fold(f64::INFINITY, f64::min);
            errs.push((min_f / -kendall - 1.0).abs());
        }
        assert!(errs[0] > errs[2] && errs[2] < 0.01, "{errs:?}");
    }

    /// Maugis' cone: pull-off 54 w^2 / (pi E* tan^3 theta) (the review's Eq. 37);
    /// measured 40 % and 16 % at 8 and 16 cells per length 18 w / (pi E* tan^2
    /// theta) (8.6 % at 32).
    #[test]
    fn cone_pull_off_converges_to_maugis() {
        let (w, tt) = (0.002f64, 0.2f64);
        let fcone = 54.0 * w * w / (PI * tt.powi(3));
        let ac = 18.0 * w / (PI * tt * tt);
        let mut errs = Vec::new();
        for n in [64usize, 128] {
            let b = cycle(n, 8.0 * ac, w, |r| tt * r, None, 2.0 * tt * ac, 100);
            let min_f = b.iter().map(|b| b.1).fold(f64::INFINITY, f64::min);
            errs.push((min_f / -fcone - 1.0).abs());
        }
        assert!(errs[1] < 0.2 && order(&errs) > 1.0, "{errs:?}");
    }

    /// Under force control the contact holds above the approach-controlled minimum and
    /// separates below it (the same grid, the same criterion, two controls).
    #[test]
    fn force_control_separates_at_the_approach_controlled_minimum() {
        let (w, r, n) = (0.002, 1.0, 64);
        let a0 = (4.5 * PI * w * r * r).cbrt();
        let l = 4.0 * a0;
        let d_max = (1.3 * a0).powi(2);
        let branch = cycle(n, l, w, |x| x * x / (2.0 * r), None, d_max, 200);
        let min_f = branch.iter().map(|b| b.1).fold(f64::INFINITY, f64::min);
        let heights = crate::mask::centred(n, l, |x, y| -(x * x + y * y) / (2.0 * r));
        let top = branch[0].1;
        let run = |last: f64| -> AdhesiveStep {
            let op = NonPeriodicHalfSpace::new(n, n, l, l, 1.0);
            let mut c = AdhesiveContact::new(op, &heights, None, w).unwrap();
            let steps = 100;
            let mut s = None;
            for k in 1..=steps {
                s = Some(
                    c.step(Load::Force(top * k as f64 / steps as f64), 1e-8)
                        .unwrap(),
                );
            }
            for k in 1..=steps {
                let f = top + (last - top) * k as f64 / steps as f64;
                s = Some(c.step(Load::Force(f), 1e-8).unwrap());
                if s.as_ref().unwrap().separated {
                    break;
                }
            }
            s.unwrap()
        };
        let held = run(0.9 * min_f);
        assert!(!held.separated && (held.force / (0.9 * min_f) - 1.0).abs() < 1e-9);
        assert!(run(1.1 * min_f).separated);
    }

    /// With a vanishing work of adhesion the solver is the non-adhesive one: the same
    /// pressures as the normal contact solver at the same approach.
    #[test]
    fn vanishing_adhesion_is_the_normal_solver() {
        let n = 64;
        let l = 1.0;
        let heights = crate::mask::centred(n, l, |x, y| {
            -(x * x + y * y) / 2.0 - 0.003 * (9.0 * x).sin() * (7.0 * y).cos()
        });
        let d = 0.01;
        let op = NonPeriodicHalfSpace::new(n, n, l, l, 1.0);
        let mut c = AdhesiveContact::new(op, &heights, None, 1e-14).unwrap();
        let s = c.step(Load::Approach(d), 1e-10).unwrap();
        let op = NonPeriodicHalfSpace::new(n, n, l, l, 1.0);
        is_the_normal_solve(op, &heights, d, c.pressure(), s.force, s.contact_cells);
    }

    /// The stopping criterion's length scale does not grow with the work of adhesion: a
    /// loading step, where no cell detaches, gives the same contact whatever w (the
    /// critical stress only matters on unloading). With a scale of `w / sigma_c` a
    /// work of 1e15 stopped after 0-1 iterations (+48 % force; 1e16: no force at all).
    #[test]
    fn a_huge_work_of_adhesion_still_converges() {
        let n = 48;
        let heights = crate::mask::centred(n, 1.0, |x, y| {
            -(x * x + y * y) / 2.0 - 0.002 * (9.0 * x).sin() * (7.0 * y).cos()
        });
        let apex = heights.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let load = |w: f64| {
            let op = NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
            let mut c = AdhesiveContact::new(op, &heights, None, w).unwrap();
            let s = c.step(Load::Approach(apex + 0.01), 1e-10).unwrap();
            assert_eq!(s.detached, 0, "w = {w}");
            (s.force, s.contact_cells)
        };
        let (f0, cells0) = load(1.0);
        assert!(cells0 > 50, "{cells0} cells");
        for w in [1e6, 1e15, 1e16, 1e30] {
            let (f, cells) = load(w);
            assert_eq!(cells, cells0, "w = {w}");
            assert!(
                (f / f0 - 1.0).abs() < 1e-7,
                "w = {w}: force {f} against {f0}"
            );
        }
    }

    /// A periodic surface under a mean pressure: the force is held and an approach is
    /// refused with the reason.
    #[test]
    fn periodic_contact_takes_a_force() {
        let n = 32;
        let heights: Vec<f64> = (0..n * n)
            .map(|k| ((k % n) as f64 * 0.2).sin() + ((k / n) as f64 * 0.3).cos())
            .collect();
        let op = crate::PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
        let mut c = AdhesiveContact::new(op, &heights, None, 0.01).unwrap();
        let s = c.step(Load::MeanPressure(0.05), 1e-8).unwrap();
        assert!((s.force - 0.05).abs() < 1e-12 && s.contact_cells > 0);
        let e = c.step(Load::Approach(0.1), 1e-8).unwrap_err().to_string();
        assert!(e.contains("prescribe the force"), "{e}");
    }

    #[test]
    fn bad_input_names_the_parameter() {
        let op = || NonPeriodicHalfSpace::new(8, 8, 1.0, 1.0, 1.0);
        let flat = vec![0.0; 64];
        for (w, what) in [
            (0.0, "work of adhesion"),
            (-1.0, "work"),
            (f64::NAN, "work"),
        ] {
            let e = AdhesiveContact::new(op(), &flat, None, w)
                .err()
                .unwrap()
                .to_string();
            assert!(e.contains(what), "{e}");
        }
        let mut bad = flat.clone();
        bad[3] = f64::NAN;
        let e = AdhesiveContact::new(op(), &bad, None, 0.1)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("heights[3]"), "{e}");
        let e = AdhesiveContact::new(op(), &flat[..10], None, 0.1)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("heights have 10 values"), "{e}");
        let e = AdhesiveContact::new(op(), &flat, Some(&[false; 64]), 0.1)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("mask"), "{e}");
        let mut c = AdhesiveContact::new(op(), &flat, None, 0.1).unwrap();
        for tol in [0.0, 0.5, f64::NAN] {
            let e = c.step(Load::Approach(0.1), tol).unwrap_err().to_string();
            assert!(e.contains("tolerance"), "{e}");
        }
        let e = c
            .step(Load::Force(f64::INFINITY), 1e-8)
            .unwrap_err()
            .to_string();
        assert!(e.contains("must be finite"), "{e}");
        // Loads beyond the normal solve's bound, pushing or pulling, are refused as
        // input, not left to break the iteration down; at the bound the step runs.
        for (load, what) in [
            (
                Load::Force(1e300),
                "a force of 1e300 is a mean pressure of 1e300",
            ),
            (Load::Force(-2e10), "a force of -2e10"),
            (Load::MeanPressure(-1e300), "a mean pressure of -1e300"),
            (Load::Approach(1e300), "approach = 1e300 is more than 1e10"),
            (Load::Approach(-1e300), "approach = -1e300"),
        ] {
            let e = c.step(load, 1e-8).unwrap_err();
            assert!(matches!(e, BemError::InvalidInput(_)), "{e}");
            assert!(e.to_string().contains(what), "{e}");
        }
        assert!(c.step(Load::Approach(-1e10), 1e-8).is_ok());
        // Retraction past separation is a state, not an error; so is a history that
        // reverses at every step.
        let s = c.step(Load::Approach(-1.0), 1e-8).unwrap();
        assert!(s.separated && s.force == 0.0);
        for k in 0..20 {
            let d = if k % 2 == 0 { 0.01 } else { -0.001 };
            let s = c.step(Load::Approach(d), 1e-8).unwrap();
            assert!(s.force.is_finite());
        }
    }
}
