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

use crate::checks::bad;
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::AxisymGrid;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use dynamics::integrate::{Axis, Oscillator, Sample, Stop};
use dynamics::law::Motion;
use dynamics::{ContactLaw, ObliqueBem3d, SlipBem3d, Springs};
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
        if let Some(w) = &self.normal_wave {
            w.check(self.amplitude)?;
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
                self.ring(&mut law, d, None, (k_t, period), (self.periods, self.steps))
            })
            .ctx("MRD in the loop")?;
        let grid = AxisymGrid {
            cells: self.cells_3d,
            side: SIDE_3D * a,
            periodic: false,
        };
        let three = if self.cells_3d > 0 {
            let (n, side) = (self.cells_3d, grid.side);
            let (z, _) = grid.heights(&profile);
            let s = out
                .stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Sample>> {
                    let mut law = SlipBem3d::new(&z, (n, n), (side, side), (e, g), mu, fn_, 1e-8)?;
                    let d = law.approach();
                    self.ring(
                        &mut law,
                        d,
                        None,
                        (k_t, period),
                        (self.periods_3d, self.steps_3d),
                    )
                })
                .ctx("3D in the loop")?;
            out.scalar("cells_per_contact_radius_3d", a / (side / n as f64));
            Some(s)
        } else {
            None
        };
        let waves = match &self.normal_wave {
            Some(w) => self.waves(out, w, &profile, &grid, (e, g), (k_t, period))?,
            None => Vec::new(),
        };
        self.report(out, &mrd, three.as_deref(), (g, a, k_t, period))?;
        if let Some(w) = &self.normal_wave {
            self.report_waves(out, w, (&mrd, &waves), (g, a, period))?;
        }
        Ok(())
    }
}

/// One frequency of a normal wave: the frequency, MRD's run and the 3D run.
type WaveRun = (f64, Vec<Sample>, Option<Vec<Sample>>);

impl NormalWave {
    fn check(&self, release: f64) -> Result<()> {
        let b = self.amplitude;
        if !(b > 0.0 && b < 1.0) {
            return bad(format!("normal_wave.amplitude = {b} must lie in (0, 1)"));
        }
        if self.frequencies.is_empty() || self.frequencies.len() > MAX_FREQUENCIES {
            return bad(format!(
                "normal_wave.frequencies has {} values; give 1 to {MAX_FREQUENCIES}",
                self.frequencies.len()
            ));
        }
        if let Some(f) = self
            .frequencies
            .iter()
            .find(|f| !(f.is_finite() && **f > 0.0 && **f <= 100.0))
        {
            return bad(format!(
                "normal_wave.frequencies holds {f}: each must lie in (0, 100] (over the ring-down's angular frequency)"
            ));
        }
        if !self.phase.is_finite() {
            return bad(format!("normal_wave.phase = {} must be finite", self.phase));
        }
        // Hertz's F ~ d^(3/2): the stick limit at the release's approach, over mu F_N.
        let limit = (1.0 + b * self.phase.sin()).powf(1.5);
        if release >= 0.95 * limit {
            return bad(format!(
                "amplitude = {release} must lie below 0.95 of the stick limit at the release's approach, (1 + b sin(phase))^(3/2) = {limit:.4} with normal_wave.amplitude = {b} and normal_wave.phase = {}",
                self.phase
            ));
        }
        Ok(())
    }
}

