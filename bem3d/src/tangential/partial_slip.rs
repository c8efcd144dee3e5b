//! Partial slip of a held normal contact under a tangential load history (the model
//! and the iteration: module docs of [`super`]).

use super::cerruti::CerrutiPeriodic;
use super::compliance::TangentialCompliance;
use crate::error::{BemError, Result};
use crate::solver::Interrupt;

/// The energy of one cycle of an oscillating tangential force (Section 7).
#[derive(Debug, Clone, PartialEq)]
pub struct Cycle {
    /// The energy dissipated by slip, summed over the cycle's steps [force x length].
    pub dissipated: f64,
    /// The area of the cycle's force-shift loop (trapezoids) [force x length]: equal to
    /// the dissipation where the steps resolve the loop (the energy balance).
    pub loop_area: f64,
    /// The measured cycle's (force, shift) points: from the amplitude down to its
    /// negative and back, `2 steps + 1` points.
    pub points: Vec<(f64, f64)>,
}

/// The state of one tangential load step.
#[derive(Debug, Clone)]
pub struct TangentialStep {
    /// The tangential force reached [force].
    pub force: f64,
    /// The rigid shift of the body along x [length]: from the mean surface displacement
    /// on a periodic surface, absolute on the free half-space.
    pub shift: f64,
    /// Cells that stick (`|q| < mu p`) and cells that slip, of the cells in contact.
    pub stick_cells: usize,
    pub slip_cells: usize,
    /// Energy dissipated by slip in this step [force x length].
    pub dissipated: f64,
    /// Iterations and the final residual (largest violation of the law over the largest
    /// displacement, that scale floored at rounding: [`ROUNDING`]).
    pub iterations: usize,
    pub residual: f64,
    /// The force reached the total friction `mu sum p`: the body slides (the shift is
    /// then undefined and left at NaN; the tractions are at their bounds).
    pub sliding: bool,
}

/// Partial slip of a held normal contact under a tangential load history.
pub struct PartialSlip<C = CerrutiPeriodic> {
    pub(super) op: C,
    /// Coulomb's friction coefficient.
    mu: f64,
    /// `mu p` per cell [pressure].
    pub(super) bound: Vec<f64>,
    /// Accumulated slip per cell [length].
    pub(super) slip: Vec<f64>,
    /// The traction of the last step [pressure].
    pub(super) q: Vec<f64>,
    /// The tractions' bound `mu sum p` times the cell area [force].
    pub(super) friction: f64,
    /// The cells in contact (`p > 0`), in grid order.
    pub(super) contact: Vec<usize>,
    /// Set by the caller (from another thread) to stop the iteration.
    pub(super) interrupt: Option<Interrupt>,
}

/// The largest friction coefficient a solver takes.
const MAX_MU: f64 = 1e6;

/// Iteration limit of a step.
const MAX_ITERATIONS: usize = 20_000;

/// The most loads one [`PartialSlip::cycle`] runs (ramp and cycles), each a
/// partial-slip solve: a loop is resolved by tens of steps, and a million solves is
/// hours on a fine grid.
const MAX_CYCLE_LOADS: usize = 1_000_000;

/// The rounding level of a step's displacements relative to the largest displacement
/// it starts from: the residual's scale (the largest displacement) is floored at this
/// over the tolerance times that start. A step whose answer is no traction at all (no
/// force and no slip yet) then ends at rounding instead of iterating on a residual
/// relative to displacements of rounding size; any other step's largest displacement is
/// far above the floor (a millionth of its start at a tolerance of 1e-8).
const ROUNDING: f64 = 1e-14;

/// The rounding level of the stick cells' `u + s` about their mean (the shift),
/// relative to their largest magnitude at the step's start: the residual's scale is
/// floored at this over the tolerance times that magnitude too. Where the slip dwarfs
/// the step's elastic displacement (a step that moves the body far while its traction
/// stays near zero, as when a normal force that changes has slipped the cells), the
/// sums over the contact cannot resolve the displacement below this (measured: a stall
/// at 1.5e-14 of `|u + s|`, 120 ulps, over 592 contact cells).
const SUMS_ROUNDING: f64 = 1e-12;

/// Iterations between computations of `K q` afresh while its running update is used.
const REFRESH: usize = 50;

impl<C: TangentialCompliance> PartialSlip<C> {
    /// [`Self::new`] for any operator (its compiled entry, in `compiled.rs`, calls this).
    pub(crate) fn new_generic(op: C, pressure: &[f64], mu: f64) -> Result<Self> {
        // Above MAX_MU a load is a vanishing fraction of the friction limit, below what
        // the force balance resolves (its tolerance scales with that limit).
        if !(mu > 0.0 && mu <= MAX_MU) {
            return Err(BemError::InvalidInput(format!(
                "friction coefficient mu = {mu} must lie in (0, {MAX_MU:e}]"
            )));
        }
        let n = op.cells();
        let mut out = Self {
            op,
            mu,
            bound: vec![0.0; n],
            slip: vec![0.0; n],
            q: vec![0.0; n],
            friction: 0.0,
            contact: Vec::new(),
            interrupt: None,
        };
        out.press(pressure)?;
        Ok(out)
    }

