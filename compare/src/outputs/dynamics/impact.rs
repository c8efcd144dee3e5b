//! `impact`: the contact inside a time integration (Section 12), on the textbook case with
//! a closed form: a rigid sphere (mass m, speed v) striking an elastic half-space,
//! integrated in time with the contact evaluated at every step, by MRD's springs (the
//! rule of Hess, exact for the sphere) and by the 3D boundary-element solve
//! (warm-started from the last step), against Hertz's impact solution (Johnson 11.4):
//! contact duration, largest force and approach, coefficient of restitution 1. Both
//! converge in the time step (MRD at three steps: the observed order) and the 3D side in
//! the grid; each method's cost per step is reported beside its error.
//!
//! Set-up: the mass starts 1e-3 of the largest approach before first contact at speed v
//! and is integrated by velocity Verlet (`dynamics::integrate`) to 1.3 contact times.
//! The 3D grid is free, of side `extent` times the largest Hertz contact diameter; its
//! highest cell sits a fraction of a cell below the apex, an error of the grid that
//! vanishes with it.

use crate::checks::{bad, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::impact::{
    bem3d_law, check_resolution, check_strike, first_contact, stages as impact_stages,
    FirstContact, Strike,
};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use dynamics::integrate::{Counts, Sample};
use dynamics::{ContactLaw, Springs};
use mrd::reference::{for_profile, hertz, hertz_impact};
use serde::Deserialize;
use std::time::Instant;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Impact {
    /// The sphere's mass [mass].
    mass: f64,
    /// Its speed at first contact [length / time].
    speed: f64,
    /// MRD springs on the half line (over 2 Hertz contact radii).
    #[serde(default = "default_springs")]
    springs: usize,
    /// Time steps per Hertz contact time (MRD's finest run; its two coarser runs take a
    /// half and a quarter of them).
    #[serde(default = "default_steps")]
    steps: usize,
    /// Cells per side of the 3D grids, coarse to fine (empty: MRD alone).
    #[serde(default = "default_cells")]
    cells: Vec<usize>,
    /// Time steps per contact time of the 3D runs.
    #[serde(default = "default_steps_3d")]
    steps_3d: usize,
    /// Side of the 3D grid over the largest Hertz contact diameter.
    #[serde(default = "default_extent")]
    extent: f64,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
}

fn default_springs() -> usize {
    4000
}
fn default_steps() -> usize {
    4000
}
fn default_cells() -> Vec<usize> {
    vec![32, 64]
}
fn default_steps_3d() -> usize {
    400
}
fn default_extent() -> f64 {
    1.5
}

/// One integrated impact: its label, resolution, samples and counts, and the time it took.
struct Run {
    label: String,
    dt: f64,
    samples: Vec<Sample>,
    counts: Counts,
    seconds: f64,
}

impl Run {
    /// The first contact: duration, largest force and approach, restitution.
    fn outcome(&self) -> Option<FirstContact> {
        first_contact(&self.samples)
    }
}

impl Output for Impact {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if for_profile::sphere_radius(ctx.profile()?).is_none() {
            return bad("impact needs a sphere (profile = paraboloid): Hertz's impact solution is the reference");
        }
        let r = for_profile::sphere_radius(ctx.profile()?).unwrap_or(1.0);
        check_strike(ctx.material.e_star, r, self.mass, self.speed)?;
        check_resolution(
            self.springs,
            (self.steps, self.steps_3d),
            &self.cells,
            1024,
            self.extent,
            self.tolerance,
        )?;
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        impact_stages(!self.cells.is_empty())
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let ctx = env.ctx;
        let profile = ctx.profile()?.clone();
        let e = ctx.material.e_star;
        let r = for_profile::sphere_radius(&profile).unwrap_or(1.0);
        let (m, v) = (self.mass, self.speed);
        out.stage(Stage::HessTransform, || profile.z1d(0.0));
        let (tc, fmax, dmax) = out.stage(Stage::ClosedForm, || {
            (
                hertz_impact::duration(e, r, m, v),
                hertz_impact::max_force(e, r, m, v),
                hertz_impact::max_approach(e, r, m, v),
            )
        });
        let a = hertz::radius(r, dmax);
        let mrd = out
            .stage(Stage::Dynamics, || -> dynamics::Result<Vec<Run>> {
                [4, 2, 1]
                    .iter()
                    .map(|&k| {
                        let mut law = Springs::body(&profile, e, self.springs, 2.0 * a)?;
                        self.integrate(&mut law, tc, fmax, dmax, self.steps / k)
                    })
                    .collect()
            })
            .ctx("MRD in the loop")?;
        let three = out
            .stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Run>> {
                self.cells
                    .iter()
                    .map(|&n| {
                        let side = 2.0 * self.extent * a;
                        let mut law = bem3d_law(&profile, e, n, side, self.tolerance)?;
                        self.integrate(&mut law, tc, fmax, dmax, self.steps_3d)
                    })
                    .collect()
            })
            .ctx("3D in the loop")?;
        self.report(out, &mrd, &three, (tc, fmax, dmax))
    }
}

impl Impact {
    fn integrate(
        &self,
        law: &mut dyn ContactLaw,
        tc: f64,
        fmax: f64,
        dmax: f64,
        steps: usize,
    ) -> dynamics::Result<Run> {
        let strike = Strike {
            mass: self.mass,
            speed: self.speed,
            tc,
            fmax,
            dmax,
        };
        let t0 = Instant::now();
        let (samples, counts, dt) = strike.run(law, steps)?;
        Ok(Run {
            label: law.describe(),
            dt,
            samples,
            counts,
            seconds: t0.elapsed().as_secs_f64(),
        })
    }