impl RingDown {
    /// One run in the loop: the virgin loading of `law` at the approach of t = 0 (`d`, or
    /// the wave's `d (1 + b sin(phase))` under `wave` = (b, omega, phase)) to the starting
    /// force, quasi-statically (shifts of a hundredth of its elastic one), then the
    /// release at rest and `periods` periods at `steps` steps each.
    fn ring(
        &self,
        law: &mut dyn ContactLaw,
        d: f64,
        wave: Option<(f64, f64, f64)>,
        (k_t, period): (f64, f64),
        (periods, steps): (usize, usize),
    ) -> dynamics::Result<Vec<Sample>> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let target = self.amplitude * mu * fn_;
        let (axis, d_start) = match wave {
            None => (Axis::Tangential { approach: d }, d),
            Some((amplitude, omega, phase)) => (
                Axis::TangentialWave {
                    approach: d,
                    amplitude,
                    omega,
                    phase,
                },
                d * (1.0 + amplitude * phase.sin()),
            ),
        };
        let mut u = 0.0;
        let du = target / k_t / 100.0;
        // Mindlin's virgin loading reaches 0.95 mu F_N at 1.7 elastic displacements.
        for shift in 0.. {
            if shift == 100_000 {
                return Err(dynamics::DynamicsError::InvalidInput(format!(
                    "the starting force amplitude x mu F_N = {target:.4e} was not reached in 1000 elastic displacements (the contact slides below it)"
                )));
            }
            let f = law.trial(Motion {
                normal: d_start,
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
            axis,
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

    /// The columns of a cycles table of one method (`who`: "MRD" or "3D"), as
    /// [`Self::cycles`] gives them.
    fn cycle_columns(who: &str) -> Vec<String> {
        vec![
            "cycle [index]".into(),
            "time over period [1]".into(),
            "force_amplitude over mu F_N [1]".into(),
            format!("loss per cycle, {who} in the loop [force x length]"),
            "loss per cycle, Mindlin-Deresiewicz [force x length]".into(),
            format!("loss ratio {who} / MD [1]"),
            "damping ratio zeta [1]".into(),
            "damping ratio zeta, MD [1]".into(),
        ]
    }

    /// The cycles table of one method (`who`: "MRD" or "3D"), `lead` columns before the
    /// cycles' own (each row starting with their values).
    fn cycles_table(
        name: &str,
        who: &str,
        lead: &[&str],
        rows: Vec<Vec<f64>>,
        note: String,
    ) -> Table {
        let own = Self::cycle_columns(who);
        let columns: Vec<&str> = lead
            .iter()
            .copied()
            .chain(own.iter().map(String::as_str))
            .collect();
        let mut t = Table::new(name, &columns);
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
        let t = Self::cycles_table(
            "cycles",
            "MRD",
            &[],
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
                let t3 = Self::cycles_table(
                    "cycles_3d",
                    "3D",
                    &[],
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

    /// The runs under the normal wave `w`, frequency by frequency: MRD's springs and,
    /// with `cells_3d`, the 3D contact with both motions free, both about Hertz's
    /// approach of F_N.
    fn waves(
        &self,
        out: &mut Section,
        w: &NormalWave,
        profile: &mrd::profile::Profile,
        grid: &AxisymGrid,
        (e, g): (f64, f64),
        (k_t, period): (f64, f64),
    ) -> Result<Vec<WaveRun>> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let r = for_profile::sphere_radius(profile).unwrap_or(1.0);
        let d0 = hertz::depth(e, r, fn_);
        let a = hertz::radius(r, d0);
        let z = (self.cells_3d > 0).then(|| grid.heights(profile).0);
        let mut runs = Vec::new();
        for &f in &w.frequencies {
            let wave = Some((w.amplitude, f * 2.0 * PI / period, w.phase));
            let sm = out
                .stage(Stage::Dynamics, || -> dynamics::Result<Vec<Sample>> {
                    let mut law =
                        Springs::body(profile, e, self.springs, 1.5 * a)?.with_friction(g, mu)?;
                    self.ring(
                        &mut law,
                        d0,
                        wave,
                        (k_t, period),
                        (self.periods, self.steps),
                    )
                })
                .ctx(format!(
                    "MRD in the loop under the normal wave at {f} omega_t"
                ))?;
            let s3 = match &z {
                Some(z) => Some(
                    out.stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Sample>> {
                        let (n, side) = (grid.cells, grid.side);
                        let mut law = ObliqueBem3d::new(z, (n, n), (side, side), (e, g), mu, 1e-8)?;
                        let (periods, steps) = (self.periods_3d, self.steps_3d);
                        self.ring(&mut law, d0, wave, (k_t, period), (periods, steps))
                    })
                    .ctx(format!(
                        "3D in the loop under the normal wave at {f} omega_t"
                    ))?,
                ),
                None => None,
            };
            runs.push((f, sm, s3));
        }
        Ok(runs)
    }

    /// The normal wave's tables and figures: each frequency's cycles by MRD (and in 3D),
    /// their loss against the held approach's at the same amplitude, and the 3D run
    /// against MRD's cycle by cycle.
    fn report_waves(
        &self,
        out: &mut Section,
        w: &NormalWave,
        (held_run, runs): (&[Sample], &[WaveRun]),
        (g, a, period): (f64, f64, f64),
    ) -> Result<()> {
        let (mu, fn_) = (self.mu, self.normal_force);
        let with_3d = self.cells_3d > 0;
        let motion = format!(
            "approach d0 (1 + {} sin(f omega_t t + {})) about Hertz's d0 of F_N = {fn_}, omega_t = sqrt(k_t / m) = {:.6e}; released at rest from {} mu F_N (virgin loading at the approach of t = 0); mu = {mu}, G* = {g}",
            w.amplitude,
            w.phase,
            2.0 * PI / period,
            self.amplitude
        );
        let mut summary = self.wave_summary(&motion);
        let mut cycles_m = Vec::new();
        let mut cycles_3 = Vec::new();
        // Summed losses over summed held losses: the large cycles weigh most (a cycle's
        // ratio grows without bound as its amplitude falls under a wave).
        let held = |rows: &[Vec<f64>]| {
            rows.iter().map(|r| r[3]).sum::<f64>() / rows.iter().map(|r| r[4]).sum::<f64>()
        };
        let (mut amp_dev, mut loss_dev, mut held_dev) = (0.0f64, 0.0f64, 0.0f64);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut history = Figure::new(
            "ring_down_wave",
            "Ring-down under an oscillating normal approach: tangential force, MRD and 3D in the loop",
            "time over the stick period t / T [1]",
            "tangential force over mu F_N [1]",
        );
        let end = if with_3d {
            self.periods_3d
        } else {
            self.periods
        } as f64
            * period;
        // A run's tangential force over mu F_N against t / T, up to the time `end`.
        let force = |s: &[Sample], end: f64| -> Vec<(f64, f64)> {
            let kept = s.iter().filter(|p| p.t <= end);
            kept.map(|p| (p.t / period, p.force / (mu * fn_))).collect()
        };
        for (k, (f, sm, s3)) in runs.iter().enumerate() {
            let rows = self.cycles(sm, (g, a, period));
            if rows.is_empty() {
                out.failures.push(format!(
                    "MRD under the normal wave at {f} omega_t made no full cycle"
                ));
                continue;
            }
            let mut row = vec![*f, rows.len() as f64, held(&rows)];
            lo = lo.min(row[2]);
            hi = hi.max(row[2]);
            history = history.with(
                Series::new(format!("MRD, f = {f} omega_t"), force(sm, end), Style::Line)
                    .colored(k)
                    .thin(),
            );
            if let Some(s3) = s3 {
                let rows3 = self.cycles(s3, (g, a, period));
                if rows3.is_empty() {
                    out.failures.push(format!(
                        "the 3D run under the normal wave at {f} omega_t made no full cycle"
                    ));
                    continue;
                }
                let (mut amp, mut loss) = (0.0f64, 0.0f64);
                for (r3, rm) in rows3.iter().zip(&rows) {
                    amp = amp.max((r3[2] / rm[2] - 1.0).abs());
                    loss = loss.max((r3[3] / rm[3] - 1.0).abs());
                }
                let same = rows3.len().min(rows.len());
                let (w3, wm) = (held(&rows3), held(&rows[..same]));
                row.extend([rows3.len() as f64, w3, wm, amp, loss]);
                held_dev = held_dev.max((w3 / wm - 1.0).abs());
                amp_dev = amp_dev.max(amp);
                loss_dev = loss_dev.max(loss);
                history = history.with(
                    Series::new(
                        format!("3D, f = {f} omega_t"),
                        force(s3, f64::INFINITY),
                        Style::Dashed,
                    )
                    .colored(k),
                );
                cycles_3.extend(rows3.into_iter().map(|r| [vec![*f], r].concat()));
            }
            cycles_m.extend(rows.into_iter().map(|r| [vec![*f], r].concat()));
            summary.push(row);
        }
        if summary.rows.is_empty() {
            return Ok(());
        }
        history = history.with(
            Series::new("MRD, held approach", force(held_run, end), Style::Line)
                .colored(runs.len())
                .thin(),
        );
        out.scalar("normal_wave_loss_over_held_mrd_min", lo);
        out.scalar("normal_wave_loss_over_held_mrd_max", hi);
        if with_3d {
            out.scalar("normal_wave_amplitude_max_rel_dev_3d_vs_mrd", amp_dev);
            out.scalar("normal_wave_loss_per_cycle_max_rel_dev_3d_vs_mrd", loss_dev);
            out.scalar("normal_wave_loss_over_held_max_rel_dev_3d_vs_mrd", held_dev);
        }
        let ratio = Self::wave_ratio_figure(runs, &cycles_m, &cycles_3);
        out.tables.push(summary);
        for (name, who, rows) in [
            ("cycles_wave", "MRD", cycles_m),
            ("cycles_wave_3d", "3D", cycles_3),
        ] {
            if rows.is_empty() {
                continue;
            }
            out.tables.push(Self::cycles_table(
                name,
                who,
                &["normal frequency over omega_t [1]"],
                rows,
                format!("{motion}; {who} in the loop; the Mindlin-Deresiewicz columns are the held approach's loss at the cycle's force amplitude, and their ratio the loss over the held approach's"),
            ));
        }
        out.figures.push(history);
        out.figures.push(ratio);
        Ok(())
    }

    /// The normal wave's summary table, one row per frequency (its columns without the
    /// 3D run's where there is none).
    fn wave_summary(&self, motion: &str) -> Table {
        let with_3d = self.cells_3d > 0;
        let mut columns = vec![
            "normal frequency over omega_t [1]".to_string(),
            "cycles, MRD [count]".into(),
            "loss over the held approach's, MRD [1]".into(),
        ];
        if with_3d {
            columns.extend([
                "cycles, 3D [count]".into(),
                "loss over the held approach's, 3D [1]".into(),
                "loss over the held approach's, MRD over the 3D run's cycles [1]".into(),
                "force amplitude max rel dev 3D vs MRD [1]".into(),
                "loss per cycle max rel dev 3D vs MRD [1]".into(),
            ]);
        }
        let names: Vec<&str> = columns.iter().map(String::as_str).collect();
        let mut summary = Table::new("normal_wave", &names);
        summary.notes.push(format!(
            "{motion}; the loss over the held approach's: the cycles' losses (slip energy between turning points two apart) summed, over the sum of Mindlin-Deresiewicz's losses at each cycle's force amplitude (the mean of its three extremes; MRD's held run meets them, table cycles), so the largest cycles weigh most; MRD {} springs at {} steps per period for {} periods{}",
            self.springs,
            self.steps,
            self.periods,
            if with_3d {
                format!(
                    "; 3D: the pressure solved at every step (dynamics' oblique law), {0}^2 cells over {SIDE_3D} contact radii, {1} steps per period for {2} periods, compared with MRD's first cycles",
                    self.cells_3d, self.steps_3d, self.periods_3d
                )
            } else {
                String::new()
            }
        ));
        summary
    }

    /// Each cycle's loss over the held approach's against its force amplitude, every
    /// frequency, by MRD and (where there are rows) in 3D; `cycles_*`: the cycles
    /// tables' rows (the frequency first).
    fn wave_ratio_figure(runs: &[WaveRun], cycles_m: &[Vec<f64>], cycles_3: &[Vec<f64>]) -> Figure {
        // Cycle by cycle against the amplitude: every frequency, both methods.
        let (x0, x1) = cycles_m
            .iter()
            .chain(cycles_3)
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), r| {
                (lo.min(r[3]), hi.max(r[3]))
            });
        let mut ratio = Figure::new(
            "normal_wave",
            "Loss per cycle over the held approach's at the same amplitude, under a normal wave",
            "force amplitude over mu F_N [1]",
            "loss per cycle over the held approach's [1]",
        )
        .plot(
            "held approach (Mindlin-Deresiewicz)",
            vec![(x0, 1.0), (x1, 1.0)],
            Style::Line,
        );
        ratio.log_x = true;
        ratio.log_y = true;
        for (k, (f, _, _)) in runs.iter().enumerate() {
            let of = |rows: &[Vec<f64>]| -> Vec<(f64, f64)> {
                let here = rows.iter().filter(|r| r[0] == *f);
                here.map(|r| (r[3], r[6])).collect()
            };
            ratio = ratio.with(
                Series::new(
                    format!("MRD, f = {f} omega_t"),
                    of(cycles_m),
                    Style::Markers,
                )
                .colored(k + 1),
            );
            if !cycles_3.is_empty() {
                ratio = ratio.with(
                    Series::new(format!("3D, f = {f} omega_t"), of(cycles_3), Style::Crosses)
                        .colored(k + 1),
                );
            }
        }
        ratio
    }

    /// Mindlin's tangential displacement at the force `q` on the virgin loading:
    /// `3 mu F_N / (8 G* a) ... ` in MRD's terms `(3 mu F_N / (4 a G*)) (1 - (1 - q /
    /// (mu F_N))^(2/3))` (Eq. 45 with G* the composite tangential modulus).
    fn md_displacement(&self, g: f64, a: f64, q: f64) -> f64 {
        let (mu, fn_) = (self.mu, self.normal_force);
        3.0 * mu * fn_ / (4.0 * a * g) * (1.0 - (1.0 - q / (mu * fn_)).powf(2.0 / 3.0))
    }
}
