//! The contact law a time integrator calls ([`ContactLaw`]) and its two families: MRD's
//! springs ([`Springs`]) and the 3D boundary-element solve ([`Bem3d`]).
//!
//! **Conventions.** The normal coordinate is the approach `d` from first contact
//! (positive pressing; below 0 the bodies are apart), the tangential one the relative
//! displacement `u` of the body along x. Forces are those the contact exerts on the
//! body against the motion: the normal force `F >= 0` (compressive; no adhesion in
//! these laws, the adhesive ones of [`crate::adhesive`] pull with `F < 0`), the
//! tangential force `Q` resisting `u`. A step is tried at a motion
//! ([`ContactLaw::trial`]), then accepted ([`ContactLaw::commit`]) or discarded
//! ([`ContactLaw::rollback`]); a trial always starts from the last accepted state, so
//! an integrator can try several motions for one step.

use crate::{bad, Result};
use bem3d::{ContactSolver, Load, Solution, SolverOperator, SolverOptions};
use mrd::foundation::Foundation;

/// The motion of one step: its end's approach and tangential displacement, and its
/// duration (for laws with memory in time; the elastic laws here do not use it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// Approach from first contact [length].
    pub normal: f64,
    /// Tangential displacement [length].
    pub tangential: f64,
    /// Time step [time], > 0.
    pub dt: f64,
}

/// The forces of a state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Forces {
    /// Normal force [force], >= 0.
    pub normal: f64,
    /// Tangential force [force], resisting the displacement.
    pub tangential: f64,
    /// Real contact area [length^2] (MRD: its own measure, module docs of [`Springs`]).
    pub contact_area: f64,
    /// Normal tangent stiffness dF/dd with the contact set held [force / length]; NaN
    /// where the law does not compute it.
    pub stiffness: f64,
    /// Energy dissipated by slip in the step [force x length].
    pub dissipated: f64,
    /// Work of the law's solver in the step (3D: conjugate-gradient iterations; MRD: 0).
    pub iterations: usize,
}

impl Forces {
    /// The forces of a frictionless state: the normal force, the contact area and the
    /// solver's work; no tangential force, no slip, the stiffness not computed (NaN).
    pub fn frictionless(normal: f64, contact_area: f64, iterations: usize) -> Self {
        Self {
            normal,
            tangential: 0.0,
            contact_area,
            stiffness: f64::NAN,
            dissipated: 0.0,
            iterations,
        }
    }
}

/// A contact law with history, called once or more per time step (module docs).
pub trait ContactLaw: Send {
    /// The forces at `motion` from the last accepted state; the trial is held until
    /// [`Self::commit`] or [`Self::rollback`] (a new trial replaces it).
    fn trial(&mut self, motion: Motion) -> Result<Forces>;
    /// Accepts the last trial as the new state; an error if none is held.
    fn commit(&mut self) -> Result<()>;
    /// Discards the last trial: the state is the last accepted one.
    fn rollback(&mut self);
    /// The forces of the last accepted state.
    fn committed(&self) -> Forces;
    /// The approach at which the contact carries the normal force `force` with the
    /// history as accepted (a query: the state does not change).
    fn approach_at(&mut self, force: f64) -> Result<f64>;
    /// A one-line description (the method and its resolution).
    fn describe(&self) -> String;
}

pub(crate) fn check_motion(m: Motion) -> Result<()> {
    if !(m.normal.is_finite() && m.tangential.is_finite()) {
        return bad(format!(
            "motion: normal = {} and tangential = {} must be finite",
            m.normal, m.tangential
        ));
    }
    if !(m.dt.is_finite() && m.dt > 0.0) {
        return bad(format!("time step dt = {} must be finite and > 0", m.dt));
    }
    Ok(())
}

/// The normal motion of a trial of a frictionless law (`who` names it): a tangential
/// motion is refused, not ignored.
pub(crate) fn normal_only(motion: Motion, who: &str) -> Result<()> {
    check_motion(motion)?;
    if motion.tangential != 0.0 {
        return bad(format!(
            "tangential = {}: the {who} law is frictionless (normal motion only)",
            motion.tangential
        ));
    }
    Ok(())
}

/// Coulomb friction on tangential springs: `G* dx` per spring, friction coefficient mu.
#[derive(Debug, Clone)]
struct Friction {
    g_star: f64,
    mu: f64,
    /// Each spring's slip point (its tangential spring's anchor), by gap order.
    slip: Vec<f64>,
    /// The trial's slip points.
    slip_trial: Vec<f64>,
    /// Springs in contact in the accepted state.
    contacts: usize,
    contacts_trial: usize,
}

/// MRD's independent springs (module docs of the crate): a body of revolution by the
/// rule of Hess on a mirrored half line, or a rough line; optionally tangential springs
/// with Coulomb slip.
///
/// Contact area: a body of revolution's is `pi a^2` with `a` the contact's half length
/// (exact by MRD); a rough line's is the contact length's fraction of the line times
/// the nominal area (MRD's measure of Section 11: right at small loads only).
#[derive(Debug, Clone)]
pub struct Springs {
    foundation: Foundation,
    /// Gaps in increasing order (the order of `foundation`'s springs).
    gaps: Vec<f64>,
    dx: f64,
    e_star: f64,
    /// Springs one entry stands for: 2 on a mirrored half line, 1 on a rough line.
    weight: f64,
    area: Area,
    friction: Option<Friction>,
    committed: Forces,
    trial: Option<Forces>,
    label: String,
}

