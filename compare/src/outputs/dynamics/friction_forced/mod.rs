//! `friction_forced`: frictional damping under a steady harmonic drive (Section 7 in
//! time): a mass held on a sphere by a constant normal force F_N and driven tangentially
//! by `F1 cos(Omega t)`, damped by partial slip (and a light dashpot), the contact
//! evaluated at every step by MRD's tangential springs with Coulomb slip and by the 3D
//! partial slip in the loop. The drive frequency is stepped through the resonance; at
//! each the drive's periods are run one by one until the amplitude settles.
//!
//! The closed form at the steady state: the tangential force runs a symmetric loop
//! between +-Q*, and a loop's slip energy is Mindlin and Deresiewicz's `W(Q*)` whatever
//! the path between the extremes (Johnson, Contact Mechanics, Eq. 7.59; the sphere's loop
//! after its first loading depends only on its extremes). So the steady slip energy per
//! period is held against `W(Q*)` at the measured force amplitude, and the work the drive
//! does over a period against the slip and the dashpot's losses (the energy balance of a
//! periodic motion). MRD's frequency response against the 3D one: the amplitude at each
//! frequency, the resonance's peak.
//!
//! Set-up: as `ring_down`'s (`k_t = 2 a G*` the initial tangential stiffness, `omega_t =
//! sqrt(k_t / m)`); a dashpot `c = 2 zeta m omega_t`; the sweep starts at rest at the
//! held approach, each frequency from the last one's end; `steps` velocity-Verlet steps
//! per drive period (whole periods, so each starts in phase).

mod report;

