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

use crate::checks::bad;
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::AxisymGrid;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use dynamics::integrate::{Axis, Oscillator, Sample, Stop};
use dynamics::law::Motion;
use dynamics::{ContactLaw, SlipBem3d, Springs};
use mrd::reference::{for_profile, hertz, mindlin_damping as md};
use serde::Deserialize;
use std::f64::consts::PI;

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
    /// Cells per side of the 3D run in the loop (the free half-space over
    /// [`SIDE_3D`] contact radii); 0: MRD alone.
    #[serde(default = "crate::checks::default_count::<64>")]
    cells_3d: usize,
    /// Periods of the 3D run (the first cycles: the largest amplitudes).
    #[serde(default = "crate::checks::default_count::<4>")]
    periods_3d: usize,
    /// Time steps per period of the 3D run.
    #[serde(default = "crate::checks::default_count::<100>")]
    steps_3d: usize,
}

/// The side of the 3D run's grid in Hertz contact radii.
const SIDE_3D: f64 = 2.5;

fn default_periods() -> usize {
    30
}
fn default_steps() -> usize {
    400
}
fn default_springs() -> usize {
    2000
}

/// A turning point of the motion: where the velocity changes sign.
#[derive(Debug, Clone, Copy)]
struct Turn {
    t: f64,
    x: f64,
    force: f64,
    /// Slip energy since the start [force x length].
    dissipated: f64,
}

impl Output for RingDown {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if for_profile::sphere_radius(ctx.profile()?).is_none() {
            return bad("ring_down needs a sphere (profile = paraboloid): Mindlin and Deresiewicz's loss per cycle is the reference");
        }
        ctx.material.g_star().ctx("ring_down")?;
        for (key, v) in [
            ("normal_force", self.normal_force),
            ("mu", self.mu),
            ("mass", self.mass),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return bad(format!("{key} = {v} must be finite and > 0"));
            }
        }
        if !(self.amplitude > 0.0 && self.amplitude < 1.0) {
            return bad(format!(
                "amplitude = {} must lie in (0, 1) (a fraction of mu F_N; at 1 the body slides)",
                self.amplitude
            ));
        }
        if !(2..=100_000).contains(&self.periods)
            || !(50..=100_000).contains(&self.steps)
            || self.periods * self.steps > 50_000_000
        {
            return bad(format!(
                "periods = {} in 2..=100000 and steps = {} per period in 50..=100000, at most 5e7 steps in all",
                self.periods, self.steps
            ));
        }
        let ratio = ctx.material.g_star().ctx("ring_down")? / ctx.material.e_star;
        if self.cells_3d != 0 && !(2.0 / 3.0..=1.0).contains(&ratio) {
            return bad(format!(
                "G* / E* = {ratio}: the 3D run (cells_3d = {}) takes one elastic body, G* / E* in [2/3, 1] (Poisson's ratio in [0, 0.5]); or set cells_3d = 0",
                self.cells_3d
            ));
        }
        if self.cells_3d != 0 && !(16..=512).contains(&self.cells_3d) {
            return bad(format!(
                "cells_3d = {} must be 0 (MRD alone) or lie in 16..=512",
                self.cells_3d
            ));
        }
        if !(2..=1000).contains(&self.periods_3d)
            || !(50..=100_000).contains(&self.steps_3d)
            || self.periods_3d * self.steps_3d > 1_000_000
        {
            return bad(format!(
                "periods_3d = {} in 2..=1000 and steps_3d = {} per period in 50..=100000, at most 1e6 steps in all",
                self.periods_3d, self.steps_3d
            ));
        }
        if !(100..=1_000_000).contains(&self.springs) {
            return bad(format!(
                "springs = {} must lie in 100..=1000000",
                self.springs
            ));
        }
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        let mut s = vec![Stage::HessTransform, Stage::ClosedForm, Stage::Dynamics];
        if self.cells_3d > 0 {
            s.push(Stage::Dynamics3d);
        }
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let ctx = env.ctx;
        let profile = ctx.profile()?.clone();
        let (e, g) = (ctx.material.e_star, ctx.material.g_star().ctx("ring_down")?);
        let r = for_profile::sphere_radius(&profile).unwrap_or(1.0);
        let (mu, fn_) = (self.mu, self.normal_force);
        out.stage(Stage::HessTransform, || profile.z1d(0.0));
        let a = out.stage(Stage::ClosedForm, || {
            hertz::radius(r, hertz::depth(e, r, fn_))
        });
        let k_t = 2.0 * a * g;
        let period = 2.0 * PI * (self.mass / k_t).sqrt();
        let mrd = out
            .stage(Stage::Dynamics, || -> dynamics::Result<Vec<Sample>> {
                let mut law =
                    Springs::body(&profile, e, self.springs, 1.5 * a)?.with_friction(g, mu)?;
                let d = law.approach_at(fn_)?;
                self.ring(&mut law, d, (k_t, period), (self.periods, self.steps))
            })
            .ctx("MRD in the loop")?;
        let three = if self.cells_3d > 0 {
            let n = self.cells_3d;
            let side = SIDE_3D * a;
            let (z, _) = AxisymGrid {
                cells: n,
                side,
                periodic: false,
            }
            .heights(&profile);
            let s = out
                .stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Sample>> {
                    let mut law = SlipBem3d::new(&z, (n, n), (side, side), (e, g), mu, fn_, 1e-8)?;
                    let d = law.approach();
                    self.ring(&mut law, d, (k_t, period), (self.periods_3d, self.steps_3d))
                })
                .ctx("3D in the loop")?;
            out.scalar("cells_per_contact_radius_3d", a / (side / n as f64));
            Some(s)
        } else {
            None
        };
        self.report(out, &mrd, three.as_deref(), (g, a, k_t, period))
    }
}