#[derive(Debug, Clone, Copy)]
enum Area {
    /// pi a^2, a = contacts x dx (a half line).
    Disc,
    /// The nominal area times the contact length over the line's length.
    Fraction { nominal: f64, length: f64 },
}

impl Springs {
    /// A body of revolution: `springs` springs on the half line `[0, half_length]`
    /// (mirrored), gaps by the rule of Hess.
    pub fn body(
        profile: &mrd::profile::Profile,
        e_star: f64,
        springs: usize,
        half_length: f64,
    ) -> Result<Self> {
        let (_, dx, gaps) = mrd::foundation::half_line(profile, springs, half_length)?;
        Self::from_gaps(
            gaps,
            dx,
            e_star,
            2.0,
            Area::Disc,
            format!("MRD, {springs} springs on the half line"),
        )
    }

    /// A rough line of heights `heights` (peaks up) over `length`, its contact area
    /// measured as a fraction of `nominal_area`.
    pub fn rough_line(
        heights: &[f64],
        length: f64,
        e_star: f64,
        nominal_area: f64,
    ) -> Result<Self> {
        if !(length.is_finite() && length > 0.0 && nominal_area.is_finite() && nominal_area > 0.0) {
            return bad(format!(
                "length = {length} and nominal_area = {nominal_area} must be finite and > 0"
            ));
        }
        if heights.len() < 2 || heights.iter().any(|h| !h.is_finite()) {
            return bad("heights: a rough line needs at least 2 finite heights");
        }
        let top = heights.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let gaps: Vec<f64> = heights.iter().map(|h| top - h).collect();
        let dx = length / heights.len() as f64;
        Self::from_gaps(
            gaps,
            dx,
            e_star,
            1.0,
            Area::Fraction {
                nominal: nominal_area,
                length,
            },
            format!("MRD rough line, {} springs", heights.len()),
        )
    }

    fn from_gaps(
        mut gaps: Vec<f64>,
        dx: f64,
        e_star: f64,
        weight: f64,
        area: Area,
        label: String,
    ) -> Result<Self> {
        if !(e_star.is_finite() && e_star > 0.0) {
            return bad(format!("e_star = {e_star} must be finite and > 0"));
        }
        gaps.sort_unstable_by(f64::total_cmp);
        Ok(Self {
            foundation: Foundation::new(&gaps, dx, weight * e_star)?,
            gaps,
            dx,
            e_star,
            weight,
            area,
            friction: None,
            committed: Forces::default(),
            trial: None,
            label,
        })
    }

    /// The same springs with tangential springs `G* dx` and Coulomb's friction
    /// coefficient `mu` (Sections 6-7: exact for bodies of revolution).
    pub fn with_friction(mut self, g_star: f64, mu: f64) -> Result<Self> {
        if !(g_star.is_finite() && g_star > 0.0) {
            return bad(format!("g_star = {g_star} must be finite and > 0"));
        }
        if !(mu.is_finite() && mu > 0.0 && mu <= 1e6) {
            return bad(format!(
                "friction coefficient mu = {mu} must lie in (0, 1e6]"
            ));
        }
        let n = self.gaps.len();
        self.friction = Some(Friction {
            g_star,
            mu,
            slip: vec![0.0; n],
            slip_trial: vec![0.0; n],
            contacts: 0,
            contacts_trial: 0,
        });
        self.label.push_str(&format!(", Coulomb mu = {mu}"));
        Ok(self)
    }

    fn area_of(&self, contacts: usize) -> f64 {
        match self.area {
            Area::Disc => {
                let a = contacts as f64 * self.dx;
                std::f64::consts::PI * a * a
            }
            Area::Fraction { nominal, length } => nominal * contacts as f64 * self.dx / length,
        }
    }
}

impl ContactLaw for Springs {
    fn trial(&mut self, motion: Motion) -> Result<Forces> {
        check_motion(motion)?;
        let d = motion.normal;
        let state = if d > self.gaps[0] {
            self.foundation.at_depth(d)?
        } else {
            mrd::foundation::FoundationState {
                depth: d,
                force: 0.0,
                contacts: 0,
                stiffness: 0.0,
            }
        };
        let mut forces = Forces {
            normal: state.force,
            tangential: 0.0,
            contact_area: self.area_of(state.contacts),
            stiffness: state.stiffness,
            dissipated: 0.0,
            iterations: 0,
        };
        if let Some(fr) = &mut self.friction {
            let u = motion.tangential;
            let k = self.weight * fr.g_star * self.dx;
            let kn = self.weight * self.e_star * self.dx;
            let (mut q, mut dissipated) = (0.0, 0.0);
            for i in 0..state.contacts {
                // A spring that touches in this step sticks from its first contact.
                let anchor = if i < fr.contacts { fr.slip[i] } else { u };
                let limit = fr.mu * kn * (d - self.gaps[i]);
                let elastic = k * (u - anchor);
                let (qi, s) = if elastic.abs() > limit {
                    let qi = limit.copysign(elastic);
                    (qi, u - qi / k)
                } else {
                    (elastic, anchor)
                };
                dissipated += (s - anchor).abs() * limit;
                fr.slip_trial[i] = s;
                q += qi;
            }
            fr.contacts_trial = state.contacts;
            forces.tangential = q;
            forces.dissipated = dissipated;
        }
        self.trial = Some(forces);
        Ok(forces)
    }

