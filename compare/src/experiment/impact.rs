//! A rigid body striking a contact, integrated in time with the contact law evaluated
//! at every step (Section 12): the run the `impact` kind and the `references` kind's
//! Hertz impact share, and what a run's first contact gives.

use super::axisym_3d::AxisymGrid;
use bem3d::NonPeriodicHalfSpace;
use dynamics::integrate::{Axis, Counts, Oscillator, Sample, Stop};
use dynamics::{Bem3d, ContactLaw};
use mrd::Profile;

/// The 3D contact law of a body of revolution in the loop: `cells` per side over `side`
/// on the free half-space of modulus `e_star`, solved to `tolerance` (warm-started from
/// the last step).
pub fn bem3d_law(
    profile: &Profile,
    e_star: f64,
    cells: usize,
    side: f64,
    tolerance: f64,
) -> dynamics::Result<Bem3d<NonPeriodicHalfSpace>> {
    let grid = AxisymGrid {
        cells,
        side,
        periodic: false,
    };
    let (z, _) = grid.heights(profile);
    let op = NonPeriodicHalfSpace::try_new(cells, cells, side, side, e_star)?;
    Bem3d::new(op, &z, None, tolerance, 10_000)
}

/// The impact: a free mass `mass` arriving at `speed` on the contact `law`, whose
/// closed-form contact time `tc`, largest force `fmax` and approach `dmax` scale the run:
/// velocity Verlet at `tc / steps` (steps rejected where the force jumps by 5 % of
/// `fmax`, down to a thousandth of the step), from 1e-3 `dmax` before first contact to
/// 1.3 `tc`.
pub struct Strike {
    pub mass: f64,
    pub speed: f64,
    pub tc: f64,
    pub fmax: f64,
    pub dmax: f64,
}

impl Strike {
    /// The run's samples and counts at `steps` steps per `tc`, and its time step.
    pub fn run(
        &self,
        law: &mut dyn ContactLaw,
        steps: usize,
    ) -> dynamics::Result<(Vec<Sample>, Counts, f64)> {
        self.run_until(law, steps, Stop::At(1.3 * self.tc))
    }

    /// [`Self::run`] to the stop `stop` instead of 1.3 `tc`.
    pub fn run_until(
        &self,
        law: &mut dyn ContactLaw,
        steps: usize,
        stop: Stop<'_>,
    ) -> dynamics::Result<(Vec<Sample>, Counts, f64)> {
        let drive = |_t: f64| 0.0;
        let osc = Oscillator {
            mass: self.mass,
            damping: 0.0,
            drive: &drive,
            axis: Axis::Normal { tangential: 0.0 },
            dt: self.tc / steps as f64,
            dt_min: self.tc / (1000.0 * steps as f64),
            max_jump: 0.05,
            force_scale: self.fmax,
        };
        let init = (-1e-3 * self.dmax, self.speed);
        let (samples, counts) = osc.run(law, init, stop, 1)?;
        Ok((samples, counts, osc.dt))
    }
}

/// The stages of a kind that runs a sphere's contact through a motion (the impacts,
/// `oblique_cycle`): the rule of Hess, the closed form, MRD in the loop, and the 3D
/// solve in the loop where it has grids.
pub fn stages(with_3d: bool) -> Vec<crate::plan::Stage> {
    use crate::plan::Stage;
    let mut s = vec![Stage::HessTransform, Stage::ClosedForm, Stage::Dynamics];
    if with_3d {
        s.push(Stage::Dynamics3d);
    }
    s
}

/// Refuses a sphere of radius `r` (modulus `e_star`) struck by `mass` at `speed` (each
/// finite and > 0, checked by name) so hard that Hertz's largest approach passes a tenth
/// of the radius, where the small-strain half-space no longer holds.
pub fn check_strike(e_star: f64, r: f64, mass: f64, speed: f64) -> crate::error::Result<()> {
    use crate::checks::bad;
    for (key, v) in [("mass", mass), ("speed", speed)] {
        if !(v.is_finite() && v > 0.0) {
            return bad(format!("{key} = {v} must be finite and > 0"));
        }
    }
    let dmax = mrd::reference::hertz_impact::max_approach(e_star, r, mass, speed);
    if dmax > 0.1 * r {
        return bad(format!(
            "mass and speed press the sphere to {dmax:.3e}, beyond a tenth of its radius {r}: the small-strain half-space no longer holds"
        ));
    }
    Ok(())
}

/// The resolution keys of the impact kinds, each checked by name: `springs` in
/// 100..=1000000, `steps` in 100..=1000000 and `steps_3d` in 50..=100000 per contact
/// time, `cells` increasing grid sides in 16..=`largest_grid`, `extent` in [1.1, 10] and
/// the 3D `tolerance`.
pub fn check_resolution(
    springs: usize,
    (steps, steps_3d): (usize, usize),
    cells: &[usize],
    largest_grid: usize,
    extent: f64,
    tolerance: f64,
) -> crate::error::Result<()> {
    use crate::checks::bad;
    if !(100..=1_000_000).contains(&springs) {
        return bad(format!("springs = {springs} must lie in 100..=1000000"));
    }
    if !(100..=1_000_000).contains(&steps) || !(50..=100_000).contains(&steps_3d) {
        return bad(format!(
            "steps = {steps} must lie in 100..=1000000 and steps_3d = {steps_3d} in 50..=100000 (time steps per contact time)"
        ));
    }
    if cells.iter().any(|n| !(16..=largest_grid).contains(n))
        || cells.windows(2).any(|w| w[1] <= w[0])
    {
        return bad(format!(
            "cells = {cells:?}: give increasing grid sides in 16..={largest_grid}"
        ));
    }
    if !(extent.is_finite() && (1.1..=10.0).contains(&extent)) {
        return bad(format!("extent = {extent} must lie in [1.1, 10]"));
    }
    crate::checks::check_tolerance(tolerance)
}

/// What a run's first contact gives: its duration, largest force and approach, and the
/// speed ratio out / in.
pub struct FirstContact {
    pub duration: f64,
    pub peak_force: f64,
    pub peak_approach: f64,
    pub restitution: f64,
}

/// The first contact of `s`: between the crossings of x = 0 (interpolated linearly
/// between the samples around each); None if it does not start and end in the run.
pub fn first_contact(s: &[Sample]) -> Option<FirstContact> {
    let cross = |i: usize| {
        let (a, b) = (s[i], s[i + 1]);
        let w = a.x / (a.x - b.x);
        (a.t + w * (b.t - a.t), a.v + w * (b.v - a.v))
    };
    let start = s.windows(2).position(|w| w[0].x <= 0.0 && w[1].x > 0.0)?;
    let end = start
        + s[start..]
            .windows(2)
            .position(|w| w[0].x > 0.0 && w[1].x <= 0.0)?;
    let ((t0, v_in), (t1, v_out)) = (cross(start), cross(end));
    Some(FirstContact {
        duration: t1 - t0,
        peak_force: s[start..=end].iter().map(|s| s.force).fold(0.0, f64::max),
        peak_approach: s[start..=end].iter().map(|s| s.x).fold(0.0, f64::max),
        restitution: -v_out / v_in,
    })
}