    /// Holds a new normal pressure from the next step on, the accumulated slip kept
    /// (the caller sets the slip of the cells that enter contact): the bounds `mu p`,
    /// the friction limit and the contact cells follow it; a cell out of contact carries
    /// no traction and a traction beyond its new bound is put on it (the next step
    /// slips it). Refused, the state unchanged, where the pressure is not a grid of
    /// finite values >= 0 with a cell in contact.
    pub(super) fn press(&mut self, pressure: &[f64]) -> Result<()> {
        if pressure.len() != self.op.cells() {
            return Err(BemError::InvalidInput(format!(
                "pressure has {} values for a grid of {} cells",
                pressure.len(),
                self.op.cells()
            )));
        }
        if let Some(i) = pressure.iter().position(|p| !p.is_finite() || *p < 0.0) {
            return Err(BemError::InvalidInput(format!(
                "pressure[{i}] = {} must be finite and >= 0",
                pressure[i]
            )));
        }
        let bound: Vec<f64> = pressure.iter().map(|p| self.mu * p).collect();
        let friction = bound.iter().sum::<f64>() * self.op.cell_area();
        if friction <= 0.0 {
            return Err(BemError::InvalidInput(
                "no cell is in contact (pressure is zero everywhere): nothing can carry a tangential force".into(),
            ));
        }
        for (q, b) in self.q.iter_mut().zip(&bound) {
            *q = q.clamp(-b, *b);
        }
        self.contact = (0..bound.len()).filter(|&i| bound[i] > 0.0).collect();
        self.bound = bound;
        self.friction = friction;
        Ok(())
    }

    /// Stops the iteration of a step with [`BemError::Interrupted`] once `flag` is set
    /// (from another thread), polled once per iteration. The accumulated slip is then
    /// that before the step; [`Self::traction`] holds the unfinished iterate.
    pub fn interrupt_on(&mut self, flag: Interrupt) {
        self.interrupt = Some(flag);
    }

    /// The traction of the last step [pressure], `ny x nx`.
    pub fn traction(&self) -> &[f64] {
        &self.q
    }

    /// The accumulated slip per cell [length].
    pub fn slip(&self) -> &[f64] {
        &self.slip
    }

    /// The largest tangential force the contact carries without sliding, `mu P`.
    pub fn friction_limit(&self) -> f64 {
        self.friction
    }

    /// [`Self::cycle`] for any operator (its compiled entry, in `compiled.rs`, calls this).
    pub(crate) fn cycle_generic(
        &mut self,
        amplitude: f64,
        steps: usize,
        cycles: usize,
        tolerance: f64,
    ) -> Result<Cycle> {
        if !(amplitude.is_finite() && amplitude > 0.0 && amplitude < self.friction) {
            return Err(BemError::InvalidInput(format!(
                "force amplitude {amplitude} must lie in (0, mu P = {}): at mu P the body slides",
                self.friction
            )));
        }
        if !((1..=MAX_CYCLE_LOADS).contains(&steps)
            && (1..=MAX_CYCLE_LOADS).contains(&cycles)
            && steps * (2 * cycles + 1) <= MAX_CYCLE_LOADS)
        {
            return Err(BemError::InvalidInput(format!(
                "steps = {steps} and cycles = {cycles} must be >= 1, with steps x \
                 (2 cycles + 1) = the loads of the whole history at most \
                 {MAX_CYCLE_LOADS:e}"
            )));
        }
        for k in 1..=steps {
            self.load_generic(amplitude * k as f64 / steps as f64, tolerance)?;
        }
        let mut out = Cycle {
            dissipated: 0.0,
            loop_area: 0.0,
            points: Vec::new(),
        };
        for cycle in 0..cycles {
            let mut last = self.load_generic(amplitude, tolerance)?;
            if cycle + 1 == cycles {
                out.points.push((last.force, last.shift));
            }
            for k in 1..=2 * steps {
                // Down to -amplitude in `steps` steps, back up in `steps` more.
                let f = if k <= steps {
                    amplitude * (1.0 - 2.0 * k as f64 / steps as f64)
                } else {
                    amplitude * (-1.0 + 2.0 * (k - steps) as f64 / steps as f64)
                };
                let s = self.load_generic(f, tolerance)?;
                if cycle + 1 == cycles {
                    out.dissipated += s.dissipated;
                    out.loop_area += 0.5 * (s.force + last.force) * (s.shift - last.shift);
                    out.points.push((s.force, s.shift));
                }
                last = s;
            }
        }
        Ok(out)
    }

    /// [`Self::load`] for any operator (its compiled entry, in `compiled.rs`, calls this).
    pub(crate) fn load_generic(&mut self, force: f64, tolerance: f64) -> Result<TangentialStep> {
        if !force.is_finite() {
            return Err(BemError::InvalidInput(format!(
                "tangential force {force} must be finite"
            )));
        }
        if !(tolerance > 0.0 && tolerance <= 0.1) {
            return Err(BemError::InvalidInput(format!(
                "tolerance {tolerance} must lie in (0, 0.1]"
            )));
        }
        // On a pool thread: the iteration's short parallel loops start in place instead
        // of each waking a pool thread and the caller (the module docs of `crate::pool`;
        // the times are in bench/HISTORY.md).
        crate::pool::on_pool(|| self.load_on_pool(force, tolerance))
    }

