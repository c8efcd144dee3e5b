//! Adhesive normal contact laws in the JKR limit (zero-range adhesion of work w): the
//! surfaces adhere only where they have touched, and a contact holds tension until its
//! edge detaches. The force of a step depends on the history (which springs or cells are
//! attached), so a sphere that strikes and rebounds loses the adhesive hysteresis, and
//! below a critical speed it is captured.
//!
//! - MRD ([`AdhesiveSprings`]): a body of revolution by the rule of Hess on the whole
//!   line (both halves), each spring attached once touched and detached by the review's
//!   Eq. 33 (`mrd::adhesive_row`, the contact radius the outer edge of the attached
//!   springs; a jump-out cascades within a step).
//! - 3D ([`AdhesiveBem3d`]): `bem3d::adhesion`'s solve (Pohrt & Popov's one-cell
//!   detachment criterion) under the step's approach, from the accepted state.
//!
//! Forces are compressive positive, tensile negative (the convention of [`crate::law`]
//! extended to tension). A trial steps a copy of the row (MRD) or a snapshot taken
//! before it (3D); a rollback returns to it.

use crate::held::Held;
use crate::law::{normal_only, ContactLaw, Forces, Motion};
use crate::{bad, Result};
use bem3d::adhesion::AdhesiveContact;
use bem3d::{HalfSpaceOperator, Load};
use mrd::adhesive_row::{AdhesiveRow, EdgeRadius};
use std::f64::consts::PI;

/// The refusal of `approach_at` by both adhesive laws: the approach that carries a force
/// depends on which springs or cells are attached.
fn history_dependent(force: f64) -> Result<f64> {
    bad(format!(
        "approach_at(force = {force}): an adhesive contact's approach depends on its history; step it instead"
    ))
}

/// MRD's adhesive springs for a body of revolution (module docs).
#[derive(Debug, Clone)]
pub struct AdhesiveSprings {
    row: AdhesiveRow,
    trial: Option<(AdhesiveRow, Forces)>,
    committed: Forces,
    label: String,
}

impl AdhesiveSprings {
    /// `springs` springs on each half of the line `[-half_length, half_length]`, gaps by
    /// the rule of Hess, modulus `e_star` and work of adhesion `work` > 0; apart.
    pub fn body(
        profile: &mrd::profile::Profile,
        e_star: f64,
        work: f64,
        springs: usize,
        half_length: f64,
    ) -> Result<Self> {
        let (_, dx, gaps) = mrd::foundation::half_line(profile, springs, half_length)?;
        // Both halves, the axis between the two middle springs.
        let n = gaps.len();
        let x: Vec<f64> = (0..2 * n)
            .map(|i| (i as f64 + 0.5 - n as f64) * dx)
            .collect();
        let heights: Vec<f64> = (0..2 * n)
            .map(|i| -gaps[if i < n { n - 1 - i } else { i - n }])
            .collect();
        Ok(Self {
            row: AdhesiveRow::new(&x, &heights, dx, e_star, work, EdgeRadius::Outer)?,
            trial: None,
            committed: Forces::default(),
            label: format!("MRD adhesive (Eq. 33), {springs} springs on the half line"),
        })
    }
}

impl ContactLaw for AdhesiveSprings {
    fn trial(&mut self, motion: Motion) -> Result<Forces> {
        normal_only(motion, "adhesive MRD")?;
        let mut row = self.row.clone();
        let s = row.step(motion.normal)?;
        let forces = Forces::frictionless(s.force, PI * s.radius * s.radius, 0);
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

    /// Not defined: an adhesive contact's force is not a function of the approach alone
    /// (it depends on which springs are attached), and a force may be carried at two
    /// approaches.
    fn approach_at(&mut self, force: f64) -> Result<f64> {
        history_dependent(force)
    }

    fn describe(&self) -> String {
        self.label.clone()
    }
}

/// The 3D adhesive contact as a contact law (module docs): each trial is one step of
/// the adhesive solve to the step's approach (from first contact of the highest cell).
pub struct AdhesiveBem3d<O: HalfSpaceOperator> {
    contact: Held<AdhesiveContact<O>>,
    tolerance: f64,
    label: String,
}

impl<O: HalfSpaceOperator> AdhesiveBem3d<O> {
    /// `heights` (`ny x nx`) on `op` with an optional `mask`, work of adhesion `work` > 0;
    /// each step to `tolerance` (relative, the adhesive solve's).
    pub fn new(
        op: O,
        heights: &[f64],
        mask: Option<&[bool]>,
        work: f64,
        tolerance: f64,
    ) -> Result<Self> {
        if !(tolerance.is_finite() && tolerance > 0.0 && tolerance <= 1e-2) {
            return bad(format!("tolerance = {tolerance} must lie in (0, 0.01]"));
        }
        let label = format!("3D adhesive (JKR limit), {} x {} cells", op.nx(), op.ny());
        Ok(Self {
            contact: Held::new(
                AdhesiveContact::new(op, heights, mask, work)?,
                Forces::default(),
            ),
            tolerance,
            label,
        })
    }
}

impl<O: HalfSpaceOperator> ContactLaw for AdhesiveBem3d<O> {
    fn trial(&mut self, motion: Motion) -> Result<Forces> {
        normal_only(motion, "3D adhesive")?;
        let tolerance = self.tolerance;
        self.contact.trial(|c| {
            let step = c.step(Load::Approach(motion.normal), tolerance)?;
            Ok(Forces::frictionless(
                step.force,
                step.contact_area,
                step.iterations,
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

    /// Not defined (see [`AdhesiveSprings`]'s).
    fn approach_at(&mut self, force: f64) -> Result<f64> {
        history_dependent(force)
    }

    fn describe(&self) -> String {
        self.label.clone()
    }
}