impl RingDown {
    /// One run in the loop: the virgin loading of `law` at the approach `d` to the
    /// starting force, quasi-statically (shifts of a hundredth of its elastic one), then the
    /// release at rest and `periods` periods at `steps` steps each.
    fn ring(
        &self,
        law: &mut dyn ContactLaw,
        d: f64,
        (k_t, period): (f64, f64),
        (periods, steps): (usize, usize),
    ) -> dynamics::Result<Vec<Sample>> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let target = self.amplitude * mu * fn_;
        let mut u = 0.0;
        let du = target / k_t / 100.0;
        loop {
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
            mass: self.mass,
            damping: 0.0,
            drive: &drive,
            axis: Axis::Tangential { approach: d },
            dt: period / steps as f64,
            dt_min: period / (100.0 * steps as f64),
            max_jump: 0.05,
            force_scale: mu * fn_,
        };
        let (s, _) = osc.run(law, (u, 0.0), Stop::At(periods as f64 * period), 1)?;
        Ok(s)
    }

    /// Per cycle of a run (from a turning point to the second after it, same sign):
    /// [cycle, time over period, force amplitude over mu F_N (the mean of its three
    /// extremes' magnitudes), loss, Mindlin-Deresiewicz's loss at that amplitude, their
    /// ratio, zeta, zeta of Mindlin-Deresiewicz].
    fn cycles(&self, s: &[Sample], (g, a, period): (f64, f64, f64)) -> Vec<Vec<f64>> {
        let (mu, fn_) = (self.mu, self.normal_force);
        // Turning points, with the slip energy accumulated up to each.
        let mut turns = Vec::new();
        let mut dissipated = 0.0;
        for w in s.windows(2) {
            dissipated += w[1].dissipated;
            if w[0].v * w[1].v < 0.0 || w[1].v == 0.0 {
                turns.push(Turn {
                    t: w[1].t,
                    x: w[1].x,
                    force: w[1].force,
                    dissipated,
                });
            }
        }
        turns
            .windows(3)
            .step_by(2)
            .enumerate()
            .map(|(c, w)| {
                let q = (w[0].force.abs() + w[1].force.abs() + w[2].force.abs()) / 3.0;
                let xa = (w[0].x.abs() + w[1].x.abs() + w[2].x.abs()) / 3.0;
                let loss = w[2].dissipated - w[0].dissipated;
                let exact = md::dissipation_force_amplitude_exact(g, a, mu, fn_, q);
                let stored = 0.5 * q * xa;
                let exact_stored = 0.5 * q * self.md_displacement(g, a, q);
                vec![
                    c as f64,
                    w[0].t / period,
                    q / (mu * fn_),
                    loss,
                    exact,
                    loss / exact,
                    loss / (4.0 * PI * stored),
                    exact / (4.0 * PI * exact_stored),
                ]
            })
            .collect()
    }

    /// The cycles table of one method (`who`: "MRD" or "3D").
    fn cycles_table(&self, name: &str, who: &str, rows: Vec<Vec<f64>>, note: String) -> Table {
        let loss = format!("loss per cycle, {who} in the loop [force x length]");
        let ratio = format!("loss ratio {who} / MD [1]");
        let mut t = Table::new(
            name,
            &[
                "cycle [index]",
                "time over period [1]",
                "force_amplitude over mu F_N [1]",
                &loss,
                "loss per cycle, Mindlin-Deresiewicz [force x length]",
                &ratio,
                "damping ratio zeta [1]",
                "damping ratio zeta, MD [1]",
            ],
        );
        t.notes.push(note);
        for r in rows {
            t.push(r);
        }
        t
    }

    fn report(
        &self,
        out: &mut Section,
        s: &[Sample],
        three: Option<&[Sample]>,
        (g, a, k_t, period): (f64, f64, f64, f64),
    ) -> Result<()> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let common = format!(
            "sphere under F_N = {fn_} with mu = {mu}, G* = {g}, contact radius a = {a:.6e}; mass {} released at rest from {} mu F_N (virgin loading)",
            self.mass, self.amplitude
        );
        let tail = format!("velocity Verlet at STEPS steps per period 2 pi sqrt(m / k_t) = {period:.6e} (k_t = 2 a G*); loss per cycle: the slip energy between turning points two apart, against Johnson's Eq. 7.59 at the mean of the cycle's three force extremes; zeta = W / (4 pi U), U = Q*^2 / (2 k_sec) with the secant stiffness of the cycle's extremes");
        let rows = self.cycles(s, (g, a, period));
        if rows.is_empty() {
            out.failures.push("the motion made no full cycle".into());
            return Ok(());
        }
        let worst = |rows: &[Vec<f64>]| rows.iter().fold(0.0f64, |w, r| w.max((r[5] - 1.0).abs()));
        out.scalar(
            "loss_per_cycle_max_rel_dev_vs_mindlin_deresiewicz",
            worst(&rows),
        );
        out.scalar("initial_tangential_stiffness", k_t);
        out.scalar(
            "amplitude_decay_first_to_last_cycle",
            rows[rows.len() - 1][2] / rows[0][2],
        );
        let t = self.cycles_table(
            "cycles",
            "MRD",
            rows,
            format!(
                "{common}; MRD's {} springs with Coulomb slip, {}",
                self.springs,
                tail.replace("STEPS", &self.steps.to_string())
            ),
        );
        let rows_3d = three.map(|s3| self.cycles(s3, (g, a, period)));
        let mut fig = Figure::new(
            "ring_down",
            "Frictional ring-down on a sphere: tangential force, MRD and 3D in the loop",
            "time over the stick period t / T [1]",
            "tangential force over mu F_N [1]",
        )
        .plot(
            format!("MRD, {} springs, Coulomb slip", self.springs),
            s.iter()
                .step_by((s.len() / 2000).max(1))
                .map(|p| (p.t / period, p.force / (mu * fn_)))
                .collect(),
            Style::Line,
        );
        if let Some(s3) = three {
            fig = fig.plot(
                format!(
                    "3D partial slip, {0}^2 cells, {1} steps per period",
                    self.cells_3d, self.steps_3d
                ),
                s3.iter()
                    .map(|p| (p.t / period, p.force / (mu * fn_)))
                    .collect(),
                Style::Dashed,
            );
        }
        out.figures.push(fig);
        let mut zeta = Figure::new(
            "damping",
            "Loss per cycle over Mindlin-Deresiewicz's, and damping ratio, against amplitude",
            "force amplitude over mu F_N [1]",
            "[1]",
        )
        .plot(
            "loss per cycle: MRD in the loop / Mindlin-Deresiewicz",
            t.rows.iter().map(|r| (r[2], r[5])).collect(),
            Style::Markers,
        )
        .plot(
            "damping ratio zeta, MRD in the loop",
            t.rows.iter().map(|r| (r[2], r[6])).collect(),
            Style::Crosses,
        )
        .plot(
            "damping ratio zeta, Mindlin-Deresiewicz",
            t.rows.iter().map(|r| (r[2], r[7])).collect(),
            Style::Line,
        );
        let mrd_rows = t.rows.clone();
        out.tables.push(t);
        if let Some(rows) = rows_3d {
            if rows.is_empty() {
                out.failures.push("the 3D run made no full cycle".into());
            } else {
                out.scalar(
                    "loss_per_cycle_max_rel_dev_3d_vs_mindlin_deresiewicz",
                    worst(&rows),
                );
                // Cycle by cycle against MRD's run: the amplitude and the loss.
                let (mut amp, mut loss) = (0.0f64, 0.0f64);
                for (r3, rm) in rows.iter().zip(&mrd_rows) {
                    amp = amp.max((r3[2] / rm[2] - 1.0).abs());
                    loss = loss.max((r3[3] / rm[3] - 1.0).abs());
                }
                out.scalar("amplitude_max_rel_dev_3d_vs_mrd", amp);
                out.scalar("loss_per_cycle_max_rel_dev_3d_vs_mrd", loss);
                zeta = zeta.plot(
                    "loss per cycle: 3D in the loop / Mindlin-Deresiewicz",
                    rows.iter().map(|r| (r[2], r[5])).collect(),
                    Style::Markers,
                );
                let t3 = self.cycles_table(
                    "cycles_3d",
                    "3D",
                    rows,
                    format!(
                        "{common}; 3D partial slip on the free half-space, {0}^2 cells over {SIDE_3D} contact radii (the normal pressure of F_N held, Poisson's ratio of the one body equivalent to E* and G*), {1}",
                        self.cells_3d,
                        tail.replace("STEPS", &self.steps_3d.to_string())
                    ),
                );
                out.tables.push(t3);
            }
        }
        out.figures.push(zeta);
        Ok(())
    }

    /// Mindlin's tangential displacement at the force `q` on the virgin loading:
    /// `3 mu F_N / (8 G* a) ... ` in MRD's terms `(3 mu F_N / (4 a G*)) (1 - (1 - q /
    /// (mu F_N))^(2/3))` (Eq. 45 with G* the composite tangential modulus).
    fn md_displacement(&self, g: f64, a: f64, q: f64) -> f64 {
        let (mu, fn_) = (self.mu, self.normal_force);
        3.0 * mu * fn_ / (4.0 * a * g) * (1.0 - (1.0 - q / (mu * fn_)).powf(2.0 / 3.0))
    }
}
