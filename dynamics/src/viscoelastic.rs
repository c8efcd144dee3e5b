//! Viscoelastic normal contact laws: the contact modulus relaxes as
//! `E*(t) = E_inf + sum_k E_k exp(-t / tau_k)` (Section 8), and the force of a step
//! depends on the whole history of the motion, not on the approach alone.
//!
//! - MRD ([`ViscoelasticSprings`]): a body of revolution by the rule of Hess on a
//!   mirrored half line, each spring of width dx carrying the hereditary integral of
//!   its elongation (Eq. 63), separating at zero force and recovering freely while apart
//!   (`mrd::viscoelastic::SpringRow`).
//! - 3D ([`ViscoelasticBem3d`]): the transient boundary-element solve of `bem3d` on the
//!   same modulus (`bem3d::viscoelastic::TransientContact`), one step per trial.
//!
//! Both step the hereditary integrals exactly for a motion linear in time over the step,
//! so the integrator's time step is the only discretisation in time. A trial steps a copy
//! of the state (MRD) or a snapshot taken before it (3D); a rollback returns to it.

use crate::held::Held;
use crate::law::{normal_only, ContactLaw, Forces, Motion};
use crate::{bad, Result};
use bem3d::viscoelastic::{Relaxation, TransientContact};
use bem3d::{HalfSpaceOperator, Load, SolverOptions};
use mrd::rheology::Prony;
use mrd::viscoelastic::{RowLoad, SpringRow};
use std::f64::consts::PI;

/// MRD's viscoelastic springs for a body of revolution (module docs).
#[derive(Debug, Clone)]
pub struct ViscoelasticSprings {
    row: SpringRow,
    dx: f64,
    /// The shortest relaxation time, at most 1 (the scale of [`ContactLaw::approach_at`]'s
    /// step).
    tau_min: f64,
    trial: Option<(SpringRow, Forces)>,
    committed: Forces,
    label: String,
}

impl ViscoelasticSprings {
    /// `springs` springs on the half line `[0, half_length]` (mirrored), gaps by the rule
    /// of Hess, on the modulus `modulus`; undeformed at t = 0.
    pub fn body(
        profile: &mrd::profile::Profile,
        modulus: &Prony,
        springs: usize,
        half_length: f64,
    ) -> Result<Self> {
        if modulus.relaxed + modulus.terms.iter().map(|t| t.0).sum::<f64>() <= 0.0 {
            return bad("modulus: the glassy modulus E_inf + sum E_k must be > 0");
        }
        let (_, dx, gaps) = mrd::foundation::half_line(profile, springs, half_length)?;
        let tau_min = modulus.terms.iter().map(|t| t.1).fold(1.0, f64::min);
        Ok(Self {
            row: SpringRow::new(&gaps, dx, modulus)?,
            dx,
            tau_min,
            trial: None,
            committed: Forces::default(),
            label: format!("MRD viscoelastic, {springs} springs on the half line"),
        })
    }
}

impl ContactLaw for ViscoelasticSprings {
    fn trial(&mut self, motion: Motion) -> Result<Forces> {
        normal_only(motion, "viscoelastic MRD")?;
        let mut row = self.row.clone();
        let s = row.step(motion.dt, RowLoad::Depth(motion.normal))?;
        // The mirrored half line: each spring stands for two; its contact is the disc of
        // radius (springs in contact) x dx, the springs touching from the centre out.
        let a = s.contacts as f64 * self.dx;
        let forces = Forces::frictionless(2.0 * s.force, PI * a * a, 0);
        self.trial = Some((row, forces));
        Ok(forces)
    }

    fn commit(&mut self) -> Result<()> {
        let Some((row, forces)) = self.trial.take() else {
            return bad("commit: no trial step to accept (call trial first)");
        };
        self.row = row;
        self.committed = forces;
        Ok(())
    }

    fn rollback(&mut self) {
        self.trial = None;
    }

    fn committed(&self) -> Forces {
        self.committed
    }

    /// The approach that carries `force` in an instant (a step of a millionth of the
    /// shortest relaxation time: the glassy response on top of the accepted history).
    fn approach_at(&mut self, force: f64) -> Result<f64> {
        if !(force.is_finite() && force >= 0.0) {
            return bad(format!("force = {force} must be finite and >= 0"));
        }
        let dt = 1e-6 * self.tau_min;
        Ok(self
            .row
            .clone()
            .step(dt, RowLoad::Force(force / 2.0))?
            .depth)
    }

    fn describe(&self) -> String {
        self.label.clone()
    }
}

/// The 3D transient viscoelastic contact as a contact law (module docs): each trial is
/// one step of the transient solve under the step's approach (from first contact of the
/// highest cell), linear in time over the step.
pub struct ViscoelasticBem3d<O: HalfSpaceOperator> {
    contact: Held<TransientContact<O>>,
    options: SolverOptions,
    /// The shortest relaxation time, at most 1 (the scale of [`ContactLaw::approach_at`]'s
    /// step).
    tau_min: f64,
    label: String,
}

impl<O: HalfSpaceOperator> ViscoelasticBem3d<O> {
    /// `heights` (`ny x nx`) on `op` (any reference modulus: the transient solve rescales)
    /// with an optional `mask`, on the relaxation `modulus`; each solve to `tolerance` in
    /// at most `max_iterations`.
    pub fn new(
        op: O,
        heights: &[f64],
        mask: Option<Vec<bool>>,
        modulus: Relaxation,
        tolerance: f64,
        max_iterations: usize,
    ) -> Result<Self> {
        let label = format!("3D viscoelastic, {} x {} cells", op.nx(), op.ny());
        let tau_min = modulus.terms.iter().map(|t| t.1).fold(1.0, f64::min);
        let options = SolverOptions::new(tolerance, max_iterations);
        options.validate()?;
        Ok(Self {
            contact: Held::new(
                TransientContact::new(op, heights, mask, modulus)?,
                Forces::default(),
            ),
            options,
            tau_min,
            label,
        })
    }
}

impl<O: HalfSpaceOperator> ContactLaw for ViscoelasticBem3d<O> {
    fn trial(&mut self, motion: Motion) -> Result<Forces> {
        normal_only(motion, "3D viscoelastic")?;
        let options = &self.options;
        self.contact.trial(|c| {
            let step = c.step(motion.dt, Load::Approach(motion.normal), options)?;
            let iterations = step.solve.as_ref().map_or(0, |s| s.iterations);
            Ok(Forces::frictionless(
                step.force,
                step.contact_area,
                iterations,
            ))
        })
    }

    fn commit(&mut self) -> Result<()> {
        self.contact.commit()
    }

    fn rollback(&mut self) {
        self.contact.rollback()
    }

    fn committed(&self) -> Forces {
        self.contact.committed()
    }

    /// The approach that carries `force` in an instant (a step of a millionth of the
    /// shortest relaxation time from the accepted state, then taken back).
    fn approach_at(&mut self, force: f64) -> Result<f64> {
        if !(force.is_finite() && force >= 0.0) {
            return bad(format!("force = {force} must be finite and >= 0"));
        }
        if force == 0.0 {
            return bad("approach_at(force = 0): any approach short of contact carries it");
        }
        let (dt, options) = (1e-6 * self.tau_min, &self.options);
        self.contact
            .query(|c| Ok(c.step(dt, Load::Force(force), options)?.approach))
    }

    fn describe(&self) -> String {
        self.label.clone()
    }
}