    /// [`Self::load`] of a checked force and tolerance, on a pool thread.
    fn load_on_pool(&mut self, force: f64, tolerance: f64) -> Result<TangentialStep> {
        if force.abs() >= self.friction {
            return Ok(self.sliding(force));
        }
        // `u = K q` of the converged traction, from the iteration's last check.
        let (iterations, residual, shift, u) = self.iterate(force, tolerance)?;
        let (mut stick, mut slipping, mut dissipated) = (0, 0, 0.0);
        for &i in &self.contact {
            if self.q[i].abs() < self.bound[i] {
                stick += 1;
            } else {
                slipping += 1;
                let ds = shift - u[i] - self.slip[i];
                // New slip of the traction's sign (within the tolerance of the law).
                let ds = if ds * self.q[i] > 0.0 { ds } else { 0.0 };
                dissipated += self.q[i] * ds;
                self.slip[i] += ds;
            }
        }
        Ok(TangentialStep {
            force,
            shift,
            stick_cells: stick,
            slip_cells: slipping,
            dissipated: dissipated * self.op.cell_area(),
            iterations,
            residual,
            sliding: false,
        })
    }

    /// The state at gross sliding: every contact cell at its bound. The body has slid by
    /// an amount the quasi-static problem leaves open; the next step starts from where it
    /// stops (every cell's `u + s` equal, the shift's reference reset to 0).
    fn sliding(&mut self, force: f64) -> TangentialStep {
        let sign = force.signum();
        for (q, b) in self.q.iter_mut().zip(&self.bound) {
            *q = sign * b;
        }
        let mut u = vec![0.0; self.q.len()];
        self.op.apply(&self.q, &mut u);
        for (s, u) in self.slip.iter_mut().zip(&u) {
            *s = -u;
        }
        let cells = self.bound.iter().filter(|b| **b > 0.0).count();
        TangentialStep {
            force: sign * self.friction,
            shift: f64::NAN,
            stick_cells: 0,
            slip_cells: cells,
            dissipated: f64::NAN,
            iterations: 0,
            residual: 0.0,
            sliding: true,
        }
    }

    /// The projected conjugate gradient of one step (module docs); returns the
    /// iterations, the residual, the shift and the displacement `K q`. Its loops run
    /// over the contact cells; only the operator and the displacement's scale see the
    /// whole grid.
    fn iterate(&mut self, force: f64, tolerance: f64) -> Result<(usize, f64, f64, Vec<f64>)> {
        let n = self.q.len();
        let target = force / self.op.cell_area();
        let floor = self.friction / self.op.cell_area();
        let (q, bound, slip, cells) = (&mut self.q, &self.bound, &self.slip, &self.contact);
        restore_force(q, bound, cells, target, floor);
        let m = cells.len();
        let (mut u, mut t, mut v) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        // The residual on the stick set (zero elsewhere) and its preconditioned image.
        let (mut w, mut z) = (vec![0.0; n], vec![0.0; n]);
        // Per contact cell: u + s, and the stick set of this iterate and the last.
        let mut r = vec![0.0; m];
        let mut free = vec![false; m];
        let mut free_prev: Vec<bool> = Vec::new();
        let mut g_old = 0.0;
        let mut last = f64::INFINITY;
        self.op.apply(q, &mut u);
        let start = u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let sums = cells
            .iter()
            .fold(0.0f64, |m, &i| m.max((u[i] + slip[i]).abs()));
        let least_scale = (ROUNDING / tolerance * start)
            .max(SUMS_ROUNDING / tolerance * sums)
            .max(f64::MIN_POSITIVE);
        // Iterations since `u` was last computed as `K q` (0: it is `K q` itself).
        let mut followed = 0;
        let interrupt = self.interrupt.clone();
        for it in 0..MAX_ITERATIONS {
            for (k, &i) in cells.iter().enumerate() {
                r[k] = u[i] + slip[i];
            }
            let shift = shift_and_stick_set(q, bound, cells, &r, &mut free);
            let scale = u
                .iter()
                .fold(0.0f64, |m, x| m.max(x.abs()))
                .max(least_scale);
            let worst = (0..m)
                .filter(|&k| free[k])
                .fold(0.0f64, |w, k| w.max((r[k] - shift).abs()));
            let residual = worst / scale;
            last = residual;
            if residual <= tolerance {
                if followed == 0 {
                    return Ok((it, residual, shift, u));
                }
                // Stop only on `u = K q` itself, not on its running update.
                self.op.apply(q, &mut u);
                followed = 0;
                continue;
            }
            if interrupt.as_ref().is_some_and(Interrupt::is_set) {
                return Err(BemError::Interrupted {
                    what: "partial slip",
                    iterations: it,
                });
            }
            // Conjugate direction on the stick set from its residual about its mean,
            // preconditioned where the operator has a preconditioner (its image again
            // about its mean on the set, so that the force stays).
            let fc = free.iter().filter(|f| **f).count().max(1) as f64;
            let mean_f = (0..m).filter(|&k| free[k]).map(|k| r[k]).sum::<f64>() / fc;
            for (k, &i) in cells.iter().enumerate() {
                w[i] = if free[k] { r[k] - mean_f } else { 0.0 };
            }
            let d: &[f64] = if self.op.precondition(&w, &mut z) {
                let mean_z = (0..m)
                    .filter(|&k| free[k])
                    .map(|k| z[cells[k]])
                    .sum::<f64>()
                    / fc;
                for (k, &i) in cells.iter().enumerate() {
                    z[i] = if free[k] { z[i] - mean_z } else { 0.0 };
                }
                &z
            } else {
                &w
            };
            let g: f64 = cells.iter().map(|&i| w[i] * d[i]).sum();
            let beta = if free == free_prev && g_old > 0.0 {
                g / g_old
            } else {
                0.0
            };
            for (k, &i) in cells.iter().enumerate() {
                t[i] = if free[k] { d[i] + beta * t[i] } else { 0.0 };
            }
            g_old = g;
            free_prev.clone_from(&free);
            self.op.apply(&t, &mut v);
            let on_set = || (0..m).filter(|&k| free[k]).map(|k| cells[k]);
            let vbar = on_set().map(|i| v[i]).sum::<f64>() / fc;
            let den: f64 = on_set().map(|i| t[i] * (v[i] - vbar)).sum();
            let num: f64 = (0..m)
                .filter(|&k| free[k])
                .map(|k| t[cells[k]] * (r[k] - mean_f))
                .sum();
            if !(den > 0.0 && num.is_finite()) {
                return Err(BemError::Breakdown {
                    what: "partial slip",
                    iterations: it,
                    residual,
                    reason: "a direction without curvature",
                });
            }
            let tau = num / den;
            let mut projected = false;
            for (k, &i) in cells.iter().enumerate() {
                if free[k] {
                    let step = q[i] - tau * t[i];
                    q[i] = step.clamp(-bound[i], bound[i]);
                    projected |= q[i] != step;
                }
            }
            let restored = restore_force(q, bound, cells, target, floor);
            // Where the step moved q by exactly -tau t, K q moves by -tau K t = -tau v:
            // one operator application an iteration instead of two. The running update
            // is refreshed every `REFRESH` iterations against rounding.
            if projected || restored || followed + 1 >= REFRESH {
                self.op.apply(q, &mut u);
                followed = 0;
            } else {
                for (u, v) in u.iter_mut().zip(&v) {
                    *u -= tau * v;
                }
                followed += 1;
            }
        }
        Err(BemError::Breakdown {
            what: "partial slip",
            iterations: MAX_ITERATIONS,
            residual: last,
            reason: "no convergence within the iteration limit",
        })
    }
}

