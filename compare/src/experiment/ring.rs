//! A mass on a frictional contact released from a tangential force (Sections 7 and 12):
//! the quasi-static virgin loading to the starting force, the release at rest, and each
//! cycle's loss between turning points; what the ring-down kinds stand on.

use dynamics::integrate::{Axis, Oscillator, Sample, Stop};
use dynamics::law::Motion;
use dynamics::ContactLaw;

/// A release: the mass, the starting tangential force, the stiffness and period that set
/// the loading's shifts and the time step, and how long to run.
#[derive(Debug, Clone, Copy)]
pub struct Release {
    pub mass: f64,
    /// The tangential force the mass is pulled to before it is let go [force].
    pub target: f64,
    /// The contact's initial tangential stiffness [force / length].
    pub k_t: f64,
    /// The period of `k_t` with the mass [time].
    pub period: f64,
    pub periods: usize,
    /// Time steps per period.
    pub steps: usize,
    /// The force scale of the integrator's jump control (mu F_N) [force].
    pub force_scale: f64,
}

/// The virgin loading of `law` at the approach `d` to the force `r.target`,
/// quasi-statically (shifts of a hundredth of its elastic one, `target / k_t`), then the
/// release at rest and `r.periods` periods of `r.steps` steps along `axis` (the normal
/// motion held or prescribed by it).
pub fn ring(
    law: &mut dyn ContactLaw,
    d: f64,
    axis: Axis,
    r: &Release,
) -> dynamics::Result<Vec<Sample>> {
    let target = r.target;
    let mut u = 0.0;
    let du = target / r.k_t / 100.0;
    // Mindlin's virgin loading takes at most 1.5 elastic displacements (target / k_t)
    // to any force below mu F_N: the cap stops only a contact that slides.
    for shift in 0.. {
        if shift == 100_000 {
            return Err(dynamics::DynamicsError::InvalidInput(format!(
                "the starting force amplitude x mu F_N = {target:.4e} was not reached in 1000 elastic displacements (the contact slides below it)"
            )));
        }
        let f = law.trial(Motion {
            normal: d,
            tangential: u + du,
            dt: 1.0,
        })?;
        if f.tangential >= target {
            law.rollback();
            break;
        }
        law.commit()?;
        u += du;
    }
    let drive = |_t: f64| 0.0;
    let osc = Oscillator {
        mass: r.mass,
        damping: 0.0,
        drive: &drive,
        axis,
        dt: r.period / r.steps as f64,
        dt_min: r.period / (100.0 * r.steps as f64),
        max_jump: 0.05,
        force_scale: r.force_scale,
    };
    let (s, _) = osc.run(law, (u, 0.0), Stop::At(r.periods as f64 * r.period), 1)?;
    Ok(s)
}

/// One cycle of a ring-down: from a turning point to the second after it (same sign).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cycle {
    /// The time of its first turning point [time].
    pub t: f64,
    /// The mean of its three extremes' force magnitudes [force].
    pub force: f64,
    /// Its three extremes' force magnitudes, in time order [force]: each half of the
    /// cycle, turning point to turning point, is a branch of `extremes[k] +
    /// extremes[k + 1]` in force.
    pub extremes: [f64; 3],
    /// The mean of its three extremes' displacement magnitudes [length].
    pub x: f64,
    /// The slip energy between its first and last turning points [force x length].
    pub loss: f64,
}

/// The cycles of a run: turning points where the velocity changes sign, with the slip
/// energy accumulated up to each, taken three at a time, two apart.
pub fn cycles(s: &[Sample]) -> Vec<Cycle> {
    // (t, x, force, dissipated since the start)
    let mut turns = Vec::new();
    let mut dissipated = 0.0;
    for w in s.windows(2) {
        dissipated += w[1].dissipated;
        if w[0].v * w[1].v < 0.0 || w[1].v == 0.0 {
            turns.push((w[1].t, w[1].x, w[1].force, dissipated));
        }
    }
    turns
        .windows(3)
        .step_by(2)
        .map(|w| Cycle {
            t: w[0].0,
            force: (w[0].2.abs() + w[1].2.abs() + w[2].2.abs()) / 3.0,
            extremes: [w[0].2.abs(), w[1].2.abs(), w[2].2.abs()],
            x: (w[0].1.abs() + w[1].1.abs() + w[2].1.abs()) / 3.0,
            loss: w[2].3 - w[0].3,
        })
        .collect()
}