    fn commit(&mut self) -> Result<()> {
        let Some(t) = self.trial.take() else {
            return bad("commit: no trial step to accept (call trial first)");
        };
        if let Some(fr) = &mut self.friction {
            let m = fr.contacts_trial;
            fr.slip[..m].copy_from_slice(&fr.slip_trial[..m]);
            fr.contacts = m;
        }
        self.committed = t;
        Ok(())
    }

    fn rollback(&mut self) {
        self.trial = None;
    }

    fn committed(&self) -> Forces {
        self.committed
    }

    fn approach_at(&mut self, force: f64) -> Result<f64> {
        if !(force.is_finite() && force >= 0.0) {
            return bad(format!("force = {force} must be finite and >= 0"));
        }
        Ok(self.foundation.at_force(force)?.depth)
    }

    fn describe(&self) -> String {
        self.label.clone()
    }
}

/// The approach at which the 3D normal contact `solver` carries `force` (>= 0; 0 at no
/// force), its solve warm-started from `start`: the frictionless query of the 3D laws.
pub(crate) fn approach_of<O: SolverOperator>(
    solver: &mut ContactSolver<O>,
    options: &SolverOptions,
    start: Option<&Solution>,
    force: f64,
) -> Result<f64> {
    if !(force.is_finite() && force >= 0.0) {
        return bad(format!("force = {force} must be finite and >= 0"));
    }
    if force == 0.0 {
        return Ok(0.0);
    }
    Ok(solver.solve(Load::Force(force), options, start)?.approach)
}

/// The 3D boundary-element normal contact (`bem3d`) as a contact law: each trial is a
/// solve under the step's approach (from first contact of the highest cell of the
/// heights), warm-started from the last accepted solution. Frictionless: a tangential
/// motion is refused, not ignored.
pub struct Bem3d<O: SolverOperator> {
    solver: ContactSolver<O>,
    options: SolverOptions,
    committed: Option<Solution>,
    trial: Option<Option<Solution>>,
    forces: Forces,
    trial_forces: Forces,
    label: String,
}

impl<O: SolverOperator> Bem3d<O> {
    /// `heights` (`ny x nx`) on `op` with an optional `mask`; each solve to `tolerance`
    /// in at most `max_iterations`.
    pub fn new(
        op: O,
        heights: &[f64],
        mask: Option<Vec<bool>>,
        tolerance: f64,
        max_iterations: usize,
    ) -> Result<Self> {
        let label = format!("3D, {} x {} cells", op.nx(), op.ny());
        let solver = ContactSolver::new(op, heights, mask)?;
        let options = SolverOptions::new(tolerance, max_iterations);
        options.validate()?;
        Ok(Self {
            solver,
            options,
            committed: None,
            trial: None,
            forces: Forces::default(),
            trial_forces: Forces::default(),
            label,
        })
    }
}

impl<O: SolverOperator> ContactLaw for Bem3d<O> {
    fn trial(&mut self, motion: Motion) -> Result<Forces> {
        check_motion(motion)?;
        if motion.tangential != 0.0 {
            return bad(format!(
                "tangential = {}: the 3D law is frictionless (normal motion only)",
                motion.tangential
            ));
        }
        if motion.normal <= 0.0 {
            self.trial = Some(None);
            self.trial_forces = Forces::default();
            return Ok(self.trial_forces);
        }
        let sol = self.solver.solve(
            Load::Approach(motion.normal),
            &self.options,
            self.committed.as_ref(),
        )?;
        let cell = self.solver.operator().cell_area();
        self.trial_forces =
            Forces::frictionless(sol.force, sol.contact_cells as f64 * cell, sol.iterations);
        self.trial = Some(Some(sol));
        Ok(self.trial_forces)
    }

    fn commit(&mut self) -> Result<()> {
        let Some(t) = self.trial.take() else {
            return bad("commit: no trial step to accept (call trial first)");
        };
        // Apart: the next contact starts cold.
        self.committed = t;
        self.forces = self.trial_forces;
        Ok(())
    }

    fn rollback(&mut self) {
        self.trial = None;
    }

    fn committed(&self) -> Forces {
        self.forces
    }

    fn approach_at(&mut self, force: f64) -> Result<f64> {
        approach_of(
            &mut self.solver,
            &self.options,
            self.committed.as_ref(),
            force,
        )
    }

    fn describe(&self) -> String {
        self.label.clone()
    }
}
