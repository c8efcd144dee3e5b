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
//! **Iteration.** A round solves the contact with every bonded cell's pressure free (it
//! holds its gap closed, in compression or tension) and every other cell's in `[0, inf)`
//! (a cell that is not bonded joins only by pressing): the kit's projected conjugate
//! gradient (`kit::box_cg`) under the approach, or under the force with the approach as
//! its multiplier. Then bonded cells whose tension exceeds `sigma_c` let go and lose
//! their bond (all of a round's at once, as Pohrt & Popov's rounds do); cells pressed
//! (`p > 0`) join and are bonded from the next round on; the rounds repeat from the last
//! pressures until no cell lets go. A round where only cells joined ends the step: the
//! joined cells carry a pressure, which a bond leaves free, so the next round's solution
//! would be the same. So a loading step is one round, whatever its size (cells join at the
//! approach of equilibrium, never at a round's overshoot), and an unloading step is one
//! round per ring of cells that lets go. Each round is a convex problem, stopped when
//! the largest violation of its conditions (`kit::box_cg`) is at most `tolerance * l`
//! with `l = max(rms of z, |d|, min(w / sigma_c, L))` (L the map's larger side: an
//! adhesive length beyond it would not set the size of the displacements' errors). On a
//! free half-space a round solves on the smallest box of cells that holds the bonded
//! and the penetrating cells (module `window`), at the box's transform size; `K` is
//! applied on the grid for the gaps outside the box, and cells found penetrating there
//! widen the next round's box before any bond changes. The problem is not convex (the
//! energy of detachment is not), so the result is an equilibrium reached from the
//! previous state (the physical one along a quasi-static history), not a global
//! minimum. A step reports the cells that joined and detached, and whether the body
//! separated; a set that keeps changing after [`MAX_ROUNDS`] rounds, or a solve that
//! stalls, is an error carrying the residual reached. Under a force the bonded cells
//! cannot carry (below `-sigma_c` times their area), the body pulls off: every bond
//! lets go.