use crate::checks::{bad, count_in, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
// The side of the 3D run's grid in Hertz contact radii.
use crate::experiment::axisym_3d::{AxisymGrid, SIDE_IN_RADII as SIDE_3D};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use dynamics::integrate::{Axis, Oscillator, Stop};
use dynamics::{ContactLaw, SlipBem3d, Springs};
use mrd::reference::{for_profile, hertz, mindlin_damping as md};
use serde::Deserialize;
use std::f64::consts::PI;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionForced {
    /// Normal force F_N holding the contact [force].
    normal_force: f64,
    /// Coulomb friction coefficient.
    mu: f64,
    /// Mass of the body driven tangentially [mass].
    mass: f64,
    /// The drive's amplitude F1 over mu F_N, in (0, 1).
    drive: f64,
    /// Drive frequencies Omega over omega_t, in the sweep's order (1 to 60, each in
    /// (0, 10]).
    frequencies: Vec<f64>,
    /// Frequencies of the 3D sweep (over omega_t; empty: MRD alone).
    #[serde(default)]
    frequencies_3d: Vec<f64>,
    /// Damping ratio zeta of the dashpot at omega_t, in [0, 1).
    #[serde(default = "default_damping")]
    damping: f64,
    /// Time steps per drive period.
    #[serde(default = "crate::checks::default_count::<200>")]
    steps: usize,
    /// Settling: a frequency's periods run until one period's amplitude differs from
    /// the last one's by at most this fraction of it (after at least five periods).
    #[serde(default = "default_settle_tolerance")]
    settle_tolerance: f64,
    /// The most periods at one frequency; one that reaches it unsettled is a failure of
    /// the run, named.
    #[serde(default = "crate::checks::default_count::<2000>")]
    max_periods: usize,
    /// MRD springs on the half line (over 1.5 contact radii).
    #[serde(default = "crate::checks::default_count::<2000>")]
    springs: usize,
    /// Cells per side of the 3D run (the free half-space over 2.5 contact radii).
    #[serde(default = "crate::checks::default_count::<32>")]
    cells_3d: usize,
}

fn default_damping() -> f64 {
    0.02
}
fn default_settle_tolerance() -> f64 {
    1e-6
}

/// Periods at each frequency before the settling test may stop.
const MIN_PERIODS: usize = 5;
/// Steps per period of omega_t at the lowest drive frequency, at least.
const MIN_STEPS_T: f64 = 40.0;
/// A force amplitude within this fraction of mu F_N is gross slip: the contact slides
/// over part of each period, and Mindlin-Deresiewicz's loop no longer holds.
const SLIDING: f64 = 1e-6;

/// The steady state at one drive frequency, over its last period.
#[derive(Debug, Clone, Copy)]
struct Steady {
    omega: f64,
    /// Half the range of the displacement [length].
    amplitude: f64,
    /// Half the range of the contact force [force].
    force_amplitude: f64,
    /// Slip energy, the dashpot's loss and the drive's work [force x length].
    slip: f64,
    viscous: f64,
    work: f64,
    periods: usize,
    settled: bool,
}

impl Output for FrictionForced {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if for_profile::sphere_radius(ctx.profile()?).is_none() {
            return bad("friction_forced needs a sphere (profile = paraboloid): Mindlin and Deresiewicz's loss per cycle is the reference");
        }
        let g = ctx.material.g_star().ctx("friction_forced")?;
        require_positive("normal_force", self.normal_force)?;
        require_positive("mu", self.mu)?;
        require_positive("mass", self.mass)?;
        if !(self.drive > 0.0 && self.drive < 1.0) {
            return bad(format!(
                "drive = {} must lie in (0, 1) (a fraction of mu F_N)",
                self.drive
            ));
        }
        for (key, list, most) in [
            ("frequencies", &self.frequencies, 60),
            ("frequencies_3d", &self.frequencies_3d, 20),
        ] {
            if list.len() > most || (key == "frequencies" && list.is_empty()) {
                return bad(format!(
                    "{key} has {} values; give {} to {most}",
                    list.len(),
                    if key == "frequencies" { 1 } else { 0 }
                ));
            }
            if let Some(f) = list
                .iter()
                .find(|f| !(f.is_finite() && **f > 0.0 && **f <= 10.0))
            {
                return bad(format!(
                    "{key} holds {f}: each must lie in (0, 10] (over omega_t)"
                ));
            }
        }
        // The stuck contact's period 2 pi / omega_t needs its own steps, whatever the
        // drive's: at least MIN_STEPS_T of them at the lowest frequency.
        let lowest = self
            .frequencies
            .iter()
            .chain(&self.frequencies_3d)
            .fold(f64::INFINITY, |a, f| a.min(*f));
        if (self.steps as f64) * lowest < MIN_STEPS_T {
            return bad(format!(
                "steps = {} per drive period gives {:.1} steps per period of omega_t at the lowest frequency {lowest}: at least {MIN_STEPS_T} are needed (raise steps to {} or drop the frequency)",
                self.steps,
                self.steps as f64 * lowest,
                (MIN_STEPS_T / lowest).ceil()
            ));
        }
        if !(self.damping.is_finite() && (0.0..1.0).contains(&self.damping)) {
            return bad(format!("damping = {} must lie in [0, 1)", self.damping));
        }
        if !(self.settle_tolerance > 0.0 && self.settle_tolerance <= 0.1) {
            return bad(format!(
                "settle_tolerance = {} must lie in (0, 0.1]",
                self.settle_tolerance
            ));
        }
        count_in("steps", self.steps as u64, 50..=100_000)?;
        count_in(
            "max_periods",
            self.max_periods as u64,
            MIN_PERIODS as u64..=100_000,
        )?;
        count_in("springs", self.springs as u64, 100..=1_000_000)?;
        let runs = self.frequencies.len() + self.frequencies_3d.len();
        let total = (runs * self.max_periods).saturating_mul(self.steps);
        if total > 200_000_000 {
            return bad(format!(
                "(frequencies + frequencies_3d) x max_periods x steps = {total} steps: at most 2e8"
            ));
        }
        if !self.frequencies_3d.is_empty() {
            count_in("cells_3d", self.cells_3d as u64, 16..=512)?;
            let ratio = g / ctx.material.e_star;
            if !(2.0 / 3.0..=1.0).contains(&ratio) {
                return bad(format!(
                    "G* / E* = {ratio}: the 3D run (frequencies_3d) takes one elastic body, G* / E* in [2/3, 1] (Poisson's ratio in [0, 0.5]); or leave frequencies_3d empty"
                ));
            }
        }
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        let mut s = vec![Stage::HessTransform, Stage::ClosedForm, Stage::Dynamics];
        if !self.frequencies_3d.is_empty() {
            s.push(Stage::Dynamics3d);
        }
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let ctx = env.ctx;
        let profile = ctx.profile()?.clone();
        let (e, g) = (
            ctx.material.e_star,
            ctx.material.g_star().ctx("friction_forced")?,
        );
        let r = for_profile::sphere_radius(&profile).unwrap_or(1.0);
        let fn_ = self.normal_force;
        out.stage(Stage::HessTransform, || profile.z1d(0.0));
        let a = out.stage(Stage::ClosedForm, || {
            hertz::radius(r, hertz::depth(e, r, fn_))
        });
        let omega_t = (2.0 * a * g / self.mass).sqrt();
        let mrd = out
            .stage(Stage::Dynamics, || -> dynamics::Result<Vec<Steady>> {
                let mut law =
                    Springs::body(&profile, e, self.springs, 1.5 * a)?.with_friction(g, self.mu)?;
                let d = law.approach_at(fn_)?;
                self.sweep(&mut law, d, omega_t, &self.frequencies)
            })
            .ctx("MRD in the loop")?;
        let three = if self.frequencies_3d.is_empty() {
            None
        } else {
            let grid = AxisymGrid {
                cells: self.cells_3d,
                side: SIDE_3D * a,
                periodic: false,
            };
            let (z, _) = grid.heights(&profile);
            let (n, side) = (grid.cells, grid.side);
            let s = out
                .stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Steady>> {
                    let mut law =
                        SlipBem3d::new(&z, (n, n), (side, side), (e, g), self.mu, fn_, 1e-8)?;
                    let d = law.approach();
                    self.sweep(&mut law, d, omega_t, &self.frequencies_3d)
                })
                .ctx("3D in the loop")?;
            out.scalar("cells_per_contact_radius_3d", a / (side / n as f64));
            Some(s)
        };
        self.report(out, &mrd, three.as_deref(), (g, a, omega_t))
    }
}