/// Restores `sum q = target` on the contact `cells` by a uniform change of the cells
/// strictly inside their bounds, projecting again (a few rounds: each round moves the
/// rest to fewer cells); `floor` is the scale of the miss's tolerance when `target` is
/// small. Returns whether it changed any traction.
fn restore_force(q: &mut [f64], bound: &[f64], cells: &[usize], target: f64, floor: f64) -> bool {
    for round in 0..50 {
        let miss = target - cells.iter().map(|&i| q[i]).sum::<f64>();
        if miss.abs() <= 1e-14 * target.abs().max(floor) {
            return round > 0;
        }
        let free: Vec<usize> = cells
            .iter()
            .copied()
            .filter(|&i| q[i].abs() < bound[i])
            .collect();
        let moved = if free.is_empty() { cells } else { &free };
        let d = miss / moved.len() as f64;
        for &i in moved {
            q[i] = (q[i] + d).clamp(-bound[i], bound[i]);
        }
    }
    true
}

/// The shift of an iterate with `r = u + s` on the contact `cells`: the stick cells'
/// mean of `r`, or with none, a value the bound cells' residuals bracket (any value
/// between keeps them at their bounds). Fills `free` with the stick set: interior cells,
/// and bound cells whose residual asks to leave their bound (at +mu p a new slip would
/// be negative, at -mu p positive).
fn shift_and_stick_set(
    q: &[f64],
    bound: &[f64],
    cells: &[usize],
    r: &[f64],
    free: &mut [bool],
) -> f64 {
    let interior = |k: usize| q[cells[k]].abs() < bound[cells[k]];
    let (sum, count) = (0..cells.len())
        .filter(|&k| interior(k))
        .fold((0.0, 0usize), |(s, c), k| (s + r[k], c + 1));
    let shift = if count > 0 {
        sum / count as f64
    } else {
        let hi = (0..cells.len())
            .filter(|&k| q[cells[k]] > 0.0)
            .map(|k| r[k])
            .fold(f64::INFINITY, f64::min);
        let lo = (0..cells.len())
            .filter(|&k| q[cells[k]] < 0.0)
            .map(|k| r[k])
            .fold(f64::NEG_INFINITY, f64::max);
        match (lo.is_finite(), hi.is_finite()) {
            (true, true) => 0.5 * (lo + hi),
            (true, false) => lo,
            (false, true) => hi,
            _ => 0.0,
        }
    };
    for (k, f) in free.iter_mut().enumerate() {
        let qk = q[cells[k]];
        *f = interior(k) || (qk > 0.0 && r[k] > shift) || (qk < 0.0 && r[k] < shift);
    }
    shift
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Hertz pressure of radius `a` at the centre of an `n x n` unit cell, cell centres.
    fn hertz(n: usize, a: f64, p0: f64) -> Vec<f64> {
        crate::mask::centred(n, 1.0, |x, y| {
            let s = 1.0 - (x * x + y * y) / (a * a);
            if s > 0.0 {
                p0 * s.sqrt()
            } else {
                0.0
            }
        })
    }

    /// Cattaneo's traction for a Hertz pressure of peak `p0` and radius `a` at the
    /// force ratio `Q / (mu P)`, at the cell centres of the grid of [`hertz`].
    fn cattaneo(n: usize, a: f64, p0: f64, mu: f64, ratio: f64) -> Vec<f64> {
        let c = a * (1.0 - ratio).cbrt();
        crate::mask::centred(n, 1.0, |x, y| {
            let r2 = x * x + y * y;
            let outer = (1.0 - r2 / (a * a)).max(0.0).sqrt();
            let inner = (1.0 - r2 / (c * c)).max(0.0).sqrt();
            mu * p0 * (outer - c / a * inner)
        })
    }

    /// Bad input gets an error naming it; a force at or beyond `mu P` is gross sliding,
    /// reported as such, not as a failure.
    #[test]
    fn bad_input_and_gross_sliding() {
        let op = || CerrutiPeriodic::new(16, 16, 1.0, 1.0, 1.0, 0.5).unwrap();
        let p = hertz(16, 0.3, 1.0);
        for mu in [0.0, -1.0, f64::NAN, f64::INFINITY, 1.1e6] {
            let e = PartialSlip::new(op(), &p, mu).err().unwrap().to_string();
            assert!(e.contains("mu"), "{e}");
        }
        let e = PartialSlip::new(op(), &vec![0.0; 256], 0.3)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("no cell is in contact"), "{e}");
        let mut bad = p.clone();
        bad[7] = f64::NAN;
        let e = PartialSlip::new(op(), &bad, 0.3).err().unwrap().to_string();
        assert!(e.contains("pressure[7]"), "{e}");
        for nu in [-0.1, 0.6] {
            assert!(CerrutiPeriodic::new(16, 16, 1.0, 1.0, 1.0, nu).is_err());
        }
        // Sizes and moduli in the normal operators' range (beyond it a cell's area or
        // the tractions overflow).
        for (l, g) in [(1e300, 1.0), (1e-300, 1.0), (1.0, 1e-300), (1.0, 1e300)] {
            assert!(
                CerrutiPeriodic::new(16, 16, l, 1.0, g, 0.3).is_err(),
                "{l} {g}"
            );
            let free = super::super::CerrutiFree::new(16, 16, 1.0, l, g, 0.3);
            assert!(free.is_err(), "{l} {g}");
        }
        let mut ps = PartialSlip::new(op(), &p, 0.3).unwrap();
        assert!(ps.load(f64::NAN, 1e-8).is_err() && ps.load(0.1, 0.0).is_err());
        let slide = ps.load(-2.0 * ps.friction_limit(), 1e-8).unwrap();
        assert!(slide.sliding && slide.force == -ps.friction_limit());
        assert!(ps.traction().iter().zip(&p).all(|(q, p)| *q == -0.3 * p));
        // Back below the limit, the contact sticks again and carries the force.
        let back = ps.load(0.5 * ps.friction_limit(), 1e-8).unwrap();
        assert!(!back.sliding && back.stick_cells > 0);
    }

    /// Cattaneo-Mindlin (a sphere under Q = mu P / 2, nu = 0.5, contact radius a tenth
    /// of the period): the stick radius c/a = (1 - Q/(mu P))^(1/3) = 0.7937 within 1 %
    /// from 25 cells per contact radius on (measured 0.42 % at 25.6 and 51.2 cells: the
    /// radius comes from a count of cells), and the traction's relative L2 distance from
    /// Cattaneo's closed form falls with the cells per radius (measured 1.12 %, 0.71 %,
    /// 0.53 % at 12.8, 25.6, 51.2 cells: order 0.43-0.65, limited by the square-root
    /// edges of both tractions). With a contact radius of a fifth of the period the
    /// distance stays at 1.6-1.8 %: the periodic images, whose tangential influence
    /// decays as 1/r, set the floor; take the period >= 10 contact radii.
    #[test]
    fn cattaneo_mindlin_stick_radius_and_traction_converge() {
        let (a, mu, ratio) = (0.1, 0.3, 0.5);
        let exact = (1.0f64 - ratio).cbrt();
        let (mut radius, mut traction) = (Vec::new(), Vec::new());
        for n in [128usize, 256, 512] {
            let p = hertz(n, a, 1.0);
            let op = CerrutiPeriodic::new(n, n, 1.0, 1.0, 1.0, 0.5).unwrap();
            let mut ps = PartialSlip::new(op, &p, mu).unwrap();
            let q = ratio * ps.friction_limit();
            let step = ps.load(q, 1e-8).unwrap();
            assert!(!step.sliding && step.force == q && step.residual <= 1e-8);
            let h2 = 1.0 / (n * n) as f64;
            let c = (step.stick_cells as f64 * h2 / PI).sqrt();
            radius.push(((c / a - exact) / exact).abs());
            // The closed form for the discrete total force (P sums the sampled pressure).
            let ratio_d = q / (mu * p.iter().sum::<f64>() * h2);
            let reference = cattaneo(n, a, 1.0, mu, ratio_d);
            let num: f64 =
                ps.q.iter()
                    .zip(&reference)
                    .map(|(x, y)| (x - y).powi(2))
                    .sum();
            let den: f64 = reference.iter().map(|y| y * y).sum();
            traction.push((num / den).sqrt());
        }
        let order = (traction[1] / traction[2]).log2();
        assert!(
            radius[1] < 0.01 && radius[2] < 0.01,
            "c/a errors {radius:?}"
        );
        assert!(
            traction[2] < 0.0065 && order >= 0.35,
            "L2 {traction:?}, order {order}"
        );
        assert!(
            traction[0] > traction[1] && traction[1] > traction[2],
            "{traction:?}"
        );
    }

    /// Mindlin-Deresiewicz: an oscillating tangential force of amplitude Q* dissipates
    /// W = 9 mu^2 P^2 (2 - nu) / (10 G a) [1 - (1 - x)^(5/3) - 5x/6 (1 + (1 - x)^(2/3))]
    /// per cycle, x = Q*/(mu P) (its small-amplitude limit is Mindlin's Q*^3 (2 - nu) /
    /// (36 G a mu P)). The dissipation summed over the 80 steps of the second cycle
    /// matches it within 1.5 % at 25.6 cells per radius and a period of 10 radii
    /// (measured -0.9 % and -0.4 % at x = 0.3 and 0.7; -0.6 % and -0.4 % at 51.2 cells;
    /// -4 % with a period of 5 radii), and equals the loop's area, the work of the force
    /// over the shift (the energy balance of a closed cycle), within 0.2 % (measured
    /// 0.06 %: the end-of-step traction of the dissipation against the trapezoid of the
    /// work).
    #[test]
    fn mindlin_deresiewicz_dissipation_per_cycle_and_energy_balance() {
        let (n, a, mu, nu, g) = (256usize, 0.1, 0.3, 0.5, 1.0);
        let p = hertz(n, a, 1.0);
        let op = CerrutiPeriodic::new(n, n, 1.0, 1.0, g, nu).unwrap();
        let mut ps = PartialSlip::new(op, &p, mu).unwrap();
        let limit = ps.friction_limit();
        for x in [0.3, 0.7] {
            let amp = x * limit;
            let steps = 40;
            let half: Vec<f64> = (0..=steps)
                .map(|k| amp * (1.0 - 2.0 * k as f64 / steps as f64))
                .collect();
            // First loading, then two full cycles; the second is measured.
            for k in 1..=steps / 2 {
                ps.load(amp * k as f64 / (steps / 2) as f64, 1e-9).unwrap();
            }
            let (mut dissipated, mut work) = (0.0, 0.0);
            for cycle in 0..2 {
                let mut last = ps.load(amp, 1e-9).unwrap();
                let path: Vec<f64> = half
                    .iter()
                    .skip(1)
                    .copied()
                    .chain(half.iter().rev().skip(1).copied())
                    .collect();
                for &f in &path {
                    let step = ps.load(f, 1e-9).unwrap();
                    if cycle == 1 {
                        dissipated += step.dissipated;
                        work += 0.5 * (step.force + last.force) * (step.shift - last.shift);
                    }
                    last = step;
                }
            }
            let pn = p.iter().sum::<f64>() / (n * n) as f64;
            let xd = amp / (mu * pn);
            let exact = 9.0 * (mu * pn).powi(2) * (2.0 - nu) / (10.0 * g * a)
                * (1.0
                    - (1.0 - xd).powf(5.0 / 3.0)
                    - 5.0 * xd / 6.0 * (1.0 + (1.0 - xd).powf(2.0 / 3.0)));
            let err = (dissipated - exact) / exact;
            let balance = (work - dissipated) / dissipated;
            assert!(
                err.abs() < 0.015,
                "x = {x}: W = {dissipated:e} against {exact:e}"
            );
            assert!(
                balance.abs() < 0.002,
                "x = {x}: work {work:e}, dissipated {dissipated:e}"
            );
        }
    }

    /// Ciavarella and Jaeger: at nu = 0 Cerruti's operator is the normal one (G = E* / 2),
    /// so q = mu [p(d) - p(d')] solves partial slip exactly on the grid, with the stick
    /// set the contact set at d' (F_N(d') = F_N(d) - Q / mu) and the shift mu (d - d'),
    /// for any surface: here a periodic one with several contact spots.
    #[test]
    fn at_nu_zero_partial_slip_is_the_normal_curve_shifted() {
        use crate::{ContactSolver, Load, PeriodicHalfSpace, SolverOptions};
        let n = 64;
        let z = crate::testing::on_unit_cell(n, |x, y| {
            let t = 2.0 * PI;
            0.01 * ((3.0 * t * x).cos() + (2.0 * t * y).cos())
                + 0.004 * (t * (5.0 * x + 3.0 * y)).cos()
        });
        let mut solver =
            ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &z, None).unwrap();
        let opts = SolverOptions::new(1e-12, 5000);
        let (f, mu) = (0.002, 0.4);
        let sol = solver.solve(Load::Force(f), &opts, None).unwrap();
        let spots = sol.pressure.iter().filter(|p| **p > 0.0).count();
        assert!(spots > 50 && spots < n * n / 2, "{spots} cells in contact");
        let op = CerrutiPeriodic::new(n, n, 1.0, 1.0, 0.5, 0.0).unwrap();
        let mut ps = PartialSlip::new(op, &sol.pressure, mu).unwrap();
        for x in [0.2, 0.5, 0.8] {
            let s = ps.load(x * mu * f, 1e-10).unwrap();
            let reduced = solver
                .solve(Load::Force((1.0 - x) * f), &opts, None)
                .unwrap();
            let mapped = mu * (sol.approach - reduced.approach);
            assert!(
                (s.shift / mapped - 1.0).abs() < 1e-6,
                "Q = {x} mu F: shift {} against {mapped}",
                s.shift
            );
            let stick_mapped = reduced.pressure.iter().filter(|p| **p > 0.0).count();
            assert_eq!(s.stick_cells, stick_mapped, "Q = {x} mu F");
        }
    }

    /// Every step's returned state obeys Coulomb's law on `K q` computed afresh by a
    /// second operator, whatever the iteration used inside (its running update of `K q`
    /// included): the force is carried, no traction exceeds `mu p`, stick cells keep
    /// `|u + s - delta| <= tolerance x max |u|`, and slip cells lie on the side of
    /// `delta` their traction allows. A loading, unloading past zero and reloading history
    /// on both half-spaces (steps that project cells and steps that do not).
    #[test]
    fn each_step_obeys_the_law_on_a_fresh_displacement() {
        fn check<C: crate::SlipOperator>(make: impl Fn() -> C, n: usize) {
            let (mu, tol) = (0.3, 1e-8);
            let p = hertz(n, 0.3, 1.0);
            let mut ps = PartialSlip::new(make(), &p, mu).unwrap();
            let mut fresh = make();
            let mut u = vec![0.0; n * n];
            for x in [0.3, 0.6, 0.2, -0.4, 0.5, 0.55] {
                let force = x * ps.friction_limit();
                let step = ps.load(force, tol).unwrap();
                let (q, s, bound) = (ps.traction(), ps.slip(), &ps.bound);
                let carried = q.iter().sum::<f64>() * fresh.cell_area();
                assert!(
                    (carried - force).abs() <= 1e-12 * ps.friction_limit(),
                    "{x}"
                );
                fresh.apply(q, &mut u);
                let scale = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let slack = tol * scale * (1.0 + 1e-9);
                for i in (0..n * n).filter(|&i| bound[i] > 0.0) {
                    let off = u[i] + s[i] - step.shift;
                    assert!(q[i].abs() <= bound[i], "x = {x}, cell {i}: |q| > mu p");
                    let ok = if q[i].abs() < bound[i] {
                        off.abs() <= slack
                    } else {
                        off * q[i].signum() <= slack
                    };
                    assert!(
                        ok,
                        "x = {x}, cell {i}: u + s - delta = {off:e}, q = {}",
                        q[i]
                    );
                }
            }
        }
        check(
            || CerrutiPeriodic::new(64, 64, 1.0, 1.0, 1.0, 0.3).unwrap(),
            64,
        );
        check(
            || super::super::CerrutiFree::new(48, 48, 1.0, 1.0, 1.0, 0.3).unwrap(),
            48,
        );
    }

    /// An operator without its preconditioner: the plain projected conjugate gradient.
    struct Plain<C>(C);

    impl<C: TangentialCompliance> TangentialCompliance for Plain<C> {
        fn grid(&self) -> (usize, usize, f64, f64) {
            self.0.grid()
        }
        fn is_periodic(&self) -> bool {
            self.0.is_periodic()
        }
        fn apply(&mut self, q: &[f64], u: &mut [f64]) {
            self.0.apply(q, u)
        }
    }

    /// The preconditioner changes the path, not the answer: along a loading, unloading
    /// and reloading history on both half-spaces, the preconditioned and the plain
    /// iterations reach the same tractions and shifts (within 1e-6 of the largest
    /// traction and shift, at tolerance 1e-10), the same stick sets, and the
    /// preconditioned one in at most half the iterations (measured: 78 against 297 on
    /// the periodic 128^2 grid, 72 against 219 on the free 96^2 one).
    #[test]
    fn the_preconditioner_changes_the_path_not_the_answer() {
        fn check<C: TangentialCompliance>(make: impl Fn() -> C, n: usize, what: &str) {
            let (mu, tol) = (0.3, 1e-10);
            let p = hertz(n, 0.3, 1.0);
            let mut pre = PartialSlip::new_generic(make(), &p, mu).unwrap();
            let mut plain = PartialSlip::new_generic(Plain(make()), &p, mu).unwrap();
            let (mut it_pre, mut it_plain) = (0, 0);
            for x in [0.3, 0.6, 0.2, -0.4, 0.5] {
                let force = x * pre.friction_limit();
                let (a, b) = (
                    pre.load_generic(force, tol).unwrap(),
                    plain.load_generic(force, tol).unwrap(),
                );
                it_pre += a.iterations;
                it_plain += b.iterations;
                let peak = pre.traction().iter().fold(0.0f64, |m, q| m.max(q.abs()));
                let dq = pre
                    .traction()
                    .iter()
                    .zip(plain.traction())
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                assert!(dq <= 1e-6 * peak, "{what}, x = {x}: tractions {dq:e} apart");
                assert!(
                    (a.shift - b.shift).abs() <= 1e-6 * a.shift.abs(),
                    "{what}, x = {x}: shifts {} and {}",
                    a.shift,
                    b.shift
                );
                assert_eq!(a.stick_cells, b.stick_cells, "{what}, x = {x}");
            }
            eprintln!("{what}: {it_pre} iterations preconditioned, {it_plain} plain");
            assert!(
                2 * it_pre <= it_plain,
                "{what}: {it_pre} iterations preconditioned against {it_plain} plain"
            );
        }
        check(
            || CerrutiPeriodic::new(128, 128, 1.0, 1.0, 1.0, 0.3).unwrap(),
            128,
            "periodic",
        );
        check(
            || super::super::CerrutiFree::new(96, 96, 1.0, 1.0, 1.0, 0.3).unwrap(),
            96,
            "free",
        );
    }

    /// A coarse grid (3.2 cells per contact radius) under a small oscillation: no cell
    /// slips, so the step at zero force has no traction at all as its answer. Its
    /// displacements are then of rounding size, and the residual's floor ([`ROUNDING`])
    /// lets it end; without the floor both half-spaces iterate to the limit on a
    /// residual of 0.2-0.8 relative to rounding.
    #[test]
    fn a_step_whose_answer_is_no_traction_ends() {
        fn check<C: crate::SlipOperator>(op: C, n: usize) {
            let p = hertz(n, 0.1, 1.0);
            let mut ps = PartialSlip::new(op, &p, 0.5).unwrap();
            let limit = ps.friction_limit();
            let c = ps.cycle(0.2 * limit, 20, 2, 1e-8).unwrap();
            assert_eq!(c.dissipated, 0.0, "n = {n}");
            // The loop is a line through the origin: a linear spring, no hysteresis.
            let (f, s) = c.points[10];
            assert!(f.abs() < 1e-12 * limit, "{f}");
            assert!(s.abs() < 1e-6 * c.points[0].1.abs(), "{s}");
            let zero = ps.load(0.0, 1e-8).unwrap();
            let q_max = ps.q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(zero.residual <= 1e-8 && q_max < 1e-9, "{q_max}");
        }
        check(
            CerrutiPeriodic::new(32, 32, 1.0, 1.0, 1.0, 0.5).unwrap(),
            32,
        );
        check(
            super::super::CerrutiFree::new(24, 24, 1.0, 1.0, 1.0, 0.5).unwrap(),
            24,
        );
    }

    /// A set interrupt stops a step after its first iteration and leaves the slip as it
    /// was before the step; cleared, the same step then ends where an uninterrupted
    /// history does (to the tolerance: it starts from the unfinished traction).
    #[test]
    fn an_interrupted_step_keeps_the_history() {
        let p = hertz(64, 0.2, 1.0);
        let op = || CerrutiPeriodic::new(64, 64, 1.0, 1.0, 1.0, 0.5).unwrap();
        let (mut ps, mut reference) = (
            PartialSlip::new(op(), &p, 0.3).unwrap(),
            PartialSlip::new(op(), &p, 0.3).unwrap(),
        );
        let flag = Interrupt::default();
        ps.interrupt_on(flag.clone());
        let limit = ps.friction_limit();
        for f in [0.6, -0.3] {
            ps.load(f * limit, 1e-10).unwrap();
            reference.load(f * limit, 1e-10).unwrap();
        }
        let before = ps.slip.clone();
        flag.set();
        let e = ps.load(0.5 * limit, 1e-10).err().unwrap();
        assert!(
            matches!(e, BemError::Interrupted { iterations: 0, .. }),
            "{e}"
        );
        assert_eq!(ps.slip, before);
        flag.clear();
        let (a, b) = (
            ps.load(0.5 * limit, 1e-10).unwrap(),
            reference.load(0.5 * limit, 1e-10).unwrap(),
        );
        assert_eq!(a.stick_cells, b.stick_cells);
        assert!(
            (a.shift - b.shift).abs() < 1e-8 * b.shift.abs(),
            "{a:?} {b:?}"
        );
        let q_max = p.iter().fold(0.0f64, |m, x| m.max(0.3 * x));
        let dq =
            ps.q.iter()
                .zip(&reference.q)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(dq < 1e-7 * q_max, "{dq}");
    }

    #[test]
    fn a_cycle_refuses_what_it_cannot_run() {
        let p = hertz(32, 0.2, 1.0);
        let op = CerrutiPeriodic::new(32, 32, 1.0, 1.0, 1.0, 0.5).unwrap();
        let mut ps = PartialSlip::new(op, &p, 0.5).unwrap();
        let limit = ps.friction_limit();
        for (amp, steps, cycles) in [
            (limit, 4, 1),
            (-0.1 * limit, 4, 1),
            (f64::NAN, 4, 1),
            (0.5 * limit, 0, 1),
            (0.5 * limit, 4, 0),
            (0.5 * limit, 1_000_000_000, 1),
            (0.5 * limit, 1, usize::MAX),
            (0.5 * limit, 1000, 500),
        ] {
            assert!(matches!(
                ps.cycle(amp, steps, cycles, 1e-8),
                Err(BemError::InvalidInput(_))
            ));
        }
        let c = ps.cycle(0.5 * limit, 8, 2, 1e-8).unwrap();
        assert!(c.dissipated > 0.0 && (c.loop_area / c.dissipated - 1.0).abs() < 0.05);
        // The loop's points: the amplitude, down to its negative, back up; their
        // trapezoids are the loop's area.
        assert_eq!(c.points.len(), 17);
        let ends = [c.points[0].0, c.points[8].0, c.points[16].0];
        assert_eq!(ends, [0.5 * limit, -0.5 * limit, 0.5 * limit]);
        let area: f64 = c
            .points
            .windows(2)
            .map(|w| 0.5 * (w[0].0 + w[1].0) * (w[1].1 - w[0].1))
            .sum();
        assert_eq!(area, c.loop_area);
    }
}