use crate::error::{BemError, Result};
use crate::kit::box_cg::{self, Bound, BoxProblem, Hold, Scratch};
use crate::kit::surface::{rigid_surface, RigidSurface};
use crate::operator::{GridForms, Preconditioner};
use crate::solver::window::Window;
use crate::solver::{Interrupt, Load};

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
    /// Each cell's lower bound of a round on the grid: none bonded, else 0.
    lo: Vec<f64>,
    /// Cells a round's window must hold (module docs of `window`): the bonded and the
    /// penetrating ones, and those found penetrating outside an earlier round's window.
    reach: Vec<bool>,
    /// The window of the last solves on a set, kept while it fits the set.
    window: Option<window::SetWindow>,
    scratch: Scratch,
    /// Set by the caller (from another thread) to stop the iteration.
    interrupt: Option<Interrupt>,
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
            lo: vec![0.0; n],
            reach: vec![false; n],
            window: None,
            scratch: Scratch::default(),
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
        let (mut joined, mut detached, mut iterations) = (0, 0, 0);
        let mut residual = 0.0;
        let cell = self.op.cell_area();
        // A retraction opens every gap outside the set (module `window`): the rounds may
        // leave them for the end of the step.
        let retracting = matches!(target, Target::Approach(d) if d <= self.approach);
        self.reach.iter_mut().for_each(|r| *r = false);
        let mut bonded = self.contact.iter().filter(|c| **c).count();
        for round in 1..=MAX_ROUNDS {
            let apart = match target {
                // A tension beyond what the bonded cells carry pulls the body off (with
                // no cell bonded: any tension, or no force).
                Target::Force(f) => f <= -self.critical * cell * bonded as f64,
                // No cell bonded and none penetrating at the approach.
                Target::Approach(d) => {
                    bonded == 0 && !(0..self.z.len()).any(|i| self.domain[i] && self.z[i] < d)
                }
            };
            if apart {
                detached += bonded;
                self.contact.iter_mut().for_each(|c| *c = false);
                self.p.iter_mut().for_each(|p| *p = 0.0);
                self.u.iter_mut().for_each(|u| *u = 0.0);
                if let Target::Approach(d) = target {
                    self.approach = d;
                }
                return Ok(self.report(round, joined, detached, iterations, residual));
            }
            // A retraction only shrinks the bonded set and opens gaps: the first round's
            // reach holds for the step.
            let widen = round == 1 || !retracting;
            let (it, res, window) = self.solve_round(target, tolerance, retracting, widen)?;
            iterations += it;
            residual = res;
            // Gaps outside the window, which its solve could not close: such cells widen
            // the next round's window before any cell changes its bond.
            if let Some(w) = window.filter(|_| !retracting) {
                if self.mark_outside(&w) > 0 {
                    continue;
                }
            }
            let (left, came) = self.update_set(window);
            detached += left;
            joined += came;
            bonded = bonded + came - left;
            if left > 0 {
                continue;
            }
            if let Some(w) = window.filter(|_| retracting) {
                // `u` is current in the window only until the set holds.
                self.op.apply(&self.p, &mut self.u);
                if self.mark_outside(&w) > 0 {
                    continue;
                }
            }
            return Ok(self.report(round, joined, detached, iterations, residual));
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

    /// Marks in `reach` the cells of the domain outside `w` that penetrate (`u` current
    /// on the grid); returns how many.
    fn mark_outside(&mut self, w: &Window) -> usize {
        let (nx, d) = (self.op.nx(), self.approach);
        let mut count = 0;
        for i in 0..self.z.len() {
            if !w.holds(i % nx, i / nx) && self.domain[i] && self.u[i] + self.z[i] - d < 0.0 {
                self.reach[i] = true;
                count += 1;
            }
        }
        count
    }

    /// Cells held at the critical tension let go, cells pressed join; returns (left,
    /// joined). Where cells left, `u` is stale until the next round's solve computes
    /// `K p` afresh.
    fn update_set(&mut self, window: Option<Window>) -> (usize, usize) {
        let (mut left, mut came) = (0, 0);
        let (nx, n) = (self.op.nx(), self.z.len());
        // Runs of cells (first, length): the window's rows (off it no cell is bonded or
        // pressed), or the whole grid.
        let runs: Vec<(usize, usize)> = match window {
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
            } else if self.p[i] > 0.0 {
                self.contact[i] = true;
                came += 1;
            }
        }
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
            force: self.p.iter().sum::<f64>() * cell,
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

    /// One round's solve (module docs): the kit's projected conjugate gradient over the
    /// domain, each bonded cell's pressure free, every other cell's in `[0, inf)`, on the smallest window of the grid that holds the cells of `reach`
    /// (with the bonded and the penetrating ones added) where the operator has one
    /// (module `window`), else on the grid. Returns the iterations, the criterion reached
    /// and the window, if one was used: `u = K p` is then current in the window only
    /// while `retracting` (else on the grid).
    fn solve_round(
        &mut self,
        target: Target,
        tolerance: f64,
        retracting: bool,
        widen: bool,
    ) -> Result<(usize, f64, Option<Window>)> {
        let d = match target {
            Target::Approach(d) => d,
            Target::Force(_) => self.approach,
        };
        if widen {
            for (i, r) in self.reach.iter_mut().enumerate() {
                *r |= self.contact[i] || (self.domain[i] && self.u[i] + self.z[i] - d < 0.0);
            }
        }
        let bound = |bonded: bool| if bonded { f64::NEG_INFINITY } else { 0.0 };
        let hold = match target {
            Target::Approach(d) => Hold::Approach(d),
            Target::Force(f) => Hold::Sum {
                sum: f / self.op.cell_area(),
                start: self.approach,
            },
        };
        let scale = self.scale.max(d.abs());
        // A first contact under a force takes the grid: its approach is not known yet.
        let no_bond = !self.contact.iter().any(|c| *c);
        let placed = if no_bond && matches!(target, Target::Force(_)) {
            None
        } else {
            window::place(&self.op, &mut self.window, &self.reach, retracting)
        };
        let Some(win) = placed else {
            for (lo, c) in self.lo.iter_mut().zip(&self.contact) {
                *lo = bound(*c);
            }
            let problem = round_problem(
                (&self.domain, &self.lo, &self.z),
                hold,
                (scale, tolerance),
                self.interrupt.as_ref(),
            );
            let r = box_cg::solve(
                &mut self.op,
                &problem,
                &mut self.p,
                &mut self.u,
                &mut self.scratch,
            )?;
            self.approach = r.approach;
            return Ok((r.iterations, r.residual, None));
        };
        let lo: Vec<f64> = win.gather(&self.contact).into_iter().map(bound).collect();
        let (z, set) = (win.gather(&self.z), win.gather(&self.domain));
        let mut p = win.gather(&self.p);
        let mut u = vec![0.0; p.len()];
        let problem = round_problem(
            (&set, &lo, &z),
            hold,
            (scale, tolerance),
            self.interrupt.as_ref(),
        );
        let solved = box_cg::solve(&mut win.op, &problem, &mut p, &mut u, &mut self.scratch);
        // Every cell off the window is unbonded with no pressure: p vanishes there, and
        // K p in the window is the grid's.
        win.scatter(&mut self.p, &p);
        let cells = win.cells;
        if retracting && solved.is_ok() {
            win.scatter(&mut self.u, &u);
        } else {
            self.op.apply(&self.p, &mut self.u);
        }
        let r = solved?;
        self.approach = r.approach;
        Ok((r.iterations, r.residual, Some(cells)))
    }
}

/// A round's box problem (module docs) on the cells, lower bounds and surface of the
/// grid or of a window.
fn round_problem<'a>(
    (set, lo, z): (&'a [bool], &'a [f64], &'a [f64]),
    hold: Hold,
    (scale, tolerance): (f64, f64),
    interrupt: Option<&'a Interrupt>,
) -> BoxProblem<'a> {
    BoxProblem {
        set,
        lo: Bound::Cells(lo),
        hi: Bound::Uniform(f64::INFINITY),
        z,
        hold,
        scale,
        tolerance,
        max_iterations: MAX_ITERATIONS,
        what: "adhesive contact",
        interrupt,
    }
}

#[derive(Debug, Clone, Copy)]
enum Target {
    Approach(f64),
    Force(f64),
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
mod tests;