impl FrictionForced {
    /// The sweep through `frequencies` (over `omega_t`) on `law` pressed to the approach
    /// `d`: from rest, each frequency from the last one's end.
    fn sweep(
        &self,
        law: &mut dyn ContactLaw,
        d: f64,
        omega_t: f64,
        frequencies: &[f64],
    ) -> dynamics::Result<Vec<Steady>> {
        let mut state = (0.0, 0.0);
        let mut out = Vec::with_capacity(frequencies.len());
        for &f in frequencies {
            let (steady, end) = self.steady(law, d, f * omega_t, omega_t, state)?;
            out.push(steady);
            state = end;
        }
        Ok(out)
    }

    /// The drive's periods at `omega` from `start` (displacement, speed), one by one,
    /// until the amplitude settles; the last period's steady state and the end state.
    fn steady(
        &self,
        law: &mut dyn ContactLaw,
        d: f64,
        omega: f64,
        omega_t: f64,
        start: (f64, f64),
    ) -> dynamics::Result<(Steady, (f64, f64))> {
        let f1 = self.drive * self.mu * self.normal_force;
        let drive = move |t: f64| f1 * (omega * t).cos();
        let period = 2.0 * PI / omega;
        let c = 2.0 * self.damping * self.mass * omega_t;
        let dt = period / self.steps as f64;
        let osc = Oscillator {
            mass: self.mass,
            damping: c,
            drive: &drive,
            axis: Axis::Tangential { approach: d },
            dt,
            dt_min: dt / 100.0,
            max_jump: 0.05,
            force_scale: self.mu * self.normal_force,
        };
        let mut state = start;
        let mut last = f64::NAN;
        for k in 1..=self.max_periods {
            let (s, _) = osc.run(law, state, Stop::At(period), 1)?;
            let range = |v: &dyn Fn(&dynamics::integrate::Sample) -> f64| {
                let (lo, hi) = s
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                        (a.min(v(p)), b.max(v(p)))
                    });
                0.5 * (hi - lo)
            };
            let amplitude = range(&|p| p.x);
            let end = s[s.len() - 1];
            state = (end.x, end.v);
            let settled = (amplitude - last).abs() <= self.settle_tolerance * amplitude;
            if (k >= MIN_PERIODS && settled) || k == self.max_periods {
                // The drive's work integrated by parts, F1 [cos(W t) x] + F1 W int sin(W t)
                // x dt: a smooth periodic integrand, whose trapezoids converge fast, where
                // int F dx is a small difference of large parts off resonance (the
                // response nearly in or out of phase). The dashpot's loss c int v^2 dt;
                // the slip energy as the law reports it.
                let (mut work, mut viscous) = (f1 * (end.x * (omega * end.t).cos() - s[0].x), 0.0);
                for w in s.windows(2) {
                    let dt = w[1].t - w[0].t;
                    let sx = |p: &dynamics::integrate::Sample| (omega * p.t).sin() * p.x;
                    work += f1 * omega * 0.5 * (sx(&w[0]) + sx(&w[1])) * dt;
                    viscous += c * 0.5 * (w[0].v * w[0].v + w[1].v * w[1].v) * dt;
                }
                let steady = Steady {
                    omega,
                    amplitude,
                    force_amplitude: range(&|p| p.force),
                    slip: s.iter().skip(1).map(|p| p.dissipated).sum(),
                    viscous,
                    work,
                    periods: k,
                    settled,
                };
                return Ok((steady, state));
            }
            last = amplitude;
        }
        unreachable!("max_periods >= {MIN_PERIODS} (validated)")
    }
}
