//! `ring_down`: frictional damping in time (Section 7 inside a time integration): a mass
//! held on a sphere by a constant normal force is released from a tangential
//! displacement and rings down on the contact alone, MRD's tangential springs with
//! Coulomb slip evaluated at every step (exact for the sphere: Cattaneo-Mindlin). Each
//! cycle's slip energy is held against Mindlin and Deresiewicz's loss per cycle at the
//! cycle's force amplitude (Johnson, Contact Mechanics, Eq. 7.59: `W(Q*)`); the
//! amplitude's decay and the equivalent damping ratio `zeta = W / (4 pi U)` (U the
//! energy stored at the turning point) against the amplitude follow.
//!
//! Set-up: the normal approach carries `normal_force` (MRD's springs, Hertz's law); the
//! mass is pulled quasi-statically to the tangential force `amplitude mu F_N` (a virgin
//! loading in shifts of a hundredth of its elastic one), then released at rest; velocity
//! Verlet at `steps` steps per period of the contact's initial tangential stiffness
//! `2 a G*` (MRD's, Mindlin's `8 G a`). Without a dashpot all loss is slip.
//!
//! The 3D side (`cells_3d > 0`): the same history on `dynamics::SlipBem3d`, the 3D
//! partial slip on the free half-space at the normal pressure of F_N (solved once, in
//! 3D, and held), the body's displacement prescribed at each step, for `periods_3d`
//! periods at `steps_3d` steps (a 3D step is a few partial-slip solves, each to 1e-8,
//! which moves the cycles' losses by 3e-8 against 1e-10: the first cycles, the largest
//! amplitudes, carry the comparison). Its cycles are held against
//! Mindlin-Deresiewicz as MRD's are, and against MRD's run cycle by cycle.
//!
//! With `normal_wave` the normal approach oscillates too (Section 7's normal and
//! tangential forces varying together, in time): `d0 (1 + b sin(f omega_t t + phase))`
//! about the held approach `d0` of F_N, at each of the `frequencies` f (over the
//! ring-down's angular frequency `omega_t = sqrt(k_t / m)`), from the same release. MRD's
//! springs run each wave for `periods`; the 3D contact with both motions free
//! (`dynamics::ObliqueBem3d`: the pressure solved at every step, the slip carried over)
//! for `periods_3d`. No closed form holds here: each cycle's loss is set against the held
//! approach's at the cycle's force amplitude (Mindlin-Deresiewicz's, which MRD's held run
//! meets to a percent), so the ratio says how the normal motion's frequency moves the
//! damping, and the 3D run against MRD's says whether MRD in the loop can be trusted there.

mod kind;
mod report;
mod wave;

// The side of the 3D run's grid in Hertz contact radii.
use crate::experiment::axisym_3d::SIDE_IN_RADII as SIDE_3D;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RingDown {
    /// Normal force F_N holding the contact [force].
    normal_force: f64,
    /// Coulomb friction coefficient.
    mu: f64,
    /// Mass of the body oscillating tangentially [mass].
    mass: f64,
    /// The starting tangential force over mu F_N, in (0, 1).
    amplitude: f64,
    /// Periods integrated.
    #[serde(default = "default_periods")]
    periods: usize,
    /// Time steps per period of the initial tangential stiffness.
    #[serde(default = "default_steps")]
    steps: usize,
    /// MRD springs on the half line (over 1.5 contact radii).
    #[serde(default = "default_springs")]
    springs: usize,
    /// Cells per side of the 3D run in the loop (the free half-space over 2.5
    /// contact radii); 0: MRD alone.
    #[serde(default = "crate::checks::default_count::<64>")]
    cells_3d: usize,
    /// Periods of the 3D run (the first cycles: the largest amplitudes).
    #[serde(default = "crate::checks::default_count::<4>")]
    periods_3d: usize,
    /// Time steps per period of the 3D run.
    #[serde(default = "crate::checks::default_count::<100>")]
    steps_3d: usize,
    /// An oscillating normal approach, run beside the held one at each of its frequencies.
    #[serde(default)]
    normal_wave: Option<NormalWave>,
}

/// The normal approach `d0 (1 + amplitude sin(f omega_t t + phase))` at each frequency f.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NormalWave {
    /// The approach's relative amplitude b, in (0, 1).
    amplitude: f64,
    /// The normal motion's angular frequencies over the ring-down's `sqrt(k_t / m)`
    /// (1 to 8 of them, each in (0, 100]).
    frequencies: Vec<f64>,
    /// The wave's phase when the mass is released [rad]; 0: the approach at `d0`,
    /// rising.
    #[serde(default)]
    phase: f64,
}

/// The most frequencies a normal wave takes (one figure line, one 3D run each).
const MAX_FREQUENCIES: usize = 8;

fn default_periods() -> usize {
    30
}
fn default_steps() -> usize {
    400
}
fn default_springs() -> usize {
    2000
}