    fn report(
        &self,
        out: &mut Section,
        mrd: &[Run],
        three: &[Run],
        (tc, fmax, dmax): (f64, f64, f64),
    ) -> Result<()> {
        let runs: Vec<&Run> = mrd.iter().chain(three).collect();
        let mut t = Table::new(
            "impact",
            &[
                "method [index: 0-2 MRD, then 3D]",
                "time step over t_c [1]",
                "contact_time over Hertz [1]",
                "peak_force over Hertz [1]",
                "peak_approach over Hertz [1]",
                "restitution [1]",
                "accepted_steps [count]",
                "rejected_steps [count]",
                "iterations_per_step, mean [1]",
                "seconds_per_step [s]",
            ],
        );
        t.notes.push(format!(
            "Hertz's impact (Johnson 11.4): t_c = {tc:.6e}, F_max = {fmax:.6e}, d_max = {dmax:.6e} (mass {}, speed {}); methods: {}; velocity Verlet, steps rejected where the force jumps by 5 % of F_max; iterations: the 3D solver's conjugate-gradient iterations per accepted step (warm-started)",
            self.mass,
            self.speed,
            runs.iter()
                .enumerate()
                .map(|(i, r)| format!("{i} = {} at dt = t_c/{:.0}", r.label, tc / r.dt))
                .collect::<Vec<_>>()
                .join("; ")
        ));
        let mut outcomes = Vec::new();
        for (i, r) in runs.iter().enumerate() {
            let Some(o) = r.outcome() else {
                out.failures.push(format!(
                    "{}: the contact did not end within 1.3 t_c",
                    r.label
                ));
                continue;
            };
            let steps = r.counts.accepted.max(1) as f64;
            let iterations: usize = r.samples.iter().map(|s| s.iterations).sum();
            t.push(vec![
                i as f64,
                r.dt / tc,
                o.duration / tc,
                o.peak_force / fmax,
                o.peak_approach / dmax,
                o.restitution,
                r.counts.accepted as f64,
                r.counts.rejected as f64,
                iterations as f64 / steps,
                r.seconds / steps,
            ]);
            outcomes.push((i, o));
        }
        out.tables.push(t);
        let err = |o: &FirstContact| {
            [
                (o.duration / tc - 1.0).abs(),
                (o.peak_force / fmax - 1.0).abs(),
                (o.restitution - 1.0).abs(),
            ]
            .into_iter()
            .fold(0.0, f64::max)
        };
        // MRD at dt, dt/2, dt/4 (runs 0, 1, 2): the error and its observed order in dt.
        let mrd_err: Vec<f64> = outcomes
            .iter()
            .filter(|(i, _)| *i < 3)
            .map(|(_, o)| err(o))
            .collect();
        if let [e4, e2, e1] = mrd_err[..] {
            out.scalar("mrd_rel_error_vs_hertz", e1);
            if e4 > e2 && e2 > e1 && e1 > 0.0 {
                out.scalar("mrd_observed_order_in_dt", (e2 / e1).log2());
            }
            out.scalar("mrd_rel_error_coarsest_dt", e4);
        }
        if let Some((_, o)) = outcomes.iter().rfind(|(i, _)| *i >= 3) {
            out.scalar("bem3d_rel_error_vs_hertz", err(o));
            out.scalar("bem3d_contact_time_over_hertz", o.duration / tc);
        }
        if let (Some(m), Some(b)) = (mrd.last(), three.last()) {
            let per = |r: &Run| r.seconds / r.counts.accepted.max(1) as f64;
            out.scalar("cost_per_step_3d_over_mrd", per(b) / per(m));
        }
        // Figures: F(t) and the phase portrait F(d) with Hertz's law.
        let mut fig = Figure::new(
            "force_time",
            "Hertz impact with the contact evaluated at every step: force against time",
            "time over Hertz's contact time t / t_c [1]",
            "contact force over Hertz's largest F / F_max [1]",
        );
        let mut phase = Figure::new(
            "phase",
            "Hertz impact: contact force against approach, every step",
            "approach over Hertz's largest d / d_max [1]",
            "contact force over Hertz's largest F / F_max [1]",
        );
        let hertz_curve: Vec<(f64, f64)> = (0..=100)
            .map(|k| {
                let d = k as f64 / 100.0;
                (d, d.powf(1.5))
            })
            .collect();
        phase = phase.plot("Hertz F = 4/3 E* R^1/2 d^3/2", hertz_curve, Style::Dashed);
        for (i, r) in runs.iter().enumerate().skip(2) {
            let style = if i == 2 { Style::Line } else { Style::Markers };
            let label = format!("{} (dt = t_c/{:.0})", r.label, tc / r.dt);
            // The line at 200 points; markers at 40, each run's shifted by a fraction of
            // the spacing so that runs on the same steps do not hide each other or the line.
            let (every, start) = match style {
                Style::Markers => {
                    let every = (r.samples.len() / 40).max(1);
                    (every, (i - 3) * every / 3)
                }
                _ => ((r.samples.len() / 200).max(1), 0),
            };
            let pts = |f: &dyn Fn(&Sample) -> (f64, f64)| -> Vec<(f64, f64)> {
                r.samples.iter().skip(start).step_by(every).map(f).collect()
            };
            fig = fig.plot(label.clone(), pts(&|s| (s.t / tc, s.force / fmax)), style);
            phase = phase.plot(
                label,
                pts(&|s| (s.x / dmax, s.force / fmax))
                    .into_iter()
                    .filter(|p| p.0 >= 0.0)
                    .collect(),
                style,
            );
        }
        out.figures.push(fig);
        out.figures.push(phase);
        Ok(())
    }
}
