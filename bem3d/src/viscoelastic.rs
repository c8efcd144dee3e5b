//! Transient frictionless normal contact of a rigid rough surface on a linear
//! viscoelastic half-space (Section 8 of the MRD review in 3D), under a prescribed
//! history of force or approach.
//!
//! Material: the contact modulus relaxes as a Prony series (a generalised Maxwell
//! model) `E*(t) = E_inf + sum_k E_k exp(-t / tau_k)`; for an incompressible medium
//! E* = 4 G. With the Poisson ratio constant in time the half-space's spatial response is
//! the elastic one at every instant (correspondence principle): with `K0` the compliance
//! of unit modulus, the pressure p and the surface displacement u obey
//! `K0 p(t) = v(t)`, `v(x, t) = Int_{-inf}^t E*(t - t') du(x, t')/dt' dt'`, a hereditary
//! integral taken cell by cell.
//!
//! Time integration, exact for u piecewise linear in time (as `mrd::viscoelastic`):
//! with `h_k(t) = Int exp(-(t - t')/tau_k) du/dt' dt'` per cell and term, a step dt from
//! t_n to t_n+1 gives `h_k <- a_k h_k + b_k (u_n+1 - u_n)` with `a_k = exp(-dt/tau_k)`,
//! `b_k = (tau_k / dt)(1 - a_k)`, hence
//! `v_n+1 = E_eff u_n+1 + H_n`, `E_eff = E_inf + sum_k E_k b_k`,
//! `H_n = sum_k E_k (a_k h_k - b_k u_n)`.
//! So `u_n+1 = (K0 p_n+1 - H_n) / E_eff`: each step is an elastic contact problem of
//! modulus E_eff on the heights raised by the history, `h + H_n / E_eff`, solved by the
//! elastic solver (warm-started from the previous step). No stability limit on dt;
//! accuracy: exact under approach control with a fixed contact set, first order in dt
//! after a load jump (the step treats it as a ramp over dt), second order for smooth
//! histories (tests in `bem3d/tests/suite/viscoelastic.rs`).
//!
//! Approach: the rigid body's position D from the first contact of the undeformed
//! surface (the approach of the elastic solver at t = 0). On the periodic half-space the
//! mean displacement is zero at all times (its k = 0 mode is the load's, as in the
//! elastic solver), so D is measured in the same convention there.

use crate::error::{BemError, Result};
use crate::operator::GridOperator;
use crate::solver::{ContactSolver, Load, Solution, SolverOptions};
use rayon::prelude::*;

/// A contact modulus relaxing as `E_inf + sum_k E_k exp(-t / tau_k)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Relaxation {
    /// Relaxed (long-time) modulus E_inf >= 0.
    pub relaxed: f64,
    /// (E_k > 0, tau_k > 0) pairs.
    pub terms: Vec<(f64, f64)>,
}

impl Relaxation {
    /// Checks the moduli and times: finite, E_inf >= 0, E_k > 0, tau_k > 0, and a glassy
    /// modulus E*(0) > 0.
    pub fn new(relaxed: f64, terms: Vec<(f64, f64)>) -> Result<Self> {
        if !(relaxed.is_finite() && relaxed >= 0.0) {
            return Err(BemError::InvalidInput(format!(
                "relaxed modulus {relaxed} must be finite and >= 0"
            )));
        }
        for &(e, tau) in &terms {
            if !(e.is_finite() && e > 0.0 && tau.is_finite() && tau > 0.0) {
                return Err(BemError::InvalidInput(format!(
                    "Prony term (modulus {e}, relaxation time {tau}): both must be finite and > 0"
                )));
            }
        }
        let r = Self { relaxed, terms };
        if r.glassy() <= 0.0 {
            return Err(BemError::InvalidInput(
                "the modulus vanishes: give a relaxed modulus or a Prony term".into(),
            ));
        }
        Ok(r)
    }

    /// E*(t).
    pub fn at(&self, t: f64) -> f64 {
        self.relaxed
            + self
                .terms
                .iter()
                .map(|&(e, tau)| e * (-t / tau).exp())
                .sum::<f64>()
    }

    /// E*(0).
    pub fn glassy(&self) -> f64 {
        self.relaxed + self.terms.iter().map(|t| t.0).sum::<f64>()
    }

    /// The effective modulus of a step with the factors `(a_k, b_k)`:
    /// `E_inf + sum_k E_k b_k` (module docs).
    pub(crate) fn effective(&self, factors: &[(f64, f64)]) -> f64 {
        self.relaxed
            + self
                .terms
                .iter()
                .zip(factors)
                .map(|(&(e, _), &(_, b))| e * b)
                .sum::<f64>()
    }

    /// (a_k, b_k) of a step dt (module docs).
    pub(crate) fn step_factors(&self, dt: f64) -> Vec<(f64, f64)> {
        self.terms
            .iter()
            .map(|&(_, tau)| {
                let x = -dt / tau;
                (x.exp(), -x.exp_m1() * tau / dt)
            })
            .collect()
    }
}

/// The state after a step.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    pub time: f64,
    /// Rigid-body position from the first contact of the undeformed surface.
    pub approach: f64,
    pub force: f64,
    pub contact_cells: usize,
    pub contact_area: f64,
    /// Cell pressures (`ny x nx`).
    pub pressure: Vec<f64>,
    /// The step's elastic solve (its pressures at the reference modulus; its
    /// `iterations`, `residual` and `certificate` are the step's); None when the
    /// approach leaves the surface out of contact and no solve ran.
    pub solve: Option<Solution>,
    /// E_eff of the step (module docs).
    pub effective_modulus: f64,
}

/// The state of a [`TransientContact`] between steps ([`TransientContact::snapshot`]).
#[derive(Debug, Clone)]
pub struct Snapshot {
    u: Vec<f64>,
    history: Vec<Vec<f64>>,
    time: f64,
    last: Option<Solution>,
}

/// A rough rigid surface on a viscoelastic half-space, stepped in time.
pub struct TransientContact<K: GridOperator> {
    solver: ContactSolver<K>,
    modulus: Relaxation,
    heights: Vec<f64>,
    /// The largest height on the domain (first contact of the undeformed surface).
    top: f64,
    mask: Vec<bool>,
    /// Surface displacement u and the hereditary integrals h_k (term-major).
    u: Vec<f64>,
    history: Vec<Vec<f64>>,
    time: f64,
    last: Option<Solution>,
}

impl<K: GridOperator> TransientContact<K> {
    /// `op` gives the grid and the reference modulus its solves run at (any value: the
    /// pressures are rescaled); `heights` and `mask` as for [`ContactSolver::new`]. The
    /// medium starts undeformed at t = 0.
    pub fn new(
        op: K,
        heights: &[f64],
        mask: Option<Vec<bool>>,
        modulus: Relaxation,
    ) -> Result<Self> {
        let n = op.cells();
        let mask = mask.unwrap_or_else(|| vec![true; n]);
        let solver = ContactSolver::new_generic(op, heights, Some(mask.clone()))?;
        let top = heights
            .iter()
            .zip(&mask)
            .filter(|p| *p.1)
            .map(|p| *p.0)
            .fold(f64::NEG_INFINITY, f64::max);
        Ok(Self {
            solver,
            history: vec![vec![0.0; n]; modulus.terms.len()],
            modulus,
            heights: heights.to_vec(),
            top,
            mask,
            u: vec![0.0; n],
            time: 0.0,
            last: None,
        })
    }

    pub fn time(&self) -> f64 {
        self.time
    }

    /// The surface displacement u (`ny x nx`, into the half-space).
    pub fn displacement(&self) -> &[f64] {
        &self.u
    }

    /// The state a step changes (time, displacement, hereditary integrals and the last
    /// solve that warm-starts the next), for [`Self::restore`]: a time integrator tries
    /// a step and takes it back when it rejects it.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            u: self.u.clone(),
            history: self.history.clone(),
            time: self.time,
            last: self.last.clone(),
        }
    }

    /// Returns to a state taken by [`Self::snapshot`] of this contact: the next step is
    /// the one that would have followed it, bit for bit.
    pub fn restore(&mut self, s: Snapshot) -> Result<()> {
        if s.u.len() != self.u.len() || s.history.len() != self.history.len() {
            return Err(BemError::InvalidInput(
                "restore: the snapshot is of another contact (its grid or modulus differs)".into(),
            ));
        }
        self.u = s.u;
        self.history = s.history;
        self.time = s.time;
        self.last = s.last;
        Ok(())
    }

    /// [`Self::step`] for any operator (its compiled entry, in `compiled.rs`, calls this).
    pub(crate) fn step_generic(
        &mut self,
        dt: f64,
        load: Load,
        opts: &SolverOptions,
    ) -> Result<Step> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(BemError::InvalidInput(format!(
                "time step {dt} must be finite and > 0"
            )));
        }
        // The bound on the load as given (the solve below sees it scaled by E* / E_eff).
        let op = self.solver.operator();
        crate::solver::check_load_magnitude(load, op.e_star(), (op.lx(), op.ly()))?;
        let factors = self.modulus.step_factors(dt);
        let e_eff = self.modulus.effective(&factors);
        // H_n / E_eff: the history's displacement, raising the heights it acts on.
        let n = self.u.len();
        let mut lift = vec![0.0; n];
        for (k, &(e, _)) in self.modulus.terms.iter().enumerate() {
            let (a, b) = factors[k];
            lift.par_iter_mut()
                .zip(&self.history[k])
                .zip(&self.u)
                .for_each(|((l, h), u)| *l += e * (a * h - b * u) / e_eff);
        }
        let raised: Vec<f64> = self.heights.iter().zip(&lift).map(|(h, l)| h + l).collect();
        let top = raised
            .iter()
            .zip(&self.mask)
            .filter(|p| *p.1)
            .map(|p| *p.0)
            .fold(f64::NEG_INFINITY, f64::max);
        // Solves at the reference modulus E_ref: pressures p_ref = p E_ref / E_eff.
        let scale = self.solver.operator().e_star() / e_eff;
        let solver_load = match load {
            Load::Force(f) => Load::Force(f * scale),
            Load::MeanPressure(p) => Load::MeanPressure(p * scale),
            // Approach from the first contact of the raised heights.
            Load::Approach(d) => Load::Approach(d + top - self.top),
        };
        let sol = match solver_load {
            Load::Approach(d) if d <= 0.0 => None,
            _ => {
                self.solver.set_heights_generic(&raised)?;
                let warm = self.last.as_ref();
                Some(self.solver.solve_generic(solver_load, opts, warm)?)
            }
        };
        // u = K_ref p_ref - lift, K_ref p_ref from the solver's operator.
        let mut u = vec![0.0; n];
        let (pressure, approach) = match &sol {
            Some(s) => {
                self.solver.displacement(&s.pressure, &mut u);
                let p: Vec<f64> = s.pressure.iter().map(|v| v / scale).collect();
                (p, s.approach - top + self.top)
            }
            None => (
                vec![0.0; n],
                match load {
                    Load::Approach(d) => d,
                    _ => unreachable!("only an approach gives no solve"),
                },
            ),
        };
        u.par_iter_mut().zip(&lift).for_each(|(u, l)| *u -= l);
        for (k, &(a, b)) in factors.iter().enumerate() {
            self.history[k]
                .par_iter_mut()
                .zip(&u)
                .zip(&self.u)
                .for_each(|((h, new), old)| *h = a * *h + b * (new - old));
        }
        self.u = u;
        self.time += dt;
        let area = self.solver.operator().lx() * self.solver.operator().ly() / n as f64;
        let contact_cells = pressure.iter().filter(|&&p| p > 0.0).count();
        self.last = sol.clone();
        Ok(Step {
            time: self.time,
            approach,
            force: pressure.iter().sum::<f64>() * area,
            contact_cells,
            contact_area: contact_cells as f64 * area,
            pressure,
            solve: sol,
            effective_modulus: e_eff,
        })
    }
}
